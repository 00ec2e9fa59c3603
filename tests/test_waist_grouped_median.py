"""Decisions W359 / W361: a lower-back summary's median stride / step time is the grouped-data median of its
whole-sample times, so the median cadence at 20 Hz does not snap to a sample (trial T1 finding F1)."""

from __future__ import annotations

import numpy as np
import pytest

import pdrlearn.track.gait as gait
from pdrlearn.kernels.grouped_median import grid_step, grouped_median
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.gait import gait_summary
from pdrlearn.track.waist import track_waist


def test_grouped_median_interpolates_inside_the_median_class():
    # 66 strides of 1.00 s and 34 of 1.05 s: 0.975 + 0.05 * 50 / 66 (Spiegel & Stephens' grouped median)
    assert grouped_median([1.0] * 66 + [1.05] * 34) == pytest.approx(0.975 + 0.05 * 50 / 66)
    assert grouped_median([1.0] * 5 + [1.05] * 5) == pytest.approx(1.025)  # an even split: the plain median
    assert grouped_median([0.7, 0.7, 0.7]) == pytest.approx(0.7)  # one value: itself
    assert grouped_median([]) is None and grouped_median([np.nan]) is None
    assert grid_step([1.0, 1.05, 1.1, 1.1]) == pytest.approx(0.05) and grid_step([1.0, 1.0]) is None
    # an even count split across a gap between classes: the plain median, not the lower class's edge
    assert grouped_median([1.0, 1.0, 1.05, 1.5, 1.5, 1.55]) == pytest.approx(1.275)
    # an outlier (a missed contact) moves it no more than half a class
    assert abs(grouped_median([1.0] * 6 + [1.05] * 5 + [1.5]) - 1.0) <= 0.025 + 1e-12


def _walk_20hz(uid: int, speed: str, variability: float):
    user = UserProfile.from_seed(uid)
    s = simulate_path([Stand(3), Straight(60), Stand(3)], user, speed=speed, rate_hz=20, seed=uid,
                      variability=variability, bounce="pendulum")
    stride = np.diff(s.steps["ic_s"].to_numpy(float))
    truth = 120.0 / float(np.median(stride[s.steps["steady"].to_numpy(bool)[1:]]))
    return track_waist(s, pipeline="waist-pendulum").steps, truth


@pytest.mark.parametrize(("speed", "variability"), [("normal", 1.0), ("slow", 2.5)])
def test_lower_back_cadence_at_20_hz_is_not_rounded_to_a_sample(speed, variability):
    steps, truth = _walk_20hz(7919, speed, variability)  # trial T1's two conditions, a fresh user
    summary = gait_summary(steps)
    assert summary["median_cadence_spm"] == pytest.approx(truth, rel=0.01)
    # the plain median of whole 50 ms samples was 2.0 % / 1.6 % off here, and a whole number of samples
    stride = summary["median_stride_time_s"]
    assert abs(stride / 0.05 - round(stride / 0.05)) > 1e-3


def test_the_switch_off_gives_the_plain_median(monkeypatch):
    steps, _ = _walk_20hz(7919, "normal", 1.0)
    monkeypatch.setattr(gait, "WAIST_GROUPED_MEDIAN", False)
    stride = gait_summary(steps)["median_stride_time_s"]
    assert abs(stride / 0.05 - round(stride / 0.05)) < 1e-6
