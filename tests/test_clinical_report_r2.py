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
