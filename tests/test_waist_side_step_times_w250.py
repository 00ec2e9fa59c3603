"""Decision W250 (session 31 prosthesis trial, finding 8): the lower back's summary gives the step-time asymmetry a
direction - the mean step time onto each foot and their ratio L/R, as `pdrlearn gait`'s keys."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.clinical import leg_summary


def test_step_onto_a_side_ends_at_that_sides_contact():
    st = np.cumsum([0.0] + [0.8, 0.4] * 8)  # contacts left, right, left ...: onto right 0.8 s, onto left 0.4 s
    waist = pd.DataFrame({"start_s": st, "end_s": np.append(st[1:], st[-1]), "length_m": 0.4, "unit": "waist",
                          "has_next": [True] * (len(st) - 1) + [False],
                          "side": (["left", "right"] * 9)[:len(st) - 1] + [""]})
    g = leg_summary(waist)
    assert g["step_time_s_left"] == pytest.approx(0.4) and g["step_time_s_right"] == pytest.approx(0.8)
    assert g["step_time_s_ratio"] == pytest.approx(0.5)
    few = leg_summary(waist.iloc[:6].assign(has_next=[True] * 5 + [False]))  # 2-3 step times a side: under 4
    assert few["step_time_s_left"] is None and few["step_time_s_ratio"] is None
    assert leg_summary(waist.assign(unit="foot").drop(columns="side"))["step_time_s_ratio"] is None


def test_paretic_right_walker_reads_longer_right_steps(tmp_path):
    """S35/S55: steps onto the paretic right foot 1.3 x the left's (labels 0.496 / 0.646 s, ratio 0.768)."""
    sim, out = tmp_path / "sim", tmp_path / "trk"
    assert main(["simulate", "--route", "stand:3, straight:30, stand:3", "--step-time-asymmetry", "0.3",
                 "--paretic-side", "right", "--user-seed", "6078", "--out", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--pipeline", "waist-pendulum", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["step_time_s_right"] > s["step_time_s_left"] and s["step_time_s_ratio"] < 0.85
    assert s["step_time_s_ratio"] == pytest.approx(s["step_time_s_left"] / s["step_time_s_right"])


def test_waist_length_is_documented_as_no_per_side_step_length():
    """W251: docs/columns.md (from pdrlearn.columns) marks the waist steps.csv length_m as no per-side step length."""
    from pathlib import Path

    from pdrlearn.columns import WAIST_STEPS

    (meaning,) = [c[3] for c in WAIST_STEPS if c[0] == "length_m"]
    assert "NOT valid as a per-side step length" in meaning
    doc = (Path(__file__).resolve().parents[1] / "docs" / "columns.md").read_text()
    assert "NOT valid as a per-side step length" in doc
