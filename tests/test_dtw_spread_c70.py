"""Decisions C69/C70: the lowest-mean-distance DTW rule draws queries to the most compact class; the spread-corrected
rule (``rule="spread"``) scores the mean distance minus half the class's own mean reference distance."""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest

import pdrlearn.classify.training as training
from pdrlearn.classify.dtw import DTWClassifier, class_spread_offsets, dtw_block
from pdrlearn.errors import DataError


def _two_mode_steps(n: int = 12, seed: int = 0):
    """Class 'a' compact at 0; class 'b' two modes, +1 and +4 (1 channel, 40 samples, noise SD 0.1)."""
    rng = np.random.default_rng(seed)
    levels = [0.0] * n + [1.0] * n + [4.0] * n
    X = np.array([lv + 0.1 * rng.standard_normal(40) for lv in levels])[:, None, :]
    y = np.array(["a"] * n + ["b"] * (2 * n))
    return X, y


def test_mean_rule_draws_queries_to_the_compact_class():
    """C69's mechanism: a query of b's near mode is nearer a's compact references on the mean than b's own (whose far
    mode adds to the mean); the spread rule gives it to b and keeps a's and b's far-mode queries."""
    X, y = _two_mode_steps()
    Q, _ = _two_mode_steps(n=5, seed=1)  # 5 of each: a, b near, b far
    want = np.array(["a"] * 5 + ["b"] * 10)
    mean = DTWClassifier(rule="mean", n_references=100).fit(X, y).predict(Q)
    spread = DTWClassifier(rule="spread", n_references=100).fit(X, y).predict(Q)
    assert list(mean[5:10]) == ["a"] * 5  # the thesis' rule: b's near mode called a
    assert list(spread) == list(want)


def test_class_spread_offsets_by_hand_and_pruning_stays_exact():
    X, y = _two_mode_steps()
    clf = DTWClassifier(rule="spread", n_references=100).fit(X, y)
    R, lab = clf.references_, clf.reference_labels_
    for k in range(2):
        D = dtw_block(R[lab == k], R[lab == k], window=clf.window_samples_)
        m = len(D)
        assert clf.class_offset_[k] == pytest.approx(0.5 * D.sum() / (m * (m - 1)))  # diagonal is 0
    assert class_spread_offsets(R[:1], lab[:1], 2, window=4).tolist() == [0.0, 0.0]  # one reference: 0
    Q, _ = _two_mode_steps(n=5, seed=2)
    pruned = DTWClassifier(rule="spread", n_references=100, prune=True).fit(X, y)
    assert list(pruned.predict(Q)) == list(clf.predict(Q))
    np.testing.assert_allclose(clf.predict_proba(Q).sum(axis=1), 1.0)
    assert np.all(DTWClassifier(rule="mean").fit(X, y).class_offset_ == 0)
    with pytest.raises(DataError, match="rule must be 'mean' or 'spread'"):
        DTWClassifier(rule="median").fit(X, y)


def _balanced(truth, pred) -> float:
    return float(np.mean([np.mean(pred[truth == c] == c) for c in np.unique(truth)]))


def test_waist_dtw_above_chance_on_fresh_users(monkeypatch):
    """C70: on fresh simulated users 3572-3573 (held-out exercises, seed 1000) the waist DTW with the spread rule is
    at least 10 points above chance in terrain and direction (balanced accuracy) and 20 points above the thesis' rule
    (seen when written: terrain 42.55 -> 82.74 %, direction 57.04 -> 83.31 %)."""
    from pdrlearn.features import TASK_COLUMNS
    from pdrlearn.sim import simulate

    sim = partial(simulate, device_errors=True)
    exercises = ("terrain", "direction", "length")
    scores: dict[tuple[str, str], list] = {}
    for user in (3572, 3573):
        cal = [sim(ex, user_seed=user, speed="normal") for ex in exercises]
        held = [sim(ex, user_seed=user, speed="normal", seed=1000) for ex in exercises]
        for rule in ("mean", "spread"):
            monkeypatch.setattr(training, "DTW_RULE", rule)
            model = training.train_user(cal, tasks=["terrain", "direction"], methods=["dtw"], units=["waist"],
                                        cv=2, distance_calibration=False)
            for task in ("terrain", "direction"):
                col = TASK_COLUMNS[task]
                for s in held:
                    pr = model.predict_steps(s, tasks=[task], method="dtw", unit="waist", windows="given")
                    t, p = scores.setdefault((task, rule), [[], []])
                    t += list(s.steps[col].astype(str))
                    p += list(pr[col].astype(str))
    for task, chance in (("terrain", 1 / 3), ("direction", 1 / 2)):
        spread = _balanced(*map(np.array, scores[(task, "spread")]))
        mean = _balanced(*map(np.array, scores[(task, "mean")]))
        assert spread >= chance + 0.10, (task, spread)
        assert spread >= mean + 0.20, (task, mean, spread)  # C69: the thesis' rule on the pooled classes


def test_sklearn_contract_with_the_spread_rule():
    from sklearn.utils.estimator_checks import check_estimator

    results = check_estimator(DTWClassifier(n_references=8, rule="spread"), on_fail=None)
    assert not [(r["check_name"], str(r["exception"])[:120]) for r in results if r["status"] == "failed"]
