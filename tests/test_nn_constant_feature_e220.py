"""Decision E220: a feature constant in training up to float64 rounding is not standardized by its ~1e-16 std."""

from __future__ import annotations

import numpy as np

from pdrlearn.classify.nn import NNClassifier, input_scale


def _data():
    rng = np.random.default_rng(10360)  # simulated-user range of session 39's fixer FQ
    x = rng.normal(size=90)
    # a duration fraction: 1 but for rounding (what the waist yaw duration of a simulated walk gave)
    const = 1.0 + rng.choice([-1, 0, 1, 2], size=90) * np.finfo(float).eps / 2
    y = np.where(x > 0, "long", "short")
    return np.column_stack([x, const]), y


def test_a_rounding_noise_feature_gets_unit_scale():
    X, _ = _data()
    s = input_scale(X, X.mean(axis=0))
    assert s[1] == 1.0
    assert s[0] == X[:, 0].std()


def test_rounding_noise_does_not_move_the_probability():
    X, y = _data()
    clf = NNClassifier(task="length", random_state=0, max_epochs=30).fit(X, y)
    a, b = X[:5].copy(), X[:5].copy()
    a[:, 1] = 1.0 - np.finfo(float).eps / 2  # 0.9999999999999999
    b[:, 1] = 1.0  # its float32 rounding
    assert np.abs(clf.predict_proba(a) - clf.predict_proba(b)).max() < 1e-9
