"""A site environment in place of Table 2-1: a site's own condition table, Table 2-1 with the
site's current, Tz turned into Tp [3.3.3], and bad keys refused by name."""

import pytest

from allocator_pkg.dp.inputs.site import SiteSea, load_site, site_from_mapping
from allocator_pkg.dp.standard.weather import WEATHER_CONDITIONS, condition_at, limit

TABLE = {"name": "shelf", "wind": [5.0, 10.0, 15.0, 20.0], "hs": [0.5, 1.5, 3.0, 5.0], "tz": [4.0, 5.0, 6.0, 7.0],
         "current": [0.5, 0.8, 1.0, 1.2]}


def test_a_sites_own_table_with_tz():
    site = site_from_mapping(TABLE)
    assert len(site.conditions) == 5 and site.conditions[0] == WEATHER_CONDITIONS[0]
    third = site.conditions[3]
    assert (third.wind, third.hs, third.current) == (15.0, 3.0, 1.0)
    assert third.tp == pytest.approx(1.4049 * 6.0, rel=1e-12)                 # [3.3.3]
    assert site.given == ("wind", "hs", "tz", "current")
    assert "site 'shelf'" in site.describe() and "Table 2-1's" not in site.describe()
    # Halfway between 2 and 3 and the search over four numbers: the top is the site's 20 m/s.
    assert condition_at(2.5, site.conditions).wind == 12.5
    assert limit(lambda level: True, site.conditions) == (4, 20.0)
    assert limit(lambda level: level <= 2.25, site.conditions)[0] == 2


def test_table_2_1_with_the_sites_current():
    site = site_from_mapping({"current": 1.2})
    assert len(site.conditions) == 12
    for number in range(1, 12):
        condition = site.conditions[number]
        assert condition.current == 1.2
        assert (condition.wind, condition.hs, condition.tp) == (WEATHER_CONDITIONS[number].wind,
                                                                WEATHER_CONDITIONS[number].hs,
                                                                WEATHER_CONDITIONS[number].tp)
    assert "Table 2-1's wind, hs, tp" in site.describe()


def test_a_current_relation_over_fewer_numbers_keeps_table_2_1s_first_rows():
    site = site_from_mapping({"current": [0.3, 0.6, 0.9]})
    assert [c.current for c in site.conditions] == [0.0, 0.3, 0.6, 0.9]
    assert [c.wind for c in site.conditions] == [c.wind for c in WEATHER_CONDITIONS[:4]]


@pytest.mark.parametrize(("data", "message"), [
    ({"waves": 1.0}, r"level2\.site: unknown key\(s\) waves"),
    ({}, r"level2\.site: give at least one of"),
    ({"tp": 8.0, "tz": 6.0}, r"level2\.site\.tz: give tp or tz, not both"),
    ({"wind": 10.0}, r"level2\.site\.wind: a list"),
    ({"wind": [5.0, 4.0]}, r"level2\.site\.wind\[1\]: the wind speed of number 2 must exceed"),
    ({"wind": [5.0, 6.0], "hs": [1.0]}, r"level2\.site\.(wind|hs): .* entries"),
    ({"hs": [1.0] * 12}, r"level2\.site\.hs: 12 entries"),
    ({"hs": -1.0}, r"level2\.site\.hs: -1 m outside \[0, 25\]"),
    ({"tp": [8.0, 0.0]}, r"level2\.site\.tp\[1\]: 0 s outside \(0, 30\]"),
    ({"current": "strong"}, r"level2\.site\.current: a finite number \[m/s\]"),
    ({"current": [0.5, True]}, r"level2\.site\.current\[1\]: a finite number"),
    ({"current": 1.0, "name": 3}, r"level2\.site\.name: text"),
    ([1.0], r"level2\.site: a mapping"),
    ({"peak_factor": 0.5}, r"level2\.site\.peak_factor: 0\.5 outside \[1, 10\]"),
    ({"peak_factor": [3.3, 3.3], "hs": [1.0, 2.0, 3.0]}, r"level2\.site\.(peak_factor|hs): .* entries"),
    ({"peak_factor": [3.3, "high"]}, r"level2\.site\.peak_factor\[1\]: a finite number"),
    ({"spreading": -2.0}, r"level2\.site\.spreading: -2 outside \[0, 100\]"),
    ({"spreading": [2.0]}, r"level2\.site\.spreading: one value, not a list"),
    ({"wave_direction": 200.0}, r"level2\.site\.wave_direction: 200 deg outside \[-180, 180\]"),
    ({"current_direction": "abeam"}, r"level2\.site\.current_direction: a finite number \[deg\]"),
    ({"current_direction": True}, r"level2\.site\.current_direction: a finite number"),
])
def test_bad_sites_are_refused_naming_the_key(data, message):
    with pytest.raises(ValueError, match=message):
        site_from_mapping(data)


def test_a_site_file(tmp_path):
    path = tmp_path / "site.yaml"
    path.write_text("name: bank\nwind: [4.0, 8.0]\nhs: [0.5, 1.0]\ntp: [5.0, 6.0]\ncurrent: 1.5\n")
    site = load_site(path)
    assert site.name == "bank" and site.source == str(path) and len(site.conditions) == 3
    path.write_text("current: -1\n")
    with pytest.raises(ValueError, match=r"site\.yaml: site\.current: -1 m/s outside \[0, 5\]"):
        load_site(path)


def test_a_sites_sea_peak_factor_spreading_and_directions():
    """The sea's keys beside the conditions: a gamma per number (0, DNV-RP-C205's, for calm),
    the spreading and the directions relative to the wind, said in the notes; absent, Level 1's sea."""
    site = site_from_mapping({**TABLE, "peak_factor": [1.0, 2.0, 3.3, 5.0], "spreading": 4,
                              "wave_direction": 30, "current_direction": -45.5})
    assert site.sea == SiteSea((0.0, 1.0, 2.0, 3.3, 5.0), 4.0, 30.0, -45.5)
    assert [site.sea.peak_factor(n) for n in range(5)] == [0.0, 1.0, 2.0, 3.3, 5.0]
    assert "cos^4 spreading" in site.describe() and "waves 30 deg, current -45.5 deg" in site.describe()
    plain = site_from_mapping(TABLE)
    assert plain.sea == SiteSea() and plain.sea.collinear and plain.sea.peak_factor(3) == 0.0
    assert "Level 3" not in plain.describe()
    only_sea = site_from_mapping({"peak_factor": 2.5, "current_direction": 90.0})
    assert only_sea.conditions == WEATHER_CONDITIONS and only_sea.sea.peak_factors == (0.0,) + (2.5,) * 11
    assert only_sea.sea.wave_direction is None and not only_sea.sea.collinear
    assert "collinear" not in only_sea.sea.describe() and "Table 2-1's wind" in only_sea.describe()
