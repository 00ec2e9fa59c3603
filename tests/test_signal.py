"""Tests of pdrlearn.signal: filters, resampling, frames, standstill detection and calibration."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io import Session, Stream
from pdrlearn.signal import (
    CausalLowpass,
    apply_calibration,
    calibrate_standstill,
    gravity_rotation,
    lowpass,
    magnitude,
    resample_stream,
    runs,
    standstill_mask,
)


def test_magnitude():
    assert np.allclose(magnitude(np.array([[3.0, 4.0, 0.0], [0, 0, -2]])), [5.0, 2.0])
    assert np.allclose(magnitude(np.array([-1.0, 2.0])), [1.0, 2.0])


def test_lowpass_passes_dc_and_removes_high_frequency():
    fs = 20.0
    t = np.arange(200) / fs
    slow = np.sin(2 * np.pi * 0.5 * t)
    fast = np.sin(2 * np.pi * 8.0 * t)
    y = lowpass(slow + fast + 3.0, 3.0, fs)
    assert np.max(np.abs(y[20:-20] - slow[20:-20] - 3.0)) < 0.05
    yc = lowpass(np.full((50, 3), 2.5), 3.0, fs, causal=True)
    assert np.allclose(yc, 2.5)


@pytest.mark.parametrize("n", [0, 1, 2, 5])
def test_lowpass_short_inputs(n):
    y = lowpass(np.arange(n, dtype=float), 3.0, 20.0)
    assert y.shape == (n,)


def test_lowpass_bad_cutoff():
    with pytest.raises(DataError, match="Nyquist"):
        lowpass(np.zeros(10), 15.0, 20.0)


@settings(max_examples=20, deadline=None)
@given(st.lists(st.integers(1, 40), min_size=1, max_size=10))
def test_causal_lowpass_chunking_matches_batch(chunks):
    rng = np.random.default_rng(0)
    x = rng.normal(size=(sum(chunks), 2))
    full = lowpass(x, 3.0, 20.0, causal=True)
    f = CausalLowpass(3.0, 20.0)
    parts, i = [], 0
    for c in chunks:
        parts.append(f.push(x[i:i + c]))
        i += c
    assert np.allclose(np.concatenate(parts), full)


def test_resample_stream_linear():
    s = Stream("fAccelerometer", np.array([0.0, 0.1, 0.25, 0.3]), np.array([[0, 0, 0], [1, 1, 1], [2.5, 0, 0],
                                                                              [3, 0, 0]], dtype=float))
    r = resample_stream(s, 20.0)
    assert np.allclose(r.t, [0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3])
    assert np.allclose(r.values[:, 0], [0, 0.5, 1, 1.5, 2, 2.5, 3])
    with pytest.raises(DataError):
        resample_stream(Stream("fAccelerometer", np.zeros(0), np.zeros((0, 3))), 20.0)


@settings(max_examples=30, deadline=None)
@given(st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-1, 1))
       .filter(lambda v: np.linalg.norm(v) > 0.1))
def test_gravity_rotation_properties(v):
    g = 9.81 * np.asarray(v) / np.linalg.norm(v)
    R = gravity_rotation(g)
    assert np.allclose(R @ g, [0, 0, 9.81], atol=1e-9)
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-9)
    assert np.isclose(np.linalg.det(R), 1.0)


def test_gravity_rotation_minimal_and_degenerate():
    assert np.allclose(gravity_rotation([0, 0, 9.8]), np.eye(3))
    R = gravity_rotation([0, 0, -9.8])
    assert np.allclose(R @ [0, 0, -9.8], [0, 0, 9.8])
    # tilt about x only: x axis is unchanged by the minimal rotation
    R = gravity_rotation([0, 9.8 * np.sin(0.3), 9.8 * np.cos(0.3)])
    assert np.allclose(R @ [1, 0, 0], [1, 0, 0])
    with pytest.raises(DataError):
        gravity_rotation([0, 0, 0])


def _still_then_move(fs=20.0, still_s=5.0, move_s=5.0, bias=(0.02, -0.01, 0.03), seed=1):
    rng = np.random.default_rng(seed)
    n0, n1 = int(still_s * fs), int(move_s * fs)
    t = np.arange(n0 + n1) / fs
    g = np.array([0.5, 9.7, 1.0])
    acc = np.tile(g, (n0 + n1, 1)) + rng.normal(0, 0.02, (n0 + n1, 3))
    gyr = np.tile(bias, (n0 + n1, 1)) + rng.normal(0, 0.005, (n0 + n1, 3))
    tm = t[n0:]
    acc[n0:, 0] += 4 * np.sin(2 * np.pi * 1.0 * tm)
    gyr[n0:, 2] += 2 * np.sin(2 * np.pi * 1.0 * tm)
    return t, acc, gyr, g


def test_standstill_mask_and_runs():
    t, acc, gyr, _ = _still_then_move()
    m = standstill_mask(acc, gyr, 20.0)
    assert m[:90].all() and not m[110:].any()
    assert runs(np.array([0, 1, 1, 0, 1], bool)) == [(1, 3), (4, 5)]
    with pytest.raises(DataError, match="NaN"):
        standstill_mask(np.full((5, 3), np.nan), np.zeros((5, 3)), 20.0)


def test_calibrate_and_apply():
    t, acc, gyr, g = _still_then_move()
    s = Session("cal", {"fAccelerometer": Stream("fAccelerometer", t, acc),
                        "fGyroscope": Stream("fGyroscope", t, gyr)})
    cal = calibrate_standstill(s)
    c = cal["foot"]
    assert np.allclose(c.gyro_bias, [0.02, -0.01, 0.03], atol=0.003)
    assert np.allclose(c.acc_mean, g, atol=0.01)
    assert 4.0 <= c.t1 - c.t0 <= 5.0
    assert np.allclose(c.gyro_noise_std, 0.005, atol=0.002)
    out = apply_calibration(s, cal, acc_scale=True)
    assert np.allclose(out["fGyroscope"].values[:80].mean(axis=0), 0, atol=0.003)
    assert np.isclose(np.linalg.norm(out["fAccelerometer"].values[:80].mean(axis=0)), 9.80665, atol=0.01)
    assert np.allclose(s["fGyroscope"].values, gyr)  # input untouched


def test_calibrate_errors():
    t, acc, gyr, _ = _still_then_move(still_s=1.0)
    s = Session("short", {"wAccelerometer": Stream("wAccelerometer", t, acc),
                          "wGyroscope": Stream("wGyroscope", t, gyr)})
    with pytest.raises(DataError, match="standstill"):
        calibrate_standstill(s)
    s2 = Session("acc-only", {"wAccelerometer": Stream("wAccelerometer", t, acc)})
    with pytest.raises(MissingSensorError):
        calibrate_standstill(s2)


def test_calibrate_on_real_lower_back(real_dir):
    from pdrlearn.io import read_session

    s = read_session(real_dir / "mobgap_HA001_Test11_Trial1")
    cal = calibrate_standstill(s)
    c = cal["waist"]
    assert c.t0 == 0.0 and 2.0 <= c.t1 - c.t0 <= 5.0  # the recording starts standing
    assert np.all(np.abs(c.gyro_bias) < 0.05)  # rad/s
    assert 9.3 < c.gravity_norm < 10.1 and c.acc_mean[0] > 9.0  # x axis up (meta.json)
    R = gravity_rotation(c.gravity)
    assert np.allclose(R @ c.gravity, [0, 0, c.gravity_norm])
    # a session without any 2 s standstill says so
    with pytest.raises(DataError, match="standstill"):
        calibrate_standstill(read_session(real_dir / "mobgap_HA001_Test5_Trial1"))
