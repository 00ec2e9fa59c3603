"""Decision C87: evaluate-all's summary says which accuracy each column holds (detected strides first, then the
labelled boundaries) and train-all / evaluate-all name the tasks they skipped."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.cohort import skipped_task_names, task_accuracy_columns
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def test_task_accuracy_columns_put_the_detected_figure_first():
    r = {"accuracy": 1.0, "n_steps": 50, "detected": {"accuracy": 0.92, "n_steps": 48}}
    cols = task_accuracy_columns("terrain", r)
    assert list(cols) == ["terrain_accuracy_detected", "terrain_n_steps_detected", "terrain_accuracy_labelled",
                          "terrain_n_steps_labelled", "terrain_classes_absent"]  # cohort C105: the last
    assert cols["terrain_accuracy_detected"] == 0.92 and cols["terrain_accuracy_labelled"] == 1.0
    assert task_accuracy_columns("length", {"accuracy": 0.9, "n_steps": 3, "detected": None})[
        "length_accuracy_detected"] is None
    assert skipped_task_names(("terrain", "direction", "length"), {"terrain": 1}) == "direction; length"


@pytest.fixture(scope="module")
def cohort(tmp_path_factory):
    root = tmp_path_factory.mktemp("cohort_c87")
    write_session(simulate("terrain", user_seed=8600), root / "u8600" / "train" / "terrain")
    write_session(simulate("terrain", user_seed=8600, seed=7), root / "u8600" / "test" / "terrain")
    return root


def test_cohort_summaries_name_the_accuracy_and_the_skipped_tasks(cohort, tmp_path, capsys):
    models = tmp_path / "m"
    # the terrain exercise has forward steps and no long ones: direction and length are skipped
    assert main(["train-all", str(cohort), "--out", str(models), "--serial",
                 "--methods", "heuristic"]) == 0
    capsys.readouterr()
    tr = pd.read_csv(models / "cohort_summary.csv")
    assert tr.loc[0, "skipped_tasks"] == 2 and tr.loc[0, "skipped_task_names"] == "direction; length"
    assert main(["evaluate-all", str(models), str(cohort), "--serial", "--json"]) == 0
    ev = json.loads(capsys.readouterr().out)["users"][0]
    assert "terrain_accuracy" not in ev
    keys = [k for k in ev if k.startswith("terrain_")]
    assert keys == ["terrain_accuracy_detected", "terrain_n_steps_detected", "terrain_accuracy_labelled",
                    "terrain_n_steps_labelled", "terrain_classes_absent"]  # cohort C105
    assert 0 < ev["terrain_accuracy_detected"] <= 1 and ev["terrain_n_steps_detected"] > 10
    assert ev["skipped_task_names"] == "direction; length"
    table = pd.read_csv(models / "eval" / "cohort_summary.csv")
    assert table.loc[0, "skipped_task_names"] == "direction; length"
