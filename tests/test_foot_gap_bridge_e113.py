"""Decision E113: ``pdrlearn run`` (the lean runtime's replay) bridges a long foot gap across a turn as
``track --streaming`` does. The trial's session (a 30 s foot dropout over a 180 deg + -90 deg turn on a landing)
gave -90.6 deg for +92.8 deg: the Tracker trimmed its buffers to ``buffer_s`` (8 s) while the foot was silent, so
L91's waist bridge integrated only the gap's last seconds."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.io import write_session
from pdrlearn.orient import wrap_angle
from pdrlearn.runtime.__main__ import replay as lean_replay
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from tests.runtime_helpers import without

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
FOOT = ("fAccelerometer", "fGyroscope", "fForceA", "fForceB")


@pytest.fixture(scope="module")
def landing(tmp_path_factory):
    """A fresh simulated user (4040) turning 180 deg, walking 6 m, turning -90 deg; the foot unit silent from
    2 s before the first turn to 4 s after the second (over ``buffer_s`` = 8 s after the first turn)."""
    s = simulate_path(parse_route("straight:12, turn:180, straight:6, turn:-90, straight:12"),
                      UserProfile.from_seed(4040), speed="normal", rate_hz=20.0, seed=4040, name="landing",
                      scenario="route")
    g = s.trajectory
    t, h = g["t"].to_numpy(float), np.unwrap(g["heading_rad"].to_numpy(float))
    first = float(t[np.flatnonzero(np.abs(h - h[0]) > np.radians(30))[0]])  # into the 180 deg turn
    last = float(t[np.flatnonzero(np.abs(h - h[-1]) > np.radians(30))[-1]])  # out of the -90 deg turn
    a, b = first - 2.0, last + 4.0
    assert b - a > 12.0 and b - first > 10.0  # the first turn is over 8 s before the foot returns
    cut = without(s, a, b, FOOT)
    folder = tmp_path_factory.mktemp("e113") / "landing"
    write_session(cut, folder)
    truth = float(np.degrees(np.interp(b, t, h) - np.interp(a, t, h)))
    return cut, folder, (a, b), truth


def _turn_over(rows, a: float, b: float) -> float:
    """The heading change (deg, wrapped) from the last row ending before ``a`` to the first starting after ``b``."""
    end = np.asarray([r[0] for r in rows]), np.asarray([r[1] for r in rows]), np.asarray([r[2] for r in rows])
    before = int(np.flatnonzero(end[1] <= a)[-1])
    after = int(np.flatnonzero(end[0] >= b - 0.5)[0])
    return float(np.degrees(wrap_angle(end[2][after] - end[2][before])))


def test_run_bridges_a_long_foot_gap_across_a_turn_as_track_streaming(landing):
    cut, folder, (a, b), truth = landing
    assert truth == pytest.approx(90.0, abs=10.0)
    tracker, steps = lean_replay(BUNDLE, folder)
    assert tracker.buffer_s < b - a  # the case: the gap outlasts the buffer
    run = _turn_over([(s.start_s, s.end_s, s.heading_rad) for s in steps], a, b)
    st = track_plasys(cut, streaming=True).steps
    off = _turn_over(list(zip(st["start_s"], st["end_s"], st["heading_rad"], strict=True)), a, b)
    assert abs(off - truth) < 15.0
    assert abs(run - truth) < 15.0, (run, off, truth)  # main: about -90 deg (only the -90 deg turn bridged)
    assert run == pytest.approx(off, abs=1.0)
    assert any("turns with the waist gyroscope (L91)" in w for w in tracker.warnings)
