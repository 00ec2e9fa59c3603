"""Steps decision 32 (docs/decisions/steps.md): the foot contacts between the samples - the force detector's
stance onset by the line of its threshold crossing, the accelerometer detector's impact by the parabola of its
peak - offline and streamed (E49/E50) alike."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.io.session import Session, Stream
from pdrlearn.kernels import contact as C
from pdrlearn.steps import AccelForceStepDetector, AccelStepDetector
from tests.test_steps import foot_session

G = C.GRAVITY


def test_peak_time_is_the_vertex_of_the_parabola():
    """Numerical Recipes eq. 10.3.1 on samples of e = 5 - 3 (t - 0.537)^2: the vertex 0.537, evenly or unevenly
    sampled; a symmetric peak stays at its sample; collinear points (no curvature) keep the middle sample; a
    plateau's vertex lies half an interval on (the clamp)."""
    e = lambda t: 5.0 - 3.0 * (t - 0.537) ** 2  # noqa: E731
    assert C.peak_time(0.5, 0.55, 0.6, e(0.5), e(0.55), e(0.6)) == pytest.approx(0.537, abs=1e-12)
    assert C.peak_time(0.49, 0.55, 0.62, e(0.49), e(0.55), e(0.62)) == pytest.approx(0.537, abs=1e-12)
    assert C.peak_time(1.0, 1.05, 1.1, 2.0, 3.0, 2.0) == pytest.approx(1.05, abs=1e-12)
    assert C.peak_time(1.0, 1.05, 1.1, 1.0, 2.0, 3.0) == 1.05
    assert C.peak_time(1.0, 1.05, 1.1, 1.0, 3.0, 3.0) == pytest.approx(1.075, abs=1e-12)


def test_crossing_time_is_the_line_between_the_samples():
    """A level of 25 between 0 at 2.00 s and 100 at 2.05 s is reached at 2.0125 s; clamped to the interval; a
    falling pair keeps the later sample."""
    assert C.crossing_time(2.0, 2.05, 0.0, 100.0, 25.0) == pytest.approx(2.0125, abs=1e-12)
    assert C.crossing_time(2.0, 2.05, 30.0, 100.0, 25.0) == 2.0
    assert C.crossing_time(2.0, 2.05, 100.0, 50.0, 25.0) == 2.05


def _ramp_session(fs=20.0, n=10, seed=3):
    """A foot whose combined force rises on a straight line through 10 % of its 1000 N plateau exactly at each true
    contact ``t_c`` (0 N at t_c - 0.05 s, 1000 N at t_c + 0.45 s), off during a 0.45 s swing whose |acc| bumps by
    5 m/s^2; the contacts fall anywhere between the samples."""
    rng = np.random.default_rng(seed)
    tc = 2.0 + np.cumsum(1.1 + rng.uniform(-0.04, 0.04, n))
    t = np.arange(int((tc[-1] + 2.0) * fs)) / fs
    f = np.full(t.size, 1000.0)
    dyn = np.zeros(t.size)
    for c in tc:
        sw = (t >= c - 0.5) & (t < c - 0.05)
        f[sw] = 0.0
        dyn[sw] = 5.0 * np.sin(np.pi * (t[sw] - (c - 0.5)) / 0.45)
        up = (t >= c - 0.05) & (t < c + 0.45)
        f[up] = 2000.0 * (t[up] - c) + 100.0
    acc = np.column_stack([np.zeros(t.size), np.zeros(t.size), G + dyn])
    streams = {"fAccelerometer": Stream("fAccelerometer", t, acc),
               "fForceA": Stream("fForceA", t, f), "fForceB": Stream("fForceB", t, np.zeros(t.size))}
    return Session("ramp", streams), t, acc, f, tc


def test_force_onset_between_samples_is_the_true_crossing_offline_and_streamed(monkeypatch):
    """Decision 32: the force detector's onset is the line's 10 % crossing, i.e. each true contact to 1e-9 s; whole
    samples (``subsample=False``, the sample at or after it) are up to one 0.05 s sample late. The streamed onset
    (E50, ``force_onset`` on one stride's samples) gives the same time with ``SUBSAMPLE`` on."""
    s, t, acc, f, tc = _ramp_session()
    sub = AccelForceStepDetector(subsample=True).detect(s)["event_s"].to_numpy(float)
    whole = AccelForceStepDetector(subsample=False).detect(s)["event_s"].to_numpy(float)
    assert len(sub) == len(whole) == len(tc)
    np.testing.assert_allclose(sub, tc, atol=1e-9)
    assert np.all(whole >= tc - 1e-9) and np.all(whole - tc < 0.05 + 1e-9) and (whole - tc).max() > 0.02
    monkeypatch.setattr(C, "SUBSAMPLE", True)
    assert AccelForceStepDetector().detect(s)["event_s"].to_numpy(float) == pytest.approx(sub, abs=1e-12)
    for c in tc[1:]:
        m = (t >= c - 0.9) & (t <= c + 0.3)
        ic = C.force_onset(t[m], acc[m], np.column_stack([f[m], np.zeros(m.sum())]))
        assert ic == pytest.approx(c, abs=1e-9)


@pytest.mark.parametrize("fs", [20.0, 100.0])
def test_impact_between_samples_follows_the_contact(fs):
    """Decision 32 on the hand-made foot (impact bump 0.03 s after each contact, contacts anywhere between the
    samples): at 20 Hz the parabola's contacts scatter around the true ones less than half as much as the peak
    samples (whose rounding alone is 0.05 / sqrt(12) = 14 ms); at 100 Hz both are within 3 ms SD; the mean offset
    moves by under one sample."""
    s, ics = foot_session(fs=fs, n_strides=30, seed=11, jitter=0.1)
    err = {}
    for sub in (False, True):
        ev = np.sort(AccelStepDetector(subsample=sub).detect(s)["event_s"].to_numpy(float))
        assert len(ev) == len(ics)
        err[sub] = ev - ics
    if fs == 20.0:
        assert err[True].std() < 0.5 * err[False].std() and err[False].std() > 0.01
    else:
        assert err[True].std() < 0.003 and err[False].std() < 0.004
    assert abs(err[True].mean() - err[False].mean()) < 1.0 / fs


def test_streamed_impact_between_samples_is_offline_one(monkeypatch):
    """With ``SUBSAMPLE`` on, the streamed impact (E49, ``impact_time`` on one stride's samples) is the offline
    detector's contact: the same peak, the same parabola, the same group delay."""
    monkeypatch.setattr(C, "SUBSAMPLE", True)
    s, ics = foot_session(fs=20.0, n_strides=12, seed=4, jitter=0.1)
    off = AccelStepDetector().detect(s)
    acc = s["fAccelerometer"]
    for _, row in off.iterrows():
        m = (acc.t >= row["start_s"] - 0.3) & (acc.t <= row["end_s"])
        ic = C.impact_time(acc.t[m], acc.values[m])
        assert math.isfinite(ic) and ic == pytest.approx(row["event_s"], abs=1e-6)
