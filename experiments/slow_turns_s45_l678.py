"""Decision L678 (session 45, fixer FF, trial T1 finding F3): turns of slow walkers turning in small strides, before
(L104's 15 deg/s) and after (16.5 deg per stride of the walker's rhythm, ``clinical.turn_rate_threshold``) on fresh
users 12850-12859 - a 90, 180 and -90 deg pivot in small steps and a 90 deg turn, 0.25-0.45 m / 0.75-1.0 s steps,
no insoles. Measured once, after the rule was written (docs/decisions/localization.md L678).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/slow_turns_s45_l678.py [WORKDIR]
Prints one line per user: the threshold, and turns.csv's rows (angle@start-end) before and after.
Output: experiments/results/slow_turns_s45_l678.txt (the printed lines).
"""
import subprocess
import sys
import tempfile
from pathlib import Path

import pandas as pd

from pdrlearn.track import clinical

ROUTE = ("stand:3, straight:4, pivot:90:6:0.05, straight:4, stand:3, pivot:180:12:0.05, straight:4, "
         "pivot:-90:6:0.05, straight:3, turn:90, straight:3, stand:3")
STEPS = [("0.25", "1.0"), ("0.30", "0.9"), ("0.35", "0.85"), ("0.40", "0.8"), ("0.45", "0.75")] * 2
PDR = [sys.executable, "-m", "pdrlearn"]


def run(*args: str) -> None:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{args}: exit {done.returncode}: {done.stderr[-2000:]}")


def turns(folder: Path, before: bool) -> pd.DataFrame:
    keep = clinical.turn_rate_threshold
    if before:  # L104's fixed rate
        clinical.turn_rate_threshold = lambda st, rate=clinical.TURN_RATE_MIN_DPS: rate
    try:
        return clinical.turn_table(pd.read_csv(folder / "steps.csv"), pd.read_csv(folder / "bouts.csv"))
    finally:
        clinical.turn_rate_threshold = keep


def main(work: Path) -> None:
    found = [0, 0]
    for i, (length, period) in enumerate(STEPS):
        u = 12850 + i
        sim, out = work / f"sim_{u}", work / f"tr_{u}"
        run("simulate", "--route", ROUTE, "--step-length", length, "--step-time", period, "--bounce", "pendulum",
            "--rocker", "smooth", "--rate", "100", "--user-seed", str(u), "--out", str(sim), "--force")
        for f in sim.glob("fForce*"):  # the trial's set-up: foot IMU and lower-back IMU, no insoles
            f.unlink()
        run("track", "--no-plot", str(sim), "--out", str(out), "--force")
        st = pd.read_csv(out / "steps.csv").sort_values("start_s").reset_index(drop=True)
        rows = [turns(out, before) for before in (True, False)]
        found = [found[k] + len(rows[k]) for k in (0, 1)]
        text = [" ".join(f"{r.angle_deg:+.1f}@{r.start_s:.1f}-{r.end_s:.1f}" for r in t.itertuples()) for t in rows]
        print(f"user {u}: threshold {clinical.turn_rate_threshold(st):.2f} deg/s | before {len(rows[0])}: {text[0]} "
              f"| after {len(rows[1])}: {text[1]}")
    print(f"turns found of 40: before {found[0]}, after {found[1]}")


if __name__ == "__main__":
    if len(sys.argv) > 1:
        main(Path(sys.argv[1]))
    else:
        with tempfile.TemporaryDirectory() as tmp:
            main(Path(tmp))
