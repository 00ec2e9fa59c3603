"""Side steps in the foot tracks (decisions L219, E124): which ZUPT strides travel sideways, offline and streamed.

A foot stride's travel angle is its horizontal displacement's angle from the foot's facing (``lateral``, left +,
signed with the stride's x like the length). A stride at 60-120 deg over 0.15 m is sideways, and a run of at least
:data:`MIN_SIDE_STRIDES` of them is a side-stepping stretch (L219). Offline (:func:`side_travel_extra`) the whole
session's strides are known; streamed (:class:`SideRun`, E124) a stride's angle is known when it ends, so the run
test is decided at the stride that makes it :data:`MIN_SIDE_STRIDES`: from then on each sideways stride of the run
is placed along its travel angle, and the strides before it keep the facing (a streamed stride is never moved after
it is emitted). Numpy only (the runtime runs it, :mod:`pdrlearn.kernels`).
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from pdrlearn.kernels.stride import headed_by_foot, reversed_by_rules

#: decision L219: a stride whose displacement points 60-120 deg from the foot's facing travels sideways (a forward
#: or backward stride points within a few degrees of it, toe-out included; a side step at 90 deg)
SIDE_ANGLE_DEG = (60.0, 120.0)
#: decision L219: shorter strides are not judged (a shuffle on the spot, a stepping turn's small steps)
SIDE_MIN_STRIDE_M = 0.15
#: decision L219: fewer consecutive sideways strides are no side-stepping stretch; 3 before decision L486 (against a
#: 90 deg stepping turn's step, which L400's turn test now leaves out): 1, a 1-2 stride shuffle along a shelf is side
#: (adopted by L486's rule, measured in L487)
MIN_SIDE_STRIDES = 1
#: decision L400: a stride during which the foot's own heading turned by more than this (deg) is not judged (a turn on
#: the spot's stride: no facing to measure from); the half-width of :data:`SIDE_ANGLE_DEG`'s window around 90 deg
SIDE_MAX_TURN_DEG = (SIDE_ANGLE_DEG[1] - SIDE_ANGLE_DEG[0]) / 2.0
def travel_angle(dx: float, dy: float) -> float:
    """A stride's travel angle (rad) from the foot's facing, signed with its x (the lengths' sign): offline's
    ``lateral`` and :func:`pdrlearn.kernels.stride.placement_offset`'s."""
    return math.atan2(dy, abs(dx)) * (-1.0 if dx < 0 else 1.0)


def is_sideways(angle, length, turn=None):
    """Decision L219's stride test: ``angle`` rad from the foot's facing within :data:`SIDE_ANGLE_DEG` and the
    horizontal ``length`` m over :data:`SIDE_MIN_STRIDE_M` (arrays or one stride); decision L400: and the foot's
    heading change ``turn`` (rad) over the stride at most :data:`SIDE_MAX_TURN_DEG` (None: not checked)."""
    a = np.degrees(np.abs(np.asarray(angle, float)))
    side = (a >= SIDE_ANGLE_DEG[0]) & (a <= SIDE_ANGLE_DEG[1]) & (np.asarray(length, float) > SIDE_MIN_STRIDE_M)
    if turn is None:
        return side
    return side & ~(np.degrees(np.abs(np.asarray(turn, float))) > SIDE_MAX_TURN_DEG)  # L400 (NaN: not checked)


def sideways_runs(angle: np.ndarray, length: np.ndarray, turn: np.ndarray | None = None,
                  min_strides: int | None = None) -> list[tuple[int, int]]:
    """Runs ``(first, last)`` of at least ``min_strides`` (None: :data:`MIN_SIDE_STRIDES`) consecutive sideways
    strides (angle rad from the foot's facing, left +; length m; ``turn`` the foot's heading change over each stride,
    rad, L400)."""
    side = is_sideways(angle, length, turn)
    edges = np.flatnonzero(np.diff(np.r_[0, side.astype(int), 0]))
    least = MIN_SIDE_STRIDES if min_strides is None else int(min_strides)
    return [(int(a_), int(b_ - 1)) for a_, b_ in zip(edges[::2], edges[1::2], strict=True) if b_ - a_ >= least]


def side_travel_extra(lateral: np.ndarray, length: np.ndarray, turn: np.ndarray | None = None) -> np.ndarray:
    """Decision L219 for the offline foot track's waist / fused heading: per stride, the part of its travel angle
    ``lateral`` (rad from the foot's facing) that the waist heading does not see - inside a sideways run
    (:func:`sideways_runs`) the angle minus the median angle of the other strides (the foot's usual offset from the
    walking direction), elsewhere 0 (those strides are tracked as before)."""
    lateral = np.asarray(lateral, float)
    side = np.zeros(len(lateral), dtype=bool)
    for a, b in sideways_runs(lateral, length, turn):  # L400: a turning stride is none
        side[a:b + 1] = True
    if not side.any():
        return np.zeros(len(lateral))
    usual = float(np.median(lateral[~side])) if (~side).any() else 0.0
    return np.where(side, lateral - usual, 0.0)


#: decision E124 (session 28 review): the foot's usual travel angle is the median of the latest this many strides
#: outside any run (E120's window size for the live clock check); a stream shorter than that uses all of them
SIDE_USUAL_STRIDES = 256


def foot_frame(dx, dy, frame=0.0):
    """The displacement ``(dx, dy)`` (m, the step frame, whose x points ``frame`` rad from the foot's facing at the
    stride's start) in the foot's frame: ``(forward, left)`` (offline's ``disp``; scalars or arrays). Decision E319:
    its left part is a streamed table's ``lateral_m``, whose sign says a side step's side (L412's left / right)."""
    c, s = np.cos(frame), np.sin(frame)
    return c * dx - s * dy, s * dx + c * dy


class SideRun:
    """Decision E124: L219's rule one stride at a time, for a foot tracker whose strides go along the waist gyro's
    heading (the streamed ``track --streaming`` and the runtime ``Tracker``, one implementation). Adopted by E124's
    rule (measured in E125): both always call it; decision E234: no module switch turns it off.

    :meth:`stride` takes each measured stride as it ends and returns the angle (rad) to add to its direction: 0
    unless it is the :data:`MIN_SIDE_STRIDES`-th or a later consecutive sideways stride (:func:`is_sideways`), then
    its travel angle less the median travel angle of the earlier strides outside any run (the foot's usual offset,
    :func:`side_travel_extra`'s, from the past only), plus pi when the rules gave its length the sign against its x
    (decision L37's :func:`~pdrlearn.kernels.stride.reversed_by_rules`: the stride goes along its displacement)."""

    def __init__(self) -> None:
        # travel angles of the latest strides outside any run: bounded, as E120 bounds the live clock check (a median
        # over every stride since the start would grow with the stream; session 28 review)
        self.others: deque[float] = deque(maxlen=SIDE_USUAL_STRIDES)
        self.pending: list[float] = []  # those of the current run's sideways strides before it is one
        self.count = 0  # consecutive sideways strides up to the last one
        self.started = False  # decision L505: the first stride is not judged (no facing before it)
        self.lateral = math.nan  # decision E319: the last stride's displacement to the foot's left (m)

    def stride(self, dx: float, dy: float, length: float, frame: float = 0.0, turn: float | None = None) -> float:
        """The angle (rad) to add to the direction of the stride with horizontal displacement ``(dx, dy)`` m in its
        step frame, whose x points ``frame`` rad from the foot's facing at the stride's start (the foot's sixth
        levelled value, :func:`pdrlearn.kernels.window.levelled_units`; 0: the foot's own frame), and rules
        ``length`` m; ``turn`` the foot's heading change over it (rad, decision L400; None: not checked)."""
        fx, fy = foot_frame(dx, dy, frame)  # the displacement in the foot's frame (offline's ``disp``)
        self.lateral = float(fy)  # decision E319: steps.csv lateral_m of a streamed table
        angle = travel_angle(fx, fy)
        if not self.started:  # decision L505: the stream's first stride has no facing before it (a start-up heading
            self.started = True  # fault read a straight walk's first stride as sideways): not judged, not "usual"
            return 0.0
        if not bool(is_sideways(angle, math.hypot(fx, fy), turn)):
            self.others.extend(self.pending if self.count < MIN_SIDE_STRIDES else [])
            self.others.append(angle)
            self.pending, self.count = [], 0
            return 0.0
        self.count += 1
        if self.count < MIN_SIDE_STRIDES:
            self.pending.append(angle)
            return 0.0
        self.pending = []
        usual = float(np.median(self.others)) if self.others else 0.0
        return angle - usual + reversed_by_rules(True, fx, length)

    @property
    def decided(self) -> bool:
        """Decision L243: the last stride given to :meth:`stride` is the :data:`MIN_SIDE_STRIDES`-th or a later
        consecutive sideways stride (a streamed steps table's ``sideways`` column: L228's, decided at the stride)."""
        return self.count >= MIN_SIDE_STRIDES


def whole_runs(decided: np.ndarray, measured: np.ndarray) -> np.ndarray:
    """Decision L243: a streamed table's ``sideways`` flags (:attr:`SideRun.decided`, from a run's
    :data:`MIN_SIDE_STRIDES`-th stride on) extended back over each run's first ``MIN_SIDE_STRIDES - 1`` strides,
    the ``measured`` rows before it (a gap row, never given to :class:`SideRun`, is skipped): the whole run, as
    offline's L228 column marks it, for a reader of the whole table (the CVs, the straight speed)."""
    decided = np.asarray(decided, bool)
    out = decided.copy()
    idx = np.flatnonzero(np.asarray(measured, bool))
    d = decided[idx]
    for s in np.flatnonzero(d & ~np.r_[False, d[:-1]]):
        out[idx[max(0, s - (MIN_SIDE_STRIDES - 1)):s]] = True
    return out


def side_rows(flags, gap_s=None, *, streamed: bool = False) -> np.ndarray:
    """Decisions L228 / L243: (n,) bool, a steps table's side-stepping rows from its ``sideways`` column ``flags``:
    as they are for an offline table (L219's whole runs), a streamed table's (decided from a run's third stride,
    L243) extended back over each run's first strides (:func:`whole_runs`, gap rows - ``gap_s`` > 0 - skipped).
    One reading for the CVs and straight speed (:func:`pdrlearn.track.gait.sideways_rows`) and for backward travel
    (decision L270, :mod:`pdrlearn.kernels.backward`)."""
    flags = np.asarray(flags, dtype=bool)
    if not streamed:
        return flags
    gap = np.zeros(len(flags)) if gap_s is None else np.nan_to_num(np.asarray(gap_s, dtype=float))
    return whole_runs(flags, gap <= 0)


def foot_turn(levelled) -> float:
    """Decision L400: the foot's heading change (rad) over the stride, its attitude change from rest to rest (the
    fifth value of the foot's levelled tuple, :func:`pdrlearn.kernels.stride.stride_motion`'s foot heading)."""
    return float(levelled["foot"][4])


def own_turn(levelled, heading_source: str, turn: float) -> float:
    """Decision L699: a streamed stride's own turn (steps.csv ``turn_angle_rad``, E51): the heading unit's ``turn``
    for a stride headed by the foot, else the foot's (:func:`foot_turn`, L400 / L690's unwrapped rest-to-rest turn),
    as offline's L66 row reports it; the stride's heading change is not touched."""
    return float(turn) if headed_by_foot(levelled, heading_source) else foot_turn(levelled)


def step_frame(levelled) -> float:
    """The step frame's direction (rad) from the foot's facing at the stride's start (decision L34's sixth value of
    the foot's levelled tuple; 0 without it)."""
    foot = levelled["foot"]
    return float(foot[5]) if len(foot) > 5 else 0.0
