"""Decision C185 (trial T1, finding F8): after ``track --common-span`` cut a two-unit session to the time both units
cover, summary ``time_span_s`` (the console's "time N s" line) accounts for the cut span only - the seconds cut off
are ``common_span_cut_s`` (B267), not time the walker stood (main: a cut to 0-246.69 s read ``time 248.7 s``)."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main


def test_time_span_is_the_cut_span_after_common_span(tmp_path):
    sess = tmp_path / "s"
    assert main(["simulate", "--route", "stand:3, straight:6, stand:3", "--user-seed", "12860", "--rate", "100",
                 "--out", str(sess)]) == 0
    for f in sess.glob("f[A-Z]*.csv"):  # the foot unit (its sensor files) started 2 s after the lower back
        t = pd.read_csv(f)
        t[t["timestamp"] >= 2000].to_csv(f, index=False)
    foot_end = float(pd.read_csv(sess / "fAccelerometer.csv")["timestamp"].iloc[-1]) / 1000.0
    assert main(["track", "--no-plot", str(sess), "--common-span", "--out", str(tmp_path / "t")]) == 0
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert summary["time_span_s"] == pytest.approx(foot_end - 2.0, abs=0.02)  # main: foot_end (the cut 2 s in)
    parts = ("time_walking_s", "time_between_steps_s", "time_no_steps_s", "time_no_data_s")
    assert sum(summary[k] or 0.0 for k in parts if k in summary) == pytest.approx(summary["time_span_s"], abs=0.05)
