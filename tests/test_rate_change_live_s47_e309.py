"""Decisions E309, B460, B461 (session 47, I4): the live Tracker and the lean replay say a unit's sustained sample-rate
change once, through the offline detection's kernel (``kernels.rate_change.RateLevels``), and E230's dropped-sample
count follows the new period."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.io.plasys import write_session
from pdrlearn.kernels.rate_change import rate_changes
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.__main__ import replay
from pdrlearn.runtime.rate_watch import RateWatch
from pdrlearn.sim.simulate import simulate
from tests.fakes import slow_foot_from

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A 100 Hz simulated walk (user 14650) and its copy whose foot unit runs at 50 Hz from 12 s on (B458's copy:
    each slower sample the mean of its pair)."""
    root = tmp_path_factory.mktemp("e309")
    sim = simulate("walk", 14650, rate_hz=100.0, seed=0, length_m=40.0)
    steady = write_session(sim, root / "steady")
    slow_foot_from(sim)
    return steady, write_session(sim, root / "changed"), sim


def _b457(tracker) -> list[str]:
    return [w for w in tracker.warnings if "B457" in w]


def test_e309_the_lean_replay_says_the_change_once_and_keeps_it_as_a_field(walks):
    steady, changed, _ = walks
    tracker, _ = replay(BUNDLE, changed)
    lines = _b457(tracker)
    assert len(lines) == 1
    assert lines[0].startswith("fAccelerometer, fGyroscope: the sample rate changed 100 -> 50 Hz at 12.0 s")
    assert "not resampled" in lines[0]
    assert tracker.rate_changes == [{"streams": ["fAccelerometer", "fGyroscope"], "t_s": 12.0, "before_hz": 100.0,
                                     "after_hz": 50.0}]
    tracker, _ = replay(BUNDLE, steady)
    assert _b457(tracker) == [] and tracker.rate_changes == []


@pytest.mark.parametrize("slow_first", [False, True])
def test_b461_the_changed_stretch_is_no_dropped_samples_live(walks, slow_first):
    """0.5 s pushes: 100 -> 50 Hz into a Tracker that learns the foot's rate from its first samples (100 Hz), and 50 ->
    100 Hz into one declared 100 Hz (the lean replay declares the files' median rate): before B461, E230 counted each
    20 ms interval of the 50 Hz stretch as dropped samples (about 1400 / 600)."""
    _, _, sim = walks
    streams = {n: sim.streams[n] for n in ("fAccelerometer", "fGyroscope")}
    if slow_first:  # the 100 Hz walk with every other sample of its first 12 s left out (each kept one its pair's mean)
        base = simulate("walk", 14650, rate_hz=100.0, seed=0, length_m=40.0)
        slow_foot_from(base, slow_first=True)
        streams = {n: base.streams[n] for n in ("fAccelerometer", "fGyroscope")}
    rates = {n: 100.0 for n in streams} if slow_first else None
    tracker = Tracker(load_bundle(BUNDLE), units=("foot",), sensors=list(streams), input_rates_hz=rates)
    t = streams["fAccelerometer"].t
    for a in np.arange(t[0], t[-1] + 0.5, 0.5):
        tracker.push({n: (s.t[(s.t >= a) & (s.t < a + 0.5)], s.values[(s.t >= a) & (s.t < a + 0.5)])
                      for n, s in streams.items()})
    tracker.flush()
    assert len(_b457(tracker)) == 1
    assert tracker.drop_stats() == {}
    assert not [w for w in tracker.warnings if "dropped samples" in w and "B457" not in w]


def test_e309_one_sample_pushes_say_it_once(walks):
    _, _, sim = walks
    tracker = Tracker(load_bundle(BUNDLE), units=("foot",), sensors=["fAccelerometer", "fGyroscope"])
    streams = {n: sim.streams[n] for n in ("fAccelerometer", "fGyroscope")}
    for _, n, i in sorted((float(t), n, i) for n, s in streams.items() for i, t in enumerate(s.t)):
        tracker.push({n: (streams[n].t[i:i + 1], streams[n].values[i:i + 1])})
    tracker.flush()
    assert len(_b457(tracker)) == 1
    assert [(c["t_s"], c["before_hz"], c["after_hz"]) for c in tracker.rate_changes] == [(12.0, 100.0, 50.0)]
    assert sorted(tracker.rate_changes[0]["streams"]) == ["fAccelerometer", "fGyroscope"]


def test_e309_not_said_where_the_session_was_read(walks):
    _, changed, _ = walks
    tracker, _ = replay(BUNDLE, changed, clip_lines=False)  # evaluate BUNDLE: read_session said it
    assert _b457(tracker) == [] and tracker.rate_changes == []


@pytest.mark.parametrize("chunk", [1, 7, 100, 1000])
def test_b460_the_live_watch_finds_what_the_offline_kernel_finds(chunk):
    rng = np.random.default_rng(3)
    cases = [np.concatenate([np.arange(0.0, 30.0, 0.01), 30.0 + np.arange(0.0, 30.0, 0.02)]),
             np.concatenate([np.arange(0.0, 30.0, 0.02), 30.0 + np.arange(0.0, 30.0, 0.01)]),
             np.concatenate([np.arange(0.0, 20.0, 0.01), 20.0 + np.arange(0.0, 20.0, 0.02),
                             40.0 + np.arange(0.0, 20.0, 0.01)]),
             np.arange(0.0, 60.0, 0.01)[rng.random(6000) > 0.05],  # B64's drops: no change
             np.delete(np.arange(0.0, 60.0, 0.01), np.r_[2000:2100])]  # a 1 s gap: no change
    b = np.concatenate([np.arange(0.0, 30.0, 0.01), 30.0 + np.arange(0.0, 30.0, 0.02)])
    cases.append(np.sort(b + rng.uniform(-0.002, 0.002, b.size)))  # a jittered clock: the same periods, exactly
    for t in cases:
        t = t + 3.7
        w, got = RateWatch(["fGyroscope"]), []
        for a in range(0, len(t), chunk):
            if chunk == 1:  # the one-sample path's (t, values) on Python floats
                w.push({}, {"fGyroscope": (float(t[a]), [0.0, 0.0, 0.0])})
            else:
                w.push({"fGyroscope": (t[a:a + chunk], np.zeros((len(t[a:a + chunk]), 3)))})
            got += w.new
        w.flush()
        got += w.new
        want = [(round(c.t_s, 1), f"{c.before_hz:.4g}", f"{c.after_hz:.4g}") for c in rate_changes(t)]
        assert [c["key"] for c in w.changes] == want
        exact = [("fGyroscope", c.t_s, c.after_hz) for c in rate_changes(t)]
        assert [(n, t_s, 1.0 / p) for n, t_s, p, _ in got] == exact
