"""The waist unit's attitude: Madgwick's IMU filter and the quaternion <-> rotation-matrix conversions it needs
(numpy only; decision W92: the lean runtime's waist tracker and ``pdrlearn track`` run the same code).

Quaternions are ``(w, x, y, z)``, body to navigation frame.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.kernels.samples import Rows, values


def quat_matrices(q: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotation matrices of the (n, 4) quaternions ``(w, x, y, z)`` (normalised first), as
    ``scipy.spatial.transform.Rotation.from_quat(q[:, [1, 2, 3, 0]]).as_matrix()`` (the standard formula,
    e.g. Shuster 1993 eq. 159)."""
    q = np.asarray(q, dtype=np.float64).reshape(-1, 4)
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    m = np.empty((q.shape[0], 3, 3))
    m[:, 0, 0] = x * x - y * y - z * z + w * w
    m[:, 1, 0] = 2.0 * (x * y + z * w)
    m[:, 2, 0] = 2.0 * (x * z - y * w)
    m[:, 0, 1] = 2.0 * (x * y - z * w)
    m[:, 1, 1] = -x * x + y * y - z * z + w * w
    m[:, 2, 1] = 2.0 * (y * z + x * w)
    m[:, 0, 2] = 2.0 * (x * z + y * w)
    m[:, 1, 2] = 2.0 * (y * z - x * w)
    m[:, 2, 2] = -x * x - y * y + z * z + w * w
    return m


def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Each (n, 3) vector of ``v`` rotated by its quaternion of ``q`` (n, 4): ``Rotation.apply``."""
    return np.einsum("nij,nj->ni", quat_matrices(q), np.asarray(v, dtype=np.float64).reshape(-1, 3))


def quat_from_matrix(r: np.ndarray) -> np.ndarray:
    """The unit quaternion ``(w, x, y, z)`` of the rotation matrix ``r`` (3, 3): Shepperd's method, from the
    largest of the trace and the diagonal, as ``Rotation.from_matrix(r).as_quat()`` (reordered)."""
    m = np.asarray(r, dtype=np.float64).reshape(3, 3)
    dec = np.array([m[0, 0], m[1, 1], m[2, 2], m[0, 0] + m[1, 1] + m[2, 2]])
    c = int(np.argmax(dec))
    q = np.empty(4)  # x, y, z, w
    if c != 3:
        i, j, k = c, (c + 1) % 3, (c + 2) % 3
        q[i] = 1.0 - dec[3] + 2.0 * m[i, i]
        q[j] = m[j, i] + m[i, j]
        q[k] = m[k, i] + m[i, k]
        q[3] = m[k, j] - m[j, k]
    else:
        q[0], q[1], q[2], q[3] = m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1], 1.0 + dec[3]
    q /= np.linalg.norm(q)
    return np.array([q[3], q[0], q[1], q[2]])


def madgwick_imu(q0, gyr: np.ndarray, acc: np.ndarray, dt: float, *, gain: float) -> np.ndarray:
    """Madgwick's IMU attitude filter (gyroscope + accelerometer), one update per sample.

    Madgwick 2010 (the filter seed 001 sec. 2.2.1 uses), written as the ``ahrs`` package's
    ``Madgwick.updateIMU`` (ahrs 0.4) step by step on Python floats: the a-priori attitude is normalised,
    integrated with ``0.5 q (x) (0, w)`` (Madgwick eq. 12), corrected by ``gain`` times the normalised
    gradient ``J^T f`` of the gravity objective (eq. 25/26/33/34) and normalised again (eq. 13). A sample
    with zero rate keeps the attitude; one with zero specific force is not corrected. Equal to ``ahrs``
    to rounding (max 1e-14 in the quaternion over an hour at 100 Hz; tests/test_orient_madgwick.py) at
    ~3 us per sample instead of ~50 (its numpy per-sample form; docs/decisions/waist.md W43).

    Parameters
    ----------
    q0 : (4,) a-priori attitude ``(w, x, y, z)`` before the first sample (body to navigation frame)
    gyr : (n, 3) angular rate (rad/s); acc : (n, 3) specific force (any unit), in the body frame
    dt : sample period (s); gain : the filter gain beta (rad/s)

    Returns
    -------
    (n, 4) attitude ``(w, x, y, z)`` after each sample.
    """
    sqrt = math.sqrt
    qw, qx, qy, qz = (float(v) for v in q0)
    hd = 0.5 * dt
    out = Rows(4)  # decision E195: doubles, not a list of tuples (120 MB per recorded hour at 100 Hz)
    app = out.append
    gyr, acc = np.asarray(gyr, dtype=float).reshape(-1, 3), np.asarray(acc, dtype=float).reshape(-1, 3)
    cols = [values(c) for c in (*gyr.T, *acc.T)]  # Python floats (E195: one at a time): the loop touches no numpy
    for gx, gy, gz, ax, ay, az in zip(*cols, strict=True):
        n = sqrt(qw * qw + qx * qx + qy * qy + qz * qz)  # ahrs: Quaternion(q) is a versor
        qw, qx, qy, qz = qw / n, qx / n, qy / n, qz / n
        if gx == 0.0 and gy == 0.0 and gz == 0.0:  # ahrs: zero rate, attitude kept
            app((qw, qx, qy, qz))
            continue
        dw = -qx * gx - qy * gy - qz * gz  # 2 * qDot = q (x) (0, w), Madgwick eq. 12
        dx = qw * gx + qy * gz - qz * gy
        dy = qw * gy - qx * gz + qz * gx
        dz = qw * gz + qx * gy - qy * gx
        na = sqrt(ax * ax + ay * ay + az * az)
        if na > 0.0:
            ax, ay, az = ax / na, ay / na, az / na
            n = sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
            w, x, y, z = qw / n, qx / n, qy / n, qz / n
            f0 = 2.0 * (x * z - w * y) - ax  # objective function, Madgwick eq. 25
            f1 = 2.0 * (w * x + y * z) - ay
            f2 = 2.0 * (0.5 - x * x - y * y) - az
            if f0 != 0.0 or f1 != 0.0 or f2 != 0.0:
                g0 = -2.0 * y * f0 + 2.0 * x * f1  # J^T f, Madgwick eq. 26/34
                g1 = 2.0 * z * f0 + 2.0 * w * f1 - 4.0 * x * f2
                g2 = -2.0 * w * f0 + 2.0 * z * f1 - 4.0 * y * f2
                g3 = 2.0 * x * f0 + 2.0 * y * f1
                ng = sqrt(g0 * g0 + g1 * g1 + g2 * g2 + g3 * g3)
                if ng > 0.0:  # (ahrs would divide by zero: the measured gravity exactly opposite)
                    b = 2.0 * gain / ng  # eq. 33, in units of 2 * qDot
                    dw -= b * g0
                    dx -= b * g1
                    dy -= b * g2
                    dz -= b * g3
        qw, qx, qy, qz = qw + hd * dw, qx + hd * dx, qy + hd * dy, qz + hd * dz  # eq. 13
        n = sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
        qw, qx, qy, qz = qw / n, qx / n, qy / n, qz / n
        app((qw, qx, qy, qz))
    return out.to_array()
