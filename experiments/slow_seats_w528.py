"""Decision W528's measurement: a slow seated period between two walks (W450's reading at the inner bouts' edges).

Trial T1's slow limp on route :data:`ROUTE` (two seats and a 20 s stand between walks), simulated with
``--transfer-time LO:HI`` for each user, tracked with the lower back (``waist-pendulum``) today (``with_slow_seats``
as the identity: W182 + L648) and with W528. Per mode: the true transfers (simulator transfers.csv) matched by a
row of their kind whose span overlaps the true one widened by 1 s, the rows matching no true transfer, the true ones
lost against today, and the summary's sitting time against the true seated time (seated to rise).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/slow_seats_w528.py LO HI U0 U1 TMPDIR
(sessions made once into TMPDIR as s_LO:HI_USER, e.g. by ``pdrlearn simulate`` with the options below)
"""
from __future__ import annotations

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

ROUTE = ("stand:3, straight:6, sit:40, straight:6, stand:20, turn:180, straight:6, sit:40, straight:6, stand:3")
GAIT = ["--step-length", "0.3", "--step-time", "0.75", "--step-time-asymmetry", "0.25", "--step-length-asymmetry",
        "0.2", "--stance-time-asymmetry", "0.15", "--paretic-side", "right", "--bounce", "pendulum", "--rate", "100"]
W528 = T.with_slow_seats


def truth(folder: Path) -> tuple[float, list[tuple[str, float, float]]]:
    tr = pd.read_csv(folder / "transfers.csv")
    ms = {c: tr[c].to_numpy(float) / 1000 for c in ("start_ms", "seated_ms", "rise_ms", "end_ms")}
    kinds = [("stand-to-sit", a, b) for a, b in zip(ms["start_ms"], ms["seated_ms"], strict=True)]
    kinds += [("sit-to-stand", a, b) for a, b in zip(ms["rise_ms"], ms["end_ms"], strict=True)]
    return float(np.sum(ms["rise_ms"] - ms["seated_ms"])), kinds


def track(folder: Path, w528: bool) -> tuple[float | None, pd.DataFrame]:
    T.with_slow_seats = W528 if w528 else (lambda imu, tilt, rows, contacts: rows)
    s = read_session(folder)
    r = get_pipeline("waist-pendulum")(s)
    return track_summary(r, s, pipeline="waist-pendulum").get("sitting_time_s"), pd.DataFrame(r.info["transfers"] or [])


def matched(rows: pd.DataFrame, kinds) -> tuple[set[int], int]:
    """The indices of the true transfers a row matches, and the rows matching none."""
    found, false = set(), 0
    for r in rows.itertuples() if len(rows) else []:
        hit = [i for i, (k, a, b) in enumerate(kinds) if k == r.kind and r.start_s < b + 1.0 and r.end_s > a - 1.0]
        found |= set(hit)
        false += not hit
    return found, false


def run(lo: float, hi: float, users: range, tmp: Path) -> None:
    logging.disable(logging.WARNING)
    tot = {False: [0, 0, []], True: [0, 0, []]}
    n_true = lost = 0
    for u in users:
        d = tmp / f"s_{lo:g}:{hi:g}_{u}"
        if not d.is_dir():
            assert main(["simulate", "--route", ROUTE, "--transfer-time", f"{lo:g}:{hi:g}", *GAIT,
                         "--user-seed", str(u), "--out", str(d)]) == 0
        seated, kinds = truth(d)
        n_true += len(kinds)
        res = {}
        for key in (False, True):
            sit_s, rows = track(d, key)
            found, false = matched(rows, kinds)
            res[key] = found
            tot[key][0] += len(found)
            tot[key][1] += false
            tot[key][2].append((sit_s if sit_s is not None else float("nan")) - seated)
            print(f"user {u} {'W528 ' if key else 'today'}: {len(found)} of {len(kinds)} transfers, {false} false, "
                  f"sitting {sit_s if sit_s is None else round(sit_s, 1)} s of {seated:.1f} s", flush=True)
        lost += len(res[False] - res[True])
    for key, name in ((False, "today"), (True, "W528")):
        e = np.asarray(tot[key][2])
        print(f"transfer-time {lo:g}:{hi:g} users {users.start}-{users.stop - 1} {name}: {tot[key][0]} of {n_true} "
              f"true transfers found, {tot[key][1]} rows matching none, sitting time error median "
              f"{np.median(e):+.1f} s "
              f"(worst {e[np.argmax(np.abs(e))]:+.1f} s)")
    print(f"W528: true transfers lost against today {lost}")


if __name__ == "__main__":
    run(float(sys.argv[1]), float(sys.argv[2]), range(int(sys.argv[3]), int(sys.argv[4]) + 1), Path(sys.argv[5]))
