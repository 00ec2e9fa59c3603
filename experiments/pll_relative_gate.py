"""Decision steps 48's adoption measurement: the ``pll`` step detector's fixed activity gate (decision 18) vs
W76's session-relative gate (``relative_gate=True``) on fresh simulated slow and normal walkers.

Usage: .venv/bin/python experiments/pll_relative_gate.py [--out /tmp/pll_rel]
Prints one row per session (steps detected, reference, F1 of each gate) and the mean F1 per group.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.io import read_session
from pdrlearn.steps import get_detector, score_steps

ROUTE = "stand:3, straight:10, stand:4, straight:10, stand:3"
#: decision steps 48's rule: slow = 6530-6533 x two slow gaits, normal = 6534-6537 x a normal gait and the default
GROUPS = {"slow": [(u, g) for u in range(6530, 6534) for g in ((0.3, 0.9), (0.35, 0.7))],
          "normal": [(u, g) for u in range(6534, 6538) for g in ((0.7, 0.55), None)]}


def session(out: Path, user: int, gait) -> Path:
    d = out / f"u{user}_{'default' if gait is None else f'{gait[0]}_{gait[1]}'}"
    if not (d / "meta.json").exists():
        args = ["simulate", "--route", ROUTE, "--user-seed", str(user), "--out", str(d)]
        args += [] if gait is None else ["--step-length", str(gait[0]), "--step-time", str(gait[1]),
                                         "--bounce", "pendulum"]
        cli(args)
    return d


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("/tmp/pll_rel"))
    args = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    for group, runs in GROUPS.items():
        f1 = {False: [], True: []}
        for user, gait in runs:
            s = read_session(session(args.out, user, gait))
            row = []
            for rel in (False, True):
                sc = score_steps(get_detector("pll", relative_gate=rel).detect(s), s)
                f1[rel].append(sc["f1"])
                row.append(f"{sc['count']:4d} F1 {sc['f1']:.3f}")
            print(f"{group:6s} {s.name:45s} ref {sc['reference_count']:3d} | fixed {row[0]} | relative {row[1]}")
        print(f"{group}: mean F1 fixed {np.mean(f1[False]):.3f} relative {np.mean(f1[True]):.3f} "
              f"(n={len(runs)})")


if __name__ == "__main__":
    main()
