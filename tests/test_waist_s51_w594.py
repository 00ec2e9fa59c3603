"""Session 51 (FB), review s51r1 finding F3 (docs/decisions/waist.md W594): when W442 finds the waist contacts no
step count, the calibration's cadence ratio and W227's `calibration_covers_cadence` read the pelvic gyro's cadence
and count, as W579's W211 line does (before: the contacts' doubled cadence, ratio 3.35, covers False)."""

from __future__ import annotations

import dataclasses


def test_ratio_and_covers_read_the_pelvic_gyro_when_the_contacts_are_no_steps_w594():
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import WaistParams

    # W476's test walk (user 11831, 0.2 m every 1.2 s: 77 contacts at 188 per minute, the pelvic gyro 31 steps at 56)
    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(11831), step_length_m=0.2 / f_len, step_time_s=1.2 / f_time)
    s = simulate_path([Stand(2), Straight(6), Stand(2)], u, speed="normal", rate_hz=50, seed=11831,
                      bounce="pendulum", rocker="smooth")
    p = WaistParams(leg_m=0.9, source="calibrated", pipeline="waist-pendulum",
                    gait={"median_cadence_spm": 56.0, "speed_mps": 0.17})
    info = track_waist(s, pipeline="waist-pendulum", params=p).info
    assert info["step_count_unusable"] is True
    assert [w for w in info["warnings"] if "W211" in w] == []  # W579: W211 judged the pelvic gyro's 56 steps/min
    assert 0.9 < info["calibration_cadence_ratio"] < 1.1  # W594 (before: 3.348, the contacts' cadence)
    assert info["calibration_covers_cadence"] is True  # W594 (before: False, so L95 said "not reliable")
