"""The per-step fast path of the length classifiers (issue 5 latency) equals the reference path.

Reference = the code before the fast path: length features as ``np.hstack`` of the kernel calls
(``peak_stats`` -> ``yaw_stats`` for the waist), the one-vs-rest SVM scores as one ``svc_decision`` call
per class, unit probabilities aligned with ``align_proba`` and soft-voted. Checked one step at a time on
simulated length steps (the runtime case) and as a batch: features bit-identical, probabilities within
1e-12, predictions identical.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from pdrlearn.classify.fusion import align_proba, aligned_proba, soft_vote
from pdrlearn.classify.svm import SVMClassifier, ovr_scores, svc_decision
from pdrlearn.classify.training import make_estimator, session_windows, task_data
from pdrlearn.features import SIGNALS, LengthFeatures
from pdrlearn.features import _kernels as K
from pdrlearn.features.transformers import (
    LENGTH_FORCE_STATS,
    LENGTH_WAIST_STATS,
    signal,
    times,
    waist_yaw_amplitude_duration,
    waist_yaw_stats,
)
from pdrlearn.features.windows import CHANNEL_INDEX
from pdrlearn.kernels.proba import softmax


@pytest.fixture(scope="module")
def length_steps():
    from pdrlearn.sim.simulate import simulate

    train = task_data(session_windows([simulate("length", user_seed=3, seed=0)], n_samples=40), "length")
    test = task_data(session_windows([simulate("length", user_seed=3, seed=1000)], n_samples=40), "length")
    return train, test


@pytest.fixture(scope="module")
def fused_models(length_steps):
    train, _ = length_steps
    return {m: make_estimator("length", m, "fused", seed=0).fit(train.X, train.y) for m in ("svm", "nn")}


def ref_signal(X, name):
    chans, sign, _ = SIGNALS[name]
    out = X[:, CHANNEL_INDEX[chans[0]], :].copy()
    for c in chans[1:]:
        out += X[:, CHANNEL_INDEX[c], :]
    return sign * out


def ref_length_features(tf: LengthFeatures, X) -> np.ndarray:
    cols = []
    if tf.unit != "waist":
        cols.append(K.segment_stats(ref_signal(X, "foot_acc_fwd"), times(X), tf.n_segments))
        fs = K.force_stats(ref_signal(X, "force"), times(X), zero_fraction=tf.zero_fraction)
        cols.append(np.column_stack([fs[s] for s in LENGTH_FORCE_STATS]))
    if tf.unit != "foot":
        ws = K.yaw_stats(K.peak_stats(ref_signal(X, "waist_yaw"), times(X)))
        cols.append(np.column_stack([ws[s] for s in LENGTH_WAIST_STATS]))
    return np.hstack(cols)


def ref_unit_proba(est, X) -> np.ndarray:
    F = ref_length_features(est[0], X)
    clf = est[-1]
    if isinstance(clf, SVMClassifier):
        Z = (F - clf.mean_) / clf.scale_
        return softmax(np.column_stack([svc_decision(Z, **p) for p in clf.decision_params_]))
    return clf.predict_proba(F)


def ref_fused_proba(fused, X) -> np.ndarray:
    probas = [align_proba(ref_unit_proba(e, X), e.classes_, fused.classes_) for e in fused.estimators_]
    return soft_vote(probas, fused.weights_)


def test_signals_equal_the_reference(length_steps):
    X = length_steps[1].X
    for name in SIGNALS:
        got = signal(X, name)
        assert np.array_equal(got, ref_signal(X, name), equal_nan=True), name
        assert not np.shares_memory(got, X), name  # a new array, as before


@pytest.mark.parametrize("unit", ["foot", "waist", "both"])
def test_length_features_bit_identical(length_steps, unit):
    X = length_steps[1].X
    tf = LengthFeatures(unit=unit).fit(X)
    assert np.array_equal(tf.transform(X), ref_length_features(tf, X))
    for i in range(len(X)):
        assert np.array_equal(tf.transform(X[i : i + 1]), ref_length_features(tf, X[i : i + 1]))
    assert tf.transform(X).shape[1] == len(tf.get_feature_names_out())


def test_waist_amplitude_duration_is_yaw_stats(length_steps):
    X = length_steps[1].X
    amp, dur = waist_yaw_amplitude_duration(X)
    ws = waist_yaw_stats(X)
    assert LENGTH_WAIST_STATS == ("amplitude", "duration")  # the column order _compute writes
    assert np.array_equal(amp, ws["amplitude"]) and np.array_equal(dur, ws["duration"])


def test_ovr_scores_equal_per_class_decisions(length_steps, fused_models):
    X = length_steps[1].X
    for est in fused_models["svm"].estimators_:
        clf = est[-1]
        Z = (est[0].transform(X) - clf.mean_) / clf.scale_
        ref = np.column_stack([svc_decision(Z, **p) for p in clf.decision_params_])
        np.testing.assert_allclose(ovr_scores(Z, clf.decision_stack_), ref, rtol=0, atol=1e-12)
        for i in range(len(Z)):
            one = Z[i : i + 1]
            want = np.column_stack([svc_decision(one, **p) for p in clf.decision_params_])
            np.testing.assert_allclose(ovr_scores(one, clf.decision_stack_), want, rtol=0, atol=1e-12)


@pytest.mark.parametrize("method", ["svm", "nn"])
def test_fused_one_step_equals_reference_path(length_steps, fused_models, method):
    X = length_steps[1].X
    fused = fused_models[method]
    pred, ref_pred = [], []
    for i in range(len(X)):
        one = X[i : i + 1]
        want = ref_fused_proba(fused, one)
        np.testing.assert_allclose(fused.predict_proba(one), want, rtol=0, atol=1e-12)
        pred.append(fused.predict(one)[0])
        ref_pred.append(fused.classes_[np.argmax(want, axis=1)][0])
    assert pred == ref_pred
    np.testing.assert_allclose(fused.predict_proba(X), ref_fused_proba(fused, X), rtol=0, atol=1e-12)
    assert len(set(pred)) == 3  # the test steps reach every class: the comparison covers all three


def test_svm_pickled_without_stack_rebuilds_it(length_steps, fused_models):
    X = length_steps[1].X
    est = fused_models["svm"].estimators_[0]
    clf = est[-1]
    state = dict(clf.__dict__)
    state.pop("decision_stack_")
    old = SVMClassifier.__new__(SVMClassifier)
    old.__setstate__(state)  # a model saved before decision_stack_ existed
    F = est[0].transform(X)
    assert np.array_equal(old.predict_proba(F), clf.predict_proba(F))
    again = pickle.loads(pickle.dumps(clf))
    assert np.array_equal(again.decision_function(F), clf.decision_function(F))


def test_aligned_proba_equals_align_proba():
    p = np.array([[0.2, 0.5, 0.3]])
    cls = np.array(["long", "normal", "short"])
    assert np.array_equal(aligned_proba(p, cls, cls), align_proba(p, cls, cls))
    perm = np.array(["short", "long", "normal"])
    assert np.array_equal(aligned_proba(p, perm, cls), align_proba(p, perm, cls))
    two = np.array(["long", "short"])
    assert np.array_equal(aligned_proba(p[:, :2], two, cls), align_proba(p[:, :2], two, cls))
    p32 = p.astype(np.float32)
    assert aligned_proba(p32, cls, cls).dtype == np.float64
