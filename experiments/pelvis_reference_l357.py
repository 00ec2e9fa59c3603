"""Decision L357's adoption measurement (docs/decisions/localization.md): a pelvis-only reference (a lower-back copy of
a simulated session: w* files, meta.json, ics.csv, trajectory.csv, transfers.csv; no steps.csv) against the full
session's labelled strides, on fresh users 6730-6749 (6730-6739 a chair TUG, 6740-6749 a level walk with a 90 deg
turn), each tracked by the default lower-back pipeline of the tree given (before: a checkout without L357; after:
this one). Metric 1: |distance_ref_m - strides' length_m sum| in % of the latter; metric 2: |altitude_change_ref_m -
strides' height_m sum| (m).

    python experiments/pelvis_reference_l357.py WORK_DIR TREE      # e.g. /tmp/l357 /work/main, then /tmp/l357 .
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

TUG, WALK = "straight:3, turn:180, straight:3", "stand:3, straight:10, turn:90, straight:5, stand:3"
KEEP = ("meta.json", "ics.csv", "trajectory.csv", "transfers.csv")


def _cli(tree: Path, *args: str) -> str:
    return subprocess.run([sys.executable, "-m", "pdrlearn", *args], capture_output=True, text=True, check=True,
                          env={"PYTHONPATH": str(tree.resolve()), "PATH": "/usr/bin:/bin", "MPLBACKEND": "Agg",
                               "OMP_NUM_THREADS": "1"}).stdout


def main(work: Path, tree: Path) -> int:
    here = Path(__file__).resolve().parents[1]
    m1, m2 = [], []
    for u in range(6730, 6750):
        full, copy = work / f"full_{u}", work / f"w_{u}"
        if not full.exists():
            extra = ["--sit-start", "5", "--sit-end", "5"] if u < 6740 else []
            _cli(here, "simulate", "--route", TUG if u < 6740 else WALK, *extra, "--bounce", "pendulum",
                 "--user-seed", str(u), "--out", str(full))
        shutil.rmtree(copy, ignore_errors=True)
        copy.mkdir()
        for p in full.iterdir():
            if p.name.startswith("w") or p.name in KEEP:
                shutil.copy(p, copy / p.name)
        d = json.loads(_cli(tree, "track", str(copy), "--out", str(work / f"t_{u}"), "--force", "--json"))
        st = pd.read_csv(full / "steps.csv")
        length, height = st.groupby("foot")["length_m"].sum().max(), st.groupby("foot")["height_m"].sum().mean()
        m1.append(100 * abs(d["distance_ref_m"] - length) / length)
        m2.append(abs(d["altitude_change_ref_m"] - height))
        print(f"{u} distance_m {d['distance_m']:.3f} distance_ref_m {d['distance_ref_m']:.3f} strides {length:.3f} "
              f"m1 {m1[-1]:.2f} % err {d['distance_error_pct']:+.2f} % alt_ref {d['altitude_change_ref_m']:+.3f} "
              f"m2 {m2[-1]:.3f}", flush=True)
    print(f"n {len(m1)} metric1 median {np.median(m1):.2f} % max {max(m1):.2f} %; metric2 max {max(m2):.3f} m "
          f"median {np.median(m2):.3f} m")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(Path(sys.argv[1]), Path(sys.argv[2])))
