"""The Level 3 outputs on made-up runs (test_level3_plots): the criteria and "Not verified by
DNV" in every one, the assumptions, the quantile table against numpy, and the screening
estimate's place."""

import csv

import numpy as np
import pytest
from test_level3_plots import CRITERIA, made_up  # noqa: F401  (the fixture)

from allocator_pkg.dp.report.level3_report import ASSUMPTIONS, Screening, write_level3

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def written(made_up, tmp_path_factory):  # noqa: F811
    prepared, result, finished = made_up
    out = tmp_path_factory.mktemp("l3")
    screening = Screening("Screening estimate (frequency domain), made up", ("heading_deg", "sigma_m"),
                          [(0.0, 0.5), (90.0, 1.25)])
    return out, write_level3(prepared, result, finished, out, screening), made_up


def test_every_output_states_the_criteria_and_not_verified_by_dnv(written):
    out, paths, _ = written
    described = CRITERIA.describe()
    for path in paths:
        if path.suffix == ".csv":
            head = path.read_text().splitlines()[:2]
            assert head[0].startswith("# ") and described in head[1] and "Not verified by DNV" in head[1], path.name
        elif path.suffix in (".txt", ".md"):
            text = path.read_text()
            assert described in text and "Not verified by DNV" in text, path.name
            assert all(line in text for line in ASSUMPTIONS), path.name
    markdown = (out / "dp_vessel_dp_l3_report.md").read_text()
    for name, value in CRITERIA.values():
        assert f"| `{name}` | {value} |" in markdown
    assert {path.suffix for path in paths} == {".png", ".csv", ".txt", ".md"}


def test_the_quantile_table_is_numpys_over_the_seeds(written):
    out, _, (_, _, finished) = written
    with (out / "dp_vessel_dp_l3_quantiles.csv").open() as handle:
        rows = list(csv.DictReader(line for line in handle if not line.startswith("#")))
    conditions = {key[:3] for key in finished}
    assert len(rows) == len(conditions)
    for row in rows:
        runs = [finished[(float(row["heading_deg"]), int(row["capability_number"]), row["case"], s)] for s in range(3)]
        steady = [run.steady_position for run in runs]
        assert float(row["steady_position_quantile"]) == pytest.approx(np.quantile(steady, 0.9), rel=1e-5)
        assert float(row["steady_position_min"]) == pytest.approx(min(steady), rel=1e-5)
        assert float(row["steady_position_median"]) == pytest.approx(np.median(steady), rel=1e-5)
        assert float(row["steady_position_max"]) == pytest.approx(max(steady), rel=1e-5)
        assert min(steady) <= float(row["steady_position_ci_low"]) <= float(row["steady_position_ci_high"]) \
            <= max(steady) * (1 + 1e-5)
        assert (row["transient_position_quantile"] == "") == (row["case"] == "intact")
        held = np.quantile(steady, 0.9) <= 2.0 and np.quantile([r.steady_heading_deg for r in runs], 0.9) <= 3.0
        if row["case"] != "intact":
            held = held and np.quantile([r.transient_position for r in runs], 0.9) <= 3.0
        assert row["held"] == str(held)


def test_the_screening_estimate_has_its_table_and_its_section(written, made_up, tmp_path):  # noqa: F811
    out, _, _ = written
    markdown = (out / "dp_vessel_dp_l3_report.md").read_text()
    section = markdown.split("## Screening estimate\n\n")[1].split("\n## ")[0]
    assert section.splitlines()[:5] == ["Screening estimate (frequency domain), made up", "",
                                        "| heading_deg | sigma_m |", "|---|---|", "| 0.0 | 0.5 |"]
    assert (out / "dp_vessel_dp_l3_screening.csv").read_text().splitlines()[2:] == ["heading_deg,sigma_m", "0,0.5",
                                                                                    "90,1.25"]
    paths = write_level3(*made_up, tmp_path)
    assert "## Screening estimate\n\nNo screening estimate given.\n" in (tmp_path / "dp_vessel_dp_l3_report.md"
                                                                         ).read_text()
    assert not any(path.name.endswith("_screening.csv") for path in paths)
