"""Decisions C32-C37: train / evaluate say what they do with the labels and the data (duplicated and
contradicting step rows, labels that are not classes, labels off the foot's rest, training sessions evaluated,
another rate, pooled users, why a model was chosen, a task the model lacks, per-class precision and F1)."""

from __future__ import annotations

import copy
import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify.evaluation import evaluate_model
from pdrlearn.classify.labels import bad_label_warning, clean_steps, misaligned_text
from pdrlearn.classify.training import (
    TaskModel,
    _folds,
    class_metrics,
    session_windows,
    task_data,
    train_user,
)
from pdrlearn.sim.simulate import simulate


@pytest.fixture(scope="module")
def terrain():
    return simulate("terrain", user_seed=3, seed=0)


@pytest.fixture(scope="module")
def model(terrain):
    return train_user([terrain], tasks=["terrain"], methods=["svm"], units=["foot"], cv=3,
                      distance_calibration=False)


def _with_steps(session, steps):
    s = copy.copy(session)
    s.steps = steps.reset_index(drop=True)
    return s


def test_repeated_step_rows_count_once_and_contradicting_ones_are_left_out(terrain, caplog):
    st = terrain.steps
    up = st[st["terrain"] == "up"]
    conflict = st.iloc[[3]].assign(terrain="down")  # step 3 also labelled 'down'
    s = _with_steps(terrain, pd.concat([st, up, conflict]).sort_values("start_s", kind="stable"))
    with caplog.at_level(logging.WARNING):
        data = task_data(session_windows([s], n_samples=40), "terrain", [s])
    assert len(data.y) == len(st) - 1  # each step once; the contradicted step left out
    assert f"{len(up)} repeated step row(s)" in caplog.text
    assert "1 step(s) labelled twice with different labels left out" in caplog.text
    assert "'flat' / 'down'" in caplog.text


def test_labels_that_are_no_class_are_named_and_any_case_is_a_class(terrain, caplog):
    st = terrain.steps.copy().astype({"terrain": object})
    st.loc[0, "terrain"], st.loc[1, "terrain"], st.loc[2, "terrain"] = " Flat", "stairs", np.nan
    s = _with_steps(terrain, st)
    with caplog.at_level(logging.WARNING):
        data = task_data(session_windows([s], n_samples=40), "terrain", [s])
    assert len(data.y) == len(st) - 2 and data.n_skipped == 2  # 'Flat' is flat; 'stairs' and the empty one out
    line = [r.getMessage() for r in caplog.records if "not a terrain class" in r.getMessage()]
    assert len(line) == 1 and "'stairs'" in line[0] and "(empty)" in line[0] and "flat, up, down" in line[0]
    assert clean_steps(s, st)["terrain"].iloc[0] == "flat"
    # 'unclear' (the converters' marker of a step without a class) is left out and counted, not warned
    st = terrain.steps.copy().astype({"terrain": object})
    st.loc[0, "terrain"] = "unclear"
    assert bad_label_warning(terrain, st, "terrain") == (1, None)


def test_labels_shifted_against_the_foot_rest_are_said(terrain):
    assert misaligned_text(terrain, terrain.steps) is None
    late = terrain.steps.assign(start_s=terrain.steps["start_s"] + 0.5, end_s=terrain.steps["end_s"] + 0.5)
    text = misaligned_text(terrain, late)
    assert text is not None and "rest period of the foot" in text and "+0." in text
    assert misaligned_text(terrain, late, boundaries="rest") is None


def test_evaluate_warns_on_training_sessions_and_another_rate(model, terrain, caplog):
    with caplog.at_level(logging.WARNING):
        out = evaluate_model(model, [terrain], latency=False)
    assert out["training_sessions"] == [terrain.name]
    assert "were used to train the model" in caplog.text and "not held-out" in caplog.text
    assert not out["rate_mismatch"]
    other = copy.copy(model)
    other.sampling_rate_hz = {k: 100.0 for k in model.sampling_rate_hz}
    other.data_summary = {**model.data_summary, "sessions": [], "session_ids": []}
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        out = evaluate_model(other, [terrain], latency=False)
    assert "trained at 100 / 100 Hz" in caplog.text and out["rate_mismatch"]
    assert "not held-out" not in caplog.text
    # decision C36: the sessions label direction and length, which the model lacks: listed, not dropped
    assert any(s.startswith("direction: the sessions label it") for s in out["skipped"])
    # decision C37: per-class precision and F1 beside the recall
    t = out["tasks"]["terrain"]
    assert set(t["precision"]) == set(t["f1"]) == set(t["classes"])


def test_pooled_users_are_recorded_and_warned(terrain, caplog):
    other = copy.copy(terrain)
    other.meta = {**terrain.meta, "user": "someone-else"}
    with caplog.at_level(logging.WARNING):
        m = train_user([terrain, other], tasks=["terrain"], methods=["svm"], units=["foot"], cv=3,
                       distance_calibration=False)
    assert len(m.data_summary["users"]) == 2 and m.user.startswith("pooled: ")
    assert "--cv-groups user" in caplog.text


def test_cv_groups_user_with_one_user_says_so(terrain, caplog):
    with caplog.at_level(logging.WARNING):
        train_user([terrain], tasks=["terrain"], methods=["svm"], units=["foot"], cv=3, cv_groups="user",
                   distance_calibration=False)
    assert "every session is of one user" in caplog.text


def test_fold_warnings_are_collected_for_one_line():
    y = np.array(["a"] * 20 + ["b"] * 4)
    notes: list[str] = []
    for _ in range(4):  # once per unit
        _folds(y, 10, 0, "toy", notes=notes)
    assert len(notes) == 4 and len(set(notes)) == 1


def test_chosen_reason_names_the_ranking_column():
    from pdrlearn.cli.train import chosen_reason

    def r(bal):
        return {"balanced_accuracy": bal, "accuracy": bal}

    tm = TaskModel("terrain", ["flat", "up", "down"], models={"svm": {"foot": 1, "combined": 1}},
                   cv={"svm": {"foot": r(0.9), "combined": r(0.8)}}, chosen=("svm", "combined"))
    why = chosen_reason(tm)
    assert "balanced CV accuracy (80.0 %)" in why and "svm/foot 90.0 %" in why


def test_class_metrics_precision_and_f1():
    m = class_metrics(np.array(["a", "a", "b", "b"]), np.array(["a", "b", "b", "b"]), ["a", "b", "c"])
    assert m["precision"] == {"a": 1.0, "b": pytest.approx(2 / 3), "c": None}
    assert m["f1"]["b"] == pytest.approx(0.8) and m["f1"]["c"] is None
