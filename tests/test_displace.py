"""Displacement kernels on synthetic motion with a known answer, and the PLASYS rules (thesis ch.7.2)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.displace import (
    THESIS_STEP_BOUNDS,
    StepRules,
    altitude_change,
    apply_direction,
    clamp_length,
    double_integrate,
    error_clock,
    heel_rocker_samples,
    move_reference,
    parse_bounds,
    rotation_pivot,
    strapdown,
    stride_index,
    terrain_distance,
    wnj_displacement,
    wnj_kalman,
    wnj_matrices,
)
from pdrlearn.errors import DataError

G = 9.81


def synthetic_stride(fs: float, D=(1.4, 0.05, 0.1), duration=1.2, pitch_amp=0.8, roll0=0.1):
    """Minimum-jerk foot displacement D (m) over ``duration`` s with a pitch swing and a tilted mount.

    Returns FLU specific force and body rates (what an IMU on the foot would read)."""
    n = int(round(duration * fs)) + 1
    t = np.arange(n) / fs
    T = t[-1]
    s = t / T
    acc_true = ((60 * s - 180 * s**2 + 120 * s**3) / T**2)[:, None] * np.asarray(D)
    th = pitch_amp * np.sin(np.pi * s) ** 2
    thd = pitch_amp * 2 * np.sin(np.pi * s) * np.cos(np.pi * s) * np.pi / T
    rots = Rotation.from_euler("y", th[:, None]) * Rotation.from_euler("x", roll0)
    gyr = rots.inv().apply(np.column_stack([0 * t, thd, 0 * t]))
    acc = rots.inv().apply(acc_true + np.array([0, 0, G]))
    return acc, gyr, n


@pytest.mark.parametrize("fs", [100.0, 204.8])
def test_strapdown_integration_recovers_known_displacement(fs):
    acc, gyr, n = synthetic_stride(fs)
    idx, mask = stride_index(np.array([0]), np.array([n - 1]))
    a_nav, yaw = strapdown(acc, gyr, 1 / fs, idx, mask, acc[[0]])
    d1 = double_integrate(a_nav, mask, 1 / fs)
    d2 = wnj_displacement(a_nav, mask, 1 / fs)
    assert np.allclose(d1[0], [1.4, 0.05, 0.1], atol=0.005)
    assert np.allclose(d2[0], [1.4, 0.05, 0.1], atol=0.005)
    assert abs(yaw[0]) < 1e-9


def test_zupt_removes_a_constant_accelerometer_bias():
    fs = 100.0
    acc, gyr, n = synthetic_stride(fs, pitch_amp=0.0, roll0=0.0)
    a_bias = np.array([0.2, -0.1, 0.0])
    idx, mask = stride_index(np.array([0]), np.array([n - 1]))
    a_nav, _ = strapdown(acc + a_bias, gyr, 1 / fs, idx, mask, acc[[0]])
    raw = double_integrate(a_nav, mask, 1 / fs, zupt_end=False)
    fixed = double_integrate(a_nav, mask, 1 / fs, zupt_end=True)
    assert abs(raw[0, 0] - 1.4) > 0.1
    assert abs(fixed[0, 0] - 1.4) < 0.01


def test_quintic_histospline_reconstructs_block_means_better_than_cubic():
    """Decision L24: 20 Hz means of a smooth 100 Hz signal are upsampled x5 with their block means kept;
    the degree-5 histospline is closer to the signal than the cubic one."""
    from pdrlearn.displace._kernels import upsample_block_means

    t100 = (np.arange(400) + 0.5) / 100.0
    x = np.column_stack([np.sin(2 * np.pi * 1.7 * t100) * 20, np.cos(2 * np.pi * 3.1 * t100) * 5])
    t20 = t100.reshape(-1, 5).mean(axis=1)
    x20 = x.reshape(-1, 5, 2).mean(axis=1)
    err = {}
    for deg in (3, 5):
        tf, xf = upsample_block_means(t20, x20, 5, degree=deg)
        assert np.allclose(tf, t100)
        assert np.allclose(xf.reshape(-1, 5, 2).mean(axis=1), x20, atol=0.02 * np.abs(x20).max())
        err[deg] = np.sqrt(np.mean((xf - x)[20:-20] ** 2))
    assert err[5] < err[3]
    t2, x2 = upsample_block_means(t20[:3], x20[:3], 5)  # too short for degree 5: a lower odd degree
    assert x2.shape == (15, 2) and np.isfinite(x2).all()


def _impact_stride(fs: float = 204.8, clip: float = 40.0):
    """A forward swing ending in a heel-strike impact that stops the foot within 2 samples; the
    accelerometer clips the impact at ``clip`` m/s^2. Returns (a_true, a_measured, true displacement)."""
    dt = 1.0 / fs
    n_sw = int(0.5 * fs)
    s = np.arange(n_sw + 1) / n_sw
    v = 0.8 * np.sin(np.pi * s / 2)  # the foot still moves at 0.8 m/s at the heel strike
    v = np.concatenate([v, np.zeros(int(0.2 * fs))])  # impact within one sample, then stance
    a = np.gradient(v, dt)
    a3 = np.column_stack([a, 0 * a, 0 * a])[None]
    meas = np.clip(a3, -clip, clip)
    true = np.sum(0.5 * (v[1:] + v[:-1]) * dt)
    return a3, meas, true


def test_error_clock_puts_the_zupt_correction_at_a_clipped_impact():
    """Decision L21: a clipped heel strike leaves a velocity error that appears at the impact; spreading
    it evenly in time (the classical linear ZUPT correction) misplaces it, the error clock much less."""
    fs = 204.8
    a_true, meas, true = _impact_stride(fs)
    L = meas.shape[1]
    mask = np.ones((1, L), bool)
    zupt = np.zeros((1, L), bool)
    zupt[0, 0] = True
    zupt[0, -int(0.15 * fs):] = True  # the stance after the impact
    exact = double_integrate(a_true, mask, 1 / fs, zupt=zupt)[0, 0]
    assert exact == pytest.approx(true, rel=0.01)
    linear = double_integrate(meas, mask, 1 / fs, zupt=zupt)[0, 0]
    assert abs(linear - true) > 0.2 * true  # the even spread is > 20 % off
    for s_err, gain in ((0.01, 1.2), (0.05, 3.5)):  # the default and a larger proportional error
        clock = error_clock(meas, mask, r=0.01, scale_error=s_err)
        weighted = double_integrate(meas, mask, 1 / fs, zupt=zupt, clock=clock)[0, 0]
        assert abs(weighted - true) < abs(linear - true) / gain
        kf = wnj_displacement(meas, mask, 1 / fs, zupt_at=zupt,
                              q_vel=s_err**2 * np.sum(meas**2, axis=2) / fs**2)[0, 0]
        kf_plain = wnj_displacement(meas, mask, 1 / fs, zupt_at=zupt)[0, 0]
        assert abs(kf - true) < abs(kf_plain - true) / gain
    # no acceleration-proportional error: the clock is time (the classical correction)
    assert np.allclose(error_clock(meas, mask, r=0.01, scale_error=0.0)[0], np.arange(L))


def _quat(rot: Rotation) -> np.ndarray:
    xyzw = rot.as_quat().reshape(-1, 4)
    return np.column_stack([xyzw[:, 3], xyzw[:, :3]])


def test_rotation_pivot_and_reference_move_of_a_foot_turning_on_its_heel():
    """Decision L22: a foot rolling about its heel (fixed pivot) moves its sensor by w x rho; the pivot
    is recovered from body-frame velocities and rates, and a stride that only turns the foot 90 deg
    about the heel moves the heel by 0 while the lateral sensor moves ~0.1 m."""
    rng = np.random.default_rng(1)
    rho = np.array([0.05, 0.02, 0.06])  # sensor relative to the heel contact, body frame (m)
    w = rng.normal(size=(200, 3)) * np.array([0.5, 4.0, 0.5])  # mostly pitch, some roll and yaw
    v = np.cross(w, rho) + rng.normal(scale=0.005, size=(200, 3))
    est, fit = rotation_pivot(v, w)
    assert np.allclose(est, rho, atol=0.005) and fit > 0.95
    q0 = _quat(Rotation.identity())
    q1 = _quat(Rotation.from_euler("z", np.pi / 2))
    r = -rho  # heel contact - sensor
    sensor = Rotation.from_euler("z", np.pi / 2).apply(-r) - (-r)  # the sensor circles the heel
    assert np.hypot(*sensor[:2]) > 0.05
    heel = move_reference(sensor[None], q0, q1, r)
    assert np.allclose(heel, 0.0, atol=1e-12)
    # no rotation between the rests: every point of the foot moves alike
    d = np.array([[1.3, 0.1, 0.0]])
    assert np.allclose(move_reference(d, q0, q0, r), d)


def test_heel_rocker_samples_lie_between_the_impact_and_the_stance():
    dt = 0.01
    L = 100
    a = np.zeros((1, L, 3))
    a[0, 70, 2] = 80.0  # heel-strike impact
    gyr = np.zeros((1, L, 3))
    gyr[0, 40:85, 1] = 3.0  # the foot still turns after the impact until foot flat at 85
    stance = np.zeros((1, L), bool)
    stance[0, :10] = True
    stance[0, 85:] = True
    sel = heel_rocker_samples(a, gyr, stance, np.ones((1, L), bool), dt)
    assert np.flatnonzero(sel[0]).tolist() == list(range(71, 85))


def test_heel_reference_on_a_foot_recording():
    """The heel lever arm estimated from a real foot walk (gaitmap, lateral shoe mount) points back from
    the sensor, and the heel reference moves a turning stride by > 5 cm, straight ones by < 1 cm."""
    from pathlib import Path

    from pdrlearn.displace import FootDisplacement
    from pdrlearn.io import read_session
    from pdrlearn.orient import unit_data

    d = Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_level_right"
    if not d.exists():
        pytest.skip("real gaitmap recording not available")
    s = read_session(d)
    unit = unit_data(s, "foot")
    steps = s.steps[["start_s", "end_s"]]
    sensor = FootDisplacement().estimate(unit, steps)
    heel = FootDisplacement(reference_point="heel").estimate(unit, steps)
    assert sensor.lever_arm_ is None
    r = heel.lever_arm_
    assert -0.15 < r[0] < 0.0 and np.linalg.norm(r) < 0.2 and heel.lever_fit_ > 0.5
    change = np.linalg.norm(heel.disp_[:, :2] - sensor.disp_[:, :2], axis=1)  # (R_end - R_start) r
    turn = np.abs(np.degrees(heel.yaw_change_)) > 60
    assert turn.any() and change[turn].min() > 0.05 and np.median(change[~turn]) < 0.01
    with pytest.raises(DataError):
        FootDisplacement(reference_point="toe")
    few = FootDisplacement(reference_point="heel", min_rocker_samples=10**6).estimate(unit, steps)
    assert few.lever_arm_ is None and np.allclose(few.disp_, sensor.disp_)
    assert any("heel-rocker samples" in w for w in few.warnings_)
    with pytest.raises(DataError):
        FootDisplacement(accel_scale_error=-0.01)


def test_batch_of_strides_equals_single_strides():
    fs = 100.0
    a1, g1, n1 = synthetic_stride(fs, D=(1.4, 0.0, 0.0))
    a2, g2, n2 = synthetic_stride(fs, D=(0.8, 0.1, -0.2), duration=0.9)
    acc, gyr = np.vstack([a1, a2]), np.vstack([g1, g2])
    idx, mask = stride_index(np.array([0, n1]), np.array([n1 - 1, n1 + n2 - 1]))
    a_nav, _ = strapdown(acc, gyr, 1 / fs, idx, mask, acc[[0, n1]])
    d = wnj_displacement(a_nav, mask, 1 / fs)
    assert np.allclose(d, [[1.4, 0, 0], [0.8, 0.1, -0.2]], atol=0.005)


def test_wnj_matrices_follow_thesis_eq_53_54():
    F, Q = wnj_matrices(0.05, 1.8)
    T = 0.05
    assert np.allclose(F, [[1, T, T * T / 2], [0, 1, T], [0, 0, 1]])
    assert Q[0, 0] == pytest.approx(1.8 * T**5 / 20)
    assert Q[1, 2] == pytest.approx(1.8 * T**2 / 2)
    assert np.allclose(Q, Q.T)


def test_wnj_kalman_constant_acceleration_without_zupt():
    fs, a = 50.0, 0.7
    n = 101
    meas = np.full((1, n), a)
    states = wnj_kalman(meas, np.ones((1, n), bool), 1 / fs, zupt=False)
    T = (n - 1) / fs
    assert states[0, -1, 0] == pytest.approx(0.5 * a * T * T, rel=1e-3)
    assert states[0, -1, 1] == pytest.approx(a * T, rel=1e-3)


def test_direction_rule_sets_the_sign():
    d = np.array(["forward", "forward", "backward", "backward"])
    assert apply_direction(np.array([0.5, -0.5, 0.5, -0.5]), d).tolist() == [0.5, 0.5, -0.5, -0.5]


def test_length_clamp_thesis_examples():
    b = THESIS_STEP_BOUNDS
    # thesis ch.7.2.2: 60 cm estimated, class Small -> 30 cm; 40 cm, class Long -> 46 cm
    out = clamp_length(np.array([0.60, 0.40, 0.40, -0.60]), np.array(["short", "long", "normal", "short"]), b)
    assert out.tolist() == pytest.approx([0.30, 0.46, 0.40, -0.30])
    assert clamp_length(np.array([0.0]), np.array(["long"]), b)[0] == pytest.approx(0.46)


def test_altitude_and_terrain_rules():
    t = np.array(["flat", "up", "down", "up"])
    out = altitude_change(np.array([0.2, -0.2, 0.17, 0.3]), t)
    assert out.tolist() == pytest.approx([0.0, 0.2, -0.17, 0.3])
    disp = np.array([[0.6, 0.0, -0.34], [0.6, 0.0, 0.34]])
    d = terrain_distance(disp, np.array(["down", "up"]))
    assert d[0] == pytest.approx(np.hypot(0.6, 0.34))  # thesis eq. 61 on descending stairs
    assert d[1] == pytest.approx(0.6)  # the horizontal ("x-axis") filter on ascending stairs


def test_step_rules_on_constructed_strides():
    disp = np.array([[1.2, 0.1, 0.0], [-0.5, 0.0, 0.0], [0.55, 0.02, 0.33], [0.2, 0.0, 0.05]])
    classes = pd.DataFrame({"terrain": ["flat", "flat", "up", None],
                            "direction": ["forward", "forward", "forward", "backward"],
                            "length_class": ["long", "normal", None, "short"]})
    out = StepRules(bounds_scale=2.0).apply(disp, classes)
    assert out["length_m"].iloc[0] == pytest.approx(np.hypot(1.2, 0.1))  # inside long (>= 0.92)
    assert out["length_m"].iloc[1] == pytest.approx(0.6)  # sign forward, clamped to normal [0.6, 0.9]
    assert out["dz_m"].tolist() == pytest.approx([0.0, 0.0, 0.33, 0.05])  # unknown terrain: estimated dz
    assert out["length_m"].iloc[3] == pytest.approx(-0.2)
    off = StepRules(clamp=False, sign=False, altitude=False).apply(disp, classes)
    assert off["length_m"].iloc[1] == pytest.approx(-0.5)


def test_parse_bounds_and_errors():
    assert parse_bounds([0.6, 0.9])["normal"] == (0.6, 0.9)
    assert parse_bounds({"short": [0, 0.5], "long": [0.9, None]})["long"] == (0.9, 10.0)
    with pytest.raises(DataError):
        parse_bounds([0.9, 0.6])
    with pytest.raises(DataError):
        StepRules(down_mode="diagonal")
    with pytest.raises(DataError):
        StepRules().apply(np.zeros((2, 3)), pd.DataFrame({"terrain": ["flat"]}))


def test_rest_to_rest_extends_swing_windows_and_splits_missed_steps():
    from pdrlearn.displace import rest_to_rest

    t = np.arange(0, 6, 0.01)
    stance = (t % 1.0) < 0.4  # rest 0-0.4 s of every second
    # a swing-only window, one spanning three missed steps, and a duplicate of an earlier stride
    i0, i1, rows = rest_to_rest(t, stance, np.array([0.5, 1.5, 2.5]), np.array([0.9, 4.9, 2.9]))
    assert np.allclose(t[i0], [0.2, 1.2, 2.2, 3.2, 4.2], atol=0.011)
    assert np.allclose(t[i1], [1.2, 2.2, 3.2, 4.2, 5.2], atol=0.011)
    assert rows.tolist() == [0, 1, 1, 1, 1]
    # no swing between two rests -> dropped
    assert len(rest_to_rest(t, stance, np.array([0.1]), np.array([0.3]))[0]) == 0


def test_bayes_length_softens_the_clamp_by_the_class_probability():
    from pdrlearn.displace import bayes_length

    bounds = [(0.0, 1.0), (1.0, 1.5), (1.5, 10.0)]
    sig = np.array([0.04, 0.04, 0.04])
    # certain class, estimate outside it -> pulled to the bound (within about one sigma)
    certain = bayes_length(np.array([1.3, 1.2, 1.25]), np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 1.0, 0]]),
                           bounds, sig)
    assert 0.96 < certain[0] < 1.0
    # inside the certain class -> the estimate (away from the bounds)
    assert certain[1] == pytest.approx(1.2, abs=1e-3) and certain[2] == pytest.approx(1.25, abs=1e-3)
    # a doubtful wrong class (p = 0.7) cannot drag an estimate 7 sigma away from it
    doubt = bayes_length(np.array([1.3]), np.array([[0.7, 0.3, 0.0]]), bounds, sig[:1])
    assert doubt[0] == pytest.approx(1.3, abs=0.01)


def test_bayes_rules_keep_a_clear_sign_and_stair_height():
    disp = np.array([[1.3, 0.0, 0.0], [0.03, 0.0, 0.0], [0.6, 0.0, 0.35]])
    classes = pd.DataFrame({"terrain": ["flat", "flat", "flat"], "direction": ["backward"] * 3,
                            "length_class": [None, None, None]})
    thesis = StepRules(mode="thesis").apply(disp, classes)
    bayes = StepRules(mode="bayes").apply(disp, classes)
    assert thesis["length_m"].iloc[0] < 0 and bayes["length_m"].iloc[0] > 0  # clear forward estimate kept
    assert bayes["length_m"].iloc[1] < 0  # ambiguous short estimate: the class decides
    assert thesis["dz_m"].iloc[2] == 0 and bayes["dz_m"].iloc[2] == pytest.approx(0.35)
    with pytest.raises(DataError):
        StepRules(mode="fuzzy")
