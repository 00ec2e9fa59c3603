"""Steps decisions 93 / 94 (docs/decisions/steps.md): the domain of steps 91's rhythm re-take - a foot rate of at
least ``short_min_rate_hz`` and a swing spanning at most ``short_max_amp``; outside it decision 3's 8 Hz impact,
offline and streamed alike."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels import contact as C
from tests.cli_helpers import insole_free_walk
from tests.test_contact_s48_steps91 import CHILD_15219


@pytest.fixture(autouse=True)
def _quiet():
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


def test_short_stride_is_not_a_swing_spanning_more_than_the_cap():
    assert C.short_stride(0.7, 0.95) and not C.short_stride(1.0, 0.95)
    assert C.short_stride(0.7, 0.95, 40.0, 65.0)  # a child's swing
    assert not C.short_stride(0.7, 0.95, 90.0, 65.0)  # a race walker's
    assert C.short_stride(0.7, 0.95, 90.0, 0.0)  # 0: every swing (steps 91)


def _stride(fs: float):
    """A short stride's |acc| (deceleration, impact, tail; steps 91's synthetic bumps) as (t, acc (n, 3))."""
    t = np.arange(int(1.6 * fs)) / fs
    m = C.GRAVITY + sum(h * np.exp(-0.5 * ((t - c) / 0.012) ** 2)
                        for c, h in [(0.5, 10.0), (0.93, 50.0), (1.0, 45.0), (1.04, 22.0)])
    return t, np.column_stack([np.zeros_like(m), np.zeros_like(m), m])


@pytest.mark.parametrize("fs", [50.0, 100.0])
def test_impact_time_re_takes_only_at_90_hz_and_up(fs):
    t, acc = _stride(fs)
    prev = 1.0 - 0.7  # a 0.7 s stride: the rhythm's cutoff is ~19 Hz
    dec3 = C.impact_time(t, acc, prev_ic_s=prev, short_period_s=0.0)
    steps91 = C.impact_time(t, acc, prev_ic_s=prev, min_rate_hz=0.0, max_amp=0.0)
    gated = C.impact_time(t, acc, prev_ic_s=prev, min_rate_hz=90.0, max_amp=0.0)
    assert steps91 != dec3  # the re-take moves this stride's contact at either rate
    assert gated == (steps91 if fs >= 90 else dec3)
    # steps 94: a swing spanning more than the cap keeps the 8 Hz impact; under it the re-take
    assert C.impact_time(t, acc, prev_ic_s=prev, min_rate_hz=0.0, max_amp=5.0) == dec3
    assert C.impact_time(t, acc, prev_ic_s=prev, min_rate_hz=0.0, max_amp=500.0) == steps91


@pytest.fixture(scope="module")
def child50(tmp_path_factory):
    """Steps 88's development child u15219 (1.45 m, 0.36 s steps) on a short walk at a 50 Hz foot rate."""
    return insole_free_walk(tmp_path_factory.mktemp("steps93") / "u15219", *CHILD_15219, "--rate", "50")


def _events(session, **kw) -> np.ndarray:
    from pdrlearn.steps.detectors import AccelStepDetector

    return np.asarray(AccelStepDetector(**kw).detect(session)["event_s"], float)


def test_offline_detector_keeps_decision_3_outside_the_domain(child50):
    dec3 = _events(child50, short_period_s=0.0)
    steps91 = _events(child50, short_min_rate_hz=0.0, short_max_amp=0.0)
    assert len(dec3) == len(steps91) >= 8 and not np.array_equal(dec3, steps91)  # 50 Hz: steps 91 re-dates
    np.testing.assert_array_equal(_events(child50, short_min_rate_hz=90.0, short_max_amp=0.0), dec3)
    np.testing.assert_array_equal(_events(child50, short_min_rate_hz=0.0, short_max_amp=1.0), dec3)
    np.testing.assert_array_equal(_events(child50, short_min_rate_hz=0.0, short_max_amp=500.0), steps91)


def test_the_swing_span_cap_is_the_default_and_the_rate_gate_is_not():
    from pdrlearn.runtime.clocks import ACCEL
    from pdrlearn.steps.detectors import AccelStepDetector

    det = AccelStepDetector()
    assert (det.short_max_amp, det.short_min_rate_hz) == (C.SHORT_MAX_AMP, C.SHORT_MIN_RATE_HZ) == (65.0, 0.0)
    assert (ACCEL["short_max_amp"], ACCEL["short_min_rate_hz"]) == (65.0, 0.0)


@pytest.fixture(scope="module")
def race50(tmp_path_factory):
    """A race walker (steps 94's development range: 0.95 m steps in 0.29 s) on a short walk at 50 Hz."""
    return insole_free_walk(tmp_path_factory.mktemp("steps94") / "race", "--route", "stand:2, straight:12, stand:2",
                            "--rocker", "smooth", "--rate", "50", "--user-seed", "16061", "--step-length", "0.95",
                            "--step-time", "0.29")


def test_a_race_walkers_swing_keeps_decision_3_offline_and_streamed(race50):
    from pdrlearn.track import get_pipeline

    dec3 = _events(race50, short_period_s=0.0)
    assert not np.array_equal(_events(race50, short_max_amp=0.0), dec3)  # steps 91 re-dates these strides
    np.testing.assert_array_equal(_events(race50), dec3)  # steps 94, the default: every swing spans over 65
    st = get_pipeline("plasys")(race50, streaming=True, contacts=True).steps["event_s"].to_numpy(float)
    st = st[np.isfinite(st)][2:]  # the walk's opening strides are cut differently
    assert len(st) >= 4
    # the streamed contact reads the stride's span as the detector does (contact.swing_span): decision 3's impact
    np.testing.assert_allclose(st, [dec3[np.argmin(np.abs(dec3 - x))] for x in st], rtol=0, atol=1e-9)
