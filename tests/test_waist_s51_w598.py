"""Decision W598 (session 51, FF; trial s51t2 finding F4): the lower back's jitter-free stride-time CV (W558) over
its steady straight runs - each walking bout cut at a step interval outside 0.6-1.4 x the bout's median (an extra or
a missed contact) and at a turning row - with the lag-2 jitter term about each run's own mean (a pace change between
runs is not jitter)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.clinical import jitter_free_cv, lower_back_cv, steady_runs


def _walk(seed: int = 3) -> tuple[pd.DataFrame, float]:
    """A corridor walk as one bout (C180: a stepless turn fills its gap): 4 straights of 120 steps, the first two at
    0.55 s, the last two at 0.60 s a step (a slower pace), a 2.5 s turn between straights with 3 turning rows, an
    extra contact in each straight; contacts with 0.03 s of jitter. Returns the table and the true stride CV of the
    straights (pooled, as ics.csv's truth)."""
    rng = np.random.default_rng(seed)
    t, turning, strides, now = [], [], [], 0.0
    for k, step in enumerate((0.55, 0.55, 0.60, 0.60)):
        steps = rng.normal(step, step * 0.02, 120)
        true = now + np.cumsum(steps)
        strides.append(true[2:] - true[:-2])
        t += list(true)
        turning += [0] * 120
        extra = true[60] + 0.2  # a jerk's contact inside the straight
        t.append(extra)
        turning.append(0)
        now = true[-1] + 2.5
        if k < 3:  # the turn's rows
            t += list(true[-1] + np.array([0.8, 1.6, 2.4]))
            turning += [1, 1, 1]
            now = true[-1] + 3.0
    t = np.asarray(t) + rng.normal(0.0, 0.03, len(t))
    order = np.argsort(t)
    steps = pd.DataFrame({"start_s": t[order], "unit": "waist", "heading_rad": 0.0,
                          "turning": np.asarray(turning)[order]})
    s = np.concatenate(strides)
    return steps, float(100 * s.std(ddof=1) / s.mean())


@pytest.fixture(scope="module")
def walk():
    return _walk()


def test_the_cv_over_steady_straight_runs_reads_the_truth_w598(walk):
    steps, truth = walk
    before = lower_back_cv(steps, step_band=None)["jitter_free_cv_pct"]  # W558 as adopted: the bout as one run
    after = lower_back_cv(steps)
    assert before > 3 * truth  # the turns' intervals and the extra contacts
    assert after["jitter_free_cv_pct"] == pytest.approx(truth, rel=0.2)
    assert 181 <= after["n_jitter_free_strides"] < 480 - 6


def test_steady_runs_cut_at_extra_missed_contacts_and_turns_w598():
    t = np.arange(30, dtype=float)
    assert [len(r) for r in steady_runs(t, np.zeros(30, bool))] == [30]
    extra = np.sort(np.append(t, 10.3))  # splits a step: 0.3 and 0.7 of it
    assert [len(r) for r in steady_runs(extra, np.zeros(31, bool))] == [11, 20]
    missed = np.delete(t, 15)  # two steps in one interval
    assert [len(r) for r in steady_runs(missed, np.zeros(29, bool))] == [15, 14]
    turning = np.zeros(30, bool)
    turning[[12, 13]] = True
    assert [len(r) for r in steady_runs(t, turning)] == [12, 16]
    assert steady_runs(t[:7], np.zeros(7, bool)) == []


def test_the_jitter_term_is_about_each_runs_own_mean_w598():
    rng = np.random.default_rng(5)
    runs = [np.cumsum(rng.normal(step, step * 0.02, 300)) for step in (0.5, 0.7)]  # a pace change, no jitter
    s = np.concatenate([(r[2:] - r[:-2])[2:-2] for r in runs])
    raw, corrected, _ = jitter_free_cv(runs)
    assert raw == pytest.approx(100 * s.std(ddof=1) / s.mean())
    assert corrected == pytest.approx(raw, rel=0.1)  # about the pooled mean: 1.7 x the raw
