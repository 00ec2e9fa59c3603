"""Is a waist track walking? Plausibility cues that do not depend on the estimated speed (decision W98).

A waist track's warnings on slow gait (L95, W77) read the estimated cadence and speed, which a wheelchair
user's arm pushes, a phantom contact inside a slow step or a cane strike corrupt themselves. Real steps move
the weight from one foot to the other: the pelvis's medio-lateral velocity at consecutive contacts has
opposite signs (W20). :func:`alternation_index` measures that from the contacts alone.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.waist import _kernels as K

#: W98: an index under this (the midpoint between walking, ~1, and no lateral weight shift, ~0; a priori)
ALTERNATION_MIN = 0.5
#: W98: fewer consecutive-contact pairs than this are not judged
PLAUSIBILITY_MIN_PAIRS = 10


def alternation_index(v_at: np.ndarray, has_next: np.ndarray) -> tuple[float | None, int]:
    """``(A, pairs)``: ``A = -sum v_k v_(k+1) / sum (v_k^2 + v_(k+1)^2) / 2`` over the consecutive contacts
    ``k, k+1`` of one walking sequence (``has_next[k]``), ``v_at`` the pelvis's lateral velocity at each
    contact (decision W98). 1 = the contacts alternate sides, ~0 = no lateral weight shift, -1 = same side.
    None when there is no pair or no lateral motion at all."""
    v = np.asarray(v_at, dtype=np.float64)
    hn = np.asarray(has_next, dtype=bool)
    if v.size < 2:
        return None, 0
    k = np.flatnonzero(hn[:-1])
    if k.size == 0:
        return None, 0
    a, b = v[k], v[k + 1]
    den = float(np.sum(0.5 * (a * a + b * b)))
    if not np.isfinite(den) or den <= 0.0:
        return None, int(k.size)
    return float(-np.sum(a * b) / den), int(k.size)


def contact_alternation(t: np.ndarray, acc_ml: np.ndarray, fs: float, event_s: np.ndarray,
                        has_next: np.ndarray) -> tuple[float | None, int]:
    """:func:`alternation_index` of the contacts at ``event_s`` (s, on the sample times ``t``), with W20's
    :func:`~pdrlearn.waist._kernels.lateral_velocity` of the medio-lateral acceleration ``acc_ml``."""
    ev = np.asarray(event_s, dtype=np.float64)
    if ev.size < 2:
        return None, 0
    idx = np.clip(np.searchsorted(t, ev), 0, len(t) - 1)
    return alternation_index(K.lateral_velocity(acc_ml, fs)[idx], has_next)


def not_alternating_message(index: float, pairs: int) -> str:
    """Decision W98's one warning line for a waist track whose steps do not alternate left/right."""
    return (f"the detected steps do not alternate left/right (alternation index {index:.2f} over {pairs} "
            f"consecutive steps; walking is ~1, under {ALTERNATION_MIN:g} warns, decision W98): the pelvis shows "
            "no sideways weight shift from step to step, so the step count, distance and speed may not be "
            "walking (wheelchair propulsion, walking-aid strikes, phantom steps at very slow gait); check with "
            "a foot unit or 'pdrlearn steps DIR --detector pelvic-gyro'")
