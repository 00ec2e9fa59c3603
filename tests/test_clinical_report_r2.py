"""Session 39 review R2 findings on `report --clinical` (decisions W426, L531, W427): patients grouped by folder when
no subject is recorded, the 10 m walk's timed zone and trials, a summary.json that is not an object."""

from __future__ import annotations

import json

import pandas as pd

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


class _Session:
    where = "DIR"

    def has(self, *names):
        return True


class _Result:
    def __init__(self, info=None):
        self.info = dict(info or {})
        self.steps = pd.DataFrame({"start_s": [1.0], "end_s": [2.0], "event_s": [1.5]})


def test_a_dead_waist_unit_that_reads_no_transfers_leaves_a_note_w427(monkeypatch):
    from pdrlearn.track import units, waist
    from pdrlearn.track.trunk_tug import add_trunk_transfers, trunk_note

    def dead(session):  # the inner waist work of a frozen wAccelerometer (W428): it runs, and reads no transfers
        return _Result({"transfers": None, "yaw_turns": None})

    monkeypatch.setattr(waist, "trunk_events", dead)
    monkeypatch.setattr(units, "keep_units", lambda session, kept: session)
    result = _Result()
    add_trunk_transfers(result, _Session())
    note = trunk_note(result)
    assert note is not None and note.startswith("no chair transfers from the lower-back unit (its track read none")
    assert "pdrlearn track DIR --units waist" in note


def test_a_walk_without_a_tug_names_no_tug_source_w427():
    from pdrlearn.track.trunk_tug import tug_source_summary

    result = _Result({"transfers": pd.DataFrame(), "trunk_contacts": []})
    assert tug_source_summary(result, {"n_tug_trials": 0, "tug_time_s": None}) == {
        "tug_steps_source": None, "tug_turns_source": None}
    assert tug_source_summary(result, {"n_tug_trials": 1, "tug_time_s": 9.5})["tug_steps_source"] == "foot"


def test_two_unit_posture_line_says_the_track_reads_the_waist_for_the_tug_w427():
    from pdrlearn.cli.common import posture_line

    line = posture_line({"standing_time_s": None}, waist_unit=True)
    # W586: a two-unit track has the split from the unit's postures; without them (the unit read none) it says so
    assert "this track's reading of that unit gave no posture runs (W418, W586" in line
    assert "track it for the split" not in line
