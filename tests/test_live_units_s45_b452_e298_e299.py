"""Decisions B452 (docs/decisions/bad-input.md), E298 and E299 (docs/decisions/export.md): trial T2's live-input
findings of session 45.

- B452 (F8): a barometer pushed with timestamps in ms (one-sample packets) was taken at "0.02 Hz" and its later
  samples gave misleading lines (a +100 s clock jump, a foot "stopped"); it is now refused with the ms line, before
  B141's jump check.
- E298 (F9): a gyroscope in deg/s was refused only when a whole 5 s window showed it (9 steps emitted before); three
  samples over 40 "rad/s" in the window so far refuse it at the first swing.
- E299 (F5): a waist gyroscope gap over 1 s while the waist heads the strides says that a turn inside it is not
  measured.
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.units import GYRO_EARLY_SAMPLES, GYRO_RAD_S_MAX, gyro_in_deg
from pdrlearn.runtime.resample import BARO_MIN_HZ, InputStage
from pdrlearn.runtime.tracker import Tracker, heading_gap_line


class _Bundle:
    rate_hz = 20.0
    used_sensors = ("fAccelerometer", "fGyroscope", "wBarometer")

    def off_rate(self, rates):
        return {}


def test_a_barometer_in_ms_is_refused_with_the_ms_line():
    stage = InputStage(_Bundle())
    stage.unit_check({"wBarometer": 1.0})  # a 1 Hz barometer
    stage.unit_check({"wBarometer": 0.2})  # E39's 0.2 Hz one
    with pytest.raises(DataError, match=r"wBarometer: the pushed timestamps give 0.02 Hz.*B452.*in ms"):
        stage.unit_check({"wBarometer": 0.02})  # 20 Hz in ms
    assert 20.0 / 1000 < BARO_MIN_HZ < 0.2


def test_one_sample_barometer_pushes_in_ms_get_the_ms_line_not_a_clock_jump():
    from pathlib import Path

    from pdrlearn.runtime import load_bundle

    bundle = load_bundle(Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default")  # reads wBarometer
    assert "wBarometer" in bundle.used_sensors
    tr, lines = Tracker(bundle), set()
    for k in range(12):
        try:
            tr.push({"wBarometer": (np.array([50.0 * k]), np.array([[1000.0]]))})  # 20 Hz, t in ms
        except DataError as e:
            lines.add(str(e).split(":")[0] + (" ms" if "in ms" in str(e) else " other: " + str(e)[:80]))
    assert lines == {"wBarometer ms"}


def test_the_early_deg_s_reason_needs_three_samples_over_the_limit():
    v = np.zeros((40, 3))
    v[5, 2] = v[6, 2] = GYRO_RAD_S_MAX + 10
    assert gyro_in_deg(v) == ""  # two corrupt samples decide nothing
    v[7, 2] = -(GYRO_RAD_S_MAX + 30)
    assert GYRO_EARLY_SAMPLES == 3 and "deg/s" in gyro_in_deg(v)


def test_a_waist_gyroscope_in_deg_s_is_refused_at_its_first_turn_not_when_its_window_is_whole():
    """A waist turning at up to 1.2 rad/s, pushed in deg/s (69 read as rad/s: under B425's range of 100): before, only
    its whole 5 s window was judged."""
    from pdrlearn.runtime.guard import GUARD_S, UnitGuard

    guard = UnitGuard(["wAccelerometer", "wGyroscope"])
    t = np.arange(0.0, 1.5, 0.05)
    rate = np.zeros((len(t), 3))
    rate[:, 1] = np.degrees(1.2) * np.exp(-((t - 1.0) / 0.15) ** 2)  # a turn at 1 s
    assert t[-1] < GUARD_S and float(np.percentile(np.abs(rate), 99)) > GYRO_RAD_S_MAX
    acc = np.tile([0.0, 9.81, 0.0], (len(t), 1))
    guard.take({"wAccelerometer": (t[:10], acc[:10]), "wGyroscope": (t[:10], rate[:10])},
               guard.check({"wAccelerometer": (t[:10], acc[:10]), "wGyroscope": (t[:10], rate[:10])}))
    with pytest.raises(DataError, match=r"wGyroscope .*samples turn faster than 40.*deg/s.*E298"):
        guard.check({"wAccelerometer": (t[10:], acc[10:]), "wGyroscope": (t[10:], rate[10:])})


def test_the_heading_gap_line_names_the_unmeasured_turn():
    line = heading_gap_line(37.23, 39.83)
    assert line.startswith("wGyroscope: no samples for 2.60 s (37.23-39.83 s)") and "E299" in line


@pytest.mark.parametrize("waist_first", [False, True])
def test_a_gap_in_both_units_says_the_turn_inside_it_is_not_measured(synthetic_bundle, waist_first):
    """Both units silent 1.6 s in a turning walk (the waist heads the strides, L91): the gap's line says the turn is
    not measured (E299), whether the waist's gap or the foot's is pushed first; before, "turns with the waist
    gyroscope (L91)"."""
    from tests.runtime_helpers import holed_chunks, synthetic_session

    walk = synthetic_session(12, seed=12833, name="walk", turn_rad_per_step=0.3)
    tr = Tracker(synthetic_bundle)
    for chunk in holed_chunks(walk, 0.25, (5.2, 6.8)):
        if waist_first:  # the waist's samples after the gap arrive one push before the foot's
            tr.push({n: c for n, c in chunk.items() if n.startswith("w")})
            tr.push({n: c for n, c in chunk.items() if not n.startswith("w")})
        else:
            tr.push(chunk)
    tr.flush()
    lines = [w for w in tr.warnings if "E299" in w]
    assert lines and all("1.6" in w for w in lines), tr.warnings
    assert not any("turns with the waist gyroscope (L91)" in w for w in tr.warnings)
