"""A slow stair stride's swing lull is no stance (decision E345 in docs/decisions/export.md), numpy only.

The streamed segmenter (:class:`pdrlearn.kernels.stride.StanceSegmenter`, the foot gyroscope alone, E7's 0.8 rad/s)
takes the middle of a slow stair swing, where the foot turns slowly for 0.07-0.15 s, for a stance and cuts the stride
in two halves whose raw heights reverse (L611's closed loop) and whose directions flip. The foot accelerometer there
reads no rest by L611's own rest test (:func:`pdrlearn.kernels.pedal.unrested_strides`: trial s52t1's 3.1-4.8 m/s^2;
a real walk's streamed boundaries at most 0.86). So two consecutive strides cut at such an instant, each starting or
ending at a rest, are one stride. ``track --streaming`` (:func:`join_lulls`) and the live ``Tracker`` (stride by
stride) decide each pair by :func:`joins`.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.pedal import unrested_strides


def moving_at(t: np.ndarray, acc: np.ndarray, at_s, g_rest: float) -> np.ndarray:
    """Decision E345: (k,) bool, the instants ``at_s`` (s) with no rest of the foot by L611's rest test (the median
    | |acc| - g_rest | within ``REST_WINDOW_S`` of the instant at least ``UNRESTED_MPS2``; no sample there is a rest)
    on the foot accelerometer ``t`` (s), ``acc`` (n, 3) m/s^2."""
    at = np.atleast_1d(np.asarray(at_s, dtype=float))
    if not len(at) or not len(t):
        return np.zeros(len(at), dtype=bool)
    return unrested_strides(t, acc, at, at, g_rest)


def joins(first: tuple[float, float], second: tuple[float, float], moving_a: bool, moving_b: bool, moving_c: bool,
          max_step_s: float) -> bool:
    """Decision E345: whether the strides ``first`` = (a, b) and ``second`` = (b, c) (s) are one stride: the second
    starts where the first ends, that boundary ``b`` is a lull (``moving_b``) while ``a`` and ``c`` rest, and the
    joined stride lasts at most ``max_step_s`` (the segmenter's longest stride). A pedalling crank's boundaries are all
    unrested, so its strides are never joined (L611 judges them)."""
    return (second[0] == first[1] and bool(moving_b) and not moving_a and not moving_c
            and second[1] - first[0] <= max_step_s)


def join_lulls(strides: np.ndarray, t: np.ndarray, acc: np.ndarray, g_rest: float, max_step_s: float) -> np.ndarray:
    """Decision E345: the streamed ``strides`` ((n, 2) start, end s, in order) with each pair :func:`joins` accepts
    made one, in one pass from the first (a joined stride ends at a rest, so it joins no further)."""
    strides = np.asarray(strides, dtype=float).reshape(-1, 2)
    if len(strides) < 2:
        return strides
    mov_start = moving_at(t, acc, strides[:, 0], g_rest)
    mov_end = moving_at(t, acc, strides[:, 1], g_rest)
    out, i = [], 0
    while i < len(strides):
        if i + 1 < len(strides) and joins(tuple(strides[i]), tuple(strides[i + 1]), mov_start[i], mov_end[i],
                                          mov_end[i + 1], max_step_s):
            out.append((strides[i, 0], strides[i + 1, 1]))
            i += 2
        else:
            out.append((strides[i, 0], strides[i, 1]))
            i += 1
    return np.array(out, dtype=float).reshape(-1, 2)
