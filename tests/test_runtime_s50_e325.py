"""Decision E325: each streamed stride says why it is not reliable (``Step.flags``): ``"clipped"`` by the clipping
kernel (B77 / B311 / B456) on the stride's own foot samples, ``"running"`` by the session's "looks like running" rule
(L95 / W144, :mod:`pdrlearn.kernels.gait_range`) on the stride's own cadence and speed. Short simulated foot walks
(test users 17751 / 17752, the shipped bundle, 1 s pushes); the running stride made by the simulator's step override
(1.0 m steps every 0.33 s: 3 m/s at 182 steps/min, as trial s50t1's run)."""

from __future__ import annotations

import dataclasses
import logging
import math

import numpy as np
import pytest

from pdrlearn.kernels import gait_range
from pdrlearn.runtime import Tracker
from pdrlearn.runtime.tracker import Step
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import gait as offline
from tests.lean_helpers import ROOT
from tests.runtime_helpers import replay

BUNDLE = ROOT / "models" / "plasys-sim-default"


def _walk(user: int, **override):
    u = dataclasses.replace(UserProfile.from_seed(user), **override)
    s = simulate_path(parse_route("stand:2, straight:14, stand:2"), u, rate_hz=50.0, seed=1, scenario="route")
    s.streams = {n: st for n, st in s.streams.items() if n in ("fAccelerometer", "fGyroscope")}
    return s


def _stream(s, **kw):
    logging.disable(logging.WARNING)
    try:
        tr = Tracker(BUNDLE, units=("foot",), tasks=[], sensors=list(s.streams),
                     input_rates_hz={n: 50.0 for n in s.streams}, **kw)
        return replay(tr, s, chunk_s=1.0)
    finally:
        logging.disable(logging.NOTSET)


@pytest.fixture(scope="module")
def walk():
    return _walk(17751)


def test_the_offline_rule_is_the_kernel_s_and_judges_one_stride():
    """The session check reads the moved kernels (one implementation), and a stride's own figures give its verdict."""
    assert offline.range_side is gait_range.range_side and offline.fast_gait is gait_range.fast_gait
    assert "looks like running" in offline.gait_range_warning({"median_cadence_spm": 182.0, "median_speed_mps": 3.0})
    assert gait_range.running_stride(2.0, 0.66)  # 182 steps/min, 3.0 m/s
    assert not gait_range.running_stride(1.4, 1.1)  # walking
    assert not gait_range.running_stride(1.0, 0.6)  # 200 steps/min at 1.7 m/s: short fast steps (W144), not running
    assert not gait_range.running_stride(3.0, math.nan)  # no stride time: not judged
    # without an IC the start-to-start time of the emitted strides is the stride time (L66 / L80's kernel)
    prev = (10.0, 10.4, math.nan)
    assert Tracker._running(Step(10.66, 11.0, length_m=2.0), prev)
    assert not Tracker._running(Step(11.5, 12.0, length_m=2.0), prev)  # 1.5 s: 80 steps/min, 1.33 m/s


def test_a_walk_has_no_flags_and_a_run_is_flagged_running_stride_by_stride(walk):
    steps = _stream(walk)
    assert len(steps) >= 8 and all(st.flags == () for st in steps)
    run = _stream(_walk(17752, step_length_m=1.0, step_time_s=0.33))
    flagged = [st for st in run if "running" in st.flags]
    assert len(flagged) >= len(run) - 3, [(round(st.end_s, 2), st.flags) for st in run]
    assert "running" not in run[0].flags  # the first stride has no stride time
    assert all("clipped" not in st.flags for st in run)


def test_a_stride_with_clipped_foot_samples_is_flagged_clipped(walk):
    s = _walk(17751)
    g = s.streams["fGyroscope"]
    inside = (g.t >= 8.0) & (g.t < 11.0)
    g.values[inside] = np.clip(g.values[inside], -4.5, 4.5)  # a +-258 deg/s rail held (B77; the walk peaks 9.6 rad/s)
    steps = _stream(s)
    clipped = [st for st in steps if "clipped" in st.flags]
    assert clipped and all(st.end_s >= 8.0 and st.start_s < 11.0 for st in clipped)
    assert any(st.start_s < 11.0 and st.end_s >= 8.0 for st in clipped)
    # the other strides are not, and without the input checks no stride is judged
    assert all(st.flags == () for st in steps if st.end_s < 8.0 or st.start_s >= 11.0)
    assert all(st.flags == () for st in _stream(s, check_input=False))
