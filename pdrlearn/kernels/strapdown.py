"""The stride strapdown's numpy core (thesis ch.7.2): padded stride batches, the gyroscope's attitude propagation
and the trapezoid integral, one implementation for :mod:`pdrlearn.displace._kernels` (which adds scipy's
``Rotation`` start attitudes) and the numpy-only checks of :mod:`pdrlearn.kernels.handedness` (decision B129).

Strides are a padded batch: ``idx`` (B, L) holds the sample index of the j-th sample of stride b (clipped at its
last sample) and ``mask`` (B, L) marks valid samples; loops run over the sample position j only.
Quaternions are [w, x, y, z], body -> navigation frame.
"""

from __future__ import annotations

import numpy as np

#: Decision L35: coefficient of the second-order (coning) term of an attitude propagated with the rotation of the
#: mean of two adjacent samples, for samples that are the means of the rate over their own sample interval (the
#: PLASYS foot firmware averages five 100 Hz samples into each 20 Hz sample, thesis ch.4.2.3; a real IMU's delta
#: angles): 1/12 for the rate varying linearly within an interval (Bortz's rotation-vector equation, the classical
#: two-sample coning term) + 1/8 for the increments of the mean of two adjacent samples, which keep only 3/4 of the
#: non-commuting products of adjacent sample intervals. The streamed heading chain (``kernels.window.coning_yaw``)
#: and, decision L626, the offline stride strapdown (:func:`stride_quaternions`) both take it.
CONING_COEF = 1.0 / 12.0 + 1.0 / 8.0


def stride_index(starts: np.ndarray, ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Padded sample indices (B, L) and validity mask (B, L) of strides ``starts[b]..ends[b]`` inclusive."""
    starts = np.asarray(starts, dtype=np.int64)
    ends = np.asarray(ends, dtype=np.int64)
    if starts.size == 0:
        return np.zeros((0, 1), dtype=np.int64), np.zeros((0, 1), dtype=bool)
    L = int(np.max(ends - starts)) + 1
    idx = starts[:, None] + np.arange(L)[None, :]
    mask = idx <= ends[:, None]
    return np.minimum(idx, ends[:, None]), mask


def step_dt(dt):
    """Decision L83: a sample interval ``dt`` is a scalar (s) or per stride step (B, L - 1) s; shaped to multiply
    (B, L - 1, k) arrays."""
    return dt if np.ndim(dt) == 0 else np.asarray(dt, dtype=float)[:, :, None]


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Decision L663: the cross products a x b of vectors (..., 3), broadcast, written out per component (the same
    products and differences as ``np.cross``, without its axis moves and temporaries)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b, float))
    np.multiply(a1, b2, out=out[..., 0])
    out[..., 0] -= a2 * b1
    np.multiply(a2, b0, out=out[..., 1])
    out[..., 1] -= a0 * b2
    np.multiply(a0, b1, out=out[..., 2])
    out[..., 2] -= a1 * b0
    return out


def qrotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate vectors v (..., 3) by unit quaternions q (..., 4): v + 2w (u x v) + 2 u x (u x v)."""
    u = q[..., 1:]
    t = cross(u, v)
    t *= 2.0
    out = cross(u, t)
    t *= q[..., :1]  # decision L663: two arrays, the same sums ((v + w t) + u x t)
    t += v
    out += t
    return out


def cumtrapz(x: np.ndarray, dt: float | np.ndarray) -> np.ndarray:
    """Trapezoid integral along axis 1 of (B, L, k) samples ``dt`` apart (:func:`step_dt`), 0 at the start."""
    out = np.empty_like(x)
    out[:, :1] = 0.0
    step = x[:, 1:] + x[:, :-1]  # decision L663: in place, the same operations
    step *= 0.5
    step *= step_dt(dt)
    np.cumsum(step, axis=1, out=out[:, 1:])
    return out


def level_quat(g_body: np.ndarray) -> np.ndarray:
    """Quaternions (B, 4) of the minimal rotations taking each body gravity vector ``g_body`` (B, 3) to +z (the
    start attitude of :func:`pdrlearn.displace._kernels.level_rotation`, without scipy)."""
    g = np.asarray(g_body, dtype=float)
    a = g / np.linalg.norm(g, axis=1, keepdims=True)
    axis = np.cross(a, np.array([0.0, 0.0, 1.0]))
    s = np.linalg.norm(axis, axis=1, keepdims=True)
    half = 0.5 * np.arctan2(s[:, 0], a[:, 2])
    unit = np.where(s > 1e-12, axis / np.maximum(s, 1e-300), np.array([1.0, 0.0, 0.0]))
    return np.concatenate([np.cos(half)[:, None], unit * np.sin(half)[:, None]], axis=1)


def coning_increments(theta: np.ndarray, coef: float | None = None, *, inplace: bool = False) -> np.ndarray:
    """Decision L626: the body-frame rotation vectors (B, m, 3) of consecutive steps ``theta`` (each the midpoint
    rate times its interval) with the coning term ``coef`` theta_k-1 x theta_k (default :data:`CONING_COEF`, L35)
    added to each step but the first: what the rotation of the mean rate misses when the rotation axis turns (a
    swinging foot's pitch and roll, which do not commute). A new array (``inplace``: ``theta`` itself, a float array;
    decision L663); ``coef`` 0 returns the increments."""
    c = CONING_COEF if coef is None else float(coef)
    out = theta if inplace else np.array(theta, dtype=float)
    if c and out.shape[1] > 1:
        term = cross(theta[:, :-1], theta[:, 1:])
        term *= c
        out[:, 1:] += term
    return out


def stride_quaternions(q0: np.ndarray, gyr: np.ndarray, dt: float | np.ndarray, idx: np.ndarray, mask: np.ndarray,
                       gyro_bias: np.ndarray | None = None, *, coning: float | None = None) -> np.ndarray:
    """Attitude (B, L, 4) of every stride sample: ``q0`` (B, 4) at the stride start propagated with the gyroscope
    ``gyr`` (n, 3) rad/s (midpoint rate, ``gyro_bias`` (B, 3) removed, the coning term of :func:`coning_increments`
    with coefficient ``coning``, default :data:`CONING_COEF`; decision L626: 0 = the former rule); padded samples
    repeat the stride's last attitude. ``dt``, ``idx``, ``mask`` as :func:`pdrlearn.displace._kernels.strapdown`."""
    B, L = idx.shape
    bias = np.zeros((B, 3)) if gyro_bias is None else np.asarray(gyro_bias, dtype=float)
    # body-frame rotation increments of every step (midpoint rate + L626's coning term), as quaternions [w, x, y, z]
    gyr = np.asarray(gyr, dtype=float)
    w = gyr[idx[:, :-1]]  # decision L663: built in place, the same operations
    w += gyr[idx[:, 1:]]
    w *= 0.5
    w -= bias[:, None, :]
    w[~mask[:, 1:]] = 0.0
    w *= step_dt(dt)
    w = coning_increments(w, coning, inplace=True)
    ang = np.linalg.norm(w, axis=2, keepdims=True)
    half = 0.5 * ang
    w *= np.where(ang > 1e-12, np.sin(half) / np.maximum(ang, 1e-300), 0.5)
    qc = np.empty((L, 4, B))  # per sample position: components w, x, y, z of every stride (contiguous)
    qc[0] = np.asarray(q0, dtype=float).T
    qc[1:, 0] = np.cos(half[:, :, 0]).T  # decision L663: the increment dq_j waits in qc[j] until it is applied
    qc[1:, 1:] = np.transpose(w, (1, 2, 0))
    del w, ang, half
    for j in range(1, L):  # q_j = q_{j-1} * dq_j (Hamilton product, body-frame increment)
        pw, px, py, pz = qc[j - 1]
        qw_, qx_, qy_, qz_ = qc[j]
        prod = (pw * qw_ - px * qx_ - py * qy_ - pz * qz_, pw * qx_ + px * qw_ + py * qz_ - pz * qy_,
                pw * qy_ - px * qz_ + py * qw_ + pz * qx_, pw * qz_ + px * qy_ - py * qx_ + pz * qw_)
        for c in range(4):
            qc[j, c] = prod[c]
    return np.transpose(qc, (2, 0, 1))  # (B, L, 4)
