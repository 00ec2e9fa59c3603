"""Step windows of many steps at once: the per-step window kernel (levelling, heading alignment, gravity
removal, anti-aliased resampling; see :mod:`pdrlearn.features.windows`) vectorised over the steps.

Steps whose sensor segments have the same number of samples are processed as one ``(B, L, k)`` batch,
so an hour of 20 Hz data (~3000 steps, ~10 distinct segment lengths) costs a few dozen numpy calls
instead of ~30 per step. The results equal the per-step kernel's to floating-point rounding (the
attitude through the swing is ``r0 P_k0^T P_k`` with prefix products ``P`` instead of a product started
at ``k0``; tested in tests/test_track.py against the per-step path).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from scipy.ndimage import uniform_filter1d
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError, VerticalAxisError
from pdrlearn.kernels.stats import rest_score
from pdrlearn.kernels.window import TIE_S

Streams = Mapping[str, tuple[np.ndarray, np.ndarray]]


def segment_bounds(t: np.ndarray, start: np.ndarray, end: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Index ranges ``[i0, i1)`` of the samples covering each ``[start, end]`` plus one sample on each
    side (the per-step kernel's ``segment``), for arrays of step times (s)."""
    i0 = np.maximum(np.searchsorted(t, start + TIE_S, side="right") - 1, 0)  # decision E35: a sample within
    i1 = np.minimum(np.searchsorted(t, end - TIE_S, side="left") + 1, len(t))  # TIE_S of an edge is on it
    return i0, i1


def gravity_rotation_batch(g: np.ndarray) -> np.ndarray:
    """Minimal rotations (B, 3, 3) with ``R g = [0, 0, |g|]`` (Rodrigues, as
    :func:`pdrlearn.signal.gravity_rotation`) for rest specific forces ``g`` (B, 3) in m/s^2."""
    n = np.linalg.norm(g, axis=1)
    if not np.all(np.isfinite(n) & (n > 1e-9)):
        raise DataError("gravity vector is zero or not finite; estimate it from a standstill period")
    a = g / n[:, None]
    c = a[:, 2]
    v = np.stack([a[:, 1], -a[:, 0], np.zeros_like(c)], axis=1)  # a x z
    s = np.linalg.norm(v, axis=1)
    k = v / np.where(s < 1e-12, 1.0, s)[:, None]
    kx = np.zeros((len(g), 3, 3))
    kx[:, 0, 1], kx[:, 0, 2], kx[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    kx[:, 1, 0], kx[:, 2, 0], kx[:, 2, 1] = k[:, 2], -k[:, 1], k[:, 0]
    r = np.eye(3) + s[:, None, None] * kx + (1 - c)[:, None, None] * (kx @ kx)
    flat = s < 1e-12
    r[flat & (c > 0)] = np.eye(3)
    r[flat & (c <= 0)] = np.diag([1.0, -1.0, -1.0])  # 180 deg about x
    return r


def resample_rows(t_new: np.ndarray, t: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Per row ``b``: box anti-alias filter (when downsampling) and linear interpolation of ``v[b]``
    (L, k) sampled at ``t[b]`` (L,) onto ``t_new[b]`` (M,), like ``np.interp`` (clamped ends).

    Returns (B, k, M)."""
    B, L, k = v.shape
    if t_new.shape[1] > 1 and L > 2:
        w = np.rint((t_new[:, 1] - t_new[:, 0]) * (L - 1) / (t[:, -1] - t[:, 0])).astype(int)
        w = 2 * (w // 2) + 1  # odd: a centred box (thesis ch. 4.2.3: firmware averaging)
        if np.any(w > 1):
            v = v.copy()
            for width in np.unique(w[w > 1]):
                sel = w == width
                v[sel] = uniform_filter1d(v[sel], size=int(width), axis=1, mode="nearest")
    if L == 1:
        return np.repeat(v.transpose(0, 2, 1), t_new.shape[1], axis=2)
    j = np.clip((t[:, None, :] <= t_new[:, :, None]).sum(axis=2) - 1, 0, L - 2)  # (B, M)
    rows = np.arange(B)[:, None]
    x0, x1 = t[rows, j], t[rows, j + 1]
    y0, y1 = v[rows, j], v[rows, j + 1]  # (B, M, k)
    slope = (y1 - y0) / (x1 - x0)[..., None]
    out = slope * (t_new - x0)[..., None] + y0
    out = np.where((t_new < t[:, :1])[..., None], v[:, :1], out)
    out = np.where((t_new >= t[:, -1:])[..., None], v[:, -1:], out)
    return out.transpose(0, 2, 1)


def _rest_index(score: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Per row, the first argmin of ``score`` (B, L) within ``[lo, hi)``."""
    idx = np.arange(score.shape[1])[None, :]
    masked = np.where((idx >= lo[:, None]) & (idx < hi[:, None]), score, np.inf)
    return np.argmin(masked, axis=1)


def foot_levelled_batch(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, forward_s: np.ndarray, *,
                        rest_search_s: float, heading: str, first_step: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Foot acc (B, L, 3; gravity removed), gyro (B, L, 3) in each step's frame and |acc| (B, L) for
    segments of equal length L (the per-step ``foot_levelled`` on every row)."""
    B, L, _ = acc.shape
    rows = np.arange(B)
    fs = (L - 1) / (t[:, -1] - t[:, 0]) if L > 1 else np.ones(B)  # mean rate over the step (Hz)
    m = np.maximum(2, np.minimum(np.rint(rest_search_s * fs).astype(int), L // 4 + 1))
    an = np.linalg.norm(acc, axis=2)
    h = np.maximum(0, np.rint(0.02 * fs).astype(int))
    score = np.empty_like(an)  # the per-step kernel's rest score, rows grouped by their half-width h
    for hw in np.unique(h):
        sel = h == hw
        score[sel] = rest_score(an[sel], np.linalg.norm(gyr[sel], axis=2), half_width=int(hw))
    k0 = _rest_index(score, np.zeros(B, int), np.maximum(1, np.minimum(m, L)))
    lo1 = np.maximum(0, L - m)
    k1 = _rest_index(score, lo1, np.maximum(lo1 + 1, L))
    idx = np.arange(L)[None, :]

    def rest_mean(k):
        win = (idx >= np.maximum(k - h, 0)[:, None]) & (idx < (k + h + 1)[:, None])
        return (acc * win[..., None]).sum(axis=1) / win.sum(axis=1)[:, None]

    g0, g1 = rest_mean(k0), rest_mean(k1)
    r0 = gravity_rotation_batch(g0)
    # attitude R_k = r0 P_k0^T P_k, P_k = product of the interval rotations before k (dR/dt = R [w]x)
    rot = np.broadcast_to(r0[:, None], (B, L, 3, 3)).copy()
    if L > 1:
        w = 0.5 * (gyr[:, :-1] + gyr[:, 1:]) * np.diff(t, axis=1)[..., None]
        steps = Rotation.from_rotvec(w.reshape(-1, 3)).as_matrix().reshape(B, L - 1, 3, 3)
        p = np.empty((L, B, 3, 3))
        p[0] = np.eye(3)
        p[1:] = steps.transpose(1, 0, 2, 3)
        shift = 1
        while shift < L:  # Hillis-Steele inclusive scan over the samples, batched over the steps
            p[shift:] = p[:-shift] @ p[shift:]
            shift *= 2
        p = p.transpose(1, 0, 2, 3)
        rot = (r0 @ p[rows, k0].transpose(0, 2, 1))[:, None] @ p
        # tilt drift seen at the second rest spread linearly over k0..k1 (per-step correct_tilt_drift)
        g_lev = np.einsum("bij,bj->bi", rot[rows, k1], g1)
        corr = Rotation.from_matrix(gravity_rotation_batch(g_lev)).as_rotvec()
        span = np.maximum(k1 - k0, 1).astype(float)
        frac = np.clip((idx - k0[:, None]) / span[:, None], 0.0, 1.0) * (k1 > k0)[:, None]
        c = Rotation.from_rotvec((frac[..., None] * corr[:, None, :]).reshape(-1, 3)).as_matrix()
        rot = c.reshape(B, L, 3, 3) @ rot
    a_lev = np.einsum("bkij,bkj->bki", rot, acc)
    a_lev[..., 2] -= np.linalg.norm(g0, axis=1)[:, None]
    ref = (rot[rows, k0] @ forward_s)[:, :2]
    rn = np.linalg.norm(ref, axis=1)
    if np.any(rn < 0.1):
        i = int(first_step[np.flatnonzero(rn < 0.1)[0]])
        raise VerticalAxisError(f"step {i}: foot unit: the declared forward axis points (nearly) vertically at "
                        "rest; check the foot frame in meta.json")
    ref = ref / rn[:, None]
    if heading == "pca":  # principal horizontal axis, signed by the declared forward axis
        hor = a_lev[..., :2]
        vals, vecs = np.linalg.eigh(np.einsum("bki,bkj->bij", hor, hor))
        fwd = vecs[rows, :, np.argmax(vals, axis=1)]
        fwd = np.where((np.einsum("bi,bi->b", fwd, ref) < 0)[:, None], -fwd, fwd)
        fwd = fwd / np.linalg.norm(fwd, axis=1)[:, None]
    else:
        fwd = ref
    yaw_t = _yaw_rotations(fwd).transpose(0, 2, 1)
    return a_lev @ yaw_t, np.einsum("bkij,bkj->bki", rot, gyr) @ yaw_t, an


def _yaw_rotations(fwd: np.ndarray) -> np.ndarray:
    """Rotations about z (B, 3, 3) turning the horizontal unit vectors ``fwd`` (B, 2) onto +x."""
    c, s = fwd[:, 0], fwd[:, 1]
    out = np.zeros((len(fwd), 3, 3))
    out[:, 0, 0], out[:, 0, 1], out[:, 1, 0], out[:, 1, 1], out[:, 2, 2] = c, s, -s, c, 1.0
    return out


def waist_levelled_batch(acc: np.ndarray, gyr: np.ndarray, forward_s: np.ndarray, first_step: np.ndarray
                         ) -> tuple[np.ndarray, np.ndarray]:
    """Waist acc (gravity removed) and rate in each step's frame: tilt from the mean specific force over
    the step, forward = the declared forward axis projected on the horizontal (per-step waist kernel)."""
    g = acc.mean(axis=1)
    r = gravity_rotation_batch(g)
    ref = (r @ forward_s)[:, :2]
    rn = np.linalg.norm(ref, axis=1)
    if np.any(rn < 0.1):
        i = int(first_step[np.flatnonzero(rn < 0.1)[0]])
        raise DataError(f"step {i}: waist unit: the declared forward axis points (nearly) vertically; "
                        "check the waist frame in meta.json")
    rr_t = (_yaw_rotations(ref / rn[:, None]) @ r).transpose(0, 2, 1)
    a = acc @ rr_t
    a[..., 2] -= np.linalg.norm(g, axis=1)[:, None]
    return a, gyr @ rr_t


def _gather(t: np.ndarray, v: np.ndarray, i0: np.ndarray, L: int) -> tuple[np.ndarray, np.ndarray]:
    ii = i0[:, None] + np.arange(L)[None, :]
    return t[ii], v[ii]


def batch_applicable(streams: Streams, available: tuple[str, ...]) -> bool:
    """The batch path needs each unit's gyroscope on its accelerometer's clock (or no gyroscope group
    for that unit's accelerometer); otherwise the per-step kernel is used."""
    for acc, gyr, gacc, ggyr in (("fAccelerometer", "fGyroscope", "foot_acc", "foot_gyr"),
                                 ("wAccelerometer", "wGyroscope", "waist_acc", "waist_gyr")):
        if gacc in available:
            if ggyr not in available:
                return False
            if not np.array_equal(streams[acc][0], streams[gyr][0]):
                return False
    return True


def fill_windows_batch(X: np.ndarray, streams: Streams, start: np.ndarray, end: np.ndarray, *,
                       channel_index: Mapping[str, int], available: tuple[str, ...],
                       forward: Mapping[str, np.ndarray], rest_search_s: float, heading: str) -> None:
    """Fill ``X`` (n_steps, n_channels, n_samples; NaN-initialised) for all steps at once.

    Same inputs as the per-step ``fill_step_window`` with arrays of step ``start``/``end`` times (s).
    Call only when :func:`batch_applicable` is true.
    """
    ci = channel_index
    n, _, n_samples = X.shape
    u = np.linspace(0.0, 1.0, n_samples)
    tg = start[:, None] + (end - start)[:, None] * u[None, :]
    X[:, ci["t_s"]] = tg - start[:, None]
    steps_idx = np.arange(n)

    def by_length(name):
        t, _ = streams[name]
        i0, i1 = segment_bounds(t, start, end)
        lengths = i1 - i0
        for L in np.unique(lengths):
            sel = np.flatnonzero(lengths == L)
            yield sel, i0[sel], int(L)

    def acc_and_gyro(acc_name, gyr_name):
        """Per segment length: the selected steps, sample times, accelerometer and gyroscope segments."""
        t_a, v_a = streams[acc_name]
        v_g = streams[gyr_name][1]
        for sel, i0, L in by_length(acc_name):
            ta, acc = _gather(t_a, v_a, i0, L)
            yield sel, ta, acc, resample_rows(ta, ta, _gather(t_a, v_g, i0, L)[1]).transpose(0, 2, 1)

    if "foot_acc" in available and "foot" in forward:
        for sel, ta, acc, gyr in acc_and_gyro("fAccelerometer", "fGyroscope"):
            a, g, an = foot_levelled_batch(ta, acc, gyr, forward["foot"], rest_search_s=rest_search_s,
                                           heading=heading, first_step=steps_idx[sel])
            c = ci["foot_acc_x"]
            X[sel, c:c + 3] = resample_rows(tg[sel], ta, a)
            X[sel, ci["foot_acc_norm"]] = resample_rows(tg[sel], ta, an[..., None])[:, 0]
            c = ci["foot_gyr_x"]
            X[sel, c:c + 3] = resample_rows(tg[sel], ta, g)
    if "force" in available:
        for j, name in enumerate(("fForceA", "fForceB")):
            t_f, v_f = streams[name]
            for sel, i0, L in by_length(name):
                tf, f = _gather(t_f, v_f, i0, L)
                X[sel, ci["force_a"] + j] = resample_rows(tg[sel], tf, f[..., :1])[:, 0]
    if "waist_acc" in available and "waist" in forward:
        for sel, tw, wacc, wgyr in acc_and_gyro("wAccelerometer", "wGyroscope"):
            a, g = waist_levelled_batch(wacc, wgyr, forward["waist"], steps_idx[sel])
            c = ci["waist_acc_x"]
            X[sel, c:c + 3] = resample_rows(tg[sel], tw, a)
            c = ci["waist_gyr_x"]
            X[sel, c:c + 3] = resample_rows(tg[sel], tw, g)
    if "waist_baro" in available:
        # no anti-alias filter on the barometer: interpolating the whole stream brackets like the segment
        tb, b = streams["wBarometer"]
        X[:, ci["waist_baro"]] = (np.interp(tg.ravel(), tb, b[:, 0]).reshape(tg.shape)
                                  - np.interp(start, tb, b[:, 0])[:, None])
