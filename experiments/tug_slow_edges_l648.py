"""Decision L648's measurement: a TUG's slow rise and sit (W450's bounds at the walk's ends) on fresh simulated users.

Trial T1's TUG command (``simulate --route "straight:3, turn:180, straight:3, turn:180" --sit-start 5 --sit-end 5
--stand 0.5 --transfer-time LO:HI --step-length 0.4 --step-time 0.7 --bounce pendulum --rate 100``), tracked with
``--units waist``: per user the truth (the first transfer's rise to the last one's seated instant, simulator
transfers.csv) against ``tug_time_s`` today (W182 alone: ``with_slow_edges`` as the identity) and with L648, and the
transfers.csv rows L648 adds that overlap no true transfer of their kind.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/tug_slow_edges_l648.py LO HI U0 U1 TMPDIR [w506]
(w506: L648 against decision W506's candidate, the sit side's window from the turn in front of the chair)
"""
from __future__ import annotations

import functools
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.waist.transfers as T
from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

ROUTE = "straight:3, turn:180, straight:3, turn:180"
L648 = T.with_slow_edges
#: decision W506 (session 45): with a 6th argument ``w506`` the comparison is L648 (``final_turn`` off) against W506's
#: candidate (the sit side's window from the end of the turn in front of the chair) instead of today against L648
W506 = len(sys.argv) > 6 and sys.argv[6] == "w506"


def truth(folder: Path) -> tuple[float, list[tuple[str, float, float]]]:
    tr = pd.read_csv(folder / "transfers.csv")
    rise, seated = tr["rise_ms"].to_numpy(float) / 1000, tr["seated_ms"].to_numpy(float) / 1000
    start, end = tr["start_ms"].to_numpy(float) / 1000, tr["end_ms"].to_numpy(float) / 1000
    kinds = [("sit-to-stand", rise[0], end[0]), ("stand-to-sit", start[-1], seated[-1])]
    return float(seated[-1] - rise[0]), kinds


def track(folder: Path, l648: bool) -> tuple[float | None, pd.DataFrame]:
    if W506:
        T.with_slow_edges = functools.partial(L648, final_turn=l648)
    else:
        T.with_slow_edges = L648 if l648 else (lambda imu, tilt, rows, contacts: rows)
    s = read_session(folder)
    r = get_pipeline("waist-pendulum")(s)
    return track_summary(r, s, pipeline="waist-pendulum").get("tug_time_s"), pd.DataFrame(r.info["transfers"] or [])


def run(lo: float, hi: float, users: range, tmp: Path) -> None:
    logging.disable(logging.WARNING)
    within = {False: 0, True: 0}
    errs = {False: [], True: []}
    false_added = changed = 0
    for u in users:
        d = tmp / f"tug_{lo:g}-{hi:g}_{u}"
        if not d.is_dir():
            assert main(["simulate", "--route", ROUTE, "--sit-start", "5", "--sit-end", "5", "--stand", "0.5",
                         "--transfer-time", f"{lo:g}:{hi:g}", "--step-length", "0.4", "--step-time", "0.7",
                         "--bounce", "pendulum", "--rate", "100", "--user-seed", str(u), "--out", str(d)]) == 0
        true_s, kinds = truth(d)
        (t0, rows0), (t1, rows1) = track(d, False), track(d, True)
        for key, t in ((False, t0), (True, t1)):
            if t is not None:
                errs[key].append(t - true_s)
                within[key] += abs(t - true_s) <= 1.0
        if t0 is not None and (t1 is None or abs(t1 - t0) > 1e-9):
            changed += 1
        old = {(r.kind, round(r.start_s, 3)) for r in rows0.itertuples()} if len(rows0) else set()
        for r in rows1.itertuples() if len(rows1) else []:
            if (r.kind, round(r.start_s, 3)) in old:
                continue
            if not any(k == r.kind and r.start_s < b and r.end_s > a for k, a, b in kinds):
                false_added += 1
        print(f"user {u}: truth {true_s:.2f} s, {'L648' if W506 else 'today'} {t0 if t0 is None else round(t0, 2)}, "
              f"{'W506' if W506 else 'L648'} {t1 if t1 is None else round(t1, 2)}", flush=True)
    n = len(users)
    for key, name in (((False, "L648"), (True, "W506")) if W506 else ((False, "today"), (True, "L648"))):
        e = np.asarray(errs[key])
        print(f"transfer-time {lo:g}:{hi:g} users {users.start}-{users.stop - 1} {name}: timed {len(e)} of {n}, "
              f"within 1.0 s {within[key]}, median error {np.median(e) if len(e) else float('nan'):+.2f} s")
    print(f"{'W506: L648' if W506 else 'L648: today'}'s times changed on {changed}; rows added matching no true "
          f"transfer {false_added}")


if __name__ == "__main__":
    run(float(sys.argv[1]), float(sys.argv[2]), range(int(sys.argv[3]), int(sys.argv[4]) + 1), Path(sys.argv[5]))
