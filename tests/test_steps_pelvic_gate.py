"""Decision 23: the waist motion gate as an option of the pelvic-gyroscope detector."""

from __future__ import annotations

import numpy as np
import pandas as pd
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.io import Session, Stream
from pdrlearn.steps import PelvicGyroStepDetector, PLLStepDetector, score_events
from pdrlearn.steps._kernels import GateState, centred_variance, motion_gate_flush, motion_gate_kernel
from tests.steps_helpers import chunked
from tests.test_steps import waist_session


def _swaying_then_walking(fs=50.0):
    """The hand-made walk, but the first 10 steps' vertical acceleration removed: the pelvis rotates as in
    walking (yaw lobes) while the trunk does not bob -- swaying on the spot."""
    s, ics = waist_session(fs=fs, n_steps=24, seed=3)
    acc = s["wAccelerometer"]
    t, v = acc.t, acc.values.copy()
    grav = v[t < 2.5].mean(axis=0)  # the standstill's gravity in the sensor frame
    cut = 0.5 * (ics[9] + ics[10])
    rng = np.random.default_rng(1)
    v[t < cut] = grav + rng.normal(0, 0.05, (int((t < cut).sum()), 3))
    streams = {"wAccelerometer": Stream("wAccelerometer", t, v), "wGyroscope": s["wGyroscope"]}
    return Session("sway_walk", streams, extras=s.extras), ics, cut


def test_gate_off_by_default_keeps_the_thesis_chain():
    assert PelvicGyroStepDetector().gate_var == 0.0
    s, ics = waist_session(fs=50.0, n_steps=24, seed=3)
    a = PelvicGyroStepDetector().detect(s)
    b = PelvicGyroStepDetector(gate_var=0.0, gate_window_s=5.0).detect(s)
    pd.testing.assert_frame_equal(a, b)


def test_gate_drops_pelvic_lobes_without_trunk_motion_and_keeps_walking():
    s, ics, cut = _swaying_then_walking()
    thesis = PelvicGyroStepDetector().detect(s)
    gated = PelvicGyroStepDetector(gate_var=0.25).detect(s)
    # without the gate the swaying lobes are steps (the thesis' rule sees only the gyroscope)
    assert (thesis["event_s"] < cut - 1.0).sum() >= 6
    # with it, none more than the gate's half window before the walking starts
    assert (gated["event_s"] < cut - 1.0).sum() == 0
    walk = ics[ics > cut + 1.0]
    sc = score_events(gated.loc[gated["event_s"] > cut + 1.0, "event_s"], walk[:-1], tolerance_s=0.3)
    assert sc["recall"] >= 0.9, sc


@settings(max_examples=10, deadline=None)
@given(cuts=st.lists(st.integers(0, 80), min_size=1, max_size=10))
def test_gated_online_equals_offline(cuts):
    s, _, _ = _swaying_then_walking(fs=20.0)
    det = PelvicGyroStepDetector(gate_var=0.25)
    offline = det.detect(s)
    online = chunked(det, det._inputs(s), cuts)
    assert len(offline) > 5
    pd.testing.assert_frame_equal(offline.reset_index(drop=True), online, check_dtype=False)


def test_motion_gate_kernel_decides_after_half_a_window():
    t = np.arange(0, 10, 0.1)
    v = np.where(t >= 5.0, np.sin(2 * np.pi * 2 * t), 0.0)  # still until 5 s, then variance 0.5
    ev = [(2.0, 1.9, 2.1, 1.0, {}), (7.0, 6.9, 7.1, 1.0, {})]
    out, st_ = motion_gate_kernel(t[:75], v[:75], ev, GateState(), 2.0, 0.25)
    assert out == []  # 7.0 s waits for samples up to 8.0 s; 2.0 s is still (variance 0)
    out, st_ = motion_gate_kernel(t[75:], v[75:], [], st_, 2.0, 0.25)
    assert [e[0] for e in out] == [7.0]
    assert motion_gate_flush(st_, 2.0, 0.25) == []
    ok, var = centred_variance(t, v, np.array([2.0, 7.0]), 1.0)
    assert ok.all() and var[0] == 0.0 and abs(var[1] - 0.5) < 0.05


def test_pll_gate_on_the_shared_variance_kernel_still_finds_the_steps():
    """The PLL's gate now calls `centred_variance` (its real-recording outputs were checked byte-identical
    before and after, decision 23); the hand-made walk is still found."""
    s, ics = waist_session(fs=20.0, n_steps=40, seed=5)
    steps = PLLStepDetector().detect(s)
    sc = score_events(steps["event_s"], ics, tolerance_s=0.2)
    assert sc["f1"] >= 0.95, sc
