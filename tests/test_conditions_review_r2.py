"""Session 34, review R2 of the cohort condition comparisons (C81-C83, B302, B303): a copied trial among averaged
trials is named (C84), the percent change of a negative baseline has the change's sign and plain floats give no
ZeroDivisionError (C81 amended), the summary says how many subjects its percent change covers (C85), and track-all's
--metrics repeats, lists and measures without values are one line each, never a traceback (B326, B327). Simulated
users 8240-8243."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.visits import change_summary, change_table, changes_text, check_measures, pct_change


def _sessions(rows) -> pd.DataFrame:
    """sessions.csv rows ``(path, subject, visit, duplicate_of, value)`` of one measure, all tracked by plasys."""
    return pd.DataFrame([{"path": p, "group": "g", "subject": s, "visit": v, "status": "ok", "pipeline": "plasys",
                          "duplicate_of": d, "final_x_m": x} for p, s, v, d, x in rows])


def test_each_averaged_trial_that_copies_a_baseline_trial_is_named_c84():
    """R2 #1: with two trials per visit the averaged row had duplicate_of None, so c (a copy of a) and d (a copy of
    b) gave a clean ok change of 0 with no word; one trial per visit was named. Now every copied trial is."""
    rows = _sessions([("a", "s1", "bl", None, 1.0), ("b", "s1", "bl", None, 1.2), ("c", "s1", "fu", "a", 1.0),
                      ("d", "s1", "fu", "b", 1.2), ("e", "s2", "bl", None, 1.0), ("f", "s2", "fu", "e", 1.0)])
    got = change_table(rows, metrics=["final_x_m"]).set_index("subject")
    assert got.loc["s1", "reason"] == ("c holds the same recording as a (duplicate_of); d holds the same recording as "
                                       "b (duplicate_of)")
    assert got.loc["s2", "reason"] == "f holds the same recording as e (duplicate_of)"  # one trial: as before
    rows.loc[rows["path"] == "d", "duplicate_of"] = None  # only c is a copy: only c is named
    got = change_table(rows, metrics=["final_x_m"]).set_index("subject")
    assert got.loc["s1", "reason"] == "c holds the same recording as a (duplicate_of)"


def test_percent_change_of_a_negative_baseline_has_the_change_sign_and_floats_are_safe_c81():
    """R2 #2, #9: final_x_m -1 -> -2 (an increase of -1) gave +100 %; pct_change(0.0, 1.0) raised ZeroDivisionError.
    Now 100 x change / |baseline|, empty for a zero baseline, for floats and arrays alike."""
    assert pct_change(-1.0, -2.0) == pytest.approx(-100.0)
    assert pct_change(-2.0, -1.0) == pytest.approx(50.0)
    assert pct_change(2.0, 1.0) == pytest.approx(-50.0)
    assert np.isnan(pct_change(0.0, 1.0)) and np.isnan(pct_change(0, 0)) and np.isnan(pct_change(float("nan"), 1.0))
    np.testing.assert_allclose(pct_change(np.array([1.0, 0.0, -2.0]), np.array([2.0, 1.0, -1.0])),
                               [100.0, np.nan, 50.0])
    rows = _sessions([("a", "s1", "bl", None, -1.0), ("b", "s1", "fu", None, -2.0)])
    got = change_table(rows, metrics=["final_x_m"]).iloc[0]
    assert got["final_x_m_change"] == pytest.approx(-1.0) and got["final_x_m_change_pct"] == pytest.approx(-100.0)


def test_summary_counts_the_subjects_of_its_percent_change_c85():
    """R2 #3: n_freezes 0 -> 3, 0 -> 2, 2 -> 3 gave n_subjects 3 beside a mean percent change of one subject, not
    said. Now n_pct_subjects (1) is in changes_summary.csv and in the printed table."""
    rows = pd.DataFrame([{"path": f"{s}{v}", "group": "g", "subject": s, "visit": v, "status": "ok",
                          "pipeline": "plasys", "duplicate_of": None, "n_freezes": n}
                         for s, pair in (("s1", (0, 3)), ("s2", (0, 2)), ("s3", (2, 3)))
                         for v, n in zip(("bl", "fu"), pair, strict=True)])
    summary = change_summary(change_table(rows, metrics=["n_freezes"])).iloc[0]
    assert summary["n_subjects"] == 3 and summary["n_pct_subjects"] == 1
    assert summary["mean_change"] == pytest.approx(2.0) and summary["mean_pct_change"] == pytest.approx(50.0)
    text = changes_text(change_summary(change_table(rows, metrics=["n_freezes"]))).iloc[0]
    assert text["n_subjects"] == 3 and text["n % change"] == 1
    from pdrlearn.columns import undocumented
    from pdrlearn.visits import SUMMARY_COLUMNS

    assert undocumented("changes_summary.csv", SUMMARY_COLUMNS) == []  # the data dictionary has the table (C85)


def test_measures_are_named_once_and_lists_are_refused_b326():
    """R2 #7, #6: a repeated name made duplicate columns (TypeError after tracking); splits_m, split_times_s and
    schema_version passed B302 although no session has one number of them. Now each name once, the others one line."""
    assert check_measures(["gait_speed_mps", "gait_speed_mps", "median_cadence_spm"]) == ("gait_speed_mps",
                                                                                         "median_cadence_spm")
    for bad in ("splits_m", "split_times_s", "schema_version"):
        with pytest.raises(DataError) as err:
            check_measures(["gait_speed_mps", bad])
        line = str(err.value)
        assert f"'{bad}' is not a measure of one number per session" in line and "B326" in line and "\n" not in line


def _study(root):
    """Users 8240-8243 (subjects P8240-P8243), each 12 m at a normal pace (pre) and a slow pace (post), 100 Hz."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

    for uid in (8240, 8241, 8242, 8243):
        for visit, speed in (("pre", "normal"), ("post", "slow")):
            s = simulate_path([Stand(2), Straight(12), Stand(2)], UserProfile.from_seed(uid), speed=speed,
                              rate_hz=100, seed=uid, name=f"u{uid}_{visit}")
            folder = root / f"u{uid}" / visit
            write_session(s, folder)
            meta = json.loads((folder / "meta.json").read_text())
            (folder / "meta.json").write_text(json.dumps({**meta, "subject": f"P{uid}", "visit": visit}))


def test_track_all_metrics_repeated_empty_or_listed_are_one_line_never_a_traceback_b326_b327(tmp_path, capsys):
    """R2 #6-#8 end to end: --metrics gait_speed_mps,gait_speed_mps,tug_time_s crashed after tracking (TypeError) and
    dropped tug_time_s without a word; --metrics tug_time_s alone gave KeyError 'visit'; --metrics splits_m was
    accepted. Now: one set of columns and one warning line naming tug_time_s; a measure-less summary; splits_m one
    line before tracking (exit 2, no output)."""
    from pdrlearn.cli import main

    root = tmp_path / "study"
    _study(root)
    out = tmp_path / "o"
    assert main(["track-all", "--no-plot", str(root), "--out", str(out), "--metrics",
                 "gait_speed_mps,gait_speed_mps,tug_time_s"]
                ) == 0
    got = capsys.readouterr()
    assert "Traceback" not in got.err
    said = [line for line in (got.out + got.err).splitlines() if "B327" in line]
    assert len(said) == 1 and "no session has a value of tug_time_s" in said[0]
    changes = pd.read_csv(out / "changes.csv")
    assert [c for c in changes if c.startswith("gait_speed_mps")] == ["gait_speed_mps_baseline",
                                                                      "gait_speed_mps_change",
                                                                      "gait_speed_mps_change_pct"]
    assert not any(c.startswith("tug_time_s") for c in changes) and changes["status"].eq("ok").all()
    assert pd.read_csv(out / "changes_summary.csv")["n_pct_subjects"].tolist() == [4]
    # the same sessions, reused from the first run (decision D59: tracking them again is not what B327 is about)
    shutil.copytree(out, tmp_path / "o1")
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o1"), "--metrics", "tug_time_s",
                 "--resume"]) == 0
    got = capsys.readouterr()
    assert "Traceback" not in got.err and "no session has a value of tug_time_s" in got.out + got.err
    summary = pd.read_csv(tmp_path / "o1" / "changes_summary.csv")
    assert summary.empty and "n_pct_subjects" in summary
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o2"), "--metrics",
                 "gait_speed_mps,splits_m"]) == 2
    err = capsys.readouterr().err
    assert "--metrics gait_speed_mps,splits_m: 'splits_m' is not a measure" in err and "B326" in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1 and not (tmp_path / "o2").exists()
