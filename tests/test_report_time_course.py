"""Decision L386 (session 33, trial T4 finding 8): `pdrlearn report` shows a track's time course - periods.csv,
laps.csv and the rests between bouts.csv's walking bouts - when the files exist, and nothing when they do not."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.report.time_course import rest_table


def _track(folder, *, periods=True, laps=True, rest=True):
    folder.mkdir(parents=True)
    (folder / "summary.json").write_text(json.dumps({"session": folder.name, "pipeline": "plasys",
                                                     "distance_m": 150.0, "n_steps": 100}))
    pd.DataFrame({"bout": [1, 2], "start_s": [0.0, 90.0 if rest else 60.5],
                  "end_s": [60.0, 150.0]}).to_csv(folder / "bouts.csv", index=False)
    if periods:
        pd.DataFrame({"period": [1, 2, 3], "start_s": [0.0, 60.0, 120.0], "end_s": [60.0, 120.0, 150.0],
                      "duration_s": [60.0, 60.0, 30.0], "partial": [False, False, True],
                      "distance_m": [72.5, 31.25, 36.0], "median_cadence_spm": [110.0, 104.0, 108.0]}
                     ).to_csv(folder / "periods.csv", index=False)
    if laps:
        pd.DataFrame({"lap": [1, 2], "start_s": [0.0, 61.0], "end_s": [61.0, 150.0], "duration_s": [61.0, 89.0],
                      "corridor_laps": [1, 0], "distance_m": [30.0, 17.5], "distance_source": ["corridor", "tracked"],
                      "speed_mps": [0.49, 0.2], "rest_s": [0.0, 30.0], "n_steps": [50, 40]}
                     ).to_csv(folder / "laps.csv", index=False)


def test_report_shows_periods_laps_and_rests_with_a_figure(tmp_path):
    _track(tmp_path / "runs" / "walk_a")
    assert main(["report", str(tmp_path / "runs"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    section = md[md.index("## Time course — walk_a"):]
    assert "per period (periods.csv)" in section and "per lap (laps.csv)" in section
    assert "rests between walking bouts (bouts.csv)" in section
    assert "1.208" in section  # period 1's speed: 72.5 m / 60 s
    assert "speed_mps" in section and "speed_m_s" not in section  # E98's name in both tables (session 33 NU 1)
    assert "time_course_walk_a.png" in section and list((tmp_path / "rep" / "img").glob("*time_course*"))
    assert "Time course" in (tmp_path / "rep" / "index.html").read_text()


def test_report_has_no_time_course_without_the_files(tmp_path):
    _track(tmp_path / "runs" / "walk_b", periods=False, laps=False, rest=False)
    assert main(["report", str(tmp_path / "runs"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "Time course" not in md and "## Tracking" in md
    assert not list((tmp_path / "rep" / "img").glob("*time_course*"))


def test_rest_table_is_the_gaps_between_bouts():
    bouts = pd.DataFrame({"start_s": [0.0, 90.0, 150.5], "end_s": [60.0, 150.0, 200.0]})
    rests = rest_table(bouts)
    assert list(rests["start_s"]) == [60.0] and list(rests["duration_s"]) == [30.0]  # the 0.5 s gap is no rest
    assert rest_table(bouts.iloc[:1]) is None


def test_report_shows_each_tracks_walk_tests_e152(tmp_path):
    """E152: the corridor test's keys (a list per minute too), the T25FW's and the 10 m walk's show in a walk-test
    table with a row per track; a track without them gets an empty row, not no table."""
    _track(tmp_path / "runs" / "walk_a")
    s = json.loads((tmp_path / "runs" / "walk_a" / "summary.json").read_text())
    s.update({"corridor_m": 30.0, "n_laps": 9, "walk_test_distance_m": 299.8,
              "walk_test_distance_per_minute_m": [58.25, 50.0], "fatigue_index": 0.858,
              "t25fw_time_s": 6.125, "t25fw_speed_mps": 1.244, "ten_m_walk_time_s": None,
              "ten_m_walk_note": "no straight 12 m"})
    (tmp_path / "runs" / "walk_a" / "summary.json").write_text(json.dumps(s))
    _track(tmp_path / "runs" / "walk_b", periods=False, laps=False, rest=False)
    assert main(["report", str(tmp_path / "runs"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    table = md[md.index("walk tests:"):]
    table = table[:table.index("\n\n", table.index("|"))]
    assert "walk_test_distance_m" in table and "299.8" in table and "58.2 / 50.0" in table
    assert "fatigue_index" in table and "0.858" in table and "6.125" in table and "no straight 12 m" in table
    assert "walk_a" in table and "walk_b" in table
    assert "fatigue_index" in (tmp_path / "rep" / "index.html").read_text()
