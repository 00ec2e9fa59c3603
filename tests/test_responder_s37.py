"""Session 37, fixer FG (trial T5): first-responder indoor tracking - long standstills, end floor, speed."""
import numpy as np

from pdrlearn.track import plasys as P


def _two_legs(rest_s: float):
    """A 15-stride leg along 0 rad, a rest of ``rest_s``, a 15-stride leg back along pi: the foot's relative heading
    is right, the compass is off by a heading-dependent +0.15 / -0.15 rad (a hard-iron offset, as trial T5's)."""
    n = 15
    s1 = np.arange(n) * 1.1
    s2 = s1[-1] + 1.1 + rest_s + np.arange(n) * 1.1
    start = np.concatenate([s1, s2])
    end = start + 1.0
    rel = np.concatenate([np.zeros(n), np.full(n, np.pi)])
    absolute = rel + np.concatenate([np.full(n, 0.15), np.full(n, -0.15)])
    return rel, absolute, start, end


def test_fused_heading_window_runs_on_walking_time_l471():
    """L471: a 1500 s rest between two legs no longer splits L17's +-60 s compass window, so each leg keeps the
    offset it had with a 2 s rest (the compass's opposite errors cancel) instead of taking its own leg's error."""
    short = P.fuse_by_segment(*_two_legs(2.0), {}, tau_s=60.0, walking=True)
    long_ = P.fuse_by_segment(*_two_legs(1500.0), {}, tau_s=60.0, walking=True)
    np.testing.assert_allclose(long_, short, atol=1e-12)
    rel = _two_legs(1500.0)[0]
    assert np.max(np.abs(long_ - rel)) < 1e-9  # the opposite compass errors cancel: no leg is turned
    assert P.FUSED_WALKING_CLOCK is True  # the default offline track uses it (decision L471, adopted)
    old = P.fuse_by_segment(*_two_legs(1500.0), {}, tau_s=60.0)  # L17's clock time: each leg turned 0.15 rad
    assert np.max(np.abs(old - rel)) > 0.1


def test_walking_clock_caps_stops_at_three_seconds_l471():
    start = np.array([0.0, 1.1, 2.2, 1000.0, 1001.1])
    end = start + 1.0
    clock = P.walking_clock(start, end)
    np.testing.assert_allclose(np.diff(clock), [1.1, 1.1, 3.0 + 1.0, 1.1])  # 996.8 s stop -> 3 s
    short = np.array([0.0, 1.1, 4.0])  # a 1.9 s stop is walking time, untouched
    np.testing.assert_allclose(P.walking_clock(short, short + 1.0), short + 1.0)
