"""Pure numerical kernels of the gait simulator (no state, no randomness).

Conventions: body frame FLU (x forward, y left, z up); navigation frame ENU; angles in radians;
pitch ``theta`` > 0 lifts the toes (dorsiflexion); yaw ``psi`` is the ENU heading (0 = east, CCW).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

STANDARD_GRAVITY = 9.80665  # m/s^2 (thesis ch.4.2.1.1)


# -- rotations ------------------------------------------------------------------------------------
def rot_z(psi: np.ndarray | float) -> np.ndarray:
    """Rotation(s) about z by ``psi`` (rad): (..., 3, 3)."""
    psi = np.asarray(psi, dtype=float)
    c, s = np.cos(psi), np.sin(psi)
    z, o = np.zeros_like(psi), np.ones_like(psi)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def rot_y(beta: np.ndarray | float) -> np.ndarray:
    """Rotation(s) about y by ``beta`` (rad): (..., 3, 3)."""
    beta = np.asarray(beta, dtype=float)
    c, s = np.cos(beta), np.sin(beta)
    z, o = np.zeros_like(beta), np.ones_like(beta)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def rot_x(alpha: np.ndarray | float) -> np.ndarray:
    """Rotation(s) about x by ``alpha`` (rad): (..., 3, 3)."""
    alpha = np.asarray(alpha, dtype=float)
    c, s = np.cos(alpha), np.sin(alpha)
    z, o = np.zeros_like(alpha), np.ones_like(alpha)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def foot_rotation(psi: np.ndarray | float, theta: np.ndarray | float) -> np.ndarray:
    """Foot orientation body->ENU for heading ``psi`` and pitch ``theta`` (toes up > 0), roll 0."""
    return rot_z(psi) @ rot_y(-np.asarray(theta, dtype=float))


def foot_rotation_dtheta(psi: np.ndarray | float, theta: np.ndarray | float) -> np.ndarray:
    """d(foot_rotation)/d(theta) (..., 3, 3)."""
    theta = np.asarray(theta, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    z = np.zeros_like(theta)
    # d/dtheta of rot_y(-theta) = [[-s,0,-c],[0,0,0],[c,0,-s]]
    d = np.stack([np.stack([-s, z, -c], -1), np.stack([z, z, z], -1), np.stack([c, z, -s], -1)], -2)
    return rot_z(psi) @ d


# -- interpolation ---------------------------------------------------------------------------------
def hermite(u: np.ndarray, y0, y1, m0, m1, duration: float) -> np.ndarray:
    """Cubic Hermite on normalised time ``u`` in [0, 1]; ``m0``/``m1`` are slopes per second."""
    u = np.asarray(u, dtype=float)[..., None] if np.ndim(y0) else np.asarray(u, dtype=float)
    h00 = 2 * u**3 - 3 * u**2 + 1
    h10 = u**3 - 2 * u**2 + u
    h01 = -2 * u**3 + 3 * u**2
    h11 = u**3 - u**2
    return (h00 * np.asarray(y0) + h10 * duration * np.asarray(m0) + h01 * np.asarray(y1)
            + h11 * duration * np.asarray(m1))


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
    rel = np.einsum("nji,njk->nik", rot[:-1], rot[1:])
    w = Rotation.from_matrix(rel).as_rotvec() / dt  # (n-1, 3)
    out = np.zeros((rot.shape[0], 3))
    out[1:-1] = 0.5 * (w[:-1] + w[1:])
    out[0], out[-1] = w[0], w[-1]
    return out


def block_mean(x: np.ndarray, k: int) -> np.ndarray:
    """Mean of consecutive blocks of ``k`` samples along axis 0 (the firmware's FIFO averaging)."""
    if k == 1:
        return x
    n = (x.shape[0] // k) * k
    return x[:n].reshape(n // k, k, *x.shape[1:]).mean(axis=1)


# -- environment -----------------------------------------------------------------------------------
def pressure_hpa(altitude_m: np.ndarray, p0_hpa: float) -> np.ndarray:
    """International barometric formula: pressure (hPa) at ``altitude_m`` for sea-level ``p0_hpa``."""
    return p0_hpa * (1.0 - 2.25577e-5 * np.asarray(altitude_m, dtype=float)) ** 5.25588


def earth_field_enu(total_ut: float, inclination_deg: float, declination_deg: float = 0.0) -> np.ndarray:
    """Earth magnetic field vector (uT) in ENU: horizontal toward magnetic north, dipping down."""
    inc, dec = np.radians(inclination_deg), np.radians(declination_deg)
    h = total_ut * np.cos(inc)
    return np.array([h * np.sin(dec), h * np.cos(dec), -total_ut * np.sin(inc)])


def quantize(x: np.ndarray, lsb: float) -> np.ndarray:
    """Round to the sensor's least significant bit."""
    return np.round(x / lsb) * lsb
