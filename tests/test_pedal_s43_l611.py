"""Decisions L611 / L612 (docs/decisions/localization.md): pedalling strides are not walking.

A crank takes the foot round a circle with no travel and no rest: `track` (offline, without insoles) and `track
--streaming` (with them) counted its half turns as strides (trial T3 finding F1). The kernel
``pdrlearn.kernels.pedal`` marks them; both tracks remove them with one line naming the span ("cycling?").
"""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels.pedal import closed_loop_strides, pedal_line, seated_strides, unrested_strides
from pdrlearn.track.plasys import track_plasys
from tests.sim_helpers import quiet_walk

G = 9.80665


def _chain(n: int, dt: float = 0.75) -> tuple[np.ndarray, np.ndarray]:
    start = np.arange(n) * dt
    return start, start + dt


def test_reversing_steep_strides_are_a_closed_loop():
    s0, s1 = _chain(8)
    dz = np.array([0.2, -0.17, 0.2, -0.16, 0.21, -0.18, 0.2, -0.17])  # T3's offline 40 rpm raw heights
    assert closed_loop_strides(dz, s0, s1, travel=np.full(8, 0.25)).all()


def test_real_height_wander_and_stairs_are_kept():
    s0, s1 = _chain(6, 1.07)
    # gaitmap_level_right's real level strides (L611's third rule: not steep enough to reverse)
    wander = np.array([0.081, 0.075, 0.084, 0.143, -0.087, 0.080])
    assert not closed_loop_strides(wander, s0, s1, travel=np.full(6, 1.4)).any()
    s0, s1 = _chain(8)
    up_down = np.array([0.34, 0.34, 0.34, 0.34, -0.34, -0.34, -0.34, -0.34])  # a flight up, then down: one reversal
    assert not closed_loop_strides(up_down, s0, s1, travel=np.full(8, 0.55)).any()
    apart = np.array([0.2, -0.2, 0.2, -0.2])  # reversing heights, but 1.5 s apart: no chain
    assert not closed_loop_strides(apart, np.arange(4) * 2.25, np.arange(4) * 2.25 + 0.75).any()


def test_unrested_runs_are_pedalling():
    t = np.arange(0, 10, 0.05)
    still = np.tile([0.0, G, 0.0], (len(t), 1))
    s0, s1 = np.arange(0.5, 9.0, 0.75), np.arange(0.5, 9.0, 0.75) + 0.75
    assert not unrested_strides(t, still, s0, s1).any()
    w = 2 * np.pi * 80 / 60  # a 0.17 m crank at 80 rpm: 11.9 m/s^2 of centripetal acceleration on gravity
    crank = still + 0.17 * w ** 2 * np.c_[-np.cos(w * t), -np.sin(w * t), np.zeros_like(t)]
    off = unrested_strides(t, crank, s0, s1)
    assert off.mean() > 0.5
    flat = np.zeros(len(s0))  # no reversal: the second rule alone
    assert closed_loop_strides(flat, s0, s1, off).sum() >= off.sum()
    assert not closed_loop_strides(flat, s0, s1, np.zeros(len(s0), dtype=bool)).any()


def test_seated_span_and_line():
    transfers = [{"kind": "stand-to-sit", "start_s": 10.0, "end_s": 11.5},
                 {"kind": "sit-to-stand", "start_s": 60.0, "end_s": 61.5}]
    s0, s1 = np.array([5.0, 20.0, 59.5]), np.array([6.0, 21.0, 60.5])
    seated, spans = seated_strides(s0, s1, transfers)
    assert seated.tolist() == [False, True, False] and spans == [(11.5, 60.0)]
    line = pedal_line(np.zeros(3, dtype=bool), seated, s0, s1, spans)
    assert "20.00-21.00 s (1)" in line and "stand-to-sit at 11.50 s, sit-to-stand at 60.00 s" in line
    assert "L612" in line and pedal_line(np.zeros(3, dtype=bool), np.zeros(3, dtype=bool), s0, s1) is None


def _pedal(session, a: float, b: float, rpm: float) -> None:
    """Put a 0.17 m crank (T3's splicer's model, its ankle pitch ramped in) on the foot unit from ``a`` to ``b`` s."""
    acc, gyr = session.streams["fAccelerometer"], session.streams["fGyroscope"]
    m = (acc.t >= a) & (acc.t < b)
    t = acc.t[m]
    e = np.clip(np.minimum(t - a, b - t) / 3.0, 0, 1)
    phi = 2 * np.pi * rpm / 60 * np.cumsum(e) * np.median(np.diff(acc.t))
    rate = 2 * np.pi * rpm / 60 * e
    f_fwd, f_up = -0.17 * rate ** 2 * np.cos(phi), G - 0.17 * rate ** 2 * np.sin(phi)
    theta = np.radians(15) * np.sin(phi + 0.8) * e
    noise = acc.values[m] - acc.values[m].mean(axis=0)
    acc.values[m] = np.c_[np.cos(theta) * f_fwd + np.sin(theta) * f_up,
                          -np.sin(theta) * f_fwd + np.cos(theta) * f_up, np.zeros_like(t)] + noise
    gm = (gyr.t >= a) & (gyr.t < b)
    gyr.values[gm, 2] -= np.interp(gyr.t[gm], t, np.gradient(theta, t))  # pitch rate about the left axis (x, y up, z)


@pytest.fixture(scope="module")
def ride():
    s = quiet_walk("stand:3, straight:8, stand:2, sit:40, stand:2, straight:8, stand:3", 12020, 12020, rate_hz=20.0)
    tr = s.extras["transfers"]
    a, b = float(tr["seated_s"].iloc[0]) + 5, float(tr["rise_s"].iloc[0]) - 5
    _pedal(s, a, b, 40.0)
    return s, a, b


def _track(session, **kw):
    """``track_plasys`` with the pipeline's warning log silenced (the lines are read from ``info["warnings"]``)."""
    logging.disable(logging.WARNING)
    try:
        return track_plasys(session, **kw)
    finally:
        logging.disable(logging.NOTSET)


def _in(steps, a, b) -> int:
    return int(((steps["end_s"] > a) & (steps["start_s"] < b)).sum())


def test_offline_track_without_insoles_drops_the_crank(ride):
    s, a, b = ride
    res = _track(s, ignore_force=True)
    assert _in(res.steps, a, b) == 0
    assert len(res.steps) == len(s.steps)  # the walks' strides all kept
    assert any("cycling?" in w and "L611" in w for w in res.info["warnings"])


def test_streamed_track_drops_the_crank(ride):
    s, a, b = ride
    res = _track(s, streaming=True)
    assert _in(res.steps, a, b) == 0
    line = [w for w in res.info["warnings"] if "cycling?" in w]
    assert len(line) == 1 and "L611" in line[0]


def test_a_ride_alone_is_no_strides_error():
    """Only a crank, no walk: both tracks stop with B318's NoStridesError naming L611's span (streamed: no empty
    track) and B268's --units waist."""
    from pdrlearn.errors import NoStridesError

    s = quiet_walk("stand:3, sit:40, stand:3", 12021, 12021, rate_hz=20.0)
    tr = s.extras["transfers"]
    _pedal(s, float(tr["seated_s"].iloc[0]) + 3, float(tr["rise_s"].iloc[0]) - 3, 60.0)
    for kw in ({"ignore_force": True}, {"streaming": True}):
        # decision B268's fix for a session with a lower-back unit (review R2 finding 5: one helper)
        with pytest.raises(NoStridesError, match="no walking strides: .*cycling\\? decision L611\\) -- .*"
                                                 "track it with --units waist \\(decision B268\\)$"):
            _track(s, **kw)


@pytest.mark.parametrize("streaming", [False, True])
def test_a_stile_of_two_step_rises_is_walking(streaming):
    """Decision L621 (review R2 finding 4): up 2, down 2 four times reverses the height every two steep strides, but
    the strides travel ~0.6 m and rest at every stance: all kept (L611 alone removed 8 of 14)."""
    route = "stand:3, straight:3, " + ", ".join(["up:2, down:2"] * 4) + ", straight:3, stand:3"
    s = quiet_walk(route, 12102, 0, rate_hz=100.0)  # review R2's reproducer (simulate --user-seed 12102)
    res = _track(s, streaming=streaming)
    assert not any("cycling?" in w for w in res.info["warnings"])
    assert len(res.steps) == len(s.steps)


@pytest.mark.parametrize("streaming", [False, True])
def test_a_mis_scaled_foot_accelerometer_is_not_pedalling(streaming):
    """Decision L621 (second part): a foot accelerometer reading 1.2 g at rest (B201: warned, then tracked) had made
    every stride unrested (| 1.2 g - g | = 1.96 m/s^2), so L611 removed the whole walk; a rest is judged against the
    foot's own rest reading."""
    s = quiet_walk("stand:3, straight:10, stand:3", 12123, 12123, rate_hz=100.0)
    s.streams["fAccelerometer"].values[:] = s.streams["fAccelerometer"].values * 1.2
    res = _track(s, streaming=streaming)
    assert not any("cycling?" in w for w in res.info["warnings"])
    assert len(res.steps) == len(s.steps)
