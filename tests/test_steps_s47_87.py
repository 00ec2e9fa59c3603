"""Steps decision 87 (session 47, trial T1 F2): at a child's short stride the foot accelerometer's 8 Hz event signal
merges the terminal-swing deceleration and the impact into one peak, 60-80 ms before the contact; a stride whose 8 Hz
impact comes under 0.95 s after the previous contact takes its impact at 12 Hz, offline and streamed alike."""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.io.session import Session, Stream
from pdrlearn.kernels import contact as C
from pdrlearn.steps import AccelStepDetector

G = 9.80665


def _bump(t, c, w, h):
    return h * np.exp(-0.5 * ((t - c) / w) ** 2)


def _child_foot(stride_s: float, swing_s: float = 0.28, n: int = 12, fs: float = 100.0):
    """|acc| of a foot whose terminal-swing deceleration (32 m/s^2, 75 ms before the IC) sits close to a sharp
    impact (22 m/s^2 at +10 ms), as the trial's simulated child (c03_sm) shows it; contacts every ``stride_s``."""
    ics = 2.0 + swing_s + stride_s * np.arange(n)
    t = np.arange(int((ics[-1] + 2.0) * fs)) / fs
    dyn = np.zeros_like(t)
    for ic in ics:
        dyn += _bump(t, ic - swing_s + 0.04, 0.03, 20.0) + _bump(t, ic - 0.075, 0.025, 32.0) + _bump(t, ic + 0.01,
                                                                                                   0.006, 22.0)
    acc = np.outer(G + dyn, [0.0, 0.0, 1.0]) + np.random.default_rng(0).normal(0, 0.03, (t.size, 3))
    return Session("child", {"fAccelerometer": Stream("fAccelerometer", t, acc)}, check_units=False), ics


def _errors_ms(session, ics, **kw):
    ev = AccelStepDetector(**kw).detect(session)["event_s"].to_numpy(float)
    assert len(ev) == len(ics)
    return 1000.0 * (ev - ics)


def test_a_short_stride_is_dated_at_its_impact_not_the_terminal_swing():
    s, ics = _child_foot(0.8)
    before = _errors_ms(s, ics, short_period_s=0.0)  # decision 3 alone: the deceleration's peak
    after = _errors_ms(s, ics)
    assert (before < -60).all()
    assert before[0] == after[0]  # a walk's first contact has no previous one: 8 Hz
    assert (np.abs(after[1:]) < 20).all()


def test_an_adult_stride_keeps_decision_3():
    s, ics = _child_foot(1.1, swing_s=0.42)
    np.testing.assert_array_equal(_errors_ms(s, ics), _errors_ms(s, ics, short_period_s=0.0))


def test_the_streamed_impact_is_offline_one_given_the_previous_contact():
    s, _ = _child_foot(0.8)
    acc = s["fAccelerometer"]
    prev = math.nan
    for _, row in AccelStepDetector().detect(s).iterrows():
        m = (acc.t >= row["start_s"] - 0.3) & (acc.t <= row["end_s"])
        ic = C.impact_time(acc.t[m], acc.values[m], prev_ic_s=prev)
        assert abs(ic - row["event_s"]) < 1e-9
        prev = ic
