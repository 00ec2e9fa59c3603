"""Decision L669 (session 45, amends L654's text): what L654's sign does on E216's waist-placed strides. A stride
headed by the waist gyroscope whose class is "forward" and whose rules length is negative is placed by |length| along
the waist heading (the facing, E216: heading + pi with the negative length). L654 then reports it by its measured x:
turning 30 deg or more (L578) or a side step (C137) it is |length| along the facing; otherwise, with its measured x
negative, it keeps the negative length and ``heading_rad`` is the facing + pi (the same forward displacement), with a
positive measured x it is |length| along the facing."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import pdrlearn.kernels.stride as SK
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.runtime_helpers import replay

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
ROUTE_P = "stand:3, straight:8, turn:90, straight:4, turn:180, straight:6, turn:-90, straight:6, stand:3"  # E216's P
FACING = 0.3


def _placed_and_reported(length: float, measured_x: float, turn: float, sideways: bool = False):
    """E216's placement of a waist-headed stride classed forward, then L654's reported pair (the runtime's order)."""
    direction = FACING + SK.waist_forward_flip(False, "forward", length, 0.0)
    x, y, _ = SK.advance_xyz(0.0, 0.0, 0.0, direction, length, 0.0)
    rep_len, rep_head = SK.travel_sign_one(length, direction, measured_x, sideways, turn)
    return np.array([x, y]), rep_len, rep_head


@pytest.mark.parametrize(("measured_x", "turn", "sideways", "negative"), [
    (-0.07, 0.1, False, True),  # measured x backward, no turn, no side step: negative, heading = facing + pi
    (-0.07, 1.2, False, False),  # a pivot (L578): positive along the facing
    (-0.07, 0.1, True, False),  # a side step (C137): positive along the facing
    (0.02, 0.1, False, False),  # measured x forward: positive along the facing
])
def test_an_e216_stride_is_reported_by_its_measured_x_l669(measured_x, turn, sideways, negative):
    moved, rep_len, rep_head = _placed_and_reported(-0.08, measured_x, turn, sideways)
    np.testing.assert_allclose(moved, 0.08 * np.array([math.cos(FACING), math.sin(FACING)]), atol=1e-12)  # E216
    assert (rep_len < 0) == negative
    facing_of_row = FACING + (math.pi if negative else 0.0)  # L669: the facing + pi on a negative row
    assert math.remainder(rep_head - facing_of_row, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(rep_len * np.array([math.cos(rep_head), math.sin(rep_head)]), moved, atol=1e-12)


def test_the_live_tracker_reports_e216_pivot_strides_positive_along_their_move_l669(monkeypatch):
    """User 9890 on E216's route P through the live Tracker: the strides E216 places forward turn 30 deg or more
    (printed: 3, turning 1.22, 1.76 and -0.71 rad), so L578 reports each positive along the way it moved."""
    import pdrlearn.runtime.tracker as TR
    from pdrlearn.runtime import Tracker

    flipped: list[bool] = []
    flip = TR.waist_forward_flip

    def recorded(*args, **kw) -> float:
        out = flip(*args, **kw)
        flipped.append(out != 0.0)
        return out

    monkeypatch.setattr(TR, "waist_forward_flip", recorded)
    s = simulate_path(parse_route(ROUTE_P), UserProfile.from_seed(9890), rate_hz=100.0, seed=0, scenario="route")
    steps = replay(Tracker(SHIPPED), s, chunk_s=1.0, used_only=True)
    assert len(flipped) == len(steps)
    prev, seen = np.zeros(2), 0
    for st, f in zip(steps, flipped, strict=True):
        moved, prev = np.array([st.x, st.y]) - prev, np.array([st.x, st.y])
        if f:
            seen += 1
            assert abs(st.turn_angle_rad) >= math.radians(30.0)  # L578's pivot
            assert st.length_m > 0  # reported positive ...
            np.testing.assert_allclose(st.length_m * np.array([math.cos(st.heading_rad), math.sin(st.heading_rad)]),
                                       moved, atol=1e-9)  # ... along the way it moved
    assert seen >= 1
