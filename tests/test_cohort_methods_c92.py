"""Decision C92: ``evaluate-all --per-method`` writes every user's task x method x unit scores as ``pdrlearn evaluate
--json`` gives them (cohort_methods.csv) and their means over the users (cohort_methods_summary.csv|md)."""

from __future__ import annotations

import json
import math
import shutil

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from tests.sim_helpers import TERRAIN_COHORT_USERS, shared_terrain_cohort

USERS = TERRAIN_COHORT_USERS


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    """``(cohort, models, eval)``: the terrain cohort of USERS and its ``evaluate-all --per-method`` output, made
    once per run for decisions C92's and C97's tests (``tests.sim_helpers.shared_terrain_cohort``, testing D51)."""
    return shared_terrain_cohort(tmp_path_factory)


def _same(a, b) -> bool:
    return (a is None or (isinstance(a, float) and math.isnan(a))) if b is None else math.isclose(a, b, abs_tol=1e-12)


def test_per_method_rows_equal_evaluate_json(trained, capsys):
    cohort, models, out = trained
    rows = pd.read_csv(out / "cohort_methods.csv")  # evaluate-all MODELS COHORT --out eval --serial --per-method
    assert not undocumented("cohort_methods.csv", rows.columns)
    assert set(rows["user"]) == {f"u{u}" for u in USERS}
    for u in USERS:
        assert main(["evaluate", str(models / f"u{u}"), str(cohort / f"u{u}" / "test" / "terrain"), "--json"]) == 0
        ev = json.loads(capsys.readouterr().out)["tasks"]["terrain"]
        mine = rows[(rows["user"] == f"u{u}") & (rows["task"] == "terrain")]
        expected = [(m, unit, s) for m, d in ev["methods"].items() for unit, s in d["units"].items()]
        assert len(mine) == len(expected) >= 4  # heuristic and svm, on more than one unit each
        for m, unit, s in expected:
            row = mine[(mine["method"] == m) & (mine["unit"] == unit)].iloc[0]
            assert _same(row["accuracy_labelled"], s["accuracy"])
            assert _same(row["balanced_accuracy_labelled"], s["balanced_accuracy"])
            assert row["n_steps_labelled"] == s["n_steps"]
            is_chosen = (m, unit) == (ev["chosen"]["method"], ev["chosen"]["unit"])
            assert bool(row["chosen"]) is is_chosen
            if is_chosen:  # the detected-stride figure is evaluate's
                assert _same(row["accuracy_detected"], ev["detected"]["accuracy"])
                assert row["n_steps_detected"] == ev["detected"]["n_steps"]
            else:  # classifiers C97 (amends C92): every row has its own (tests/test_cohort_methods_detected_c97.py)
                assert pd.notna(row["accuracy_detected"])
    pooled = pd.read_csv(out / "cohort_methods_summary.csv")
    assert not undocumented("cohort_methods_summary.csv", pooled.columns)
    assert (out / "cohort_methods_summary.md").is_file()
    for (t, m, unit), grp in rows.groupby(["task", "method", "unit"]):
        p = pooled[(pooled["task"] == t) & (pooled["method"] == m) & (pooled["unit"] == unit)].iloc[0]
        assert p["n_users"] == len(grp) == len(USERS)
        assert math.isclose(p["accuracy_labelled_mean"], grp["accuracy_labelled"].mean())
        assert p["n_chosen"] == int(grp["chosen"].sum())
    assert pooled["n_chosen"].sum() == len(USERS)


def test_without_per_method_no_method_tables_are_left(trained, tmp_path, capsys):
    cohort, models, per_method = trained
    out = tmp_path / "eval"
    shutil.copytree(per_method, out)  # an evaluate-all --per-method output (the shared fixture's), overwritten:
    assert (out / "cohort_methods.csv").is_file()
    assert main(["evaluate-all", str(models), str(cohort), "--out", str(out), "--serial", "--force"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["cohort_summary.csv", "cohort_summary.md"]
