"""Decision C205's measurement: how short a calibrated lower back tracks a 10 m walkway walked end to end (trial T2
finding F7), and the share C193's rule then needs, on fresh simulated users.

Per user (even: the user's own gait; odd: patient-like, T2's ``--variability 5 --irregular-rate 0.3 --step-width 0.28
--pelvis realistic --speed slow --bounce pendulum``; 100 Hz): a 20 m calibration walk (``stand:3, straight:20,
stand:3``, --seed 9) -> ``calibrate -d 20`` (waist-pendulum); the walkway walked end to end (``stand:3, straight:10,
stand:3``, T2's w10b) and a control stopping 1 m short (``straight:9``), each tracked on the lower back with the
parameters and timed by ``ten_metre_walk(..., (2, 6, 2), calibrated=True)``. Truth: the body's crossing of 2 m and
8 m (trajectory.csv). Prints each walk's tracked metres, the 90th percentile of the shortfalls, the share it gives
(whole percent up), and with it the timed walks, their speed error and the timed controls (rule: the decision).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/walkway_lower_back_c205.py U0 U1 TMPDIR
"""
from __future__ import annotations

import logging
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.track.walk_test as W
from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.clinical import bout_rows
from pdrlearn.track.waist import track_waist

PATIENT = ["--variability", "5", "--irregular-rate", "0.3", "--step-width", "0.28", "--pelvis", "realistic",
           "--speed", "slow", "--bounce", "pendulum"]
ZONES = (2.0, 6.0, 2.0)


def crossing(traj: pd.DataFrame, metres: float) -> float:
    t, x = traj["timestamp"].to_numpy(float) / 1000, traj["x"].to_numpy(float)
    return float(np.interp(metres, x - x[0], t))


def sim(d: Path, route: str, u: int, opts: list[str], seed: str = "0") -> None:
    if not d.is_dir():
        assert main(["simulate", "--route", route, "--user-seed", str(u), "--rate", "100", *opts, "--seed", seed,
                     "--out", str(d)]) == 0


def tracked_m(steps: pd.DataFrame) -> float:
    """The longest walking bout's tracked metres (the pass C193 reads)."""
    ln = np.abs(np.nan_to_num(steps["length_m"].to_numpy(float)))
    return max((float(ln[a:b].sum()) for a, b in bout_rows(steps)), default=0.0)


def timed(steps: pd.DataFrame, share: float | None) -> float | None:
    W.DECLARED_SHORT_SHARE_LOWER_BACK = share
    try:
        return W.ten_metre_walk(steps, ZONES, calibrated=True)["ten_m_walk_time_s"]
    finally:
        W.DECLARED_SHORT_SHARE_LOWER_BACK = None


def run(users: range, tmp: Path) -> None:
    logging.disable(logging.WARNING)
    walks, controls = [], []
    for u in users:
        opts = PATIENT if u % 2 else []
        cal, walk, ctl = tmp / f"cal_{u}", tmp / f"w10_{u}", tmp / f"w9_{u}"
        sim(cal, "stand:3, straight:20, stand:3", u, opts, seed="9")
        params = tmp / f"p_{u}.json"
        if not params.is_file():
            assert main(["calibrate", str(cal), "-d", "20", "--pipeline", "waist-pendulum", "--out", str(params)]) == 0
        sim(walk, "stand:3, straight:10, stand:3", u, opts)
        sim(ctl, "stand:3, straight:9, stand:3", u, opts)
        tr = pd.read_csv(walk / "trajectory.csv")
        truth = 6.0 / (crossing(tr, 8.0) - crossing(tr, 2.0))
        sw = track_waist(read_session(walk), pipeline="waist-pendulum", params=str(params)).steps
        sc = track_waist(read_session(ctl), pipeline="waist-pendulum", params=str(params)).steps
        walks.append((u, tracked_m(sw), truth, sw))
        controls.append((u, tracked_m(sc), sc))
        print(f"user {u} {'patient' if u % 2 else 'normal'}: walkway tracked {walks[-1][1]:.2f} m (truth speed "
              f"{truth:.3f} m/s), control tracked {controls[-1][1]:.2f} m", flush=True)
    short = np.array([max(0.0, 100.0 * (10.0 - m) / 10.0) for _, m, _, _ in walks])
    p90 = float(np.percentile(short, 90))
    share = math.ceil(p90 - 1e-9) / 100.0
    print(f"users {users.start}-{users.stop - 1}: shortfall % {', '.join(f'{s:.1f}' for s in short)}; 90th "
          f"percentile {p90:.2f} %, share {100 * share:g} %")
    for name, sh in (("today", None), ("C205", share)):
        n, errs = 0, []
        for _u, _m, truth, steps in walks:
            t = timed(steps, sh)
            if t is not None:
                n += 1
                errs.append(100.0 * ((6.0 / t) / truth - 1.0))
        nc = sum(timed(steps, sh) is not None for _, _, steps in controls)
        e = np.abs(np.asarray(errs))
        print(f"{name}: walks timed {n} of {len(walks)}, speed error max |.| "
              f"{e.max() if len(e) else float('nan'):.2f} % ({', '.join(f'{x:+.2f}' for x in errs)}); controls "
              f"timed {nc} of {len(controls)}")


if __name__ == "__main__":
    run(range(int(sys.argv[1]), int(sys.argv[2]) + 1), Path(sys.argv[3]))
