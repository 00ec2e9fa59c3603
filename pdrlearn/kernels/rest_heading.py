"""The rotation of a waist unit across a long rest without steps, its gyroscope's bias taken from the rest itself
(decision L296 in docs/decisions/localization.md), numpy only.

W72 (``integrate_stops``) adds the vertical rate integrated from a walking sequence's last contact to the next one's
first, so a turn made standing carries into the heading. Across an hour seated that integral is the gyroscope's bias
times an hour: the simulated waist's bias random walk (5e-5 rad/s/sqrt(s), docs/decisions S12) integrates to ~6 rad
(1 sd) over 3600 s, a calibrated constant bias cannot remove it, and the trial `night` saw a 113 deg "turn" in 0.3 s
after each sit. While the unit is still the body does not turn: its rate there is the bias. So across a rest longer
than :data:`REST_BIAS_MIN_S`, the still samples (``standstill_mask``) add nothing, and the moving ones (standing up,
a turn on the spot) add their rate less the bias of the still samples around them (:data:`BIAS_BLOCK_S` blocks).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.waist import integrate_rate

#: decision L296: a stop longer than this (s) has its bias taken from its own still samples; over a shorter one
#: the rate is integrated whole (W72): the bias walk's integral over a minute is 5e-5 * 60^1.5 / sqrt(3) = 0.013 rad
#: (0.8 deg, 1 sd), under the heading's other errors, and the stop's still samples are too few for a better bias
REST_BIAS_MIN_S = 60.0
#: decision L296: the bias is the mean rate of the still samples of consecutive blocks this long (s), interpolated to
#: the moving samples (the bias walk changes by 5e-5 * sqrt(30) = 2.7e-4 rad/s in a block, 0.016 deg/s)
BIAS_BLOCK_S = 30.0
#: decision L296: a block gives a bias only with this much (s) of still samples
BIAS_MIN_STILL_S = 1.0


def rest_rotation(t: np.ndarray, w: np.ndarray, still: np.ndarray, t0: float, t1: float, *,
                  cum: np.ndarray | None = None, max_dt_s: float | None = None) -> float:
    """Decision L296: the rotation (rad) of the vertical rate ``w`` (rad/s, at ``t`` s) from ``t0`` to ``t1``:
    W72's integral when the stop lasts up to :data:`REST_BIAS_MIN_S` or has no block with :data:`BIAS_MIN_STILL_S`
    of still samples (``still``, bool per sample); else the sum over its moving samples of the rate less the bias
    (the mean rate of each :data:`BIAS_BLOCK_S` block's still samples, interpolated in time). ``cum``:
    :func:`pdrlearn.kernels.waist.rate_integral` of ``(t, w)``, for the short stops. ``max_dt_s`` (decision E334,
    E324's long stop; None: every interval counts, as L296's offline and live waist rests): the samples' weights
    :func:`sample_weights` with a gap in the samples over it adding nothing."""
    if t1 - t0 <= REST_BIAS_MIN_S:
        return integrate_rate(t, w, t0, t1, cum=cum)
    a, b = int(np.searchsorted(t, t0, side="left")), int(np.searchsorted(t, t1, side="right"))
    tt, ww, st = t[a:b], w[a:b], np.asarray(still[a:b], dtype=bool)
    dt = sample_weights(tt, max_dt_s) if len(tt) > 1 else None
    blocks = block_bias(tt, ww, st, dt=dt)
    if blocks is None:
        return integrate_rate(t, w, t0, t1, cum=cum)
    centres, bias = blocks
    moving = ~st
    return float(np.sum((ww[moving] - np.interp(tt[moving], centres, bias)) * dt[moving]))


def sample_weights(t: np.ndarray, max_dt_s: float | None = None) -> np.ndarray:
    """Decisions L296 / E334: each sample's time weight (s) at ``t`` (2 samples or more): half its intervals to its
    neighbours (``np.gradient``'s). With ``max_dt_s``, an interval longer than it (a gap in the samples) counts as the
    median interval: a sample at a gap's edge no longer stands for half the gap (review s51r1 F1: a 90 deg spin read
    718 deg with a waist gap from its end), so a rotation is split at the gap, each side by its own samples."""
    if max_dt_s is None:
        return np.gradient(t)
    d = np.diff(t)
    d = np.where(d > max_dt_s, np.median(d), d)
    return np.concatenate((d[:1], 0.5 * (d[:-1] + d[1:]), d[-1:]))


def block_bias(t: np.ndarray, w: np.ndarray, still: np.ndarray, *,
               dt: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray] | None:
    """Decision L296: the gyroscope's bias over a rest's samples ``t`` (s), rates ``w`` (rad/s; (n,) or (n, k)
    axes) and ``still`` (bool per sample): ``(centres, bias)``, the mean time and the mean rate of the still samples
    of each :data:`BIAS_BLOCK_S` block holding :data:`BIAS_MIN_STILL_S` of them (bias (m,) or (m, k)); None when
    there are fewer than 2 samples or no such block. Shared by the waist's rests (:func:`rest_rotation`) and the
    foot's (decision L476, ``FootDisplacement(rest_bias=...)``). ``dt``: the samples' weights (s;
    :func:`sample_weights`, its default)."""
    st = np.asarray(still, dtype=bool)
    if len(t) < 2:
        return None
    dt = np.gradient(t) if dt is None else dt
    block = np.floor((t - t[0]) / BIAS_BLOCK_S).astype(np.int64)
    n_still = np.bincount(block, weights=st * dt)
    ok = n_still >= BIAS_MIN_STILL_S
    if not ok.any():
        return None
    cols = w[:, None] if w.ndim == 1 else w
    s_rate = np.column_stack([np.bincount(block, weights=np.where(st, c, 0.0) * dt) for c in cols.T])
    t_still = np.bincount(block, weights=np.where(st, t, 0.0) * dt)
    bias = s_rate[ok] / n_still[ok][:, None]
    return t_still[ok] / n_still[ok], (bias[:, 0] if w.ndim == 1 else bias)


def rest_frame_drift(t: np.ndarray, w: np.ndarray, still: np.ndarray, t0: float, t1: float, *,
                     cum: np.ndarray | None = None) -> float:
    """Decision W285: how far (rad) the AHRS's navigation frame turned about the vertical over the rest ``[t0, t1]``
    while the body did not: the raw vertical rate ``w``'s integral (the AHRS integrates the gyroscope as it is,
    bias and all; no compass, W5) less the body's own rotation, L296's :func:`rest_rotation` - the bias integral of
    the rest's still samples and the still-block bias under its moving ones. 0 for a rest up to
    :data:`REST_BIAS_MIN_S` or one without a block of :data:`BIAS_MIN_STILL_S` still samples (no bias known)."""
    if t1 - t0 <= REST_BIAS_MIN_S:
        return 0.0
    return integrate_rate(t, w, t0, t1, cum=cum) - rest_rotation(t, w, still, t0, t1, cum=cum)
