"""Decision C55 (adoption rule in docs/decisions/classifiers.md, written before this ran): are a walking bout's
edge strides better trained on the windows the runtime cuts (``detected.runtime_bout_edges``)?

Per fresh simulated user (20 Hz): the three calibration exercises (walk seed 0) train two models with
`train_user`'s defaults, without ("labels") and with ("runtime") the candidate; each is evaluated
(`evaluate_model`) on the three exercises at walk seed 7 and scenario D at walk seed 55 (C49's detected-stride and
the labelled-boundary accuracy of each task's chosen model), and scenario D is tracked with `--method M3 --model`
(distance error, %). Usage: OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/c55_bout_edges.py --users 2400 2401
--out experiments/results/c55_bout_edges.csv

Session 41 (decision C162): C55 is the code (its switch ``detected.RUNTIME_BOUT_EDGES`` is gone); the "labels" arm
stands in ``runtime_bout_edges`` returning the labelled steps as they are (:func:`before_c55`).
"""

from __future__ import annotations

import argparse
import contextlib
import logging
import time
from pathlib import Path
from unittest import mock

import pandas as pd

from c50_rest_default import summary, task_rows  # noqa: E402  (the same rows and pooling as C50)
from pdrlearn.classify import detected
from pdrlearn.classify.evaluation import evaluate_model
from pdrlearn.classify.training import train_user
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

CALIBRATION = ("terrain", "direction", "length")
RATE_HZ = 20.0


def before_c55():
    """Training on the labels' bout edges, as before C55 (a stand-in for the "labels" arm, decision C162)."""
    return mock.patch.object(detected, "runtime_bout_edges", lambda session, steps: steps)


def user_rows(user: int) -> tuple[list[dict], list[dict]]:
    calib = [simulate(s, user, rate_hz=RATE_HZ, seed=0) for s in CALIBRATION]
    tests = {**{s: simulate(s, user, rate_hz=RATE_HZ, seed=7) for s in CALIBRATION},
             "D": simulate("D", user, rate_hz=RATE_HZ, seed=55)}
    rows, dist = [], []
    for variant, on in (("labels", False), ("runtime", True)):
        with contextlib.nullcontext() if on else before_c55():
            model = train_user(calib)
        for walk, session in tests.items():
            rows += task_rows(evaluate_model(model, [session], latency=False), user=user, rate_hz=RATE_HZ,
                              edges=variant, walk=walk)
        ev = evaluate_track(track_plasys(tests["D"], method="M3", model=model), tests["D"])
        dist.append({"user": user, "edges": variant, "distance_error_pct": ev["distance_error_pct"]})
    return rows, dist


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", type=int, nargs="+", required=True)
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    rows, dist = [], []
    for u in a.users:
        t0 = time.perf_counter()
        r, d = user_rows(u)
        rows, dist = rows + r, dist + d
        print(f"user {u}: {time.perf_counter() - t0:.0f} s", flush=True)
        pd.DataFrame(rows).to_csv(a.out, index=False)
        pd.DataFrame(dist).to_csv(a.out.with_name(a.out.stem + "_distance.csv"), index=False)
    print(summary(pd.DataFrame(rows), variant="edges").to_string(index=False))
    d = pd.DataFrame(dist).pivot(index="user", columns="edges", values="distance_error_pct")
    print(f"scenario D distance error: mean |runtime - labels| = {(d['runtime'] - d['labels']).abs().mean():.3f} "
          f"points (labels mean {d['labels'].mean():.2f} %, runtime mean {d['runtime'].mean():.2f} %)")


if __name__ == "__main__":
    main()
