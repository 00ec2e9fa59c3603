"""Decision L484 (trial T2 findings 7 and 9): summary.json's distance by travel direction, periods.csv's backward and
side strides, and the console line naming them."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import TRAVEL_DISTANCE_KEYS, backward_travel
from pdrlearn.track.gait import sideways_rows
from pdrlearn.track.travel import travel_line

ROUTE = "stand:2, straight:3, stand:2, backward:2, stand:2, side:1.5, stand:2, straight:3, stand:2"


@pytest.fixture(scope="module")
def tracked(tmp_path_factory):
    root = tmp_path_factory.mktemp("travel")
    assert main(["simulate", "--route", ROUTE, "--user-seed", "9558", "--rate", "100", "--out", str(root / "s")]) == 0
    return root


def test_the_distance_splits_by_travel_direction_and_periods_count_the_strides(tracked, capsys):
    out = tracked / "t"
    assert main(["track", "--no-plot", str(tracked / "s"), "--out", str(out), "--per", "10s"]) == 0
    printed = capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    steps = pd.read_csv(out / "steps.csv")
    back = steps["backward_travel"].to_numpy(bool)
    side = sideways_rows(steps)
    assert summary["n_backward_strides"] >= 1 and summary["n_side_strides"] >= 1  # the route's backward and side
    length = steps["length_m"].abs().to_numpy(float)
    assert summary["backward_distance_m"] == pytest.approx(length[back].sum(), abs=1e-6)
    assert summary["side_distance_m"] == pytest.approx(length[side].sum(), abs=1e-6)
    assert sum(summary[k] for k in TRAVEL_DISTANCE_KEYS) == pytest.approx(summary["distance_m"], abs=1e-6)
    assert summary["side_distance_m"] == pytest.approx(1.5, abs=0.3)  # the route's 1.5 m side step
    periods = pd.read_csv(out / "periods.csv")
    assert len(periods) > 1
    assert int(periods["n_backward_strides"].sum()) == summary["n_backward_strides"]
    assert int(periods["n_side_strides"].sum()) == summary["n_side_strides"]
    line = travel_line(summary)
    assert line in printed  # the console names the counts (was: only the changes of direction)
    assert f"{summary['n_backward_strides']} backward and {summary['n_side_strides']} side stride(s)" in line
    assert f"{summary['side_distance_m']:.2f} m sideways" in line


def test_a_lower_back_track_has_no_split(tracked):
    out = tracked / "w"
    assert main(["track", "--no-plot", str(tracked / "s"), "--out", str(out), "--units", "waist", "--per", "10s"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert all(summary[k] is None for k in TRAVEL_DISTANCE_KEYS)
    periods = pd.read_csv(out / "periods.csv")
    assert periods["n_backward_strides"].isna().all() and periods["n_side_strides"].isna().all()


def test_the_line_counts_backward_strides_without_a_change_of_direction():
    summary = {"n_backward_strides": 3, "n_side_strides": 0, "direction_changes": 0, "backward_distance_m": 1.5,
               "side_distance_m": 0.0, "distance_m": 1.5}
    assert travel_line(summary).startswith("3 backward and 0 side stride(s) (1.50 m backward, 0.00 m sideways of")
    assert travel_line({"n_backward_strides": None, "n_side_strides": None, "direction_changes": None}) is None
    assert backward_travel(pd.DataFrame({"length_m": np.ones(2), "unit": "waist"})) is None  # lower back: no facing
