"""Session 42, trial T2 finding F4: the PLL detector's band follows a slow walker's pelvic-gyro rhythm (decision W475,
steps decision 83)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.kernels.waist import PLL_SLOW_F_MIN_HZ, SHORTEST_STEP_FRAC, pll_slow_band
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.steps import PLLStepDetector
from pdrlearn.steps.evaluate import score_steps
from pdrlearn.waist.pelvic_rhythm import median_step_period


def slow_walk(user: int = 11837, length: float = 0.2, step_s: float = 1.5, rate_hz: float = 50):
    """A short slow walk (40 steps/min) of one of W475's fresh users, as trial T2 simulated it."""
    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(user), step_length_m=length / f_len, step_time_s=step_s / f_time)
    return simulate_path([Stand(2), Straight(6), Stand(2)], u, speed="normal", rate_hz=rate_hz, seed=user,
                         bounce="pendulum", rocker="smooth")


def test_slow_band_only_below_70_steps_per_min_w475():
    f0, f_min, f_max = pll_slow_band(1.5)  # 40 steps/min
    assert f0 == pytest.approx(1 / 1.5) and f_min == PLL_SLOW_F_MIN_HZ
    assert f_max == pytest.approx(1 / 1.5 / SHORTEST_STEP_FRAC) and f_max < 2 * f0  # the harmonic is outside
    assert pll_slow_band(0.58) is None  # a real recording's rhythm (HA001 Test11): W117 as before
    assert pll_slow_band(float("nan")) is None
    assert pll_slow_band(1.5, f_max_hz=2.5)[2] == 2.5  # candidate B (not adopted)


def test_median_step_period_skips_pauses_w475():
    g = np.concatenate([np.arange(0.0, 6.0, 1.5), 20.0 + np.arange(0.0, 6.0, 1.5)])
    assert median_step_period(g) == pytest.approx(1.5)  # the 15.5 s pause is no step
    assert np.isnan(median_step_period(np.array([0.0, 1.0])))


def test_pll_counts_a_40_steps_per_min_walk_w475():
    s = slow_walk()
    sc = score_steps(PLLStepDetector().detect(s), s)
    assert abs(sc["count_error_pct"]) < 10.0  # measured: 30 for 31
    old = score_steps(PLLStepDetector(f_max_hz=3.2).detect(s), s)  # W117's clamp given: no slow band
    assert old["count_error_pct"] > 100.0  # measured: 112 for 31, the harmonic
    assert sc["f1"] > old["f1"] + 0.2
