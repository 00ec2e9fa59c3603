"""Decision W351 (docs/decisions/waist.md): W350's lower-back gait-quality columns checked once. (a) fresh simulated
users 7542-7549 walking 60 m symmetric, then the same users with a limp (S35 / S42: steps onto the left foot 30 %
longer in time and in length): the harmonic ratios and the step symmetry must drop; (b) the real mobgap Test5 /
Test11 lower-back recordings, printed beside the healthy-adult ranges as recalled. No default changes: a check.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/gait_quality_w351.py
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn import sim
from pdrlearn.cli import main
from pdrlearn.io import write_session

ROOT = Path(__file__).resolve().parents[1]
USERS = range(7542, 7550)  # the lead's fresh users for I7 (7540-7559)
LIMP = {"step_time_asymmetry": 0.3, "step_length_asymmetry": 0.3}  # S35, S42
SHOWN = ("hr_ap", "hr_v", "hr_ml", "step_symmetry_v", "step_symmetry_ap", "stride_regularity_v", "rms_ml_ratio")


def bouts(folder: Path, out: Path) -> pd.DataFrame:
    """bouts.csv of ``pdrlearn track folder --pipeline waist-pendulum --gait-quality`` (W352; its 10+ stride rows)."""
    assert main(["track", str(folder), "--pipeline", "waist-pendulum", "--gait-quality", "--out", str(out)]) == 0
    b = pd.read_csv(out / "bouts.csv")
    return b[b["hr_ap"].notna()]


def simulated(tmp: Path) -> None:
    rows = []
    for u in USERS:
        for name, knobs in (("symmetric", {}), ("limp", LIMP)):
            d = tmp / f"{name}{u}"
            write_session(sim.simulate("walk", u, length_m=60, **knobs), d)
            for f in d.glob("f*.csv"):  # the lower back only
                f.unlink()
            b = bouts(d, tmp / f"out_{name}{u}")
            rows.append({"user": u, "walk": name, **b[list(SHOWN)].median().to_dict()})
    df = pd.DataFrame(rows)
    print(df.round(2).to_string(index=False))
    wide = df.pivot(index="user", columns="walk")
    for col in SHOWN:
        drop = int((wide[(col, "limp")] < wide[(col, "symmetric")]).sum())
        print(f"{col}: median symmetric {wide[(col, 'symmetric')].median():.2f}, limp "
              f"{wide[(col, 'limp')].median():.2f}; lower with the limp for {drop}/{len(wide)} users")


def real(tmp: Path) -> None:
    rows = []
    for d in sorted((ROOT / "datasets" / "external").glob("mobgap_*_Test*")):
        b = bouts(d, tmp / d.name)
        rows.append({"recording": d.name.removeprefix("mobgap_"), "bouts": len(b),
                     "strides": int(b["n_strides"].sum()), **b[list(SHOWN)].median().to_dict()})
    print(pd.DataFrame(rows).round(2).to_string(index=False))
    print("healthy adults (as recalled, not checked): HR AP ~2-3.5, V ~2.5-4, ML ~1.5-2.5")


if __name__ == "__main__":
    np.seterr(all="ignore")
    with tempfile.TemporaryDirectory() as t:
        simulated(Path(t))
        if "--sim-only" not in sys.argv:
            real(Path(t))
