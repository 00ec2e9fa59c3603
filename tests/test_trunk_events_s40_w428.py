"""Decision W428: a two-unit foot track's inner waist work (W418) is ``trunk_events``, the waist-pendulum track's own
code stopped once the chair transfers, contacts and yaw-rate turns are known: the TUG outputs are the whole waist
track's (kept here as the reference), and the skipped stages are not run."""

from __future__ import annotations

import filecmp

import pytest

from pdrlearn import write_session
from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.units import keep_units
from pdrlearn.track.waist import trunk_events
from pdrlearn.warning_lines import isolated_warnings

#: (user, route, stand_s, speed): two TUGs of different stand / turn / pace settings
TUGS = [(10440, "straight:3, turn:180, straight:3, turn:180", 0.5, "slow"),
        (10441, "straight:3, curve:180:0.6, straight:3, turn:-180", 2.0, "normal")]
#: a session with lying transfers too (W245: postures_and_transfers adds them, W278 flags them)
LIE = (10442, "straight:5, lie:20, straight:5, sit:5, straight:3, turn:180, straight:3")
#: the TUG outputs W418 / W419 write (W428's rule: identical to the whole waist track's)
TUG_FILES = ("transfers.csv", "tug_phases.csv", "tug_trials.csv", "turns.csv", "summary.json")


@pytest.fixture(scope="module")
def tugs(tmp_path_factory):
    root = tmp_path_factory.mktemp("w428")
    for uid, route, stand, speed in TUGS:
        s = simulate_path(parse_route(route), UserProfile.from_seed(uid), speed=speed, rate_hz=100, seed=0,
                          scenario="route", sit_start_s=3, sit_end_s=3, stand_s=stand, bounce="pendulum")
        write_session(s, root / f"tug_{uid}")
    s = simulate_path(parse_route(LIE[1]), UserProfile.from_seed(LIE[0]), rate_hz=100, seed=0, scenario="route",
                      sit_start_s=3)
    write_session(s, root / f"tug_{LIE[0]}")
    return root


def _whole_track_events(session):
    """The reference: W418's inner work before W428, the whole waist-pendulum track."""
    return get_pipeline("waist-pendulum")(session)


@pytest.mark.parametrize("uid, n_transfers", [(10440, 2), (10441, 2), (LIE[0], 7)])
def test_trunk_events_are_the_whole_waist_tracks_w428(tugs, uid, n_transfers):
    session = keep_units(read_session(tugs / f"tug_{uid}"), ("waist",))
    with isolated_warnings():
        whole, part = _whole_track_events(session), trunk_events(session)
    assert part.info["transfers"] == whole.info["transfers"] and len(part.info["transfers"]) == n_transfers
    assert part.info["yaw_turns"] == whole.info["yaw_turns"] and len(part.info["yaw_turns"]) >= 2
    cols = ["start_s", "end_s", "event_s"]
    assert part.steps[cols].to_dict("records") == whole.steps[cols].to_dict("records")


@pytest.mark.parametrize("uid", [u for u, *_ in TUGS])
def test_two_unit_tug_outputs_are_unchanged_w428(tugs, uid, monkeypatch):
    import pdrlearn.track.waist as waist

    assert main(["track", str(tugs / f"tug_{uid}"), "--no-plot", "--out", str(tugs / f"new_{uid}")]) == 0
    monkeypatch.setattr(waist, "trunk_events", _whole_track_events)  # the old path, as reference
    assert main(["track", str(tugs / f"tug_{uid}"), "--no-plot", "--out", str(tugs / f"old_{uid}")]) == 0
    for name in TUG_FILES:
        assert filecmp.cmp(tugs / f"new_{uid}" / name, tugs / f"old_{uid}" / name, shallow=False), name


def test_two_unit_foot_track_skips_the_waist_tracks_other_stages_w428(tugs, monkeypatch, tmp_path):
    import pdrlearn.track.waist as waist

    def not_run(*a, **k):
        raise AssertionError("the waist track's step lengths ran inside a foot track")

    monkeypatch.setattr(waist, "_step_lengths", not_run)
    monkeypatch.setattr(waist, "_step_headings", not_run)
    assert main(["track", str(tugs / "tug_10440"), "--no-plot", "--out", str(tmp_path / "t")]) == 0
    assert (tmp_path / "t" / "tug_trials.csv").is_file()
