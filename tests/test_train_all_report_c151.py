"""Cohort decision C151: ``train-all --report DIR`` writes train --report's folder (C143) for every trained user,
``DIR/<user>/`` (cv.csv, confusion PNG, report.md), atomically after the models; a bad --report path is one line,
exit 2, nothing written. Users 9996-9997."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

ARGS = ["--serial", "--tasks", "terrain", "--methods", "svm,heuristic", "--units", "foot", "--cv", "3"]


@pytest.fixture(scope="module")
def cohort(tmp_path_factory):
    root = tmp_path_factory.mktemp("c151") / "cohort"
    for u in (9996, 9997):
        write_session(simulate("terrain", user_seed=u), root / f"u{u}" / "walk")
    return root


def test_train_all_report_writes_trains_report_per_user(cohort, tmp_path, capsys):
    from pdrlearn.classify import load_model
    from pdrlearn.classify.cv_report import cv_frame

    rep, models = tmp_path / "rep", tmp_path / "models"
    assert main(["train-all", str(cohort), "--out", str(models), "--report", str(rep), "--json", *ARGS]) == 0
    assert json.loads(capsys.readouterr().out)["report"] == str(rep)
    assert sorted(p.name for p in rep.iterdir()) == ["u9996", "u9997"]
    for u in ("u9996", "u9997"):
        assert sorted(p.name for p in (rep / u).iterdir()) == ["confusion_terrain.png", "cv.csv", "report.md"]
        cv = pd.read_csv(rep / u / "cv.csv")
        want = cv_frame(load_model(models / u))  # the user's model's own CV table, as train --report writes it
        assert list(cv["accuracy_pct"]) == pytest.approx(list(want["accuracy_pct"]), abs=0.01)
        assert list(cv["thesis_pct"]) == pytest.approx(list(want["thesis_pct"]), abs=0.01)
        assert "## terrain (3-fold CV accuracy" in (rep / u / "report.md").read_text()
    # a second run needs --force for the report too, and replaces it
    code = main(["train-all", str(cohort), "--out", str(tmp_path / "models2"), "--report", str(rep), *ARGS])
    assert code == 2 and "pass --force" in capsys.readouterr().err and not (tmp_path / "models2").exists()
    assert main(["train-all", str(cohort), "--out", str(models), "--report", str(rep), "--force", *ARGS]) == 0
    assert f"replaced {rep}" in capsys.readouterr().err and (rep / "u9997" / "cv.csv").is_file()


@pytest.mark.parametrize("out, rep, says", [
    ("m", "m", "is, or is inside, or holds the --out models folder"),
    ("m", "m/rep", "is, or is inside, or holds the --out models folder"),
    ("r/m", "r", "is, or is inside, or holds the --out models folder"),
    ("m", "COHORT/rep", "is inside the cohort folder"),
    ("m", "afile", "is a file; --report must be a folder"),
    ("m", "notes", "exists and does not hold per-user training reports"),
])
def test_a_bad_report_path_is_one_line_exit_2_and_nothing_written(cohort, tmp_path, capsys, out, rep, says):
    (tmp_path / "afile").write_text("x")
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "todo.md").write_text("keep")
    before = sorted(p.name for p in cohort.rglob("*"))
    report = cohort / "rep" if rep.startswith("COHORT") else tmp_path / rep
    code = main(["train-all", str(cohort), "--out", str(tmp_path / out), "--report", str(report), *ARGS])
    err = capsys.readouterr().err
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "m").exists() and not (tmp_path / "r").exists() and not (tmp_path / "rep").exists()
    assert sorted(p.name for p in cohort.rglob("*")) == before
    assert (tmp_path / "afile").read_text() == "x" and (tmp_path / "notes" / "todo.md").read_text() == "keep"
