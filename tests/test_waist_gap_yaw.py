"""Decision L61 (docs/decisions/localization.md): a stride headed by the waist gyroscope adds the waist's turn
between two strides that do not touch (a turn on the spot while the tracked foot stands), in ``track
--streaming`` and the runtime alike (shared :func:`pdrlearn.kernels.stride.stride_gap_yaw`)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io import Stream
from pdrlearn.kernels.stride import stride_gap_yaw
from pdrlearn.orient import wrap_angle
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.plasys import track_streaming
from tests.runtime_helpers import replay, synthetic_session, trained_dirs

WAIST_HEADED = {"waist": (np.zeros(2), np.zeros((2, 3)), np.zeros((2, 3)), None, float("nan"))}
FOOT_HEADED = {"foot": (np.zeros(2), np.zeros((2, 3)), None, None, 0.0, 0.0)}


def _turn_profile(n: int, angle: float, dt: float) -> np.ndarray:
    """Rate (rad/s) of a raised-cosine turn of ``angle`` rad over ``n`` samples (trapezoid sum = angle)."""
    w = 1.0 - np.cos(2 * np.pi * np.arange(n) / (n - 1))
    return angle * w / (0.5 * float(np.sum(w[1:] + w[:-1])) * dt)


def _streams(rate_up: np.ndarray, fs: float, tilt_deg: float, bias: float = 0.0, sway: float = 0.0, seed: int = 0):
    """Waist and foot streams (100 Hz) whose waist, tilted by ``tilt_deg`` about x, turns at ``rate_up`` about
    gravity (+ a constant ``bias`` and white ``sway`` rad/s); the foot still."""
    rng = np.random.default_rng(seed)
    n = len(rate_up)
    t = np.arange(n) / fs
    a = np.radians(tilt_deg)
    rot = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
    gyr = np.zeros((n, 3))
    gyr[:, 2] = rate_up + bias
    gyr += rng.normal(0.0, sway, (n, 3))
    acc = np.tile([0.0, 0.0, 9.81], (n, 1)) + rng.normal(0.0, 0.05, (n, 3))
    s = {"wGyroscope": (t, gyr @ rot.T), "wAccelerometer": (t, acc @ rot.T),
         "fGyroscope": (t, np.zeros((n, 3))), "fAccelerometer": (t, np.tile([0.0, 9.81, 0.0], (n, 1)))}
    return s.__getitem__


@pytest.mark.parametrize("tilt", [0.0, 20.0])
def test_a_turn_on_the_spot_between_strides_is_recovered(tilt):
    fs = 100.0
    rate = np.zeros(300)
    rate[110:190] = _turn_profile(80, np.pi / 2, 1 / fs)  # 90 deg in 0.8 s, inside the gap 1.0-1.9 s
    stream = _streams(rate, fs, tilt, bias=0.0004, sway=0.02)  # the simulator's waist z-bias sd (sim/sensors.py)
    got = stride_gap_yaw(WAIST_HEADED, "auto", stream, 1.0, 1.9, waist=True)
    assert got == pytest.approx(np.pi / 2, abs=0.01)  # within 0.6 deg
    assert stride_gap_yaw(WAIST_HEADED, "auto", stream, 1.0, 1.9, waist=False) == 0.0  # the former behaviour
    assert stride_gap_yaw(WAIST_HEADED, "waist-gyro", stream, 1.0, 1.9, waist=True) == got
    # a stride headed by the foot takes the foot's pivot (L31: a still foot, 0), not the waist's turn
    assert stride_gap_yaw(FOOT_HEADED, "auto", stream, 1.0, 1.9, waist=True) == 0.0


def test_a_gap_without_a_turn_adds_about_nothing():
    fs = 100.0
    stream = _streams(np.zeros(300), fs, 10.0, bias=0.0004, sway=0.02, seed=3)  # standing: sway and bias only
    assert abs(stride_gap_yaw(WAIST_HEADED, "auto", stream, 1.0, 1.9, waist=True)) < 0.003  # < 0.2 deg
    stream = _streams(np.full(300, 1.0), fs, 0.0)  # turning, but the strides touch / overlap: no gap
    assert stride_gap_yaw(WAIST_HEADED, "auto", stream, 1.5, 1.5, waist=True) == 0.0
    assert stride_gap_yaw(WAIST_HEADED, "auto", stream, None, 1.5, waist=True) == 0.0  # the first stride
    assert stride_gap_yaw(WAIST_HEADED, "auto", stream, 1.6, 1.5, waist=True) == 0.0


def _with_waist_turns(s, angle: float, every: int = 4, turn_s: float = 0.8):
    """Copy of the synthetic two-unit session ``s`` with every ``every``-th stance lengthened by ``turn_s``: the
    foot stands still (its strides then do not touch) while the waist turns ``angle`` about its y axis (the
    thesis waist frame: y up); ``angle=0``: the same session with the waist standing still instead."""
    t = s.streams["fAccelerometer"].t
    dt = float(t[1] - t[0])
    still = np.linalg.norm(s.streams["fGyroscope"].values, axis=1) < 0.2
    starts = np.flatnonzero(still[1:] & ~still[:-1]) + 1  # stance starts
    cut = starts[2:-2:every] + 3  # each turn followed by strides
    n_p = int(round(turn_s / dt))
    out = s.copy()
    out.streams = {}
    for name, st in s.streams.items():
        v = st.values
        block = np.repeat(v[cut], n_p, axis=0)  # each stream held at its value at the cut
        if name == "fGyroscope":
            block = np.zeros_like(block)
        if name == "wGyroscope":
            block = np.zeros_like(block)
            block[:, 1] = np.tile(_turn_profile(n_p, angle, dt), len(cut))
        if name in ("fAccelerometer", "wAccelerometer"):
            block = np.tile([0.0, 9.81, 0.0], (n_p * len(cut), 1))
        vv = np.insert(v, np.repeat(cut, n_p), block, axis=0)
        out.streams[name] = Stream(name, t[0] + np.arange(len(vv)) * dt, vv)
    out.steps = None
    return out


def test_runtime_and_streaming_track_add_the_waist_turn_alike(tmp_path_factory):
    base = synthetic_session(24, seed=11, name="waist_turns")
    s, calm = _with_waist_turns(base, np.pi / 2), _with_waist_turns(base, 0.0)
    root = trained_dirs(tmp_path_factory)["root"]
    on = track_streaming(s, method="M3", model=str(root / "model"))  # heading auto = the waist gyroscope
    steps = replay(Tracker(root / "bundle"), s, 0.37)
    assert len(steps) == len(on.steps) >= 20
    dh = np.array([st.heading_rad for st in steps]) - on.steps["heading_rad"].to_numpy(float)
    np.testing.assert_allclose(wrap_angle(dh), 0.0, atol=1e-9)
    xyz = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(xyz - on.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    # the turns made while the foot stood, against the same walk with the waist still there (same strides, same
    # sway): one gap per turn
    n_gaps = int((on.steps["start_s"].to_numpy()[1:] > on.steps["end_s"].to_numpy()[:-1] + 1e-9).sum())
    assert n_gaps >= 5
    head = {}
    for label, sess, kw in (("on", s, {}), ("calm", calm, {}), ("off", s, {"waist_gap_yaw": False}),
                            ("calm_off", calm, {"waist_gap_yaw": False})):
        r = on if label == "on" else track_streaming(sess, method="M3", model=str(root / "model"), **kw)
        head[label] = r.steps["heading_rad"].to_numpy(float)
    # the turn added by each stride against the calm walk's same stride, unwrapped along the walk: since L654
    # heading_rad is turned by pi on every stride whose reported length is signed by its measured x against the
    # rules' sign (here E216's waist-placed tiny strides, in both walks alike), so one walk's own unwrapped heading
    # lost a whole turn at such a pi jump next to a 90-degree gap turn (4.71 for 11.00 rad; FN, session 44)
    turned = float(np.unwrap(wrap_angle(head["on"] - head["calm"]))[-1])
    assert turned == pytest.approx(n_gaps * np.pi / 2, abs=0.01 * n_gaps)  # each 90-degree turn within 0.6 deg
    # without L61 only the part of each turn inside the strides' own windows (~0.08 of 1.57 rad) is kept
    assert float(np.unwrap(wrap_angle(head["off"] - head["calm_off"]))[-1]) < 0.2 * n_gaps
