"""Decision E115: a live Tracker whose waist unit stops (E23) goes on with the foot's strides (their turn from the
foot, E114) and takes the waist's samples again when they return, instead of refusing every later push (the trial,
session 28, finding 7: 245 refused pushes after a 60 s waist dropout, 102 of 284 strides)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.orient import wrap_angle
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.__main__ import replay as lean_replay
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.runtime_helpers import time_chunks, without

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def _walk_with_turns():
    """A fresh simulated user (4045) walking two 90 deg turns, and the time (s) its heading has first turned 30 deg."""
    s = simulate_path(parse_route("straight:15, turn:90, straight:10, turn:-90, straight:15"),
                      UserProfile.from_seed(4045), speed="normal", rate_hz=20.0, seed=4045, name="waist_drop",
                      scenario="route")
    g = s.trajectory
    t, h = g["t"].to_numpy(float), np.unwrap(g["heading_rad"].to_numpy(float))
    return s, float(t[np.flatnonzero(np.abs(h - h[0]) > np.radians(30))[0]])


@pytest.fixture(scope="module")
def dropout(tmp_path_factory):
    """Every waist stream of :func:`_walk_with_turns` silent for 20 s across its first turn."""
    s, first = _walk_with_turns()
    cut = without(s, first - 5.0, first + 15.0, [n for n in s.streams if n.startswith("w")])
    return cut, write_session(cut, tmp_path_factory.mktemp("e115") / "waist_drop")


def _live(session, tracker) -> list:
    steps = []
    for _, chunk in time_chunks(session, 1.0):
        steps += tracker.push(chunk)  # main: DataError (E23) from 2 s into the dropout on
    return steps + tracker.flush()


def test_the_live_tracker_resumes_after_a_waist_dropout_as_run(dropout):
    cut, folder = dropout
    tracker = Tracker(load_bundle(BUNDLE))  # live: no stream ends, max_lag_s 2 s
    live = _live(cut, tracker)
    assert any("decision E115" in w and "taken again when they return" in w for w in tracker.warnings)
    assert any("samples again by" in w for w in tracker.warnings)
    _, run = lean_replay(BUNDLE, folder)  # `run`: the recording's stream ends, the steps wait for the waist
    assert len(live) == len(run)
    np.testing.assert_allclose([s.end_s for s in live], [s.end_s for s in run], atol=1e-6)  # the CSV's ms clock
    # the same turns: the foot's across the gap (E114), the waist's after it; the classes inside the gap read the
    # waist's held values live and its interpolated ones in the replay (a backward stride may be reported as its
    # magnitude turned by pi, L65): the path is compared
    xy = np.array([[s.x - r.x, s.y - r.y] for s, r in zip(live, run, strict=True)])
    assert float(np.hypot(*xy.T).max()) < 0.05
    after = [i for i, s in enumerate(live) if s.start_s > dropout[0].streams["wAccelerometer"].t[-1] - 10.0]
    head = np.degrees(np.abs(wrap_angle(np.array([live[i].heading_rad - run[i].heading_rad for i in after]))))
    assert float(head.max()) < 1.0


def test_a_waist_clock_far_ahead_is_still_refused(dropout):
    """B141 still refuses a paused waist stream whose samples come back far ahead of the foot's clock."""
    cut, _ = dropout
    tracker = Tracker(load_bundle(BUNDLE))
    chunks = list(time_chunks(cut, 1.0))
    drop = min(float(cut.streams["wAccelerometer"].t[np.argmax(np.diff(cut.streams["wAccelerometer"].t))]) + 8.0,
               chunks[-1][0])
    for t0, chunk in chunks:
        if t0 > drop:
            break
        tracker.push({n: tv for n, tv in chunk.items() if not n.startswith("w") or t0 < drop - 8.0})
    assert tracker._paused
    far = tracker._latest + 100.0
    with pytest.raises(DataError, match="B141"):
        tracker.push({"wAccelerometer": (np.array([far]), np.array([[0.0, 0.0, 9.81]])),
                      "wGyroscope": (np.array([far]), np.zeros((1, 3)))})


def test_waist_streams_that_stop_apart_pause_and_resume_once():
    """E115 (session 28 review): the waist gyroscope stopping 0.3 s after the accelerometer is not "back" at the
    accelerometer's last time: one pause line and one resume line (main: two of each, a false "samples again")."""
    s, first = _walk_with_turns()
    waist = [n for n in s.streams if n.startswith("w")]
    cut = without(s, first - 5.0, first + 15.0, [n for n in waist if n != "wGyroscope"])
    cut = without(cut, first - 4.7, first + 15.0, ["wGyroscope"])
    tracker = Tracker(load_bundle(BUNDLE))
    _live(cut, tracker)
    assert sum("taken again when they return" in w for w in tracker.warnings) == 1
    assert sum("samples again by" in w for w in tracker.warnings) == 1
