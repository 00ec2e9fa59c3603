"""Sim-to-real study: terrain classifiers trained on simulated users only vs trained on real recordings.

1. sim -> real: train each method (foot unit; the real recordings have no waist unit) on the terrain
   calibration exercises of N simulated users, test on every labelled stride of the real foot recordings.
2. real -> real: stratified k-fold cross-validation on the real recordings themselves.
3. The gap per method (points of accuracy).

Only terrain is studied: the real foot recordings carry terrain labels only (direction is always forward,
and the stair strides have no reference length). Writes experiments/results/sim_to_real.md|csv.

    .venv/bin/python experiments/sim_to_real.py [--users 4] [--cv 5]
"""

from __future__ import annotations

import argparse
import logging
import time
from pathlib import Path

import pandas as pd

from pdrlearn.classify import evaluate_model, train_user
from pdrlearn.io import read_session
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
RESULTS = ROOT / "experiments" / "results"
REAL_FOOT = ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]
METHODS = ["heuristic", "dtw", "svm", "nn"]


def main(argv: list[str] | None = None) -> pd.DataFrame:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=4, help="simulated users to train on")
    ap.add_argument("--cv", type=int, default=5, help="folds of the real-data cross-validation")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--rate", type=float, default=20.0,
                    help="simulated output rate (Hz); the real foot recordings are 204.8 Hz")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)

    real = [read_session(REAL / n) for n in REAL_FOOT]
    t0 = time.perf_counter()
    sims = [simulate("terrain", user_seed=u, speed=sp, rate_hz=args.rate) for u in range(1, args.users + 1)
            for sp in ("slow", "normal", "fast")]
    sim_s = time.perf_counter() - t0
    sim_model = train_user(sims, tasks=["terrain"], methods=METHODS, units=["foot"], cv=3, seed=args.seed,
                           user="simulated")
    sim_eval = evaluate_model(sim_model, real, latency=False)["tasks"]["terrain"]
    real_model = train_user(real, tasks=["terrain"], methods=METHODS, units=["foot"], cv=args.cv,
                            seed=args.seed, user="real")
    rows = []
    for m in METHODS:
        real_cv = real_model.tasks["terrain"].cv[m]["foot"]
        s2r = sim_eval["methods"].get(m, {}).get("units", {}).get("foot")
        rows.append({
            "method": m,
            "sim->real accuracy %": 100 * s2r["accuracy"] if s2r else float("nan"),
            "sim->real balanced %": 100 * s2r["balanced_accuracy"] if s2r else float("nan"),
            "real CV accuracy %": 100 * real_cv["accuracy"],
            "real CV balanced %": 100 * real_cv["balanced_accuracy"],
            "gap (points)": 100 * (real_cv["accuracy"] - s2r["accuracy"]) if s2r else float("nan"),
            **{f"sim->real {c} %": 100 * s2r["per_class"][c] for c in sim_eval["classes"] if s2r},
        })
    df = pd.DataFrame(rows)
    RESULTS.mkdir(parents=True, exist_ok=True)
    df.to_csv(RESULTS / "sim_to_real.csv", index=False)
    n_real = sim_eval["n_steps"]
    text = (
        "# Sim-to-real: terrain (foot unit)\n\n"
        f"Trained on {len(sims)} simulated terrain exercises ({args.users} users x 3 speeds, {args.rate:g} Hz, "
        f"{sum(len(s.steps) for s in sims)} strides, simulated in {sim_s:.1f} s); tested on the {n_real} "
        f"labelled strides of the real foot recordings ({', '.join(REAL_FOOT)}). Real CV = {args.cv}-fold "
        "stratified cross-validation on the real strides.\n\n"
        + df.to_markdown(index=False, floatfmt=".1f") + "\n"
    )
    (RESULTS / "sim_to_real.md").write_text(text)
    print(text)
    return df


if __name__ == "__main__":
    main()
