"""trajectory.csv must lie on the sensor files' clock and in their unit (decision B25): a trajectory in
seconds beside millisecond sensor files, or on another clock, was read silently and every error number
computed against it was wrong."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
FOOT = ROOT / "datasets" / "real" / "gaitmap_level_left"


def _copy_with_trajectory(tmp_path: Path, edit) -> Path:
    d = tmp_path / "s"
    shutil.copytree(FOOT, d)
    tr = edit(pd.read_csv(d / "trajectory.csv"))
    tr.to_csv(d / "trajectory.csv", index=False)
    return d


def test_trajectory_in_seconds_beside_ms_sensor_files_is_refused_with_the_factor(tmp_path):
    d = _copy_with_trajectory(tmp_path, lambda tr: tr.assign(timestamp=tr["timestamp"] / 1000.0))
    with pytest.raises(DataError) as exc:
        read_session(d)
    m = str(exc.value)
    assert "\n" not in m and str(d / "trajectory.csv") in m
    assert "read as s they fit" in m and "multiply by 1000" in m


def test_a_sparse_trajectory_in_seconds_is_refused_too(tmp_path):
    """1 Hz in s read as ms is a plausible 1000 Hz inside the first 0.04 s: the span gives it away."""
    d = _copy_with_trajectory(tmp_path, lambda tr: tr.iloc[::100].assign(timestamp=lambda f: f["timestamp"] / 1000.0))
    with pytest.raises(DataError, match="read as s they fit"):
        read_session(d)


def test_trajectory_on_another_clock_is_refused(tmp_path):
    d = _copy_with_trajectory(tmp_path, lambda tr: tr.assign(timestamp=tr["timestamp"] + 3.6e6))
    with pytest.raises(DataError) as exc:
        read_session(d)
    m = str(exc.value)
    assert str(d / "trajectory.csv") in m and "does not lie on the sensors' clock" in m and "offset" in m


def test_truthful_trajectories_are_read(tmp_path):
    s = read_session(FOOT)
    assert s.trajectory is not None and s.trajectory["t"].iloc[-1] == pytest.approx(38.69, abs=0.05)
    sim = simulate("A", 0, "normal")
    write_session(sim, tmp_path / "sim")
    back = read_session(tmp_path / "sim")
    assert back.trajectory["t"].to_numpy() == pytest.approx(sim.trajectory["t"].to_numpy())
    # a session written in seconds throughout, declared: read
    d = tmp_path / "sec"
    shutil.copytree(FOOT, d)
    for f in d.glob("*.csv"):
        df = pd.read_csv(f)
        if "timestamp" in df:
            df["timestamp"] = df["timestamp"] / 1000.0
            df.to_csv(f, index=False)
        elif f.name == "steps.csv":
            f.unlink()
    meta = json.loads((d / "meta.json").read_text())
    meta["units"] = {**meta.get("units", {}), "timestamp": "s"}
    (d / "meta.json").write_text(json.dumps(meta))
    assert read_session(d).trajectory["t"].iloc[-1] == pytest.approx(38.69, abs=0.05)
