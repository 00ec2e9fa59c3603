"""Decision L194: a break in the rows (a gap over 3 s, or a contact without a next one) across which the heading
turns 30 deg or more is a turn (L119), so its time is walking time; a break without a turn stays a stop."""
import numpy as np
import pytest

from pdrlearn.track.gait import walking_pieces


def test_a_turn_across_a_gap_bridges_it():
    st, en = [0.0, 1.0, 5.5, 6.5], [1.0, 2.0, 6.5, 7.5]  # 3.5 s gap
    flat = np.zeros(4)
    turned = np.radians([0.0, 0.0, 180.0, 180.0])
    assert walking_pieces(st, en) == [(0.0, 2.0), (5.5, 7.5)]
    assert walking_pieces(st, en, heading_rad=flat) == [(0.0, 2.0), (5.5, 7.5)]
    assert walking_pieces(st, en, heading_rad=turned) == [(0.0, 7.5)]


def test_the_turn_time_bounds_the_bridge():
    # 180 deg at 20 deg/s is 9 s: a 3 + 9 = 12 s break is bridged, 12.5 s is not (L119's bound)
    for gap, one in ((12.0, True), (12.5, False)):
        st, en = [0.0, 2.0 + gap], [2.0, 4.0 + gap]
        got = walking_pieces(st, en, heading_rad=np.radians([0.0, 180.0]))
        assert (len(got) == 1) is one
    # under 30 deg the break stays a stop
    assert len(walking_pieces([0.0, 5.5], [2.0, 7.5], heading_rad=np.radians([0.0, 29.0]))) == 2


def test_an_invalid_row_between_is_bridged_only_by_a_turn():
    st, en = [0.0, 1.0, 2.0, 3.0], [1.0, 2.0, 3.0, 4.0]
    valid = [True, True, False, True]
    assert walking_pieces(st, en, valid) == [(0.0, 2.0), (3.0, 4.0)]
    assert walking_pieces(st, en, valid, heading_rad=np.radians([0, 0, 90, 90])) == [(0.0, 4.0)]


def test_a_slow_timed_up_and_go_on_the_lower_back_reads_the_bouts_speed():
    """The rehab trial (session 27, finding 1): user 21's slow TUG read 0.84 m/s on the waist where its bout said
    0.54 (the turn's missed steps left a 3.65 s contact gap, dropped as a stop while no pause was reported)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.base import get_pipeline
    from pdrlearn.track.evaluate import track_summary

    s = simulate_path(parse_route("stand:3, straight:3, turn:180, straight:3, stand:3"), UserProfile.from_seed(21),
                      speed="slow", rate_hz=20.0, seed=0, scenario="route", sit_start_s=5.0, sit_end_s=5.0)
    res = get_pipeline("waist-pendulum")(s)
    summary = track_summary(res, s, pipeline="waist-pendulum")
    assert summary["n_pauses"] == 0
    st = res.steps
    span = float(st["end_s"].max() - st["start_s"].min())
    assert summary["walking_time_s"] == pytest.approx(span, abs=1e-6)  # the turn's time is walking
    assert 0.45 < summary["gait_speed_mps"] < 0.62
