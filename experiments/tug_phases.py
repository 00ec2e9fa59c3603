"""Decisions W293 / W294 / W295 (session 32): a lower-back track's TUG phases (tug_phases.csv) against the
simulator's truth (:func:`pdrlearn.sim.tug_truth.true_tug_phases`). Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/tug_phases.py   # fresh users 6620-6639
Output: experiments/results/tug_phases_sim.txt (the printed lines).
Decision W307 (the turn-to-sit from the yaw-rate turns): ``experiments/tug_phases.py w307`` (fresh users 6770-6799)
prints the same table for "today" (turns.csv only) and "yaw turn-to-sit (W307)" from the same tracks, then the rule's
numbers; output experiments/results/tug_tts_sim.txt.

Routes by user % 2: a TUG with a turn before sitting and one without; speed normal / slow by (user // 2) % 2;
20 Hz, seated 5 s at both ends. The track is the default waist-pendulum one; its phases are
:func:`pdrlearn.waist.tug_phases.tug_phases` of its transfers, turns.csv and contacts, as ``track`` writes them.
"""
import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.tug_truth import true_tug_phases
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.transfers import transfer_summary
from pdrlearn.waist.tug_phases import TUG_PHASES, tug_phases

logging.disable(logging.WARNING)

USERS = range(6620, 6640)
ROUTES = ("straight:3, turn:180, straight:3, turn:180", "straight:3, turn:180, straight:3")
#: decision W294's stated tolerance (s) of |track - truth| per phase duration
TOLERANCE_S = {"sit_to_stand": 0.5, "stand_to_sit": 0.5, "walk_out": 1.5, "turn": 1.5, "walk_back": 1.5,
               "turn_to_sit": 1.5}


def session(u: int):
    route = ROUTES[u % 2]
    speed = "slow" if (u // 2) % 2 else "normal"
    s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed=speed, seed=u, sit_start_s=5.0,
                      sit_end_s=5.0)
    return s, route, speed


def track_phases(s, variants=(True,)) -> tuple[list[dict | None], float | None]:
    """Each variant's phases (``yaw_to_sit`` of :func:`tug_phases`; True: the default, W308) from one track."""
    res = track_waist(s, pipeline="waist-pendulum")
    table = turn_table(res.steps, yaw_turns=res.info.get("yaw_turns"))
    tug = transfer_summary(res.info.get("transfers"), res.steps)["tug_time_s"]
    return [tug_phases(res.info.get("transfers"), table, res.steps, yaw_turns=res.info.get("yaw_turns"),
                       yaw_to_sit=v) for v in variants], tug


def new_table() -> dict:
    return {"err": {p: [] for p in TUG_PHASES}, "missing": {p: 0 for p in TUG_PHASES}, "tts_found": 0,
            "two_turn": 0, "one_turn_tts": 0, "one_turn": 0}


def score(tab: dict, u: int, speed: str, route: str, tug, got: dict | None, truth: dict, label: str = "") -> None:
    err, missing = tab["err"], tab["missing"]
    cells = []
    for p in TUG_PHASES:
        a, b = (got or {}).get(p), truth.get(p)
        if a is None or b is None:
            if (a is None) != (b is None):
                missing[p] += 1
            da = "-" if a is None else f"{a['duration_s']:.2f}"
            db = "-" if b is None else f"{b['duration_s']:.2f}"
            cells.append(f"{p} {da}/{db}")
            continue
        e = a["duration_s"] - b["duration_s"]
        err[p].append(e)
        cells.append(f"{p} {a['duration_s']:.2f}/{b['duration_s']:.2f} ({e:+.2f})")
    tug_txt = "none" if tug is None else f"{tug:.2f}"
    print(f"{label}user {u} {speed} turns {route.count('turn')}: TUG {tug_txt}; " + ", ".join(cells), flush=True)
    two = route.count("turn") == 2
    tab["two_turn" if two else "one_turn"] += 1
    has = bool(got and got.get("turn_to_sit"))
    tab["tts_found" if two else "one_turn_tts"] += int(has)


def summarise(tab: dict) -> None:
    err, missing = tab["err"], tab["missing"]
    print("phase: n, median error, median |error|, max |error| (s), within tolerance, track/truth disagree on presence")
    for p in TUG_PHASES:
        e = np.asarray(err[p])
        if not e.size:
            print(f"{p}: n 0, presence mismatches {missing[p]}")
            continue
        within = int((np.abs(e) <= TOLERANCE_S[p]).sum())
        print(f"{p}: n {e.size}, median {np.median(e):+.2f}, median |.| {np.median(np.abs(e)):.2f}, max |.| "
              f"{np.abs(e).max():.2f}, within {TOLERANCE_S[p]:g} s: {within}/{e.size}, presence mismatches "
              f"{missing[p]}")
    print(f"turn_to_sit found on {tab['tts_found']}/{tab['two_turn']} two-turn TUGs; on one-turn TUGs "
          f"{tab['one_turn_tts']}/{tab['one_turn']}")


def main(users=USERS) -> None:
    tab = new_table()
    for u in users:
        s, route, speed = session(u)
        (got,), tug = track_phases(s)
        score(tab, u, speed, route, tug, got, true_tug_phases(s, route))
    summarise(tab)


#: decision W307's fresh users
USERS307 = range(6770, 6800)


def main307(users=USERS307) -> None:
    """Decision W307's measurement: "today" (``yaw_to_sit=False``) and "yaw turn-to-sit (W307)" from the same tracks."""
    names = ("today", "yaw turn-to-sit (W307)")
    tabs = [new_table(), new_table()]
    for u in users:
        s, route, speed = session(u)
        truth = true_tug_phases(s, route)
        gots, tug = track_phases(s, (False, True))
        for name, tab, got in zip(names, tabs, gots, strict=True):
            score(tab, u, speed, route, tug, got, truth, label=f"[{name}] ")
    for name, tab in zip(names, tabs, strict=True):
        print(f"== {name}")
        summarise(tab)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "w307":
        main307()
    else:
        main(range(int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else USERS)
