"""Decisions L596-L598 (session 42, trial T2 F1-F3): a slow swing's short lulls are no foot rests where the foot's
own stride rhythm asks longer rests (L597), and a slow foot is not told it is off the foot (L598)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.track import track_session, track_settings
from pdrlearn.displace.foot import inertial_stance
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.track.foot_rest import foot_placement_warning


def test_stride_period_and_short_rests_kernel():
    fs = 100.0
    t = np.arange(0, 40, 1 / fs)
    w = np.where((t % 3.6) < 1.4, 2.0 * np.sin(np.pi * (t % 3.6) / 1.4) ** 2, 0.02)  # one swing per 3.6 s
    assert FR.stride_period(w, fs) == pytest.approx(3.6, abs=0.02)
    assert np.isnan(FR.stride_period(w[:500], fs))  # shorter than two of the longest periods searched
    rest = np.array([1, 1, 1, 0, 1, 0, 0, 1, 1, 1, 1, 0], dtype=bool)
    assert FR.drop_short_rests(rest, 3).tolist() == [1, 1, 1, 0, 0, 0, 0, 1, 1, 1, 1, 0]
    assert FR.slow_swing_rate(3.0, 1.0) == 3.0 and FR.slow_swing_rate(3.0, 3.6) == pytest.approx(1.0)


@pytest.fixture(scope="module")
def stop_and_go(tmp_path_factory):
    """T2 F3's pattern, short: 0.3 m steps in 1.2 s, two bouts of 1.2 m (truth 5 strides, 2.40 m; before L597 this
    walk tracked 8 strides, 1.705 m, -29.03 %, cadence 115.4 steps/min)."""
    out = tmp_path_factory.mktemp("l597") / "sg"
    assert main(["simulate", "--route", "stand:3, straight:1.2, stand:3, straight:1.2, stand:3", "--step-length",
                 "0.3", "--step-time", "1.2", "--bounce", "pendulum", "--rocker", "smooth", "--user-seed", "11822",
                 "--rate", "100", "--out", str(out)]) == 0
    return out


def test_slow_stop_and_go_strides_are_whole_l597(stop_and_go):
    out = track_session(stop_and_go, track_settings(pipeline="plasys"))
    s, steps = out["summary"], out["result"].steps
    assert len(steps) == 5
    assert abs(s["distance_error_pct"]) < 5.0
    assert s["median_cadence_spm"] == pytest.approx(50.0, rel=0.05)
    assert not (steps["travel"] == "backward").any()


def test_the_rhythm_rule_keeps_the_window_tests_rests_at_a_normal_rhythm_l597():
    """A normal 1.1 s stride asks 0.066 s (under the 0.1 s window): a 0.08 s rest stays (L596 had dropped it)."""
    fs = 100.0
    t = np.arange(0, 30, 1 / fs)
    ph = t % 1.1
    gyr = np.zeros((len(t), 3))
    gyr[:, 1] = np.where(ph < 0.6, 6.0 * np.sin(np.pi * ph / 0.6), np.where(ph < 0.68, 0.0, 1.5))
    acc = np.tile([0.0, 0.0, 9.81], (len(t), 1))
    kept = inertial_stance(acc, gyr, fs)
    assert kept.any()
    assert np.array_equal(kept, inertial_stance(acc, gyr, fs, rhythm_frac=0))


def test_a_slow_foot_is_not_told_it_is_off_the_foot_l598():
    stats = {"walking": True, "swing_rad_s": np.radians(140.0), "rest_acc_g": 1.0, "rest_fraction": 0.6,
             "stride_period_s": 3.6, "no_swing_rad_s": FR.slow_swing_rate(3.0, 3.6)}
    assert foot_placement_warning(stats, "s") is None
    normal = {**stats, "stride_period_s": 1.1, "no_swing_rad_s": FR.slow_swing_rate(3.0, 1.1)}
    assert "is this unit on the foot?" in foot_placement_warning(normal, "s")


def _swinging_foot(period_s: float, fs: float = 100.0) -> np.ndarray:
    t = np.arange(0, 40, 1 / fs)
    ph = t % period_s
    gyr = np.zeros((len(t), 3))
    gyr[:, 1] = np.where(ph < 1.3, 2.5 * np.sin(np.pi * ph / 1.3), 0.02)
    return gyr


def test_a_rhythm_over_the_stride_cap_is_named_l599():
    from pdrlearn.track.foot_rest import slow_rhythm_line

    line = slow_rhythm_line(FR.foot_period(_swinging_foot(4.0), 100.0))
    assert line and "take 4.0 s" in line and "about 30 steps/min" in line and "no cadence" in line
    assert slow_rhythm_line(FR.foot_period(_swinging_foot(2.4), 100.0)) is None
