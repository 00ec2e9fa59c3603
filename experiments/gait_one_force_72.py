"""Steps decision 72's measurement: `pdrlearn gait` step-time SI against the labelled reference, left foot without
force, right with, users 10101-10105 (and both feet with force, unchanged), with the code under ``--code`` (a
checkout whose package is imported) - run it once with this checkout and once with the code before steps 72.

    python experiments/gait_one_force_72.py --code . --work /tmp/m72
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

USERS = range(10101, 10106)  # steps 72's fresh users
ROUTE = "stand:2, straight:30, stand:2"


def _run(code: Path, *args: str) -> str:
    env = {**os.environ, "PYTHONPATH": str(code)}
    out = subprocess.run([sys.executable, "-m", "pdrlearn", *args], env=env, capture_output=True, text=True,
                         check=True, cwd=code)  # `-m` puts the working folder first on sys.path: the code's
    return out.stdout


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--code", type=Path, required=True)
    ap.add_argument("--work", type=Path, required=True)
    a = ap.parse_args()
    a.code, a.work = a.code.resolve(), a.work.resolve()
    a.work.mkdir(parents=True, exist_ok=True)
    for u in USERS:
        d = {foot: a.work / f"u{u}_{foot}" for foot in ("left", "right")}
        for foot, folder in d.items():
            if not folder.exists():
                _run(a.code, "simulate", "--route", ROUTE, "--user-seed", str(u), "--rate", "100", "--rocker",
                     "smooth", "--foot", foot, "--out", str(folder))
        nf = a.work / f"u{u}_left_nf"
        if not nf.exists():
            shutil.copytree(d["left"], nf)
            for f in nf.glob("fForce*"):
                f.unlink()
        for kind, left in (("one-force", nf), ("both-force", d["left"])):
            res = json.loads(_run(a.code, "gait", str(left), str(d["right"]), "--json"))
            si, ref = res["walk"]["step_time_s_si_pct"], res["reference"]["walk"]["step_time_s_si_pct"]
            print(f"user {u} {kind}: step-time SI {si:.2f} % reference {ref:.2f} % |diff| {abs(si - ref):.2f}",
                  flush=True)


if __name__ == "__main__":
    main()
