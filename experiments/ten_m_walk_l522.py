"""Decisions L522, L523 (session 39, trial T1 finding 5): a 10 m walkway timed over its middle 6 m
(``track --ten-m-walk 2,6,2``) against the trunk's true crossing times, beside ``--splits 2,8``; fresh users
10080-10083 (slow) and 10084-10087 (fast). Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/ten_m_walk_l522.py [WORKDIR]
Output: experiments/results/ten_m_walk_l522.txt (the printed lines).
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

USERS = {**dict.fromkeys(range(10080, 10084), "slow"), **dict.fromkeys(range(10084, 10088), "fast")}
ROUTE = "stand:3, straight:10.5, stand:3"  # a 10 m walkway with 0.5 m of run-out (L349)
ZONES = (2.0, 6.0, 2.0)  # decision L522: the clinic's 10 m walkway, its middle 6 m
PDR = [sys.executable, "-m", "pdrlearn"]


def run(*args: str) -> None:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{args}: exit {done.returncode}: {done.stderr[-2000:]}")


def true_times(sim: Path, marks) -> np.ndarray:
    """The trunk's crossing times (s) of ``marks`` metres from its start (trajectory.csv, x along the walk)."""
    tr = pd.read_csv(sim / "trajectory.csv")
    t, x = tr["timestamp"].to_numpy(float) / 1000.0, tr["x"].to_numpy(float) - float(tr["x"].iloc[0])
    return np.array([np.interp(m, *(lambda i: (x[i - 1:i + 1], t[i - 1:i + 1]))(int(np.flatnonzero(x >= m)[0])))
                     for m in marks])


def main(work: Path) -> None:
    errors = []
    for u, speed in USERS.items():
        sim, out = work / f"sim_{u}", work / f"tr_{u}"
        run("simulate", "--route", ROUTE, "--speed", speed, "-u", str(u), "--rate", "100", "--out", str(sim), "--force")
        run("track", str(sim), "--units", "foot", "--ten-m-walk", ",".join(f"{z:g}" for z in ZONES), "--splits",
            f"{ZONES[0]:g},{ZONES[0] + ZONES[1]:g}", "--out", str(out), "--force")
        t0, t1 = true_times(sim, [ZONES[0], ZONES[0] + ZONES[1]])
        truth = ZONES[1] / (t1 - t0)
        s = json.loads((out / "summary.json").read_text())
        got = s.get("ten_m_walk_speed_mps")
        sp = pd.read_csv(out / "splits.csv")
        split_speed = float(sp["speed_mps"].iloc[-1]) if len(sp) == 2 else float("nan")
        err = (got - truth) if got is not None else float("nan")
        errors.append(err)
        print(f"u{u} {speed}: true {truth:.3f} m/s; --ten-m-walk 2,6,2 "
              + (f"{got:.3f} m/s ({err:+.3f})" if got is not None else f"not timed: {s.get('ten_m_walk_note')}")
              + f"; --splits 2,8 {split_speed:.3f} m/s ({split_speed - truth:+.3f})")
    e = np.abs(np.array(errors))
    print(f"--ten-m-walk: timed {np.isfinite(e).sum()}/{len(e)}, |error| median {np.nanmedian(e):.3f} max "
          f"{np.nanmax(e):.3f} m/s; criterion (all timed, all within 0.05 m/s): "
          f"{'met' if np.isfinite(e).all() and (e <= 0.05).all() else 'NOT met'}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="tenmwt_")))
