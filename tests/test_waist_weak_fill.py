"""Decision W148: a weak step on the decided alternating side where the alternation and the local rhythm ask for one
(option ``weak_fill`` of the offline ``InitialContactDetector``, measured and not adopted: off by default). The
kernel on hand-made maxima (it fires; it must not for an undecided side, a side that breaks the alternation or a
maximum off the rhythm), the end step, the option's reach (offline only, off by default), and the measured real
HA002 Test11 row."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.events import InitialContactDetector
from tests.conftest import external_session

FS = 100.0
PER = 0.6  # the hand-made walk's step period (s)
# kept maxima 0.6 s apart, alternating, then a same-side pair 0.84 s apart (1.4 periods: W18 does not fill under 1.5)
KEPT_T = np.array([0.0, 0.6, 1.2, 1.8, 2.64, 3.24, 3.84, 4.44])
KEPT_SIDE = np.array([1, -1, 1, -1, -1, 1, -1, 1])


def pair(t_weak: float = 2.22, side_weak: int = 1, h_weak: float = 0.05):
    """``(cand, height, keep, side)``: the kept maxima above and one weak maximum left out at ``t_weak`` (s)."""
    t = np.r_[KEPT_T, t_weak]
    order = np.argsort(t)
    cand = np.round(t[order] * FS).astype(int)
    h = np.r_[np.ones(KEPT_T.size), h_weak][order]
    keep = np.r_[np.ones(KEPT_T.size, dtype=bool), False][order]
    side = np.r_[KEPT_SIDE, side_weak][order].astype(np.int8)
    return cand, h, keep, side


def test_a_weak_maximum_on_the_missing_side_at_the_rhythm_is_filled():
    cand, h, keep, side = pair()
    out = K.fill_weak_alternating(cand, h, keep, side, FS)
    assert out.all() and not keep.all()  # the weak maximum (0.05 m/s^2, under W16's 0.1 floor) is added
    # through rhythm_complete: with weak_fill the pair gets its step, without it (W18: gap < 1.5 periods) not
    kw = {"min_peak": 0.1, "side": side, "unshifted": False}
    assert K.rhythm_complete(cand, h, keep, FS, weak_fill=True, **kw).all()
    assert not K.rhythm_complete(cand, h, keep, FS, **kw).all()


@pytest.mark.parametrize("case", [{"side_weak": 0}, {"side_weak": -1}, {"t_weak": 1.95}, {"h_weak": 0.0}])
def test_no_fill_for_an_undecided_side_the_wrong_side_a_rhythm_mismatch_or_no_bounce(case):
    """Undecided side; the pair's own side (it breaks the alternation); 0.15 s after the pair's first contact (one
    period +- 35 % after the first and before the second is 2.19-2.25 s: off the rhythm); a height of 0 (no positive
    maximum)."""
    cand, h, keep, side = pair(**case)
    np.testing.assert_array_equal(K.fill_weak_alternating(cand, h, keep, side, FS), keep)


def test_pairs_of_opposite_sides_or_in_different_sequences_are_left_alone():
    cand, h, keep, side = pair()
    side = side.copy()
    side[np.searchsorted(cand, 264)] = 1  # the pair now alternates (-1, +1): nothing is missing
    np.testing.assert_array_equal(K.fill_weak_alternating(cand, h, keep, side, FS), keep)
    cand, h, keep, side = pair()
    np.testing.assert_array_equal(K.fill_weak_alternating(cand, h, keep, side, FS, max_step_s=0.8), keep)


def test_the_weak_end_step_only_where_w28_finds_none_and_at_one_period():
    t = np.array([1.0, 1.6, 2.2, 2.8])  # a walk of four kept contacts; a weak maximum before it
    side = np.array([-1, 1, -1, 1, -1], dtype=np.int8)  # the weak maximum on the side opposite the first contact
    for t0, fires in ((0.4, True), (0.1, False)):  # one period before the first contact / 0.9 s: off the rhythm
        cand = np.round(np.r_[t0, t] * FS).astype(int)
        h = np.array([0.05, 1.0, 1.0, 1.0, 1.0])
        keep = np.array([False, True, True, True, True])
        assert not K.extend_alternating(cand, h, keep, side, FS, min_peak=0.1)[0]  # W28: under its floor
        assert K.extend_alternating(cand, h, keep, side, FS, min_peak=0.1, weak=True)[0] == fires
    # W28's full-height step wins: the weak one is not taken beside it (one step per end)
    cand = np.round(np.r_[0.3, 0.45, t] * FS).astype(int)
    out = K.extend_alternating(cand, np.array([0.05, 0.5, 1, 1, 1, 1]), np.r_[False, False, [True] * 4],
                               np.r_[-1, -1, side[1:]].astype(np.int8), FS, min_peak=0.1, weak=True)
    assert out.tolist() == [False, True, True, True, True, True]


def test_the_option_is_off_by_default_and_offline_only():
    assert InitialContactDetector().weak_fill is False and OPTION_DEFAULTS["weak_fill"] is False
    assert InitialContactDetector(weak_fill=True).rule_settings()["weak_fill"] is True
    assert InitialContactDetector(weak_fill=True, realtime=True).rule_settings()["weak_fill"] is False
    assert InitialContactDetector(weak_fill=True, learned=True).rule_settings()["weak_fill"] is False


def test_the_measured_real_row_ha002_test11():
    """W148's (b) row: HA002 Test11 in-bout F1 0.8182 -> 0.8090 (36/42 -> 36/43 of 46): one contact added, at 19.30 s
    (W149: a pause), no miss recovered."""
    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    off = track_waist(s, pipeline="waist-pendulum")
    on = track_waist(s, pipeline="waist-pendulum", weak_fill=True)
    added = np.setdiff1d(on.steps["event_s"].round(6), off.steps["event_s"].round(6))
    assert np.setdiff1d(off.steps["event_s"].round(6), on.steps["event_s"].round(6)).size == 0
    assert added.size == 1 and abs(added[0] - 19.30) < 0.005
    m0, m1 = step_metrics(off.steps, s), step_metrics(on.steps, s)
    assert (m0["n_detected"], m1["n_detected"], m1["n_reference"]) == (42, 43, 46)
    assert round(m0["step_f1"], 4) == 0.8182 and round(m1["step_f1"], 4) == 0.8090
