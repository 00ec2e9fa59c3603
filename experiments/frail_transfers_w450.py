"""Decision W450's measurement: W182's chair transfers on simulated slow (frail) transfers (S95 ``transfer_s``) and
on UCI HAPT, today vs a ``slow_bounds`` candidate (:data:`pdrlearn.waist.transfers.W450_CANDIDATE`).

Simulated: users U0-U1, route ``straight:3, turn:180, straight:3, sit:30, straight:3, turn:180, straight:3`` with
``sit_start_s=20, sit_end_s=20``, 0.3 m steps in 0.8 s, ``bounce="pendulum"``, 20 Hz: 4 true transfers each; a row
matches a true transfer it overlaps with the same kind. HAPT: experiments/hapt_transfers.py's tables.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/frail_transfers_w450.py LO HI U0 U1 [CANDIDATE_JSON]
     ... --hapt [CANDIDATE_JSON] OUT.md
"""
from __future__ import annotations

import dataclasses
import functools
import json
import logging
import sys

import numpy as np
import pandas as pd

import pdrlearn.waist.transfers as T
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist

logging.disable(logging.WARNING)
ROUTE = "straight:3, turn:180, straight:3, sit:30, straight:3, turn:180, straight:3"


def use_candidate(text: str | None) -> None:
    """Every transfers_from_tilt call with the candidate's ``slow_bounds`` (None: today's W182)."""
    if text:
        T.transfers_from_tilt = functools.partial(T.transfers_from_tilt, slow_bounds=json.loads(text))


def truth_of(s) -> list[tuple[str, float, float]]:
    """The simulated session's true transfers ``(kind, start_s, end_s)`` (its ``extras["transfers"]``)."""
    truth = []
    for r in (s.extras["transfers"].itertuples() if "transfers" in s.extras else ()):
        if r.start_s >= 0 and r.seated_s - r.start_s > 0.5:
            truth.append(("stand-to-sit", r.start_s, r.seated_s))
        if r.end_s > r.rise_s:
            truth.append(("sit-to-stand", r.rise_s, r.end_s))
    return truth


def match(truth, rows: pd.DataFrame) -> tuple[int, int, list[float]]:
    """``(found, false, duration errors)``: a row matches a true transfer it overlaps with the same kind."""
    used, found, derr = set(), 0, []
    for kind, a, b in truth:
        m = [i for i, r in rows.iterrows() if r["kind"] == kind and r["start_s"] < b and r["end_s"] > a
             and i not in used]
        if m:
            used.add(m[0])
            found += 1
            derr.append(rows.loc[m[0], "duration_s"] - (b - a))
    return found, len(rows) - len(used), derr


def sim(lo: float, hi: float, users: range) -> str:
    found = tot = false = 0
    derr = []
    for u in users:
        p = UserProfile.from_seed(u)
        p = dataclasses.replace(p, step_length_m=0.3, step_time_s=0.8, class_step_length_m=p.step_length_m)
        s = simulate_path(parse_route(ROUTE), p, seed=0, bounce="pendulum", sit_start_s=20, sit_end_s=20,
                          transfer_s=(lo, hi))
        truth = truth_of(s)
        f, x, d = match(truth, pd.DataFrame(track_waist(s, pipeline="waist-pendulum").info["transfers"] or []))
        tot, found, false = tot + len(truth), found + f, false + x
        derr += d
    return (f"transfer-time {lo:g}:{hi:g} users {users.start}-{users.stop - 1}: found {found} of {tot}, false {false}, "
            f"median |duration error| {np.median(np.abs(derr)):.2f} s")


if __name__ == "__main__":
    if sys.argv[1] == "--hapt":
        use_candidate(sys.argv[2] if len(sys.argv) > 3 else None)
        import hapt_transfers

        hapt_transfers.main(["--out", sys.argv[-1]])
    else:
        use_candidate(sys.argv[5] if len(sys.argv) > 5 else None)
        print(sim(float(sys.argv[1]), float(sys.argv[2]), range(int(sys.argv[3]), int(sys.argv[4]) + 1)))
