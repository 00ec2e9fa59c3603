"""Decision W415: which way the foot unit's strides travel, so that checks that assume forward walking judge it only.

D10's waist frame check and D25's compass mount check take the waist's walking direction for its forward, and B134's
placement check a forward swing's |gyro|: a side-shuffle or backpedal drill read as a mis-declared frame, a unit turned
on the belt and a foot unit that is not on the foot (trial T3 finding 4). The foot unit's rest-to-rest ZUPT strides
(:func:`pdrlearn.track.frame_inference.foot_travel_angles`, with its declared frame) over L219's 0.15 m are classed by
their travel angle from the foot's facing with L219's window (:data:`~pdrlearn.kernels.sideways.SIDE_ANGLE_DEG`):
forward under 60 deg, side 60-120, backward over 120; a stride during which the foot turned more than L400's 30 deg
is not classed (a turn on the spot has no facing). When fewer than :data:`FORWARD_SHARE_MIN` of them travel forward,
the checks are not judged (:func:`not_judged`).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.sideways import SIDE_ANGLE_DEG, SIDE_MAX_TURN_DEG, SIDE_MIN_STRIDE_M

#: decision W415: a check that assumes forward walking is judged when at least this share of the foot's classed
#: strides travel forward (a drill mostly of side or backward strides is not)
FORWARD_SHARE_MIN = 0.5
#: decision W415: B134's placement check needs at least this many classed strides to be silenced (a unit that is not
#: on a foot has no ZUPT stride over 0.15 m: a waist unit's data in the foot files gave 22 strides, none that long)
MIN_CLASSED_STRIDES = 3


def stride_kinds(angle, length, turn=None) -> dict[str, int]:
    """Decision W415: the numbers of ``forward``, ``side`` and ``backward`` strides among those with a horizontal
    ``length`` (m) over L219's :data:`SIDE_MIN_STRIDE_M`, by the travel ``angle`` (rad from the foot's facing) against
    L219's :data:`SIDE_ANGLE_DEG`; ``turn`` (rad, the foot's heading change over each stride) over L400's
    :data:`SIDE_MAX_TURN_DEG` leaves a stride out."""
    kind = stride_kind_labels(angle, length, turn)
    return {k: int((kind == k).sum()) for k in ("forward", "side", "backward")}


def stride_kind_labels(angle, length, turn=None) -> np.ndarray:
    """Decision W415 per stride: (n,) object, ``forward`` / ``side`` / ``backward`` as :func:`stride_kinds` counts
    them, ``""`` for a stride it leaves out (not over 0.15 m, or turning over 30 deg). Decisions L656 / B449 pick the
    strides of L182's compass check and of L390's insole clock offset by it."""
    a = np.degrees(np.abs(np.asarray(angle, float)))
    judged = np.asarray(length, float) > SIDE_MIN_STRIDE_M
    if turn is not None:
        judged &= ~(np.degrees(np.abs(np.asarray(turn, float))) > SIDE_MAX_TURN_DEG)
    lo, hi = SIDE_ANGLE_DEG
    out = np.full(len(a), "", dtype=object)
    out[judged & (a < lo)] = "forward"
    out[judged & (a >= lo) & (a <= hi)] = "side"
    out[judged & (a > hi)] = "backward"
    return out


def disp_kind_labels(disp, turn) -> np.ndarray:
    """:func:`stride_kind_labels` of strides given by their displacement ``disp`` ``(n, >=2)`` in the foot's frame (m,
    x forward, y left) and the foot's heading change ``turn`` (rad) over each."""
    d = np.asarray(disp, float)
    return stride_kind_labels(np.arctan2(d[:, 1], d[:, 0]), np.hypot(d[:, 0], d[:, 1]), turn)


def foot_stride_kinds(session, span: tuple[float, float] | None = None) -> dict[str, int] | None:
    """:func:`stride_kinds` of the session's foot unit's ZUPT strides (inside ``span`` s when given); None without a
    foot unit with a declared frame."""
    from pdrlearn.track.frame_inference import foot_travel_angles

    strides = foot_travel_angles(session, span)
    if strides is None:
        return None
    _t0, _t1, angle, length, turn = strides
    return stride_kinds(angle, length, turn)


def not_judged(kinds: dict[str, int] | None, min_strides: int = 1) -> str | None:
    """Decision W415: why a check that assumes forward walking is not judged ("not judged: N of M foot strides travel
    sideways, K backward"), when at least ``min_strides`` strides are classed and fewer than
    :data:`FORWARD_SHARE_MIN` of them travel forward; None (judge it) otherwise or without ``kinds``."""
    if not kinds:
        return None
    n = kinds["forward"] + kinds["side"] + kinds["backward"]
    if n < max(min_strides, 1) or kinds["forward"] >= FORWARD_SHARE_MIN * n:
        return None
    return (f"not judged: {kinds['side'] + kinds['backward']} of {n} foot strides travel sideways or backward "
            f"({kinds['side']} sideways, {kinds['backward']} backward; the check assumes forward walking, decision "
            "W415)")
