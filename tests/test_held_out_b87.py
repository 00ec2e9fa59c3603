"""Decision B87: `evaluate` knows a training session by its data, not its name (trial `teaching`, finding 2:
`import --out Kalibrierung/Gelände` and `--out Test/Gelände` are two recordings of one name); B88: a model whose
sessions name no user is 'unnamed', not named after the first session's folder."""

from __future__ import annotations

import copy
import logging

import pytest

from pdrlearn.classify.evaluation import evaluate_model
from pdrlearn.classify.training import UNNAMED_USER, train_user
from pdrlearn.sim.simulate import simulate


def _named(session, name: str, user=None):
    s = copy.copy(session)
    s.name = name
    s.meta = {k: v for k, v in session.meta.items() if k not in ("user", "subject")}
    if user is not None:
        s.meta["user"] = user
    return s


@pytest.fixture(scope="module")
def calib():
    return _named(simulate("terrain", user_seed=261, seed=0), "Gelände")


@pytest.fixture(scope="module")
def model(calib):
    return train_user([calib], tasks=["terrain"], methods=["svm"], units=["foot"], cv=3, distance_calibration=False)


def test_another_recording_of_the_same_name_is_held_out(model, caplog):
    test = _named(simulate("terrain", user_seed=261, seed=1), "Gelände")
    with caplog.at_level(logging.WARNING):
        out = evaluate_model(model, [test], latency=False)
    assert out["training_sessions"] == [] and "not held-out" not in caplog.text


def test_the_training_recording_under_another_name_is_not(model, calib, caplog):
    with caplog.at_level(logging.WARNING):
        out = evaluate_model(model, [_named(calib, "Kopie")], latency=False)
    assert out["training_sessions"] == ["Kopie"]
    line = [r.getMessage() for r in caplog.records if "not held-out" in r.getMessage()]
    assert len(line) == 1 and "the same recordings as in its manifest" in line[0], line


def test_a_model_without_ids_is_matched_by_name(model, caplog):
    old = copy.copy(model)
    old.data_summary = {k: v for k, v in model.data_summary.items() if k != "session_ids"}
    test = _named(simulate("terrain", user_seed=261, seed=1), "Gelände")
    with caplog.at_level(logging.WARNING):
        out = evaluate_model(old, [test], latency=False)
    assert out["training_sessions"] == ["Gelände"] and "matched by session name" in caplog.text


def test_the_model_user_is_not_the_first_folder_name(model, calib):
    assert model.user == UNNAMED_USER
    named = train_user([_named(calib, "Gelände", user="anna")], tasks=["terrain"], methods=["svm"],
                       units=["foot"], cv=3, distance_calibration=False)
    assert named.user == "anna"
