"""Decisions E96 and E97 (docs/decisions/export.md): the notebook entry points at the top level, imported on first
use, and DataFrame views of the nested result dicts with the CSVs' column names (session 24 trial ``api``)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pdrlearn
from pdrlearn.errors import DataError

ROOT = Path(__file__).resolve().parents[1]


def test_entry_points_are_top_level_and_import_pdrlearn_still_imports_none():
    code = ("import sys, pdrlearn; before = sorted(m for m in sys.modules if m.startswith('pdrlearn.')); "
            "from pdrlearn import read_session, simulate, get_pipeline, load_model, to_dataframe; print(before); "
            "print(read_session.__module__, simulate.__name__, get_pipeline.__module__, load_model.__module__, "
            "to_dataframe.__module__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}, check=True).stdout.splitlines()
    assert out == ["['pdrlearn.errors']",
                   "pdrlearn.io.plasys simulate pdrlearn.track.base pdrlearn.classify.model_dir pdrlearn.tables"]
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    assert pdrlearn.read_session is read_session and pdrlearn.get_pipeline is get_pipeline
    assert {"read_session", "simulate", "get_pipeline", "load_model", "Tracker"} <= set(pdrlearn.__all__)
    assert {"read_session", "to_dataframe"} <= set(dir(pdrlearn))
    for name in pdrlearn.__all__:  # every advertised name resolves
        assert getattr(pdrlearn, name) is not None


@pytest.fixture(scope="module")
def evaluated():
    from pdrlearn.classify import evaluate_model, train_user
    from tests.test_classify_training import labelled_session

    model = train_user([labelled_session(1, 12), labelled_session(2, 12)], tasks=["terrain"], methods=["svm"],
                       cv=3, seed=0, units=["foot", "waist", "combined"])
    return evaluate_model(model, [labelled_session(11, 6)], latency=False)


def test_evaluation_frame_has_a_row_per_task_method_unit_with_per_class_accuracy(evaluated):
    from pdrlearn.classify.evaluation import results_table
    from pdrlearn.tables import EVALUATION_COLUMNS, evaluation_frame

    df = evaluation_frame(evaluated)
    r = evaluated["tasks"]["terrain"]
    assert list(df.columns[:len(EVALUATION_COLUMNS)]) == list(EVALUATION_COLUMNS)
    assert [f"accuracy_{c}" for c in r["classes"]] == list(df.columns[len(EVALUATION_COLUMNS):])
    table = results_table(r)  # report.md's rows: the same order and numbers
    assert df[["method", "unit"]].values.tolist() == [row[:2] for row in table]
    np.testing.assert_allclose(100 * df["accuracy"], [float(row[-3]) for row in table], atol=0.051)
    # decision C60: the table's balanced column, what train ranks by
    np.testing.assert_allclose(100 * df["balanced_accuracy"], [float(row[-2]) for row in table], atol=0.051)
    from pdrlearn.classify.evaluation import markdown_tables, results_head

    assert results_head(r)[-3:] == ["all %", "balanced %", "ms/step"] and "| all % | balanced % |" in markdown_tables(
        evaluated)
    first = df.iloc[0]
    unit = r["methods"][first["method"]]["units"][first["unit"]]
    assert first["accuracy_flat"] == unit["per_class"]["flat"] and first["n_steps"] == unit["n_steps"]
    chosen = df[df["chosen"]]
    assert chosen[["method", "unit"]].values.tolist() == [[r["chosen"]["method"], r["chosen"]["unit"]]]
    assert df["latency_ms"].isna().all()  # latency=False
    named = pdrlearn.to_dataframe({"u1": evaluated, "u2": evaluated})
    assert list(named.columns[:2]) == ["name", "task"] and len(named) == 2 * len(df)


def test_step_scores_and_summaries_are_frames_with_the_csv_names(gaitmap_level_left):
    from pdrlearn.cli.cohort import _session_row
    from pdrlearn.cohort import JobResult
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelStepDetector, score_steps
    from pdrlearn.track import get_pipeline

    s = read_session(gaitmap_level_left)
    score = score_steps(AccelStepDetector().detect(s), s)
    df = pdrlearn.to_dataframe({"left": score})
    assert df.loc[0, "name"] == "left" and df.loc[0, "f1"] == score["f1"]
    assert df.loc[0, "timing_error_abs_mean_s"] == score["timing_error_abs_mean_s"]
    summary = get_pipeline("plasys")(s).summary(s)
    sm = pdrlearn.to_dataframe([summary])
    assert list(sm.columns[:4]) == ["session", "pipeline", "method", "distance_m"]
    assert sm.loc[0, "final_x_m"] == summary["final_position"]["x"] and "final_position" not in sm.columns
    assert sm.loc[0, "gait_speed_mps"] == summary["gait_speed_mps"] and "info" not in sm.columns
    row = _session_row("a", "g", JobResult(name="a", ok=True, value={"summary": summary, "warnings": []}))
    same = [c for c in sm.columns if c != "input_dir"]  # track-all's input_dir is relative to ROOT (C18)
    assert {k: row[k] for k in same} == {k: sm.loc[0, k] for k in same}  # track-all's sessions.csv row


@pytest.mark.parametrize("bad, match", [
    ({"a": 1}, r"^to_dataframe: expected evaluate_model\(...\)'s result, a UserModel .*, a score_steps\(...\) dict "
               r"or a "
               r"TrackResult.summary\(session\) dict .*got dict$"),
    (42, "got int$"),
])
def test_something_else_is_one_line(bad, match):
    with pytest.raises(DataError, match=match):
        pdrlearn.to_dataframe(bad)
    from pdrlearn.tables import summary_frame

    with pytest.raises(DataError, match=r"^summary_frame: expected a TrackResult.summary\(session\) dict"):
        summary_frame(bad)
