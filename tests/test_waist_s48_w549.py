"""Decision W549 (trial T1 finding F4): L95's fast line of an uncalibrated waist-pendulum track at W178's running-first
speed names fast long strides (race walking) and says which way each fast gait reads, with the measured ranges."""

from __future__ import annotations

from pdrlearn.track.gait import RACE_WALK_RANGES, gait_range_warning

#: T1's sim/rw15620/right on the uncalibrated lower back (179 steps/min, 1.60 m/s straight; 1 m steps, -48.97 %)
RW = {"median_cadence_spm": 179.3, "median_speed_straight_mps": 1.60, "n_straight_strides": 50, "leg_length_m": 0.84,
      "pipeline": "waist-pendulum", "info": {"pipeline": "waist-pendulum", "params_source": "defaults"}}


def test_an_uncalibrated_pendulum_at_a_fast_cadence_says_which_way_each_gait_reads():
    line = gait_range_warning(RW)
    assert "(fast long strides: race walking or running; or short fast steps" in line
    assert f"race walks: {RACE_WALK_RANGES['race']} % distance" in line
    assert f"simulated shuffling: {RACE_WALK_RANGES['shuffle']} %" in line and "decision W549" in line
    assert "?" not in RACE_WALK_RANGES["race"] + RACE_WALK_RANGES["shuffle"]  # the measured ranges, filled in


def test_the_clause_needs_an_uncalibrated_pendulum_at_a_running_first_speed():
    calibrated = {**RW, "info": {"pipeline": "waist-pendulum", "params_source": "calibrated"}}
    pll = {**RW, "pipeline": "waist-pll", "info": {"pipeline": "waist-pll", "params_source": "defaults"}}
    shuffle = {**RW, "median_speed_straight_mps": 0.45}  # W144's short fast steps at a low speed keep their line
    foot = {k: v for k, v in RW.items() if k not in ("pipeline", "info")}
    for summary in (calibrated, pll, shuffle, foot):
        line = gait_range_warning(summary)
        assert line is not None and "decision W549" not in line and "race walking" not in line
