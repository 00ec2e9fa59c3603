"""DTW, SVM, NN and unit-fusion classifiers: scikit-learn contract, held-out accuracy, kernels."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sklearn.linear_model import LogisticRegression
from sklearn.naive_bayes import GaussianNB
from sklearn.utils.estimator_checks import check_estimator

from pdrlearn.classify.dtw import DTWClassifier, as_series, dtw_block, envelope, lb_keogh
from pdrlearn.classify.fusion import UnitFusionClassifier, simplex_grid, soft_vote
from pdrlearn.classify.nn import THESIS_HIDDEN, NNClassifier
from pdrlearn.classify.svm import SVMClassifier, kernel_for
from pdrlearn.errors import DataError


def synthetic_steps(n: int, seed: int, noise: float = 0.35):
    """Three classes of 3-channel, 40-sample 'steps' (chirps of class-dependent frequency) + labels."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 1, 40)
    y = np.array(["flat", "up", "down"])[rng.integers(0, 3, n)]
    freq = {"flat": 1.0, "up": 1.35, "down": 1.7}
    X = np.stack(
        [
            np.stack(
                [
                    np.sin(2 * np.pi * freq[c] * t + rng.normal(0, 0.3)) + rng.normal(0, noise, 40)
                    for _ in range(3)
                ]
            )
            for c in y
        ]
    )
    return X, y


def synthetic_features(n: int, seed: int, sep: float = 1.5, n_features: int = 12):
    """Gaussian blobs with class-dependent means in a few features."""
    rng = np.random.default_rng(seed)
    y = np.array(["short", "normal", "long"])[rng.integers(0, 3, n)]
    centre = {"short": -sep, "normal": 0.0, "long": sep}
    X = rng.normal(size=(n, n_features))
    X[:, :3] += np.array([centre[c] for c in y])[:, None]
    return X, y


@pytest.mark.parametrize(
    "est, xfail",
    [
        (SVMClassifier(C=1.0), {}),  # C="cv" only wraps fits of this estimator (test_svm_c_by_cv)
        (NNClassifier(max_epochs=10), {}),
        (DTWClassifier(n_references=8), {}),
        (
            UnitFusionClassifier([("a", GaussianNB(), [0]), ("b", GaussianNB(), [1])], weight_step=0.25),
            {"check_fit2d_1feature": "units address columns 0 and 1; a 1-column X cannot feed them"},
        ),
    ],
)
def test_sklearn_estimator_checks(est, xfail):
    results = check_estimator(est, on_fail=None, expected_failed_checks=xfail)
    failed = [(r["check_name"], str(r["exception"])[:120]) for r in results if r["status"] == "failed"]
    assert not failed


def test_dtw_beats_chance_on_held_out_steps():
    X, y = synthetic_steps(260, seed=1)
    clf = DTWClassifier(n_references=36).fit(X[:160], y[:160])
    assert len(clf.references_) <= 108
    acc = np.mean(clf.predict(X[160:]) == y[160:])
    assert acc > 0.9  # chance = 1/3
    proba = clf.predict_proba(X[160:])
    np.testing.assert_allclose(proba.sum(axis=1), 1.0)
    assert np.array_equal(clf.classes_[proba.argmax(axis=1)], clf.predict(X[160:]))


def test_dtw_pruning_gives_the_exact_argmin():
    X, y = synthetic_steps(200, seed=2, noise=0.8)
    full = DTWClassifier(prune=False).fit(X[:120], y[:120])
    pruned = DTWClassifier(prune=True).fit(X[:120], y[:120])
    assert np.array_equal(full.predict(X[120:]), pruned.predict(X[120:]))


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 10_000), window=st.integers(1, 8))
def test_lb_keogh_is_a_lower_bound(seed, window):
    rng = np.random.default_rng(seed)
    S = as_series(rng.normal(size=(6, 2, 30)))
    upper, lower = envelope(S, window=window)
    assert np.all(lb_keogh(S[:2], upper, lower) <= dtw_block(S[:2], S, window=window) + 1e-9)


def test_dtw_rejects_nan():
    X, y = synthetic_steps(30, seed=3)
    X[0, 0, 0] = np.nan
    with pytest.raises(ValueError):
        DTWClassifier().fit(X, y)


def test_svm_thesis_kernels():
    assert kernel_for("terrain", "up") == {"kernel": "poly", "degree": 3}
    assert kernel_for("direction", "backward") == {"kernel": "linear"}
    kernels = [kernel_for("length", c)["kernel"] for c in ("short", "normal", "long")]
    assert kernels == ["rbf", "poly", "linear"]
    X, y = synthetic_features(300, seed=4)
    clf = SVMClassifier(task="length").fit(X[:200], y[:200])
    assert clf.kernels_["normal"] == {"kernel": "poly", "degree": 2}
    assert np.mean(clf.predict(X[200:]) == y[200:]) > 0.75


def test_svm_c_by_cv():
    X, y = synthetic_features(150, seed=9)
    clf = SVMClassifier(task="terrain", C_grid=(0.3, 10.0)).fit(X, np.where(y == "short", "up", "flat"))
    assert clf.C_ in (0.3, 10.0)
    with pytest.raises(DataError, match="'cv'"):
        SVMClassifier(C="auto").fit(X, y)


def test_nn_thesis_sizes_and_determinism():
    X, y = synthetic_features(300, seed=5)
    a = NNClassifier(task="terrain", random_state=3).fit(X[:200], y[:200])
    b = NNClassifier(task="terrain", random_state=3).fit(X[:200], y[:200])
    assert a.coefs_[0].shape == (X.shape[1], THESIS_HIDDEN["terrain"]) == (12, 144)
    np.testing.assert_array_equal(a.predict_proba(X[200:]), b.predict_proba(X[200:]))
    assert np.mean(a.predict(X[200:]) == y[200:]) > 0.75


def test_one_class_is_a_named_error():
    X, _ = synthetic_features(20, seed=6)
    with pytest.raises(DataError, match="one class"):
        NNClassifier().fit(X, ["flat"] * 20)


def test_fusion_beats_its_worst_unit_and_learns_weights():
    # unit "good" sees informative columns, unit "poor" sees mostly noise
    rng = np.random.default_rng(7)
    X, y = synthetic_features(400, seed=7, sep=1.2)
    X = np.column_stack([X[:, :3], rng.normal(size=(400, 3)) + 0.3 * X[:, :1]])
    units = [("good", LogisticRegression(), [0, 1, 2]), ("poor", LogisticRegression(), [3, 4, 5])]
    fused = UnitFusionClassifier(units, random_state=0).fit(X[:250], y[:250])
    probas = fused.unit_proba(X[250:])
    acc = {name: np.mean(fused.classes_[p.argmax(1)] == y[250:]) for name, p in probas.items()}
    acc_fused = np.mean(fused.predict(X[250:]) == y[250:])
    assert acc_fused > min(acc.values())
    assert fused.weights_[0] > fused.weights_[1]
    np.testing.assert_allclose(fused.weights_.sum(), 1.0)


def test_fusion_given_weights_and_dtw_units():
    X, y = synthetic_steps(150, seed=8)
    units = [("foot", DTWClassifier(), [0, 1]), ("waist", DTWClassifier(), [2])]
    fused = UnitFusionClassifier(units, weights=[0.6, 0.4]).fit(X[:100], y[:100])  # thesis ch. 6.2.2.3
    np.testing.assert_allclose(fused.weights_, [0.6, 0.4])
    assert np.mean(fused.predict(X[100:]) == y[100:]) > 0.85
    with pytest.raises(DataError, match="weights"):
        UnitFusionClassifier(units, weights=[1.0]).fit(X, y)


def test_soft_vote_and_grid():
    p1, p2 = np.array([[0.9, 0.1]]), np.array([[0.2, 0.8]])
    np.testing.assert_allclose(soft_vote([p1, p2], np.array([0.5, 0.5])), [[0.55, 0.45]])
    g = simplex_grid(3, 0.5)
    assert len(g) == 6 and np.allclose(g.sum(axis=1), 1)
