"""Session 50 (FE), trial s50t3 findings F9 and F1 (docs/decisions/waist.md): W579 (W211's calibration-speed line
judges the pelvic gyro's cadence when W476 withheld the contacts') and W580 (W442's / W476's advice names `track
--detector pelvic-gyro`; an imported session's frame refusal leads with the --frames fix)."""

from __future__ import annotations

from pdrlearn.waist.plausibility import (
    calibration_line,
    not_alternating_message,
    step_count_withheld_reason,
)

#: trial s50t3's p17401: calibrated at 86 steps/min, 0.29 m/s; 609 contacts at 176 per minute; the pelvic gyro 344
#: steps at 88.2 steps/min
GAIT = {"median_cadence_spm": 86.0, "speed_mps": 0.29}


def test_w211_reads_the_pelvic_gyro_when_the_contacts_are_no_steps_w579():
    contacts = calibration_line(GAIT, 176.0, 609, "waist-pendulum")
    assert contacts is not None and "this walk's median cadence 176 steps/min" in contacts  # W211 as before
    assert calibration_line(GAIT, 176.0, 609, "waist-pendulum", pelvic=(88.2, 344)) is None
    fast = calibration_line(GAIT, 176.0, 609, "waist-pendulum", pelvic=(120.0, 344))
    assert fast.startswith("the pelvic gyro's median cadence (the waist contacts are no step count, decisions W476, "
                           "W579) 120 steps/min (344 steps) is outside the waist-pendulum calibration's 86")


def test_uncountable_lines_name_a_track_on_the_pelvic_gyro_w580():
    track = "'pdrlearn track DIR --units waist --detector pelvic-gyro' (with --params) for a track on its steps"
    assert track in not_alternating_message(0.2, 609, (617, 344))
    assert track in step_count_withheld_reason((617, 344), 0.68)


def test_imported_frame_refusal_leads_with_the_frames_fix_w580(tmp_path):
    from pdrlearn.errors import DataError
    from pdrlearn.io import read_session
    from tests.test_frail_s40 import imported_unframed_walk

    imported_unframed_walk(tmp_path)  # B419's slow 20 Hz walk whose rhythm fixes no axes
    try:
        read_session(tmp_path).require_frame("waist")
    except DataError as exc:
        msg = str(exc)
    else:
        raise AssertionError("no refusal")
    assert "declares no axis frame for the waist unit; re-import it with its axes named" in msg
    assert msg.index("--frames") < msg.index("its data does not fix the axes")
    assert msg.rstrip().endswith(")")


def test_a_calibrated_track_of_uncountable_contacts_judges_the_pelvic_gyro_w579():
    """W475's fresh user 11831 at 0.2 m every 1.2 s (W476's test walk): 77 contacts at 188 per minute, the pelvic gyro
    31 steps at 56 steps/min; before W579 a calibration at 56 steps/min read "this walk's median cadence 188"."""
    import dataclasses

    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import WaistParams

    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(11831), step_length_m=0.2 / f_len, step_time_s=1.2 / f_time)
    s = simulate_path([Stand(2), Straight(6), Stand(2)], u, speed="normal", rate_hz=50, seed=11831,
                      bounce="pendulum", rocker="smooth")

    def w211(cadence):
        p = WaistParams(leg_m=0.9, source="calibrated", pipeline="waist-pendulum",
                        gait={"median_cadence_spm": cadence, "speed_mps": 0.17})
        r = track_waist(s, pipeline="waist-pendulum", params=p)
        assert r.info["step_count_unusable"] is True
        return [w for w in r.info["warnings"] if "W211" in w]

    assert w211(56.0) == []
    assert [w[:81] for w in w211(100.0)] == ["the pelvic gyro's median cadence (the waist contacts are no step count, "
                                             "decisions"]
