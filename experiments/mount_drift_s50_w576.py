"""Decision W576 (session 50): a belt slide moves the quiet standing too, a lean does not. Measured by the rule written
in docs/decisions/waist.md before measuring, on W565's route (``mount_drift_s49_w565``'s truth and scoring).

Users 17150-17179 drifted (``y:20``, ``y:-20``, ``x:15``), 17180-17209 undrifted stand-ins for a stooped / leaning
trunk (``--waist-mount y:15``, ``y:-15``, ``--trunk-jerks 0.5``); each tracked with ``mount_drift`` true (W565) and
"standing" (W576), W566's correction on. Then every real lower-back recording and the trial s49t3's slid files.
``PYTHONPATH=. python experiments/mount_drift_s50_w576.py [sim|real]``.
"""

from __future__ import annotations

import logging
import subprocess
import sys
from pathlib import Path

import numpy as np

import mount_drift_s49_w565 as base

SIM = Path("/tmp/i4_w576/sim")
DRIFTED = range(17150, 17180)
UNDRIFTED = range(17180, 17210)
MODES = (True, "standing")
REAL = sorted([*Path("/work/shared/data").glob("mobgap_*"), *Path("/work/main/datasets/external").glob("mobgap_*")])


def condition(user: int) -> list[str]:
    if user < 17160:
        return ["--waist-mount-drift", "y:20"]
    if user < 17170:
        return ["--waist-mount-drift", "y:-20"]
    if user < 17180:
        return ["--waist-mount-drift", "x:15"]
    if user < 17190:
        return ["--waist-mount", "y:15"]
    if user < 17200:
        return ["--waist-mount", "y:-15"]
    return ["--trunk-jerks", "0.5"]


def simulate(user: int) -> Path:
    out = SIM / f"u{user}"
    if not (out / "meta.json").exists():
        cmd = [sys.executable, "-m", "pdrlearn", "simulate", "--route", base.ROUTE, "--user-seed", str(user),
               "--bounce", "pendulum", "--rate", "100", "--out", str(out), "--force", *condition(user)]
        subprocess.run(cmd, check=True, capture_output=True)
    return out


def sim() -> None:
    res = {}
    for u in [*DRIFTED, *UNDRIFTED]:
        folder = simulate(u)
        rows, sit_true = base.truth(folder)
        for mode in MODES:
            tr, sit, stand, warned = base.run(folder, True, mode)
            miss, false = base.errors(tr, rows)
            res[(u, mode)] = (miss, false, abs(sit - sit_true), warned)
            print(f"{u} {' '.join(condition(u)):26s} mount_drift={mode!s:8s} transfers {len(tr)}/{len(rows)} "
                  f"miss {miss} false {false} sitting {sit:.2f} (true {sit_true:.2f}) warned {warned}", flush=True)
    for name, users in (("drifted", DRIFTED), ("undrifted", UNDRIFTED)):
        for mode in MODES:
            v = [res[(u, mode)] for u in users]
            print(f"SUMMARY {name:9s} mount_drift={mode!s:8s} n={len(v)} misses+false {sum(m + f for m, f, _, _ in v)} "
                  f"median |sitting err| {np.median([e for _, _, e, _ in v]):.2f} s warned {sum(w for *_, w in v)}")


def real() -> None:
    for folder in [*REAL, *sorted(base.TRIAL.glob("HA001_*"))]:
        for mode in MODES:
            tr, sit, stand, warned = base.run(folder, True, mode)
            print(f"REAL {folder.parent.parent.name}/{folder.name} mount_drift={mode!s:8s} transfers {len(tr)} "
                  f"sitting {sit:.2f} standing {stand:.2f} warned {warned}", flush=True)


if __name__ == "__main__":
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    {"sim": sim, "real": real}[(sys.argv[1:] or ["sim"])[0]]()
