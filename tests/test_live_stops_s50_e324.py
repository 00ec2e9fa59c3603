"""Decision E324 (session 50, FD, trial s50t1 F1): a turn made on the spot during a stop over a minute is kept by the
streamed waist heading (L296's rest rotation over the stop, up to 600 s of it), live and in ``track --streaming``."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.carried_yaw import carried_turn
from pdrlearn.kernels.stride import long_stop_span, long_stop_turn, stride_gap_yaw

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]


def stop_streams(stop_s: float, spin_at: float, spin_deg: float, *, fs: float = 50.0, bias: float = 0.002,
                 gap: tuple[float, float] | None = None):
    """A waist at rest (z up) from 0 to ``stop_s`` s with a gyroscope bias ``bias`` rad/s about the vertical and a
    raised-cosine spin of ``spin_deg`` over 4 s from ``spin_at`` s; the rate under 0.25 rad/s at its ends. ``gap``:
    ``(a, b)`` s with no waist samples (decision E334, a dropout)."""
    t = np.arange(0.0, stop_s + 1e-9, 1.0 / fs)
    rng = np.random.default_rng(3)
    u = np.clip((t - spin_at) / 4.0, 0.0, 1.0)
    rate = np.where((u > 0) & (u < 1), math.radians(spin_deg) / 4.0 * (1 - np.cos(2 * np.pi * u)), 0.0)
    gyr = np.column_stack([np.zeros_like(t), np.zeros_like(t), rate + bias]) + rng.normal(0, 0.003, (len(t), 3))
    acc = np.tile([0.0, 0.0, 9.81], (len(t), 1)) + rng.normal(0, 0.02, (len(t), 3))
    keep = np.ones(len(t), dtype=bool) if gap is None else (t < gap[0]) | (t > gap[1])
    s = {"wAccelerometer": (t[keep], acc[keep]), "wGyroscope": (t[keep], gyr[keep])}
    return s.__getitem__


def test_the_span_is_the_stop_over_a_minute_bounded_by_600_s():
    assert long_stop_span(10.0, 69.0) is None  # L498 integrates a stop up to 60 s whole: unchanged
    assert long_stop_span(None, 100.0) is None
    assert long_stop_span(10.0, 100.0) == (10.0, 99.0)  # to L498's last second, which keeps its own reading
    assert long_stop_span(0.0, 8 * 3600.0) == (8 * 3600.0 - 600.0, 8 * 3600.0 - 1.0)  # E305: an 8 h sit stays bounded


@pytest.mark.parametrize("stop_s", [90.0, 300.0])
def test_a_spin_in_a_long_stop_is_kept_and_the_bias_is_not(stop_s):
    stream = stop_streams(stop_s, stop_s - 20.0, 90.0)
    got = math.degrees(long_stop_turn(stream, 0.0, stop_s))
    assert abs(got - 90.0) < 1.5, got  # the raw integral adds the bias: 0.002 rad/s x stop_s (10-34 deg)
    whole = math.degrees(stride_gap_yaw({}, "waist", stream, 0.0, stop_s, waist=True))
    assert abs(whole - 90.0) < 2.0, whole  # L498's last second + E324's rest: before E324 ~0 deg (its last second)


def test_the_spin_s_slow_ends_are_turn_not_bias():
    stream = stop_streams(95.0, 88.0, 90.0, bias=0.0)  # the spin in the stop's last (short) block, as the trial's
    assert abs(math.degrees(long_stop_turn(stream, 0.0, 95.0)) - 90.0) < 1.5
    no_margin = long_stop_turn(stream, 0.0, 95.0, still_margin_s=0.0)
    assert abs(math.degrees(no_margin) - 90.0) > 3.0  # without E324's margin


def test_the_carried_turn_adds_the_long_stop_s_rest():
    stream = stop_streams(100.0, 80.0, -90.0, bias=0.0)
    lev = {"waist": (np.array([100.0, 101.0]), None, None, None, 0.0)}
    got = carried_turn(stream, lev, "waist", 0.0, 99.9, 100.0)
    assert got is not None and abs(math.degrees(got[1]) + 90.0) < 2.0


@pytest.fixture(scope="module")
def stand_spin():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:3, straight:5, stand:70, spin:90:4, straight:5, stand:3"),
                         UserProfile.from_seed(5031), seed=5031, scenario="route", waist_mount_deg=(0.0, 20.0, 0.0))


def test_the_live_tracker_keeps_the_turn_as_track_streaming_does(stand_spin):
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.track.plasys import track_plasys
    from tests.runtime_helpers import time_chunks

    s = stand_spin
    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), tasks=[], sensors=list(s.streams))
    steps = [st for _, c in time_chunks(s, 1.0) for st in tr.push(c)] + list(tr.flush())
    gap = [k for k in range(1, len(steps)) if steps[k].start_s - steps[k - 1].end_s > 60.0]
    assert len(gap) == 1
    k = gap[0]
    turned = math.degrees(steps[-1].heading_rad - steps[k - 1].heading_rad)
    assert abs(turned - 90.0) < 10.0, turned  # before E324: ~0 (the spin ended more than 1 s before the stride)
    off = track_plasys(s, streaming=True).steps
    assert len(off) == len(steps)
    assert abs(float(off["heading_rad"].iloc[-1]) - steps[-1].heading_rad) < 1e-6


def test_the_long_stop_turn_is_read_once_per_stride_e335(stand_spin, monkeypatch):
    """Decision E335 (session 51, FA, review s51r1 F1 (c)): one read per stride, shared by L61's gap yaw and E285."""
    from pdrlearn.kernels import carried_yaw as KCY
    from pdrlearn.kernels import stride as SK
    from pdrlearn.runtime import tracker as RT
    from pdrlearn.track.plasys import track_plasys

    calls = []

    def counted(stream, prev_end, t0, **kw):
        if long_stop_span(prev_end, t0) is not None:
            calls.append(t0)
        return long_stop_turn(stream, prev_end, t0, **kw)

    for mod in (SK, KCY, RT):
        monkeypatch.setattr(mod, "long_stop_turn", counted, raising=False)
    steps = track_plasys(stand_spin, streaming=True).steps
    k = [i for i in range(1, len(steps)) if steps["start_s"].iloc[i] - steps["end_s"].iloc[i - 1] > 60.0]
    assert len(k) == 1 and len(calls) == 1, calls  # before E335: twice (stride_gap_yaw's, then carried_turn's)
    turned = math.degrees(steps["heading_rad"].iloc[k[0]] - steps["heading_rad"].iloc[k[0] - 1])
    assert abs(turned - 90.0) < 10.0, turned
