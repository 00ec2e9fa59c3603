"""Decision B105: a unit turned over mid-session is not "gravity removed" (trial `indoor` finding 8)."""

from __future__ import annotations

import logging
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.validate import check_gravity, orientation_change

WAIST = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _flipped(dst: Path) -> tuple[Path, float]:
    """Copy of WAIST whose unit is turned upside down (180 deg about a horizontal axis) halfway through."""
    shutil.copytree(WAIST, dst)
    acc = pd.read_csv(dst / "wAccelerometer.csv")
    g = acc[["x", "y", "z"]].mean().to_numpy()
    n = np.cross(g, np.eye(3)[int(np.argmin(np.abs(g)))])
    n /= np.linalg.norm(n)  # a horizontal axis: the 180 deg turn about it reverses gravity
    t_flip = float(acc["timestamp"].median())
    for name in ("wAccelerometer", "wGyroscope"):
        df = pd.read_csv(dst / f"{name}.csv")
        after = (df["timestamp"] >= t_flip).to_numpy()
        v = df[["x", "y", "z"]].to_numpy()
        v[after] = 2.0 * (v[after] @ n)[:, None] * n - v[after]  # Rodrigues' formula at 180 deg
        df[["x", "y", "z"]] = v
        df.to_csv(dst / f"{name}.csv", index=False)
    return dst, (t_flip - float(acc["timestamp"].iloc[0])) / 1000.0


def test_a_unit_turned_over_mid_session_is_read_with_a_warning_naming_the_time(tmp_path, caplog):
    d, t_flip = _flipped(tmp_path / "flipped")
    with caplog.at_level(logging.WARNING):
        s = read_session(d)  # before B105: "gravity has been removed ... export the raw (total) accelerometer"
    assert "wAccelerometer" in s.streams
    lines = [r.getMessage() for r in caplog.records if "orientation changed" in r.getMessage()]
    assert len(lines) == 1 and str(d / "wAccelerometer.csv") in lines[0] and "gravity has been removed" not in lines[0]
    at = float(lines[0].split("at about ")[1].split(" s")[0])
    assert abs(at - t_flip) <= 4.0 and "split the session" in lines[0]


def test_gravity_removed_is_still_refused_and_not_called_a_turn():
    rng = np.random.default_rng(105)
    t = np.arange(3000) / 100.0
    lin = rng.normal(0.0, 2.0, (3000, 3)) + np.sin(2 * np.pi * 1.8 * t)[:, None]  # linear acceleration: mean ~0
    assert orientation_change(lin, t) is None
    with pytest.raises(DataError, match="gravity has been removed"):
        check_gravity(lin, "lin.csv", t)
    still = np.tile([0.0, 0.0, 9.81], (3000, 1)) + rng.normal(0.0, 0.5, (3000, 3))  # a unit at rest: no change
    check_gravity(still, "still.csv", t)


def test_a_unit_turned_over_and_back_reports_the_turn_not_zero():
    """B105 (review of session 19): the angle was the first window's gravity against the last's, so a unit
    turned over and back again read ~0 deg."""
    t = np.arange(4000) / 100.0
    g = np.tile([0.0, 0.0, 9.81], (4000, 1))
    g[1500:2500] *= -1.0  # upside down from 15 s to 25 s
    g += np.random.default_rng(1).normal(0.0, 0.3, g.shape)
    found = orientation_change(g, t)
    assert found is not None and found[1] > 170.0
