"""Decision L449 (session 36, trial T2 finding 4): periods.csv gives the steps of both feet per period
(``n_steps_both_feet``, as the summary's), beside ``n_steps`` (the rows of steps.csv: one foot's strides on a foot
track); docs/columns.md says in one line which count is which."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]


def test_periods_csv_counts_both_feet_as_the_summary_l449(tmp_path):
    sim, out = tmp_path / "s", tmp_path / "t"
    assert main(["simulate", "--route", "stand:3, straight:30, stand:20, straight:30, stand:3", "-u", "8907",
                 "-o", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--per", "30", "--out", str(out)]) == 0
    per = pd.read_csv(out / "periods.csv")
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_steps_counts"] == "strides of the tracked foot" and len(per) >= 3
    assert (per["n_steps_both_feet"] == 2 * per["n_steps"]).all()  # no gap rows on this walk
    assert per["n_steps_both_feet"].sum() == summary["n_steps_both_feet"] == 2 * summary["n_steps"]
    bouts = pd.read_csv(out / "bouts.csv")
    assert bouts["n_steps"].sum() == summary["n_steps_both_feet"]  # the trial's daily total, from either file


def test_columns_md_says_which_step_count_is_which_l449():
    from pdrlearn.columns import STEP_COUNT_LINE, expanded

    text = (ROOT / "docs" / "columns.md").read_text(encoding="utf-8")
    assert STEP_COUNT_LINE in text and "n_steps_both_feet" in STEP_COUNT_LINE
    assert "n_steps_both_feet" in expanded("periods.csv")
