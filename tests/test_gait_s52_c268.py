"""Decision C268: ``gait``'s flight time is said per gait cycle (both flights summed) and per step
(``step_flight_time_s``); decision C269: ``track``'s ``n_flight_phases`` is the tracked unit's own free fall, which a
foot swinging through a running stride's flight never reaches (0 on a foot-tracked run), and its column says so."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.gait import gait_lines
from pdrlearn.columns import GAIT_BOUTS, GAIT_CYCLES, SESSIONS
from pdrlearn.kernels.units import STANDARD_GRAVITY as G
from pdrlearn.track.bilateral import bilateral_gait
from pdrlearn.track.flight import flight_phases

CYCLE, STANCE = 0.66, 0.22  # s: a runner's gait cycle and contact (trial s52t2's re-timed copies)


def _feet(n: int = 24) -> list[pd.DataFrame]:
    """Both feet's labels: each contact 0.22 s, so 0.11 s of flight after each toe-off (two per cycle)."""
    out = []
    for start in (0.0, 0.5 * CYCLE):
        ic = 1.0 + start + CYCLE * np.arange(n)
        out.append(pd.DataFrame({"ic_s": ic, "tc_s": ic - CYCLE + STANCE}))
    return out


@pytest.fixture(scope="module")
def run():
    return bilateral_gait(*_feet())


def test_flight_is_per_cycle_and_per_step_c268(run):
    w = run["walk"]
    flight = 0.5 * CYCLE - STANCE  # one step's flight: a toe-off to the other foot's contact
    assert w["n_flight_cycles"] > 0
    assert w["flight_time_s"] == pytest.approx(2 * flight)  # per cycle: its two flights summed (L729, unchanged)
    assert w["step_flight_time_s"] == pytest.approx(flight)  # C268: what runners call flight time
    assert all(b["step_flight_time_s"] == pytest.approx(flight) for b in run["bouts"])
    line = next(x for x in run["warnings"] if "have a flight" in x)
    assert "220 ms per gait cycle on average (its two flights summed; 110 ms per step)" in line
    con = next(x for x in gait_lines(w) if x.startswith("flight ("))
    assert "220 ms per gait cycle" in con and "110 ms per step" in con and "C268" in con
    assert "summed" in dict((c[0], c[3]) for c in GAIT_CYCLES)["flight_time_s"]
    bouts = dict((c[0], c[3]) for c in GAIT_BOUTS)
    assert "per gait cycle" in bouts["flight_time_s"] and "per step" in bouts["step_flight_time_s"]


def test_walking_has_no_step_flight_c268():
    w = bilateral_gait(*[f.assign(tc_s=f["tc_s"] + 0.2) for f in _feet()])["walk"]  # 0.42 s contacts overlap
    assert w["n_flight_cycles"] == 0 and w["step_flight_time_s"] is None


def test_a_foot_in_a_running_flight_is_no_free_fall_c269():
    """A foot unit through a running stride: |acc| near 1 g at the contact, the swing's several g through the flight
    (the foot whips forward): no run under 0.3 g, so n_flight_phases is 0 - while a jump's passive foot counts."""
    fs = 200.0
    t = np.arange(0.0, 6.6, 1 / fs)
    phase = (t % CYCLE) / CYCLE
    mag = np.where(phase < STANCE / CYCLE, G, G * (1.0 + 2.5 * np.abs(np.sin(np.pi * phase))))  # swing 1-3.5 g
    acc = np.c_[np.zeros_like(t), mag, np.zeros_like(t)]
    assert flight_phases(t, acc) == []
    acc[(t > 2.0) & (t < 2.4), 1] = 0.05 * G  # a jump: the passive foot falls with the body for 0.4 s
    assert len(flight_phases(t, acc)) == 1
    text = dict((c[0], c[3]) for c in SESSIONS)["n_flight_phases"]
    assert "a foot-tracked run counts 0" in text and "n_flight_cycles" in text and "C269" in text
