"""Decision L222 (session 28 navigation trial, finding 3): a streamed foot track (``pdrlearn run``, ``track
--streaming``) has no initial contact, so no cadence or per-stride speed; on a walk with stairs L179 then judged no
speed either and ``gait_out_of_range`` read false (no warning) for a 0.35 m/s walk. Now the streamed strides' speed
comes from their gait cycle (start to the next start) and an unjudged range is null."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import add_gait_range_flag
from pdrlearn.track.gait import cycle_speeds

#: the trial's g_slow70 route, shortened: stairs up and a landing turn, then level straight walking
MODEL = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
SLOW = "stand:3, straight:10, up:17, turn:180, up:17, turn:90, straight:10, turn:180, straight:10, stand:3"


def test_cycle_speed_is_length_over_start_to_start():
    t = pd.DataFrame({"start_s": [0.0, 1.7, 3.4, 10.0, 11.7], "end_s": [1.2, 2.9, 4.6, 11.2, 12.9],
                      "length_m": [0.7, 0.7, -0.7, 0.7, 0.7], "gap_s": [0.0, 0.0, 0.0, 0.0, 0.0],
                      "unit": ["foot"] * 5})
    v = cycle_speeds(t)
    np.testing.assert_allclose(v[:2], [0.7 / 1.7, 0.7 / 1.7])
    assert np.isnan(v[2]) and np.isnan(v[4])  # a stop (6.6 s, over MAX_STRIDE_S) and the last stride
    np.testing.assert_allclose(v[3], 0.7 / 1.7)
    t.loc[1, "gap_s"] = 2.0  # a gap row is no stride: neither it nor the stride before it has a cycle
    assert np.isnan(cycle_speeds(t)[:2]).all()


def test_an_unjudged_range_is_null_not_false():
    assert add_gait_range_flag({"median_cadence_spm": None, "gait_speed_mps": None})["gait_out_of_range"] is None
    assert add_gait_range_flag({"median_cadence_spm": 110.0})["gait_out_of_range"] is False
    assert add_gait_range_flag({"median_cadence_spm": None, "n_bouts_out_of_range": 1})["gait_out_of_range"] is True


@pytest.mark.parametrize("command", ["run", "streaming"])
def test_a_slow_streamed_walk_with_stairs_warns(tmp_path, capsys, command):
    """0.35 m steps every 0.85 s (0.41 m/s): offline warned, the streamed track said false with no line."""
    sim = tmp_path / "slow"
    assert main(["simulate", "--route", SLOW, "--user-seed", "4109", "--step-length", "0.35", "--step-time", "0.85",
                 "--out", str(sim)]) == 0
    capsys.readouterr()
    args = (["run", "--no-plot", str(MODEL), str(sim)] if command == "run"
            else ["track", "--no-plot", str(sim), "--streaming"])
    assert main([*args, "--out", str(tmp_path / "o"), "--json"]) == 0
    out, err = capsys.readouterr()
    s = json.loads(out)
    assert s["median_cadence_spm"] is None and s["n_stair_strides"] >= 5  # L179 would judge no speed
    assert s["gait_out_of_range"] is True, s
    assert 0.3 < s["median_speed_straight_mps"] < 0.5 and s["n_straight_strides"] >= 5
    assert "straight-walking speed" in err and "slower than the walking" in err and "(decision L95)" in err


def test_a_normal_streamed_walk_is_judged_inside(tmp_path, capsys):
    sim = tmp_path / "a"
    assert main(["simulate", "--scenario", "A", "--user-seed", "4109", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", str(MODEL), str(sim), "--out", str(tmp_path / "o"), "--json"]) == 0
    out, err = capsys.readouterr()
    s = json.loads(out)
    assert s["gait_out_of_range"] is False and "(decision L95)" not in err
    assert 0.8 < s["median_speed_straight_mps"] < 1.8
