"""The waist gyroscope's bias about the vertical read at each stop of a streamed walk, causally (decision E272 in
docs/decisions/export.md), numpy only.

A streamed stride headed by the waist gyroscope turns by the integral of its levelled vertical rate (thesis ch.7.1,
:func:`pdrlearn.kernels.stride.yaw_change`), bias and all; the simulator's waist bias walks (docs/decisions S12) and a
warming MEMS gyroscope drifts by ~0.1 deg/s, which turned trial T2's streamed day by -3.5 deg a minute. While the body
stands or sits still its heading does not turn: the vertical rate there is the bias (L296, W126). So at the first
stride after a stop of at least :data:`STOP_MIN_S`, :class:`StopBias` reads the mean vertical rate of the still
samples of the stop's last :data:`WINDOW_S` seconds (ending :data:`LEAD_S` before the stride), and the strides after
it lose that bias times their span. It reads only samples before the stride (causal): ``pdrlearn run`` / the
``Tracker`` and ``track --streaming`` call the same code.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from pdrlearn.kernels.contact import MAX_STRIDE_S
from pdrlearn.kernels.rest_heading import block_bias
from pdrlearn.kernels.waist import still_from_magnitudes
from pdrlearn.kernels.window import interp, segment

#: decision E272: a stop (no stride) this long (s) or longer gives a bias (W105's still periods are >= 2 s; 10 s holds
#: several seconds of still samples after sitting down or before standing up)
STOP_MIN_S = 10.0
#: decision E272: the bias is read over the stop's last this many seconds (the bias walk changes by 5e-5 * sqrt(20) =
#: 2.2e-4 rad/s in them, docs/decisions S12)
WINDOW_S = 20.0
#: decision E272: ending this long (s) before the next stride's start: the other foot steps first and the pelvis turns
#: into the walk before the instrumented foot leaves the ground
LEAD_S = 1.5
#: decision E272: the live tracker keeps this much (s) of a stop's samples, so the window is held when the stride after
#: it is measured (the stride lasts up to ``MAX_STRIDE_S``; 2 s for the step's window and the computed-ahead step)
KEEP_S = WINDOW_S + LEAD_S + MAX_STRIDE_S + 2.0

Stream = Callable[[str], tuple[np.ndarray, np.ndarray]]


def stop_yaw_bias(stream: Stream, prev_end: float | None, t0: float) -> float | None:
    """Decision E272: the waist gyroscope's vertical rate (rad/s) at the stop between the stride that ended at
    ``prev_end`` and the one starting at ``t0`` (s): the rate on the mean specific force's direction (as the gap yaw
    reads it, L31 / L61), averaged over the still samples (L296's test, :func:`still_from_magnitudes`, and its block
    mean, :func:`block_bias`) of ``[max(prev_end, t0 - LEAD_S - WINDOW_S), t0 - LEAD_S]``. None when there is no
    such stop (the stop under :data:`STOP_MIN_S`), no waist accelerometer / gyroscope, or no second of still samples.
    Decision E286: ``prev_end`` None (no stride yet) reads the rest before the first stride, from the stream's first
    sample (the docs' "stand still 10 s before a walk"; before, it was never read). ``stream(name)`` -> ``(t,
    values)`` of a buffered stream."""
    if prev_end is None:  # decision E286: the rest before the first stride counts from the stream's first sample
        try:
            prev_end = float(stream("wAccelerometer")[0][0])
        except (KeyError, IndexError):
            return None
    if not t0 - prev_end >= STOP_MIN_S:
        return None
    read = vertical_rate(stream, max(float(prev_end), float(t0) - LEAD_S - WINDOW_S), float(t0) - LEAD_S)
    if read is None:
        return None
    blocks = block_bias(*read)
    return None if blocks is None else float(blocks[1][-1])  # the newest block: nearest the walk


def vertical_rate(stream: Stream, a: float, b: float) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Decisions E272 / E324: ``(t, w, still)`` of the waist samples in ``[a, b]`` (s): the gyroscope's rate on the
    mean specific force's direction (as the gap yaw reads it, L31 / L61) on the accelerometer's clock, and L296's still
    test (:func:`still_from_magnitudes`); None without the waist accelerometer / gyroscope or with under 3 samples."""
    try:
        ta, acc = segment(*stream("wAccelerometer"), a, b)
        tg, gyr = segment(*stream("wGyroscope"), a, b)
    except KeyError:
        return None
    keep = (ta >= a) & (ta <= b)  # segment adds a sample either side (for interpolation)
    ta, acc = ta[keep], np.asarray(acc, dtype=float)[keep, :3]
    if len(ta) < 3 or len(tg) < 2:
        return None
    g = np.column_stack([interp(ta, tg, np.asarray(gyr, dtype=float)[:, k]) for k in range(3)])  # on acc's clock
    up = acc.mean(axis=0)
    n = float(np.sqrt(up.dot(up)))
    period = float(np.median(np.diff(ta)))
    if not n > 0 or not period > 0:
        return None
    still = still_from_magnitudes(np.sqrt((acc * acc).sum(axis=1)), np.sqrt((g * g).sum(axis=1)), 1.0 / period)
    return ta, g.dot(up / n), still


class StopBias:
    """Decision E272's running bias: :meth:`update` at each waist-headed stride reads a new one after a stop
    (:func:`stop_yaw_bias`); :meth:`turn` is what the stride's turn loses. ``rps`` starts at 0 (nothing known)."""

    def __init__(self) -> None:
        self.rps = 0.0
        self.n_stops = 0

    def update(self, stream: Stream, prev_end: float | None, t0: float) -> None:
        b = stop_yaw_bias(stream, prev_end, t0)
        if b is not None:
            self.rps = b
            self.n_stops += 1

    def turn(self, t0: float, t1: float) -> float:
        """The bias's turn (rad) over ``[t0, t1]`` (s): what a stride's (or gap's) integrated rate loses."""
        return self.rps * max(0.0, float(t1) - float(t0))
