"""Side steps (decisions L218, L219): the lower-back pipelines track a sideways stretch as forward distance.

A lower-back unit gives a step's length and the unit's heading, not the way the step went, so a side step is
counted as forward distance. The cue is the foot unit's ZUPT stride: its horizontal displacement points sideways from
the foot's facing (:func:`pdrlearn.track.frame_inference.foot_travel_angles`). Only with a foot unit and its declared
frame. A run of at least :data:`MIN_SIDE_STRIDES` consecutive sideways strides gives one warning line
(:func:`sideways_warnings`); the waist steps are not changed. The foot track's fused heading used to take the waist
compass's facing for these strides' direction; :func:`side_travel_extra` adds their travel angle after it
(``plasys.SIDE_TRAVEL_HEADING``, adopted by L219's rule), and with it off ``plasys`` gives the line too.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.track.frame_inference import foot_travel_angles

#: decision L219: a stride whose displacement points 60-120 deg from the foot's facing travels sideways (a forward
#: or backward stride points within a few degrees of it, toe-out included; a side step at 90 deg)
SIDE_ANGLE_DEG = (60.0, 120.0)
#: decision L219: shorter strides are not judged (a shuffle on the spot, a stepping turn's small steps)
SIDE_MIN_STRIDE_M = 0.15
#: decision L219: fewer consecutive sideways strides are no side-stepping stretch (a 90 deg stepping turn's step)
MIN_SIDE_STRIDES = 3


def sideways_runs(angle: np.ndarray, length: np.ndarray) -> list[tuple[int, int]]:
    """Runs ``(first, last)`` of at least :data:`MIN_SIDE_STRIDES` consecutive sideways strides (angle rad from the
    foot's facing, left +; length m)."""
    a = np.degrees(np.abs(np.asarray(angle, float)))
    side = (a >= SIDE_ANGLE_DEG[0]) & (a <= SIDE_ANGLE_DEG[1]) & (np.asarray(length, float) > SIDE_MIN_STRIDE_M)
    edges = np.flatnonzero(np.diff(np.r_[0, side.astype(int), 0]))
    return [(int(a_), int(b_ - 1)) for a_, b_ in zip(edges[::2], edges[1::2], strict=True)
            if b_ - a_ >= MIN_SIDE_STRIDES]


def sideways_warnings(session, consequence) -> list[str]:
    """Decision L219's lines: one per sideways run of the session's foot unit. ``consequence(t0, t1)`` is the
    pipeline's half sentence on what its track did over that span."""
    strides = foot_travel_angles(session)
    if strides is None:
        return []
    t0, t1, angle, length = strides
    out = []
    for a, b in sideways_runs(angle, length):
        ang = np.degrees(angle[a:b + 1])
        way = "left" if np.median(ang) > 0 else "right"
        out.append(f"{b - a + 1} foot strides at {t0[a]:.1f}-{t1[b]:.1f} s travel sideways to the {way} "
                   f"({length[a:b + 1].sum():.1f} m by the foot unit's ZUPT strides, median "
                   f"{np.median(np.abs(ang)):.0f} deg from the foot's facing): {consequence(t0[a], t1[b])} "
                   "(decision L219)")
    return out


def side_travel_extra(lateral: np.ndarray, length: np.ndarray) -> np.ndarray:
    """Decision L219 for the foot track's waist / fused heading: per stride, the part of its travel angle
    ``lateral`` (rad from the foot's facing) that the waist heading does not see - inside a sideways run
    (:func:`sideways_runs`) the angle minus the median angle of the other strides (the foot's usual offset from the
    walking direction), elsewhere 0 (those strides are tracked as before)."""
    lateral = np.asarray(lateral, float)
    side = np.zeros(len(lateral), dtype=bool)
    for a, b in sideways_runs(lateral, length):
        side[a:b + 1] = True
    if not side.any():
        return np.zeros(len(lateral))
    usual = float(np.median(lateral[~side])) if (~side).any() else 0.0
    return np.where(side, lateral - usual, 0.0)
