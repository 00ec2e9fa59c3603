"""Decision L582 (session 41, trial T1 finding F5): `report` and its clinical.md give the backward and side strides,
their distances, the bouts holding them (bouts.csv, L581) and the turns, when a track has any."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.report.travel import travel_lines, travel_table
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def test_clinical_and_report_name_backward_and_side_strides(tmp_path):
    s = simulate_path(parse_route("stand:2, straight:3, backward:4, stand:3, side:1.5, stand:3, backward:2, "
                                  "straight:3, stand:2"), UserProfile.from_seed(11526), rate_hz=100.0, seed=0,
                      scenario="route", speed="slow")
    write_session(s, tmp_path / "ex")
    assert main(["track", str(tmp_path / "ex"), "--out", str(tmp_path / "t")]) == 0
    assert main(["report", str(tmp_path / "t"), "--out", str(tmp_path / "r"), "--clinical"]) == 0
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    nb, ns = summary["n_backward_strides"], summary["n_side_strides"]
    assert nb > 0 and ns > 0
    text = (tmp_path / "r" / "clinical.md").read_text()
    assert (f"- Walking directions: {summary['distance_m']:.2f} m in all: "
            f"forward {summary['forward_distance_m']:.2f} m; "
            f"backward {nb} stride(s), {summary['backward_distance_m']:.2f} m; sideways {ns} stride(s), "
            f"{summary['side_distance_m']:.2f} m (strides of the foot unit: a step of each foot)") in text
    bouts = pd.read_csv(tmp_path / "t" / "bouts.csv")
    assert len(bouts) > 1 and "  bouts with backward / side strides: " in text
    side = bouts[bouts["direction"] == "side"].iloc[0]
    assert f"bout {side['bout']} side ({side['n_side_strides']} side stride(s) of {side['n_strides']}," in text
    report = (tmp_path / "r" / "report.md").read_text()
    assert "**distance by travel direction (strides of the tracked foot)**" in report
    assert "**walking bouts by travel direction (bouts.csv)**" in report


def test_a_forward_walk_adds_nothing_and_turns_get_a_line(tmp_path):
    forward = {"n_backward_strides": 0, "n_side_strides": 0, "turn_count": 0, "distance_m": 10.0}
    assert travel_lines(forward, tmp_path, "foot unit") == []
    assert travel_table(pd.DataFrame([{**forward, "run": "a"}])) is None
    turns = {**forward, "turn_count": 2, "median_turn_duration_s": 3.86, "turn_time_s": 7.71, "turn_count_min_deg": 80}
    assert travel_lines(turns, tmp_path, "foot unit") == [
        "- Turns of >= 80 deg: 2 (median 3.9 s, 7.7 s in all) (foot unit)"]
    # a lower-back summary: no stride counts (None), no line
    assert travel_lines({"n_backward_strides": None, "n_side_strides": None}, tmp_path, "lower-back unit") == []
    t = travel_table(pd.DataFrame([{**forward, "run": "a"}, {**forward, "run": "b", "n_side_strides": 3}]))
    assert t["run"].tolist() == ["b"]
