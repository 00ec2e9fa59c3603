"""Session 39 review R2 findings on `report --clinical` (decisions W426, L531, W427): patients grouped by folder when
no subject is recorded, the 10 m walk's timed zone and trials, a summary.json that is not an object."""

from __future__ import annotations

import json

from pdrlearn.cli import main
from pdrlearn.report.clinical import clinical_markdown


def _summary(folder, **extra):
    folder.mkdir(parents=True)
    data = {"pipeline": "plasys", "session": folder.name, "gait_speed_mps": 1.2, **extra}
    (folder / "summary.json").write_text(json.dumps(data))


def test_two_patients_with_same_session_folder_name_stay_apart_w426(tmp_path):
    _summary(tmp_path / "out" / "patientA" / "tug")
    _summary(tmp_path / "out" / "patientB" / "tug")
    text = clinical_markdown(tmp_path / "out")
    assert text.count("## Patient ") == 2, text
    assert "## Patient patientA/tug (no subject in meta.json)" in text
    assert "Session tug (patientA/tug), " in text and "Session tug (patientB/tug), " in text


def test_a_subject_still_groups_its_sessions_w426(tmp_path):
    _summary(tmp_path / "out" / "a" / "tug", subject="P7")
    _summary(tmp_path / "out" / "b" / "walk", subject="P7")
    text = clinical_markdown(tmp_path / "out")
    assert text.count("## Patient ") == 1 and "## Patient P7" in text
    assert "Session tug (a/tug), " in text and "Session walk (b/walk), " in text


def test_clinical_on_a_summary_that_is_not_an_object_is_one_line(tmp_path, capsys):
    _summary(tmp_path / "multi" / "ok")
    (tmp_path / "multi" / "d").mkdir()
    (tmp_path / "multi" / "d" / "summary.json").write_text("[]")
    assert main(["report", str(tmp_path / "multi"), "--out", str(tmp_path / "rep"), "--clinical"]) == 2
    err = capsys.readouterr().err
    assert "must hold a JSON object, not list" in err and "Traceback" not in err, err
    assert not (tmp_path / "rep").exists()


WALK_262 = {"ten_m_walk_time_s": 3.676, "ten_m_walk_speed_mps": 1.632, "n_ten_m_walk_trials": 2,
            "ten_m_walk_max_speed_mps": 1.6398, "ten_m_walk_zones_m": [2.0, 6.0, 2.0]}


def test_clinical_ten_m_walk_names_its_timed_metres_and_trials_l531(tmp_path):
    _summary(tmp_path / "out" / "p" / "walk", subject="P1", **WALK_262)
    _summary(tmp_path / "out" / "p" / "plain", subject="P1", ten_m_walk_time_s=7.0, ten_m_walk_speed_mps=1.43,
             n_ten_m_walk_trials=1, ten_m_walk_max_speed_mps=1.43)
    lines = [x for x in clinical_markdown(tmp_path / "out").splitlines() if x.startswith("- 10 m walk")]
    assert lines == ["- 10 m walk: 1.43 m/s (7.0 s over the middle 10 m of a 14 m walkway; foot unit)",
                     "- 10 m walk: 1.63 m/s (3.7 s over the middle 6 m of a 10 m walkway; 2 trials, fastest "
                     "1.64 m/s; foot unit)"], lines


def test_report_walk_table_shows_the_walkway_and_trials_l531(tmp_path):
    _summary(tmp_path / "out" / "walk", **WALK_262)
    assert main(["report", str(tmp_path / "out"), "--out", str(tmp_path / "rep")]) == 0
    text = (tmp_path / "rep" / "report.md").read_text()
    head = next(x for x in text.splitlines() if "ten_m_walk_time_s" in x and x.startswith("|"))
    for col in ("n_ten_m_walk_trials", "ten_m_walk_max_speed_mps", "ten_m_walk_zones_m"):
        assert col in head, head
    assert "2 / 6 / 2" in text


def test_ten_m_walk_speed_column_text_is_not_a_fixed_10_m_l531():
    from pdrlearn.columns import markdown

    row = next(x for x in markdown().splitlines() if x.startswith("| `ten_m_walk_speed_mps`"))
    assert "10 m / ten_m_walk_time_s" not in row and "ten_m_walk_zones_m" in row, row
