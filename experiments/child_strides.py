"""Steps decision 37: the foot accelerometer detector's shortest stride (``min_stride_s``) 0.6 s vs 0.4 s on
simulated children (users 1100-1139), adults (users 1140-1159), the thesis scenarios of step_count.py (users 1-10,
20 Hz) and the real foot recordings; the rule is in docs/decisions/steps.md (37).

Usage: OMP_NUM_THREADS=1 .venv/bin/python experiments/child_strides.py [--real-dir /work/shared/data]
Writes experiments/results/child_strides.md.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate
from pdrlearn.steps import AccelStepDetector, one_per_stride, score_steps

ROOT = Path(__file__).resolve().parents[1]
FLOORS = (0.6, 0.4)
REAL = ("gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left")


def child(user: int) -> UserProfile:
    """A child of the rule: stature U(0.90, 1.45) m, leg 0.5 h, step 0.40 h, cadence 3.3 Hz at 0.95 m to 2.35 Hz at
    1.40 m (the session 23 trial's ages 3-10), linear, clipped to 2.2-3.5 Hz."""
    h = float(np.random.default_rng([user, 37]).uniform(0.90, 1.45))
    f = float(np.clip(3.3 + (h - 0.95) * (2.35 - 3.3) / (1.40 - 0.95), 2.2, 3.5))
    return dataclasses.replace(UserProfile.from_seed(user).scaled(h, 0.5 * h), step_length_m=round(0.40 * h, 4),
                               step_time_s=round(1.0 / f, 4))


def score(s, floor: float, cli: bool = True) -> dict:
    table = AccelStepDetector(min_stride_s=floor).detect(s)
    if cli and len(table):
        table = one_per_stride(table, s)[0]
    sc = score_steps(table, s)
    return {"count": sc["scored_count"], "reference": sc["reference_count"], "tp": sc["true_positives"], "f1": sc["f1"]}


def rows(kind: str, sessions, cli: bool = True) -> list[dict]:
    out = []
    for label, s in sessions:
        for floor in FLOORS:
            out.append({"kind": kind, "session": label, "floor_s": floor, **score(s, floor, cli)})
    return out


def pooled(df: pd.DataFrame, by: list[str]) -> pd.DataFrame:
    g = df.assign(abs_err=(df["count"] - df["reference"]).abs()).groupby(by)
    t = g.agg(sessions=("session", "size"), reference=("reference", "sum"), detected=("count", "sum"),
              abs_err=("abs_err", "sum"), tp=("tp", "sum")).reset_index()
    t["recall"] = t["tp"] / t["reference"]
    t["count_error_pct"] = 100 * t["abs_err"] / t["reference"]
    return t


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--real-dir", default="/work/shared/data")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    kids = ((f"c{u}_{sc}_{sp}", simulate(sc, child(u), sp, rate_hz=100.0))
            for u in range(1100, 1140) for sc in "AB" for sp in ("normal", "fast"))
    df = pd.DataFrame(rows("children", kids))
    adults = ((f"a{u}_{sc}_{sp}_{r:g}", simulate(sc, u, sp, rate_hz=r)) for u in range(1140, 1160) for sc in "AB"
              for sp in ("slow", "normal", "fast") for r in (20.0, 100.0))
    df = pd.concat([df, pd.DataFrame(rows("adults", adults))])
    thesis = ((f"t{u}_{sc}_{sp}", simulate(sc, u, sp)) for sc in "AB" for sp in ("slow", "normal", "fast")
              for u in range(1, 11))
    th = pd.DataFrame(rows("thesis", thesis, cli=False))
    th["row"] = th["session"].str.split("_", n=1).str[1]
    real = ((n, read_session(Path(a.real_dir) / n)) for n in REAL)
    rl = pd.DataFrame(rows("real", real))
    parts = ["# Steps decision 37: min_stride_s 0.6 vs 0.4 s\n",
             "## Children (users 1100-1139, A/B normal/fast, 100 Hz) and adults (1140-1159), `steps` strides\n",
             pooled(df, ["kind", "floor_s"]).to_markdown(index=False),
             "\n## Thesis scenarios (step_count.py, users 1-10, 20 Hz, detector alone)\n",
             pooled(th, ["row", "floor_s"]).to_markdown(index=False),
             "\n## Real foot recordings, `steps` strides\n", rl.to_markdown(index=False)]
    text = "\n".join(parts) + "\n"
    (ROOT / "experiments" / "results" / "child_strides.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
