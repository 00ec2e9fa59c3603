"""Per-sample indoor tracker of seed 004 (Colombo et al. 2014) for a waist-worn IMU: the attitude EKF
(eqs. 1-11), the hybrid-automaton velocity estimator (Sec. III-C, Fig. 3), the planar position EKF with
absolute fixes every T_p seconds only while moving (eqs. 15-23) and yaw stretching fed back to the
attitude EKF (eqs. 24-28).

Frames: body FLU (x forward, y left, z up), navigation ENU (x east, y north, z up); Euler angles
``theta = (roll, pitch, yaw)`` with R = Rz(yaw) Ry(pitch) Rx(roll) taking body vectors to ENU (seed 004
App. A); yaw 0 = east, counter-clockwise (the project's heading convention). The paper's W frame has
X north and Z along gravity; the decision to use ENU is in docs/decisions/aided.md.
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.aid._base import ParamsMixin, stretched_trajectory
from pdrlearn.aid._kernels import kf_update, stretch_segment, wrap_angle
from pdrlearn.aid.sporadic import P_P0_M2, Q_C_M2
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session

log = logging.getLogger(__name__)

G_MS2 = 9.8  # g_w = [0, 0, 9.8] m/s^2 (seed 004 Sec. III-B)
# First EKF defaults (seed 004 Sec. V)
P_THETA0_RAD2 = 0.001  # P_theta(0) = diag(0.001, 0.001, 0.001) rad^2
Q_OMEGA = 0.01  # Q_omega = diag(0.01, 0.01, 0.01) (rad/s)^2
Q_G = 0.24  # Q_g = diag(0.24, 0.24, 0.24) (m/s^2)^2
Q_N = 7.3e-10  # Q_n = diag(7.3e-10, ...) (unit north vector)
Q_ETA_RAD2 = 0.32  # variance of the stretched-yaw measurement eta_z, rad^2
# Hybrid automaton (seed 004 Sec. III-C)
SIGMA_A_MIN = 0.2  # sigma_a_min, m/s^2
T_M_S = 0.5  # T_m, s
STILL, ACCEL, DECEL = 0, 1, 2  # gamma_0, gamma_1, gamma_2


# -- attitude kernels -------------------------------------------------------------------------------
def rot_zyx(theta: np.ndarray) -> np.ndarray:
    """R_zyx = Rz(yaw) Ry(pitch) Rx(roll): body -> navigation (seed 004 eqs. A.1-A.3)."""
    cx, sx = np.cos(theta[0]), np.sin(theta[0])
    cy, sy = np.cos(theta[1]), np.sin(theta[1])
    cz, sz = np.cos(theta[2]), np.sin(theta[2])
    return np.array(
        [
            [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
            [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
            [-sy, cy * sx, cy * cx],
        ]
    )


def euler_rates_matrix(theta: np.ndarray) -> np.ndarray:
    """E(theta): body angular rate -> Euler angle rates (seed 004 eq. 2 without the paper's sign flip)."""
    sx, cx = np.sin(theta[0]), np.cos(theta[0])
    cy, ty = np.cos(theta[1]), np.tan(theta[1])
    return np.array([[1.0, sx * ty, cx * ty], [0.0, cx, -sx], [0.0, sx / cy, cx / cy]])


def _rot_derivs(theta: np.ndarray) -> tuple[np.ndarray, list[np.ndarray]]:
    """R_zyx and its derivatives with respect to roll, pitch and yaw."""
    cx, sx = np.cos(theta[0]), np.sin(theta[0])
    cy, sy = np.cos(theta[1]), np.sin(theta[1])
    cz, sz = np.cos(theta[2]), np.sin(theta[2])
    Rx = np.array([[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]])
    Ry = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
    Rz = np.array([[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]])
    dRx = np.array([[0.0, 0.0, 0.0], [0.0, -sx, -cx], [0.0, cx, -sx]])
    dRy = np.array([[-sy, 0.0, cy], [0.0, 0.0, 0.0], [-cy, 0.0, -sy]])
    dRz = np.array([[-sz, -cz, 0.0], [cz, -sz, 0.0], [0.0, 0.0, 0.0]])
    RzRy = Rz @ Ry
    return RzRy @ Rx, [RzRy @ dRx, Rz @ dRy @ Rx, dRz @ Ry @ Rx]


_G_W = np.array([0.0, 0.0, G_MS2])
_N_W = np.array([0.0, 1.0, 0.0])  # north unit vector in ENU


def attitude_output(theta: np.ndarray, with_yaw: bool) -> np.ndarray:
    """o_r = U(theta) o_w: gravity and north unit vector in the body frame (+ yaw) (seed 004 eqs. 3-4)."""
    Rt = rot_zyx(theta).T
    out = np.concatenate([Rt @ _G_W, Rt @ _N_W])
    return np.append(out, theta[2]) if with_yaw else out


def attitude_output_jacobian(theta: np.ndarray, with_yaw: bool) -> np.ndarray:
    """H = d(U(theta) o_w) / d(theta) (seed 004 eq. 9), analytic."""
    _, dR = _rot_derivs(theta)
    H = np.empty((7 if with_yaw else 6, 3))
    for i, d in enumerate(dR):
        H[0:3, i] = d.T @ _G_W
        H[3:6, i] = d.T @ _N_W
    if with_yaw:
        H[6] = (0.0, 0.0, 1.0)
    return H


def euler_rates_jacobian(theta: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """d(E(theta) omega) / d(theta), analytic (for F_theta of seed 004 eq. 6)."""
    sx, cx = np.sin(theta[0]), np.cos(theta[0])
    cy, sy, ty = np.cos(theta[1]), np.sin(theta[1]), np.tan(theta[1])
    a = sx * omega[1] + cx * omega[2]
    b = cx * omega[1] - sx * omega[2]
    return np.array([[b * ty, a / cy**2, 0.0], [-a, 0.0, 0.0], [b / cy, a * sy / cy**2, 0.0]])


def _jac(fun, x: np.ndarray, eps: float = 1e-6) -> np.ndarray:
    """Central-difference Jacobian (used by the tests to check the analytic ones)."""
    f0 = fun(x)
    J = np.empty((f0.size, x.size))
    for i in range(x.size):
        d = np.zeros_like(x)
        d[i] = eps
        J[:, i] = (fun(x + d) - fun(x - d)) / (2 * eps)
    return J


def attitude_ekf_step(
    theta, P, omega, acc, north, dt, *, yaw_meas=None, q_omega=Q_OMEGA, q_g=Q_G, q_n=Q_N, q_eta=Q_ETA_RAD2
):
    """One prediction (eqs. 5-6) + update (eqs. 7-11) of the attitude EKF.

    ``acc`` is the specific force (m/s^2, body), ``north`` the measured horizontal north unit vector in
    the body frame (``None`` without a magnetometer: that block is removed), ``yaw_meas`` an optional
    stretched yaw (rad) (eta_z; the last row of eqs. 4 and 10 is removed when absent).
    """
    E = euler_rates_matrix(theta)
    theta_p = theta + dt * E @ omega  # eq. 5
    F = np.eye(3) + dt * euler_rates_jacobian(theta, omega)
    G = dt * E
    P_p = F @ P @ F.T + q_omega * (G @ G.T)  # eq. 6
    with_yaw = yaw_meas is not None
    h = attitude_output(theta_p, with_yaw)
    H = attitude_output_jacobian(theta_p, with_yaw)
    r = np.array([q_g] * 3 + [q_n] * 3 + ([q_eta] if with_yaw else []))
    z = np.empty(h.size)
    z[0:3] = acc
    if north is not None:
        z[3:6] = north
        rows = np.arange(h.size)
    else:
        rows = np.r_[0:3, 6 : h.size]
    if with_yaw:
        z[6] = yaw_meas
    nu = (z - h)[rows]
    if with_yaw:
        nu[-1] = wrap_angle(nu[-1])
    H, R = H[rows], np.diag(r[rows])
    S = H @ P_p @ H.T + R
    K = np.linalg.solve(S, H @ P_p).T  # eq. 9
    theta_n = theta_p + K @ nu  # eq. 8
    theta_n[2] = wrap_angle(theta_n[2])
    P_n = (np.eye(3) - K @ H) @ P_p  # eq. 11
    return theta_n, 0.5 * (P_n + P_n.T)


def initial_attitude(acc: np.ndarray, mag: np.ndarray | None) -> np.ndarray:
    """Roll/pitch from a static specific force and yaw from the tilt-compensated magnetometer (rad)."""
    roll = np.arctan2(acc[1], acc[2])
    pitch = np.arctan2(-acc[0], np.hypot(acc[1], acc[2]))
    if mag is None:
        return np.array([roll, pitch, 0.0])
    m = rot_zyx(np.array([roll, pitch, 0.0])) @ mag  # levelled magnetic field
    # the horizontal field points north: yaw = angle from body-forward to north, north at +90 deg (ENU)
    return np.array([roll, pitch, wrap_angle(np.pi / 2 - np.arctan2(m[1], m[0]))])


def horizontal_north(up_body: np.ndarray, mag: np.ndarray) -> np.ndarray:
    """Unit north vector in the body frame: the magnetic field minus its component along ``up_body`` (the
    vertical in the body frame, e.g. from the predicted attitude)."""
    g = up_body / np.linalg.norm(up_body)
    h = mag - (mag @ g) * g
    n = np.linalg.norm(h)
    return h / n if n > 0 else np.array([np.nan] * 3)


# -- hybrid automaton --------------------------------------------------------------------------------
class VelocityAutomaton:
    """Hybrid automaton H = (Xi, Xi_0, Sigma, Lambda, Delta, R) of seed 004 Sec. III-C (Fig. 3).

    Discrete states: ``STILL`` (gamma_0), ``ACCEL`` (gamma_1), ``DECEL`` (gamma_2); continuous state
    (delta_v, v) in m/s. Guards: M1 sigma(a, T_m) > sigma_min, M2 time in gamma_0 >= T_m, M3/M4 zero
    crossing of a with negative/positive slope, M5 a > 0, M6 v changes sign. Edges (decision, the paper's
    Fig. 3 is not in the text): gamma_0 -> gamma_1 on M1 & M2 & M5; gamma_1 -> gamma_2 on M3;
    gamma_2 -> gamma_1 on M4 with the reset of eqs. 13-14; gamma_1/gamma_2 -> gamma_0 on not M1 or M6.
    """

    def __init__(self, *, rate_hz: float, window_s: float = T_M_S, sigma_min: float = SIGMA_A_MIN):
        if not rate_hz > 0:
            raise DataError(f"VelocityAutomaton: rate_hz must be > 0 Hz, got {rate_hz}")
        self.dt = 1.0 / rate_hz
        self.window_s = window_s
        self.sigma_min = sigma_min
        self.n_win = max(int(round(window_s * rate_hz)), 2)
        self.reset()

    def reset(self) -> None:
        self.state = STILL
        self.dv = 0.0
        self.v = 0.0
        self.still_s = 0.0
        self.steps = 0
        self.prev_a = 0.0
        self._buf: list[float] = []

    def sigma(self) -> float:
        return float(np.std(self._buf)) if len(self._buf) >= 2 else 0.0

    def update(self, a: float) -> float:
        """Advance one sample with the tangential acceleration ``a`` (m/s^2); return v (m/s)."""
        self._buf.append(a)
        if len(self._buf) > self.n_win:
            self._buf.pop(0)
        m1 = self.sigma() > self.sigma_min
        m2 = self.still_s >= self.window_s
        m3 = self.prev_a > 0.0 >= a
        m4 = self.prev_a < 0.0 <= a
        m5 = a > 0.0
        s = self.state
        if s == STILL:
            if m1 and m2 and m5:
                s, self.dv, self.v, self.steps = ACCEL, 0.0, 0.0, 0
        elif not m1:
            s = STILL
        elif s == ACCEL and m3:
            s = DECEL
        elif s == DECEL and m4:
            # reset map R(gamma_2, gamma_1), eqs. 13-14
            self.v = self.v if self.steps < 2 else self.v - self.dv
            self.dv = 0.0
            self.steps += 1
            s = ACCEL
        if s == STILL:
            self.dv = self.v = 0.0  # A(gamma_0) = 0, B(gamma_0) = 0
            self.still_s = self.still_s + self.dt if self.state == STILL else 0.0
        else:
            v_old = self.v
            self.dv += self.dt * a  # A = I, B = T_c 1
            self.v += self.dt * a
            if v_old != 0.0 and np.sign(self.v) != np.sign(v_old):  # M6
                s, self.dv, self.v, self.still_s = STILL, 0.0, 0.0, 0.0
        self.state = s
        self.prev_a = a
        return self.v


def automaton_velocity(a_xu: np.ndarray, rate_hz: float, **kwargs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Run :class:`VelocityAutomaton` over a signal: ``(v m/s, discrete state, sigma_a m/s^2)``."""
    va = VelocityAutomaton(rate_hz=rate_hz, **kwargs)
    v = np.empty(len(a_xu))
    s = np.empty(len(a_xu), int)
    sg = np.empty(len(a_xu))
    for k, a in enumerate(np.asarray(a_xu, float)):
        v[k] = va.update(float(a))
        s[k] = va.state
        sg[k] = va.sigma()
    return v, s, sg


# -- the tracker -------------------------------------------------------------------------------------
class ColomboTracker(ParamsMixin):
    """Waist-IMU tracker of seed 004 with absolute fixes every ``period_s`` while moving.

    Parameters (keyword-only)
    ----------
    period_s : T_p (s). fix_sigma_m : per-axis fix standard deviation (m), default sqrt(Q_c(0)).
    sigma_v : standard deviation of the automaton velocity (m/s) (seed 004 Fig. 7: RMSE ~ 0.25 m/s).
    q_omega, q_g, q_eta : attitude EKF covariances (seed 004 Sec. V).
    q_n : variance of the measured unit north vector; ``None`` (default) = measured over the initial
        standstill window (at least 1e-6). The paper's 7.3e-10 (``Q_N``) assumes its own magnetometer
        units; with a unit vector from a phone-grade magnetometer it makes the EKF diverge
        (docs/decisions/aided.md).
    window_s, sigma_min : automaton guard settings (T_m, sigma_a_min).
    use_magnetometer : use the magnetometer block of the attitude EKF when the session has one.
    stretch, yaw_feedback : stretching output and stretched-yaw feedback to the attitude EKF.
    """

    def __init__(
        self,
        *,
        period_s: float = 8.0,
        fix_sigma_m: float = float(np.sqrt(Q_C_M2)),
        sigma_v: float = 0.25,
        q_omega: float = Q_OMEGA,
        q_g: float = Q_G,
        q_n: float | None = None,
        q_eta: float = Q_ETA_RAD2,
        window_s: float = T_M_S,
        sigma_min: float = SIGMA_A_MIN,
        use_magnetometer: bool = True,
        stretch: bool = True,
        yaw_feedback: bool = True,
        query_tolerance_s: float = 0.5,
    ):
        self.period_s = period_s
        self.fix_sigma_m = fix_sigma_m
        self.sigma_v = sigma_v
        self.q_omega, self.q_g, self.q_n, self.q_eta = q_omega, q_g, q_n, q_eta
        self.window_s = window_s
        self.sigma_min = sigma_min
        self.use_magnetometer = use_magnetometer
        self.stretch = stretch
        self.yaw_feedback = yaw_feedback
        self.query_tolerance_s = query_tolerance_s

    def run(self, session: Session, fixes: pd.DataFrame | None = None, *, start_xy=(0.0, 0.0)) -> ColomboTracker:
        """Track a session with waist accelerometer + gyroscope (+ magnetometer); returns ``self``.

        Results: ``trajectory_`` (per sample: ``t``, ``x``, ``y`` stretched, ``x_rt``, ``y_rt``, ``v``,
        ``yaw``, ``state``, ``fix_used``), ``stats_``.
        """
        acc_s = session.require("wAccelerometer", "wGyroscope", purpose="the seed 004 tracker")
        gyr_s = session["wGyroscope"]
        frame = session.require_frame("waist")
        M = frame.matrix()
        t = acc_s.t
        if len(t) < 10:
            raise DataError(f"session '{session.name}': wAccelerometer has only {len(t)} samples")
        acc = acc_s.values @ M.T
        # B21: the gyroscope (and the magnetometer) are interpolated onto the accelerometer's clock
        session.require_cover("wAccelerometer", "wGyroscope",
                              *(("wMagneticField",) if self.use_magnetometer and "wMagneticField" in session else ()))
        gyr = np.column_stack([np.interp(t, gyr_s.t, gyr_s.values[:, i]) for i in range(3)]) @ M.T
        mag = None
        if self.use_magnetometer and "wMagneticField" in session:
            ms = session["wMagneticField"]
            mag = np.column_stack([np.interp(t, ms.t, ms.values[:, i]) for i in range(3)]) @ M.T
        if not (np.isfinite(acc).all() and np.isfinite(gyr).all()):
            raise DataError(f"session '{session.name}': NaN in waist accelerometer/gyroscope; interpolate gaps first")
        fs = acc_s.rate_hz
        n0 = max(int(round(self.window_s * fs)), 1)
        theta = initial_attitude(acc[:n0].mean(0), None if mag is None else mag[:n0].mean(0))
        P = np.eye(3) * P_THETA0_RAD2
        q_n = self.q_n
        if q_n is None and mag is not None:
            up0 = rot_zyx(theta)[2]
            n_init = np.array([horizontal_north(up0, m) for m in mag[:n0]])
            q_n = float(max(np.nanmean(np.nanvar(n_init, axis=0)), 1e-6))
        self.q_n_ = q_n
        auto = VelocityAutomaton(rate_hz=fs, window_s=self.window_s, sigma_min=self.sigma_min)
        fx = fixes.sort_values("t") if fixes is not None else pd.DataFrame(columns=["t", "x", "y"], dtype=float)
        ft, fxy = fx["t"].to_numpy(float), fx[["x", "y"]].to_numpy(float)
        p = np.asarray(start_xy, float).copy()
        Pp = np.eye(2) * P_P0_M2
        n = len(t)
        out = np.zeros((n, 7))  # x, y, x_rt, y_rt, v, yaw, state
        used = np.zeros(n, bool)
        seg_inc, seg_idx = [], []
        anchor, anchor_i, l_start = p.copy(), -1, np.zeros(2)
        yaw_meas = None
        counts = dict(queries=0, fixes_used=0, fixes_missing=0, still_skipped=0)
        fix_done = np.zeros(len(ft), bool)
        for k in range(n):
            dt = t[k] - t[k - 1] if k else 1.0 / fs
            # tilt compensation with the attitude predicted from the gyroscope (not the accelerometer, which
            # carries the walking acceleration); decision in docs/decisions/aided.md
            if mag is not None:
                th_pred = theta + dt * euler_rates_matrix(theta) @ gyr[k]
                north = horizontal_north(rot_zyx(th_pred)[2], mag[k])
            else:
                north = None
            if north is not None and not np.isfinite(north).all():
                north = None
            theta, P = attitude_ekf_step(
                theta,
                P,
                gyr[k],
                acc[k],
                north,
                dt,
                yaw_meas=yaw_meas,
                q_omega=self.q_omega,
                q_g=self.q_g,
                q_n=q_n or Q_N,
                q_eta=self.q_eta,
            )
            yaw_meas = None
            # eq. 12: level the acceleration with roll and pitch, remove gravity; a_xu = forward component
            lev = rot_zyx(np.array([theta[0], theta[1], 0.0])) @ acc[k]
            v = auto.update(float(lev[0]))
            # second EKF, eqs. 16-17
            s = np.array([np.cos(theta[2]), np.sin(theta[2])])
            inc = dt * s * v
            p = p + inc
            G_th = dt * v * np.array([-np.sin(theta[2]), np.cos(theta[2])])
            Pp = Pp + np.outer(G_th, G_th) * P[2, 2] + np.outer(dt * s, dt * s) * self.sigma_v**2
            seg_inc.append(inc)
            seg_idx.append(k)
            out[k, 2:4] = p
            # eq. 19: query at i*T_p while moving
            if k and np.floor(t[k] / self.period_s) > np.floor(t[k - 1] / self.period_s):
                if auto.sigma() <= self.sigma_min:
                    counts["still_skipped"] += 1
                else:
                    counts["queries"] += 1
                    j = int(np.searchsorted(ft, t[k]))
                    cand = [c for c in (j - 1, j) if 0 <= c < len(ft) and not fix_done[c]
                            and abs(ft[c] - t[k]) <= self.query_tolerance_s]
                    if not cand:
                        counts["fixes_missing"] += 1
                    else:
                        c = min(cand, key=lambda c: abs(ft[c] - t[k]))
                        fix_done[c] = True  # a fix is used at most once (decision D15)
                        z = fxy[c]
                        l_end = z - p
                        inc_a = np.asarray(seg_inc)
                        st, _, th_bar = stretch_segment(inc_a, l_start, l_end)
                        if self.stretch:
                            out[seg_idx, 0:2] = anchor + l_start + np.cumsum(st, axis=0)
                        moving = np.hypot(inc_a[:, 0], inc_a[:, 1]) > 0
                        if self.yaw_feedback and moving.any():
                            yaw_meas = float(th_bar[np.flatnonzero(moving)[-1]])  # eta_z = theta_z bar, j = 0
                        p, Pp, _, _ = kf_update(p, Pp, z, np.array([self.fix_sigma_m]))
                        out[k, 2:4] = p
                        used[k] = True
                        counts["fixes_used"] += 1
                        anchor, anchor_i, l_start = p.copy(), k, z - p
                        seg_inc, seg_idx = [], []
            out[k, 4:7] = (v, theta[2], auto.state)
        tail = np.ones(n, bool)
        if self.stretch and anchor_i >= 0:
            tail[: anchor_i + 1] = False
        self.trajectory_ = stretched_trajectory(
            t, out, used, keep_causal=tail,
            extra={"v": out[:, 4], "yaw": out[:, 5], "state": out[:, 6].astype(int)},
        )
        self.stats_ = counts
        return self
