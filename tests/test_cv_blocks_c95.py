"""Decision C95: ``train --cv-groups block``, folds of contiguous blocks of each walk with their neighbours left out
of training, so no stretch of a walk is on both sides of a fold (trial T6 finding 8)."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.classify.blocks import block_folds
from pdrlearn.classify.training import train_user
from pdrlearn.sim import simulate


def _check_no_leak(session, start, end, side, folds):
    """Every step is tested exactly once; no training window overlaps or touches a test window of its session, and
    each foot's stride right before and right after a held-out block (in time) is not trained on."""
    tested = np.concatenate([te for _, te in folds])
    assert sorted(tested) == list(range(len(session)))
    for tr, te in folds:
        assert not set(tr) & set(te)
        for s in np.unique(session[te]):
            a, b = te[session[te] == s], tr[session[tr] == s]
            gap = np.maximum(start[b][:, None] - end[a][None, :], start[a][None, :] - end[b][:, None])
            assert (gap > 0).all()  # no training window touches a test window
            first, last = start[a].min(), start[a].max()
            for f in np.unique(side[session == s]):
                own = np.flatnonzero((session == s) & (side == f))
                own = own[np.argsort(start[own], kind="stable")]
                before, after = own[start[own] < first], own[start[own] > last]
                for neighbour in [*before[-1:], *after[:1]]:
                    assert neighbour not in set(b)


def _walk(n, rng, two_feet=False):
    """Start/end of ``n`` consecutive strides (each ends where the next of its foot starts); two feet: left and
    right strides interleaved, half a stride apart (as mobgap's tables)."""
    dur = rng.uniform(1.0, 1.3, n)
    if not two_feet:
        start = np.concatenate([[0.0], np.cumsum(dur)[:-1]])
        return start, start + dur, np.full(n, "right", dtype=object)
    side = np.array(["right", "left"] * (n // 2), dtype=object)
    start, end = np.zeros(n), np.zeros(n)
    for f, off in (("right", 0.0), ("left", 0.6)):
        i = np.flatnonzero(side == f)
        start[i] = off + np.concatenate([[0.0], np.cumsum(dur[i])[:-1]])
        end[i] = start[i] + dur[i]
    return start, end, side


def test_block_folds_never_put_a_stretch_of_a_walk_or_its_neighbour_on_both_sides():
    rng = np.random.default_rng(9000)
    parts = [_walk(70, rng) for _ in range(3)]
    session = np.repeat(np.arange(3), 70)
    start, end, side = (np.concatenate([p[j] for p in parts]) for j in range(3))
    folds = block_folds(session, start, end, 5, side)
    assert len(folds) == 5
    _check_no_leak(session, start, end, side, folds)
    for tr, te in folds:  # one foot in time order: one neighbour each side per session, as before
        assert len(tr) >= 210 - len(te) - 2 * 3


def test_block_folds_sort_a_shuffled_table_by_time():
    """Review R2 finding 4: the rows of steps.csv shuffled (the toolkit reads them unsorted) gave 305 touching
    train/test pairs when blocks followed the row order."""
    rng = np.random.default_rng(9001)
    start, end, side = _walk(120, rng)
    perm = rng.permutation(120)
    start, end, side = start[perm], end[perm], side[perm]
    session = np.zeros(120, dtype=int)
    folds = block_folds(session, start, end, 5, side)
    _check_no_leak(session, start, end, side, folds)


def test_block_folds_leave_out_both_feet_neighbours_of_an_interleaved_table():
    """Review R2 finding 4: in a two-feet table the row neighbour is the other foot's stride; the same foot's
    neighbour overlapped or touched a test window."""
    rng = np.random.default_rng(9002)
    start, end, side = _walk(120, rng, two_feet=True)
    session = np.zeros(120, dtype=int)
    folds = block_folds(session, start, end, 5, side)
    _check_no_leak(session, start, end, side, folds)


def test_training_folds_follow_the_times_of_a_shuffled_steps_table():
    """The times reach the folds train uses: a walk whose steps.csv rows are shuffled gives leak-free folds."""
    from pdrlearn.classify.training import _folds, session_windows, task_data

    walk = simulate("length", 9003, seed=0)
    walk.steps = walk.steps.sample(frac=1, random_state=0).reset_index(drop=True)
    data = task_data(session_windows([walk], n_samples=40), "length", [walk])
    folds, n = _folds(data.y, 4, 0, "length", data.session, kind="block", times=data.times, side=data.side)
    assert n == 4
    _check_no_leak(data.session, data.times[:, 0], data.times[:, 1], data.side, folds)


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


def test_settings_record_the_block_folds_used_and_asked():
    """Decision C114 (review R2, side point): ``settings.cv_blocks`` recorded --cv while each task model recorded
    the folds it used; with fewer labelled steps per session than --cv the two disagreed (20 against 15)."""
    walk = simulate("length", 9060, seed=0)
    walk.steps = walk.steps.groupby("length_class", group_keys=False).head(5).sort_values("start_s").reset_index(
        drop=True)  # 15 labelled steps, 5 per class
    m = train_user([walk], tasks=["length"], methods=["svm"], units=["foot"], cv=20, cv_groups="block",
                   distance_calibration=False)
    r = m.tasks["length"].cv["svm"]["foot"]
    assert r["n_folds"] == r["cv_blocks"] == 15  # a fold per labelled step; the empty blocks are dropped
    assert (m.settings["cv_blocks"], m.settings["cv_blocks_asked"]) == (15, 20)
