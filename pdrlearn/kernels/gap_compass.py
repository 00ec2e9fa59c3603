"""Decision E361: the streamed heading re-anchored to the waist compass after a waist gyroscope gap.

Offline `track` re-aligns each stretch of strides between foot gaps to the waist heading (L90, ``fuse_by_segment``:
the compass through thesis ch. 7.1's complementary filter), so the turn a gap hid comes back from the compass. The
streamed paths (the live ``Tracker``, ``track --streaming``) bridge the gap by E354's line between the gait-cycle
mean rates either side (:class:`~pdrlearn.kernels.stride.CycleGapLine`), which misses a curve's turn inside a gap
longer than the rest of the curve. :class:`GapCompass` keeps, stride by stride, the offset of the waist compass
against the streamed heading and, at the first stride after a gap, turns the heading by the change of that offset,
weighed against E354's line by the two estimates' variances. Pure numpy (the lean ``run`` path imports it)."""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable

import numpy as np

Stream = Callable[[str], tuple[np.ndarray, np.ndarray]]


def level_axis(up: np.ndarray) -> int:
    """Decision E361: the body axis (0, 1, 2) furthest from the vertical ``up`` (the one the compass heading is of)."""
    return int(np.argmin(np.abs(np.asarray(up, dtype=float))))


def _in(t: np.ndarray, t0: float, t1: float) -> slice:
    return slice(int(np.searchsorted(t, t0, side="left")), int(np.searchsorted(t, t1, side="right")))


def compass_offset(stream: Stream, t0: float, t1: float, heading_end: float, axis: int | None = None,
                   field_ut: tuple[float, float] | None = None) -> tuple[float, int] | None:
    """Decision E361: the circular mean (rad) over the waist magnetometer's samples in ``[t0, t1]`` (s) of the
    tilt-compensated compass heading of a level body axis (thesis eq. 33-35, the stride's mean specific force as up;
    ``axis``: the body axis, None = :func:`level_axis`) less the streamed heading at that sample: ``heading_end``
    (rad, the heading after the stride) less the waist's vertical rate integrated (trapezoid) from the sample to
    ``t1``; the pelvis' yaw oscillation, seen by both, cancels. Returns (offset, axis), or None without at least two
    samples of ``wMagneticField``, ``wGyroscope`` and ``wAccelerometer`` in the stride, or (decision E362) when the
    stride's mean field norm is outside ``field_ut`` (uT; None: any)."""
    try:
        (tm, mag), (tg, gyr), (ta, acc) = (stream(n) for n in ("wMagneticField", "wGyroscope", "wAccelerometer"))
    except KeyError:
        return None
    sm, sg, sa = _in(tm, t0, t1), _in(tg, t0, t1), _in(ta, t0, t1)
    if min(sm.stop - sm.start, sg.stop - sg.start, sa.stop - sa.start) < 2:
        return None
    up = np.add.reduce(acc[sa], axis=0)
    n = float(np.sqrt(up @ up))
    if not n > 0:
        return None
    up = up / n
    axis = level_axis(up) if axis is None else int(axis)
    e = np.zeros(3)
    e[axis] = 1.0
    fwd = e - (e @ up) * up
    nf = float(np.sqrt(fwd @ fwd))
    if not nf > 1e-6:  # the axis is vertical: no heading of it
        return None
    fwd = fwd / nf
    left = np.cross(up, fwd)
    m = np.asarray(mag[sm], dtype=float)
    if field_ut is not None and not field_ut[0] <= float(np.mean(np.sqrt(np.add.reduce(m * m, axis=1)))) <= field_ut[1]:
        return None  # decision E362: not the Earth's field (hard iron, steel, a wrong unit): no compass
    compass = -np.arctan2(m @ left, m @ fwd)  # thesis eq. 35 (up to the constant pi/2: the offset absorbs it)
    t, rate = tg[sg], np.asarray(gyr[sg], dtype=float) @ up
    turned = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])  # from t[0]
    heading = heading_end - (turned[-1] - np.interp(tm[sm], t, turned))
    d = compass - heading
    return math.atan2(float(np.mean(np.sin(d))), float(np.mean(np.cos(d)))), axis


def gap_weight(spread: float, offsets: np.ndarray) -> float:
    """Decision E361: the weight (0-1) of the compass's estimate of a gap's turn against E354's line, by their
    variances: ``spread`` (rad) E354's (half the difference of the mean rates either side times the gap's length),
    the compass's ``V * (1 / N + 1)`` (``V = -2 ln R``: the circular variance of the ``N`` offsets before the gap,
    the one stride after adds its own); 0 with fewer than 2 offsets."""
    if len(offsets) < 2:
        return 0.0
    r = math.hypot(float(np.mean(np.sin(offsets))), float(np.mean(np.cos(offsets))))
    var = -2.0 * math.log(max(r, 1e-300)) * (1.0 / len(offsets) + 1.0)
    s2 = float(spread) ** 2
    return s2 / (s2 + var) if s2 + var > 0 else 0.0


class GapCompass:
    """Decision E361: the streamed heading re-anchored to the waist compass after a waist gyroscope gap. Feed every
    row's turn in order: :meth:`row` for a row without its own compass reading (a stride across a foot gap, a
    foot-headed stride), :meth:`stride` for a waist-headed stride (its turn ``dyaw`` complete, E354's line included);
    :meth:`stride` returns the turn (rad, CCW) to add to that stride: 0 unless ``spread`` (E354's
    :attr:`~pdrlearn.kernels.stride.CycleGapLine.spread` of the gap it took, None without) says a gap was just
    bridged, else ``w * wrap(o_after - o_before)`` (:func:`gap_weight`; ``o_before`` the circular mean offset of the
    strides in the ``window_s`` (60 s, L17's window) before it). ``field_ut`` (decision E362): a stride whose mean
    magnetometer norm is outside this range (uT) has no compass reading (None: any). The live ``Tracker`` and ``track
    --streaming`` share it; a session without a waist gap gets 0 at every stride."""

    # decision E362: the Earth's field is 25-65 uT (the physical range kernels.units judges a magnetometer's unit by)
    def __init__(self, *, window_s: float = 60.0, field_ut: tuple[float, float] | None = (25.0, 65.0)) -> None:
        self.window_s = float(window_s)  # decision L17: +-60 s of strides
        self.field_ut = field_ut
        self.heading = 0.0  # the streamed heading's change so far (rad): only differences of offsets are read
        self.axis: int | None = None  # the body axis the compass reads, fixed at the first reading
        self.offsets: deque[tuple[float, float]] = deque()  # (stride end s, offset rad)

    def state(self) -> dict:
        """Decision E370: what a restart state carries (plain numbers, a copy): the heading, the compass's axis and the
        offsets of the last ``window_s`` of strides."""
        return {"heading": float(self.heading), "axis": None if self.axis is None else int(self.axis),
                "offsets": [[float(t), float(o)] for t, o in self.offsets]}

    def restore(self, state: dict) -> None:
        """Decision E370: set to a :meth:`state` (a restart state's ``gap_compass``)."""
        self.heading = float(state["heading"])
        self.axis = None if state["axis"] is None else int(state["axis"])
        self.offsets = deque((float(t), float(o)) for t, o in state["offsets"])

    def row(self, dyaw: float) -> None:
        """A row's turn (rad) without a compass reading of its own."""
        self.heading += float(dyaw)

    def stride(self, stream: Stream, t0: float, t1: float, dyaw: float, spread: float | None) -> float:
        """The waist-headed stride ``[t0, t1]`` (s) turning by ``dyaw`` (rad); returns the turn to add to it."""
        end = self.heading + float(dyaw)
        got = compass_offset(stream, float(t0), float(t1), end, self.axis, self.field_ut)
        turn = 0.0
        while self.offsets and self.offsets[0][0] < float(t0) - self.window_s:
            self.offsets.popleft()
        if got is not None:
            self.axis = got[1]
            if spread is not None and self.offsets:
                before = np.array([d for _, d in self.offsets])
                o_before = math.atan2(float(np.mean(np.sin(before))), float(np.mean(np.cos(before))))
                turn = gap_weight(spread, before) * math.remainder(got[0] - o_before, 2.0 * math.pi)
            self.offsets.append((float(t1), got[0] - turn))
        self.heading = end + turn
        return turn
