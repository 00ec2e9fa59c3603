"""Decision E216 (docs/decisions/export.md): a waist-headed stride classed forward placed by |length|, old vs new.

Simulates E216's scenarios (fresh users 9890-9899, 100 Hz), replays each through ``pdrlearn run`` with the default
bundle (two units: strides headed by the waist gyroscope) with ``kernels.stride.waist_forward_flip`` replaced by 0
(old) and as shipped, and prints per user: the median and max per-stride position error (the track's position at
each stride end against the tracked foot's true position there, both from the first stride's start), the final
position error and the strides placed against the truth's travel (more than 90 deg off the foot's true
displacement, strides over 0.2 m); then the means per scenario. Offline ``pdrlearn track DIR`` (no model) is printed
as the check E216 names (unchanged code).

    PYTHONPATH=. python experiments/waist_forward_sign_e216.py --out /tmp/e216 [--sets P]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROUTES = {
    "P": ("stand:3, straight:8, turn:90, straight:4, turn:180, straight:6, turn:-90, straight:6, stand:3",
          range(9890, 9900)),
    "Q": ("stand:3, straight:5, turn:135, straight:3, turn:-135, straight:3, turn:180, straight:5, stand:3",
          range(9890, 9895)),
    "S": ("stand:3, straight:20, stand:3", range(9895, 9900)),
}
BUNDLE = "models/plasys-sim-default"


def _cli(args: list[str], flag: bool | None = None) -> None:
    code = "import sys; from pdrlearn.cli import main; "
    if flag is False:  # E216's old arm: no flip in either path (the adopted rule has no module switch, W413)
        code = ("import pdrlearn.kernels.stride as S, pdrlearn.runtime.tracker as T; "
                "S.waist_forward_flip = T.waist_forward_flip = lambda *a, **k: 0.0; ") + code
    subprocess.run([sys.executable, "-c", code + f"sys.exit(main({args!r}))"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def stride_errors(sim: Path, out: Path) -> tuple[float, float, float, int]:
    """(median, max per-stride error, final error, wrong-way strides) of the track in ``out`` against ``sim``."""
    steps = pd.read_csv(out / "steps.csv")
    truth = pd.read_csv(sim / "foot_trajectory.csv")
    t = truth["t_ms"].to_numpy(float) / 1000.0

    def at(ts):
        ts = np.asarray(ts, float)
        return np.column_stack([np.interp(ts, t, truth[c].to_numpy(float)) for c in ("x", "y")])

    if "x" not in steps:  # offline track: positions in trajectory.csv, one row per stride end after its start
        traj = pd.read_csv(out / "trajectory.csv")
        steps = steps.assign(x=traj["x"].to_numpy(float)[1:len(steps) + 1] - float(traj["x"].iloc[0]),
                             y=traj["y"].to_numpy(float)[1:len(steps) + 1] - float(traj["y"].iloc[0]))
    t0 = float(steps["start_s"].iloc[0])
    true_end = at(steps["end_s"]) - at([t0])[0]
    true_start = at(steps["start_s"]) - at([t0])[0]
    est = steps[["x", "y"]].to_numpy(float)
    err = np.hypot(*(est - true_end).T)
    prev = np.vstack([[0.0, 0.0], est[:-1]])
    moved, true_moved = est - prev, true_end - true_start
    long = np.hypot(*true_moved.T) > 0.2
    cosang = np.sum(moved * true_moved, axis=1)
    wrong = int(np.count_nonzero(long & (np.hypot(*moved.T) > 0) & (cosang < 0)))
    return float(np.median(err)), float(err.max()), float(err[-1]), wrong


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="/tmp/e216")
    ap.add_argument("--sets", default="PQS", help="the scenarios to run (letters of ROUTES; run as parallel processes)")
    a = ap.parse_args()
    root = Path(a.out)
    means = {}
    for name, (route, users) in ROUTES.items():
        if name not in a.sets:
            continue
        rows = []
        for u in users:
            sim = root / f"{name}_u{u}"
            if not (sim / "meta.json").exists():
                _cli(["simulate", "--route", route, "--user-seed", str(u), "--rate", "100", "--out", str(sim),
                      "--force"])
            row = {"user": u}
            for tag, flag in (("old", False), ("new", True)):
                out = root / f"{name}_u{u}_run_{tag}"
                _cli(["run", BUNDLE, str(sim), "--out", str(out), "--force"], flag)
                row.update(dict(zip([f"{tag}_{k}" for k in ("med", "max", "end", "wrong")],
                                    stride_errors(sim, out), strict=True)))
            for tag, flag in (("off_old", False), ("off_new", True)):
                out = root / f"{name}_u{u}_track_{tag}"
                _cli(["track", str(sim), "--out", str(out), "--force"], flag)
                row[f"{tag}_end"] = stride_errors(sim, out)[2]
            rows.append(row)
            print(name, u, " ".join(f"{k} {v:.3f}" if isinstance(v, float) else f"{k} {v}"
                                    for k, v in row.items() if k != "user"), flush=True)
        df = pd.DataFrame(rows)
        means[name] = df.drop(columns="user").mean()
    print("\nmeans per scenario (m; wrong = strides placed against the travel, mean per user)")
    for name, m in means.items():
        print(name, " ".join(f"{k} {v:.3f}" for k, v in m.items()))


if __name__ == "__main__":
    main()
