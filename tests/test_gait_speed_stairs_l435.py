"""Decision L435 (session 35, trial T3 finding 8): L353's low-gait-speed line stays quiet on a walk mostly of stairs
(at least 5 stair strides and no fewer than the straight strides), as README says, also when L123 still has 5 straight
strides to judge; a level walk with a few stair strides is still judged."""

from __future__ import annotations

from pdrlearn.track.gait import gait_speed_warning

#: trial T3's s2s_u8390 as tracked in session 35: 24 of 32 strides on stairs, 5 straight ones at 1.06 m/s
S2S = {"median_cadence_spm": 110.2, "median_speed_straight_mps": 1.06, "n_straight_strides": 5,
       "n_stair_strides": 24, "gait_speed_mps": 0.38, "leg_length_m": 0.8452, "leg_length_source": "meta.json",
       "pipeline": "plasys"}


def test_no_gait_speed_line_on_a_walk_mostly_of_stairs_l435():
    assert gait_speed_warning(S2S) is None
    # a level walk with a few stair strides: the line still fires
    assert gait_speed_warning({**S2S, "n_straight_strides": 30, "n_stair_strides": 6}) is not None
    assert gait_speed_warning({**S2S, "n_stair_strides": 4}) is not None  # under 5 stair strides: judged
