"""Trial T3 (session 39) finding 7, decision L514: periods.csv gives each period's start / end position and net
displacement (user 10033, fixer FB's fresh-test range)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.periods import POSITION_KEYS, period_displacement


def test_period_displacement_reads_the_position_after_the_last_counted_step_l528():
    traj = pd.DataFrame({"t": [1.0, 2.0, 3.0, 4.0], "x": [0.0, 1.0, 2.0, 2.5], "y": [0.0, 0.0, 1.0, 1.0]})
    start, end = np.array([1.0, 2.0, 3.0]), np.array([2.0, 3.0, 4.0])  # steps whose middles are 1.5, 2.5, 3.5
    # [0, 3): the steps of middle 1.5 and 2.5, from the first step's start to the second's end (not the row at 3.0 s)
    assert period_displacement(traj, start, end, 0.0, 3.0) == {"start_x_m": 0.0, "start_y_m": 0.0, "end_x_m": 2.0,
                                                              "end_y_m": 1.0, "dx_m": 2.0, "dy_m": 1.0}
    assert period_displacement(traj, start, end, 3.0, 9.0, last=True)["dx_m"] == 0.5
    assert period_displacement(traj, start, end, 5.0, 9.0, last=True)["dx_m"] == 0.0  # no step: no displacement
    assert period_displacement(traj.iloc[:0], start, end, 0.0, 1.0) == dict.fromkeys(POSITION_KEYS)


def test_periods_csv_gives_each_shuffle_legs_net_displacement_l514(tmp_path):
    sim, out = tmp_path / "sh", tmp_path / "sh_tr"
    assert main(["simulate", "--route", "stand:2, side:3, side:-3, stand:2", "--user-seed", "10033",
                 "--out", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--per", "10s", "--out", str(out)]) == 0
    per = pd.read_csv(out / "periods.csv")
    assert set(POSITION_KEYS) <= set(per.columns)
    # consecutive periods join, and the net displacements add up to the track's final position
    assert np.allclose(per["end_x_m"].to_numpy()[:-1], per["start_x_m"].to_numpy()[1:])
    assert np.allclose(per["dx_m"], per["end_x_m"] - per["start_x_m"])
    final = json.loads((out / "summary.json").read_text())["final_position"]
    assert abs(per["dx_m"].sum() - final["x"]) < 1e-6 and abs(per["dy_m"].sum() - final["y"]) < 1e-6
    # the shuffle out and back: a period goes one way by over 1 m and a later one comes back, though distance_m adds
    d = np.hypot(per["dx_m"], per["dy_m"])
    assert d.max() > 1.0 and per["distance_m"].sum() > 5.0 and np.hypot(final["x"], final["y"]) < 0.5, per
