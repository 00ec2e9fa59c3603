"""Decisions L237-L242: the offline two-unit radius (`plasys-fused`) with the compass's place-dependent error, on
fresh simulated users: L237/L238 as a random walk per metre walked (``path_diffusion_m2``, mode ``evaluate``, users
4700-4739); L239/L240 as a bounded heading error on the route's extent (``extent_heading_rad``, mode ``extent``, users
5040-5079, ``--first-user 5040``); L241/L242 as that error on the part of the extent the track has come back from
(``extent_return_rad``, mode ``extent-return``, users 5130-5169, ``--first-user 5130``).

``prepare``: simulate and track (offline ``track``, no model) - long routes R1 x (2 + u mod 3), users 4700-4739; short
level routes (L182's two, users 4700-4709) and scenarios A-D at 100 Hz (users 4700-4704). Prints no error.
``evaluate`` / ``extent``: today's radius (main's ``SIGMA_PARAMS``) and the candidate's from the same steps.csv,
against the truth.

    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_place.py prepare --work W
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_place.py evaluate --work W
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_place.py prepare --work W2 --first-user 5040
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_place.py extent --work W2 --first-user 5040
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_place.py prepare --work W3 --first-user 5130
    PYTHONPATH=<checkout> .venv/bin/python experiments/position_sigma_place.py extent-return --work W3 --first-user 5130
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from aided_streamed import R1  # noqa: E402
from pdrlearn.track.position_sigma import (  # noqa: E402
    EXTENT_HEADING_RAD,
    PLACE_DIFFUSION_M2,
    SIGMA_PARAMS,
    sigma_per_row,
)
from position_sigma import errors  # noqa: E402

SHORT_ROUTES = ("straight:30, turn:90, straight:30", ", ".join(["straight:15, curve:-90:1"] * 8))  # L182's level walks
#: the first of the 40 users of a run: L237/L238 used 4700-4739, L239/L240 the fresh users 5040-5079, L241/L242 the
#: fresh users 5130-5169
FIRST_USER = 4700
#: mode -> the candidate's kernel term and value: L237's per-metre random walk, L239's bounded heading on the extent,
#: L241's same heading error on the part of the extent the track has come back from
CANDIDATES = {"evaluate": ("path_diffusion_m2", PLACE_DIFFUSION_M2),
              "extent": ("extent_heading_rad", EXTENT_HEADING_RAD),
              "extent-return": ("extent_return_rad", EXTENT_HEADING_RAD)}


def long_routes(u0: int) -> dict[int, str]:
    """Long routes R1 x (2 + u mod 3), users u0 .. u0 + 39."""
    return {u: ", ".join([R1] * (2 + u % 3)) for u in range(u0, u0 + 40)}


def short_sessions(u0: int) -> dict[str, tuple]:
    """L182's two level walks (users u0 .. u0 + 9) and scenarios A-D at 100 Hz (users u0 .. u0 + 4)."""
    return ({f"level{i}_u{u}": ("--route", r, "--user-seed", str(u)) for i, r in enumerate(SHORT_ROUTES)
             for u in range(u0, u0 + 10)}
            | {f"scen{c}_u{u}": ("--scenario", c, "--rate", "100", "--user-seed", str(u)) for c in "ABCD"
               for u in range(u0, u0 + 5)})


def cli(*args) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *map(str, args)], check=True, capture_output=True)


def sessions(u0: int = FIRST_USER) -> dict[str, tuple[str, tuple]]:
    out = {f"long_u{u}": ("long", ("--route", r, "--user-seed", str(u))) for u, r in long_routes(u0).items()}
    return out | {k: ("short", a) for k, a in short_sessions(u0).items()}


def prepare(work: Path, u0: int = FIRST_USER) -> None:
    for name, (_, args) in sessions(u0).items():
        sim, out = work / name, work / f"{name}.off"
        if not (sim / "meta.json").is_file():
            cli("simulate", *args, "--out", sim)
        if not (out / "summary.json").is_file():
            cli("track", sim, "--out", out)
        print(f"prepared {name}", flush=True)


def evaluate(work: Path, u0: int = FIRST_USER, mode: str = "evaluate") -> None:
    today = dict(SIGMA_PARAMS["plasys-fused"])
    term, value = CANDIDATES[mode]
    cand = {**today, term: value}
    print(f"today {today}; candidate {term} = {value:.5f}")
    loops: dict = {}
    res: dict = {}
    for name, (group, _) in sessions(u0).items():
        sim, out = work / name, work / f"{name}.off"
        info = json.loads((out / "summary.json").read_text()).get("info") or {}
        warned = bool((info.get("compass_check") or {}).get("gyro_fallback"))
        key = f"{group}{' (L182 warned)' if warned and group == 'long' else ''}"
        tr, e = errors(sim, out)
        e = np.hypot(e[:, 0], e[:, 1])
        steps, t = pd.read_csv(out / "steps.csv"), pd.read_csv(out / "trajectory.csv")["t"].to_numpy(float)
        line = []
        for tag, par in (("today", today), ("candidate", cand)):
            s = sigma_per_row(steps, t, par)[1:]
            r = res.setdefault((key, tag), {"k": 0, "n": 0, "fin": [], "ratio": [], "sig": []})
            r["k"] += int(np.sum(e <= 2 * s))
            r["n"] += len(e)
            r["fin"].append(bool(e[-1] <= 2 * s[-1]))
            r["ratio"].append(e[-1] / s[-1])
            r["sig"].append(s[-1])
            line.append(f"{tag} 2 sigma {2 * s[-1]:.2f} m {'in' if e[-1] <= 2 * s[-1] else 'OUT'}")
            if key == "long":
                lp = loops.setdefault((2 + int(name.rsplit("u", 1)[1]) % 3, tag), {"fin": [], "err": []})
                lp["fin"].append(bool(e[-1] <= 2 * s[-1]))
                lp["err"].append(e[-1])
        print(f"{key} {name}: final error {e[-1]:.2f} m; " + "; ".join(line), flush=True)
    for (key, tag), r in res.items():
        f = sum(r["fin"])
        print(f"{key} {tag}: finals within 2 sigma {f}/{len(r['fin'])} = {100 * f / len(r['fin']):.1f} %, strides "
              f"{r['k']}/{r['n']} = {100 * r['k'] / r['n']:.1f} %, median final error / 1-sigma "
              f"{np.median(r['ratio']):.3f}, median final 1-sigma {np.median(r['sig']):.2f} m")
    for (n, tag), lp in sorted(loops.items()):  # reported, not in either rule
        print(f"long R1 x {n} {tag}: finals within 2 sigma {sum(lp['fin'])}/{len(lp['fin'])}, median final error "
              f"{np.median(lp['err']):.2f} m")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("prepare", *CANDIDATES))
    ap.add_argument("--work", type=Path, required=True, help="folder for the sessions and tracks (reused)")
    ap.add_argument("--first-user", type=int, default=FIRST_USER,
                    help="first of the 40 users (L237/L238: 4700; L239/L240: 5040; L241/L242: 5130)")
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    if a.mode == "prepare":
        prepare(a.work, a.first_user)
    else:
        evaluate(a.work, a.first_user, a.mode)


if __name__ == "__main__":
    main()
