"""Lower-back contacts of a ride: no pelvic step rhythm and a vibration-like vertical signal (decision W486).

A vehicle's bounce passes the lower back's motion gate and its contact rules (T3 finding F3: a standing bus and tram
gave 180 and 139 contacts, no step), and without a foot unit W336 cannot tell. The pelvis still tells: it rotates once
per step whatever the cadence (thesis ch.5.3, W440), so the pelvic-gyro detector finds no step in a ride; and a walk
repeats itself stride after stride (W338's stride regularity) while a vehicle's broad-band bounce does not. A run of
at least W336's :data:`~pdrlearn.waist.foot_rest.MIN_STILL_CONTACTS` consecutive contacts none within W336's
:data:`~pdrlearn.waist.foot_rest.FOOT_MARGIN_S` of a pelvic-gyro step, whose vertical acceleration over the run (padded
by that margin) has a stride regularity under W338's :data:`~pdrlearn.waist.rhythm.MIN_STRIDE_REGULARITY`, is a
ride? - named in one line, not dropped (W486's drop rule was not met). Pure numerical kernels on event times and one
signal; no new threshold.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.signal.conditioning import runs
from pdrlearn.waist.foot_rest import FOOT_MARGIN_S, MIN_STILL_CONTACTS
from pdrlearn.waist.rhythm import MIN_STRIDE_REGULARITY, stride_regularity


def stepless_pelvis(event_s: np.ndarray, gyro_s: np.ndarray, margin_s: float = FOOT_MARGIN_S) -> np.ndarray:
    """Per contact (``event_s``, s): True when no pelvic-gyro step (``gyro_s``, s) lies within ``margin_s``."""
    ev = np.asarray(event_s, dtype=np.float64)
    g = np.sort(np.asarray(gyro_s, dtype=np.float64))
    if not g.size:
        return np.ones(ev.shape, dtype=bool)
    j = np.clip(np.searchsorted(g, ev), 1, max(g.size - 1, 1))
    near = np.minimum(np.abs(ev - g[j - 1]), np.abs(g[np.minimum(j, g.size - 1)] - ev))
    return near > margin_s


def ride_runs(event_s: np.ndarray, gyro_s: np.ndarray, t: np.ndarray, acc_v: np.ndarray, fs: float,
              min_contacts: int = MIN_STILL_CONTACTS, margin_s: float = FOOT_MARGIN_S,
              max_regularity: float = MIN_STRIDE_REGULARITY) -> list[tuple[int, int, float]]:
    """Decision W486: ``(first, last, regularity)`` of each run of at least ``min_contacts`` consecutive contacts
    (``event_s``, s, sorted) none within ``margin_s`` of a pelvic-gyro step (``gyro_s``), whose vertical acceleration
    ``acc_v`` (clock ``t``, rate ``fs``) from ``margin_s`` before the first to ``margin_s`` after the last contact has
    W338's :func:`~pdrlearn.waist.rhythm.stride_regularity` (at the run's median contact interval) under
    ``max_regularity``; a run too short to judge (NaN) is no ride."""
    ev = np.asarray(event_s, dtype=np.float64)
    if ev.size < min_contacts:
        return []
    out = []
    for i, j in runs(stepless_pelvis(ev, gyro_s, margin_s)):
        if j - i < min_contacts:
            continue
        a, b = np.searchsorted(t, [ev[i] - margin_s, ev[j - 1] + margin_s])
        r = stride_regularity(acc_v[a:b], fs, float(np.median(np.diff(ev[i:j]))))
        if np.isfinite(r) and r < max_regularity:
            out.append((int(i), int(j - 1), float(r)))
    return out


def ride_message(event_s: np.ndarray, found: list[tuple[int, int, float]]) -> str:
    """Decision W486's one line for the runs ``found`` (:func:`ride_runs`) of contacts ``event_s`` (still counted:
    W486's rule for dropping them was not met, the simulator's own vehicle bounce repeats itself too often)."""
    ev = np.asarray(event_s, dtype=np.float64)
    n = sum(b - a + 1 for a, b, _ in found)
    spans = ", ".join(f"{ev[a]:.1f}-{ev[b]:.1f} s" for a, b, _ in found)
    regs = [r for _, _, r in found]
    return (f"{n} lower-back contacts in {len(found)} run(s) ({spans}) have no pelvic step rhythm (the pelvic-gyro "
            f"detector finds no step within {FOOT_MARGIN_S:g} s) and a vibration-like vertical signal (stride "
            f"regularity {min(regs):.2f}-{max(regs):.2f}, walking's is about 0.8): vehicle / ride? These contacts "
            "are still counted as steps and distance; check the span, or track with a foot unit, which tells "
            "(decisions W486, W336)")


def ride_spans(event_s: np.ndarray, found: list[tuple[int, int]], pad_s: float = FOOT_MARGIN_S
               ) -> list[tuple[float, float]]:
    """Decision W488: ``(start_s, end_s)`` of each run ``(first, last, ...)`` of dropped contacts ``event_s``, padded by
    ``pad_s``: where the pelvis rode."""
    ev = np.asarray(event_s, dtype=np.float64)
    return [(float(ev[r[0]] - pad_s), float(ev[r[1]] + pad_s)) for r in found]
