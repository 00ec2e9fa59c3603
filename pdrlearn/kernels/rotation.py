"""Rotations in numpy only: gravity alignment and rotation vector <-> matrix (Rodrigues' formula)."""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import DataError

_I3 = np.eye(3)
_I3.flags.writeable = False
_SKEW_AT = np.array([1, 2, 3, 5, 6, 7])  # flat 3x3 positions of [w]x's entries
_SKEW_FROM = np.array([2, 1, 2, 0, 1, 0])  # the component of w at each of them
_SKEW_SIGN = np.array([-1.0, 1.0, 1.0, -1.0, -1.0, 1.0])


def vec_norm(v: np.ndarray) -> float:
    """Euclidean norm of a 1-D vector: ``np.linalg.norm(v)`` (the same ``sqrt(v.dot(v))``) without its overhead."""
    return math.sqrt(float(v.dot(v)))


def skew(k: np.ndarray) -> np.ndarray:
    """Cross-product matrix ``[k]x`` (3x3) of a 3-vector."""
    x, y, z = np.asarray(k, dtype=np.float64).tolist()  # Python floats: a faster np.array, same values
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def gravity_rotation(g_sensor: np.ndarray) -> np.ndarray:
    """Minimal rotation ``R`` (3x3) with ``R @ g_sensor = [0, 0, |g|]`` (z up, gravity-aligned frame).

    ``g_sensor`` is the specific force measured at rest (points up, ~9.81 m/s^2). The rotation is the
    shortest one (axis ``g x z``, Rodrigues' formula), so the heading about z stays as close to the
    sensor's as possible. Raises :class:`DataError` for a zero or non-finite vector.
    """
    return gravity_rotation_xyz(*np.asarray(g_sensor, dtype=np.float64).reshape(3).tolist())


def gravity_rotation_xyz(gx: float, gy: float, gz: float) -> np.ndarray:
    """:func:`gravity_rotation` of the vector given as three Python floats (the runtime's call, E17)."""
    n = math.sqrt(gx * gx + gy * gy + gz * gz)
    if not math.isfinite(n) or n < 1e-9:
        raise DataError(f"gravity_rotation: gravity vector {[gx, gy, gz]} is zero or not finite; "
                        "estimate it from a standstill period")
    a0, a1, c = gx / n, gy / n, gz / n
    s = math.sqrt(a1 * a1 + a0 * a0)  # |a x z|, a x z = (a1, -a0, 0)
    if s < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])  # 180 deg about x
    # R = I + s [k]x + (1 - c) [k]x^2 with k = (a x z) / s = (k0, k1, 0), written out in Python floats
    # (one array construction instead of ~15 numpy calls on 3-vectors; the same formula)
    k0, k1 = a1 / s, -a0 / s
    b = 1.0 - c
    return np.array((1.0 - b * k1 * k1, b * k0 * k1, s * k1,  # flat + reshape: cheaper than nested (E20)
                     b * k0 * k1, 1.0 - b * k0 * k0, -s * k0,
                     -s * k1, s * k0, 1.0 - b * (k0 * k0 + k1 * k1))).reshape(3, 3)


def rotvec_to_matrix(w: np.ndarray) -> np.ndarray:
    """Rotation matrices ``(n, 3, 3)`` of rotation vectors ``(n, 3)`` (rad), Rodrigues' formula."""
    w = np.atleast_2d(np.asarray(w, dtype=np.float64))
    th2 = np.add.reduce(w * w, axis=1)
    th = np.sqrt(th2)  # = np.linalg.norm(w, axis=1), same arithmetic
    small = th < 1e-8
    if small.any():
        safe = np.where(small, 1.0, th)
        # sin(th)/th and (1-cos th)/th^2 with their Taylor series near 0
        a = np.where(small, 1.0 - th**2 / 6.0, np.sin(th) / safe)
        b = np.where(small, 0.5 - th**2 / 24.0, (1.0 - np.cos(th)) / safe**2)
        K = np.zeros((len(w), 9))  # [w]x, row by row: entries 1, 2, 3, 5, 6, 7
        K[:, _SKEW_AT] = w[:, _SKEW_FROM] * _SKEW_SIGN
        K = K.reshape(-1, 3, 3)
        return _I3[None] + a[:, None, None] * K + b[:, None, None] * (K @ K)
    # R = cos(th) I + a [w]x + b w w^T (the same rotation as I + a [w]x + b [w]x^2, since
    # [w]x^2 = w w^T - th^2 I): one outer product and in-place column updates, ~10 fewer numpy calls
    # than the 3x3-stack products (decision E13; within 2e-16 of the other form)
    c = np.cos(th)
    out = np.empty((len(w), 3, 3))
    np.multiply(((1.0 - c) / th2)[:, None, None] * w[:, :, None], w[:, None, :], out=out)
    aw = (np.sin(th) / th)[:, None] * w
    f = out.reshape(-1, 9)
    f[:, 0] += c
    f[:, 4] += c
    f[:, 8] += c
    f[:, 7] += aw[:, 0]
    f[:, 2] += aw[:, 1]
    f[:, 3] += aw[:, 2]
    f[:, 5] -= aw[:, 0]
    f[:, 6] -= aw[:, 1]
    f[:, 1] -= aw[:, 2]
    return out


def matrix_to_rotvec(R: np.ndarray) -> np.ndarray:
    """Rotation vector (3,) of a rotation matrix (rad; any angle up to pi)."""
    c = min(max((float(R[0, 0] + R[1, 1] + R[2, 2]) - 1.0) / 2.0, -1.0), 1.0)  # cos(angle), clipped
    th = math.acos(c)
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if th < 1e-8:
        return 0.5 * v
    if math.pi - th < 1e-6:  # 180 deg: axis from the symmetric part
        k = np.sqrt(np.clip((np.diag(R) + 1.0) / 2.0, 0.0, None))
        i = int(np.argmax(k))
        k = (R[i] + R[:, i]) / (2.0 * k[i]) if k[i] > 0 else k
        k[i] = math.sqrt(max((R[i, i] + 1.0) / 2.0, 0.0))
        return th * k / vec_norm(k)
    return th * v / (2.0 * math.sin(th))
