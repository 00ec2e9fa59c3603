"""Decisions W359 / W361: a lower-back summary's median stride / step time is the grouped-data median of its
whole-sample times, so the median cadence at 20 Hz does not snap to a sample (trial T1 finding F1)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import pdrlearn.track.gait as gait
from pdrlearn.kernels.grouped_median import grid_step, grouped_median, sample_grid
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


def test_without_a_grid_the_median_is_plain_l595():
    """W359 is the rule (L595: its switch ``WAIST_GROUPED_MEDIAN`` and the test that flipped it on a simulated walk
    are gone); a table whose contacts sit on no sample grid keeps the plain median."""
    times = np.array([1.0, 1.05, 1.1, 1.05])
    assert gait._waist_time_median(times, None) == pytest.approx(1.05)
    assert gait._waist_time_median(times, 0.05) == pytest.approx(grouped_median(times, 0.05))


def test_classes_are_the_contacts_sample_period_not_the_few_stride_times_gaps():
    """W359 amended (review R1): a short 100 Hz walk's few stride times can all lie 2-4 samples apart; the class is
    the contacts' own sample grid (their times' common divisor), not the stride times' smallest gap."""
    assert grouped_median([1.0, 1.0, 1.0, 1.2], 0.01) == pytest.approx(1.0 + 0.01 / 6)  # R1's case: 1.0333 by the gap
    contacts = 12.345 + np.array([0, 54, 108, 156, 207, 260, 311]) / 100  # whole samples at 100 Hz
    assert sample_grid(contacts) == pytest.approx(0.01)
    assert sample_grid(contacts[:1]) is None  # one contact: no grid, the plain median
    stride = contacts[2:] - contacts[:-2]  # 1.08, 1.02, 0.99, 1.04, 1.04 s: no two one sample apart
    steps = pd.DataFrame({"start_s": contacts, "end_s": np.r_[contacts[1:], np.nan], "has_next": [True] * 6 + [False],
                          "length_m": 0.7, "unit": "waist"})
    med = gait_summary(steps)["median_stride_time_s"]
    assert abs(med - float(np.median(stride))) <= 0.005 + 1e-9  # within half a sample of the plain median
    assert med == pytest.approx(grouped_median(stride, 0.01)) == pytest.approx(1.0375)
    assert grouped_median(stride) == pytest.approx(1.025)  # the stride times' own 0.02 s gap: 1.5 samples off
