"""Decision L450 (session 36, trial T2 finding 7): bouts.csv gives the floors climbed per bout (``floors_up`` /
``floors_down``) by the summary's floor logic: a bout up a flight and back down reads 1 / 1, not its 0 m altitude
change; the bouts sum to the summary's floors."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cli import main


def test_bouts_csv_counts_the_floors_of_each_bout_l450(tmp_path):
    sim, out = tmp_path / "s", tmp_path / "t"
    assert main(["simulate", "--route", "stand:3, straight:20, stand:10, straight:5, up:17, turn:180, down:17, "
                 "stand:10, straight:20, stand:3", "-u", "8908", "-o", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    bouts = pd.read_csv(out / "bouts.csv")
    assert summary["floors_up"] == 1 and summary["floors_down"] == 1, (summary["floors_up"], summary["floors_down"])
    assert bouts["floors_up"].sum() == 1 and bouts["floors_down"].sum() == 1
    stairs = bouts[bouts["floors_up"] > 0]
    assert len(stairs) == 1 and int(stairs["floors_down"].iloc[0]) == 1  # up and back down in one bout
    assert abs(float(stairs["altitude_change_m"].iloc[0])) < 1.0  # what the trial had to go on
    assert (bouts.drop(stairs.index)[["floors_up", "floors_down"]] == 0).all().all()
