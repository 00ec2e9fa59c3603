"""Steps decision 70: slow hemiparetic walkers' foot tracks, stride count against the labels, and L365's insole lines.

Users 9180-9189 (fresh, session 37), 0.3-0.5 m/s with a step-time asymmetry of 0.3-0.5, each foot simulated with its
insoles. ``--code DIR`` tracks with the pdrlearn checkout at DIR (``PYTHONPATH``), so the same sessions are tracked
before (main) and after the change. Also lists the gaitmap foot recordings' stride counts (rule 3).

    PYTHONPATH=. python experiments/paretic_lull_70.py --code /work/main --sessions out/paretic70
    PYTHONPATH=. python experiments/paretic_lull_70.py --code . --fresh-71   # steps 71's users 9350-9354
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd

# (user, step length m, step time s, step-time asymmetry): 0.3-0.5 m/s, asymmetry 0.3-0.5 (rule 1)
USERS = [(9180, 0.30, 0.75, 0.3), (9181, 0.30, 0.85, 0.4), (9182, 0.25, 0.80, 0.5), (9183, 0.35, 0.80, 0.3),
         (9184, 0.30, 0.70, 0.4), (9185, 0.28, 0.90, 0.5), (9186, 0.35, 0.75, 0.35), (9187, 0.32, 0.85, 0.45),
         (9188, 0.27, 0.75, 0.3), (9189, 0.30, 0.65, 0.5)]
#: steps 71's fresh users 9350-9354 (rule 3), same speeds and asymmetries
USERS_71 = [(9350, 0.30, 0.80, 0.45), (9351, 0.27, 0.85, 0.35), (9352, 0.33, 0.70, 0.5), (9353, 0.26, 0.75, 0.4),
            (9354, 0.34, 0.85, 0.3)]
ROUTE = "stand:3, straight:16, stand:3"


def run(code: str, *args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=code)
    return subprocess.run([sys.executable, "-m", "pdrlearn", *args], env=env, capture_output=True, text=True)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--code", required=True)
    ap.add_argument("--sessions", default="out/paretic70")
    ap.add_argument("--real", nargs="*", default=[])
    ap.add_argument("--fresh-71", action="store_true", help="steps 71's fresh users 9350-9354 instead")
    a = ap.parse_args()
    root = Path(a.sessions)
    rows = []
    for user, sl, st, asym in (USERS_71 if a.fresh_71 else USERS):
        for foot in ("left", "right"):
            d = root / f"s{user}_{foot}"
            if not d.exists():
                r = run(".", "simulate", "--route", ROUTE, "--bounce", "pendulum", "--rate", "100", "--user-seed",
                        str(user), "--step-length", str(sl), "--step-time", str(st), "--step-time-asymmetry",
                        str(asym), "--foot", foot, "--out", str(d))
                if r.returncode:
                    raise SystemExit(r.stderr)
            out = root / f"t{user}_{foot}_{Path(a.code).name}"
            r = run(a.code, "track", str(d), "--out", str(out), "--force")
            n = json.load(open(out / "summary.json"))["n_strides_one_foot"]
            true = len(pd.read_csv(d / "steps.csv"))
            rows.append((user, foot, true, n, n - true, int("disagree with the foot IMU" in r.stderr)))
    df = pd.DataFrame(rows, columns=["user", "foot", "true_strides", "tracked", "error", "insole_line"])
    print(df.to_string(index=False))
    print(f"tracks with a stride-count error: {(df.error != 0).sum()} of {len(df)}; "
          f"insole lines: {df.insole_line.sum()}")
    for rd in a.real:
        out = root / f"real_{Path(rd).name}_{Path(a.code).name}"
        run(a.code, "track", rd, "--out", str(out), "--force")
        print(Path(rd).name, "strides", json.load(open(out / "summary.json"))["n_strides_one_foot"])


if __name__ == "__main__":
    main()
