"""`train-all --force` replaces the whole models folder (docs/decisions/bad-input.md B19): before, each user's
model directory was replaced on its own, so a re-run kept the models of users no longer in the cohort (and
the old model of a user who failed this time) next to a summary that did not list them."""

from __future__ import annotations

import json
import shutil

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

ARGS = ["--serial", "--methods", "heuristic", "--tasks", "terrain", "--units", "foot", "--cv", "3", "--json"]


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    root = tmp_path_factory.mktemp("force_cohort")
    return write_session(simulate("terrain", user_seed=3), root / "terrain")


def _cohort(root, session, users):
    for u in users:
        shutil.copytree(session, root / u / "train" / "s1")
        shutil.copytree(session, root / u / "test" / "s1")
    return root


def test_force_rerun_leaves_no_stale_user(session, tmp_path, capsys):
    cohort = _cohort(tmp_path / "cohort", session, ["u1", "u2", "u3"])
    models = tmp_path / "models"
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS]) == 0
    assert main(["evaluate-all", str(models), str(cohort), "--serial", "--json"]) == 0  # -> models/eval
    capsys.readouterr()
    shutil.rmtree(cohort / "u3")  # u3 left the cohort
    for p in (cohort / "u2" / "train" / "s1").glob("fAccelerometer.csv"):
        p.write_text("timestamp,x,y,z\n")  # u2 fails this time
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS, "--force"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert [u["user"] for u in out["users"]] == ["u1", "u2"]
    # only what this run wrote: no u3 from the first run, no old model for the failed u2, no stale eval/
    assert sorted(p.name for p in models.iterdir()) == ["cohort_summary.csv", "cohort_summary.md", "u1"]
    assert list(pd.read_csv(models / "cohort_summary.csv")["user"]) == ["u1", "u2"]
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []  # no temporary folder left


def test_eval_folder_replaced_with_the_models_and_said(session, tmp_path, capsys):
    cohort = _cohort(tmp_path / "cohort", session, ["u1"])
    models = tmp_path / "models"
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS]) == 0
    assert main(["evaluate-all", str(models), str(cohort), "--serial", "--json"]) == 0
    capsys.readouterr()
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS, "--force"]) == 0
    err = capsys.readouterr().err
    assert f"replaced {models} (and {models / 'eval'}" in err
    assert not (models / "eval").exists()


def test_foreign_file_in_models_folder_is_refused_even_with_force(session, tmp_path, capsys):
    cohort = _cohort(tmp_path / "cohort", session, ["u1"])
    models = tmp_path / "models"
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS]) == 0
    (models / "notes.txt").write_text("precious")
    capsys.readouterr()
    before = sorted(p.name for p in models.iterdir())
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS, "--force"]) == 2
    err = capsys.readouterr().err
    assert "notes.txt" in err and "'pdrlearn train-all' did not write" in err
    assert sorted(p.name for p in models.iterdir()) == before
    assert (models / "notes.txt").read_text() == "precious"


def test_every_user_failing_on_force_rerun_keeps_the_old_folder(session, tmp_path, capsys):
    cohort = _cohort(tmp_path / "cohort", session, ["u1"])
    models = tmp_path / "models"
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS]) == 0
    manifest = (models / "u1" / "manifest.json").read_text()
    (cohort / "u1" / "train" / "s1" / "fAccelerometer.csv").write_text("timestamp,x,y,z\n")
    assert main(["train-all", str(cohort), "--out", str(models), *ARGS, "--force"]) == 2
    assert "every user failed" in capsys.readouterr().err
    assert (models / "u1" / "manifest.json").read_text() == manifest  # B5: nothing written, old one kept


def test_output_inside_the_cohort_folder_is_refused(session, tmp_path, capsys):
    """Before, the second run took COHORT/models for a user ("no session folders", exit 1)."""
    cohort = _cohort(tmp_path / "cohort", session, ["u1"])
    assert main(["train-all", str(cohort), "--out", str(cohort / "models"), *ARGS]) == 2
    assert "inside the cohort folder" in capsys.readouterr().err
    (tmp_path / "m").mkdir()
    assert main(["evaluate-all", str(tmp_path / "m"), str(cohort), "--serial", "--out", str(cohort / "ev")]) == 2
    assert "inside the cohort folder" in capsys.readouterr().err
    assert sorted(p.name for p in cohort.iterdir()) == ["u1"]
