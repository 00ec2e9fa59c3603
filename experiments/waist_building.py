"""Decisions W155 and W157: how often the stairs_length line (W155) and the start-stop micro-bout line (W157) fire
on fresh simulated users' normal level routes (users 3000-3039; walks with stops, no stairs, no queue) and on the
real lower-back recordings (mobgap, uncalibrated), on both waist pipelines. Prints counts; no behaviour change.

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_building.py
"""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline

ROUTE = "straight:20, stand:5, straight:10, turn:90, straight:15, stand:3, straight:10, turn:-90, straight:8"
USERS = range(3000, 3040)
REAL = sorted(Path("datasets/external").glob("mobgap_*"))


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


if __name__ == "__main__":
    main()
