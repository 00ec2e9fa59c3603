"""Decisions L226 / L227 (session 29 check): the gyroscope fallback's heading is finite on the inputs that could
have made it NaN -- a waist gap, a magnetometer gap, a constant magnetometer, a foot gap (L90's stretches), a short
recording -- each with the fallback applied; its kernel, ``fuse_by_segment`` with ``tau_s=inf``, on stretches of one
stride. (Checked on main: no NaN; no fix needed.)"""

from __future__ import annotations

import copy
import logging

import numpy as np
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import fuse_by_segment, track_plasys

_CACHE: dict = {}


def _loop():
    if "s" not in _CACHE:
        route = parse_route(", ".join(["straight:15, curve:-90:1"] * 4))
        _CACHE["s"] = simulate_path(route, UserProfile.from_seed(4745), seed=4745, mag_disturbance_ut=30.0)
    return _CACHE["s"]


def _cut(s, prefix: str, keep):
    s = copy.deepcopy(s)
    for k, st in list(s.streams.items()):
        if k.startswith(prefix):
            m = keep(st.t)
            s.streams[k] = Stream(k, st.t[m], st.values[m])
    return s


def _variant(name: str):
    s = _loop()
    t0, t1 = s.streams["wAccelerometer"].t[[0, -1]]
    mid = (t0 + t1) / 2
    if name == "waist gap 20 s":
        return _cut(s, "w", lambda t: (t < mid) | (t > mid + 20))
    if name == "magnetometer gap 10 s":
        return _cut(s, "wMagneticField", lambda t: (t < mid) | (t > mid + 10))
    if name == "foot gap 5 s":
        return _cut(s, "f", lambda t: (t < mid) | (t > mid + 5))
    if name == "constant magnetometer":
        s = copy.deepcopy(s)
        st = s.streams["wMagneticField"]
        s.streams["wMagneticField"] = Stream("wMagneticField", st.t, np.tile(st.values[0], (len(st.t), 1)))
        return s
    route = parse_route("straight:15, curve:-90:1, straight:10")  # a short recording (19 strides)
    return simulate_path(route, UserProfile.from_seed(4746), seed=4746, mag_disturbance_ut=60.0)


@pytest.mark.parametrize("name", ["waist gap 20 s", "magnetometer gap 10 s", "constant magnetometer", "foot gap 5 s",
                                  "short"])
def test_the_fallback_heading_is_finite(name):
    logging.disable(logging.WARNING)
    try:
        r = track_plasys(_variant(name))
    finally:
        logging.disable(logging.NOTSET)
    assert r.info["compass_check"]["gyro_fallback"] is True  # the fallback path ran
    assert np.isfinite(r.steps["heading_rad"].to_numpy(float)).all()
    assert np.isfinite(r.trajectory[["x", "y"]].to_numpy(float)).all()


def test_one_constant_offset_per_stretch_is_finite_for_one_stride_stretches():
    rel = np.array([0.1, 0.2, 0.3, 0.4])
    ab = np.array([1.1, np.pi, -np.pi, 1.4])
    start, end = np.array([0.0, 2.0, 4.0, 6.0]), np.array([1.0, 3.0, 5.0, 7.0])
    gaps = {"fAccelerometer": [(1.2, 1.8), (3.2, 3.8), (5.2, 5.8)]}
    out = fuse_by_segment(rel, ab, start, end, gaps, tau_s=np.inf)
    assert np.isfinite(out).all()
    np.testing.assert_allclose(np.angle(np.exp(1j * (out - ab))), 0.0, atol=1e-12)  # each alone: its own offset
