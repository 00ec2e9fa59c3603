"""Decision C70's measurement: the DTW decision rule "mean" (thesis ch. 6.1.2.2, lowest mean distance) against
"spread" (the mean distance minus half the class's own mean reference distance), on the same users and seeds.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/dtw_waist_c70.py                 # the rule's users (C70)
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/dtw_waist_c70.py --users 3570 --diagnose
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/dtw_waist_c70.py --real

Each user's DTW models (units foot, waist, fused; cv 5) are trained with ``train_user`` on the three calibration
exercises at normal speed (as experiments/dtw_calibration.py, C67), once per ``training.DTW_RULE``; the held-out
windows are the same exercises with ``seed=1000``, classified on their labelled windows, every task on every
exercise that labels it. ``--diagnose`` prints C69's evidence for the users instead: leave-one-out on the training
windows (mean-distance rule, 1-nearest neighbour, spread rule) and the class x class mean DTW distances.
"""

from __future__ import annotations

import argparse
import logging
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.classify.training as training
from pdrlearn.classify.dtw import as_series, dtw_block
from pdrlearn.features import TASK_COLUMNS
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
RULES = ("mean", "spread")
EXERCISES = ("terrain", "direction", "length")
UNITS = ("foot", "waist", "fused")


def _sessions(user: int, seed: int | None):
    sim = partial(simulate, device_errors=True)  # as experiments/localization.py's run_sim
    kw = {} if seed is None else {"seed": seed}
    return [sim(ex, user_seed=user, speed="normal", **kw) for ex in EXERCISES]


def measure(user: int) -> list[dict]:
    cal, held = _sessions(user, None), _sessions(user, 1000)
    rows = []
    for rule in RULES:
        training.DTW_RULE = rule
        model = training.train_user(cal, user=f"sim{user}", methods=["dtw"], units=list(UNITS), cv=5)
        for task, tm in model.tasks.items():
            col = TASK_COLUMNS[task]
            for s in held:
                truth = s.steps[col].astype(str).to_numpy()
                for unit in UNITS:
                    pr = model.predict_steps(s, tasks=[task], method="dtw", unit=unit, windows="given")
                    rows += [{"user": user, "rule": rule, "task": task, "unit": unit, "exercise": s.meta["scenario"],
                              "cv_accuracy": tm.cv["dtw"][unit]["accuracy"], "truth": t, "pred": p}
                             for t, p in zip(truth, pr[col].astype(str), strict=True)]
    return rows


def _balanced(d: pd.DataFrame) -> float:
    return float(np.mean([np.mean(g["pred"] == g["truth"]) for _, g in d.groupby("truth")]))


def summarise(w: pd.DataFrame) -> None:
    print(f"users completed: {w['user'].nunique()} ({w['user'].min()}-{w['user'].max()})")
    for task in EXERCISES:
        for unit in UNITS:
            parts = []
            for rule in RULES:
                d = w[(w["task"] == task) & (w["unit"] == unit) & (w["rule"] == rule)]
                cv = d.groupby("user")["cv_accuracy"].first().mean()
                parts.append(f"{rule}: accuracy {100 * np.mean(d['pred'] == d['truth']):.2f} %, balanced "
                             f"{100 * _balanced(d):.2f} %, mean CV {100 * cv:.2f} % ({len(d)} windows)")
            print(f"{task} dtw/{unit}: " + " | ".join(parts))


def diagnose(user: int) -> None:
    """C69's evidence: the training windows' leave-one-out accuracy by three rules; class x class mean distances."""
    cal = _sessions(user, None)
    data = {t: training.task_data(training.session_windows(cal, n_samples=40), t, cal) for t in EXERCISES}
    for task, d in data.items():
        cls, yi = np.unique(d.y, return_inverse=True)
        for unit in ("foot", "waist"):
            S = as_series(training.select_signals(d.X, names=training.DTW_SIGNALS[task][unit]))
            S = np.ascontiguousarray((S - S.mean(axis=(0, 1))) / S.std(axis=(0, 1)))  # as DTWClassifier (C2)
            D = dtw_block(S, S, window=4)  # C2: +-10 % of 40 samples
            np.fill_diagonal(D, np.nan)
            means = np.stack([np.nanmean(D[:, yi == k], axis=1) for k in range(len(cls))], axis=1)
            M = np.array([[np.nanmean(D[np.ix_(yi == a, yi == b)]) for b in range(len(cls))]
                          for a in range(len(cls))])
            nn1 = yi[np.argmin(np.where(np.isnan(D), np.inf, D), axis=1)]
            spread = np.argmin(means - 0.5 * np.diag(M)[None], axis=1)
            rec = {n: [round(float(np.mean(p[yi == k] == k)), 3) for k in range(len(cls))]
                   for n, p in (("mean", np.argmin(means, axis=1)), ("spread", spread))}
            print(f"user {user} {task} {unit} classes {list(map(str, cls))} n {np.bincount(yi).tolist()}: LOO "
                  f"mean-distance {np.mean(np.argmin(means, 1) == yi):.3f} (recall {rec['mean']}), 1-NN "
                  f"{np.mean(nn1 == yi):.3f}, spread {np.mean(spread == yi):.3f} (recall {rec['spread']}); "
                  f"class x class mean distance {np.round(M, 2).tolist()}")


REAL_LEFT = ("real/gaitmap_level_left", "real/gaitmap_stairs_up_left", "real/gaitmap_stairs_down_left")
REAL_RIGHT = ("real/gaitmap_level_right", "external/gaitmap_stairs_up_right", "external/gaitmap_stairs_down_right")


def real_check() -> None:
    """The real gaitmap foot terrain recordings (no waist unit): dtw/foot trained on the left foot, tested on the
    right, per rule."""
    from pdrlearn.io import read_session

    left = [read_session(ROOT / "datasets" / n) for n in REAL_LEFT]
    right = [read_session(ROOT / "datasets" / n) for n in REAL_RIGHT]
    for rule in RULES:
        training.DTW_RULE = rule
        model = training.train_user(left, tasks=["terrain"], methods=["dtw"], units=["foot"], cv=5,
                                    user="gaitmap-left")
        ok = []
        for s in right:
            pr = model.predict_steps(s, tasks=["terrain"], method="dtw", unit="foot", windows="given")
            truth = s.steps["terrain"].astype(str).to_numpy()
            keep = np.isin(truth, model.tasks["terrain"].classes)
            ok += list(pr["terrain"].astype(str).to_numpy()[keep] == truth[keep])
        print(f"real gaitmap terrain dtw/foot, left -> right ({len(ok)} strides) {rule}: accuracy "
              f"{100 * np.mean(ok):.2f} %")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, nargs="*", default=list(range(3575, 3600)))
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "dtw_waist_c70.csv")
    ap.add_argument("--diagnose", action="store_true")
    ap.add_argument("--real", action="store_true")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    if a.real:
        return real_check()
    if a.diagnose:
        for u in a.users:
            diagnose(u)
        return None
    rows: list[dict] = []
    for u in a.users:
        rows += measure(u)
        pd.DataFrame(rows).to_csv(a.out, index=False)  # after each user: a stopped run keeps its users
        print(f"user {u} done", flush=True)
    summarise(pd.DataFrame(rows))
    return None


if __name__ == "__main__":
    main()
