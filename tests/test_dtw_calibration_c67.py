"""Decisions C67/C68: DTW probabilities calibrated by a temperature fitted in an inner cross-validation; the
temperature is what the bundle carries, so the runtime gives the training side's probabilities."""

from __future__ import annotations

import math

import numpy as np
import pytest
from sklearn.utils.estimator_checks import check_estimator

import pdrlearn.classify.training as training
from pdrlearn.classify.calibration import (
    confidence_ece,
    cv_scores,
    expected_calibration_error,
    fit_temperature,
    smoothed_targets,
)
from pdrlearn.classify.dtw import DTWClassifier
from pdrlearn.errors import DataError
from tests.test_classify_estimators import synthetic_steps


def test_smoothed_targets_by_hand():
    # Platt 1999 sec. 2.2: class 0 has 2 steps -> 3/4, class 1 has 1 step -> 2/3
    t = smoothed_targets(np.array([0, 0, 1]), 2)
    np.testing.assert_allclose(t, [[0.75, 0.25], [0.75, 0.25], [1 / 3, 2 / 3]])
    t3 = smoothed_targets(np.array([2, 2]), 3)  # the rest spread over the other two classes
    np.testing.assert_allclose(t3, [[0.125, 0.125, 0.75]] * 2)


def test_fit_temperature_on_hand_made_distances():
    # 10 steps per class, own-class mean distance 1, other 3: scores = -distances, gap 2. The smoothed
    # target is 11/12, so the optimum solves 1 / (1 + exp(-2 / T)) = 11/12: T = 2 / ln 11.
    d = np.array([[1.0, 3.0]] * 10 + [[3.0, 1.0]] * 10)
    y = np.array([0] * 10 + [1] * 10)
    t = fit_temperature(-d, y)
    assert t == pytest.approx(2 / math.log(11), rel=1e-3)
    # more evidence (100 steps per class) -> surer: T = 2 / ln 101
    t100 = fit_temperature(-np.repeat(d, 10, axis=0), np.repeat(y, 10))
    assert t100 == pytest.approx(2 / math.log(101), rel=1e-3) and t100 < t
    # held-out mistakes make the model less sure: 1 of 10 per class wrong puts a weight of 9 * 11/12 + 1/12 on
    # "right" and 9/12 + 11/12 on "wrong", so p(right) = 100/120 = 5/6 at the optimum: T = 2 / ln 5
    d_err = d.copy()
    d_err[[0, 10]] = d_err[[0, 10]][:, ::-1]
    assert fit_temperature(-d_err, y) == pytest.approx(2 / math.log(5), rel=1e-3)
    # nothing to fit: the scale comes back
    assert fit_temperature(-np.ones((4, 2)), np.array([0, 1, 0, 1]), scale=2.5) == 2.5
    assert fit_temperature(-d[:, :1], y, scale=0.7) == 0.7


def test_expected_calibration_error_by_hand():
    # bin [0.9, 1.0): accuracy 1/2 at confidence 0.9; bin [0.6, 0.7): accuracy 1 at 0.6 -> (2*0.4 + 2*0.4) / 4
    assert confidence_ece([0.9, 0.9, 0.6, 0.6], [1, 0, 1, 1]) == pytest.approx(0.4)
    p = np.array([[0.9, 0.1], [0.9, 0.1], [0.4, 0.6], [0.4, 0.6]])
    assert expected_calibration_error(p, np.array([0, 1, 1, 1])) == pytest.approx(0.4)
    assert expected_calibration_error(np.eye(2), np.array([0, 1])) == 0.0
    assert math.isnan(confidence_ece([], []))


@pytest.mark.parametrize("noise", [0.35, 1.2])
def test_cv_calibration_keeps_predict_and_is_better_calibrated(noise):
    X, y = synthetic_steps(460, seed=1, noise=noise)
    gap = DTWClassifier(calibration="gap").fit(X[:200], y[:200])
    cv = DTWClassifier(calibration="cv").fit(X[:200], y[:200])
    Xt, yt = X[200:], y[200:]
    assert np.array_equal(gap.predict(Xt), cv.predict(Xt))  # a positive temperature keeps the argmin
    np.testing.assert_array_equal(gap.references_, cv.references_)
    p = cv.predict_proba(Xt)
    assert np.all((p >= 0) & (p <= 1))
    np.testing.assert_allclose(p.sum(axis=1), 1.0)
    assert np.array_equal(cv.classes_[p.argmax(axis=1)], cv.predict(Xt))
    yi = np.searchsorted(cv.classes_, yt)
    ece_gap, ece_cv = (expected_calibration_error(m.predict_proba(Xt), yi) for m in (gap, cv))
    assert ece_cv < ece_gap / 3  # gap: p(top) ~0.5-0.6 at ~100 % accuracy (L184); cv: near the accuracy
    assert np.mean(p.max(axis=1) >= 0.95) > 0.5 and np.mean(gap.predict_proba(Xt).max(axis=1) >= 0.95) == 0


def test_cv_temperature_comes_from_the_training_steps_only():
    X, y = synthetic_steps(300, seed=3, noise=0.8)
    a = DTWClassifier(calibration="cv").fit(X[:150], y[:150])
    yi = np.searchsorted(a.classes_, y[:150])
    held = cv_scores(lambda: DTWClassifier(calibration="gap"), X[:150], yi, lambda e, Xp: -e.mean_distances(Xp))
    assert a.temperature_ == pytest.approx(fit_temperature(*held, scale=DTWClassifier().fit(X[:150], y[:150])
                                                           .temperature_))
    # a class with one step cannot be held out: C4's temperature stays
    y1 = y[:30].copy()
    y1[0] = "odd"
    one = DTWClassifier(calibration="cv").fit(X[:30], y1)
    assert one.temperature_ == DTWClassifier(calibration="gap").fit(X[:30], y1).temperature_


def test_unknown_calibration_is_one_line():
    X, y = synthetic_steps(30, seed=0)
    with pytest.raises(DataError, match="calibration must be 'gap' or 'cv'"):
        DTWClassifier(calibration="platt").fit(X, y)


def test_sklearn_contract_with_cv_calibration():
    results = check_estimator(DTWClassifier(n_references=8, calibration="cv"), on_fail=None)
    assert not [(r["check_name"], str(r["exception"])[:120]) for r in results if r["status"] == "failed"]


@pytest.mark.parametrize("rule", ["mean", "spread"])
def test_exported_calibrated_dtw_gives_the_same_probabilities(tmp_path, monkeypatch, rule):
    """C68: the bundle's temperature is the calibrated one; the runtime equals predict_steps. C70: with the spread
    rule the bundle carries the class offsets (absent with the thesis' rule, as before)."""
    from pdrlearn.classify import load_model, train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.features import TASK_COLUMNS, step_windows
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.classify import TaskClassifier
    from tests.runtime_helpers import _with_bounds, synthetic_session

    monkeypatch.setattr(training, "DTW_CALIBRATION", "cv")
    monkeypatch.setattr(training, "DTW_RULE", rule)
    train = synthetic_session(90, seed=0)
    _with_bounds(train_user([train], cv=2, seed=0, units=["foot", "waist", "fused"], methods=["dtw"],
                            tasks=["terrain"])).save(tmp_path / "model")
    export_model(tmp_path / "model", tmp_path / "bundle", methods=["dtw"])
    model = load_model(tmp_path / "model")
    bundle = load_bundle(tmp_path / "bundle")
    test = synthetic_session(30, seed=5, name="held_out")
    W = step_windows(test, test.steps, n_samples=model.n_samples).X
    ctx = {"signals": bundle.manifest["features"]["signals"],
           "channel_index": {c: i for i, c in enumerate(bundle.manifest["features"]["channels"])}}
    for unit in ("foot", "waist"):
        clf = model.tasks["terrain"].models["dtw"][unit].steps[-1][1]
        assert clf.calibration == "cv"
        entry = bundle.tasks["terrain"]["methods"]["dtw"][unit]
        assert entry["temperature"] == clf.temperature_
        assert ("class_offset" in entry) == (rule == "spread") and clf.rule == rule
    for unit in ("foot", "waist", "fused"):
        ref = model.predict_steps(test, test.steps, tasks=["terrain"], method="dtw", unit=unit, windows="given")
        classes, proba = TaskClassifier(bundle, "terrain", ctx, method="dtw", unit=unit).predict(W)
        want = ref[[f"p_terrain_{c}" for c in bundle.tasks["terrain"]["classes"]]].to_numpy()
        assert list(classes) == list(ref[TASK_COLUMNS["terrain"]])
        assert np.abs(proba - want).max() <= 1e-6, unit
