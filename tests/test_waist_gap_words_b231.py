"""Decision B231: the gap warning says what a gap does per unit: a waist gap does not stop the strides (their
lengths are counted) and its heading clause follows what heads them; a foot gap is still "no displacement is counted
inside them" (the trial, session 28, finding 8: a waist gap was told the foot gap's words)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.runtime.tracker import Tracker
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from tests.runtime_helpers import replay, without

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
WAIST = ("wAccelerometer", "wGyroscope")


@pytest.fixture(scope="module")
def walk():
    """A fresh simulated user (4046): 30 m with a turn."""
    return simulate_path(parse_route("straight:15, turn:90, straight:15"), UserProfile.from_seed(4046),
                         speed="normal", rate_hz=20.0, seed=4046, name="gap_words", scenario="route")


def _gap_lines(res, name: str) -> list[str]:
    return [w for w in res.info["warnings"] if w.startswith(name) and "gap(s) longer than 1 s" in w]


def test_offline_waist_gap_says_the_strides_go_on(walk):
    clean, gapped = track_plasys(walk), track_plasys(without(walk, 10.0, 13.0, WAIST))
    (line,) = _gap_lines(gapped, "wAccelerometer, wGyroscope")
    assert "no displacement is counted" not in line and "foot gap" not in line  # main: the foot gap's words
    assert "the strides go on and their lengths (the foot's) are counted" in line and "(W34" in line
    assert gapped.steps["length_m"].sum() == pytest.approx(clean.steps["length_m"].sum(), abs=0.01)  # as it says


def test_streamed_waist_gap_says_the_foot_heads_the_strides(walk):
    res = track_plasys(without(walk, 10.0, 13.0, WAIST), streaming=True)
    (line,) = _gap_lines(res, "wAccelerometer, wGyroscope")
    assert "turns with the foot's gyroscope (E114)" in line and "no displacement is counted" not in line
    foot = track_plasys(without(walk, 10.0, 13.0, WAIST), streaming=True, heading="foot")
    assert "the foot heads them" in _gap_lines(foot, "wAccelerometer, wGyroscope")[0]


def test_a_foot_gap_keeps_its_words(walk):
    res = track_plasys(without(walk, 10.0, 13.0, ("fAccelerometer", "fGyroscope")))
    (line,) = _gap_lines(res, "fAccelerometer, fGyroscope")
    assert "no displacement is counted inside them: a stride across a foot gap is one row of 0 m" in line


def test_the_runtime_waist_gap_line_names_the_foot_heading(walk):
    s = without(walk, 10.0, 13.0, [n for n in walk.streams if n.startswith("w")])
    tr = Tracker(BUNDLE, stream_ends_s={n: float(st.t[-1]) for n, st in s.streams.items()})
    replay(tr, s, 1.0)
    (line,) = [w for w in tr.warnings if "no samples for" in w and w.startswith("bundle") is False
               and "wAccelerometer" in w]
    assert "so a stride across it turns with the foot's gyroscope (E114) and its classes are unreliable" in line
