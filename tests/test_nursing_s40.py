"""Session 40, fixer FI (trial T2, nursing home, one lower-back unit): W445 (a seat-to-seat walk is a TUG trial
only when it looks like one), W446 (clinical.md's calibrated / uncalibrated gait speed and warnings), W447
(subjects.csv's gait speed is sessions.csv's), W448 (clinical.md's daily-living block; the time-course label)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.report.clinical import gait_speed_line, warnings_line
from pdrlearn.report.daily_living import daily_living_lines
from pdrlearn.visits import subject_totals
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT, TUG_MAX_S, transfer_summary, tug_like


def _tr(*rows):
    return pd.DataFrame([{"transfer": i + 1, "kind": k, "start_s": t0, "end_s": t0 + 1.5, "duration_s": 1.5,
                          "peak_s": t0 + 0.7, "peak_tilt_deg": 40.0, "height_change_m": 0.4, "flag": ""}
                         for i, (k, t0) in enumerate(rows)])


def _walk(t0, legs):
    """Contacts every 0.8 s from ``t0`` with 0.35 m steps along ``legs`` [(n steps, heading rad), ...]."""
    rows, t = [], t0
    for n, h in legs:
        for _ in range(n):
            rows.append({"start_s": t, "length_m": 0.35, "heading_rad": h})
            t += 0.8
    return pd.DataFrame(rows)


def test_tug_like_kernel_w445():
    c = np.arange(8.0, 24.0, 0.8)
    out = np.r_[np.zeros(10), np.full(10, np.pi)]
    assert tug_like(5.0, 6.5, 25.0, 26.5, c, np.full(20, 0.35), out)  # 3.5 m out, 3.5 m back: nets 0
    assert not tug_like(5.0, 6.5, 25.0, 26.5, c, np.full(20, 0.35), np.zeros(20))  # one way: a chair-to-chair walk
    half = np.r_[np.zeros(10), np.full(10, np.pi / 2)]  # 3.5 m, turn 90 deg, 3.5 m: nets 0.71 of the path
    assert not tug_like(5.0, 6.5, 25.0, 26.5, c, np.full(20, 0.35), half)
    assert tug_like(5.0, 6.5, 25.0, 26.5, c)  # no lengths / headings (a two-unit track's contacts): duration only
    assert not tug_like(5.0, 6.5, 5.0 + TUG_MAX_S, 6.5 + TUG_MAX_S, c)  # longer than TUG_MAX_S


def test_a_chair_to_chair_walk_is_no_tug_trial_w445():
    tr = _tr((SIT_TO_STAND, 5.0), (STAND_TO_SIT, 25.0))
    back = _walk(8.0, [(10, 0.0), (10, np.pi)])
    s = transfer_summary(tr, back)
    assert s["tug_time_s"] == pytest.approx(21.5) and s["n_tug_trials"] == 1 and s["n_chair_walks"] == 0
    one_way = _walk(8.0, [(10, 0.0), (10, np.pi / 2)])
    s = transfer_summary(tr, one_way)
    assert s["tug_time_s"] is None and s["n_tug_trials"] == 0 and s["n_chair_walks"] == 1
    assert s["tug_time_note"].startswith("no TUG time: 1 chair-to-chair walk(s) (rises at 5.0 s) do not look like")
    assert transfer_summary(None)["n_chair_walks"] is None  # a foot track


def test_a_simulated_tug_and_a_chair_to_chair_walk_w445(tmp_path, capsys):
    """User 10912: a slow TUG (3 m, 180 deg, 3 m, 180 deg to sit), seated 20 s, then a walk to another chair (4 m,
    90 deg, 3 m): W325 alone called both TUG trials; W445 keeps the TUG and calls the other a chair-to-chair walk."""
    d, out = tmp_path / "mix", tmp_path / "mix_w"
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3, turn:180, sit:20, straight:4, turn:90, "
                 "straight:3", "--sit-start", "5", "--sit-end", "5", "--step-length", "0.35", "--step-time", "0.8",
                 "--bounce", "pendulum", "--height", "1.58", "--user-seed", "10912", "--out", str(d)]) == 0
    capsys.readouterr()
    assert main(["track", str(d), "--units", "waist", "--per", "30s", "--no-plot", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    s = json.loads((out / "summary.json").read_text())
    assert s["n_sit_to_stand"] == 2 and s["n_tug_trials"] == 1 and s["n_chair_walks"] == 1
    trials = pd.read_csv(out / "tug_trials.csv")
    assert len(trials) == 1 and trials["start_s"].iloc[0] < 10.0  # the TUG, not the walk
    assert "1 chair-to-chair walk(s) not timed (W445)" in printed
    # decision W448: periods.csv counts each rise in the period it starts in
    periods, rises = pd.read_csv(out / "periods.csv"), pd.read_csv(out / "transfers.csv")
    rises = rises[rises["kind"] == SIT_TO_STAND]["start_s"]
    assert periods["n_sit_to_stand"].sum() == 2
    assert periods["n_sit_to_stand"].tolist() == [int(((rises >= a) & (rises < b)).sum())
                                                  for a, b in zip(periods["start_s"], periods["end_s"], strict=True)]
    assert main(["report", str(out), "--out", str(tmp_path / "rep"), "--clinical"]) == 0
    md = (tmp_path / "rep" / "clinical.md").read_text()
    assert "- TUG: 1 trials" in md and "found among 1 chair-to-chair walk(s) of daily life" in md
    assert "uncalibrated" in md and "- Track warnings:" in md and "W169" in md


def _summary(**kw):
    base = {"pipeline": "waist-pendulum", "gait_speed_mps": 0.33, "median_cadence_spm": 71.0,
            "info": {"params_source": "defaults", "warnings": ["a", "b"], "warning_codes": ["W169", "L351"]}}
    return {**base, **kw}


def test_clinical_gait_speed_says_calibrated_or_is_withheld_w446():
    line = gait_speed_line(_summary(), "lower-back unit")  # T2's day2: 0.33 m/s read for 0.21 m/s
    assert line.startswith("- Gait speed not given: an uncalibrated lower-back reading under the validated 0.5 m/s")
    assert "0.33" not in line and "cadence 71 steps/min" in line
    fast = gait_speed_line(_summary(gait_speed_mps=0.82, median_cadence_spm=95.0), "lower-back unit")
    assert fast.startswith("- Gait speed 0.82 m/s, cadence 95 steps/min (lower-back unit; uncalibrated")
    cal = gait_speed_line(_summary(gait_speed_mps=0.24, median_cadence_spm=80.0,
                                   info={"params_source": "calibrated"}), "lower-back unit")
    assert cal.startswith("- Gait speed 0.24 m/s, cadence 80 steps/min (lower-back unit; calibrated; slower than")
    assert gait_speed_line(_summary(pipeline="plasys", gait_speed_mps=1.1, median_cadence_spm=105.0),
                           "foot unit") == "- Gait speed 1.10 m/s, cadence 105 steps/min (foot unit)"
    assert warnings_line(_summary()).split("\n")[0].startswith("- Track warnings: 2 (W169, L351), what each means")
    assert warnings_line(_summary(info={})) is None


def test_clinical_daily_living_block_w448(tmp_path):
    pd.DataFrame({"duration_s": [20.0, 40.0, 60.0]}).to_csv(tmp_path / "bouts.csv", index=False)
    pd.DataFrame({"n_steps": [58, 167, 0]}).to_csv(tmp_path / "periods.csv", index=False)
    s = {"pipeline": "waist-pendulum", "time_span_s": 7200.0, "n_steps": 300, "median_cadence_spm": 65.0,
         "walking_time_s": 150.0, "n_sit_to_stand": 4, "median_sit_to_stand_s": 2.25, "n_stand_to_sit": 4,
         "n_lie_down": 0, "n_get_up": 0, "n_chair_walks": 2, "sitting_time_s": 6000.0, "standing_time_s": 900.0,
         "lying_time_s": 0.0, "unknown_time_s": 0.0, "per_s": 3600.0}
    assert daily_living_lines(s, tmp_path) == [
        "- Daily living over 2.0 h recorded: 300 steps (150 per hour); walking 2.5 min in 3 walking bouts (median "
        "40 s, longest 60 s, 2 of 30 s or more); lower-back step count not validated below 70 steps/min (L95)",
        "- Transfers: 4 sit-to-stand (median 2.2 s), 4 stand-to-sit, 0 lie-down, 0 get-up; 2 chair-to-chair "
        "walk(s) (W445)",
        "- Posture: sitting 1.7 h, standing 15 min, lying 0 min, unknown 0 min",
        "- Steps per 1 h (periods.csv): 58, 167, 0"]
    assert daily_living_lines({**s, "time_span_s": 1799.0}, tmp_path) == []  # under 30 min: no block (C254)


def test_time_course_speed_is_not_labelled_a_gait_speed_w448(tmp_path, monkeypatch):
    import pdrlearn.plots
    from pdrlearn.report.time_course import plot_time_course

    seen = {}
    monkeypatch.setattr(pdrlearn.plots, "save_atomic", lambda fig, path: seen.setdefault("fig", fig))
    p = pd.DataFrame({"start_s": [0.0, 3600.0], "end_s": [3600.0, 7200.0], "distance_m": [14.3, 43.3]})
    assert plot_time_course([("period", p)], None, tmp_path / "t.png")
    label = seen["fig"].axes[1].get_ylabel()
    assert "rests included" in label and "mean speed" not in label


def test_subjects_gait_speed_is_the_sessions_definition_w447():
    """T2's cohort: R01 read 0.3601 m/s in subjects.csv (bouts) and 0.3468 in sessions.csv (summary)."""
    sessions = pd.DataFrame({"path": ["day1"], "group": ["."], "status": ["ok"], "subject": ["R01"], "visit": [None],
                             "distance_m": [93.64], "walking_time_s": [270.05], "gait_speed_mps": [93.64 / 270.05],
                             "n_bouts": [8], "bouts_time_s": [260.05], "bouts_distance_m": [93.64],
                             "bouts_n_steps": [355], "bouts_n_strides": [339], "bouts_contact_span_s": [250.0],
                             "bouts_n_step_intervals": [340]})
    row = subject_totals(sessions).iloc[0]
    assert row["walking_time_s"] == pytest.approx(270.05)
    assert row["gait_speed_mps"] == pytest.approx(sessions["gait_speed_mps"].iloc[0], rel=1e-12)
    assert row["bouts_time_s"] == pytest.approx(260.05)
    assert row["bouts_gait_speed_mps"] == pytest.approx(93.64 / 260.05)


def test_w445_return_bound_sits_between_a_pll_tug_and_a_one_way_walk():
    """W445 amended by the lead: a waist-pll TUG read a return ratio of 0.31, T2's lowest one-way walk 0.37."""
    import numpy as np

    from pdrlearn.waist.transfers import TUG_RETURN_MAX, tug_like

    def ratio_walk(r):  # 5 contacts of 1 m out, 5 back of B / 5 m: net / path = (5 - B) / (5 + B) = r
        back = 5.0 * (1.0 - r) / (1.0 + r)
        return np.r_[np.full(5, 1.0), np.full(5, back / 5.0)], np.r_[np.zeros(5), np.full(5, np.pi)]

    contacts = np.arange(10) + 10.0
    for r, tug in ((0.31, True), (0.37, False)):
        ln, hd = ratio_walk(r)
        net = abs((ln * np.cos(hd)).sum()) / ln.sum()
        assert bool(net <= TUG_RETURN_MAX) is tug
        assert bool(tug_like(0.0, 5.0, 25.0, 30.0, contacts, ln, hd)) is tug
