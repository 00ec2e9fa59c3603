"""Side steps (decisions L218, L219): the lower-back pipelines track a sideways stretch as forward distance.

A lower-back unit gives a step's length and the unit's heading, not the way the step went, so a side step is
counted as forward distance. The cue is the foot unit's ZUPT stride: its horizontal displacement points sideways from
the foot's facing (:func:`pdrlearn.track.frame_inference.foot_travel_angles`). Only with a foot unit and its declared
frame. A run of at least :data:`WARN_MIN_SIDE_STRIDES` consecutive sideways strides gives one warning line
(:func:`sideways_warnings`); the waist steps are not changed. The foot track's fused heading used to take the waist
compass's facing for these strides' direction; :func:`side_travel_extra` adds their travel angle after it
(``plasys.SIDE_TRAVEL_HEADING``, adopted by L219's rule), and with it off ``plasys`` gives the line too. The
stride rule and the run test live in :mod:`pdrlearn.kernels.sideways` (decision E124: the streamed trackers run
them one stride at a time).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.sideways import (  # noqa: F401 - re-exported: the rule lives in the kernel (E124)
    MIN_SIDE_STRIDES,
    SIDE_ANGLE_DEG,
    SIDE_MIN_STRIDE_M,
    side_travel_extra,
    sideways_runs,
)
from pdrlearn.track.frame_inference import foot_travel_angles

#: decision L487: L219's warning lines (foot with the side placement off, and the lower-back pipelines, W344) keep the
#: former 3-stride stretch: a line per 1-stride shuffle would flood a picker's shift; the steps table and the counts
#: take :data:`MIN_SIDE_STRIDES` (1 since L486)
WARN_MIN_SIDE_STRIDES = 3


def sideways_warnings(session, consequence) -> list[str]:
    """Decision L219's lines: one per sideways run of the session's foot unit. ``consequence(t0, t1)`` is the
    pipeline's half sentence on what its track did over that span."""
    strides = foot_travel_angles(session)
    if strides is None:
        return []
    t0, t1, angle, length, turn = strides
    out = []
    for a, b in sideways_runs(angle, length, turn, WARN_MIN_SIDE_STRIDES):  # L400: a turn's stride is no side step
        ang = np.degrees(angle[a:b + 1])
        out.append(f"{b - a + 1} foot strides at {t0[a]:.1f}-{t1[b]:.1f} s travel sideways {side_ways(ang)} "
                   f"({length[a:b + 1].sum():.1f} m by the foot unit's ZUPT strides, median "
                   f"{np.median(np.abs(ang)):.0f} deg from the foot's facing): {consequence(t0[a], t1[b])} "
                   "(decision L219)")
    return out


def side_ways(angle_deg: np.ndarray) -> str:
    """Decision W362: the sides a run of sideways strides went, from their travel angles (deg from the foot's facing,
    > 0 = left, FLU): "to the left" when all went one way, else each stretch in order with its stride count ("10 to
    the left, then 10 to the right"); the old wording named only the median's side (trial T3: "to the right" for 10
    left + 10 right strides)."""
    left = np.asarray(angle_deg, float) > 0
    cuts = np.flatnonzero(np.diff(left.astype(int))) + 1
    parts = np.split(left, cuts)
    if len(parts) == 1:
        return f"to the {'left' if left[0] else 'right'}"
    return ", then ".join(f"{len(p)} to the {'left' if p[0] else 'right'}" for p in parts)
