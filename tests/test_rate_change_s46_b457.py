"""Decision B457 (session 46, FG, trial T3 finding F5): a sustained change of a unit's sample rate mid-recording is
told from dropped samples and said in one line."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.io.plasys import write_session
from pdrlearn.io.session import Stream
from pdrlearn.kernels.rate_change import rate_changes
from pdrlearn.sim.simulate import simulate
from tests.fakes import slow_foot_from


def _changed(rate0: float, rate1: float, at: float, end: float) -> np.ndarray:
    t0 = np.arange(0.0, at, 1.0 / rate0)
    return np.concatenate([t0, at + np.arange(0.0, end - at, 1.0 / rate1)])


def test_b457_a_rate_change_is_found_with_its_time_and_rates():
    for r0, r1 in ((100.0, 50.0), (200.0, 100.0), (50.0, 100.0)):
        ch = rate_changes(_changed(r0, r1, 30.0, 60.0))
        assert len(ch) == 1
        assert round(ch[0].t_s, 1) == 30.0
        assert (round(ch[0].before_hz), round(ch[0].after_hz)) == (r0, r1)


def test_b457_dropped_samples_and_a_steady_rate_are_no_rate_change():
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 60.0, 0.01)
    assert rate_changes(t) == []
    for frac in (0.01, 0.05, 0.3):  # B64's scattered drops, and far more
        keep = rng.random(t.size) >= frac
        assert rate_changes(t[keep]) == []
    burst = np.delete(t, np.r_[2000:2100])  # a 1 s gap (B11), the same rate either side
    assert rate_changes(burst) == []
    short = np.delete(t, np.arange(3001, 3300, 2))  # 3 s at half the rate: shorter than a stretch
    assert rate_changes(short) == []
    b = np.arange(0.0, 300.0, 1 / 104)  # B182's sorted receive-time stamps, +-12 and +-30 ms at 104 Hz
    for jit in (0.012, 0.03):
        assert rate_changes(np.unique(b + rng.uniform(-jit, jit, b.size))) == []


def _rate_changed_walk(tmp_path):
    sim = simulate("walk", 2, rate_hz=100.0, seed=0, length_m=40.0)
    for name in ("fAccelerometer", "fGyroscope"):
        s = sim.streams[name]
        keep = (s.t < s.t[0] + 12.0) | (np.arange(len(s)) % 2 == 0)  # T3's unit: 50 Hz from 12 s on
        sim.streams[name] = Stream(name, s.t[keep], s.values[keep])
    return write_session(sim, tmp_path / "changed")


def test_b457_read_session_says_the_change_in_one_line(tmp_path, caplog):
    folder = _rate_changed_walk(tmp_path)
    with caplog.at_level(logging.WARNING):
        read_session(folder)
    lines = [r.getMessage() for r in caplog.records if "B457" in r.getMessage()]
    assert len(lines) == 1
    assert "fAccelerometer, fGyroscope: the sample rate changed 100 -> 50 Hz at 12.0 s" in lines[0]
    assert "not dropped samples" in lines[0]
    assert [getattr(r, "code", None) for r in caplog.records if "B457" in r.getMessage()] == ["B457"]


def test_b457_a_steady_walk_gets_no_line(tmp_path, caplog):
    sim = simulate("walk", 2, rate_hz=100.0, seed=0, length_m=40.0, drop_rate=0.03)
    folder = write_session(sim, tmp_path / "steady")
    with caplog.at_level(logging.WARNING):
        read_session(folder)
    assert not any("B457" in r.getMessage() for r in caplog.records)


def _pair_mean_walk(tmp_path):
    """B458's sessions: a 100 Hz walk whose foot unit runs at 50 Hz from 12 s on, each sample its pair's mean."""
    sim = simulate("walk", 2, rate_hz=100.0, seed=0, length_m=40.0)
    steady = write_session(sim, tmp_path / "steady")
    slow_foot_from(sim)
    return steady, write_session(sim, tmp_path / "changed")


def test_b458_a_changed_stream_is_read_on_its_fastest_clock_and_keeps_the_distance(tmp_path):
    from pdrlearn.track.plasys import track_plasys

    steady, changed = _pair_mean_walk(tmp_path)
    s = read_session(changed)
    acc = s.streams["fAccelerometer"]
    assert np.allclose(np.diff(acc.t), 0.01)  # one uniform 100 Hz clock, no interval left as "dropped samples"
    assert acc.gaps() == []
    d0 = track_plasys(read_session(steady)).distance_m
    d1 = track_plasys(s).distance_m
    assert abs(d1 / d0 - 1.0) < 0.01  # B458's bound; read as 100 Hz with dt 10 ms the 50 Hz stretch lost ~half
