"""Trial T2 (session 47) F2, decision W538: a lower-back flight phase is a jump (0.2 s or more) or a dip at a running
cadence (a step period under 0.4 s), not the trough of a brisk walker's vertical bounce; the foot's test is unchanged.
Users 15060-15079 (fixer FF's fresh range)."""

from __future__ import annotations

import json

import numpy as np

from pdrlearn.kernels.units import STANDARD_GRAVITY as G
from pdrlearn.track.flight import flight_phases, step_period_at, unit_flights

FS = 100.0


def _acc(vertical_g: np.ndarray) -> np.ndarray:
    """A lower-back accelerometer (m/s^2) whose specific force is ``vertical_g`` (g) along one axis."""
    return np.column_stack([np.zeros_like(vertical_g), vertical_g * G, np.zeros_like(vertical_g)])


def _bounce(seconds: float = 20.0, step_s: float = 0.5, amp_g: float = 0.97):
    """A brisk walker's pelvis: 1 g minus a sinusoidal bounce of ``amp_g`` at the step period (T2 F2's trace: its
    trough reads under 0.3 g for about 0.12 s)."""
    t = np.arange(0.0, seconds, 1.0 / FS)
    return t, 1.0 - amp_g * np.cos(2 * np.pi * t / step_s)


def test_a_brisk_walkers_bounce_trough_is_a_foot_rule_flight_but_not_a_lower_back_one_w538():
    t, g = _bounce()
    acc = _acc(g)
    old = flight_phases(t, acc)
    assert len(old) >= 30, old  # W363/W409's rule alone: every trough (the false line of T2 F2)
    assert abs(step_period_at(t, acc, old[5]) - 0.5) < 0.02
    assert unit_flights("waist", t, acc) == []
    assert unit_flights("foot", t, acc) == old  # the foot's test is unchanged


def test_a_jump_and_a_run_are_still_lower_back_flights_w538():
    t, g = _bounce()
    g[(t >= 8.0) & (t < 8.4)] = 0.0  # a 0.4 s jump (W416's synthetic jumps' flight)
    phases = unit_flights("waist", t, _acc(g))
    assert len(phases) == 1 and abs(phases[0][0] - 8.0) < 0.1 and phases[0][1] - phases[0][0] >= 0.4 - 1e-9
    # a run at 170 steps/min: 0.12 s at 0 g each step, a half-sine stance keeping the mean at 1 g
    step = 60.0 / 170.0
    t = np.arange(0.0, 20.0, 1.0 / FS)
    ph = np.mod(t, step)
    stance = step - 0.12
    g = np.where(ph < stance, np.pi / 2 * step / stance * np.sin(np.pi * ph / stance), 0.0)
    acc = _acc(g)
    assert step_period_at(t, acc, (10.0, 10.12)) < 0.4
    assert len(unit_flights("waist", t, acc)) == len(flight_phases(t, acc)) >= 50


def test_a_brisk_walkers_lower_back_track_says_no_flight_w538(tmp_path):
    """User 15070 at 0.45 s / 0.933 m steps (2.07 m/s, population bounce): W363/W409's rule alone finds 10 phases
    on its lower-back accelerometer (T2 F2's false "jumps or running" line); W538 names none."""
    from pdrlearn.cli import main
    from pdrlearn.io import read_session

    sim, out = tmp_path / "brisk", tmp_path / "brisk_tr"
    assert main(["simulate", "--route", "stand:2, straight:60, stand:2", "--step-length", "0.933", "--step-time",
                 "0.45", "--bounce", "population", "--rate", "100", "--user-seed", "15070", "--out", str(sim)]) == 0
    acc = read_session(sim).streams["wAccelerometer"]
    assert len(flight_phases(acc.t, acc.values)) >= 5  # the troughs the old rule named
    assert main(["track", "--no-plot", str(sim), "--units", "waist", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_flight_phases"] == 0, summary["n_flight_phases"]
    assert not [ln for ln in summary["info"]["warnings"] if "flight phase" in ln]
    assert "waist" not in (out / "flights.csv").read_text()


def test_a_step_period_of_0_4_s_read_just_under_it_is_no_run_r1_f4():
    """Review R1 F4 (session 48): on a clock starting at 3.7 s the 40-sample lag reads 0.3999999999999915 s; W538's
    "under 0.4 s" is a cadence over 150 steps/min, not float noise (before: 49 lower-back flights)."""
    t, g = _bounce(step_s=0.4, amp_g=1.0)
    t = t + 3.7
    acc = _acc(g)
    phases = flight_phases(t, acc)
    assert len(phases) >= 40 and step_period_at(t, acc, phases[3]) < 0.4
    assert unit_flights("waist", t, acc) == []
