"""Decisions B213 / B214: B203's frozen foot IMU (force sensors that step beside a foot IMU that does not move),
judged live by the ``Tracker`` on blocks of stream time with offline's test, and what the live ``Tracker`` does with
a foot stream that stops updating mid-session."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.frozen_foot import FORCE_STEPS_MIN, LIVE_BLOCK_S, frozen_foot_evidence
from pdrlearn.runtime import Tracker
from pdrlearn.runtime.guard import FrozenFootWatch
from tests.runtime_helpers import per_timestamp, time_chunks

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
TAG = "(decision B213)"


@pytest.fixture(scope="module")
def walk():
    from pdrlearn import sim

    return sim.simulate("walk", 2, length_m=40)  # 43.5 s, 20 Hz, foot IMU + force sensors + waist


def _held(s, at_s: float | None):
    """``s`` with the foot IMU frozen: from the start at 1 g / 0 rad/s (``at_s`` None, the B203 trial's), or
    holding the values of ``at_s`` from then on (a link that re-sends its last sample)."""
    out = copy.deepcopy(s)
    for name in ("fAccelerometer", "fGyroscope"):
        st = out.streams[name]
        if at_s is None:
            st.values[:] = [0.0, 9.81, 0.0] if name == "fAccelerometer" else 0.0
        else:
            i = int(np.searchsorted(st.t, at_s))
            st.values[i:] = st.values[i]
    return out


def _run(s, how: str):
    """The steps and B213 lines of ``s`` pushed whole, in 1 s chunks, or one sample time at a time."""
    tr = Tracker(BUNDLE)
    pushes = ([{n: (st.t, st.values) for n, st in s.streams.items()}] if how == "whole"
              else [c for _, c in time_chunks(s, 1.0)] if how == "1 s" else per_timestamp(s))
    steps = []
    for p in pushes:
        steps += tr.push(p)
    steps += tr.flush()
    return steps, [w for w in tr.warnings if TAG in w], tr


def test_kernel_is_offlines_test():
    rng = np.random.default_rng(0)
    n = 400
    still_acc, still_gyr = np.tile([0.0, 9.81, 0.0], (n, 1)), np.zeros((n, 3))
    steps = (np.arange(n) // 50) % 2 == 1  # loaded 4 times (50 samples off, 50 on)
    force = [np.where(steps, 600.0, 5.0) + rng.normal(0, 1, n)]
    got = frozen_foot_evidence(still_acc, still_gyr, force)
    assert got is not None and got[0] == 4 and got[1] == 0.0
    # a walking foot (B37's |acc| sd, B91's swing) is no frozen IMU, whatever the force sensors do
    moving = still_acc + np.column_stack([np.zeros(n), np.sin(np.arange(n) / 3.0) * 3.0, np.zeros(n)])
    assert frozen_foot_evidence(moving, still_gyr, force) is None
    swing = still_gyr.copy()
    swing[::20, 2] = 6.0  # 5 % of the samples at 6 rad/s: the 99th percentile swings
    assert frozen_foot_evidence(still_acc, swing, force) is None
    # fewer loads than FORCE_STEPS_MIN (a subject standing still loads once)
    once = [np.where(np.arange(n) > 200, 600.0, 5.0)]
    assert frozen_foot_evidence(still_acc, still_gyr, once) is None and FORCE_STEPS_MIN == 3
    # a reference given from earlier blocks: this block's small values are no loads
    assert frozen_foot_evidence(still_acc, still_gyr, [force[0] / 100.0], refs=[600.0]) is None


@pytest.mark.parametrize("how", ["whole", "1 s", "one sample"])
def test_frozen_from_the_start_is_warned_once_whatever_the_pushes(walk, how):
    steps, lines, tr = _run(_held(walk, None), how)
    assert len(lines) == 1, tr.warnings
    assert lines[0].startswith("the foot IMU did not move from 0.0 to 10.0 s: The force sensors (fForceA, fForceB) "
                               "load ")
    assert sum(abs(s.length_m) for s in steps) == 0.0  # what the line is about: nothing is tracked
    assert tr._frozen_foot is None  # decided: the watch and its samples are dropped
    # the same line from every push pattern (chunk-size invariant)
    assert lines == _run(_held(walk, None), "whole")[1]


@pytest.mark.parametrize("how", ["whole", "1 s", "one sample"])
def test_a_clean_walk_is_not_warned_and_the_watch_holds_under_two_blocks(walk, how):
    steps, lines, tr = _run(walk, how)
    assert lines == [] and sum(abs(s.length_m) for s in steps) > 35.0
    # bounded memory: the watch keeps the samples of the open block (and what arrived past it) only
    w = FrozenFootWatch()
    most = 0
    for p in per_timestamp(walk) if how == "one sample" else [c for _, c in time_chunks(walk, 1.0)]:
        arrays = {n: tv for n, tv in p.items()}
        assert w.push(arrays) is None
        most = max(most, sum(len(np.atleast_1d(it[0])) for v in w.items.values() for it in v))
    assert w.k == int(43.45 // LIVE_BLOCK_S)  # every whole block judged
    assert most <= 4 * (LIVE_BLOCK_S + 1.0) * 20 + 4


def test_foot_imu_that_stops_updating_mid_walk_is_warned_b214(walk):
    """B214: the foot IMU re-sending its sample of 15 s (force sensors and waist go on). Before B213 the tracker
    emitted 9 strides (12.12 m of 40 m) and nothing else: B120's frozen-sample line needs the unit's other sensor
    moving, and both foot sensors were held."""
    held = _held(walk, 15.0)
    lines = {how: _run(held, how)[1] for how in ("whole", "1 s", "one sample")}
    assert lines["whole"] == lines["1 s"] == lines["one sample"] and len(lines["whole"]) == 1
    # the first block wholly after the freeze (10-20 s still holds 5 s of walking)
    assert lines["whole"][0].startswith("the foot IMU did not move from 20.0 to 30.0 s: ")


def test_foot_stream_whose_samples_stop_mid_walk_is_refused_by_e23_b214(walk):
    """B214: the foot unit's samples stop arriving at 15 s while the waist goes on: E23's one line names the
    stream (pushed in 1 s chunks, as live), no silent short track."""
    tr = Tracker(BUNDLE)
    with pytest.raises(DataError, match=r"^fAccelerometer: no samples since 14\.95 s while other sensors are at "):
        for t0, chunk in time_chunks(walk, 1.0):
            tr.push({n: tv if not n.startswith("f") or t0 < 15.0 else (tv[0][:0], tv[1][:0])
                     for n, tv in chunk.items()})
