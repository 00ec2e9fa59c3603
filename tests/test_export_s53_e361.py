"""Decisions E361 / E362 (session 53, I4; E354's open part): after a waist gyroscope gap (a dropout of both units)
the live ``Tracker`` and ``track --streaming`` re-anchor the heading to the waist compass
(``kernels.gap_compass.GapCompass``), weighed against E354's line between the gait-cycle mean rates either side: a gap
longer than the rest of a curve no longer loses the curve's turn, a straight walk keeps E354's line; E362: only a
field of the Earth's size (25-65 uT) is read as a compass (an uncalibrated unit's hard iron is not)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.gap_compass import GapCompass, compass_offset, gap_weight
from pdrlearn.kernels.stride import CycleGapLine, stride_mean_rate
from pdrlearn.runtime import Tracker
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_streaming
from tests.runtime_helpers import replay, without

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
GAP = (60.01, 63.6)  # the sample at 60 s (the stride before's end) kept


def _walk(curve_end: float | None, fs: float = 50.0, seed: int = 361, hard_iron_ut: float = 0.0):
    """A waist walking 50-80 s: the pelvis' +-0.4 rad/s yaw oscillation over a 1.2 s cycle, turning 0.3 rad/s from
    55 s to ``curve_end`` (None: straight), a 20 uT horizontal field with 0.7 uT noise, no sample in ``GAP``; the
    stream and the true heading's function. ``hard_iron_ut``: a constant offset on the body's x axis."""
    t = np.arange(50.0, 80.0, 1.0 / fs)
    t = t[(t < GAP[0]) | (t >= GAP[1])]
    w = 2 * math.pi / 1.2

    def heading(x):
        x = np.asarray(x, float)
        turn = 0.0 if curve_end is None else 0.3 * (np.clip(x, 55.0, curve_end) - 55.0)
        return turn + 0.4 / w * np.sin(w * x)  # the pelvis' yaw, the integral of its rate

    rate = (0.0 if curve_end is None else 0.3 * ((t >= 55.0) & (t < curve_end))) + 0.4 * np.cos(w * t)
    gyr = np.column_stack([0 * t, 0 * t, rate])
    acc = np.column_stack([0 * t, 0 * t, np.full_like(t, 9.81)])
    h = heading(t)  # the body's x axis at heading h: north (+y) seen at angle pi/2 - h from it, CCW
    rng = np.random.default_rng(seed)
    mag = np.column_stack([20 * np.sin(h), 20 * np.cos(h), np.full_like(t, -40.0)]) + rng.normal(0, 0.7, (len(t), 3))
    mag[:, 0] += hard_iron_ut
    s = {"wGyroscope": (t, gyr), "wAccelerometer": (t, acc), "wMagneticField": (t, mag)}
    return s.__getitem__, heading


def _track(stream, compass: bool | dict) -> list[tuple[float, float, float]]:
    """The streamed chain on 1.2 s strides before and after ``GAP``: each stride's own turn, E354's line across the
    gap (held at the gap, taken by the stride after) and, with ``compass`` (True or :class:`GapCompass`'s keywords),
    E361's turn; (start, end, heading)."""
    strides = [(50.4 + 1.2 * k, 51.6 + 1.2 * k) for k in range(8)] + [(63.6 + 1.2 * k, 64.8 + 1.2 * k)
                                                                      for k in range(5)]
    line, anchor, h, out = CycleGapLine(), GapCompass(**(compass if isinstance(compass, dict) else {})), 0.0, []
    for i, (a, b) in enumerate(strides):
        if a == GAP[1]:
            line.hold(stream, strides[i - 1][1], a)
        dyaw = stride_mean_rate(stream, a, b) * (b - a) + line.take(stream, a, b)
        line.note(stream, a, b)  # decision E365: the rate before a next gap
        if compass:
            dyaw += anchor.stride(stream, a, b, dyaw, line.spread)
        h += dyaw
        out.append((a, b, h))
    return out


def _error(rows, heading) -> float:
    """The heading change (deg) from the end of the stride before the gap to the end of the first after it, less
    the truth's."""
    (_, b0, h0), (_, b1, h1) = next((r, rows[i + 1]) for i, r in enumerate(rows) if rows[i + 1][0] >= GAP[1])
    return math.degrees((h1 - h0) - float(heading(b1) - heading(b0)))


def test_the_compass_brings_back_a_curves_turn_the_gap_hid():
    """The curve ends at 63 s inside the 3.6 s gap: E354's line takes half the rate either side (0.54 rad) where
    the pelvis turned 0.9 rad; the compass re-anchors it (its weight ~1: the rates either side differ by 0.3)."""
    stream, heading = _walk(63.0)
    line, anchored = _error(_track(stream, False), heading), _error(_track(stream, True), heading)
    assert line < -15.0, line  # E354 alone: about -20 deg
    assert abs(anchored) < 3.0, (anchored, line)


def test_a_straight_walk_keeps_the_line_and_a_walk_without_gap_is_untouched():
    """Straight: the mean rates either side agree, the line's spread is ~0, so the compass's noisy offset weighs
    ~nothing; without a gap ``stride`` adds exactly 0 (a session without a waist gap is bit-identical)."""
    stream, heading = _walk(None)
    line, anchored = _error(_track(stream, False), heading), _error(_track(stream, True), heading)
    assert abs(anchored - line) < 0.2, (anchored, line)
    anchor = GapCompass()
    for k in range(8):
        a, b = 50.4 + 1.2 * k, 51.6 + 1.2 * k
        assert anchor.stride(stream, a, b, stride_mean_rate(stream, a, b) * 1.2, None) == 0.0
    assert len(anchor.offsets) == 8


def test_a_field_that_is_not_the_earths_is_no_compass():
    """E362: a 200 uT hard iron (the field's norm ~200 uT, as the real mobgap MS001's 255 uT) gives no offset, so
    the gap keeps E354's line; without the gate (E361 alone) the compass turns it."""
    stream, heading = _walk(63.0, hard_iron_ut=200.0)
    line = _error(_track(stream, False), heading)
    assert _error(_track(stream, True), heading) == line
    assert abs(_error(_track(stream, {"field_ut": None}), heading) - line) > 5.0
    assert compass_offset(stream, 50.4, 51.6, 0.0, field_ut=(25.0, 65.0)) is None
    assert compass_offset(stream, 50.4, 51.6, 0.0) is not None


def test_the_offset_cancels_the_pelvis_and_the_weight_needs_two_offsets():
    """The offset of the compass against the chain is the same stride after stride (the pelvis' yaw cancels);
    fewer than two offsets before a gap give no weight."""
    stream, _ = _walk(None)
    offs = [compass_offset(stream, 50.4 + 1.2 * k, 51.6 + 1.2 * k, 0.0)[0] for k in range(4)]
    assert np.ptp(np.degrees(offs)) < 2.0, np.degrees(offs)
    assert compass_offset(stream, GAP[0] + 0.5, GAP[1] - 0.5, 0.0) is None  # no sample inside the gap
    assert gap_weight(0.5, np.array([0.1])) == 0.0
    assert gap_weight(0.5, np.array([0.1, 0.1])) == pytest.approx(1.0)
    assert gap_weight(0.0, np.array([0.1, 0.3])) == 0.0


@pytest.fixture(scope="module")
def curve_gap():
    """A fresh simulated curve (user 5361, 50 Hz) with every sensor silent for 4 s from where it has turned 20 deg."""
    s = simulate_path(parse_route("stand:2, straight:6, curve:90:4, straight:6, stand:2"),
                      UserProfile.from_seed(5361), speed="normal", rate_hz=50.0, seed=5361, name="e361",
                      scenario="route")
    tr = s.trajectory
    t = tr.iloc[:, 0].to_numpy(float)
    t = t / 1000.0 if t[-1] > 1000 else t
    h = np.unwrap(tr["heading_rad"].to_numpy(float))
    a = float(t[np.argmax(np.abs(h - h[0]) > math.radians(20))])
    return without(s, a, a + 4.0), a, (t, h)


def _change_error(st: pd.DataFrame, a: float, b: float, truth) -> float:
    """The heading change (deg) from the 2 walking strides before ``a`` to the 2 after ``b``, less the truth's."""
    t, h = truth
    t0, t1, hh = (st[k].to_numpy(float) for k in ("start_s", "end_s", "heading_rad"))
    walk = st["length_m"].to_numpy(float) > 0
    sides = np.flatnonzero(walk & (t1 <= a))[-2:], np.flatnonzero(walk & (t0 >= b))[:2]
    est = [float(np.mean(np.unwrap(hh[i]))) for i in sides]
    tru = [float(np.mean([np.mean(h[(t >= t0[k]) & (t <= t1[k])]) for k in i])) for i in sides]
    return math.degrees(math.remainder((est[1] - est[0]) - (tru[1] - tru[0]), 2 * math.pi))


def test_track_streaming_and_the_live_tracker_reanchor_a_curve_after_a_dropout(curve_gap):
    """``track --streaming`` (-49.83 deg off with E354's line alone, 6.57 with E361) and the live ``Tracker`` (the
    same kernel, 1 s chunks: 6.80 deg)."""
    s, a, truth = curve_gap
    new = _change_error(track_streaming(s, method="M2").steps, a, a + 4.0, truth)
    old = _change_error(track_streaming(s, method="M2", gap_compass=False).steps, a, a + 4.0, truth)
    steps = replay(Tracker(ROOT / "models" / "plasys-sim-default"), s, 1.0)
    live = _change_error(pd.DataFrame([{k: getattr(x, k) for k in ("start_s", "end_s", "length_m", "heading_rad")}
                                       for x in steps]), a, a + 4.0, truth)
    assert abs(old) > 30.0, (new, old)
    assert abs(new) < 12.0, (new, old)
    assert abs(live - new) < 0.5, (live, new)
