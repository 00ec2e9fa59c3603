"""Decision L220: the 2-sigma coverage of offline two-unit tracks (`plasys-fused`) on the trial's multi-floor route R1
repeated, and the fit of the distance-walked term ``path_rel``.

``fit``: the smallest ``path_rel`` (3 significant digits) with which 17 of 20 finals lie within 2 sigma on the offline
tracks of ``experiments/aided_streamed.py``'s cache (users 4000-4019, R1 x 2).
``evaluate``: users 4020-4039, long route R1 x (2 + u mod 3) and short route R1 x 1, offline ``track`` without a model;
the coverage of main's parameters (today's) and of the candidate (``--path-rel``), from the same steps.csv.

    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_long.py fit --cache DIR
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_long.py evaluate --work W --path-rel V
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from aided_streamed import R1  # noqa: E402
from pdrlearn.track.position_sigma import SIGMA_PARAMS, sigma_per_row  # noqa: E402
from position_sigma import errors  # noqa: E402

#: main's `plasys-fused` parameters before L220 (decision L128), today's model
TODAY = {k: v for k, v in SIGMA_PARAMS["plasys-fused"].items() if k != "path_rel"}


def cli(*args) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *map(str, args)], check=True, capture_output=True)


def ratios(sim: Path, out: Path, params: dict) -> tuple[np.ndarray, np.ndarray]:
    """The true error and the 2-sigma radius after every stride under ``params``."""
    tr, e = errors(sim, out)
    t = pd.read_csv(out / "trajectory.csv")["t"].to_numpy(float)
    s = sigma_per_row(pd.read_csv(out / "steps.csv"), t, params)[1:]
    return np.hypot(e[:, 0], e[:, 1]), 2 * s


def needed(sim: Path, out: Path) -> float:
    """The smallest path_rel putting this track's final position within 2 sigma (bisection)."""
    e, r = ratios(sim, out, TODAY)
    if e[-1] <= r[-1]:
        return 0.0
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        e, r = ratios(sim, out, {**TODAY, "path_rel": mid})
        lo, hi = (lo, mid) if e[-1] <= r[-1] else (mid, hi)
    return hi


def fit(args) -> None:
    need = []
    for u in range(4000, 4020):
        v = needed(args.cache / f"u{u}", args.cache / f"u{u}.off")
        need.append(v)
        print(f"user {u}: path_rel needed for the final within 2 sigma {v:.5f}", flush=True)
    k = np.sort(need)[16]  # 17 of 20 finals (L150's criterion)
    print(f"path_rel = 17th smallest = {k:.5g} -> {float(f'{k:.3g}') if k else 0.0:.3g} (3 significant digits, "
          "rounded up below when needed)")
    v = float(f"{k:.3g}")
    if v < k:
        v = float(f"{k * 1.0005:.3g}")
    print(f"path_rel chosen: {v:g}")


def track(u: int, work: Path, loops: int) -> tuple[Path, Path]:
    sim, out = work / f"s{u}_x{loops}", work / f"t{u}_x{loops}"
    if not (sim / "meta.json").is_file():
        cli("simulate", "--route", ", ".join([R1] * loops), "--user-seed", u, "--out", sim)
    if not (out / "summary.json").is_file():
        cli("track", sim, "--out", out)
    return sim, out


def evaluate(args) -> None:
    cand = {**TODAY, "path_rel": args.path_rel}
    for name, loops_of in (("long", lambda u: 2 + u % 3), ("short", lambda u: 1)):
        res = {"today": [0, 0, 0], "candidate": [0, 0, 0]}  # strides inside, strides, finals inside
        for u in range(4020, 4040):
            sim, out = track(u, args.work, loops_of(u))
            line = []
            for tag, par in (("today", TODAY), ("candidate", cand)):
                e, r = ratios(sim, out, par)
                res[tag][0] += int(np.sum(e <= r))
                res[tag][1] += len(e)
                res[tag][2] += int(e[-1] <= r[-1])
                line.append(f"{tag} 2 sigma {r[-1]:.2f} m {'in' if e[-1] <= r[-1] else 'OUT'}")
            print(f"{name} user {u} (R1 x {loops_of(u)}): final error {e[-1]:.2f} m; " + "; ".join(line), flush=True)
        for tag, (k, n, f) in res.items():
            print(f"{name} {tag}: finals within 2 sigma {f}/20 = {5 * f:.0f} %, strides {k}/{n} = {100 * k / n:.1f} %")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("fit", "evaluate"))
    ap.add_argument("--cache", type=Path, help="fit: experiments/aided_streamed.py's --cache")
    ap.add_argument("--work", type=Path, help="evaluate: folder for the sessions and tracks (reused)")
    ap.add_argument("--path-rel", type=float, default=0.0)
    a = ap.parse_args()
    if a.mode == "fit":
        fit(a)
    else:
        a.work.mkdir(parents=True, exist_ok=True)
        evaluate(a)


if __name__ == "__main__":
    main()
