"""Frame test helpers: a real lower-back recording clipped turned on its mount (W607's, shared with W615's test)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pandas as pd
from scipy.spatial.transform import Rotation

ROOT = Path(__file__).resolve().parents[1]
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def yawed_lower_back(dest: Path) -> Path:
    """The mobgap lower-back recording turned 90 deg about its up axis (x: a unit clipped at the side), meta.json
    (source_project's frame) unchanged, copied to ``dest``; returns ``dest``."""
    shutil.copytree(WAIST, dest)
    rot = Rotation.from_euler("x", 90, degrees=True)
    for f in dest.glob("w*.csv"):
        df = pd.read_csv(f)
        if {"x", "y", "z"} <= set(df.columns):
            df[["x", "y", "z"]] = rot.apply(df[["x", "y", "z"]].to_numpy())
            df.to_csv(f, index=False)
    return dest
