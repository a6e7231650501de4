"""The Level 3 criteria file: the shipped one is the defaults, every key read, overrides, and
bad keys and values refused naming the file and the key."""

import pytest
import yaml
from conftest import ROOT

from allocator_pkg.configuration.file_keys import INTEGER, NUMBER, TEXT, defaults
from allocator_pkg.dp.level3.case import CRITERIA_KEYS, Criteria
from allocator_pkg.dp.level3.criteria_file import criteria_from_mapping, read_criteria

SHIPPED = ROOT / "config" / "level3" / "criteria.yaml"


def test_the_shipped_file_holds_every_key_at_its_default():
    data = yaml.safe_load(SHIPPED.read_text())
    assert list(data) == [key.name for key in CRITERIA_KEYS]
    assert data == defaults(CRITERIA_KEYS)
    assert read_criteria(SHIPPED) == Criteria() == read_criteria(None)


def changed(key):
    """A good value of ``key`` other than its default."""
    if key.kind == TEXT:
        return next(choice for choice in key.choices if choice != key.default)
    if key.kind == INTEGER:
        return key.default + 1
    return key.default * 0.5 if key.default else 1.0


@pytest.mark.parametrize("key", CRITERIA_KEYS, ids=lambda key: key.name)
def test_each_key_is_read_and_an_override_wins(key, tmp_path):
    path = tmp_path / "criteria.yaml"
    path.write_text(yaml.safe_dump({key.name: changed(key)}))
    read = read_criteria(path)
    assert getattr(read, key.name) == changed(key)
    assert all(getattr(read, other.name) == other.default for other in CRITERIA_KEYS if other is not key)
    assert getattr(read_criteria(path, {key.name: key.default}), key.name) == key.default


def bad_values(key):
    if key.kind == TEXT:
        return ["cubic", 3]
    values = ["five", True, None, [1.0]]
    if key.minimum is not None:
        values.append(key.minimum - 1)
        if key.exclusive_minimum:
            values.append(key.minimum)
    if key.maximum is not None:
        values.append(key.maximum + 1)
    if key.kind == INTEGER:
        values.append(key.default + 0.5)
    if key.kind == NUMBER:
        values += [float("nan"), float("inf")]
    return values


@pytest.mark.parametrize("key", CRITERIA_KEYS, ids=lambda key: key.name)
def test_a_bad_value_is_refused_naming_the_file_and_the_key(key, tmp_path):
    path = tmp_path / "criteria.yaml"
    for value in bad_values(key):
        path.write_text(yaml.safe_dump({key.name: value}))
        with pytest.raises(ValueError, match=rf"^{path}: {key.name}: "):
            read_criteria(path)
        with pytest.raises(ValueError, match=rf"^{key.name}: "):
            Criteria(**{key.name: value})


def test_an_unknown_key_or_a_file_that_is_not_a_mapping_is_refused(tmp_path):
    path = tmp_path / "criteria.yaml"
    path.write_text("position_limit: 5\nposition_limt: 4\n")
    with pytest.raises(ValueError, match=rf"^{path}: unknown key\(s\) position_limt; known: position_limit, "):
        read_criteria(path)
    path.write_text("- 5\n")
    with pytest.raises(ValueError, match=rf"^{path}: a Level 3 criteria file is a mapping"):
        read_criteria(path)
    with pytest.raises(ValueError, match=r"missing\.yaml"):
        read_criteria(tmp_path / "missing.yaml")
    with pytest.raises(ValueError, match=r"^criteria: seeds: an integer >= 1, not 0$"):
        criteria_from_mapping({"seeds": 0})


def test_the_criteria_are_stated_by_key_and_a_run_is_told_apart_by_what_changes_it():
    criteria = Criteria()
    assert [name for name, _ in criteria.values()] == [key.name for key in CRITERIA_KEYS]
    assert criteria.describe().startswith("position_limit 5 m; heading_limit_deg 3 deg; settle 60 s;")
    assert "seeds 10" in criteria.describe() and "quantile_method linear" in criteria.describe()
    judged = Criteria(seeds=3, quantile=1.0, quantile_method="higher", confidence=0.5, resamples=500,
                      bootstrap_seed=4)
    assert judged.run_fingerprint() == criteria.run_fingerprint()
    for name in ("position_limit", "settle", "post_failure_window", "post_failure_heading_limit_deg"):
        assert Criteria(**{name: 7.0}).run_fingerprint() != criteria.run_fingerprint()
