"""Decisions L701 / L702: a two-unit foot track's rest gap takes the lower back's turn the foot missed (L701), and
every rest gap turning the heading 80 deg or more is a turns.csv row (L702). S106's stepless spins are the test."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.gap_turn import GAP_TURN_GATE_RAD_S, gated_turn, missed_turn
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.folder import clinical_tables


def test_missed_turn_and_the_gate():
    assert missed_turn(math.radians(90), math.radians(40), 80) == pytest.approx(math.radians(50))
    assert missed_turn(math.radians(90), math.radians(46), 80) == 0.0  # missed by 44 deg: the foot's stays
    assert missed_turn(math.radians(79), 0.0, 80) == 0.0  # under L104's 80 deg
    assert missed_turn(math.radians(-180), math.radians(-20), 80) == pytest.approx(math.radians(-160))
    t = np.arange(0, 100, 0.05)
    acc = np.tile([0.0, 0.0, 9.81], (t.size, 1))
    still = np.column_stack([np.zeros(t.size), np.zeros(t.size), np.full(t.size, 0.9 * GAP_TURN_GATE_RAD_S)])
    assert gated_turn(t, still, acc)[1][-1] == 0.0  # an offset under the gate adds nothing over 100 s
    spin = still + [0.0, 0.0, math.radians(18)] * (np.abs(t - 50) < 5)[:, None]
    # 10 s at 18 deg/s over the offset: 180 deg and the offset's 10 x 1.8 deg while the spin is above the gate
    assert math.degrees(gated_turn(t, spin, acc)[1][-1]) == pytest.approx(198, abs=1)


def _track(route: str, user: int):
    s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20, seed=0, name="spin")
    result = get_pipeline("plasys")(s)
    return s, result, track_summary(result, s, pipeline="plasys")


def _heading_change(s, result, spin) -> tuple[float, float]:
    st, tr = result.steps, s.trajectory
    before, after = st[st["end_s"] <= spin["start_s"]], st[st["start_s"] >= spin["end_s"]]
    t0, t1 = float(before["start_s"].iloc[-1]), float(after["start_s"].iloc[0])
    h = np.unwrap(tr["heading_rad"].to_numpy())
    true = math.degrees(np.interp(t1, tr["t"], h) - np.interp(t0, tr["t"], h))
    got = math.degrees(float(after["heading_rad"].iloc[0]) - float(before["heading_rad"].iloc[-1]))
    return got, true


def test_a_slow_stepless_spin_turns_the_foot_heading_and_is_a_turn_l701():
    s, result, summary = _track("stand:3, straight:8, spin:-150:15, straight:8, stand:3", 14747)
    spin = s.extras["spins"].iloc[0]
    got, true = _heading_change(s, result, spin)
    assert abs((got - true + 180) % 360 - 180) < 20  # main: the foot's heading missed most of it
    turns = clinical_tables(result, None)["turns.csv"]
    row = turns[turns["n_rows"] == 0]
    assert len(row) == 1 and row["angle_deg"].iloc[0] == pytest.approx(-150, abs=30)
    assert spin["start_s"] - 1 <= row["start_s"].iloc[0] < row["end_s"].iloc[0] <= spin["end_s"] + 1
    assert summary["turn_count"] == 1
    assert summary["final_position_error_m"] < 1.5
    gap = result.info["waist_gap_turns"]
    assert len(gap) == 1 and abs(gap[0]["added_deg"]) > 45


def test_a_window_keeps_the_gap_turns_inside_it():
    from pdrlearn.track.window import window_track

    s, result, _ = _track("stand:3, straight:8, spin:-150:15, straight:8, stand:3", 14747)
    spin = s.extras["spins"].iloc[0]
    t_rec = s.t_recording_start
    before, _ = window_track(result, s, 0.0, float(spin["start_s"]) - t_rec - 0.5)
    assert before.info["waist_gap_turns"] == [] and len(clinical_tables(before, None)["turns.csv"]) == 0
    whole, _ = window_track(result, s, 0.0, float(s.trajectory["t"].iloc[-1]) - t_rec)
    assert len(whole.info["waist_gap_turns"]) == 1


def test_a_quick_spin_the_foot_saw_is_a_turn_too_l702():
    s, result, summary = _track("stand:3, straight:8, spin:120:2, straight:8, stand:3", 14748)
    gap = result.info["waist_gap_turns"]
    assert len(gap) == 1 and gap[0]["added_deg"] == 0.0  # L28's gap yaw turned the heading; L701 added nothing
    assert gap[0]["angle_deg"] == pytest.approx(120, abs=30)
    assert summary["turn_count"] == 1  # main: 0 (turns.csv's foot turns were the strides' own)


def test_a_walk_with_stepping_turns_has_no_gap_turn():
    _, result, summary = _track("stand:3, straight:8, turn:180, straight:6, pivot:90, straight:4, stand:3", 14749)
    assert "waist_gap_turns" not in result.info
    assert summary["turn_count"] == 2
