"""Decisions W155 and W157: how often the stairs_length line (W155) and the start-stop micro-bout line (W157) fire
on fresh simulated users' normal level routes (users 3000-3039; walks with stops, no stairs, no queue) and on the
real lower-back recordings (mobgap, uncalibrated), on both waist pipelines. Prints counts; no behaviour change.
``--w156``: decision W156's adoption rule, ``stairs_length`` false against "climbs" on the same users' stair route
(the trial's floors2) and level route, and on the real recordings.

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_building.py [--w156]
"""

from __future__ import annotations

import dataclasses
import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

ROUTE = "straight:20, stand:5, straight:10, turn:90, straight:15, stand:3, straight:10, turn:-90, straight:8"
USERS = range(3000, 3040)
REAL = sorted(Path("datasets/external").glob("mobgap_*"))
#: the trial's stair route (two storeys up, two down, four U-turns)
STAIRS = ("straight:10, up:17, turn:180, up:17, turn:180, straight:10, turn:180, down:17, turn:180, down:17, "
          "straight:5")
PIPELINES = ("waist-pendulum", "waist-pll")


def _waist_only(session):
    keep = {k: v for k, v in session.streams.items() if k.startswith("w")}
    return dataclasses.replace(session, streams=keep, steps=session.steps,
                               frames={k: v for k, v in session.frames.items() if k == "waist"})


def _flags(res) -> tuple[bool, bool]:
    w = res.info["warnings"]
    return any("decision W155" in x for x in w), any("decision W157" in x for x in w)


def main() -> None:
    logging.disable(logging.WARNING)
    counts = {p: [0, 0, 0] for p in ("waist-pendulum", "waist-pll")}
    for u in USERS:
        s = _waist_only(simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), rate_hz=20.0, seed=3,
                                      scenario="route"))
        for p, c in counts.items():
            st, mb = _flags(get_pipeline(p)(s))
            c[0] += 1
            c[1] += st
            c[2] += mb
    for p, (n, st, mb) in counts.items():
        print(f"simulated users {USERS.start}-{USERS.stop - 1}, {p}: {n} tracks, W155 lines {st}, W157 lines {mb}")
    for d in REAL:
        s = read_session(d)
        for p in ("waist-pendulum", "waist-pll"):
            res = get_pipeline(p)(s)
            st, mb = _flags(res)
            print(f"{d.name} {p}: W155 {int(st)}, W157 {int(mb)}, stairs steps {int(res.steps['stairs'].sum())}")


def _sim(route: str, user: int):
    return _waist_only(simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=3,
                                     scenario="route"))


def w156() -> None:
    """Decision W156's rule: stairs_length false against "climbs" (printed; the rule is in the decision text)."""
    logging.disable(logging.WARNING)
    values = (False, "climbs")
    for name, route in (("stairs", STAIRS), ("level", ROUTE)):
        rows = {(p, v): [] for p in PIPELINES for v in values}
        for u in USERS:
            s = _sim(route, u)
            for p in PIPELINES:
                for v in values:
                    ev = evaluate_track(get_pipeline(p)(s, stairs_length=v), s)
                    rows[p, v].append((ev["distance_m"], abs(ev["distance_error_pct"]), ev["final_position_error_m"]))
        for p in PIPELINES:
            off, on = np.array(rows[p, False]), np.array(rows[p, "climbs"])
            changed = int(np.sum(np.abs(off[:, 0] - on[:, 0]) > 1e-9))
            print(f"W156 {name} users {USERS.start}-{USERS.stop - 1} {p}: mean |distance error| "
                  f"{off[:, 1].mean():.2f} -> {on[:, 1].mean():.2f} %, mean final error {off[:, 2].mean():.3f} -> "
                  f"{on[:, 2].mean():.3f} m, distances changed {changed} of {len(off)}")
    for d in REAL:
        s = read_session(d)
        for p in PIPELINES:
            a, b = (get_pipeline(p)(s, stairs_length=v) for v in values)
            da, db = (float(r.steps["length_m"].abs().sum()) for r in (a, b))
            print(f"W156 {d.name} {p}: distance {da:.3f} -> {db:.3f} m ({100 * (db - da) / da:+.2f} %)")


if __name__ == "__main__":
    w156() if "--w156" in sys.argv[1:] else main()
