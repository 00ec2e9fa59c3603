"""Decision L224 (session 28 navigation trial, finding 10): steps.csv's ``direction`` (the model's class) had 17
``backward`` rows where summary.json's ``n_backward_strides`` (L203) said 8: the pivot strides of right turns were
classed backward. ``direction`` keeps the class; steps.csv's ``backward_travel`` marks the rows the count counts."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main

MODEL = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
#: right turns on the spot, then 3 m backward
ROUTE = "stand:2, straight:8, turn:-90, straight:6, turn:-90, straight:6, turn:90, straight:4, backward:3, stand:2"


def test_steps_csv_marks_the_strides_the_backward_count_counts(tmp_path, capsys):
    sim = tmp_path / "s"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "20", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", str(MODEL), str(sim), "--out", str(tmp_path / "r"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    steps = pd.read_csv(tmp_path / "r" / "steps.csv")
    cols = list(steps.columns)
    assert cols[cols.index("direction") + 1] == "backward_travel"
    classed = steps["direction"].eq("backward").to_numpy()
    travel = steps["backward_travel"].to_numpy(bool)
    assert int(travel.sum()) == summary["n_backward_strides"] >= 1
    assert classed.sum() > travel.sum()  # the pivot strides: classed backward, not counted
    turn = np.degrees(np.abs(steps["turn_angle_rad"].to_numpy(float)))
    assert (turn[classed & ~travel] >= 30).all()  # L203's rule is the only difference
    assert not (travel & ~classed).any()  # a replay counts the strides its model classes backward (L203 amended)


def test_an_offline_model_free_table_has_the_column(tmp_path, capsys):
    sim = tmp_path / "s"
    assert main(["simulate", "--route", "stand:3, straight:6, backward:5, stand:3", "--user-seed", "14",
                 "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--out", str(tmp_path / "t"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    assert int(steps["backward_travel"].sum()) == summary["n_backward_strides"] >= 1
    assert steps["direction"].isna().all()  # no model: no class, the column still says which strides


def test_a_lower_back_table_has_no_column(tmp_path, capsys):
    sim = tmp_path / "w"
    assert main(["simulate", "--scenario", "A", "--user-seed", "3561", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--pipeline", "waist-pendulum", "--out", str(tmp_path / "tw")]) == 0
    assert "backward_travel" not in pd.read_csv(tmp_path / "tw" / "steps.csv")


def test_one_backward_rule_for_the_tracks_and_the_lean_runtime():
    """L203 / L224: the lean runtime's steps.csv marks backward travel with the tracks' own kernel; its turn bound is
    L119's pause turn cue."""
    from pdrlearn.kernels.backward import BACKWARD_MAX_TURN_DEG, backward_mask, is_backward
    from pdrlearn.track.clinical import PAUSE_MAX_TURN_DEG

    assert BACKWARD_MAX_TURN_DEG == PAUSE_MAX_TURN_DEG
    mask = backward_mask([-0.5, -0.5, -0.5, -0.5, 0.5], [0.0, 2.0, 0.0, 0.0, 0.0], [False, False, True, False, False],
                         [0.1, 0.0, 0.0, 0.6, 0.0])
    assert mask.tolist() == [True, False, False, False, False]
    assert is_backward({"length_m": -0.4, "turn_angle_rad": 0.2, "gap_s": 0.0, "impossible": False})
    assert not is_backward({"length_m": -0.4, "turn_angle_rad": 0.6})  # 34 deg: a turn
    assert not is_backward({"length_m": 0.4, "turn_angle_rad": None})
