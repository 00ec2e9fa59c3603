"""Decisions L568-L572 (trial s41 T3, findings F4, F6, F7: an accessibility route audit): ramp_runs.csv, ramps.csv's
compliance flags and end positions, stairs.csv's end positions, the ramps and flights on the map (GeoJSON features,
GPX waypoints), the ramps console line, the report's ramps / stairs / climb section, the ten-m-walk note naming a
ramp, and track-all's pooled ramps.csv and max_ramp_grade_pct."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.geoexport import GPX_NS, write_geo_files
from pdrlearn.track.grade import ramp_table
from pdrlearn.track.ramp_audit import compliance_flags, ramp_run_table, ramps_line, route_features

#: a 1:12 run of 7 m (rise 0.58 m), a 1.5 m landing, a steeper 12 m run (rise 1.00 m), as T3's three-run route
ROUTE = "stand:3, straight:3, slope:7:8.33, straight:1.5, slope:12:8.33, straight:5, stand:3"


def _steps(rows):
    """A fused foot track's steps (one row per stride of (length, dz)), 1 s per stride."""
    length, dz = (np.array(c, float) for c in zip(*rows, strict=True))
    t = np.arange(len(rows), dtype=float)
    return pd.DataFrame({"unit": "foot", "start_s": t, "end_s": t + 1.0, "length_m": length, "dz_m": dz})


FUSED = {"altitude_source": "fused"}


def test_compliance_flags_compare_the_grade_and_rise_with_the_ada_limits():
    assert compliance_flags(8.34, 0.5) == {"over_1_12": True, "over_1_20": True, "run_rise_over_0_76": False}
    assert compliance_flags(-8.33, -0.77) == {"over_1_12": False, "over_1_20": True, "run_rise_over_0_76": True}
    assert compliance_flags(5.0, 0.76) == {"over_1_12": False, "over_1_20": False, "run_rise_over_0_76": False}
    assert compliance_flags(float("nan"), None) == {"over_1_12": None, "over_1_20": None, "run_rise_over_0_76": None}


def test_ramp_runs_table_has_one_row_per_run_and_landing_with_flags_and_positions():
    run1, landing, run2 = [(1.25, 0.10)] * 4, [(1.5, 0.0)], [(1.25, 0.1125)] * 8  # 8.0 %, level, 9.0 % (rise 0.9 m)
    steps = _steps(run1 + landing + run2)
    traj = pd.DataFrame({"t": np.arange(14, dtype=float), "x": np.arange(14, dtype=float) * 2.0, "y": 1.0,
                         "lat": 41.0 + np.arange(14) * 1e-5, "lon": -8.0})
    runs = ramp_run_table(steps, FUSED, traj)
    assert list(runs["kind"]) == ["run", "landing", "run"] and list(runs["part"]) == [1, 2, 3]
    assert runs["ramp"].eq(1).all() and list(runs["n_steps"]) == [4, 1, 8]
    assert runs["horizontal_m"].tolist() == pytest.approx([5.0, 1.5, 10.0])
    assert runs["grade_pct"].tolist() == pytest.approx([8.0, 0.0, 9.0])
    assert runs["over_1_12"].tolist()[::2] == [False, True]
    assert runs["run_rise_over_0_76"].tolist()[::2] == [False, True]
    assert runs["over_1_12"].isna().iloc[1]  # a landing has no flag
    assert (runs["start_s"].tolist(), runs["end_s"].tolist()) == ([0.0, 4.0, 5.0], [4.0, 5.0, 13.0])
    assert runs["start_x_m"].tolist() == pytest.approx([0.0, 8.0, 10.0]) and runs["end_y_m"].eq(1.0).all()
    assert runs["end_lat"].iloc[-1] == pytest.approx(41.0 + 13e-5)
    ramps = ramp_table(steps, FUSED, traj)
    assert len(ramps) == 1 and ramps["max_run_rise_m"].iloc[0] == pytest.approx(0.9)
    assert (ramps["over_1_12"].iloc[0], ramps["over_1_20"].iloc[0], ramps["run_rise_over_0_76"].iloc[0]) \
        == (True, True, True)
    assert ramps["end_x_m"].iloc[0] == pytest.approx(26.0)
    # 9.0 % is within a point of 1:12 (decision L588)
    assert ramps_line(ramps) == ("ramps 1 (steepest 9.0 %, rise +1.30 m; 1 over 1:12; 1 near the limit: measure it; "
                                 "ramps.csv)")
    assert ramp_table(steps, {}, traj).empty and ramp_run_table(steps, {}, traj).empty  # no grade_source: none
    assert ramp_table(steps, FUSED)["start_lat"].isna().all()  # no trajectory: the position columns empty


def test_ramps_and_flights_are_geojson_features_and_gpx_waypoints(tmp_path):
    ramps = pd.DataFrame({"ramp": [1], "start_s": [1.0], "end_s": [3.0], "direction": ["up"],
                          "mean_grade_pct": [8.6], "max_run_grade_pct": [8.9], "rise_m": [1.2],
                          "horizontal_run_m": [14.0], "landings": [1], "over_1_12": [True], "over_1_20": [True],
                          "run_rise_over_0_76": [False]})
    stairs = pd.DataFrame({"flight": [1], "start_s": [4.0], "end_s": [5.0], "direction": ["down"],
                           "height_m": [-0.99], "n_strides": [3], "n_stairs": [np.nan]})
    traj = pd.DataFrame({"t": np.arange(7, dtype=float), "x": 0.0, "y": 0.0, "z": np.arange(7) * 0.1,
                         "lat": 41.0 + np.arange(7) * 1e-5, "lon": -8.0})
    feats = route_features({"ramps.csv": ramps, "stairs.csv": stairs})
    assert [f["name"] for f in feats] == ["ramp 1 up 8.6 %", "stairs 1 down -0.99 m"]
    write_geo_files(tmp_path, traj, session="s", pipeline="plasys", distance_m=1.0, with_ele=True, features=feats)
    doc = json.loads((tmp_path / "track.geojson").read_text())
    marks = [f for f in doc["features"] if f["properties"].get("kind")]
    assert [m["properties"]["kind"] for m in marks] == ["ramp", "stairs"]
    ramp = marks[0]
    assert ramp["geometry"]["type"] == "LineString" and len(ramp["geometry"]["coordinates"]) == 3  # t = 1, 2, 3
    assert ramp["geometry"]["coordinates"][0] == [-8.0, 41.00001, 0.1]
    assert (ramp["properties"]["grade_pct"], ramp["properties"]["over_1_12"], ramp["properties"]["direction"]) \
        == (8.6, True, "up")
    assert marks[1]["properties"]["n_stairs"] is None and marks[1]["properties"]["rise_m"] == -0.99
    wpts = ET.parse(tmp_path / "track.gpx").getroot().findall(f"{{{GPX_NS}}}wpt")
    assert [w.find(f"{{{GPX_NS}}}name").text for w in wpts] == ["ramp 1 up 8.6 %", "stairs 1 down -0.99 m"]
    assert [w.find(f"{{{GPX_NS}}}type").text for w in wpts] == ["ramp", "stairs"]
    assert wpts[0].get("lat") == "41.0000100" and wpts[0].find(f"{{{GPX_NS}}}ele").text == "0.10"


@pytest.fixture(scope="module")
def audit(tmp_path_factory):
    """One simulated route with two 1:12 runs (user 11460), tracked with --altitude fused and a geodetic start, then
    through track-all; the track's console text."""
    import io
    from contextlib import redirect_stdout

    d = tmp_path_factory.mktemp("audit")
    assert main(["simulate", "--route", ROUTE, "--user-seed", "11460", "--out", str(d / "root" / "s1")]) == 0
    buf = io.StringIO()
    with redirect_stdout(buf):
        code = main(["track", str(d / "root" / "s1"), "--altitude", "fused", "--start", "41.178,-8.598,100",
                     "--no-plot", "--out", str(d / "t")])
    assert code == 0
    return d, buf.getvalue()


def test_a_tracked_ramp_has_its_runs_flags_map_features_and_console_line(audit):
    d, text = audit
    ramps, runs = pd.read_csv(d / "t" / "ramps.csv"), pd.read_csv(d / "t" / "ramp_runs.csv")
    summary = json.loads((d / "t" / "summary.json").read_text())
    assert len(ramps) >= 1 and summary["n_ramps"] == len(ramps)
    assert summary["max_ramp_grade_pct"] == pytest.approx(ramps["max_run_grade_pct"].abs().max())
    assert set(runs["ramp"]) == set(ramps["ramp"]) and set(runs["kind"]) <= {"run", "landing"}
    assert ramps["start_lat"].notna().all() and runs["end_lon"].notna().all()
    assert {"over_1_12", "over_1_20", "run_rise_over_0_76"} <= set(ramps.columns)
    line = [s for s in text.splitlines() if s.startswith("ramps ")]
    assert len(line) == 1 and line[0].startswith(f"ramps {len(ramps)} (steepest ") and line[0].endswith("ramps.csv)")
    assert "ramp_runs.csv" in text
    doc = json.loads((d / "t" / "track.geojson").read_text())
    assert sum(f["properties"].get("kind") == "ramp" for f in doc["features"]) == len(ramps)
    note = summary["ten_m_walk_note"] or ""
    assert "ramp or stair stride(s)" in note and "ramps.csv" in note  # the ramp starts 3 m in (L571)


def test_report_lists_ramps_stairs_and_climb(audit, tmp_path):
    d, _ = audit
    assert main(["report", str(d / "t"), "--out", str(tmp_path / "r")]) == 0
    md = (tmp_path / "r" / "report.md").read_text()
    assert "## Ramps, stairs and climb" in md and "ramp_runs.csv" in md and "ascent_m" in md


def test_track_all_pools_the_ramps_and_writes_the_steepest_grade(audit, tmp_path):
    from pdrlearn.columns import undocumented

    d, _ = audit
    assert main(["track-all", str(d / "root"), "--altitude", "fused", "--out", str(tmp_path / "o")]) == 0
    pooled, own = pd.read_csv(tmp_path / "o" / "ramps.csv"), pd.read_csv(tmp_path / "o" / "s1" / "ramps.csv")
    assert list(pooled.columns[:2]) == ["path", "visit"] and len(pooled) == len(own) >= 1
    assert pooled["mean_grade_pct"].tolist() == pytest.approx(own["mean_grade_pct"].tolist())
    assert undocumented("ramps.csv", pooled.columns) == []
    assert undocumented("ramp_runs.csv", pd.read_csv(tmp_path / "o" / "s1" / "ramp_runs.csv").columns) == []
    assert undocumented("stairs.csv", pd.read_csv(tmp_path / "o" / "s1" / "stairs.csv").columns) == []
    sessions = pd.read_csv(tmp_path / "o" / "sessions.csv")
    assert sessions["max_ramp_grade_pct"].iloc[0] == pytest.approx(own["max_run_grade_pct"].abs().max())
