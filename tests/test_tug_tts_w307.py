"""Decisions W307 / W308 (session 32): a TUG's turn-to-sit comes from the track's yaw-rate turns
(``info["yaw_turns"]``, L210) when turns.csv has no second turn in the TUG; turns.csv itself is unchanged."""

from __future__ import annotations

import inspect
import json

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.tug_truth import true_tug_phases
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT
from pdrlearn.waist.tug_phases import tug_phases, yaw_turn_to_sit

TWO_TURNS, ONE_TURN = "straight:3, turn:180, straight:3, turn:180", "straight:3, turn:180, straight:3"


def _yaw(start, end, angle):
    return {"start_s": start, "end_s": end, "peak_s": 0.5 * (start + end), "angle_deg": angle, "peak_dps": 90.0,
            "start_5_s": start, "end_95_s": end}


def test_the_turn_to_sit_rule_on_a_table():
    assert inspect.signature(tug_phases).parameters["yaw_to_sit"].default is True  # W308: adopted (W467)
    tr = pd.DataFrame([{"transfer": 1, "kind": SIT_TO_STAND, "start_s": 5.0, "end_s": 7.0},
                       {"transfer": 2, "kind": STAND_TO_SIT, "start_s": 25.0, "end_s": 27.0}])
    steps = pd.DataFrame({"start_s": [9.0, 9.5, 10.0, 14.0, 15.0, 20.0, 21.0]})
    turns = pd.DataFrame({"start_s": [11.0], "end_s": [13.5]})  # turns.csv missed the turn before the sit
    yaw = [_yaw(11.0, 13.5, 180.0),  # turns.csv's own turn (not after its end)
           _yaw(16.0, 17.0, 50.0),  # under turns.csv's 80 deg (L200)
           _yaw(21.5, 23.5, -178.0),  # the turn on the spot before the sit
           _yaw(24.5, 26.5, 120.0)]  # midpoint after the sit's start: part of the sit
    ph = tug_phases(tr, turns, steps, yaw_turns=yaw)
    assert ph["turn_to_sit"] == {"start_s": 21.5, "end_s": 23.5, "duration_s": 2.0}
    assert ph["walk_back"] == {"start_s": 13.5, "end_s": 21.5, "duration_s": 8.0}  # ends at the turn-to-sit (W293)
    assert ph["turn"]["start_s"] == 11.0 and ph["walk_out"]["end_s"] == 11.0
    # the option off: W293's phases (no turn-to-sit, the walk back to the last contact)
    off = tug_phases(tr, turns, steps, yaw_turns=yaw, yaw_to_sit=False)
    assert off["turn_to_sit"] is None and off["walk_back"]["end_s"] == 21.0
    # no yaw-rate turn (a foot track, an old caller) or none that qualifies: as before
    assert tug_phases(tr, turns, steps)["turn_to_sit"] is None
    assert tug_phases(tr, turns, steps, yaw_turns=[yaw[0], yaw[1], yaw[3]])["turn_to_sit"] is None
    # turns.csv's second turn wins over the yaw-rate turns
    two = tug_phases(tr, pd.DataFrame({"start_s": [11.0, 20.5], "end_s": [13.5, 23.0]}), steps, yaw_turns=yaw)
    assert two["turn_to_sit"]["start_s"] == 20.5
    # no first turn: nothing to take a turn-to-sit after
    assert tug_phases(tr, turns.iloc[:0], steps, yaw_turns=yaw)["turn_to_sit"] is None
    # the last qualifying one when there are several; the minimum angle is a parameter
    assert yaw_turn_to_sit([_yaw(15.0, 16.0, 90.0), *yaw], 13.5, 25.0)["start_s"] == 21.5
    assert yaw_turn_to_sit(yaw, 13.5, 21.0) is None
    assert yaw_turn_to_sit(yaw, 13.5, 20.0, min_deg=45.0)["start_s"] == 16.0


def test_a_missed_last_turn_is_the_turn_to_sit_and_a_one_turn_tug_has_none():
    # users of W308's run: 6794 (slow) lost its turn-to-sit from turns.csv, 6795 walks one turn
    for u, route, speed, has in [(6794, TWO_TURNS, "slow", True), (6795, ONE_TURN, "slow", False)]:
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed=speed, seed=u, sit_start_s=5.0,
                          sit_end_s=5.0)
        res = track_waist(s, pipeline="waist-pendulum")
        turns = turn_table(res.steps, yaw_turns=res.info.get("yaw_turns"))
        got = tug_phases(res.info.get("transfers"), turns, res.steps, yaw_turns=res.info.get("yaw_turns"))
        today = tug_phases(res.info.get("transfers"), turns, res.steps, yaw_turns=res.info.get("yaw_turns"),
                           yaw_to_sit=False)
        truth = true_tug_phases(s, route)
        assert today["turn_to_sit"] is None  # W295's miss: turns.csv holds one turn in the TUG
        assert (got["turn_to_sit"] is not None) == has == (truth["turn_to_sit"] is not None)
        if has:
            for p in ("turn_to_sit", "walk_back"):  # W294's tolerance
                assert abs(got[p]["duration_s"] - truth[p]["duration_s"]) <= 1.5, p
            assert got["walk_back"]["end_s"] == got["turn_to_sit"]["start_s"]
        for p in ("sit_to_stand", "walk_out", "turn", "stand_to_sit"):  # untouched by W307
            assert got[p] == today[p]


def test_track_writes_the_turn_to_sit_and_leaves_turns_csv_alone(tmp_path, capsys):
    sim = tmp_path / "sim"
    assert main(["simulate", "--route", TWO_TURNS, "--sit-start", "5", "--sit-end", "5", "--user-seed", "6794",
                 "--speed", "slow", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--units", "waist", "--out", str(tmp_path / "t")]) == 0
    out = capsys.readouterr().out
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    table = pd.read_csv(tmp_path / "t" / "tug_phases.csv")
    assert list(table["phase"]) == ["sit_to_stand", "walk_out", "turn", "walk_back", "turn_to_sit", "stand_to_sit"]
    assert summary["tug_turn_to_sit_s"] == summary["tug_phases"]["turn_to_sit"]["duration_s"] > 0
    assert "turn-to-sit -" not in out and "turn-to-sit " in out
    turns = pd.read_csv(tmp_path / "t" / "turns.csv")
    mid = 0.5 * (turns["start_s"] + turns["end_s"])
    tts = summary["tug_phases"]["turn_to_sit"]
    assert not ((turns["start_s"] == tts["start_s"]) & (turns["end_s"] == tts["end_s"])).any()  # turns.csv as before
    assert summary["turn_count"] == len(turns) and (mid > summary["tug_phases"]["turn"]["end_s"]).sum() == 0
