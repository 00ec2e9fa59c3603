"""Decisions W28 and W29 (offline waist IC detector): the initiation / termination step on the alternating
side (``pdrlearn.waist._kernels.extend_alternating``), the shortest step in whole samples, and the IC as
the last AP maximum above the AP signal's 2 s mean."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.waist import _kernels as K

FS = 100.0


def _sequence(n: int = 6, period_s: float = 0.55, start: int = 300):
    cand = start + np.round(np.arange(n) * period_s * FS).astype(np.int64)
    side = np.where(np.arange(n) % 2 == 0, 1, -1).astype(np.int8)
    return cand, np.full(n, 1.0), side


def _with(cand, h, side, at_s: float, height: float, sd: int):
    c = int(round(at_s * FS))
    i = int(np.searchsorted(cand, c))
    return (np.insert(cand, i, c), np.insert(h, i, height), np.insert(side, i, np.int8(sd)), i)


# ------------------------------------------------------------------ W28 end steps
@pytest.mark.parametrize("beyond", ["start", "end"])
def test_slow_first_or_last_step_on_the_other_side_is_added(beyond):
    cand, h, side = _sequence()
    # 0.9 s beyond the end: outside W18's one period +- 35 % (0.55 s -> 0.36-0.74 s), inside max_step_s
    if beyond == "start":
        cand, h, side, k = _with(cand, h, side, cand[0] / FS - 0.9, 0.6, -side[0])
    else:
        cand, h, side, k = _with(cand, h, side, cand[-1] / FS + 0.9, 0.6, -side[-1])
    keep = np.ones(cand.size, dtype=bool)
    keep[k] = False
    out = K.extend_alternating(cand, h, keep, side, FS, min_peak=0.1)
    assert out[k] and out.sum() == cand.size
    # W18's rhythm extension alone does not reach it
    acc = keep.copy()
    assert not K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=side)[k]
    assert K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=side, end_steps=True)[k]


@pytest.mark.parametrize("case", ["same side", "undecided", "weak", "too far", "end undecided", "short"])
def test_end_step_needs_alternation_height_and_reach(case):
    cand, h, side = _sequence(n=2 if case == "short" else 6)
    at, height, sd = cand[-1] / FS + 0.9, 0.6, -side[-1]
    if case == "same side":
        sd = side[-1]
    elif case == "undecided":
        sd = 0
    elif case == "weak":
        height = 0.05
    elif case == "too far":
        at = cand[-1] / FS + 1.6  # beyond max_step_s (1.5 s)
    elif case == "end undecided":
        side[-1] = 0
    cand, h, side, k = _with(cand, h, side, at, height, sd)
    keep = np.ones(cand.size, dtype=bool)
    keep[k] = False
    assert not K.extend_alternating(cand, h, keep, side, FS, min_peak=0.1)[k]


def test_end_steps_do_not_chain():
    cand, h, side = _sequence()
    last = cand[-1] / FS
    cand, h, side, _ = _with(cand, h, side, last + 0.9, 0.6, -side[-1])
    cand, h, side, k2 = _with(cand, h, side, last + 1.8, 0.6, side[-1])  # one more, alternating again
    keep = np.zeros(cand.size, dtype=bool)
    keep[:6] = True
    out = K.extend_alternating(cand, h, keep, side, FS, min_peak=0.1)
    assert out.sum() == 7 and not out[k2]


def test_nearest_candidate_is_taken():
    cand, h, side = _sequence()
    last = cand[-1] / FS
    cand, h, side, k_near = _with(cand, h, side, last + 0.8, 0.3, -side[-1])
    cand, h, side, k_far = _with(cand, h, side, last + 1.2, 1.0, -side[-1])
    keep = np.zeros(cand.size, dtype=bool)
    keep[:6] = True
    out = K.extend_alternating(cand, h, keep, side, FS, min_peak=0.1)
    assert out[k_near] and not out[k_far]


# ------------------------------------------------------------------ W28 shortest step in whole samples
def test_maxima_exactly_the_shortest_step_apart_are_both_kept():
    fs = 100.00000000000213  # a rate estimated from timestamps: 0.3 s x fs is a hair over 30 samples
    cand = np.array([100, 160, 220, 250, 310], dtype=np.int64)  # 220 -> 250: exactly 30 samples
    h = np.array([1.0, 1.0, 1.0, 0.5, 1.0])
    keep = K.rhythm_complete(cand, h, np.ones(5, dtype=bool), fs, min_peak=0.1, min_step_s=0.3)
    assert keep.all()
    closer = cand.copy()
    closer[3] = 249  # 29 samples: the lower one goes
    assert K.rhythm_complete(closer, h, np.ones(5, dtype=bool), fs, min_peak=0.1, min_step_s=0.3).sum() == 4


# ------------------------------------------------------------------ W29 AP maximum above the mean
def test_ic_is_last_ap_maximum_above_the_mean():
    x = np.zeros(200)
    x[100] = 2.0                                  # the AP peak at the contact
    x[101:130] = -1.0
    x[120] = -0.5                                 # a ripple in the trough after it (a local maximum)
    level = np.zeros(200)
    assert K._nearest_local_max_before(x, 130, 95) == 120           # seed 003 / W3: the last maximum
    assert K._nearest_local_max_before(x, 130, 95, level=level) == 100
    # no maximum above the level in the window: W3's rule
    assert K._nearest_local_max_before(x, 130, 105, level=level) == 120


@pytest.mark.parametrize("fs", [20.0, 100.0, 204.8])
def test_ap_mean_level_is_the_centred_two_second_mean(fs):
    t = np.arange(int(10 * fs)) / fs
    x = 0.3 + np.sin(2 * np.pi * 1.0 * t)         # whole periods in 2 s: the mean is the offset
    lv = K.ap_mean_level(x, fs)
    mid = (t > 1.5) & (t < 8.5)
    assert np.allclose(lv[mid], 0.3, atol=0.05 if fs == 20.0 else 0.02)


@pytest.mark.parametrize("fs", [20.0, 100.0, 204.8])
def test_offline_detector_keeps_synthetic_gait_with_both_rules(fs):
    from scipy.signal import find_peaks

    t = np.arange(int(12 * fs)) / fs
    f_step = 1.8
    v = np.sin(2 * np.pi * f_step * t)            # vertical maxima every step
    ap = np.sin(2 * np.pi * f_step * t + 0.8)      # AP leads the vertical (seed 003: IC just before)
    ml = np.sin(np.pi * f_step * t)               # sway at half the step frequency: alternating sides
    on = K.ic_offline(v, ap, fs, rhythm=True, acc_ml=ml, end_steps=True, ap_above_mean=True)
    off = K.ic_offline(v, ap, fs, rhythm=True, acc_ml=ml)
    np.testing.assert_array_equal(on[2], off[2])  # the same steps
    vmax, _ = find_peaks(v)
    assert on[0].size == off[0].size >= vmax.size - 2
    lead = (on[2] - on[0]) / fs                   # IC before the vertical maximum, within 0.25 s
    assert np.all((lead >= 0) & (lead <= 0.25 + 1 / fs))
