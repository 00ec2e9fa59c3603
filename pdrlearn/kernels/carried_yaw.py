"""The waist's turn over a streamed stride on the vertical of each instant, carried by the waist gyroscope (decision
E285 in docs/decisions/export.md), numpy only.

A streamed stride headed by the waist gyroscope turned by its rate on the stride's mean specific force
(:func:`pdrlearn.kernels.window.waist_levelled`: "the pelvis never rests while walking"). A stride that starts from
rest (a stop, a turn on the spot) or ends in one gains or loses walking speed within it, so that mean leans by about
``v / (g T)`` (~6 deg at 1.2 m/s over 1.1 s) and the pelvis' roll into or out of the gait leaks into the "vertical"
rate, the same way each time: trial T2 (session 44, F1) lost -0.15 to -0.64 deg at each such stride, always
clockwise (decision E285; judged again in E289). Here the vertical is the mean specific force over the stride and
the :data:`CARRY_BACK_S` seconds before it, each sample's expressed in one body frame by the gyroscope's own
rotation, and carried through the window by the same rotation (a world-fixed vector seen from the turning pelvis).
It reads only samples up to the stride's end (causal): ``pdrlearn run`` / the ``Tracker`` and ``track --streaming``
call the same function.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from pdrlearn.kernels.rotation import rotvec_to_matrix
from pdrlearn.kernels.stride import WAIST_GAP_S, headed_by_foot, long_stop_turn, waist_gap_from, yaw_change
from pdrlearn.kernels.window import TIE_S, interp, segment

#: decision E285: the vertical is the mean specific force over the stride and this many seconds (s) before its start
#: (or the gap L498 counts, when longer): a start's speed change v leans it by v / (g W), ~1.4 deg at 1.2 m/s over 5 s
CARRY_BACK_S = 4.0

Stream = Callable[[str], tuple[np.ndarray, np.ndarray]]


def carried_yaw(stream: Stream, lo: float, t0: float, t1: float) -> tuple[float, float] | None:
    """Decision E285: ``(gap, own)``, the waist's turn (rad, CCW) over ``[lo, t0]`` and over ``[t0, t1]`` (s,
    ``lo <= t0 < t1``), on the carried vertical (the module's doc) of the window ``[min(lo, t0 - CARRY_BACK_S),
    t1]``. None without the waist accelerometer / gyroscope samples to read it. ``stream(name)`` -> ``(t,
    values)`` of a buffered stream."""
    a = min(float(lo), float(t0) - CARRY_BACK_S)
    try:
        ta, acc = segment(*stream("wAccelerometer"), a, float(t1))
        tg, gyr = segment(*stream("wGyroscope"), a, float(t1))
    except KeyError:
        return None
    # the sample at or before the window's start; E35's TIE_S: a sample within it of a limit is on it (a clock shifted
    # by a waist_clock_offset_s moves the last bits of the times, not the window)
    i0 = max(int(np.searchsorted(tg, a + TIE_S, side="right")) - 1, 0)
    tg, gyr = tg[i0:], np.asarray(gyr, dtype=float)[i0:, :3]
    gaps = np.flatnonzero(np.diff(tg) > WAIST_GAP_S)  # E114's waist gap: no rotation is known across it
    if len(gaps):
        tg, gyr = tg[gaps[-1] + 1:], gyr[gaps[-1] + 1:]
        a = float(tg[0]) if len(tg) else a
        if not a <= lo + TIE_S:  # the gap L61 / L498 count has no carried vertical: the caller keeps the old reading
            return None
    if len(ta) < 2 or len(tg) < 2 or not tg[-1] >= t1 - TIE_S or tg[0] > t0 + TIE_S:  # E35: within TIE_S is on it
        return None
    f = np.column_stack([interp(tg, ta, np.asarray(acc, dtype=float)[:, k]) for k in range(3)])  # gyro's clock
    # frame j+1 -> frame j by the gyroscope's mean rate over the interval; c[j]: frame j -> frame 0
    steps = rotvec_to_matrix(0.5 * (gyr[1:] + gyr[:-1]) * np.diff(tg)[:, None])
    c = np.empty((len(tg), 3, 3))
    c[0] = np.eye(3)
    for j in range(1, len(tg)):
        c[j] = c[j - 1] @ steps[j - 1]
    inside = (tg >= a - TIE_S) & (tg <= t1 + TIE_S)
    up = np.einsum("jik,jk->i", c[inside], f[inside])  # the specific forces in frame 0, summed
    n = float(np.sqrt(up.dot(up)))
    if not n > 0:
        return None
    ups = np.einsum("jki,k->ji", c, up / n)  # frame 0's vertical in each frame j (c[j] transposed)
    rate = np.einsum("ij,ij->i", gyr, ups)
    return yaw_change(tg, rate, float(lo), float(t0)), yaw_change(tg, rate, float(t0), float(t1))


def carried_turn(stream: Stream, levelled, heading_source: str, prev_end: float | None, t0: float, t1: float,
                 waist_gap: bool = True, *, stop_turn: float | None = None) -> tuple[float, float] | None:
    """Decision E285: ``(turn, dyaw)`` of a stride headed by the waist gyroscope: its own turn over ``[t0, t1]`` and
    its heading change with the gap before it (the span L61 / L498's gap yaw covers,
    :func:`~pdrlearn.kernels.stride.waist_gap_from`, when ``waist_gap``), both by :func:`carried_yaw` (and E324's
    :func:`~pdrlearn.kernels.stride.long_stop_turn` before that span); None for a
    foot-headed stride (or no waist samples), which keeps :func:`~pdrlearn.kernels.stride.stride_motion` and
    :func:`~pdrlearn.kernels.stride.stride_gap_yaw`'s. The runtime and ``track --streaming`` call it alike.
    ``stop_turn``: that long-stop turn when the caller has it (decision E335: read once per stride)."""
    if headed_by_foot(levelled, heading_source):
        return None
    s = carried_yaw(stream, waist_gap_from(prev_end, t0, waist_gap), t0, t1)
    if s is None:
        return None
    gap, own = s
    if waist_gap:  # decision E324: a stop over 60 s adds its turn before L498's last second (L296's rest rotation)
        gap += long_stop_turn(stream, prev_end, t0) if stop_turn is None else stop_turn
    return own, own + gap
