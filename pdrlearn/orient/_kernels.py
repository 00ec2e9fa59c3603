"""Pure numerical kernels of the orientation stage (thesis ch.7.1 and 7.2.1).

All vectors are in the project's body frame FLU (x forward, y left, z up) unless said otherwise;
angles in rad; headings in the ENU convention (0 = east, counter-clockwise positive).
"""

from __future__ import annotations

import numpy as np
from scipy.signal import lfilter

from pdrlearn.kernels.ahrs import madgwick_imu  # noqa: F401  (W92: numpy only, in the kernels)


def wrap_angle(a: np.ndarray | float) -> np.ndarray | float:
    """Wrap angle(s) to [-pi, pi)."""
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def tilt_from_accel(acc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roll and pitch (rad) of a FLU body from its specific force (m/s^2), thesis eq. 38/39.

    Angles of the body-to-level rotation ``R = Ry(pitch) @ Rx(roll)``; at rest the body measures
    ``g * (-sin(pitch), sin(roll) cos(pitch), cos(roll) cos(pitch))``. Eq. 38 carries over unchanged.
    Eq. 39 is NOT used: it is ``roll = arctan(z / sqrt(x^2 + y^2))`` in the thesis foot frame (y up,
    z lateral), ``atan(+-y / hypot(x, z))`` in FLU, i.e. ``asin`` of the lateral gravity component - the
    roll of the other rotation order (``Rx @ Ry``). Paired with eq. 38 (the ``Ry @ Rx`` pitch) it does not
    rebuild the measured gravity once the foot is pitched; ``atan2(y, z)`` is the roll of the same
    ``Ry @ Rx`` as the pitch, so (roll, pitch) reproduce the rest specific force exactly. Both agree at
    zero pitch (decision L4; test ``test_tilt_roll_replaces_thesis_eq39_when_pitched``).
    """
    acc = np.atleast_2d(acc)
    x, y, z = acc[:, 0], acc[:, 1], acc[:, 2]
    pitch = np.arctan2(-x, np.hypot(y, z))  # thesis eq. 38
    roll = np.arctan2(y, z)  # replaces thesis eq. 39: the roll of the same Ry @ Rx as eq. 38 (decision L4)
    return roll, pitch


def level_axes(acc: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit up, level-forward and level-left vectors (body coordinates) from the gravity direction.

    ``acc`` (n, 3) is the specific force (a low-passed accelerometer at the waist); ``up`` is its
    direction, ``fwd`` the body x axis projected on the level plane, ``left = up x fwd``.
    """
    acc = np.atleast_2d(acc)
    up = acc / np.linalg.norm(acc, axis=1, keepdims=True)
    ex = np.array([1.0, 0.0, 0.0])
    fwd = ex - up[:, :1] * up  # ex - (ex . up) up
    fwd /= np.linalg.norm(fwd, axis=1, keepdims=True)
    left = np.cross(up, fwd)
    return up, fwd, left


def tilt_compensated_heading(acc: np.ndarray, mag: np.ndarray) -> np.ndarray:
    """ENU heading (rad, 0 = east, CCW) of the body's forward axis from accelerometer + magnetometer.

    Thesis eq. 33-35 in vector form: the magnetic field is projected on the level forward (``M_x``) and
    level left (``M_y``) axes, the tilt-compensated components of eq. 33/34; the compass angle
    ``atan2(M_y, M_x)`` (eq. 35) is the angle from forward to magnetic north (CCW), so the forward axis
    points ``pi/2 - atan2(M_y, M_x)`` from east. Magnetic north is taken as north (no declination).
    """
    _, fwd, left = level_axes(acc)
    mag = np.atleast_2d(mag)
    mx = np.einsum("ij,ij->i", mag, fwd)  # thesis eq. 33
    my = np.einsum("ij,ij->i", mag, left)  # thesis eq. 34
    return wrap_angle(np.pi / 2 - np.arctan2(my, mx))  # thesis eq. 35


def fit_horizontal_hard_iron(m_fwd: np.ndarray, m_left: np.ndarray, psi: np.ndarray) -> tuple[np.ndarray, float, float]:
    """Horizontal hard-iron offset from level field components seen at known relative headings (decision L84).

    With the forward axis at heading ``psi + c`` (``psi`` known up to the unknown constant ``c``) the level
    components of thesis eq. 33/34 are ``m_fwd = H sin(psi + c) + b_f`` and ``m_left = H cos(psi + c) + b_l``;
    expanded, ``m_fwd = A sin psi + B cos psi + b_f`` and ``m_left = A cos psi - B sin psi + b_l`` with
    ``A = H cos c``, ``B = H sin c``: linear least squares in (A, B, b_f, b_l). The offset is separable from
    ``c`` only when ``psi`` varies (a straight walk confounds them).

    Returns
    -------
    b : (2,) (b_f, b_l) in the field's unit;  field : fitted horizontal field ``H = hypot(A, B)``;
    resultant : resultant length of ``psi`` (1 = one heading, 0 = headings spread evenly)
    """
    psi = np.asarray(psi, dtype=float)
    s, c = np.sin(psi), np.cos(psi)
    one, zero = np.ones_like(psi), np.zeros_like(psi)
    X = np.vstack([np.column_stack([s, c, one, zero]), np.column_stack([c, -s, zero, one])])
    y = np.concatenate([np.asarray(m_fwd, dtype=float), np.asarray(m_left, dtype=float)])
    coef = np.linalg.lstsq(X, y, rcond=None)[0]
    resultant = float(np.hypot(s.mean(), c.mean())) if psi.size else 1.0
    return coef[2:4].copy(), float(np.hypot(coef[0], coef[1])), resultant


def drift_line(d: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Decisions L266 / L544: the least-squares line in ``t`` (s) of the wrapped angle difference ``d`` (rad) about
    its circular mean, iterated 3 x so a drift past +-180 deg does not wrap away; its value at each ``t``
    (unwrapped, rad): an offset plus a constant rate (a gyroscope's remaining bias)."""
    d, t = np.asarray(d, dtype=float), np.asarray(t, dtype=float)
    line = np.zeros(len(d))
    X = np.column_stack([np.ones_like(t), t - t.mean()]) if len(t) else np.zeros((0, 2))
    for _ in range(3):  # the line about the current offset
        centre = np.arctan2(np.mean(np.sin(d - line)), np.mean(np.cos(d - line))) + line
        r = wrap_angle(d - centre)
        line = centre + X @ np.linalg.lstsq(X, r, rcond=None)[0]
    return line


def compass_disagreement(m_fwd: np.ndarray, m_left: np.ndarray, psi: np.ndarray, *,
                         max_resultant: float | None = None,
                         t: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """Decision L182: how far the compass disagrees with a gyroscope-integrated heading ``psi`` (rad, relative),
    beyond a hard-iron offset and a constant heading offset: :func:`fit_horizontal_hard_iron`'s model fitted, the
    angle (rad) between each sample's level field less the fitted offset and the model's field at its ``psi``.
    A field of the Earth plus a hard-iron offset (any mounting yaw) fits it up to noise; a field that changes
    along the walk (steel, an indoor disturbance) or a heading that drifts away from the compass does not.
    ``max_resultant`` (decision L544): when the headings' resultant length exceeds it (they spread too little to
    separate the offset from the field: a straight walk, L84's gate), no offset is fitted (zero) and only the
    field's size and heading offset are - else the offset swallows the Earth field and the angle is the noise of
    the little left (a straight 17 min walk: fitted field 0.5 uT of 26 uT, median 40-55 deg per window).
    ``t`` (s, decision L544): the heading offset is a line in ``t`` (:func:`drift_line` of the compass's heading
    less ``psi``), not a constant: a foot heading whose gyroscope bias turns it steadily (T3: up to 1.3 deg/s after
    an hour) agrees with a consistent compass, while a field that changes from place to place still does not.

    Returns (angles (n,) wrapped rad, fitted horizontal field ``H``)."""
    psi = np.asarray(psi, dtype=float)
    b, field, resultant = fit_horizontal_hard_iron(m_fwd, m_left, psi)
    zeroed = max_resultant is not None and resultant > max_resultant  # decision L544
    b = np.zeros(2) if zeroed else b
    s, c = np.sin(psi), np.cos(psi)
    X = np.vstack([np.column_stack([s, c]), np.column_stack([c, -s])])
    y = np.concatenate([np.asarray(m_fwd, dtype=float) - b[0], np.asarray(m_left, dtype=float) - b[1]])
    a, bb = np.linalg.lstsq(X, y, rcond=None)[0] if psi.size else (0.0, 0.0)
    pf, pl = a * s + bb * c, a * c - bb * s  # the model's level field at each heading
    mf, ml = y[: psi.size], y[psi.size:]
    if t is not None and psi.size > 1:  # decision L544: the compass's heading (pi/2 - atan2, eq. 35) less psi
        d = wrap_angle(np.pi / 2 - np.arctan2(ml, mf) - psi)  # about a drifting line
        return wrap_angle(d - drift_line(d, t)), float(np.hypot(a, bb)) if zeroed else field
    return wrap_angle(np.arctan2(ml, mf) - np.arctan2(pl, pf)), float(np.hypot(a, bb)) if zeroed else field


def yaw_rate(acc: np.ndarray, gyr: np.ndarray) -> np.ndarray:
    """Rate of turn about the vertical (rad/s, CCW positive): gyroscope projected on the up direction."""
    acc = np.atleast_2d(acc)
    up = acc / np.linalg.norm(acc, axis=1, keepdims=True)
    return np.einsum("ij,ij->i", np.atleast_2d(gyr), up)


def phi_for_rate(dt: float, *, phi: float = 0.92, rate_hz: float = 20.0) -> float:
    """Complementary-filter coefficient at sample period ``dt`` with the thesis time constant.

    The thesis uses phi = 0.92 at 20 Hz (thesis ch.7.1), i.e. a time constant
    ``tau = phi * dT / (1 - phi) = 0.575 s`` (thesis eq. 37); other rates keep ``tau``.
    """
    tau = phi * (1.0 / rate_hz) / (1.0 - phi)  # thesis eq. 37
    return tau / (tau + dt)


def complementary_filter(theta_ma: np.ndarray, rate: np.ndarray, dt: float, *, phi: float) -> np.ndarray:
    """Complementary filter of an absolute angle and an angular rate (thesis eq. 36).

    ``theta_k = phi * (theta_{k-1} + rate_k * dt) + (1 - phi) * theta_ma_k`` on the unwrapped
    magnetometer angle; ``phi`` weights the gyroscope path (see docs/decisions/localization.md:
    eq. 36 prints the weights the other way round, eq. 37 and the text fix them this way).
    Returns the unwrapped filtered angle (rad).
    """
    theta_ma = np.unwrap(np.asarray(theta_ma, dtype=float))
    if theta_ma.size == 0:
        return theta_ma
    u = phi * np.asarray(rate, dtype=float) * dt + (1.0 - phi) * theta_ma
    zi = np.array([phi * theta_ma[0]])
    out, _ = lfilter([1.0], [1.0, -phi], u, zi=zi)
    return out


def deadband(theta: np.ndarray, threshold: float) -> np.ndarray:
    """Hold an angle until it moves more than ``threshold`` (rad) from the held value (thesis ch.7.1)."""
    vals = np.asarray(theta, dtype=float).tolist()
    out = np.empty(len(vals))
    if not vals:
        return out
    held = vals[0]
    for i, v in enumerate(vals):
        if abs(v - held) > threshold:
            held = v
        out[i] = held
    return out


def angle_kalman(theta_meas: np.ndarray, rate: np.ndarray, dt: float, *, q_angle: float, q_bias: float,
                 r: float, use_meas: np.ndarray | None = None,
                 x0: tuple[float, float] = (0.0, 0.0)) -> tuple[np.ndarray, np.ndarray]:
    """Two-state angle Kalman filter, state ``[theta, b]`` (thesis eq. 40-43).

    Parameters
    ----------
    theta_meas : (n,) measured angle (rad), e.g. the accelerometer pitch (thesis eq. 41)
    rate : (n,) gyroscope rate (rad/s), the control input ``u`` (thesis eq. 40)
    dt : sample period (s)
    q_angle, q_bias : process noise of angle and bias (thesis eq. 42)
    r : measurement noise variance of the angle (rad^2, thesis eq. 43)
    use_meas : (n,) bool; where False the measurement is skipped (e.g. foot in swing, accelerometer
        not measuring gravity)

    Returns
    -------
    theta, bias : (n,) filtered angle (rad) and gyroscope bias (rad/s)
    """
    z = np.asarray(theta_meas, dtype=float).tolist()
    u = np.asarray(rate, dtype=float).tolist()
    m = [True] * len(z) if use_meas is None else np.asarray(use_meas, dtype=bool).tolist()
    th, b = float(x0[0]), float(x0[1])
    p00, p01, p11 = 1.0, 0.0, 1.0
    qa, qb = q_angle * dt, q_bias  # thesis eq. 42: Q = diag(sigma(wg) dT, sigma(b))
    out_t = np.empty(len(z))
    out_b = np.empty(len(z))
    for k in range(len(z)):
        # predict, thesis eq. 40: theta_k = theta_{k-1} - dT b_{k-1} + dT u_{k-1}
        th = th + dt * (u[k] - b)
        p00 = p00 - dt * (2 * p01 - dt * p11) + qa
        p01 = p01 - dt * p11
        p11 = p11 + qb
        if m[k]:
            # update with H = [1 0] (thesis eq. 41)
            s = p00 + r
            k0, k1 = p00 / s, p01 / s
            y = z[k] - th
            th += k0 * y
            b += k1 * y
            p11 -= k1 * p01
            p01 -= k0 * p01
            p00 -= k0 * p00
        out_t[k] = th
        out_b[k] = b
    return out_t, out_b
