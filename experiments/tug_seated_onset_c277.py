"""Decision C277's measurement: the TUG time's rise start and seated end at slow and normal chair transfers (trial
s53t1 finding F7), on fresh simulated users.

s53t1's TUG (``simulate --route "straight:3, turn:180, straight:3, turn:180" --sit-start 5 --sit-end 5 --stand 0.5``
with a foot unit and the lower back, ``--bounce pendulum --pelvis realistic --variability 1.5``), 100 Hz, once with
slow transfers (``--transfer-time 4:6``, the trial's week 2) and once with normal ones (the simulator's default
1.5-2.5 s), tracked with the foot + lower-back pipeline (``plasys``): per session the truth (the first rise to the last
seated instant, simulator transfers.csv) against ``tug_time_s`` without C277 (``seated_onset_dps=None``) and with it.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/tug_seated_onset_c277.py U0 U1 TMPDIR [ONSET_DPS]
"""
from __future__ import annotations

import functools
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.track.waist as W
from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

ROUTE = "straight:3, turn:180, straight:3, turn:180"
COMMON = ["--sit-start", "5", "--sit-end", "5", "--stand", "0.5", "--bounce", "pendulum", "--pelvis", "realistic",
          "--variability", "1.5", "--rate", "100"]
SPEEDS = {"slow": ["--transfer-time", "4:6", "--step-length", "0.38", "--step-time", "0.72"], "normal": []}
PIPELINE = "plasys"
CHAIR = W.chair_transfers_upright


def truth(folder: Path) -> tuple[float, float, float]:
    """(TUG time, rise start, seated instant) in s, from the simulator's transfers.csv."""
    tr = pd.read_csv(folder / "transfers.csv")
    rise, seated = float(tr["rise_ms"].iloc[0]) / 1000, float(tr["seated_ms"].iloc[-1]) / 1000
    return seated - rise, rise, seated


def track(folder: Path, onset: float | None) -> tuple[float | None, pd.DataFrame]:
    W.chair_transfers_upright = functools.partial(CHAIR, seated_onset_dps=onset)
    try:
        s = read_session(folder)
        r = get_pipeline(PIPELINE)(s)
        return track_summary(r, s, pipeline=PIPELINE).get("tug_time_s"), pd.DataFrame(r.info.get("transfers") or [])
    finally:
        W.chair_transfers_upright = CHAIR


def run(users: range, tmp: Path, onset: float) -> None:
    logging.disable(logging.WARNING)
    errs = {(g, k): [] for g in SPEEDS for k in ("before", "C277")}
    worse = {g: [] for g in SPEEDS}
    for u in users:
        for speed, opts in SPEEDS.items():
            d = tmp / f"tug_{speed}_{u}"
            if not d.is_dir():
                assert main(["simulate", "--route", ROUTE, *COMMON, *opts, "--user-seed", str(u),
                             "--out", str(d)]) == 0
            true_s, rise, seated = truth(d)
            (t0, _), (t1, r1) = track(d, None), track(d, onset)
            e0 = None if t0 is None else t0 - true_s
            e1 = None if t1 is None else t1 - true_s
            if e0 is not None:
                errs[(speed, "before")].append(e0)
            if e1 is not None:
                errs[(speed, "C277")].append(e1)
            if e0 is not None and e1 is not None:
                worse[speed].append(abs(e1) - abs(e0))
            starts = (r1["start_s"].iloc[0], r1["end_s"].iloc[-1]) if len(r1) else (None, None)
            print(f"user {u} {speed}: truth {true_s:.2f} s (rise {rise:.2f}, seated {seated:.2f}), before "
                  f"{t0 if t0 is None else round(t0, 2)}, C277 {t1 if t1 is None else round(t1, 2)} "
                  f"(rise {starts[0]}, seated {starts[1]})", flush=True)
    n = len(users)
    for speed in SPEEDS:
        for key in ("before", "C277"):
            e = np.asarray(errs[(speed, key)])
            print(f"{speed} users {users.start}-{users.stop - 1} {key}: timed {len(e)} of {n}, median |error| "
                  f"{np.median(np.abs(e)) if len(e) else float('nan'):.3f} s, median signed error "
                  f"{np.median(e) if len(e) else float('nan'):+.3f} s, max |error| "
                  f"{np.max(np.abs(e)) if len(e) else float('nan'):.3f} s")
        w = np.asarray(worse[speed])
        print(f"{speed}: sessions worse by > 0.3 s with C277: {int((w > 0.3).sum())} of {len(w)} (largest "
              f"{np.max(w) if len(w) else float('nan'):+.3f} s)")


if __name__ == "__main__":
    run(range(int(sys.argv[1]), int(sys.argv[2]) + 1), Path(sys.argv[3]), float(sys.argv[4]) if len(sys.argv) > 4
        else 1.0)
