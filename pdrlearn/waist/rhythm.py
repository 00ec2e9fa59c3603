"""Lower-back contacts without walking's stride rhythm: a phone-only track warns (decision W338).

Without a foot unit (W336) nothing tells a standing passenger's bounce in a bus or train (S71, T1 finding 1) from
walking but the lower back itself. Walking repeats itself stride after stride: the vertical trunk acceleration's
autocorrelation has a dominant peak at the stride (Moe-Nilssen & Helbostad 2004, J Biomech 37:121-126, "stride
regularity"; healthy adults about 0.8-0.9, as recalled and not checked), while a vehicle's broad-band bounce (1-3 Hz,
S71) forgets itself within a second. Each walking sequence is cut into chunks of :data:`CHUNK_CONTACTS` contacts (at
least :data:`MIN_CONTACTS`); a chunk's regularity is the autocorrelation of the vertical acceleration between its first
and last contact at lags within :data:`LAG_TOL` of twice its median contact interval (one stride); consecutive chunks
under :data:`MIN_STRIDE_REGULARITY` get one warning line. Nothing is dropped.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.waist.lengths import walking_sequences

#: decision W338: a sequence of fewer contacts is not judged (4 strides: Mobilise-D's bout minimum, W218)
MIN_CONTACTS = 8
#: decision W338: a sequence is judged in chunks of this many contacts (8 strides; our choice)
CHUNK_CONTACTS = 16
#: decision W338: under this stride regularity a sequence lacks walking's rhythm: half the healthy adults' ~0.8 of
#: Moe-Nilssen & Helbostad 2004 (as recalled); our choice, not tuned to data
MIN_STRIDE_REGULARITY = 0.4
#: decision W338: the stride lag is searched within +-20 % of twice the median contact interval
LAG_TOL = 0.2


def stride_regularity(acc_v: np.ndarray, fs: float, step_s: float) -> float:
    """Largest normalised autocorrelation of ``acc_v`` (mean removed) at lags within :data:`LAG_TOL` of
    ``2 * step_s`` (s); NaN when the signal is shorter than two strides or flat."""
    return autocorrelation_peak(acc_v, fs, 2.0 * float(step_s))


def autocorrelation_peak(x: np.ndarray, fs: float, lag_s: float, *, unbiased: bool = False) -> float:
    """Largest autocorrelation of ``x`` (mean removed) at lags within :data:`LAG_TOL` of ``lag_s`` (s), normalised by
    the zero-lag one; ``unbiased`` (decision W350): each lag's sum over its N - m products, as Moe-Nilssen &
    Helbostad 2004 eq. 1 (as recalled), else over N (W338). NaN when ``x`` is shorter than twice the longest lag
    searched or flat."""
    x = np.asarray(x, dtype=np.float64)
    x = x - x.mean() if x.size else x
    lag = float(lag_s) * fs
    if not np.isfinite(lag):
        return float("nan")
    lo, hi = max(int(np.floor(lag * (1 - LAG_TOL))), 1), int(np.ceil(lag * (1 + LAG_TOL)))
    energy = float(x @ x)
    if x.size <= 2 * hi or energy <= 0.0:
        return float("nan")
    n = x.size
    return max(float(x[:-k] @ x[k:]) / (n - k if unbiased else 1) / (energy / (n if unbiased else 1))
               for k in range(lo, hi + 1))


def _chunks(seq: np.ndarray) -> list[np.ndarray]:
    """``seq`` in consecutive chunks of :data:`CHUNK_CONTACTS` (a last one under :data:`MIN_CONTACTS` joins the one
    before; a sequence under :data:`MIN_CONTACTS`: none)."""
    if seq.size < MIN_CONTACTS:
        return []
    cuts = list(range(0, seq.size, CHUNK_CONTACTS))
    if len(cuts) > 1 and seq.size - cuts[-1] < MIN_CONTACTS:
        cuts.pop()
    return [seq[a:b] for a, b in zip(cuts, [*cuts[1:], seq.size], strict=True)]


def arrhythmic_sequences(steps: pd.DataFrame, t: np.ndarray, acc_v: np.ndarray, fs: float
                         ) -> list[tuple[int, int, float]]:
    """``(first, last, regularity)`` of each run of consecutive chunks (:data:`CHUNK_CONTACTS` contacts of one walking
    sequence of ``steps``: ``event_s``, ``has_next``) whose :func:`stride_regularity` is under
    :data:`MIN_STRIDE_REGULARITY` (``t``, ``acc_v``: the lower back's clock and vertical acceleration, gravity
    removed); ``regularity``: the run's median chunk's. Chunks, not whole sequences: a walk and a ride chained into one
    sequence (waist-pll) would average out."""
    if not len(steps):
        return []
    ev = steps["event_s"].to_numpy(float)
    out: list[tuple[int, int, float]] = []
    for seq in walking_sequences(steps["has_next"].to_numpy(bool)):
        run: list[tuple[int, int, float]] = []
        for chunk in _chunks(seq):
            a, b = np.searchsorted(t, [ev[chunk[0]], ev[chunk[-1]]])
            r = stride_regularity(acc_v[a:b], fs, float(np.median(np.diff(ev[chunk]))))
            if np.isfinite(r) and r < MIN_STRIDE_REGULARITY:
                run.append((int(chunk[0]), int(chunk[-1]), r))
                continue
            if run:
                out.append((run[0][0], run[-1][1], float(np.median([x[2] for x in run]))))
            run = []
        if run:
            out.append((run[0][0], run[-1][1], float(np.median([x[2] for x in run]))))
    return out


def arrhythmic_message(steps: pd.DataFrame, first: int, last: int, regularity: float) -> str:
    """Decision W338's one line for the contacts ``first..last`` of a waist track."""
    ev = steps["event_s"].to_numpy(float)
    return (f"{last - first + 1} lower-back contacts at {ev[first]:.1f}-{ev[last]:.1f} s lack walking's stride rhythm "
            f"(vertical stride regularity {regularity:.2f}, walking's is about 0.8: Moe-Nilssen & Helbostad 2004): "
            "standing in a moving bus or train bounces the lower back without a step, so these steps and their "
            "distance may not be walked; a foot unit tells (decisions W336, W338)")
