"""Decision W161's cue (experiments/waist_ap_cue.py): the trunk's forward-to-vertical oscillation ratio over a step,
pinned on hand-made signals (the measured numbers are the experiment's, experiments/results/waist_ap_cue.txt)."""

from __future__ import annotations

import numpy as np
import pytest

cue = pytest.importorskip("experiments.waist_ap_cue")

FS = 100.0
T = np.arange(0, 0.5, 1 / FS)  # one 0.5 s step, 51 samples with both contacts
STEP_HZ = 2.0  # the trunk oscillates once per step


def _sine(amp: float, hz: float = STEP_HZ, phase: float = 0.0) -> np.ndarray:
    return amp * np.sin(2 * np.pi * hz * T + phase)


def test_equal_forward_and_vertical_oscillation_reads_one_in_both_forms():
    v, ap = _sine(2.0), _sine(2.0, phase=np.pi / 2)  # the forward sway a quarter step out of phase
    assert cue.ap_ratio(ap, v, 0, len(T) - 1) == pytest.approx(1.0, abs=0.03)
    assert cue.ap_ratio(ap, v, 0, len(T) - 1, velocity=True) == pytest.approx(1.0, abs=0.05)


def test_a_weight_shift_without_forward_sway_reads_near_zero():
    v = _sine(2.0)
    ap = 0.05 * np.random.default_rng(0).standard_normal(len(T))  # sensor noise only
    assert cue.ap_ratio(ap, v, 0, len(T) - 1) < 0.05
    assert cue.ap_ratio(ap, v, 0, len(T) - 1, velocity=True) < 0.05


def test_a_constant_offset_does_not_count_and_the_ratio_scales_with_the_forward_sway():
    v = _sine(2.0)
    base = cue.ap_ratio(_sine(1.0), v, 0, len(T) - 1)
    assert base == pytest.approx(0.5, abs=0.02)
    assert cue.ap_ratio(_sine(1.0) + 3.0, v + 9.81, 0, len(T) - 1) == pytest.approx(base, abs=1e-9)
    assert cue.ap_ratio(_sine(2.0), v, 0, len(T) - 1) == pytest.approx(2 * base, rel=1e-9)


def test_the_velocity_form_weighs_down_a_fast_forward_jitter():
    # a forward oscillation at three times the step frequency has the same acceleration RMS as the vertical one,
    # but a third of its velocity swing: the velocity form reads it about a third
    v, ap = _sine(2.0), _sine(2.0, hz=3 * STEP_HZ)
    assert cue.ap_ratio(ap, v, 0, len(T) - 1) == pytest.approx(1.0, abs=0.03)
    assert cue.ap_ratio(ap, v, 0, len(T) - 1, velocity=True) == pytest.approx(1 / 3, abs=0.05)


def test_a_step_without_vertical_motion_or_too_short_has_no_ratio():
    assert np.isnan(cue.ap_ratio(_sine(1.0), np.zeros(len(T)), 0, len(T) - 1))
    assert np.isnan(cue.ap_ratio(_sine(1.0), _sine(2.0), 3, 4))
