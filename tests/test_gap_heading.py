"""Decisions L90-L92, L99: a foot-gyroscope gap does not turn the strides before it, its turn is the waist
gyroscope's (L91; the streamed default since L99) and the gap warning says what happens to the heading."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.orient import wrap_angle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route("straight:8, curve:90:3, straight:8"), UserProfile.from_seed(7), speed="slow",
                         rate_hz=20.0, seed=0, name="gap_heading", scenario="route")


def _gap(session, t0: float, t1: float, names=("fGyroscope",)):
    s = session.copy()
    for n in names:
        g = s.streams[n]
        keep = ~((g.t > t0) & (g.t <= t1))
        s.streams[n] = Stream(n, g.t[keep], g.values[keep])
    return s


def _turned_at(session, deg: float) -> float:
    g = session.trajectory
    h = np.degrees(np.unwrap(g["heading_rad"].to_numpy(float)))
    return float(g["t"].iloc[int(np.flatnonzero(np.abs(h - h[0]) >= deg)[0])])


def _heading_diff(a, b) -> np.ndarray:
    return np.degrees(np.abs(wrap_angle(np.asarray(a, float) - np.asarray(b, float))))


def test_a_foot_gyroscope_gap_does_not_turn_the_strides_before_it(walk):
    """The trial's bug: the gyroscope interpolated across a gap was integrated as a pivot (L28) and the fused
    heading's +-60 s offset moved every stride before the gap (-15.4 deg on the trial's session). Now the strides
    before a gap have the same heading whatever happens after it (here: a second gap, inside the curve)."""
    tg, tc = float(walk.steps["start_s"].iloc[4]) + 0.2, _turned_at(walk, 45.0) - 0.5
    clean = track_plasys(walk).steps
    one, two = (track_plasys(g).steps for g in (_gap(walk, tg, tg + 1.0), _gap(_gap(walk, tg, tg + 1.0), tc, tc + 1)))
    n = int((clean["end_s"] < tg - 0.5).sum())  # the stride ending at the gap's edge ends at its rest there
    assert n >= 2
    assert one["end_s"].iloc[:n].tolist() == two["end_s"].iloc[:n].tolist() == clean["end_s"].iloc[:n].tolist()
    assert one["heading_rad"].iloc[:n].tolist() == two["heading_rad"].iloc[:n].tolist()
    # against the intact session: its offset to the waist heading comes from its own strides only (L90)
    assert _heading_diff(one["heading_rad"].iloc[:n], clean["heading_rad"].iloc[:n]).max() < 3.0


def test_the_offline_heading_after_a_gap_is_re_anchored_to_the_waist(walk):
    tc = _turned_at(walk, 45.0) - 0.5
    clean, gapped = track_plasys(walk).steps, track_plasys(_gap(walk, tc, tc + 1.0))
    assert _heading_diff(gapped.steps["heading_rad"].iloc[-4:], clean["heading_rad"].iloc[-4:]).max() < 5.0
    assert any("aligned to the waist heading on its own (L90)" in w for w in gapped.info["warnings"])


def test_the_streamed_turn_inside_a_foot_gap_is_the_waist_gyroscopes_with_the_option(walk):
    """Decision L91: the stride across the gap turns by the waist gyroscope (streamed: the default, L99)."""
    tc = _turned_at(walk, 45.0) - 0.5
    gapped = _gap(walk, tc, tc + 1.0)
    last = track_plasys(walk, streaming=True).steps["heading_rad"].iloc[-4:].to_numpy()
    res = {wb: track_plasys(gapped, streaming=True, waist_bridge=wb) for wb in (False, True)}
    assert _heading_diff(res[False].steps["heading_rad"].iloc[-4:], last).min() > 10.0  # the turn is lost
    assert _heading_diff(res[True].steps["heading_rad"].iloc[-4:], last).max() < 5.0
    assert any("the turn inside them is the waist gyroscope's (L91)" in w for w in res[True].info["warnings"])
    assert any("the heading after them is uncertain" in w for w in res[False].info["warnings"])


@pytest.fixture(scope="module")
def u_turn():
    return simulate_path(parse_route("straight:6, turn:180, straight:6"), UserProfile.from_seed(11), speed="normal",
                         rate_hz=20.0, seed=1, name="gap_u_turn", scenario="route")


def test_the_streamed_default_bridges_a_gap_inside_a_180_deg_turn(u_turn):
    """Decision L99: streamed, the stride across a 1.5 s foot-gyroscope gap in the middle of a 180 deg turn turns
    by default with the waist gyroscope from the foot's rest before the gap to its rest after it; with L90's 0
    (``waist_bridge=False``, the default before L99) the walk back heads the way it came."""
    tc = _turned_at(u_turn, 90.0) - 0.75
    gapped = _gap(u_turn, tc, tc + 1.5)
    intact = track_plasys(u_turn, streaming=True).steps["heading_rad"].iloc[-4:].to_numpy()
    default, off = track_plasys(gapped, streaming=True), track_plasys(gapped, streaming=True, waist_bridge=False)
    assert (default.steps["gap_s"] > 1.0).sum() == 1  # the gap is one stride of 0 m (E30 / E46)
    assert _heading_diff(default.steps["heading_rad"].iloc[-4:], intact).max() < 5.0
    assert _heading_diff(off.steps["heading_rad"].iloc[-4:], intact).min() > 90.0
    truth = u_turn.trajectory
    end = np.interp(default.steps["end_s"].iloc[-1], truth["t"], np.unwrap(truth["heading_rad"]))
    assert _heading_diff(default.steps["heading_rad"].iloc[-1], end) < 10.0
    assert any("the turn inside them is the waist gyroscope's (L91)" in w for w in default.info["warnings"])


def test_offline_keeps_l90_by_default(u_turn):
    """L99 changes the streamed paths only: offline the default is still L90's (L91's bridge an option)."""
    tc = _turned_at(u_turn, 90.0) - 0.75
    gapped = _gap(u_turn, tc, tc + 1.5)
    a, b = track_plasys(gapped), track_plasys(gapped, waist_bridge=False)
    assert a.steps.equals(b.steps) and a.trajectory.equals(b.trajectory)
    assert not any("(L91)" in w for w in a.info["warnings"])


def test_without_a_waist_the_gap_warning_says_the_heading_is_uncertain(walk):
    s = _gap(walk, 8.0, 9.0)
    for n in [n for n in s.streams if n.startswith("w")]:
        del s.streams[n]
    for streaming in (False, True):
        w = track_plasys(s, streaming=streaming).info["warnings"]
        assert any("fGyroscope" in x and "taken as 0, L90): the heading after them is uncertain" in x for x in w), w


def test_a_clean_session_is_unchanged_by_the_bridge(walk):
    for streaming in (False, True):
        a, b = (track_plasys(walk, streaming=streaming, waist_bridge=wb) for wb in (False, True))
        assert a.steps.equals(b.steps) and a.trajectory.equals(b.trajectory)
