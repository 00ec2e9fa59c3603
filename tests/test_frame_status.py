"""Decision C142 (trial T3, session 38, finding 6): counting needs no frame (``steps --detector accel`` on a foot yawed
40 deg on the shoe, no frame declared, was refused: "declares no axis frame ... 39 deg from every sensor axis"), and
each unit's frame status is a summary.json key and a track-all sessions.csv column (``frame_foot``, ``frame_waist``:
declared / inferred / contradicted / forced)."""

from __future__ import annotations

import json

import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.track.frame_inference import remount


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("walk", user_seed=9643, length_m=30.0, rate_hz=100.0)


def _turned(walk, axis: str, deg: float):
    """The walk with its foot unit turned ``deg`` about its own ``axis`` and meta.json's foot frame kept."""
    s = remount(walk, "foot", Rotation.from_euler(axis, deg, degrees=True).as_matrix().T)
    s.frames["foot"] = walk.frames["foot"]
    return s


def _stripped(s):
    s = s.copy()
    s.frames = {}
    s.meta = {k: v for k, v in s.meta.items() if k not in ("frames", "source_project")}
    return s


def test_steps_accel_counts_a_yawed_foot_without_a_frame(walk, tmp_path, capsys):
    s = _stripped(remount(walk, "foot", Rotation.from_euler("y", 40, degrees=True).as_matrix().T))
    write_session(s, tmp_path / "yaw40")
    assert main(["steps", str(tmp_path / "yaw40"), "--detector", "accel", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["count"] == got["reference_count"] > 10 and got["f1"] == 1.0


def test_summary_holds_each_units_frame_status(walk):
    from pdrlearn.track import get_pipeline

    forced = _turned(walk, "y", 90.0)
    forced.meta = {**forced.meta, "force_frame": True}
    cases = {"declared": walk.copy(), "contradicted": _turned(walk, "x", 180.0), "forced": forced,
             "inferred": _stripped(walk)}
    for want, s in cases.items():
        sm = get_pipeline("plasys")(s).summary(s)
        assert sm["frame_foot"] == want, (want, sm["frame_foot"])
        assert sm["frame_waist"] == ("inferred" if want == "inferred" else "declared")


def test_track_all_sessions_csv_has_the_frame_columns(walk, tmp_path):
    root = tmp_path / "root"
    write_session(walk, root / "a")
    write_session(_stripped(walk), root / "b")
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "out")]) == 0
    df = pd.read_csv(tmp_path / "out" / "sessions.csv").set_index("path")
    assert df.loc["a", "frame_foot"] == "declared" and df.loc["b", "frame_foot"] == "inferred"
    assert df.loc["b", "frame_waist"] == "inferred"


def test_the_missing_frame_error_says_to_declare_the_nearest_axes(walk):
    from pdrlearn.errors import DataError

    s = _stripped(remount(walk, "foot", Rotation.from_euler("y", 40, degrees=True).as_matrix().T))
    with pytest.raises(DataError) as exc:
        s.require_frame("foot")
    m = str(exc.value)
    assert "a yawed mount" in m and "the sensor axes nearest its forward, left and up" in m
    assert m.endswith('"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}')
