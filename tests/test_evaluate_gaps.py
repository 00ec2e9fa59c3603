"""evaluate on a session with a sensor gap (decision B17, docs/decisions/bad-input.md): the steps that lost a
unit are scored the way ``track`` classifies them (``UserModel.predict_steps``, decision B11) -- by the best
model that runs without that unit, or, with none, left out of the score with one warning naming the
session and the gap. Before, evaluate stopped with "terrain features: N of M steps have NaN foot_acc samples"."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.io.session import Stream


def _with_gap(s, t0, t1, prefixes=("w",)):
    for name in [n for n in s.streams if n[0] in prefixes and n[1:] in ("Accelerometer", "Gyroscope")]:
        x = s.streams[name]
        keep = (x.t < t0) | (x.t >= t1)
        s.streams[name] = Stream(name, x.t[keep], x.values[keep])
    return s


@pytest.fixture(scope="module")
def model():
    from pdrlearn.classify import train_user
    from tests.test_classify_training import labelled_session

    return train_user([labelled_session(1, 12), labelled_session(2, 12)], tasks=["terrain"],
                      methods=["svm"], cv=3, seed=0, units=["foot", "waist", "fused", "combined"])


def _gap_rows(s, model, unit):
    from pdrlearn.features import step_windows

    return step_windows(s, n_samples=model.n_samples, boundaries=model.boundaries).gap_steps[unit]


def test_a_waist_gap_is_scored_like_track_classifies_it(model):
    from pdrlearn.classify import evaluate_model
    from tests.test_classify_training import labelled_session

    s = _with_gap(labelled_session(11, 4), 4.0, 8.0)
    gap = _gap_rows(s, model, "waist")
    assert gap.any() and (~gap).any()
    res = evaluate_model(model, [s], latency=False)["tasks"]["terrain"]
    df = model.predict_steps(s, tasks=["terrain"])  # what track uses
    assert set(df["method_terrain"][gap].str.split("/").str[1]) == {"foot"}
    expected = float(np.mean(df["terrain"].to_numpy() == s.steps["terrain"].to_numpy()))
    assert res["n_steps"] == len(s.steps) and res["n_gap_unclassified"] == 0
    assert res["accuracy"] == pytest.approx(expected)
    units = res["methods"]["svm"]["units"]
    assert units["foot"]["n_steps"] == len(s.steps)
    assert units["waist"]["n_steps"] == units["fused"]["n_steps"] == units["combined"]["n_steps"] == int((~gap).sum())


def test_a_gap_in_every_unit_leaves_those_steps_out_with_one_warning(model, caplog):
    from pdrlearn.classify import evaluate_model
    from tests.test_classify_training import labelled_session

    s = _with_gap(labelled_session(12, 4, name="gappy"), 4.0, 8.0, prefixes=("f", "w"))
    gap = _gap_rows(s, model, "foot")
    with caplog.at_level(logging.WARNING, logger="pdrlearn.classify.evaluation"):
        res = evaluate_model(model, [s], latency=False)["tasks"]["terrain"]
    assert res["n_steps"] == int((~gap).sum()) and res["n_gap_unclassified"] == int(gap.sum())
    df = model.predict_steps(s, tasks=["terrain"])
    assert df["terrain"][gap].isna().all()  # track leaves them unclassified too
    msgs = [r.getMessage() for r in caplog.records if r.name == "pdrlearn.classify.evaluation"]
    assert len(msgs) == 1, msgs
    assert "session 'gappy'" in msgs[0] and f"{int(gap.sum())} of {len(gap)}" in msgs[0], msgs
    assert "s at 4.0 s in " in msgs[0], msgs


def test_a_session_lost_entirely_to_gaps_is_skipped_not_scored(model):
    from pdrlearn.classify import evaluate_model
    from tests.test_classify_training import labelled_session

    s = _with_gap(labelled_session(13, 4), 0.5, 13.5, prefixes=("f", "w"))  # every step (1-13 s)
    res = evaluate_model(model, [s], latency=False)
    assert "terrain" not in res["tasks"]
    assert any("every labelled step overlaps a sensor gap" in x for x in res["skipped"]), res["skipped"]
