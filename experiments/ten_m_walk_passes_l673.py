"""Decision L673's measurement: `track --ten-m-walk 2,8,2` on trial T3's walkway protocol, three 12 m passes with a
180 deg turn on the spot between them (one walking bout), users 12810-12819, --speed normal, 100 Hz, --rocker smooth,
no insoles (T3 removed fForce*.csv). Truth per pass: the body's crossing of 2 m and 10 m of that pass along x
(trajectory.csv; pass 1 from the start, pass 2 back from the farthest x, pass 3 out from the nearest x after it).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/ten_m_walk_passes_l673.py TMPDIR
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.walk_test import ten_metre_walk_trials

USERS = range(12810, 12820)
ROUTE = "stand:3, straight:12, turn:180, straight:12, turn:180, straight:12, stand:3"


def crossing(t: np.ndarray, x: np.ndarray, after: float, mark: float, sign: float) -> float:
    """The first time after ``after`` the body's x passes ``mark`` going in direction ``sign``."""
    ok = (t > after) & (sign * (x - mark) >= 0)
    return float(t[np.argmax(ok)])


def truth(folder: Path) -> list[tuple[float, float]]:
    """The three passes' middle 8 m: the body's times at 2 m and 10 m (s)."""
    tr = pd.read_csv(folder / "trajectory.csv")
    t, x = tr["timestamp"].to_numpy(float) / 1000, tr["x"].to_numpy(float)
    x0 = x[0]
    i1 = int(np.argmax(x))  # the first turn
    x1 = x[i1]
    i2 = i1 + int(np.argmin(x[i1:]))  # the second turn
    x2 = x[i2]
    out = []
    for start_t, x_start, sign in ((t[0], x0, 1.0), (t[i1], x1, -1.0), (t[i2], x2, 1.0)):
        a = crossing(t, x, start_t, x_start + sign * 2.0, sign)
        b = crossing(t, x, a, x_start + sign * 10.0, sign)
        out.append((a, b))
    return out


def run(tmp: Path) -> pd.DataFrame:
    rows = []
    for u in USERS:
        sim, out = tmp / f"u{u}", tmp / f"tr_u{u}"
        if not sim.exists():
            assert main(["simulate", "--route", ROUTE, "--speed", "normal", "--rate", "100", "--rocker", "smooth",
                  "--user-seed", str(u), "--out", str(sim)]) == 0
            for f in sim.glob("fForce*.csv"):
                f.unlink()
        if not (out / "steps.csv").exists():
            assert main(["track", str(sim), "--toe-off", "--ten-m-walk", "2,8,2", "--out", str(out)]) == 0
        # the trials from the tracked steps.csv by the kernel track uses (ten_m_walk_trials.csv is not written
        # without a timed trial)
        trials = ten_metre_walk_trials(pd.read_csv(out / "steps.csv"), (2.0, 8.0, 2.0))
        for p, (a, b) in enumerate(truth(sim), start=1):
            v = 8.0 / (b - a)
            # the trial timed on this pass: the one whose timed stretch overlaps the pass's middle 8 m
            hit = trials[(trials["start_s"] < b) & (trials["end_s"] > a)]
            got = float(hit["speed_mps"].iloc[0]) if len(hit) else np.nan
            rows.append({"user": u, "pass": p, "truth_mps": v, "track_mps": got, "err_pct": 100 * (got / v - 1),
                         "n_trials": len(trials)})
    return pd.DataFrame(rows)


if __name__ == "__main__":
    df = run(Path(sys.argv[1]))
    print(df.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    print(f"passes timed {int(df['track_mps'].notna().sum())} of {len(df)}; |err| max "
          f"{df['err_pct'].abs().max():.2f} %, median {df['err_pct'].abs().median():.2f} %")
