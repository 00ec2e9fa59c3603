"""Decision W517 (session 45, fixer FK, trial T1 finding F4): the lower back reads its ramps on the least-squares
slope of its walked barometric altitude over a 4 m window of each walking sequence, not on three noisy steps."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.grade import WAIST_SLOPE_WINDOW_M, fitted_grades_pct, ramp_runs, track_ramps

STEP_M = 0.3  # a slow rollator walker's lower-back step (T1's 12767: 0.25 m / 0.85 s)
RISE = 1 / 12  # ADA 2010 sec. 405.2: the steepest ramp, 1:12


def _slow_ramp_walk(seed: int, grade: float = RISE, noise_m: float = 0.03):
    """4 m level, a 9 m ramp at ``grade``, 4 m level, in 0.3 m steps; each step boundary's barometric altitude off by
    ``noise_m`` (sd): a step's ``dz_m`` is the difference of two noisy readings, as on T1's 12767 (-24 ... +33 %)."""
    rng = np.random.default_rng(seed)
    x = np.arange(0.0, 17.0 + 1e-9, STEP_M)
    z = np.clip(x - 4.0, 0.0, 9.0) * grade + rng.normal(0.0, noise_m, len(x))
    return np.diff(x), np.diff(z)


def test_an_exact_slope_reads_its_grade_and_the_window_stays_in_its_walking_sequence():
    length = np.full(20, 0.5)
    dz = np.r_[np.full(10, 0.5 / 12), np.full(10, -0.05)]  # 10 steps up at 1:12, then (after a pause) down at 10 %
    g = fitted_grades_pct(length, dz, WAIST_SLOPE_WINDOW_M, ends=np.arange(20) == 9)
    assert g[:10] == pytest.approx(100 / 12) and g[10:] == pytest.approx(-10.0)  # no mixing across the pause
    mixed = fitted_grades_pct(length, dz, WAIST_SLOPE_WINDOW_M)  # one sequence: the rows at the top mix
    assert mixed[9] == pytest.approx(0.0, abs=2.0)
    assert fitted_grades_pct([1.0, 5.0], [0.1, 0.25], 4.0)[1] == pytest.approx(5.0)  # a row longer than the window


@pytest.mark.parametrize("seed", range(5))
def test_a_slow_noisy_1_12_ramp_is_one_ramp_with_its_rise(seed):
    length, dz = _slow_ramp_walk(seed)
    ramps = ramp_runs(length, dz, 3, lone_stair_joins=True, window_m=WAIST_SLOPE_WINDOW_M)
    assert [r["direction"] for r in ramps] == ["up"]
    assert ramps[0]["rise_m"] == pytest.approx(0.75, abs=0.12)
    three_steps = ramp_runs(length, dz, 3, lone_stair_joins=True)  # L301's three-step window: pieces or nothing
    assert sum(r["rise_m"] for r in three_steps if r["direction"] == "up") < 0.6


@pytest.mark.parametrize("seed", range(5))
def test_a_slow_noisy_level_walk_has_no_ramp(seed):
    length, dz = _slow_ramp_walk(seed, grade=0.0)
    assert ramp_runs(length, dz, 3, lone_stair_joins=True, window_m=WAIST_SLOPE_WINDOW_M) == []


def test_a_lower_back_track_reads_its_ramps_on_the_window_and_a_foot_track_does_not():
    length, dz = _slow_ramp_walk(0)
    n = len(length)
    steps = pd.DataFrame({"unit": "waist", "length_m": length, "dz_m": dz, "has_next": np.arange(n) < n - 1,
                          "start_s": np.arange(n) * 0.85, "end_s": (np.arange(n) + 1) * 0.85})
    ramps, _, _ = track_ramps(steps, {})
    assert [r["direction"] for r in ramps] == ["up"] and ramps[0]["rise_m"] == pytest.approx(0.75, abs=0.12)
    foot = steps.assign(unit="foot")
    foot_ramps, _, _ = track_ramps(foot, {"altitude_source": "fused"})  # a foot stride's grade is its own (L301)
    assert sum(r["rise_m"] for r in foot_ramps if r["direction"] == "up") < 0.6
