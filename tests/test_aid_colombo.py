"""Seed 004 per-sample components: hybrid-automaton guards, attitude EKF, waist tracker."""

import numpy as np
import pytest

from pdrlearn.aid.colombo import (
    ACCEL,
    DECEL,
    STILL,
    ColomboTracker,
    VelocityAutomaton,
    attitude_ekf_step,
    automaton_velocity,
    horizontal_north,
    initial_attitude,
    rot_zyx,
)
from pdrlearn.aid.fixgen import infrastructure_fixes
from pdrlearn.aid.synth import position_errors, synthetic_waist_session
from pdrlearn.errors import DataError, MissingSensorError

FS = 100.0


def _half_steps(n_steps=10, f=2.0, amp=1.5, push=1.0, bias=0.0):
    """Still 1 s | n steps (accelerate/decelerate half-steps), the first with an extra push | still 1 s."""
    tt = np.arange(int(n_steps / f * FS)) / FS
    a = amp * np.sin(2 * np.pi * f * tt) + bias
    a[: int(FS / f / 2)] += push
    return np.r_[np.zeros(int(FS)), a, np.zeros(int(FS))], tt


def test_automaton_states_follow_half_steps_and_drift_is_reset():
    a, tt = _half_steps(bias=0.05)
    v, s, sg = automaton_velocity(a, FS)
    i0 = int(FS)
    assert (s[: i0 - 1] == STILL).all() and (v[:i0] == 0).all()  # no motion: gamma_0, x_s = 0
    walk = s[i0 + 60 : i0 + len(tt)]
    assert set(np.unique(walk)) == {ACCEL, DECEL}
    # M3: gamma_1 -> gamma_2 where a crosses zero downwards; M4: back where it crosses upwards
    k12 = np.flatnonzero((s[:-1] == ACCEL) & (s[1:] == DECEL)) + 1
    k21 = np.flatnonzero((s[:-1] == DECEL) & (s[1:] == ACCEL)) + 1
    assert len(k12) >= 8 and len(k21) >= 8
    assert (a[k12 - 1] > 0).all() and (a[k12] <= 0).all() and (a[k21 - 1] < 0).all() and (a[k21] >= 0).all()
    # after two steps the velocity increment of each step is removed: no drift despite the 0.05 m/s^2 bias
    v_at_reset = v[k21]
    assert np.ptp(v_at_reset[2:]) < 2e-3  # one sample of integration after the reset
    plain = np.cumsum(a[i0:]) / FS
    assert plain[len(tt) - 1] - plain[len(tt) // 2] > 0.1  # plain integration drifts
    assert (s[-5:] == STILL).all() and v[-1] == 0.0  # not M1 at the end: back to gamma_0


def test_automaton_guards_m1_m2_m5_and_m6():
    va = VelocityAutomaton(rate_hz=FS)
    # M1 false (quiet signal below sigma_min): stays still even with a > 0
    for _ in range(100):
        va.update(0.05 + 0.01 * np.sin(_))
    assert va.state == STILL
    # M2: after leaving motion, gamma_0 must last T_m before a new start
    va = VelocityAutomaton(rate_hz=FS)
    a, _ = _half_steps(n_steps=2)
    for x in a[: int(FS) + 10]:
        va.update(x)
    assert va.state == ACCEL
    va.state, va.still_s = STILL, 0.0  # just came back to gamma_0
    va.update(1.0)  # M1 and M5 hold, but M2 does not
    assert va.state == STILL
    va.still_s = 0.5
    va.update(1.0)
    assert va.state == ACCEL
    # M5: a negative sample does not start the motion
    va2 = VelocityAutomaton(rate_hz=FS)
    va2.still_s = 1.0
    va2._buf = [1.0, -1.0] * 25
    va2.update(-0.5)
    assert va2.state == STILL
    # M6: the velocity changing sign sends the automaton to gamma_0 with x_s reset
    va3 = VelocityAutomaton(rate_hz=FS)
    va3.state, va3.v, va3.dv, va3._buf = DECEL, 0.005, 0.0, [1.0, -1.0] * 25
    va3.prev_a = -1.0
    va3.update(-1.0)
    assert va3.state == STILL and va3.v == 0.0
    with pytest.raises(DataError):
        VelocityAutomaton(rate_hz=0.0)


def test_attitude_from_static_gravity_and_magnetometer():
    theta = np.array([0.1, -0.2, 0.7])
    R = rot_zyx(theta)
    acc = R.T @ [0, 0, 9.8]
    mag = R.T @ [0.0, 22.0, -40.0]
    assert initial_attitude(acc, mag) == pytest.approx(theta, abs=1e-9)
    # EKF from a wrong start converges to the static attitude
    th, P = np.array([0.0, 0.0, 0.3]), np.eye(3) * 0.001
    north = horizontal_north(R[2], mag)
    for _ in range(300):
        th, P = attitude_ekf_step(th, P, np.zeros(3), acc, north, 0.01, q_n=1e-4)
    assert th == pytest.approx(theta, abs=2e-3)


def test_attitude_follows_gyro_yaw_and_yaw_feedback():
    th, P = np.zeros(3), np.eye(3) * 0.001
    for _ in range(200):  # 2 s at 0.5 rad/s about z, level, no magnetometer
        th, P = attitude_ekf_step(th, P, np.array([0, 0, 0.5]), np.array([0, 0, 9.8]), None, 0.01)
    assert th[2] == pytest.approx(1.0, abs=1e-6) and abs(th[0]) < 1e-6
    th2, _ = attitude_ekf_step(th, P * 1000, np.zeros(3), np.array([0, 0, 9.8]), None, 0.01, yaw_meas=1.2, q_eta=1e-6)
    assert th2[2] == pytest.approx(1.2, abs=0.01)


def test_tracker_with_fixes_beats_open_loop():
    ses, truth = synthetic_waist_session(1, duration_s=40)
    fx = infrastructure_fixes(truth, seed=1)
    start = (truth["x"].iloc[0], truth["y"].iloc[0])
    open_loop = ColomboTracker(period_s=1e9).run(ses, fx, start_xy=start)
    aided = ColomboTracker(period_s=4.0).run(ses, fx, start_xy=start)
    e_open = np.sqrt(np.mean(position_errors(open_loop.trajectory_, truth) ** 2))
    e_aid = np.sqrt(np.mean(position_errors(aided.trajectory_, truth) ** 2))
    assert aided.stats_["fixes_used"] >= 5 and open_loop.stats_["fixes_used"] == 0
    assert e_aid < 0.5 * e_open
    ses.frames, ses.infer_frames = {}, False  # decision D8: otherwise the frame is inferred from the data
    with pytest.raises(DataError, match="axis frame"):
        ColomboTracker().run(ses, fx)
    del ses.streams["wGyroscope"]
    with pytest.raises(MissingSensorError, match="wGyroscope"):
        ColomboTracker().run(ses, fx)


def test_analytic_jacobians_match_finite_differences():
    from pdrlearn.aid.colombo import (
        _jac,
        attitude_output,
        attitude_output_jacobian,
        euler_rates_jacobian,
        euler_rates_matrix,
    )

    rng = np.random.default_rng(0)
    for _ in range(5):
        th = rng.uniform([-0.6, -0.6, -3.0], [0.6, 0.6, 3.0])
        w = rng.normal(0, 1, 3)
        assert euler_rates_jacobian(th, w) == pytest.approx(
            _jac(lambda x, w=w: euler_rates_matrix(x) @ w, th), abs=1e-6
        )
        for yaw in (False, True):
            num = _jac(lambda x, yaw=yaw: attitude_output(x, yaw), th)
            assert attitude_output_jacobian(th, yaw) == pytest.approx(num, abs=1e-6)
