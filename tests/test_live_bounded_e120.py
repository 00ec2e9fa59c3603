"""Decisions E120 / E121: the live ``Tracker``'s clock check (L177) and position-fix filter (D19) do bounded work and
hold bounded state however long the stream runs. The clock estimate reads the last 256 foot events (E120: up to
that many it is the estimate over every event, as before; longer streams read the last window, the offset at its
own ``ref_s``, L198); the fix filter keeps the steps since its last fix as a few sums (E121), with the same estimate.
Bounds are asserted by counting (events the estimate sees, list lengths), never by timing."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.kernels.fixes import FixConfig, StepFixState
from pdrlearn.runtime import Tracker, clocks, load_bundle
from pdrlearn.runtime.replay import replay_chunks
from pdrlearn.sim import simulate

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # foot + waist units
ALIGN = clocks.align_events


@pytest.fixture(scope="module")
def long_walk():
    """A 700 m walk (fresh simulated user 4140, 20 Hz): about 450 strides, longer than the 256-event window."""
    logging.disable(logging.WARNING)
    try:
        return simulate("walk", 4140, length_m=700, rate_hz=20.0)
    finally:
        logging.disable(logging.NOTSET)


def _feed(session, monkeypatch, *, drift=0.0, offset_s=0.0):
    """The check's sensors pushed in 1 s chunks, as ``Tracker._check_clocks`` feeds them (waist clock
    ``t (1 + drift) + offset_s``, the simulator's convention, L199); returns the check and, for every estimate made,
    the numbers of foot and waist events ``align_events`` read and the estimate."""
    seen = []
    def counting(foot, waist):
        est = ALIGN(foot, waist)
        seen.append((len(foot), len(waist), est))
        return est

    monkeypatch.setattr(clocks, "align_events", counting)
    streams = {}
    for n in clocks.SENSORS:
        st = session.streams[n]
        streams[n] = (st.t * (1.0 + drift) + offset_s if n.startswith("w") else st.t, st.values)
    cc = clocks.replay_check(streams, 1.0)
    return cc, seen


def test_the_clock_estimate_reads_a_bounded_window(long_walk, monkeypatch):
    """Every estimate reads at most 256 foot and 1024 waist events (main: every event since the start, ~450 at the
    end), one every 20 strides as before; the held lists stay within the window."""
    cc, seen = _feed(long_walk, monkeypatch)
    assert max(f for f, _, _ in seen) <= 256
    assert max(w for _, w, _ in seen) <= 1024
    assert cc._foot_seen > 400  # the stream is longer than the window
    # still an estimate every 20 foot strides (a 64-sample block brings ~3), and one at the end
    assert len(seen) >= cc._foot_seen // 25
    assert seen[-1][0] == 256 and len(cc._foot_events) == 256
    assert len(cc._waist_events) <= 2 * 256 + 50  # the waist sees both feet; the pad adds a few
    assert cc.estimate["ref_s"] > long_walk.streams["fAccelerometer"].t[-1] / 3  # the offset over the last window


def test_up_to_the_window_the_estimate_is_the_one_over_every_event(long_walk, monkeypatch):
    """The same stream with an unbounded window (main's estimate): every estimate made before the window filled is
    the same dict exactly; after it, the windowed estimate reads the last 256 foot events."""
    _, windowed = _feed(long_walk, monkeypatch)
    monkeypatch.setattr(clocks, "WINDOW_FOOT_EVENTS", 10**9)
    monkeypatch.setattr(clocks, "WINDOW_WAIST_EVENTS", 10**9)
    _, every = _feed(long_walk, monkeypatch)
    assert len(windowed) == len(every)
    early = [i for i, (f, _, _) in enumerate(every) if f <= 256]
    assert len(early) >= 10
    for i in early:
        assert windowed[i] == every[i]
    assert every[-1][0] > 400 and windowed[-1][0] == 256
    # both are the same clocks' offset (clean: the detectors' gap, L161), each at its own reference
    assert abs(windowed[-1][2]["offset_s"] - every[-1][2]["offset_s"]) < 0.02


def test_a_drift_is_read_about_the_window_reference(long_walk, monkeypatch):
    """A 300 ppm drifting waist clock 0.05 s late at t = 0 (0.19 s late at the end: under half a step period, which
    L161's estimate cannot tell apart): the last window's estimate reads the drift within 100 ppm and the offset at its
    ``ref_s`` (inside the window) as 0.05 + drift x ref_s plus the clean walk's detector gap, within 0.01 s."""
    clean, _ = _feed(long_walk, monkeypatch)
    cc, _ = _feed(long_walk, monkeypatch, drift=3e-4, offset_s=0.05)
    est = cc.estimate
    assert clean.estimate["matched"] >= 200 and est["matched"] >= 200
    assert est["drift"] == pytest.approx(3e-4, abs=1e-4)
    assert min(cc._foot_events) <= est["ref_s"] <= max(cc._foot_events)
    assert est["offset_s"] - (0.05 + 3e-4 * est["ref_s"]) == pytest.approx(clean.estimate["offset_s"], abs=0.01)


def test_the_live_tracker_state_stays_bounded(long_walk):
    """The Tracker on the long walk, no fixes given: the clock check holds the window's events and the fix filter
    no steps (main: every stride of the stream in both)."""
    tr = Tracker(load_bundle(BUNDLE))
    streams = {n: (st.t, st.values) for n, st in long_walk.streams.items() if len(st)}
    n_steps = 0
    for push in replay_chunks(streams, 1.0):
        n_steps += len(tr.push(push))
    n_steps += len(tr.flush())
    assert n_steps > 400
    assert len(tr._clock._foot_events) <= 256 and len(tr._clock._waist_events) <= 1024
    state = tr._fixes.state
    assert state._seg_n == n_steps  # every step went through the filter ...
    assert len(state.seg_inc) == len(state.seg_rows) == len(state.seg_head) == 0  # ... and none is held


def _drive(state: StepFixState, steps, fixes) -> list:
    out = []
    for k, (length, heading) in enumerate(steps, start=1):
        state.predict(length, heading, k)
        if k in fixes:
            state.correct(np.asarray(fixes[k]), 0.8, k)
        out.append((state.x.copy(), state.P.copy(), state.offset))
    return out


@pytest.mark.parametrize("yaw", ["chord", "last", None])
def test_the_compact_segment_gives_the_same_estimate(yaw):
    """E121: StepFixState(segment=False) (the live filter) and the offline filter with every step kept give the same
    estimate, covariance and heading offset after every step, over 3000 steps with a fix every 150 to 700 steps and
    a heading bias the yaw feedback corrects; the compact one holds no step."""
    rng = np.random.default_rng(4141)
    steps = [(1.3 + 0.1 * rng.standard_normal(), 0.002 * k + 0.05 * rng.standard_normal()) for k in range(3000)]
    truth = np.cumsum([[L * math.cos(h + 0.1), L * math.sin(h + 0.1)] for L, h in steps], axis=0)
    at = np.cumsum(rng.integers(150, 700, size=10))
    fixes = {int(k): truth[k - 1] + rng.normal(0, 0.5, 2) for k in at if k <= len(steps)}
    cfg = FixConfig(yaw_feedback=yaw)
    full = StepFixState(cfg, (0.0, 0.0), 1.0, 0.0)
    compact = StepFixState(cfg, (0.0, 0.0), 1.0, 0.0, segment=False)
    a, b = _drive(full, steps, fixes), _drive(compact, steps, fixes)
    for (xa, pa, oa), (xb, pb, ob) in zip(a, b, strict=True):
        np.testing.assert_allclose(xb, xa, rtol=0, atol=1e-9)
        np.testing.assert_allclose(pb, pa, rtol=0, atol=1e-12)
        assert ob == pytest.approx(oa, abs=1e-12)
    assert len(fixes) >= 4 and compact.yaw_corrections == full.yaw_corrections == (len(fixes) if yaw else 0)
    assert len(full.seg_inc) > 0 and compact.seg_inc == [] and compact._seg_n == len(steps) - max(fixes)


def test_the_compact_segment_refuses_the_feedback_that_reads_every_step():
    with pytest.raises(ValueError, match="segment=False"):
        StepFixState(FixConfig(yaw_feedback="mean"), (0.0, 0.0), 1.0, 0.0, segment=False)
    with pytest.raises(ValueError, match="segment=False"):
        StepFixState(FixConfig(scale_feedback=True), (0.0, 0.0), 1.0, 0.0, segment=False)
