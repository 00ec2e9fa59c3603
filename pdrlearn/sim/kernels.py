"""Pure numerical kernels of the gait simulator (no state, no randomness).

Conventions: body frame FLU (x forward, y left, z up); navigation frame ENU; angles in radians;
pitch ``theta`` > 0 lifts the toes (dorsiflexion); yaw ``psi`` is the ENU heading (0 = east, CCW).
"""

from __future__ import annotations

import numpy as np

STANDARD_GRAVITY = 9.80665  # m/s^2 (thesis ch.4.2.1.1)
#: decision S44: rows per block of :func:`angular_rate_body` (65536 x 9 float64 = 4.7 MB of relative rotations)
RATE_CHUNK = 1 << 16


# -- rotations ------------------------------------------------------------------------------------
def _rot(angle: np.ndarray | float, i: int, j: int) -> np.ndarray:
    """Rotation(s) by ``angle`` in the (i, j) plane (i -> j positive): (..., 3, 3)."""
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    out = np.zeros((*angle.shape, 3, 3))
    k = 3 - i - j
    out[..., k, k] = 1.0
    out[..., i, i] = c
    out[..., j, j] = c
    out[..., j, i] = s
    out[..., i, j] = -s
    return out


def rot_z(psi: np.ndarray | float) -> np.ndarray:
    """Rotation(s) about z by ``psi`` (rad): (..., 3, 3)."""
    return _rot(psi, 0, 1)


def rot_y(beta: np.ndarray | float) -> np.ndarray:
    """Rotation(s) about y by ``beta`` (rad): (..., 3, 3)."""
    return _rot(beta, 2, 0)


def rot_x(alpha: np.ndarray | float) -> np.ndarray:
    """Rotation(s) about x by ``alpha`` (rad): (..., 3, 3)."""
    return _rot(alpha, 1, 2)


def euler_zyx(psi: np.ndarray | float, beta: np.ndarray | float, alpha: np.ndarray | float) -> np.ndarray:
    """``rot_z(psi) @ rot_y(beta) @ rot_x(alpha)`` filled directly: (..., 3, 3)."""
    psi, beta, alpha = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (psi, beta, alpha)))
    cz, sz, cy, sy, cx, sx = np.cos(psi), np.sin(psi), np.cos(beta), np.sin(beta), np.cos(alpha), np.sin(alpha)
    out = np.empty((*psi.shape, 3, 3))
    out[..., 0, 0] = cz * cy
    out[..., 0, 1] = cz * sy * sx - sz * cx
    out[..., 0, 2] = cz * sy * cx + sz * sx
    out[..., 1, 0] = sz * cy
    out[..., 1, 1] = sz * sy * sx + cz * cx
    out[..., 1, 2] = sz * sy * cx - cz * sx
    out[..., 2, 0] = -sy
    out[..., 2, 1] = cy * sx
    out[..., 2, 2] = cy * cx
    return out


def foot_rotation(
    psi: np.ndarray | float, theta: np.ndarray | float, roll: np.ndarray | float | None = None
) -> np.ndarray:
    """Foot orientation body->ENU for heading ``psi``, pitch ``theta`` (toes up > 0) and ``roll`` (about the
    foot's long axis, > 0 lifts the left edge)."""
    return euler_zyx(psi, -np.asarray(theta, dtype=float), 0.0 if roll is None else roll)


def foot_rotate(psi: float, theta: np.ndarray, r: np.ndarray) -> np.ndarray:
    """``foot_rotation(psi, theta) @ r`` for a fixed heading ``psi`` and pitches ``theta`` (n,) -> (n, 3)."""
    theta = np.asarray(theta, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    lx = c * r[0] - s * r[2]
    lz = s * r[0] + c * r[2]
    cp, sp = np.cos(psi), np.sin(psi)
    return np.stack([cp * lx - sp * r[1], sp * lx + cp * r[1], lz], axis=-1)


def foot_rotate_dtheta(psi: float, theta: float, r: np.ndarray) -> np.ndarray:
    """d/dtheta of :func:`foot_rotate` at a single pitch (3,)."""
    c, s = np.cos(theta), np.sin(theta)
    lx = -s * r[0] - c * r[2]
    lz = c * r[0] - s * r[2]
    cp, sp = np.cos(psi), np.sin(psi)
    return np.array([cp * lx, sp * lx, lz])


# -- interpolation ---------------------------------------------------------------------------------
def hermite(u: np.ndarray, y0, y1, m0, m1, duration: float) -> np.ndarray:
    """Cubic Hermite on normalised time ``u`` in [0, 1]; ``m0``/``m1`` are slopes per second."""
    u = np.asarray(u, dtype=float)[..., None] if np.ndim(y0) else np.asarray(u, dtype=float)
    h00 = 2 * u**3 - 3 * u**2 + 1
    h10 = u**3 - 2 * u**2 + u
    h01 = -2 * u**3 + 3 * u**2
    h11 = u**3 - u**2
    return (
        h00 * np.asarray(y0) + h10 * duration * np.asarray(m0) + h01 * np.asarray(y1) + h11 * duration * np.asarray(m1)
    )


def _windowed_exp_integral(tau: np.ndarray, k: float, duration: float) -> np.ndarray:
    """int_0^tau exp(-k s) (1 - s / duration)^2 ds, closed form (k > 0)."""

    def antiderivative(s):
        v = 1.0 - s / duration
        return -np.exp(-k * s) * (v**2 / k - 2.0 * v / (duration * k**2) + 2.0 / (duration**2 * k**3))

    return antiderivative(tau) - antiderivative(0.0)


def decaying_rocker(tau: np.ndarray, theta0: float, rate0: float, duration: float, rise_s: float,
                    decay_s: float) -> np.ndarray:
    """Pitch (rad) of a heel rocker that comes to rest gradually (decisions S31), at times ``tau`` (s) after the
    contact, clipped to [0, ``duration``].

    The pitch rate is ``[rate0 e^(-tau/rise) + c (1 - e^(-tau/rise))] e^(-tau/decay) (1 - tau/duration)^2``: it
    starts at ``rate0``, moves within a few ``rise_s`` to the rocker's largest rate, then decays (its largest
    deceleration just after the contact, none at the end), and the window reaches rest at ``duration`` with zero
    rate and zero angular acceleration. ``c`` makes the pitch go from ``theta0`` to exactly 0.
    """
    tau = np.clip(np.asarray(tau, dtype=float), 0.0, duration)
    k_decay, k_both = 1.0 / decay_s, 1.0 / decay_s + 1.0 / rise_s
    g_decay, g_both = (_windowed_exp_integral(np.float64(duration), k, duration) for k in (k_decay, k_both))
    c = -(theta0 + rate0 * g_both) / (g_decay - g_both)
    return theta0 + (rate0 - c) * _windowed_exp_integral(tau, k_both, duration) + c * _windowed_exp_integral(
        tau, k_decay, duration)


def clamped_spline(tk: np.ndarray, yk: np.ndarray, d0: np.ndarray, d1: np.ndarray, tq: np.ndarray) -> np.ndarray:
    """Cubic spline through knots ``(tk, yk)`` (k, m) with end slopes ``d0``, ``d1`` (m,), C2 inside.

    Solves the tridiagonal continuity equations for the interior slopes, then evaluates the cubic Hermite
    pieces at ``tq``; returns (len(tq), m).
    """
    tk = np.asarray(tk, float)
    yk = np.asarray(yk, float).reshape(len(tk), -1)
    h = np.diff(tk)
    k = len(tk)
    slopes = np.zeros_like(yk)
    slopes[0], slopes[-1] = d0, d1
    if k > 2:
        n = k - 2
        a = np.zeros((n, n))
        rhs = np.zeros((n, yk.shape[1]))
        for i in range(1, k - 1):
            row = i - 1
            a[row, row] = 2.0 * (1.0 / h[i - 1] + 1.0 / h[i])
            rhs[row] = 3.0 * ((yk[i] - yk[i - 1]) / h[i - 1] ** 2 + (yk[i + 1] - yk[i]) / h[i] ** 2)
            if row > 0:
                a[row, row - 1] = 1.0 / h[i - 1]
            else:
                rhs[row] -= slopes[0] / h[i - 1]
            if row < n - 1:
                a[row, row + 1] = 1.0 / h[i]
            else:
                rhs[row] -= slopes[-1] / h[i]
        slopes[1:-1] = np.linalg.solve(a, rhs)
    seg = np.clip(np.searchsorted(tk, tq, side="right") - 1, 0, k - 2)
    u = ((tq - tk[seg]) / h[seg])[:, None]
    hh = h[seg][:, None]
    return (
        (2 * u**3 - 3 * u**2 + 1) * yk[seg]
        + (u**3 - 2 * u**2 + u) * hh * slopes[seg]
        + (-2 * u**3 + 3 * u**2) * yk[seg + 1]
        + (u**3 - u**2) * hh * slopes[seg + 1]
    )


def skewed_phase(ph: np.ndarray, *, shift: float, skew: float, centre: float) -> np.ndarray:
    """Monotone warp of a step phase (1 per step) that runs fastest ``centre`` steps after each
    integer of ``ph - shift``: integers map to integers, the warp's rate is 1 + skew cos(2 pi (u - centre)).

    ``skew`` in [0, 1) (0 = identity shifted by ``shift``); smooth and periodic in the step.
    """
    x = np.asarray(ph, dtype=float) - shift
    k = np.floor(x)
    u = x - k
    return k + u + skew / (2 * np.pi) * (np.sin(2 * np.pi * (u - centre)) + np.sin(2 * np.pi * centre))


def sawtooth_surge(ph: np.ndarray, *, drop: float, harmonics: int = 3) -> np.ndarray:
    """Unit-amplitude forward displacement whose 2nd derivative is a band-limited rising sawtooth in the
    step phase ``ph``: slowly increasing forward acceleration, dropping around ``drop`` steps after each
    integer (sum of sin(2 pi n q) / n^3, n = 1..harmonics)."""
    q = np.asarray(ph, dtype=float) - drop
    return sum(np.sin(2 * np.pi * n * q) / n**3 for n in range(1, harmonics + 1))


def smoothstep(u: np.ndarray) -> np.ndarray:
    """C2 quintic ramp 0 -> 1 on ``u`` in [0, 1] (clipped outside)."""
    u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    return u**3 * (10 - 15 * u + 6 * u**2)


# -- differentiation of poses -> inertial readings ------------------------------------------------
def specific_force_body(pos: np.ndarray, rot: np.ndarray, dt: float) -> np.ndarray:
    """Specific force (m/s^2) in the body frame from positions (n, 3) and orientations (n, 3, 3).

    Acceleration is the second difference of the position (interval velocities
    ``(p[i+1]-p[i])/dt`` differenced again), so that its sum times ``dt`` telescopes exactly to the
    velocity change; gravity is added as a specific force: ``f = R^T (a + [0, 0, g])``, i.e. a unit at
    rest reads +g along its up axis.
    """
    v = np.diff(pos, axis=0) / dt  # (n-1, 3) interval velocities
    a = np.zeros_like(pos)
    a[1:-1] = np.diff(v, axis=0) / dt
    a[:, 2] += STANDARD_GRAVITY
    return np.einsum("nji,nj->ni", rot, a)


def angular_rate_body(rot: np.ndarray, dt: float) -> np.ndarray:
    """Body-frame angular rate (rad/s) from orientations (n, 3, 3) body->nav.

    The rate over each interval is the rotation vector of ``R[i]^T R[i+1]`` divided by ``dt``; a sample's
    rate is the mean of its two adjacent intervals.
    """
    n = rot.shape[0]
    w = np.empty((max(n - 1, 0), 3))  # (n-1, 3)
    for a in range(0, n - 1, RATE_CHUNK):  # decision S44: in blocks, so the (n, 3, 3) products are never all held
        b = min(a + RATE_CHUNK, n - 1)
        w[a:b] = rotvec(np.einsum("nji,njk->nik", rot[a:b], rot[a + 1 : b + 1])) / dt
    out = np.zeros((rot.shape[0], 3))
    out[1:-1] = 0.5 * (w[:-1] + w[1:])
    out[0], out[-1] = w[0], w[-1]
    return out


def rotvec(rel: np.ndarray) -> np.ndarray:
    """Rotation vectors (n, 3) of rotation matrices (n, 3, 3) with angles below pi/2 (small increments)."""
    vee = 0.5 * np.stack([rel[:, 2, 1] - rel[:, 1, 2], rel[:, 0, 2] - rel[:, 2, 0], rel[:, 1, 0] - rel[:, 0, 1]], -1)
    s = np.linalg.norm(vee, axis=1)
    c = 0.5 * (rel[:, 0, 0] + rel[:, 1, 1] + rel[:, 2, 2] - 1.0)
    angle = np.arctan2(s, c)
    scale = np.where(s > 1e-12, angle / np.where(s > 1e-12, s, 1.0), 1.0)
    return vee * scale[:, None]


def block_mean(x: np.ndarray, k: int) -> np.ndarray:
    """Mean of consecutive blocks of ``k`` samples along axis 0 (the firmware's FIFO averaging)."""
    if k == 1:
        return x
    n = (x.shape[0] // k) * k
    return x[:n].reshape(n // k, k, *x.shape[1:]).mean(axis=1)


# -- environment -----------------------------------------------------------------------------------
def earth_field_enu(total_ut: float, inclination_deg: float, declination_deg: float = 0.0) -> np.ndarray:
    """Earth magnetic field vector (uT) in ENU: horizontal toward magnetic north, dipping down."""
    inc, dec = np.radians(inclination_deg), np.radians(declination_deg)
    h = total_ut * np.cos(inc)
    return np.array([h * np.sin(dec), h * np.cos(dec), -total_ut * np.sin(inc)])


def quantize(x: np.ndarray, lsb: float) -> np.ndarray:
    """Round to the sensor's least significant bit."""
    return np.round(x / lsb) * lsb
