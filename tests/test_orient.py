"""Orientation kernels and estimators on analytic rotations (thesis ch.7.1, 7.2.1)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.orient import (
    WaistHeading,
    angle_kalman,
    complementary_filter,
    deadband,
    phi_for_rate,
    tilt_compensated_heading,
    tilt_from_accel,
    wrap_angle,
)

G = 9.81
M_NAV = np.array([0.0, 22.0, -40.0])  # ENU Earth field (uT): north and down


def _body(roll, pitch, yaw):
    """Body->nav rotation R = Rz(yaw) Ry(pitch) Rx(roll) (FLU body, ENU nav)."""
    return Rotation.from_euler("ZYX", np.column_stack([yaw, pitch, roll]))


@pytest.mark.parametrize("roll,pitch", [(0.0, 0.0), (0.3, 0.0), (0.0, -0.4), (-0.5, 0.6), (1.0, 0.2)])
def test_tilt_from_accel_recovers_roll_pitch(roll, pitch):
    R = _body(np.array([roll]), np.array([pitch]), np.array([0.7]))
    acc = R.inv().apply(np.array([0.0, 0.0, G]))
    r, p = tilt_from_accel(acc)
    assert r[0] == pytest.approx(roll, abs=1e-9)
    assert p[0] == pytest.approx(pitch, abs=1e-9)



def _thesis_eq39_roll(acc):
    """Thesis eq. 39, roll = arctan(z / sqrt(x^2 + y^2)) in its foot frame (y up, z lateral), in FLU axes
    (lateral = y, up = z), signed to agree with ours at zero pitch."""
    return np.arctan(acc[:, 1] / np.hypot(acc[:, 0], acc[:, 2]))


def _rest_force(roll, pitch):
    """Specific force at rest of the body-to-level rotation Ry(pitch) @ Rx(roll) (tilt_from_accel's model)."""
    return G * np.column_stack([-np.sin(pitch), np.sin(roll) * np.cos(pitch), np.cos(roll) * np.cos(pitch)])


def test_tilt_roll_replaces_thesis_eq39_when_pitched():
    """Decision L4: our roll is atan2(y, z), not thesis eq. 39; equal at zero pitch, different when pitched,
    and only ours rebuilds the measured gravity with eq. 38's pitch (same rotation order)."""
    level = _rest_force(np.array([0.3]), np.array([0.0]))
    assert _thesis_eq39_roll(level)[0] == pytest.approx(tilt_from_accel(level)[0][0], abs=1e-12)
    acc = _rest_force(np.array([0.3]), np.array([0.6]))  # a pitched rest pose
    r, p = tilt_from_accel(acc)
    r39 = _thesis_eq39_roll(acc)
    assert r[0] == pytest.approx(0.3, abs=1e-12) and p[0] == pytest.approx(0.6, abs=1e-12)
    assert r39[0] == pytest.approx(np.arcsin(np.sin(0.3) * np.cos(0.6)), abs=1e-12)  # 0.246 rad
    assert abs(r39[0] - r[0]) > 0.05
    np.testing.assert_allclose(_rest_force(r, p), acc, atol=1e-12)
    assert np.max(np.abs(_rest_force(r39, p) - acc)) > 0.3  # m/s^2: eq. 39 + eq. 38 miss the gravity

def test_tilt_compensated_heading_on_tilted_body():
    rng = np.random.default_rng(0)
    yaw = rng.uniform(-np.pi, np.pi, 50)
    roll = rng.uniform(-0.5, 0.5, 50)
    pitch = rng.uniform(-0.5, 0.5, 50)
    R = _body(roll, pitch, yaw)
    acc = R.inv().apply(np.array([0.0, 0.0, G]))
    mag = R.inv().apply(M_NAV)
    h = tilt_compensated_heading(acc, mag)
    # the level forward axis points along yaw (ENU heading of the body x axis)
    assert np.max(np.abs(wrap_angle(h - yaw))) < 1e-9
    # facing north gives pi/2, facing east 0
    for y, expect in ((np.pi / 2, np.pi / 2), (0.0, 0.0)):
        Rn = _body(np.array([0.0]), np.array([0.0]), np.array([y]))
        h = tilt_compensated_heading(Rn.inv().apply([0, 0, G]), Rn.inv().apply(M_NAV))
        assert h[0] == pytest.approx(expect)


def test_phi_keeps_the_thesis_time_constant():
    assert phi_for_rate(0.05) == pytest.approx(0.92)  # thesis ch.7.1: 0.92 at 20 Hz
    tau = 0.92 * 0.05 / 0.08  # thesis eq. 37
    p100 = phi_for_rate(0.01)
    assert p100 * 0.01 / (1 - p100) == pytest.approx(tau)


def _four_rotations(fs=20.0, noise=0.05, seed=1):
    """Standing body turning four times by pi/2 (thesis Table 35 experiment), with compass noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(0, 40, 1 / fs)
    rate = np.zeros_like(t)
    for k in range(4):
        sel = (t >= 5 + 8 * k) & (t < 7 + 8 * k)
        rate[sel] = (np.pi / 2) / 2.0
    yaw = 0.3 + np.concatenate([[0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) / fs)])
    R = _body(np.zeros_like(t), np.zeros_like(t), yaw)
    acc = R.inv().apply(np.array([0, 0, G])) + rng.normal(0, 0.05, (t.size, 3))
    mag = R.inv().apply(M_NAV) + rng.normal(0, noise * 40, (t.size, 3))
    gyr = np.column_stack([np.zeros_like(t), np.zeros_like(t), rate]) + rng.normal(0, 0.01, (t.size, 3))
    return t, acc, gyr, mag, yaw


@pytest.mark.parametrize("fs", [20.0, 100.0])
def test_complementary_heading_follows_four_quarter_turns(fs):
    t, acc, gyr, mag, yaw = _four_rotations(fs)
    wh = WaistHeading().estimate(t, acc, gyr, mag)
    h = wh.heading_
    ends = [np.searchsorted(t, 4.5 + 8 * k) for k in range(5)]
    turns = np.diff(h[ends])
    assert np.allclose(turns, np.pi / 2, atol=0.06)
    assert h[ends[-1]] - h[ends[0]] == pytest.approx(2 * np.pi, abs=0.08)
    # standstill (Table 34): the output is stable to far below the 0.035 rad threshold
    still = (t > 1) & (t < 4.5)
    assert np.ptp(h[still]) < 0.05  # held by the deadband: at most one small jump
    assert np.abs(wrap_angle(h[ends[0]] - yaw[ends[0]])) < 0.05


def test_complementary_filter_is_smoother_than_the_compass():
    t, acc, gyr, mag, yaw = _four_rotations(20.0, noise=0.1)
    wh = WaistHeading(threshold=0.0).estimate(t, acc, gyr, mag)
    err_f = np.std(wrap_angle(wh.heading_ - yaw)[t > 2])
    err_c = np.std(wrap_angle(wh.compass_ - yaw)[t > 2])
    assert err_f < 0.6 * err_c


def test_complementary_filter_constant_input_and_deadband():
    out = complementary_filter(np.full(50, 1.0), np.zeros(50), 0.05, phi=0.92)
    assert np.allclose(out, 1.0)
    out = deadband(np.array([0.0, 0.02, 0.03, 0.05, 0.06, 0.1]), 0.035)
    assert out.tolist() == [0, 0, 0, 0.05, 0.05, 0.1]


def test_gyro_only_heading_without_magnetometer_warns():
    t, acc, gyr, _, yaw = _four_rotations()
    wh = WaistHeading(initial_heading=0.3).estimate(t, acc, gyr, None)
    assert wh.warnings_ and "magnetometer" in wh.warnings_[0]
    assert wh.heading_[-1] - wh.heading_[0] == pytest.approx(2 * np.pi, abs=0.1)


def test_angle_kalman_estimates_gyro_bias_and_angle():
    rng = np.random.default_rng(3)
    fs, n = 100.0, 3000
    t = np.arange(n) / fs
    theta = 0.3 * np.sin(2 * np.pi * 0.2 * t)
    rate_true = np.gradient(theta, 1 / fs)
    bias = 0.05
    meas = theta + rng.normal(0, 0.02, n)
    est, b = angle_kalman(meas, rate_true + bias, 1 / fs, q_angle=1e-4, q_bias=1e-7, r=0.02**2)
    assert b[-1] == pytest.approx(bias, abs=0.01)
    assert np.sqrt(np.mean((est[1000:] - theta[1000:]) ** 2)) < 0.01
    # gyro-only integration drifts by bias * time; the filter does not
    assert abs(est[-1] - theta[-1]) < 0.02
