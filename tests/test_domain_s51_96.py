"""Steps decision 96: a class's labelled steps outside the range of the training steps of that class (a stairs-trained
terrain model on slopes) are said, though they lie inside the pooled training range (classifiers C16)."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from pdrlearn.classify.domain import (
    attach_class_ranges,
    attach_ranges,
    class_domain,
    class_domain_line,
    step_class_score,
    step_score,
)

_GRADE = {"flat": 0.0, "up": 0.6, "down": -0.6}  # a stair's rise per tread (~0.17 / 0.28 m)


def _steps(grades, rng, n=40):
    labels = np.repeat(list(grades), n)
    X = np.column_stack([np.repeat(list(grades.values()), n) + rng.normal(0, 0.03, n * len(grades)),
                         rng.normal(1.0, 0.1, n * len(grades))])  # feature 0: the step's grade; 1: its time
    return X, labels


@pytest.fixture(scope="module")
def stairs_model():
    rng = np.random.default_rng(96)
    X, y = _steps(_GRADE, rng)
    est = make_pipeline(StandardScaler(), LogisticRegression()).fit(X, y)
    attach_ranges(est, X)
    assert attach_class_ranges(est, X, y) == 1
    return est


def _line(est, X, y):
    d, worst = step_class_score(est, X, y)
    pooled = float((step_score(est, X)[0] > 0.5).mean())
    return class_domain_line("terrain", class_domain(d, y, worst), pooled), pooled


def test_slopes_on_a_stairs_model_are_said_96(stairs_model):
    X, y = _steps({"flat": 0.0, "up": 0.15, "down": -0.15}, np.random.default_rng(1))  # 15 % slopes
    line, pooled = _line(stairs_model, X, y)
    assert pooled < 0.05  # C16's pooled range sees nothing: the slopes lie between flat and stairs
    assert line is not None and "40 of 40 labelled 'down' steps (100 %, most often x0; also up 100 %)" in line
    assert "though 0 % lie outside its whole training range" in line and "trained on stairs" in line
    assert "steps.md 96" in line


def test_stairs_on_a_stairs_model_are_quiet_96(stairs_model):
    X, y = _steps(_GRADE, np.random.default_rng(2))
    assert _line(stairs_model, X, y)[0] is None
    X[:, 1] *= 4.0  # steps outside the whole range: C16's share, not this line (its detail stays opt-in)
    X[y == "up", 0] = 0.15
    line, pooled = _line(stairs_model, X, y)
    assert pooled > 0.5 and line is None


def test_without_class_ranges_no_score_96():
    X, y = _steps(_GRADE, np.random.default_rng(3))
    est = make_pipeline(StandardScaler(), LogisticRegression()).fit(X, y)  # a model trained before 96
    assert step_class_score(est, X, y) is None
    few = np.array(["flat"] * (len(y) - 5) + ["up"] * 5)  # a class with < 10 training steps keeps no range
    attach_class_ranges(est, X, few)
    d, _ = step_class_score(est, X, few)
    assert np.isnan(d[few == "up"]).all() and np.isfinite(d[few == "flat"]).all()
