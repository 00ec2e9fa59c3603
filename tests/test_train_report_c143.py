"""Decision C143: a trained model's CV and leave-one-user-out results as tables (CSV, report.md) and confusion PNGs:
``train --report``, ``pdrlearn report MODEL_DIR`` (no giant cells) and ``to_dataframe(model)``. Users 9660-9662."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.sim_helpers import terrain_cv_model


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    """The users' sessions, ``model`` and ``rep`` of ``train --report`` and ``R`` of ``pdrlearn report model``
    (``tests.sim_helpers.terrain_cv_model``: made once per run, shared with decision C150's tests, D51)."""
    return terrain_cv_model(tmp_path_factory)


def test_train_report_writes_cv_and_louo_tables_a_confusion_png_and_a_short_report_md(trained, tmp_path):
    from pdrlearn.classify import load_model
    from pdrlearn.columns import undocumented

    rep = trained / "rep"  # train USERS --out model --report rep (the shared fixture ran it)
    assert sorted(p.name for p in rep.iterdir()) == ["confusion_terrain.png", "cv.csv", "louo.csv", "report.md"]
    cv, louo = pd.read_csv(rep / "cv.csv"), pd.read_csv(rep / "louo.csv")
    tm = load_model(trained / "model").tasks["terrain"]
    assert len(cv) == sum(len(per) for per in tm.cv.values())
    for row in cv.itertuples():  # the model's own CV numbers, in %
        r = tm.cv[row.method][row.unit]
        assert row.accuracy_pct == pytest.approx(100 * r["accuracy"], abs=0.01)
        assert (row.ci95_low_pct, row.ci95_high_pct) == pytest.approx([100 * v for v in r["folds"]["ci95"]], abs=0.01)
        assert row.accuracy_up_pct == pytest.approx(100 * r["per_class"]["up"], abs=0.01)
        assert row.chosen == ((row.method, row.unit) == tm.chosen)
        assert row.cv == "leave-one-user-out CV accuracy (3 users)"
    assert len(louo) == 3 * len(cv) and set(louo["held_out"]) == {f"user.seed:{u}" for u in (9660, 9661, 9662)}
    svm_foot = louo[(louo["method"] == "svm") & (louo["unit"] == "foot")]
    assert list(svm_foot["accuracy_pct"]) == pytest.approx([100 * a for a in tm.cv["svm"]["foot"]["folds"]["accuracy"]],
                                                           abs=0.01)
    assert undocumented("cv.csv", cv.columns) == [] and undocumented("louo.csv", louo.columns) == []
    md = (rep / "report.md").read_text()
    assert "## terrain (leave-one-user-out CV accuracy (3 users)" in md and "![terrain" in md
    assert "Accuracy (%) per held-out user" in md and "user.seed:9661" in md
    assert max(len(line) for line in md.splitlines()) < 300
    assert (rep / "confusion_terrain.png").read_bytes()[:4] == b"\x89PNG"


def test_report_of_a_model_dir_gives_cv_tables_and_a_figure_not_the_manifest_in_one_cell(trained):
    out = trained / "R"  # pdrlearn report model --out R (the shared fixture ran it)
    md = (out / "report.md").read_text()
    assert max(len(line) for line in md.splitlines()) < 300  # was 55,749 characters: the tasks dict in one cell
    assert "{'terrain'" not in md
    assert "## Cross-validation — terrain" in md and "accuracy (%) per held-out user" in md
    assert [p.name for p in (out / "img").iterdir()] == ["000_confusion_cv_terrain.png"]


def test_to_dataframe_of_a_user_model_is_the_cv_table(trained):
    from pdrlearn import to_dataframe
    from pdrlearn.classify import load_model

    model = load_model(trained / "model")
    df = to_dataframe(model)
    tm = model.tasks["terrain"]
    assert list(df.columns[:4]) == ["task", "method", "unit", "chosen"] and "accuracy_flat_pct" in df.columns
    assert len(df) == sum(len(per) for per in tm.cv.values())
    for row in df.itertuples():
        assert row.balanced_accuracy_pct == pytest.approx(100 * tm.cv[row.method][row.unit]["balanced_accuracy"],
                                                          abs=0.01)


def test_train_report_folder_is_refused_when_it_is_in_or_holds_the_model_dir(trained, tmp_path, capsys):
    for out, rep in (("m", "m"), ("m", "m/rep"), ("r/m", "r")):
        code = main(["train", str(trained / "u9660"), "--out", str(tmp_path / out), "--report", str(tmp_path / rep)])
        assert code == 2
        assert "--report" in (err := capsys.readouterr().err) and "the --out model directory" in err
        assert not (tmp_path / "m").exists() and not (tmp_path / "r").exists()


def test_each_task_table_shows_its_own_classes():
    from pdrlearn.classify.cv_report import report_markdown

    def rec(classes):
        return {"per_class": dict.fromkeys(classes, 1.0), "accuracy": 1.0, "balanced_accuracy": 1.0, "n_steps": 9,
                "n_folds": 3, "confusion": [[3 if i == j else 0 for j in classes] for i in classes]}

    manifest = {"user": "x", "tasks": {
        "terrain": {"classes": ["flat", "up", "down"], "n_steps": 9, "chosen": {"method": "svm", "unit": "foot"},
                    "cv": {"svm": {"foot": rec(["flat", "up", "down"])}}},
        "direction": {"classes": ["forward", "backward"], "n_steps": 9, "chosen": {"method": "svm", "unit": "foot"},
                      "cv": {"svm": {"foot": rec(["forward", "backward"])}}}}}
    md = report_markdown(manifest, "x", {})
    direction = md[md.index("## direction"):]
    assert "forward %" in direction.splitlines()[2] and "backward %" in direction.splitlines()[2]
    assert "flat %" not in direction and "forward %" not in md[:md.index("## direction")]


def test_a_report_path_that_is_a_file_is_refused_naming_report(trained, tmp_path, capsys):
    """Review R3 finding 4: `train --report FILE` said "--out must be a folder"; it names --report."""
    (tmp_path / "afile").write_text("x")
    code = main(["train", str(trained / "u9660"), "--out", str(tmp_path / "m"), "--report", str(tmp_path / "afile")])
    err = capsys.readouterr().err
    assert code == 2 and err.strip() == f"error: {tmp_path / 'afile'}: is a file; --report must be a folder for a " \
                                        "training report (cv.csv, report.md)"
    assert not (tmp_path / "m").exists() and (tmp_path / "afile").read_text() == "x"
