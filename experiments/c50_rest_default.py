"""Decision C50 (adoption rule in docs/decisions/classifiers.md, written before this ran): is `--boundaries rest`
the better default of `pdrlearn train` / `train_user`, scored on the strides the runtime detects (C49)?

Per fresh simulated user: the three calibration exercises (terrain, direction, length; walk seed 0, normal speed) at
the user's rate train two models as `pdrlearn train` does by default (`train_user` defaults: 10-fold CV, the
thesis' five methods, every unit, seed 0) except for `boundaries` ("given", the current default, and "rest",
the candidate); both are evaluated (`evaluate_model`) on scenarios A and D (walk seed 55, normal speed, the
trial's walks) and the C49 detected-stride accuracy of each task's chosen model is pooled over users, tasks and
walks per rate. Usage: OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/c50_rest_default.py --users 800 801
--rate 100 --out experiments/results/c50_rest_default_100hz.csv
"""

from __future__ import annotations

import argparse
import logging
import time
from pathlib import Path

import pandas as pd

from pdrlearn.classify.evaluation import evaluate_model
from pdrlearn.classify.training import train_user
from pdrlearn.sim.simulate import simulate

CALIBRATION = ("terrain", "direction", "length")
WALKS = ("A", "D")


def user_rows(user: int, rate: float) -> list[dict]:
    calib = [simulate(s, user, rate_hz=rate, seed=0) for s in CALIBRATION]
    walks = [simulate(w, user, rate_hz=rate, seed=55) for w in WALKS]
    rows = []
    for boundaries in ("given", "rest"):
        t0 = time.perf_counter()
        model = train_user(calib, boundaries=boundaries)
        secs = time.perf_counter() - t0
        for walk, session in zip(WALKS, walks, strict=True):
            rows += task_rows(evaluate_model(model, [session], latency=False), user=user, rate_hz=rate,
                              boundaries=boundaries, walk=walk, train_s=round(secs, 1))
    return rows


def task_rows(out: dict, **keys) -> list[dict]:
    """One row per task of an `evaluate_model` result: the chosen model's correct / scored steps on the labelled
    boundaries and on the detected strides (C49), with ``keys`` (user, variant, walk, ...)."""
    rows = []
    for task, r in out["tasks"].items():
        det = r["detected"] or {}
        rows.append({**keys, "task": task, "chosen": f"{r['chosen']['method']}/{r['chosen']['unit']}",
                     "n_labelled": r["n_steps"], "correct_labelled": round(r["accuracy"] * r["n_steps"]),
                     "n_detected": det.get("n_steps", 0),
                     "correct_detected": round(det.get("accuracy", 0.0) * det.get("n_steps", 0))})
    return rows


def summary(df: pd.DataFrame, variant: str = "boundaries") -> pd.DataFrame:
    """Pooled detected-stride and labelled-boundary accuracy per rate, ``variant`` column and task (and all)."""
    g = df.groupby(["rate_hz", variant, "task"])[["correct_detected", "n_detected", "correct_labelled",
                                                  "n_labelled"]].sum()
    allt = df.groupby(["rate_hz", variant])[list(g.columns)].sum()
    allt["task"] = "all"
    g = pd.concat([g.reset_index(), allt.reset_index()], ignore_index=True)
    g["acc_detected"] = (g["correct_detected"] / g["n_detected"]).round(4)
    g["acc_labelled"] = (g["correct_labelled"] / g["n_labelled"]).round(4)
    return g.sort_values(["rate_hz", "task", variant])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", type=int, nargs="+", required=True)
    ap.add_argument("--rate", type=float, required=True)
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    rows = []
    for u in a.users:
        t0 = time.perf_counter()
        rows += user_rows(u, a.rate)
        print(f"user {u} at {a.rate:g} Hz: {time.perf_counter() - t0:.0f} s", flush=True)
        pd.DataFrame(rows).to_csv(a.out, index=False)
    print(summary(pd.DataFrame(rows)).to_string(index=False))


if __name__ == "__main__":
    main()
