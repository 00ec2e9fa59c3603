"""Session 39, fixer FM (review R1 findings 3, 4, 9): one force unit per model (C155), one force unit per session at
import (B407), import's force unit lines (B408)."""

from __future__ import annotations

import copy
import json

import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.test_force_units_s39 import _adc, _insole_csv, _with_force

ROUTE = "stand:2, straight:20, stand:2"


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(10270), rate_hz=100.0, seed=0, scenario="route")


def _in_units(session, name: str, heel: str, toe: str, fn=None):
    """A copy of ``session`` named ``name`` whose meta.json units say heel / toe are in ``heel`` / ``toe`` (force
    values ``fn(values)``)."""
    out = copy.copy(session) if fn is None else _with_force(session, fn)
    out.name = name
    out.meta = {**(session.meta or {}), "units": {"fForceA": f"{heel} (source {heel}, x 1)",
                                                  "fForceB": f"{toe} (source {toe}, x 1)"}}
    return out


def test_training_on_mixed_force_units_is_refused_naming_the_sessions_c155(walk):
    from pdrlearn.classify import train_user
    from pdrlearn.classify.force_scale import training_force

    n, counts = _in_units(walk, "walk_n", "N", "N"), _in_units(walk, "walk_adc", "counts", "counts", _adc)
    assert training_force([n, copy.copy(n)])["unit"] == "N"
    with pytest.raises(DataError) as e:  # before C155: {'unit': 'N; counts', ...} and no word
        training_force([n, counts])
    msg = str(e.value)
    assert "\n" not in msg and "N: session 'walk_n'" in msg and "counts: session 'walk_adc'" in msg and "C155" in msg
    with pytest.raises(DataError, match="different units"):  # train refuses before any fit
        train_user([n, counts], tasks=["length"], methods=["svm"], units=["foot"], cv=2, distance_calibration=False)


def test_the_force_unit_of_a_session_reads_heel_and_toe_c155(walk):
    from pdrlearn.classify.force_scale import force_level, force_scale_line, force_unit, training_force

    mixed = _in_units(walk, "walk_mixed", "counts", "N")
    assert force_unit(mixed) == "N; counts"  # before C155: fForceA's "counts" alone
    record = {"unit": "N", "level_p95": force_level(walk), "n_sessions": 1}
    assert force_scale_line(record, _in_units(walk, "walk_n", "N", "N")) is None
    toe_counts = _in_units(walk, "walk_toe", "N", "counts")  # before C155: fForceA's N, no line
    assert "N; counts" in force_scale_line(record, toe_counts)
    with pytest.raises(DataError, match="heel and toe in N and counts: session 'walk_mixed'"):
        training_force([mixed])


def test_a_model_trained_on_mixed_units_before_c155_says_so_c155(walk):
    from pdrlearn.classify.force_scale import force_level, force_scale_line

    record = {"unit": "N; counts", "level_p95": force_level(walk), "n_sessions": 2}
    line = force_scale_line(record, _in_units(walk, "walk_n", "N", "N"))
    # before C155: "is 1x the model's training force (... N; counts)", a ratio against no level
    assert "different force units" in line and "1x" not in line and "retrain" in line


@pytest.fixture(scope="module")
def adc_csv(walk, tmp_path_factory):
    """Review R1's d.csv case: raw ADC counts in heel and toe under names without a unit hint."""
    path = tmp_path_factory.mktemp("b407") / "insole.csv"
    _insole_csv(walk, path, "", _adc)
    return path


def _import(args, capsys):
    from pdrlearn.cli import main

    capsys.readouterr()
    rc = main(["import", *map(str, args)])
    return rc, capsys.readouterr().err.strip().splitlines()


def test_one_given_force_unit_is_both_columns_and_different_units_are_refused_b407(adc_csv, tmp_path, capsys):
    rc, err = _import([adc_csv, "--out", tmp_path / "s", "--heel-unit", "counts"], capsys)
    units = json.loads((tmp_path / "s" / "meta.json").read_text())["units"]
    # before B407: "fForceB: forefoot ... in N (default)", the counts written as N
    assert rc == 0 and units["fForceA"] == units["fForceB"] == "counts (source counts, x 1)"
    assert any(line.startswith("fForceB: forefoot") and "given with --heel-unit, B407" in line for line in err)
    rc, err = _import([adc_csv, "--out", tmp_path / "t", "--heel-unit", "counts", "--toe-unit", "N"], capsys)
    assert rc == 2 and len(err) == 1 and "B407" in err[0] and "in counts (given)" in err[0]  # before B407: 0
    assert not (tmp_path / "t").exists()


@pytest.mark.parametrize("unit, said, not_said", [
    ("1/4 N", "--heel-unit takes N, kgf", "give its unit with --heel-unit"),  # before B408: the option just given
    ("%BW", "with --heel-unit counts", "with --mapping units"),  # before B408: --mapping only
])
def test_the_force_unit_lines_name_what_heel_unit_takes_b408(adc_csv, tmp_path, capsys, unit, said, not_said):
    rc, err = _import([adc_csv, "--out", tmp_path / "s", "--heel-unit", unit], capsys)
    assert rc == 2 and len(err) == 1 and said in err[0] and not_said not in err[0]
    assert not (tmp_path / "s").exists()


def test_a_force_unit_for_an_unmapped_column_is_one_line_b408(walk, tmp_path, capsys):
    import pandas as pd

    path = tmp_path / "renamed.csv"
    _insole_csv(walk, path, "")
    df = pd.read_csv(path).rename(columns={"heel": "heel_new", "midfoot": "mid_old", "forefoot": "toe_old"})
    df.to_csv(path, index=False)  # review R1's b.csv: no force column is guessed
    rc, err = _import([path, "--out", tmp_path / "s", "--heel-unit", "kg"], capsys)
    # before B408: exit 0, the unit ignored without a word
    assert rc == 2 and len(err) == 1 and "--heel-unit kg is given" in err[0] and "--heel COLUMN" in err[0]
    assert not (tmp_path / "s").exists()


def test_a_pseudonymised_models_line_says_it_keeps_no_trace_and_names_import_subject_c156():
    from pdrlearn.classify import train_user
    from pdrlearn.classify.training import other_user_line
    from pdrlearn.sim import simulate

    model = train_user([simulate("length", user_seed=10271)], tasks=["length"], methods=["svm"], units=["foot"],
                       cv=2, user="P001", distance_calibration=False)
    # C156: no trace of the hidden id, not even a hash (session names are not users, E174)
    assert [k for k in model.data_summary if "user" in k] == ["users"] and model.data_summary["users"] == ["P001"]
    own = simulate("length", user_seed=10271, seed=5)
    line = other_user_line(model, [own])
    # before C156: only 'write "user": "P001" in their meta.json', rewriting the user's data
    assert "keeps no trace of the id it hides (decision C156)" in line and "import them with --subject P001" in line
    own.meta = {**own.meta, "subject": "P001"}  # what import --subject P001 writes
    own.meta.pop("user", None)
    assert other_user_line(model, [own]) is None
