"""Session 41, fixer FB (review R0 findings 4, 5, 7, 8): clinical.md's daily-living steps are both feet's (W458),
the GNSS distance scale is applied only when it is distinguishable from 1 (D45), a fix CSV's epoch-second `t` (D46),
and `--splits every:STEP`'s floor (L563, B420)."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.report.daily_living import daily_living_lines


# --- W458 ------------------------------------------------------------------------------------------------
def _foot_folder(tmp_path, *, both_feet=True):
    """A foot (plasys) track's folder as R0's 1.1 h recording wrote it: 443 strides of the tracked foot."""
    s = {"pipeline": "plasys", "time_span_s": 3843.15, "n_steps": 443, "n_steps_counts": "strides of the tracked foot",
         "median_cadence_spm": 100.9, "walking_time_s": 527.8, "per_s": 1200.0}
    p = pd.DataFrame({"n_steps": [222, 0, 26, 195], "n_steps_counts": "strides of the tracked foot"})
    if both_feet:
        s |= {"n_strides_one_foot": 443, "n_steps_both_feet": 886}
        p["n_steps_both_feet"] = [444, 0, 52, 390]
    else:  # a track written before L103 / L449: only n_steps, read by its pipeline
        s.pop("n_steps_counts")
        p = p.drop(columns="n_steps_counts")
    p.to_csv(tmp_path / "periods.csv", index=False)
    (tmp_path / "summary.json").write_text(json.dumps(s))
    return s


def test_daily_living_counts_both_feet_on_a_foot_track_w458(tmp_path):
    for both in (True, False):
        lines = daily_living_lines(_foot_folder(tmp_path, both_feet=both), tmp_path)
        assert lines[0].startswith("- Daily living over 1.1 h recorded: ~886 steps (830 per hour; 2 per stride of "
                                   "the tracked foot); walking 8.8 min"), lines[0]
        assert lines[-1] == ("- Steps per 20 min (periods.csv, ~2 per stride of the tracked foot): 444, 0, 52, 390")


def test_daily_living_on_the_lower_back_still_reads_steps_w458(tmp_path):
    pd.DataFrame({"n_steps": [58, 167, 0], "n_steps_both_feet": [58, 167, 0]}).to_csv(tmp_path / "periods.csv",
                                                                                     index=False)
    s = {"pipeline": "waist-pendulum", "time_span_s": 7200.0, "n_steps": 300, "n_steps_counts": "steps of both feet",
         "n_steps_both_feet": 300, "median_cadence_spm": 95.0, "per_s": 3600.0}
    lines = daily_living_lines(s, tmp_path)
    assert lines[0] == "- Daily living over 2.0 h recorded: 300 steps (150 per hour)"
    assert lines[-1] == "- Steps per 1 h (periods.csv): 58, 167, 0"
