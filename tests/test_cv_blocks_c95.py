"""Decision C95: ``train --cv-groups block``, folds of contiguous blocks of each walk with their neighbours left out
of training, so no stretch of a walk is on both sides of a fold (trial T6 finding 8)."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.classify.blocks import block_folds
from pdrlearn.classify.training import train_user
from pdrlearn.sim import simulate


def _check_no_leak(session, order, folds, gap=1):
    """Each fold's test steps are one contiguous run of each session's walking order; no training step is a test
    step or within ``gap`` steps of one in the same session; every step is tested exactly once."""
    tested = np.concatenate([te for _, te in folds])
    assert sorted(tested) == list(range(len(session)))
    for tr, te in folds:
        assert not set(tr) & set(te)
        for s in np.unique(session[te]):
            idx = np.flatnonzero(session == s)
            pos = {i: p for p, i in enumerate(idx[np.argsort(order[idx], kind="stable")])}
            test_pos = sorted(pos[i] for i in te if session[i] == s)
            assert test_pos == list(range(test_pos[0], test_pos[-1] + 1))  # one contiguous stretch
            train_pos = [pos[i] for i in tr if session[i] == s]
            assert all(p < test_pos[0] - gap or p > test_pos[-1] + gap for p in train_pos)


def test_block_folds_never_put_a_stretch_of_a_walk_or_its_neighbour_on_both_sides():
    rng = np.random.default_rng(8840)
    session = rng.integers(0, 3, 200)
    order = rng.permutation(200)  # rows of steps.csv, not in array order
    folds = block_folds(session, order, 5)
    assert len(folds) == 5
    _check_no_leak(session, order, folds)
    # gap 1 leaves out at most two neighbours per session and fold
    for tr, te in folds:
        assert len(tr) >= 200 - len(te) - 2 * 3


def test_one_session_per_exercise_trains_with_block_folds_where_session_folds_fall_back(caplog):
    """The README workflow: one length exercise holds the only long steps; session folds fall back to stratified
    steps (C59), block folds exist and are recorded (C95)."""
    walks = [simulate(sc, 8841, seed=0) for sc in ("terrain", "length")]
    kw = dict(tasks=["length"], methods=["svm"], units=["foot"], cv=4, distance_calibration=False)
    with caplog.at_level(logging.WARNING):
        by_session = train_user(walks, cv_groups="session", **kw)
    assert "CV by session not possible" in caplog.text
    assert by_session.settings["cv_groups"] == "steps"
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        m = train_user(walks, cv_groups="block", **kw)
    assert "not possible" not in caplog.text
    r = m.tasks["length"].cv["svm"]["foot"]
    assert (r["n_folds"], r["cv_blocks"], r["cv_users"]) == (4, 4, 0)
    assert (m.settings["cv_groups"], m.settings["cv_blocks"]) == ("block", 4)
    from pdrlearn.cli.train import cv_title

    assert cv_title(r) == "4-fold CV accuracy (contiguous blocks of each session, neighbours left out)"
