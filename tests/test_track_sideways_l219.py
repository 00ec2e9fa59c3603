"""Decision L219: a side-stepping stretch seen by the foot unit gives one warning line on the lower-back tracks, and
the foot track's waist / fused heading adds the strides' sideways travel angle (``plasys.SIDE_TRAVEL_HEADING``)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels import sideways as KS
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline, plasys
from pdrlearn.track.sideways import MIN_SIDE_STRIDES, side_travel_extra, sideways_runs


def test_sideways_runs_need_three_long_sideways_strides_in_a_row(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    deg = np.radians([3, 95, 92, 88, 4, 91, 89, 5, -95, -90, -100, -80, 2])
    length = np.array([1.5, 0.4, 0.4, 0.4, 1.5, 0.4, 0.4, 1.5, 0.4, 0.4, 0.1, 0.4, 1.5])
    # 1-3: a run; 5-6: too short; 8-11: broken by a 0.1 m stride at 10
    assert MIN_SIDE_STRIDES == 1  # decision L486 (the constant; the mechanism is tested at 3 here)
    assert sideways_runs(deg, length) == [(1, 3)]
    assert sideways_runs(np.radians([61, 119, 90]), np.full(3, 0.3)) == [(0, 2)]
    assert sideways_runs(np.radians([59, 90, 90]), np.full(3, 0.3)) == []


def _lines(route: str, pipeline: str) -> list[str]:
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(route), UserProfile.from_seed(4), rate_hz=20.0, seed=1, scenario="route")
        return [w for w in get_pipeline(pipeline)(s).info["warnings"] if "decision L219" in w]
    finally:
        logging.disable(logging.NOTSET)


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll", "plasys-before-l219"])
def test_a_side_stretch_gives_one_line_and_a_walk_none(pipeline, monkeypatch):
    if pipeline == "plasys-before-l219":  # the foot track says it only with SIDE_TRAVEL_HEADING off
        monkeypatch.setattr(plasys, "SIDE_TRAVEL_HEADING", False)
        pipeline = "plasys"
    lines = _lines("straight:6, side:-3, straight:6", pipeline)
    assert len(lines) == 1 and "sideways to the right" in lines[0]
    assert "deg from the foot's facing" in lines[0]
    assert _lines("straight:6, turn:90, straight:6", pipeline) == []


def test_side_travel_extra_adds_a_runs_angle_beyond_the_usual_offset_only(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    lat = np.radians([5, 4, 95, 93, 96, 6, 5, 60])
    length = np.array([1.5, 1.5, 0.4, 0.4, 0.4, 1.5, 1.5, 0.4])
    extra = np.degrees(side_travel_extra(lat, length))
    assert np.allclose(extra, [0, 0, 90, 88, 91, 0, 0, 0])  # usual offset: the median 5 deg of the others
    assert not side_travel_extra(np.radians([5, 70, 80]), np.full(3, 1.0)).any()  # no run of 3: unchanged


def _plasys(route: str, on: bool, monkeypatch) -> tuple[np.ndarray, list[str]]:
    monkeypatch.setattr(plasys, "SIDE_TRAVEL_HEADING", on)
    s = simulate_path(parse_route(route), UserProfile.from_seed(4), rate_hz=20.0, seed=1, scenario="route")
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s)
    finally:
        logging.disable(logging.NOTSET)
    tr, gt = res.trajectory, s.trajectory
    err = (tr[["x", "y"]].to_numpy(float)[-1] - tr[["x", "y"]].to_numpy(float)[0]) - (
        gt[["x", "y"]].to_numpy(float)[-1] - gt[["x", "y"]].to_numpy(float)[0])
    return err, res.info["warnings"]


def test_plasys_puts_side_strides_sideways_and_leaves_other_tracks_alone(monkeypatch):
    # a forward walk first: since L494 a foot track's heading 0 is its first walk, which a walk of side steps alone
    # would make the side direction (then L219 has nothing left to correct)
    err_off, _ = _plasys("straight:4, side:-4", False, monkeypatch)
    err_on, warn_on = _plasys("straight:4, side:-4", True, monkeypatch)
    assert np.hypot(*err_off) > 4.0 and np.hypot(*err_on) < 1.0  # L218: along the facing; L219: sideways
    assert not [w for w in warn_on if "decision L219" in w]
    a, _ = _plasys("straight:6, turn:90, straight:6", False, monkeypatch)
    b, _ = _plasys("straight:6, turn:90, straight:6", True, monkeypatch)
    assert np.array_equal(a, b)  # no sideways run: the track is bit for bit the same
