"""Decisions W333, W334 (session 33, trial T3 finding F12): the waist frame check judges straight walking only (a
turn on the spot is no walking to read the frame from), and its warning is kept in summary.json's warnings."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.io.frames import AxisFrame
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.frame_inference import check_declared_frame


def _sim(route: str, user: int):
    logging.disable(logging.WARNING)
    try:
        return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100.0, seed=0)
    finally:
        logging.disable(logging.NOTSET)


@pytest.mark.parametrize("user", [7160, 7161])
def test_turns_on_the_spot_are_no_walking_to_judge_the_frame(user):
    s = _sim("stand:3, turn:360, stand:3, turn:-360, stand:3", user)
    chk = check_declared_frame(s, "waist", s.frames["waist"])  # the simulator's own (right) frame
    assert chk.message is None  # was: "contradicts its data ... write "frames": {"waist": {"x": "backward" ..."
    assert "turning windows left out: W333" in chk.unchecked


def test_a_straight_walk_still_judges_the_frame():
    s = _sim("stand:2, straight:10, turn:180, straight:10, stand:2", 7160)
    assert check_declared_frame(s, "waist", s.frames["waist"]).message is None
    wrong = AxisFrame.from_dict({"x": "right", "y": "up", "z": "backward"})
    assert "contradicts its data" in check_declared_frame(s, "waist", wrong).message


def test_the_frame_warning_is_kept_in_summary_warnings():
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.waist import track_waist

    s = _sim("stand:2, straight:10, turn:180, straight:10, stand:2", 7161)
    s.frames["waist"] = AxisFrame.from_dict({"x": "right", "y": "up", "z": "backward"})
    logging.disable(logging.WARNING)
    try:
        summary = track_summary(track_waist(s, pipeline="waist-pendulum"), s)
    finally:
        logging.disable(logging.NOTSET)
    lines = [w for w in summary["info"]["warnings"] if "contradicts its data" in w]
    assert len(lines) == 1 and "the waist unit's frame" in lines[0]
