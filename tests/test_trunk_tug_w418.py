"""Decisions W418 / W419: the default track of a foot + waist TUG session times the TUG from the waist unit it has
(transfers.csv, tug_phases.csv, tug_trials.csv, ``tug_time_s`` as ``--units waist`` gives them) and counts the TUG's
steps and times its turns on the foot, naming each source."""

from __future__ import annotations

import dataclasses
import json

import pandas as pd
import pytest

from pdrlearn import write_session
from pdrlearn.cli import main
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.tug_truth import true_tug_phases
from pdrlearn.sim.user import SPEED_FACTORS, UserProfile
from pdrlearn.track.trunk_tug import foot_step_count

ROUTE = "straight:3, turn:180, straight:3, turn:180"  # trial T1's TUG (mk_tug.py)


@pytest.fixture(scope="module")
def tug(tmp_path_factory):
    """A slow two-unit TUG (user 10070, 0.75 m/s) tracked by default and with --units waist."""
    root = tmp_path_factory.mktemp("w418")
    fl, ft = SPEED_FACTORS["slow"]
    u = dataclasses.replace(UserProfile.from_seed(10070), step_length_m=0.45 / fl, step_time_s=0.6 / ft)
    s = simulate_path(parse_route(ROUTE), u, speed="slow", rate_hz=100, seed=0, scenario="route", sit_start_s=3,
                      sit_end_s=3, stand_s=0.5, bounce="pendulum")
    write_session(s, root / "tug")
    tr = s.extras["transfers"]
    t0, t1 = float(tr.iloc[0]["rise_s"]), float(tr.iloc[-1]["seated_s"])
    ics = pd.read_csv(root / "tug" / "ics.csv")["ic_ms"].to_numpy(float) / 1000.0
    truth = {"n_steps": int(((ics >= t0) & (ics <= t1)).sum()), **true_tug_phases(s, ROUTE)}
    assert main(["track", "--no-plot", str(root / "tug"), "--out", str(root / "both")]) == 0
    assert main(["track", "--no-plot", str(root / "tug"), "--units", "waist", "--out", str(root / "waist")]) == 0
    return root, truth


def test_default_two_unit_track_times_the_tug_from_the_waist_w418(tug):
    root, _ = tug
    both = json.loads((root / "both" / "summary.json").read_text())
    waist = json.loads((root / "waist" / "summary.json").read_text())
    assert both["pipeline"] == "plasys"  # still the foot track
    assert both["tug_time_s"] is not None and both["tug_time_s"] == pytest.approx(waist["tug_time_s"])
    for name in ("transfers.csv", "tug_phases.csv", "tug_trials.csv"):
        assert (root / "both" / name).is_file(), name
    pd.testing.assert_frame_equal(pd.read_csv(root / "both" / "transfers.csv"),
                                  pd.read_csv(root / "waist" / "transfers.csv"))
    assert both["n_sit_to_stand"] == 1 and both["n_stand_to_sit"] == 1
    assert "trunk_contacts" not in both["info"] and "trunk_yaw_turns" not in both["info"]


def test_two_unit_tug_counts_steps_and_turns_on_the_foot_w419(tug):
    root, truth = tug
    both = pd.read_csv(root / "both" / "tug_trials.csv").iloc[0]
    waist = pd.read_csv(root / "waist" / "tug_trials.csv").iloc[0]
    assert (both["steps_source"], both["turns_source"]) == ("foot", "foot")
    assert (waist["steps_source"], waist["turns_source"]) == ("waist", "waist")
    assert both["n_steps"] == truth["n_steps"]  # the waist misses the turns' steps (W331)
    assert abs(both["n_steps"] - truth["n_steps"]) < abs(waist["n_steps"] - truth["n_steps"])
    for key, phase in (("tug_turn_s", "turn"), ("tug_turn_to_sit_s", "turn_to_sit")):
        assert abs(both[key] - truth[phase]["duration_s"]) < 0.3, key
        assert abs(both[key] - truth[phase]["duration_s"]) < abs(waist[key] - truth[phase]["duration_s"]), key
    summary = json.loads((root / "both" / "summary.json").read_text())
    assert (summary["tug_steps_source"], summary["tug_turns_source"]) == ("foot", "foot")


def test_foot_units_only_track_has_no_transfers(tug, tmp_path):
    root, _ = tug
    assert main(["track", "--no-plot", str(root / "tug"), "--units", "foot", "--out", str(tmp_path / "f")]) == 0
    summary = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert summary["tug_time_s"] is None and summary["tug_steps_source"] is None
    assert not (tmp_path / "f" / "transfers.csv").exists()


def test_foot_step_count_is_twice_the_strides_inside():
    strides = pd.DataFrame({"start_s": [1.0, 2.0, 3.0, 4.0], "event_s": [1.5, 2.5, 3.5, 4.5]})
    assert foot_step_count(strides, 2.0, 4.0) == 4 and foot_step_count(strides, 0.0, 1.0) == 0
    assert foot_step_count(strides.iloc[:0], 0.0, 9.0) == 0


def test_an_untrackable_waist_unit_leaves_a_note_naming_the_command(monkeypatch):
    from pdrlearn.errors import DataError
    from pdrlearn.track import units, waist
    from pdrlearn.track.trunk_tug import add_trunk_transfers, trunk_note

    def refuse(session):  # W428: the inner waist work is trunk_events
        raise DataError("meta.json: no frame for the waist unit")

    class Session:
        where = "DIR"

        def has(self, *names):
            return True

    class Result:
        info: dict = {}
        steps = pd.DataFrame()

    monkeypatch.setattr(waist, "trunk_events", refuse)
    monkeypatch.setattr(units, "keep_units", lambda session, kept: session)
    result = Result()
    result.info = {}
    add_trunk_transfers(result, Session())
    assert "transfers" not in result.info
    assert trunk_note(result).startswith("no chair transfers from the lower-back unit (meta.json: no frame")
    assert "pdrlearn track DIR --units waist" in trunk_note(result)


@pytest.fixture(scope="module")
def patient(tug, tmp_path_factory):
    """Decision W420: a patient's folder holding the TUG's default track and a 15 m walk's (user 10071, with a
    recording_start in meta.json)."""
    root, _ = tug
    work = tmp_path_factory.mktemp("w420")
    assert main(["simulate", "--route", "stand:3, straight:15, stand:3", "-u", "10071", "--rate", "100",
                 "--out", str(work / "walk")]) == 0
    meta = json.loads((work / "walk" / "meta.json").read_text())
    meta["recording_start"] = "2026-11-30T09:15:00+01:00"
    (work / "walk" / "meta.json").write_text(json.dumps(meta))
    (work / "patient").mkdir()
    assert main(["track", str(root / "tug"), "--out", str(work / "patient" / "tug")]) == 0
    assert main(["track", str(work / "walk"), "--out", str(work / "patient" / "walk")]) == 0
    return work


def test_report_clinical_writes_a_short_summary_per_patient_w420(patient):
    work = patient
    assert main(["report", str(work / "patient"), "--out", str(work / "rep"), "--clinical"]) == 0
    text = (work / "rep" / "clinical.md").read_text()
    assert (work / "rep" / "report.md").is_file()  # the research report as before
    tug = json.loads((work / "patient" / "tug" / "summary.json").read_text())
    walk = json.loads((work / "patient" / "walk" / "summary.json").read_text())
    assert f"## Patient {tug['subject']}" in text and f"## Patient {walk['subject']}" in text
    assert f"Session {walk['session']} (walk), recorded 2026-11-30:" in text
    assert "recording date unknown (no meta.json recording_start)" in text  # the TUG session has none
    n_steps = int(pd.read_csv(work / "patient" / "tug" / "tug_trials.csv")["n_steps"].iloc[0])
    line = next(x for x in text.splitlines() if x.startswith("- TUG: "))
    assert line.startswith(f"- TUG: {tug['tug_time_s']:.1f} s (sit-to-stand ")
    assert f"; {n_steps} steps (foot unit); turn {tug['tug_turn_s']:.1f} s (foot unit)" in line
    assert line.endswith("chair transfers: lower-back unit")
    assert f"- 10 m walk: {walk['ten_m_walk_speed_mps']:.2f} m/s" in text
    assert f"- Gait speed {walk['gait_speed_mps']:.2f} m/s, cadence" in text
    # C209 (session 49): each track warning's own text (its fix and its decision) is given; C273 (session 53): once,
    # in the page's technical notes; W420's rule - no research terms - holds for the clinical lines themselves, their
    # sub-lines (pace, rests) too
    clinical = clinical_lines(text)
    assert any(x.startswith("- E153: ") and ": no model" in x for x in text.splitlines())
    assert "- Track warnings: " in clinical and "  - E153: no model" not in clinical
    for research in ("error", "MAE", "no model", "decision"):
        assert research not in clinical, research


def clinical_lines(text: str) -> str:
    """clinical.md less C209's warning items (the indented lines right under a "- Track warnings:" line): the lines
    W420's no-research-terms rule reads (review R1 F5 of session 50: the pace and rests sub-lines stay in)."""
    kept, in_warnings, in_notes = [], False, False
    for x in text.splitlines():
        in_notes = x.startswith("Technical notes (") or (in_notes and x.startswith("- "))  # decision C273
        if in_notes:
            continue
        in_warnings = x.startswith("- Track warnings:") or (in_warnings and x.startswith("  - "))
        if not (in_warnings and x.startswith("  - ")):
            kept.append(x)
    return "\n".join(kept)


def test_only_the_warning_items_are_left_out_of_w420s_check():
    text = ("- 6MWT: 420 m\n  - test speed 1.17 m/s; a decision\n- Track warnings: 1 (E153), what each means:\n"
            "  - E153: no model (decision E153)\n- Gait speed 1.10 m/s\n  - Rests during the test: 1 error")
    got = clinical_lines(text)
    assert got == ("- 6MWT: 420 m\n  - test speed 1.17 m/s; a decision\n- Track warnings: 1 (E153), what each "
                   "means:\n- Gait speed 1.10 m/s\n  - Rests during the test: 1 error")


def test_report_clinical_without_a_track_is_one_line(tmp_path, capsys):
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "x.png").write_bytes(b"")
    assert main(["report", str(tmp_path / "empty"), "--out", str(tmp_path / "rep"), "--clinical"]) == 2
    err = capsys.readouterr().err
    assert "--clinical reads track outputs (summary.json" in err and "Traceback" not in err
    assert not (tmp_path / "rep").exists()
