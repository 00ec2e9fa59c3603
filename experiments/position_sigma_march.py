"""Decisions L334/L335: the 2-sigma coverage of offline two-unit tracks (`plasys-fused`) on march-like routes of
0.8-4 km (trial s32 "load" finding 1), today's radius against L334's candidate (the compass check's measured median
disagreement as the heading error of the extent term, ``compass_extent_rad``), from the same tracks.

``simulate``: users 6320-6331 on :func:`march_route` (0.8-4 km), users 6332-6337 on L128's calibration route
(``experiments/position_sigma.py`` ROUTE, ~530 m), each tracked once with ``pdrlearn track`` as shipped.
``evaluate``: the printed coverage, per user and pooled, of today's ``pos_sigma_m`` and of the candidate.

    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_march.py simulate --work W
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_march.py evaluate --work W
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from position_sigma import ROUTE, errors  # noqa: E402

LONG_USERS = range(6320, 6332)
SHORT_USERS = range(6332, 6338)


def march_route(u: int) -> str:
    """User ``u``'s march: 800 m + 290 m per user above 6320 (800-4000 m), one of four shapes by ``u`` mod 4:
    out and back, a rectangle, an L with 6 % ramps and a right-hand curve, the trial's curves and about-turn."""
    n = 800 + 290 * (u - LONG_USERS[0])
    q = round(n / 4)
    shapes = [f"stand:5, straight:{2 * q}, turn:180, straight:{2 * q}, stand:5",
              f"stand:5, straight:{q}, turn:90, straight:{q}, turn:90, straight:{q}, turn:90, straight:{q}, stand:5",
              f"stand:5, straight:{round(0.3 * n)}, slope:{round(0.1 * n)}:6, turn:90, straight:{round(0.3 * n)}, "
              f"slope:{round(0.1 * n)}:-6, curve:-90:10, straight:{round(0.2 * n)}, stand:5",
              f"stand:5, straight:{q}, curve:90:10, straight:{q}, turn:180, straight:{q}, curve:-90:10, "
              f"straight:{q}, stand:5"]
    return shapes[u % 4]


def cli(*args) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *map(str, args)], check=True, capture_output=True)


def session(u: int, work: Path) -> tuple[Path, Path]:
    route = march_route(u) if u in LONG_USERS else ROUTE
    sim, out = work / f"s{u}", work / f"t{u}"
    if not (sim / "meta.json").is_file():
        cli("simulate", "--route", route, "--user-seed", u, "--seed", u, "--out", sim)
    if not (out / "summary.json").is_file():
        cli("track", sim, "--out", out)
    return sim, out


def simulate(args) -> None:
    for u in [*LONG_USERS, *SHORT_USERS]:
        session(u, args.work)
        print(f"user {u}: tracked", flush=True)


def coverage(users, work: Path, label: str) -> None:
    from pdrlearn.track.position_sigma import compass_extent_rad, sigma_params, sigma_per_row

    rows = {"today": [0, 0, 0], "candidate": [0, 0, 0]}
    for u in users:
        sim, out = session(u, work)
        tr, e = errors(sim, out)
        e = np.hypot(e[:, 0], e[:, 1])
        summ = json.loads((out / "summary.json").read_text())
        info = summ.get("info") or {}
        model = (info.get("position_sigma") or {}).get("model")
        today = tr["pos_sigma_m"].to_numpy(float)
        t = pd.read_csv(out / "trajectory.csv")["t"].to_numpy(float)
        cand = today  # the candidate changes plasys-fused only
        if model == "plasys-fused":  # L334's candidate: the check's median as the extent term's heading error
            params = {**sigma_params(model), "extent_heading_rad": compass_extent_rad(info.get("compass_check"))}
            cand = sigma_per_row(pd.read_csv(out / "steps.csv"), t, params)[1:]
        med = (info.get("compass_check") or {}).get("median_deg")
        line = [f"user {u} ({label}, {summ.get('distance_m', float('nan')):.0f} m, model {model}, "
                f"check median {med if med is None else round(med, 2)} deg, final error {e[-1]:.1f} m)"]
        for name, s in (("today", today), ("candidate", cand)):
            k = int(np.sum(e <= 2 * s))
            r = rows[name]
            r[0], r[1], r[2] = r[0] + k, r[1] + len(e), r[2] + int(e[-1] <= 2 * s[-1])
            line.append(f"{name}: {k}/{len(e)} strides within 2 sigma, final sigma {s[-1]:.1f} m")
        print("; ".join(line), flush=True)
    for name, (k, n, f) in rows.items():
        print(f"{label} {name}: strides within 2 sigma {k}/{n} = {100 * k / n:.1f} %, finals {f}/{len(users)}",
              flush=True)


def evaluate(args) -> None:
    coverage(LONG_USERS, args.work, "march 0.8-4 km")
    coverage(SHORT_USERS, args.work, "L128 route ~530 m")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("simulate", "evaluate"))
    ap.add_argument("--work", type=Path, required=True)
    args = ap.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    {"simulate": simulate, "evaluate": evaluate}[args.mode](args)


if __name__ == "__main__":
    main()
