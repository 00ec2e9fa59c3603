"""Decisions L525 / B401 (session 39, fixer FH, trial T2 finding 2): a foot gyroscope clipped at +-250 deg/s."""
from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.clinical import clinical_summary
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

FULL = np.deg2rad(250.0)  # a +-250 deg/s MEMS gyroscope (trial T2's $3 IMU)


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A simulated walk with a 90 deg left turn (user 10150, the fresh range of session 39) and the same files with
    the foot gyroscope clipped at +-250 deg/s (the simulated foot swings at up to ~600 deg/s)."""
    root = tmp_path_factory.mktemp("l525")
    clean = root / "clean"
    assert main(["simulate", "--route", "stand:3, straight:14, turn:90, straight:8, stand:3", "--rate", "100",
                 "--user-seed", "10150", "--out", str(clean)]) == 0
    clip = root / "clip"
    clip.mkdir()
    for f in clean.iterdir():
        (clip / f.name).write_bytes(f.read_bytes())
    g = pd.read_csv(clean / "fGyroscope.csv")
    g[["x", "y", "z"]] = np.clip(g[["x", "y", "z"]].to_numpy(), -FULL, FULL)
    g.to_csv(clip / "fGyroscope.csv", index=False)
    return clean, clip


def _scores(folder):
    s = read_session(folder)
    res = track_plasys(s)
    out = evaluate_track(res, s)
    return res, out, clinical_summary(res.steps)["turn_count"]


def test_clipped_foot_gyroscope_offline_track_turns_and_stays_level_l525(walks):
    clean, clip = walks
    res, out, turns = _scores(clip)
    # before L525: the fused heading followed the clipped foot's drifting stride yaw and the stride's gravity leak
    # climbed: turn_count 0 and metres of altitude on a level walk
    assert turns == 1
    assert abs(res.info.get("altitude_change_m", res.steps["dz_m"].sum())) < 0.5
    assert out["final_position_error_m"] < 3.0
    assert any("decision L525" in w for w in res.info["warnings"])
    res0, out0, turns0 = _scores(clean)  # unclipped: no L525 line, the fused heading as before
    assert turns0 == 1 and not any("L525" in w for w in res0.info["warnings"])
    assert res0.info["heading_source"] == "fused" and res.info["heading_source"] == "waist"


def test_clipped_foot_gyroscope_line_states_share_and_remedy_b401(walks, caplog):
    _, clip = walks
    with caplog.at_level(logging.WARNING):
        read_session(clip)
    line = next(r.getMessage() for r in caplog.records if "fGyroscope.csv" in r.getMessage())
    assert "% of its moving samples (|w| >= 0.8 rad/s) are at full scale" in line
    assert "+-1000 deg/s or more for a foot" in line and "decision L525" in line and "B401" in line
