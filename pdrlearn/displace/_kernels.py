"""Pure numerical kernels of the displacement stage (thesis ch.7.2).

Strides are processed as a padded batch: ``idx`` (B, L) holds the sample index of the j-th sample of
stride b (clipped at its last sample) and ``mask`` (B, L) marks valid samples. Loops run over the
sample position j only, so one hour of data costs a few dozen vectorised iterations.
Units: m, s, m/s, m/s^2, rad, rad/s. Frames: body FLU, navigation = level frame whose x axis is the
foot's forward direction at the stride start (yaw of the stride start = 0), z up.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import make_interp_spline
from scipy.spatial.transform import Rotation

from pdrlearn.kernels import histospline as H

# the numpy core, shared with io.handedness and the runtime (decision B129); re-exported under the old names
from pdrlearn.kernels.strapdown import cumtrapz as _cumtrapz  # noqa: F401
from pdrlearn.kernels.strapdown import qrotate as _qrotate  # noqa: F401
from pdrlearn.kernels.strapdown import (
    stride_index,  # noqa: F401
    stride_quaternions,  # noqa: F401
)
from pdrlearn.kernels.stride import (  # noqa: F401 (numpy-only rules, shared with the runtime)
    DEFAULT_DOWN_MODE,
    DOWN_MODES,
    altitude_change,
    apply_direction,
    clamp_length,
    horizontal_part,
    terrain_distance,
)


def upsample_block_means(t: np.ndarray, x: np.ndarray, k: int, *,
                         degree: int = 5) -> tuple[np.ndarray, np.ndarray]:
    """Upsample block-averaged samples ``k`` times, preserving each block's mean (a histospline).

    The PLASYS firmware sends the mean of consecutive samples (thesis ch.4: 20 Hz); each sample is the
    average over its period, stamped at the period's centre. An interpolating spline of odd ``degree``
    through the running integral at the block edges, differentiated, gives a smooth signal whose block
    averages are the samples, so the strapdown can integrate rotations and accelerations on a finer grid.
    Degree 5 (decision L24) makes the reconstructed signal the smoothest in its second derivative
    instead of its first (degree 3). Returns (t_fine, x_fine).
    """
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    edges = H.block_edges(t)  # the block edges and running integral the streamed kernel shares (decision L141)
    width = np.diff(edges)
    integral = H.running_integral(edges, x)
    deg = H.spline_degree(len(edges), degree)  # a short input takes the highest odd degree it supports
    deriv = make_interp_spline(edges, integral, k=deg, axis=0).derivative()
    frac = (np.arange(k) + 0.5) / k
    t_fine = (edges[:-1, None] + width[:, None] * frac[None, :]).ravel()
    return t_fine, deriv(t_fine)


def upsample_runs(t: np.ndarray, x: np.ndarray, k: int, period: float, *,
                  degree: int = 5) -> tuple[np.ndarray, np.ndarray]:
    """Decision L87: :func:`upsample_block_means` on each run of evenly spaced samples on its own.

    A run ends where an interval exceeds 1.5 ``period`` (s; a dropped sample, B64's ``Stream.gaps``), so no
    block is widened across the hole: every block keeps its own width, and the fine grid has one long interval
    per drop (for the timestamp integration, L83, to span). A run of one sample is held over one ``period``.
    Still ``k`` fine samples per input sample, in order. A clock without such an interval is one run: the
    same call as :func:`upsample_block_means` (bit for bit)."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    cut = np.flatnonzero(np.diff(t) > 1.5 * float(period)) + 1
    if not cut.size:
        return upsample_block_means(t, x, k, degree=degree)
    frac = (np.arange(k) + 0.5) / k - 0.5
    ts, xs = [], []
    for a, b in zip(np.r_[0, cut], np.r_[cut, len(t)], strict=True):
        if b - a == 1:
            ts.append(t[a] + float(period) * frac)
            xs.append(np.repeat(x[a:b], k, axis=0))
        else:
            tf, xf = upsample_block_means(t[a:b], x[a:b], k, degree=degree)
            ts.append(tf)
            xs.append(xf)
    return np.concatenate(ts), np.concatenate(xs, axis=0)


def erode_runs(mask: np.ndarray, frac: float, max_cut: int | None = None) -> np.ndarray:
    """Shrink every True run of ``mask`` by ``frac`` of its length at each end (keeps its calm middle), by at
    most ``max_cut`` samples at each end (None: no limit). The limit keeps a long rest a rest: 25 % of a
    600 s stand is 150 s at each end without measurements, where the attitude filter drifts on the gyroscope
    alone (a level stride after the stand came out 1.95 m down)."""
    m = np.asarray(mask, dtype=bool)
    if frac <= 0 or not m.any():
        return m.copy()
    d = np.diff(np.concatenate([[0], m.astype(np.int8), [0]]))
    starts, stops = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    cut = ((stops - starts) * frac).astype(np.int64)
    if max_cut is not None:
        cut = np.minimum(cut, int(max_cut))
    out = np.zeros_like(m)
    for a, b in zip(starts + cut, stops - cut, strict=True):
        if b > a:
            out[a:b] = True
    return out


def step_clock(dt, B: int, L: int) -> np.ndarray:
    """Time (B, L) s since each stride's start for per-step intervals ``dt`` (B, L - 1) (decision L83); the
    sample index times ``dt`` for a scalar."""
    if np.ndim(dt) == 0:
        return np.broadcast_to(np.arange(L, dtype=float)[None, :] * float(dt), (B, L))
    return np.concatenate([np.zeros((B, 1)), np.cumsum(np.asarray(dt, dtype=float), axis=1)], axis=1)


def level_rotation(g_body: np.ndarray) -> Rotation:
    """Minimal rotations (batch) taking each body gravity vector ``g_body`` (B, 3) to +z."""
    g = np.asarray(g_body, dtype=float)
    a = g / np.linalg.norm(g, axis=1, keepdims=True)
    z = np.array([0.0, 0.0, 1.0])
    axis = np.cross(a, z)
    s = np.linalg.norm(axis, axis=1, keepdims=True)
    ang = np.arctan2(s[:, 0], a @ z)
    unit = np.where(s > 1e-12, axis / np.maximum(s, 1e-300), np.array([1.0, 0.0, 0.0]))
    return Rotation.from_rotvec(unit * ang[:, None])


def strapdown(acc: np.ndarray, gyr: np.ndarray, dt: float | np.ndarray, idx: np.ndarray, mask: np.ndarray,
              g_body: np.ndarray, gyro_bias: np.ndarray | None = None,
              init: Rotation | None = None, q: np.ndarray | None = None, *,
              coning: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Rotate each stride's specific force into its navigation frame and remove gravity.

    Parameters
    ----------
    acc, gyr : (n, 3) FLU specific force (m/s^2) and angular rate (rad/s)
    dt : sample period (s), or the interval of every stride step (B, L - 1) s (decision L83: the timestamps)
    idx, mask : from :func:`stride_index`
    g_body : (B, 3) gravity as measured at each stride's start (its direction sets the initial attitude,
        its norm is the local gravity that is removed, so a sensor scale error cancels)
    gyro_bias : (B, 3) rate offset removed during each stride (ZARU), or None
    init : initial attitude per stride (overrides the one from ``g_body``)
    q : (B, L, 4) attitude of every stride sample from :func:`stride_attitude` (computed when None)
    coning : the coning coefficient of that attitude (decision L626; None: the default, 0.0: the former rule, which
        the checks that integrate at a unit's native rate keep - the lead's amendment of L626)

    Returns
    -------
    a_nav : (B, L, 3) gravity-free acceleration in the navigation frame, zero on padded samples
    yaw_change : (B,) change of the foot's heading over the stride (rad, CCW)
    """
    B, L = idx.shape
    if B == 0:
        return np.zeros((B, L, 3)), np.zeros(0)
    if q is None:
        q = stride_attitude(gyr, dt, idx, mask, g_body, gyro_bias, init, coning=coning)
    a_nav = _qrotate(q, np.asarray(acc, dtype=float)[idx])  # decision L663: no zeroed copy
    a_nav[:, :, 2] -= np.linalg.norm(g_body, axis=1)[:, None]
    a_nav[~mask] = 0.0
    n = mask.sum(axis=1) - 1
    f = _qrotate(q[np.arange(B), n], np.tile([1.0, 0.0, 0.0], (B, 1)))
    return a_nav, np.arctan2(f[:, 1], f[:, 0])


def stride_attitude(gyr: np.ndarray, dt: float | np.ndarray, idx: np.ndarray, mask: np.ndarray, g_body: np.ndarray,
                    gyro_bias: np.ndarray | None = None, init: Rotation | None = None, *,
                    coning: float | None = None) -> np.ndarray:
    """Attitude (B, L, 4) quaternions [w, x, y, z] body -> navigation frame of every stride sample:
    the gravity (or ``init``) attitude at the stride start propagated with the gyroscope (midpoint rate,
    ``gyro_bias`` (B, 3) rad/s removed). Arguments as :func:`strapdown`; padded samples repeat the
    stride's last attitude."""
    rot = level_rotation(g_body) if init is None else init
    xyzw = rot.as_quat()
    return stride_quaternions(xyzw[:, [3, 0, 1, 2]], gyr, dt, idx, mask, gyro_bias, coning=coning)


def _qmul(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Hamilton products p q of quaternions (..., 4) [w, x, y, z]."""
    pw, px, py, pz = np.moveaxis(p, -1, 0)
    qw, qx, qy, qz = np.moveaxis(q, -1, 0)
    return np.stack([pw * qw - px * qx - py * qy - pz * qz, pw * qx + px * qw + py * qz - pz * qy,
                     pw * qy - px * qz + py * qw + pz * qx, pw * qz + px * qy - py * qx + pz * qw], axis=-1)


def end_tilt(q: np.ndarray, acc: np.ndarray, idx: np.ndarray, mask: np.ndarray, half_w: int
             ) -> tuple[np.ndarray, np.ndarray]:
    """Decision L68: tilt error of each stride's propagated attitude at its end, where the foot rests again.
    Gravity there is the mean specific force over +-``half_w`` samples around the last stride sample (as
    ``g_body`` at the start, L6); the attitude ``q`` (B, L, 4) of the last sample rotates it to ``v`` in the
    navigation frame. Returns the unit horizontal axes (B, 3) and angles (B,) rad of the rotations taking
    ``v`` to +z (the correction of the end attitude)."""
    B = idx.shape[0]
    n = mask.sum(axis=1)
    last = idx[np.arange(B), n - 1]
    csum = np.concatenate([np.zeros((1, 3)), np.cumsum(np.asarray(acc, dtype=float), axis=0)])
    lo = np.clip(last - half_w, 0, len(acc))
    hi = np.clip(last + half_w + 1, 0, len(acc))
    g_end = (csum[hi] - csum[lo]) / np.maximum(hi - lo, 1)[:, None]
    v = _qrotate(q[np.arange(B), n - 1], g_end)
    v = v / np.maximum(np.linalg.norm(v, axis=1, keepdims=True), 1e-300)
    axis = np.cross(v, np.array([0.0, 0.0, 1.0]))
    s = np.linalg.norm(axis, axis=1)
    unit = np.where(s[:, None] > 1e-12, axis / np.maximum(s, 1e-300)[:, None], np.array([1.0, 0.0, 0.0]))
    return unit, np.arctan2(s, v[:, 2])


def dedrift_tilt(q: np.ndarray, acc: np.ndarray, idx: np.ndarray, mask: np.ndarray, half_w: int,
                 clock: np.ndarray | None = None) -> np.ndarray:
    """Decision L68: attitudes (B, L, 4) with the tilt error found at each stride end (:func:`end_tilt`)
    removed along the stride, as the velocity ZUPT removes the velocity error (L6): sample j is rotated
    about the error's horizontal axis by c_j x its angle, c_j = ``clock`` (B, L) normalised from 0 at the
    start to 1 at the end (default: the time fraction). Padded samples keep the corrected last attitude."""
    B, L = mask.shape
    if B == 0:
        return q
    n = mask.sum(axis=1)
    axis, ang = end_tilt(q, acc, idx, mask, half_w)
    tau = np.broadcast_to(np.arange(L, dtype=float)[None, :], (B, L)) if clock is None else np.asarray(clock, float)
    t0 = tau[:, :1]
    t1 = tau[np.arange(B), n - 1][:, None]
    c = np.clip((tau - t0) / np.maximum(t1 - t0, 1e-300), 0.0, 1.0)
    c = np.where(mask, c, 1.0)
    half = 0.5 * ang[:, None] * c
    dq = np.concatenate([np.cos(half)[..., None], np.sin(half)[..., None] * axis[:, None, :]], axis=2)
    return _qmul(dq, q)


def zupt_mask(stance: np.ndarray, idx: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """(B, L) samples of each stride where the velocity is known to be zero: its stance samples plus
    its first and last sample (the stride runs from rest to rest)."""
    B = idx.shape[0]
    z = np.asarray(stance, dtype=bool)[idx] & mask
    if B:
        z[:, 0] = True
        z[np.arange(B), mask.sum(axis=1) - 1] = True
    return z


def double_integrate(a_nav: np.ndarray, mask: np.ndarray, dt: float | np.ndarray, *, zupt_end: bool = True,
                     zupt: np.ndarray | None = None, clock: np.ndarray | None = None) -> np.ndarray:
    """Displacement (B, 3) of each stride by double integration (equations of motion, thesis ch.7.2.1).

    The velocity starts at zero (ZUPT at the stride start). With ``zupt_end`` the velocity found at the
    zero-velocity samples ``zupt`` (B, L) (default: the first and last sample) is the velocity error
    there; it is interpolated linearly in between and removed (ZUPT drift correction). Without
    ``zupt_end`` only the start reset is applied (the traditional method). ``clock`` (B, L), increasing
    along each stride, is the variable the interpolation is linear in (default: time; decision L21 uses
    :func:`error_clock`, the accumulated variance of the velocity error).
    """
    B = a_nav.shape[0]
    if B == 0:
        return np.zeros((0, 3))
    v = zupt_velocity(a_nav, mask, dt, zupt_end=zupt_end, zupt=zupt, clock=clock)
    p = _cumtrapz(v, dt)
    return p[np.arange(B), mask.sum(axis=1) - 1]


def zupt_velocity(a_nav: np.ndarray, mask: np.ndarray, dt: float | np.ndarray, *, zupt_end: bool = True,
                  zupt: np.ndarray | None = None, clock: np.ndarray | None = None) -> np.ndarray:
    """Velocity (B, L, 3) m/s of each stride sample with the ZUPT drift correction of
    :func:`double_integrate` (same arguments); zero on padded samples."""
    B, L, _ = a_nav.shape
    n = mask.sum(axis=1)
    v = _cumtrapz(a_nav, dt)
    if zupt_end:
        if zupt is None:
            v_end = v[np.arange(B), n - 1]
            if np.ndim(dt) == 0:
                frac = np.minimum(np.arange(L)[None, :] / np.maximum(n - 1, 1)[:, None], 1.0)
            else:  # decision L83: the time fraction on the timestamps
                tau = step_clock(dt, B, L)
                frac = np.minimum(tau / np.maximum(tau[np.arange(B), n - 1], 1e-300)[:, None], 1.0)
            v = v - frac[:, :, None] * v_end[:, None, :]
        else:
            _interp_between(v, zupt & mask, clock, remove=True)
    v[~mask] = 0.0
    return v


def heel_rocker_samples(a_nav: np.ndarray, gyr_b: np.ndarray, stance: np.ndarray, mask: np.ndarray,
                        dt: float, *, window_s: float = 0.25, min_rate: float = 0.5) -> np.ndarray:
    """(B, L) samples of the heel rocker of each stride: after the heel-strike impact (the largest
    |acceleration| within ``window_s`` s before the stance that ends the stride) and before that stance,
    while the foot turns faster than ``min_rate`` rad/s (it rolls over the heel, decision L22)."""
    B, L = mask.shape
    out = np.zeros((B, L), dtype=bool)
    st = np.asarray(stance, dtype=bool) & mask
    n = mask.sum(axis=1)
    w = max(1, int(round(window_s / dt)))
    anorm = np.linalg.norm(a_nav, axis=2)
    rate = np.linalg.norm(gyr_b, axis=2)
    for b in range(B):
        j = int(n[b]) - 1
        while j > 0 and st[b, j - 1]:
            j -= 1  # first sample of the final stance run
        j0 = max(j - w, 1)
        if j - j0 < 3:
            continue
        imp = j0 + int(np.argmax(anorm[b, j0:j]))
        out[b, imp + 1:j] = rate[b, imp + 1:j] > min_rate
    return out


def move_reference(disp: np.ndarray, q_start: np.ndarray, q_end: np.ndarray, r_body: np.ndarray) -> np.ndarray:
    """Displacement (B, 3) of the point at ``r_body`` (3,) m from the sensor (body frame) given the
    sensor's displacement ``disp`` (B, 3) and the attitudes (B, 4) [w, x, y, z] at the stride start and
    end: p + R r moves by disp + (R_end - R_start) r."""
    rb = np.tile(np.asarray(r_body, dtype=float), (len(disp), 1))
    return disp + _qrotate(q_end, rb) - _qrotate(q_start, rb)


def rotation_pivot(v_b: np.ndarray, w_b: np.ndarray) -> tuple[np.ndarray, float]:
    """Least-squares position (3,) m of the sensor relative to a fixed pivot from body-frame velocities
    ``v_b`` (k, 3) m/s and rates ``w_b`` (k, 3) rad/s of a rigid rotation about it: v = w x rho.
    Returns (rho, explained fraction of the velocity variance)."""
    wx = np.zeros((len(w_b), 3, 3))
    wx[:, 0, 1], wx[:, 0, 2] = -w_b[:, 2], w_b[:, 1]
    wx[:, 1, 0], wx[:, 1, 2] = w_b[:, 2], -w_b[:, 0]
    wx[:, 2, 0], wx[:, 2, 1] = -w_b[:, 1], w_b[:, 0]
    A = wx.reshape(-1, 3)
    y = np.asarray(v_b, dtype=float).reshape(-1)
    rho = np.linalg.lstsq(A, y, rcond=None)[0]
    ss = float(np.sum(y ** 2))
    return rho, (1.0 - float(np.sum((A @ rho - y) ** 2)) / ss) if ss > 0 else 0.0


def error_clock(a_nav: np.ndarray, mask: np.ndarray, *, r: float, scale_error: float,
                weight: np.ndarray | None = None) -> np.ndarray:
    """Accumulated variance (B, L), in units of the white-noise variance per sample, of the velocity error
    of each stride (decision L21).

    The error of a velocity integrated from an accelerometer grows by white noise (variance ``r``
    (m/s^2)^2 per sample, thesis eq. 55: R = 0.01) and by errors proportional to the acceleration itself
    (scale factor, non-linearity, bandwidth and clipping of impacts; relative size ``scale_error``):
    increment variance ``r + (scale_error |a|)^2``. The ZUPT correction interpolated linearly in this
    variable is the Brownian-bridge estimate of the velocity error between zero-velocity samples, so the
    drift found at a stance is attributed to the hard accelerations of the swing and heel strike rather
    than spread evenly in time. ``scale_error = 0`` gives time. ``weight`` (B, L): each sample's interval in
    nominal periods (decision L83: a sample after dropped ones carries their noise too); None = 1.
    """
    w = 1.0 + (scale_error ** 2 / r) * np.sum(np.asarray(a_nav, dtype=float) ** 2, axis=2)
    if weight is not None:
        w = w * weight
    w = np.where(mask, w, 0.0)
    w[:, 0] = 0.0
    return np.cumsum(w, axis=1)


def _interp_between(v: np.ndarray, known: np.ndarray, clock: np.ndarray | None = None, *,
                    remove: bool = False) -> np.ndarray:
    """Per row b, values of ``v[b]`` (L, k) at the ``known`` samples, linearly interpolated in between
    (held after the last known sample) along ``clock`` (B, L) (default: the sample index). Every row's
    first sample must be known. ``remove`` (decision L663): subtract them from ``v`` in place and return ``v``."""
    B, L = known.shape
    j = np.arange(L)
    tau = np.broadcast_to(j[None, :].astype(float), (B, L)) if clock is None else clock
    prev = np.maximum.accumulate(np.where(known, j, 0), axis=1)
    nxt = np.flip(np.minimum.accumulate(np.flip(np.where(known, j, L), axis=1), axis=1), axis=1)
    nxt = np.where(nxt >= L, prev, nxt)
    rows = np.arange(B)[:, None]
    span = np.maximum(tau[rows, nxt] - tau[rows, prev], 1e-300)
    w = np.where(nxt > prev, (tau - tau[rows, prev]) / span, 0.0)
    out = v if remove else np.empty(v.shape, dtype=np.result_type(v, w))
    for a in range(v.shape[2]):  # decision L663: vp + w (vn - vp) one axis at a time (no (B, L, k) temporaries)
        va = v[:, :, a]
        vp, d = va[rows, prev], va[rows, nxt]
        d -= vp
        d *= w
        d += vp
        if remove:
            va -= d
        else:
            out[:, :, a] = d
    return out


def wnj_matrices(dt: float, sw: float) -> tuple[np.ndarray, np.ndarray]:
    """Transition F (thesis eq. 53) and process noise Q (thesis eq. 54) of the white-noise-jerk model."""
    T = dt
    F = np.array([[1.0, T, T * T / 2], [0.0, 1.0, T], [0.0, 0.0, 1.0]])  # thesis eq. 53
    Q = sw * np.array([[T**5 / 20, T**4 / 8, T**3 / 6],
                       [T**4 / 8, T**3 / 3, T**2 / 2],
                       [T**3 / 6, T**2 / 2, T]])  # thesis eq. 54
    return F, Q


def _inv3_sym(M: np.ndarray) -> np.ndarray:
    """Inverse of symmetric 3x3 matrices (..., 3, 3) by cofactors (faster than LAPACK for tiny blocks)."""
    a, b, c = M[..., 0, 0], M[..., 0, 1], M[..., 0, 2]
    d, e, f = M[..., 1, 1], M[..., 1, 2], M[..., 2, 2]
    A = d * f - e * e
    Bc = c * e - b * f
    C = b * e - c * d
    det = a * A + b * Bc + c * C
    D = a * f - c * c
    E = b * c - a * e
    Fc = a * d - b * b
    inv = np.stack([np.stack([A, Bc, C], -1), np.stack([Bc, D, E], -1), np.stack([C, E, Fc], -1)], -2)
    return inv / det[..., None, None]


def wnj_kalman(a_meas: np.ndarray, mask: np.ndarray, dt: float | np.ndarray, *, sw: float = 1.8, r: float = 0.01,
               zupt: bool = True, zupt_at: np.ndarray | None = None, r_zupt: float = 1e-6,
               smooth: bool = True, q_vel: np.ndarray | None = None, final: bool = False) -> np.ndarray:
    """White-noise-jerk Kalman filter (state [d, v, a], thesis eq. 44-55) on a batch of signals.

    Parameters
    ----------
    a_meas : (N, L) or (N, L, A) measured acceleration (m/s^2); the A axes of a row share the sample
        times, so they share one covariance (thesis eq. 58-60: one filter per axis, same model)
    mask : (N, L) valid samples (each signal starts at j = 0)
    dt : sample period (s), or the interval of every step (N, L - 1) s (decision L83; filter only)
    sw : power spectral density of the jerk (thesis ch.7.2.1: 1.8)
    r : acceleration measurement variance (thesis eq. 55: 0.01)
    zupt : add v = 0 pseudo-measurements (variance ``r_zupt``) at the samples ``zupt_at`` (N, L)
        (default: the last valid sample; the first is at rest by the initial state); with ``smooth``
        the Rauch-Tung-Striebel pass carries that correction back through the stride, which is the
        KF form of the ZUPT drift correction
    smooth : run the RTS smoother (offline); ``False`` returns the causal filter
    q_vel : (N, L) extra velocity process noise (m/s)^2 added in the prediction to sample j (decision
        L21: velocity errors proportional to the acceleration); None = the white-noise-jerk model only
    final : decision L663: return only the state at each row's last valid sample, (N, 3) or (N, A, 3) (the
        filter's, which the RTS pass leaves as it is), without keeping the (N, L, ...) history

    Returns
    -------
    states : (N, L, 3) or (N, L, A, 3) distance (m), velocity (m/s), acceleration (m/s^2); the value at
    the last valid sample of each signal is its displacement estimate
    """
    squeeze = a_meas.ndim == 2
    am = a_meas[:, :, None] if squeeze else a_meas
    N, L, A = am.shape
    steps = np.ndim(dt) != 0  # decision L83: one interval per row and step (N, L - 1), from the timestamps
    if steps and smooth and not final:
        raise ValueError("wnj_kalman: per-step intervals are supported by the filter only (smooth=False)")
    smooth = smooth and not final  # the smoothed state at the last sample is the filtered one
    if not steps:
        F, Q = wnj_matrices(dt, sw)
        T, h = dt, dt * dt / 2
        q00, q01, q02, q11, q12, q22 = Q[0, 0], Q[0, 1], Q[0, 2], Q[1, 1], Q[1, 2], Q[2, 2]
    last = mask.sum(axis=1) - 1
    if zupt_at is None:
        zupt_at = np.zeros((N, L), dtype=bool)
        zupt_at[np.arange(N), last] = True
    # decision L663: the rows longest first (by their last valid sample), so the rows still running at sample j are
    # the first ``alive[j]`` (views); a finished row keeps its state, as the masked update of every row did
    end = np.where(mask.any(axis=1), L - 1 - np.argmax(mask[:, ::-1], axis=1), 0)
    order = np.argsort(-end, kind="stable")
    alive = N - np.searchsorted(np.sort(end), np.arange(L), side="left")
    amT = np.ascontiguousarray(np.moveaxis(am[order], 1, 0))  # (L, N, A)
    actT = np.ascontiguousarray(mask[order].T)
    zupT = np.ascontiguousarray((mask & zupt_at)[order].T) if zupt else None
    qvT = None if q_vel is None else np.ascontiguousarray(np.asarray(q_vel, dtype=float)[order].T)
    dtT = np.ascontiguousarray(np.asarray(dt, dtype=float)[order].T) if steps else None
    # state x[c] (N, A) for its components c = d, v, a; covariance kept as its six distinct elements P[0..5] = 00, 01,
    # 02, 11, 12, 22, each (N,), shared by the A axes
    x = np.zeros((3, N, A))
    x[2] = amT[0]
    P = np.zeros((6, N))
    P[0], P[3], P[5] = 1e-12, (1e-12 if zupt else 1e-4), r
    xf = None if final else np.zeros((L, 3, N, A))
    if xf is not None:
        xf[0] = x
    Pf = np.zeros((L, 6, N)) if smooth else None
    if smooth:
        Pf[0] = P
    col_of = ((0, 1, 2), (1, 3, 4), (2, 4, 5))  # P[:, i, comp] for comp = 0, 1, 2
    ki, kj = [0, 0, 0, 1, 1, 2], [0, 1, 2, 1, 2, 2]  # P[key] -= k_i col_j for key = ij

    def update(m: int, comp: int, z, var: float, act: np.ndarray | None) -> None:
        col = P[list(col_of[comp]), :m]  # a copy (fancy index): the values before this update
        k = col / (col[comp] + var)
        if act is not None:
            k = np.where(act[None, :], k, 0.0)
        xs = x[:, :m]
        xs += k[:, :, None] * (z - xs[comp])[None]
        P[:, :m] -= k[ki] * col[kj]

    Tc, hc = (None, None) if steps else (T, h)
    for j in range(1, L):
        m = int(alive[j])
        if m == 0:
            if final:
                break
            xf[j] = x
            if smooth:
                Pf[j] = P
            continue
        act = actT[j, :m]
        some = None if act.all() else act  # padded samples inside a row (none in a rest-to-rest stride)
        xs = x[:, :m]
        p00, p01, p02, p11, p12, p22 = P[:, :m]
        # predict: x = F x, P = F P F^T + Q (thesis eq. 53/54), written out for the 3x3 F
        if steps:  # F and Q of each row's own interval (thesis eq. 53/54 with T = t_j - t_{j-1})
            T = dtT[j - 1, :m]
            h = T * T / 2
            q00, q01, q02 = sw * T ** 5 / 20, sw * T ** 4 / 8, sw * T ** 3 / 6
            q11, q12, q22 = sw * T ** 3 / 3, sw * T ** 2 / 2, sw * T
            Tc, hc = T[:, None], h[:, None]
        d_new = xs[0] + Tc * xs[1] + hc * xs[2]
        v_new = xs[1] + Tc * xs[2]
        xs[0] = d_new if some is None else np.where(some[:, None], d_new, xs[0])
        xs[1] = v_new if some is None else np.where(some[:, None], v_new, xs[1])
        a00 = p00 + T * p01 + h * p02
        a01 = p01 + T * p11 + h * p12
        a02 = p02 + T * p12 + h * p22
        a11 = p11 + T * p12
        a12 = p12 + T * p22
        new = np.stack([a00 + T * a01 + h * a02 + q00, a01 + T * a02 + q01, a02 + q02,
                        a11 + T * a12 + q11 + (0.0 if qvT is None else qvT[j, :m]), a12 + q12, p22 + q22])
        P[:, :m] = new if some is None else np.where(some[None, :], new, P[:, :m])
        update(m, 2, amT[j, :m], r, some)  # thesis eq. 55: the acceleration is measured
        if zupt:
            zj = zupT[j, :m]
            if zj.any():  # a row without a ZUPT at j keeps its state (a zero gain)
                update(m, 1, 0.0, r_zupt, None if zj.all() else zj)
        if xf is not None:
            xf[j] = x
        if smooth:
            Pf[j] = P
    inv = np.argsort(order)
    if final:
        x = np.transpose(x, (1, 2, 0))[inv]  # (N, A, 3)
        return x[:, 0] if squeeze else x
    xf = np.transpose(xf, (2, 0, 3, 1))[inv]  # (N, L, A, 3)
    if not smooth:
        return xf[:, :, 0] if squeeze else xf
    idx = [[0, 1, 2], [1, 3, 4], [2, 4, 5]]
    Pm = np.transpose(Pf, (2, 0, 1))[inv][..., idx]  # (N, L, 3, 3)
    xs = xf.copy()
    for j in range(L - 2, -1, -1):
        act = mask[:, j + 1]
        Pp = F @ Pm[:, j] @ F.T + Q
        if q_vel is not None:
            Pp[:, 1, 1] += q_vel[:, j + 1]
        C = Pm[:, j] @ F.T @ _inv3_sym(Pp)
        upd = xf[:, j] + np.einsum("nij,naj->nai", C, xs[:, j + 1] - xf[:, j] @ F.T)
        xs[:, j] = np.where(act[:, None, None], upd, xf[:, j])
    return xs[:, :, 0] if squeeze else xs


def wnj_displacement(a_nav: np.ndarray, mask: np.ndarray, dt: float | np.ndarray, **kw) -> np.ndarray:
    """Displacement (B, 3) of each stride from one white-noise-jerk filter per axis (thesis eq. 58-60)."""
    B = a_nav.shape[0]
    if B == 0:
        return np.zeros((0, 3))
    # the smoothed state at the last sample equals the filtered one (RTS), so the filter suffices here; decision
    # L663: without its history
    kw.setdefault("smooth", False)
    if kw["smooth"]:
        states = wnj_kalman(a_nav, mask, dt, **kw)
        return states[np.arange(B), mask.sum(axis=1) - 1, :, 0]
    return wnj_kalman(a_nav, mask, dt, final=True, **kw)[:, :, 0]


# --- M3 rules (thesis ch.7.2.2) -------------------------------------------------------------------

def bayes_length(distance: np.ndarray, proba: np.ndarray, bounds: list[tuple[float, float]],
                 sigma: np.ndarray) -> np.ndarray:
    """Posterior-mean |length| (m) from the integrated estimate and the length-class probabilities.

    The estimate is a measurement ``N(L, sigma^2)`` of the true length L; the classifier gives the prior
    ``sum_c p_c U(L; lo_c, hi_c)``. The posterior mean is computed in closed form (truncated normals).
    With a certain class (p = 1) it is the truncated-normal mean inside that class's bounds, i.e. the
    thesis clamp softened by the estimate's uncertainty; with a doubtful class the estimate decides.
    The formula is :mod:`pdrlearn.kernels.bayes`'s, shared with the streaming runtime (decision L40).

    Parameters
    ----------
    distance : (B,) |estimated length| (m);  proba : (B, C) class probabilities (rows sum to 1)
    bounds : C (lo, hi) class bounds (m);  sigma : (B,) standard deviation of the estimate (m)
    """
    from pdrlearn.kernels.bayes import bayes_length as kernel

    return kernel(distance, proba, bounds, sigma)
