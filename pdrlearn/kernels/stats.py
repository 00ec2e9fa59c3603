"""Step attitude and the per-signal statistics the thesis features are built from (numpy only).

Attitude of a foot unit through one step (gyroscope propagation from the stance, tilt drift spread
over the swing), the heading of a step in the levelled frame, and the statistics of each step's signal
(peaks, peak instants, sums, segment max/min/mean/slope, force-sensor statistics, thesis eq. 31/32).
Arrays of statistics are ``(n_steps, n_samples)``, one row per step.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from pdrlearn.kernels.rotation import gravity_rotation, matrix_to_rotvec, rotvec_to_matrix, skew, vec_norm

_I3 = np.eye(3)
_I3.flags.writeable = False


#: Share of a step window's samples, quietest by gyroscope norm, whose median |acc| is the rest reference
#: of :func:`rest_index` (decisions doc, "Rest reference of the step windows").
REST_QUIET_FRACTION = 0.25
STANDARD_GRAVITY = 9.80665  # m/s^2, the rest |acc| without a gyroscope (thesis ch. 4.2.1.1)


def rest_reference(acc_norm: np.ndarray, gyr_norm: np.ndarray | None) -> float | np.ndarray:
    """Specific-force norm (m/s^2) of the unit at rest in a step window, along the last axis.

    The median |acc| of the quietest :data:`REST_QUIET_FRACTION` of the samples by gyroscope norm
    (ties kept in time order), so the reference is the sensor's own gravity reading (scale errors
    included) as long as at least half of those samples are rest (rest >= 12.5 % of the window);
    :data:`STANDARD_GRAVITY` without a gyroscope.

    Parameters
    ----------
    acc_norm : |acc| (n,) or (B, n), m/s^2
    gyr_norm : |gyro| of the same samples, rad/s, or None

    Returns
    -------
    float for 1-D input, (B,) array for 2-D input
    """
    if gyr_norm is None:
        return STANDARD_GRAVITY if acc_norm.ndim == 1 else np.full(acc_norm.shape[:-1], STANDARD_GRAVITY)
    k = max(1, int(REST_QUIET_FRACTION * acc_norm.shape[-1]))
    if acc_norm.ndim == 1:  # per-step path: plain indexing (the same values as the batch branch); the
        q = acc_norm[gyr_norm.argsort(kind="stable")[:k]]  # method, not np.argsort's wrapper (runtime E17)
        q.sort()
        q = q.tolist()  # the median's arithmetic on Python floats: the same IEEE sums, no numpy scalars (E20)
        return 0.5 * (q[(k - 1) // 2] + q[k // 2])
    q = np.take_along_axis(acc_norm, np.argsort(gyr_norm, axis=-1, kind="stable")[..., :k], axis=-1)
    q.sort(axis=-1)
    return 0.5 * (q[..., (k - 1) // 2] + q[..., k // 2])  # median (odd k: the middle value itself)


def rest_score(acc_norm: np.ndarray, gyr_norm: np.ndarray | None, *, acc_ref: float | np.ndarray | None = None,
               half_width: int = 0) -> np.ndarray:
    """Motion score of each sample of a step window (lower = quieter), along the last axis.

    Gyroscope norm (rad/s; when a gyroscope exists) plus the deviation of |acc| from its rest value
    ``acc_ref`` (default :func:`rest_reference`; a float, or (B,) for 2-D input) scaled to rad/s-like
    magnitude (1 m/s^2 ~ 0.1 rad/s), then the largest score within ``+-half_width`` samples (window
    edges truncated): the rest specific force is averaged over that neighbourhood, so all of it must be
    quiet (decisions doc, "Rest reference of the step windows").
    """
    ref = rest_reference(acc_norm, gyr_norm) if acc_ref is None else acc_ref
    score = 0.1 * np.abs(acc_norm - (np.asarray(ref)[..., None] if acc_norm.ndim > 1 else ref))
    if gyr_norm is not None:
        score = score + gyr_norm
    out = score.copy() if half_width > 0 else score
    for j in range(1, min(half_width, score.shape[-1] - 1) + 1):  # running max over [k - hw, k + hw]
        np.maximum(out[..., :-j], score[..., j:], out=out[..., :-j])
        np.maximum(out[..., j:], score[..., :-j], out=out[..., j:])
    return out


def rest_index(acc: np.ndarray, gyr: np.ndarray | None, lo: int, hi: int, *,
               score: np.ndarray | None = None) -> int:
    """Index in ``[lo, hi)`` where the unit moves least: the first minimum of :func:`rest_score`
    (``score`` (n,) when the caller has it already, e.g. for both ends of a window)."""
    lo = max(0, lo)
    hi = max(lo + 1, min(hi, acc.shape[0]))
    if score is None:
        score = rest_score(row_norm(acc), None if gyr is None else row_norm(gyr))
    return lo + int(np.argmin(score[lo:hi]))


def row_norm(v: np.ndarray) -> np.ndarray:
    """Euclidean norm of each row of ``v (n, k)`` (``np.linalg.norm(v, axis=1)`` without its overhead)."""
    return np.sqrt(np.einsum("ij,ij->i", v, v))


def propagate_attitude(gyr: np.ndarray, dt: np.ndarray, k0: int, r0: np.ndarray) -> np.ndarray:
    """Attitudes ``R_k`` (n, 3, 3), sensor -> levelled frame, from ``R_{k0} = r0`` and the angular rate.

    ``dR/dt = R [w]x`` integrated with the exact rotation of each sample interval
    (``R_{k+1} = R_k exp([w_k dt_k]x)``), forward and backward from ``k0``: ``R_k = r0 P_k0^T P_k`` with
    ``P_k`` the product of the interval rotations before sample k (one prefix scan for both directions,
    the formula of the batched training path :mod:`pdrlearn.features.batch`).

    Parameters
    ----------
    gyr : (n, 3) angular rate in the sensor frame (rad/s)
    dt : (n - 1,) sample intervals (s)
    """
    n = gyr.shape[0]
    if n < 2:
        out = np.empty((n, 3, 3))
        out[k0] = r0
        return out
    P = np.empty((n, 3, 3))
    P[0] = _I3
    P[1:] = rotvec_to_matrix(0.5 * (gyr[:-1] + gyr[1:]) * dt[:, None])  # mean rate over each interval
    P = prefix_products(P)
    out = (r0 @ P[k0].T) @ P
    out[k0] = r0  # exactly (P_k0^T P_k0 = I to rounding)
    return out


def prefix_products(m: np.ndarray) -> np.ndarray:
    """Inclusive prefix products ``m[0] @ m[1] @ ... @ m[k]`` of a stack of matrices (n, 3, 3).

    Hillis-Steele scan: log2(n) batched matrix products instead of a Python loop over the samples.
    """
    p = m.copy() if m.dtype == np.float64 else m.astype(np.float64)
    shift = 1
    while shift < p.shape[0]:
        p[shift:] = p[:-shift] @ p[shift:]
        shift *= 2
    return p


def correct_tilt_drift(rot: np.ndarray, g_end_sensor: np.ndarray, k0: int, k1: int) -> np.ndarray:
    """Spread the tilt error seen at the second rest ``k1`` linearly over ``k0..k1``.

    At ``k1`` the levelled specific force should point straight up; the minimal rotation that makes
    it so is applied with weight ``(k - k0) / (k1 - k0)`` (clipped to 0..1) to every sample.
    """
    if k1 <= k0:
        return rot
    corr = matrix_to_rotvec(gravity_rotation(rot[k1] @ g_end_sensor))
    th = vec_norm(corr)
    if th == 0.0:
        return rot
    frac = np.minimum(np.maximum((np.arange(rot.shape[0]) - k0) / float(k1 - k0), 0.0), 1.0)  # clipped to 0..1
    # rotations frac * corr share one axis k: Rodrigues' R = I + sin(a) [k]x + (1 - cos a) [k]x^2 with
    # a = frac |corr|, the 3x3 [k]x built once (rotvec_to_matrix of frac * corr, fewer numpy calls)
    K = skew(corr / th)
    ang = frac * th
    return (_I3 + np.sin(ang)[:, None, None] * K + (1.0 - np.cos(ang))[:, None, None] * (K @ K)) @ rot


def levelled_vectors(gyr: np.ndarray, dt: np.ndarray, k0: int, k1: int, r0: np.ndarray,
                     g_end_sensor: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Sensor-frame vectors ``X (n, c, 3)`` (c row vectors per sample) in the levelled frame, ``R_k x``,
    with the attitude of ``correct_tilt_drift(propagate_attitude(gyr, dt, k0, r0), g_end_sensor, k0, k1)``.

    The same rotations without forming the ``(n, 3, 3)`` attitude stack (decision E13 in
    docs/decisions/export.md: fewer numpy calls per step window, within 1e-12 of the composed functions):
    ``R_k x = A (P_k x)`` with ``A = r0 P_k0^T``, then the tilt correction of angle ``frac_k th`` about
    the fixed axis ``k`` applied to the vectors by Rodrigues' formula,
    ``v + sin(a) [k]x v + (1 - cos a) [k]x^2 v``. Only ``P_k x`` is a per-sample product; the constant
    rotations (``A``, ``[k]x``) act on all rows in one 2-D product (a stack of 3x3 products costs one
    BLAS call per sample). The correction's rotation vector comes straight from the levelled specific
    force at ``k1`` (axis ``g x z``, angle ``atan2(|g x z|, g.z)``), which is
    :func:`pdrlearn.kernels.rotation.gravity_rotation` followed by ``matrix_to_rotvec``.

    Parameters
    ----------
    gyr : (n, 3) rad/s;  dt : (n - 1,) s;  k0, k1 : rest samples (start, end)
    r0 : (3, 3) levelling rotation at ``k0``;  g_end_sensor : (3,) specific force at the end rest (m/s^2)
    X : (n, c, 3) vectors to rotate, e.g. acceleration, angular rate and a constant axis as rows

    Returns
    -------
    (n, c, 3) C-ordered
    """
    n = gyr.shape[0]
    if n < 2:
        return X @ r0.T
    P = np.empty((n, 3, 3))
    P[0] = _I3
    P[1:] = rotvec_to_matrix(0.5 * (gyr[:-1] + gyr[1:]) * dt[:, None])  # mean rate over each interval
    shift = 1
    while shift < n:  # inclusive prefix products in place (prefix_products without its copy)
        P[shift:] = P[:-shift] @ P[shift:]
        shift *= 2
    A = r0 @ P[k0].T
    Y = ((X @ P.transpose(0, 2, 1)).reshape(-1, 3) @ A.T)  # rows (A P_k x)^T, one 2-D product for A
    if k1 <= k0:
        return Y.reshape(X.shape)
    return tilt_corrected(Y.reshape(X.shape), A @ (P[k1] @ g_end_sensor), k0, k1)


def tilt_corrected(Y: np.ndarray, g_lev: np.ndarray, k0: int, k1: int) -> np.ndarray:
    """The tilt-drift correction of :func:`levelled_vectors` (also used by the runtime's push-time
    levelling, decision E15): the rotation that makes the levelled end-rest specific force ``g_lev``
    vertical, spread linearly over ``k0..k1``, applied to the rows of ``Y (n, c, 3)``."""
    if k1 <= k0:
        return Y
    n, shape = Y.shape[0], Y.shape
    gx, gy, gz = g_lev.tolist()  # levelled specific force at the end rest
    nrm = math.sqrt(gx * gx + gy * gy + gz * gz)
    if not math.isfinite(nrm) or nrm < 1e-9:
        gravity_rotation(np.array([gx, gy, gz]))  # raises its DataError
    s = math.sqrt(gx * gx + gy * gy) / nrm
    if s < 1e-12:
        if gz > 0:
            return Y  # already level: no correction (correct_tilt_drift's th == 0)
        kx, ky, th = 1.0, 0.0, math.pi  # upside down: 180 deg about x, as gravity_rotation
    else:
        kx, ky, th = gy / nrm / s, -gx / nrm / s, math.atan2(s, gz / nrm)  # axis (g x z) / |g x z|
    ang = _tilt_fraction(n, k0, k1) * th  # the fraction of the correction at each sample, times the angle
    KT = np.array((0.0, 0.0, -ky, 0.0, 0.0, kx, ky, -kx, 0.0)).reshape(3, 3)  # ([k]x)^T of k = (kx, ky, 0)
    # 2-D products by ndarray.dot: the same BLAS product as @, without the matmul ufunc's dispatch (E20)
    KY = Y.reshape(-1, 3).dot(KT)  # rows ([k]x v)^T
    K2Y = KY.dot(KT).reshape(shape)  # rows ([k]x^2 v)^T
    return Y + np.sin(ang) * KY.reshape(shape) + (1.0 - np.cos(ang)) * K2Y


@functools.lru_cache(maxsize=1024)
def _tilt_fraction(n: int, k0: int, k1: int) -> np.ndarray:
    """Read-only ``(k - k0) / (k1 - k0)`` clipped to 0..1 for ``k = 0..n-1``, as an ``(n, 1, 1)`` column that
    broadcasts over each sample's rows. It depends on the step's length and rest samples only, which repeat
    from step to step, so it is cached (runtime decision E18; the values of the three numpy calls it
    replaces, bit for bit)."""
    frac = (_arange_col(n) - float(k0)) / float(k1 - k0)  # the same values as np.arange(n) - k0 (E17)
    np.minimum(np.maximum(frac, 0.0, out=frac), 1.0, out=frac)
    frac.flags.writeable = False
    return frac


@functools.lru_cache(maxsize=64)
def _arange_col(n: int) -> np.ndarray:
    """Read-only ``np.arange(n, dtype=float).reshape(n, 1, 1)`` (cached: a step's length repeats)."""
    a = np.arange(n, dtype=np.float64).reshape(n, 1, 1)
    a.flags.writeable = False
    return a


def heading_rotation(forward_xy: np.ndarray) -> np.ndarray:
    """Rotation about z (3x3) that turns the horizontal unit vector ``forward_xy`` onto +x."""
    c, s = float(forward_xy[0]), float(forward_xy[1])
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def principal_horizontal_axis(acc_lev: np.ndarray, reference_xy: np.ndarray) -> np.ndarray:
    """Unit principal axis of the horizontal acceleration, signed to agree with ``reference_xy``.

    The foot accelerates and brakes along its direction of travel, so the dominant eigenvector of the
    horizontal second-moment matrix is the line of the step; the sign (toes side) comes from the
    declared forward axis of the sensor, so backward steps keep their sign.
    """
    r0, r1 = np.asarray(reference_xy, dtype=np.float64).tolist()[:2]
    return np.array(principal_horizontal_xy(acc_lev, r0, r1))


def principal_horizontal_xy(acc_lev: np.ndarray, r0: float, r1: float) -> tuple[float, float]:
    """:func:`principal_horizontal_axis` with the reference given and the axis returned as Python floats
    (the runtime's call, E17)."""
    h = acc_lev[:, :2]
    (sxx, sxy), (_, syy) = (h.T @ h).tolist()
    # dominant eigenvector of the symmetric 2x2 [[sxx, sxy], [sxy, syy]] in closed form: the major axis at
    # angle atan2(2 sxy, sxx - syy) / 2 (np.linalg.eigh's vector up to rounding and sign; equal
    # eigenvalues give +x like eigh's first column)
    phi = 0.5 * math.atan2(2.0 * sxy, sxx - syy)
    ex, ey = math.cos(phi), math.sin(phi)
    if ex * r0 + ey * r1 < 0:
        ex, ey = -ex, -ey
    return ex, ey


# -- per-signal statistics on (n_steps, n_samples) arrays ------------------------------------------


def row_gradient(tt: np.ndarray) -> np.ndarray:
    """``np.gradient(tt, axis=1)`` (unit index spacing) of an ``(n, m >= 2)`` array, without its overhead:
    the sample weights (s) of each row's possibly non-uniform time grid."""
    g = np.empty_like(tt)
    g[:, 0] = tt[:, 1] - tt[:, 0]
    g[:, -1] = tt[:, -1] - tt[:, -2]
    g[:, 1:-1] = (tt[:, 2:] - tt[:, :-2]) / 2.0
    return g


def peak_stats(sig: np.ndarray, t: np.ndarray) -> dict[str, np.ndarray]:
    """Peak and sum statistics of each row of ``sig`` (n, m) sampled at times ``t`` (n, m) (s).

    Thesis ch. 6.1.1.1. Returns arrays (n,): ``min``, ``max``, ``t_min``, ``t_max`` (s from the step
    start), ``dt_peaks`` (= t_max - t_min, s), ``abs_dt_peaks``, ``range`` (= max - min), ``peak_asym``
    (= |max| - |min|), ``sum_pos`` / ``sum_neg`` (time integral of the positive part / magnitude of the
    negative part, unit x s; the thesis sums samples at 20 Hz, see docs/decisions/features.md),
    ``pos_minus_neg``, ``duration`` (s).
    """
    rows = np.arange(sig.shape[0])
    i_min, i_max = np.argmin(sig, axis=1), np.argmax(sig, axis=1)
    vmin, vmax = sig[rows, i_min], sig[rows, i_max]
    tt = t - t[:, :1]
    dt = row_gradient(tt)
    sum_pos = np.sum(np.clip(sig, 0, None) * dt, axis=1)
    sum_neg = np.sum(np.clip(-sig, 0, None) * dt, axis=1)
    t_min, t_max = tt[rows, i_min], tt[rows, i_max]
    return {
        "min": vmin,
        "max": vmax,
        "t_min": t_min,
        "t_max": t_max,
        "dt_peaks": t_max - t_min,
        "abs_dt_peaks": np.abs(t_max - t_min),
        "range": vmax - vmin,
        "peak_asym": np.abs(vmax) - np.abs(vmin),
        "sum_pos": sum_pos,
        "sum_neg": sum_neg,
        "pos_minus_neg": sum_pos - sum_neg,
        "duration": tt[:, -1],
    }


@functools.lru_cache(maxsize=64)
def _edges(m: int, n_segments: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if n_segments < 1 or n_segments > m:
        raise ValueError(f"n_segments={n_segments} must be between 1 and the window length {m}")
    edges = np.linspace(0, m, n_segments + 1).round().astype(int)
    a, b = edges[:-1], edges[1:]
    mean = np.zeros((m, n_segments))  # column k averages part k: mean = sig @ mean
    for k in range(n_segments):
        mean[a[k]:b[k], k] = 1.0 / (b[k] - a[k])
    return a, b, mean


def segment_bounds(m: int, n_segments: int) -> list[tuple[int, int]]:
    """Index ranges ``[a, b)`` of ``n_segments`` nearly equal consecutive parts of ``m`` samples."""
    a, b, _ = _edges(m, n_segments)
    return [(int(i), int(j)) for i, j in zip(a, b, strict=True)]


def segment_stats(sig: np.ndarray, t: np.ndarray, n_segments: int = 6) -> np.ndarray:
    """Segment features (thesis ch. 6.1.1.2): per part max, min, mean and slope.

    The signal of each step (row of ``sig``, (n, m)) is divided into ``n_segments`` equal parts; for
    each part the maximum, minimum, mean and the slope between its first and last sample
    (``(x_last - x_first) / (t_last - t_first)``, unit/s) are returned, in that order:
    output (n, 4 * n_segments) = ``[max_1, min_1, mean_1, slope_1, max_2, ...]``.
    """
    n, m = sig.shape
    a, b, mean = _edges(m, n_segments)
    out = np.empty((n, 4 * n_segments))
    out[:, 0::4] = np.maximum.reduceat(sig, a, axis=1)
    out[:, 1::4] = np.minimum.reduceat(sig, a, axis=1)
    out[:, 2::4] = sig @ mean
    span = t[:, b - 1] - t[:, a]
    out[:, 3::4] = (sig[:, b - 1] - sig[:, a]) / np.where(span > 0, span, np.inf)  # 0 for a 1-sample part
    return out


def interp_rows(t_query: np.ndarray, t: np.ndarray, sig: np.ndarray) -> np.ndarray:
    """``sig[i]`` at times ``t_query[..., i]`` (clamped to row i's window): shape of ``t_query``.

    One ``np.interp`` call for every row: the rows' time grids are shifted to follow each other.
    """
    tn = t - t[:, :1]
    dur = tn[:, -1]
    off = np.concatenate([[0.0], np.cumsum(dur[:-1] + 1.0)])
    q = np.clip(np.asarray(t_query) - t[:, 0], 0.0, dur) + off
    return np.interp(q, (tn + off[:, None]).ravel(), sig.ravel())


def force_stats(force: np.ndarray, t: np.ndarray, *, zero_fraction: float = 0.05,
                sample_s: float = 0.05) -> dict[str, np.ndarray]:
    """Force-sensor statistics of each step (thesis Table 29 and ch. 6.3.1), rows of ``force`` (n, m).

    A sample is "zero" (foot in the air) when below ``zero_fraction`` x the step's peak force. The
    thesis counts PLASYS samples (20 Hz, thesis ch. 4.2.3: 50 ms); here counts are times (s) and
    "the k-th measurement" is ``k * sample_s`` seconds.

    Returns (n,) arrays: ``air_time`` (s of zero force; Table 29 #1), ``time_to_peak`` (s from the last
    zero to the contact peak; Table 29 #2), ``peak_mean_4`` (mean force 4 samples before and after the
    contact peak; Table 29 #3), ``contact_force_2`` (force 2 samples after the last zero; Table 29 #4),
    ``takeoff_force`` (force 2 samples before the first zero; ch. 6.3.1).
    """
    n, m = force.shape
    tt = t - t[:, :1]
    dt = row_gradient(tt)
    peak = force.max(axis=1, keepdims=True)
    zero = force < zero_fraction * np.where(peak > 0, peak, 1.0)
    any_zero = zero.any(axis=1)
    last_zero = np.where(any_zero, m - 1 - np.argmax(zero[:, ::-1], axis=1), np.argmin(force, axis=1))
    first_zero = np.where(any_zero, np.argmax(zero, axis=1), np.argmin(force, axis=1))
    rows = np.arange(n)
    i_peak = np.argmax(np.where(np.arange(m)[None, :] >= last_zero[:, None], force, -np.inf), axis=1)
    t_last, t_peak = tt[rows, last_zero], tt[rows, i_peak]
    q = np.stack([t_peak - 4 * sample_s, t_peak + 4 * sample_s, t_last + 2 * sample_s,
                  tt[rows, first_zero] - 2 * sample_s])
    v = interp_rows(q, tt, force)
    return {
        "air_time": np.sum(zero * dt, axis=1),
        "time_to_peak": t_peak - t_last,
        "peak_mean_4": 0.5 * (v[0] + v[1]),
        "contact_force_2": v[2],
        "takeoff_force": v[3],
    }


def half_balance(x: np.ndarray) -> np.ndarray:
    """Thesis eq. 31 as a signed, scale-free number: ``(sum(first half) - sum(second half)) / sum(|x|)``.

    Positive = forward step for the forward acceleration. The halves are those of the step's *motion*:
    the split is where the cumulative ``|x|`` reaches half its total (a stance-to-stance window starts
    and ends at rest, so the window's midpoint would cut the swing off-centre; decisions doc).
    """
    cum = np.cumsum(np.abs(x), axis=1)
    total = cum[:, -1:]
    split = np.argmax(cum >= 0.5 * total, axis=1)
    first_mask = np.arange(x.shape[1])[None, :] <= split[:, None]
    first = np.sum(np.where(first_mask, x, 0.0), axis=1)
    second = np.sum(np.where(first_mask, 0.0, x), axis=1)
    denom = total[:, 0]
    return np.where(denom > 0, (first - second) / np.where(denom > 0, denom, 1.0), 0.0)


def step_probability(x: np.ndarray) -> np.ndarray:
    """Thesis eq. 32: ``100 - |max(acc) + min(acc)| * 20``, normalised to 0..1 (clipped).

    A forward (backward) step's positive acceleration is followed (preceded) by a negative one of the
    same magnitude; the more the peaks differ, the less the step is trusted. ``x`` in m/s^2, the
    equation is applied in g (a foot's peaks are several g; in m/s^2 nearly every step would get 0).
    """
    g = 9.80665  # eq. 32 reads the acceleration in g (decisions doc): m/s^2 -> g
    p = 100.0 - np.abs(x.max(axis=1) + x.min(axis=1)) / g * 20.0  # thesis eq. 32
    return np.clip(p / 100.0, 0.0, 1.0)


def yaw_stats(ps: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Yaw-rate statistics from :func:`peak_stats` of the waist yaw rate (thesis Table 31, ch. 6.3.1):
    ``amplitude`` (half the range, rad/s), ``left``/``right`` (s before/after the maximum),
    ``left_minus_right`` (s), ``duration`` (s)."""
    left = ps["t_max"]
    return {"amplitude": 0.5 * ps["range"], "duration": ps["duration"], "left": left,
            "right": ps["duration"] - left, "left_minus_right": 2 * left - ps["duration"]}


def positive_net_rotation(rate: np.ndarray, t: np.ndarray) -> np.ndarray:
    """1.0 where the time integral of each row of ``rate`` (rad/s) over its times ``t`` (s) is positive
    (net left turn of the pelvis for the waist yaw rate, thesis ch. 6.2.1), else 0.0; (n,)."""
    return (np.sum(rate * row_gradient(t), axis=1) > 0).astype(float)
