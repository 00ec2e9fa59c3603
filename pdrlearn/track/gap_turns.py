"""Decisions L701 / L702: a foot track's rest gaps and the lower back's turn (offline two-unit tracks).

:func:`add_waist_gap_turns` changes ``FootDisplacement.gap_yaw_`` (L28's turn between two strides) where the lower
back turned at least ``turn_count_min_deg`` (L104) from the end of one stride to the end of the next while the
foot's heading turned by more than :data:`~pdrlearn.kernels.gap_turn.GAP_TURN_MISS_DEG` less (L701), and returns one
record per gap whose heading turn is then at least ``turn_count_min_deg`` (L702), which :func:`gap_turn_row` makes
turns.csv's rows (``n_rows`` 0: no stride holds the turn).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from pdrlearn.kernels import gap_turn as KG
from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG
from pdrlearn.waist.plausibility import STILL_YAW_RATE_WARN_RPS

#: decisions L701 / L702: the columns of a track's ``info["waist_gap_turns"]`` records: the 5-95 % times of the lower
#: back's gated turn over the gap, the heading's turn there (deg), the lower back's peak rate, L701's addition (deg)
GAP_TURN_KEYS = ("start_s", "end_s", "angle_deg", "peak_dps", "added_deg")


def _span(stream: Callable[[str], tuple[np.ndarray, np.ndarray]], t0: float, t1: float):
    tg, g = stream("wGyroscope")
    ta, a = stream("wAccelerometer")
    i0, i1 = np.searchsorted(tg, [t0, t1], side="left")
    j0, j1 = np.searchsorted(ta, [t0, t1], side="left")
    if i1 - i0 < 2 or j1 <= j0:
        return None
    return tg[i0:i1], g[i0:i1], a[j0:j1]


def setup_rest_bias(rest) -> float | None:
    """Decision L709: the waist's vertical rate (rad/s) over its first standstill (W105's, ``rest[0]`` of
    :func:`pdrlearn.waist.plausibility.waist_bias_check`) when W105 calls it a bias (over
    ``STILL_YAW_RATE_WARN_RPS``), else None. Not W126's profile of every rest: a slow spin on the spot passes its
    standstill mask, and its rate read as a bias would take the spin off."""
    first = rest[0] if rest else None
    if first is None or abs(first[0]) <= STILL_YAW_RATE_WARN_RPS:
        return None
    return float(first[0])


def add_waist_gap_turns(fd, stream: Callable[[str], tuple[np.ndarray, np.ndarray]],
                        min_deg: float = TURN_COUNT_MIN_DEG, bias_rad_s: float | None = None) -> list[dict]:
    """Decisions L701 / L702 (module docstring): ``fd`` (a fitted ``FootDisplacement`` with ``start_s_`` / ``end_s_``,
    ``yaw_change_``, ``gap_yaw_``) gains the lower back's missed turn in its gaps; ``stream(name)`` -> ``(t, values)``
    of the session's ``wGyroscope`` / ``wAccelerometer`` on the foot's clock; ``min_deg``: L104's
    ``turn_count_min_deg``; ``bias_rad_s``: the waist's vertical-rate bias (:func:`setup_rest_bias`), taken off
    before the gate (decision L709); None: none. Returns the gaps' records (:data:`GAP_TURN_KEYS`)."""
    yc = np.asarray(getattr(fd, "yaw_change_", []), float)
    if len(yc) < 2:
        return []
    st, en = np.asarray(fd.start_s_, float), np.asarray(fd.end_s_, float)
    gy = np.array(getattr(fd, "gap_yaw_", np.zeros(len(yc))), dtype=float)
    out = []
    for k in range(1, len(yc)):
        e, s, end = float(en[k - 1]), float(st[k]), float(en[k])
        if not (s > e and end > s):
            continue
        whole = _span(stream, e, end)
        if whole is None:
            continue
        t, g, a = whole
        rate, turn = KG.gated_turn(t, g, a, bias_rad_s=bias_rad_s)
        added = KG.missed_turn(float(turn[-1]), float(gy[k] + yc[k]), min_deg)
        gy[k] += added
        if abs(gy[k]) < math.radians(min_deg):  # decision L702: a gap turning the heading 80 deg or more is a row
            continue
        gap = t <= s
        if not gap.any():  # decision L709: a gap holding no lower-back sample is timed over the whole span
            gap = np.ones(len(t), bool)
        t0, t1 = KG.fraction_times(t[gap], turn[gap])
        out.append(dict(zip(GAP_TURN_KEYS, (t0, t1, math.degrees(float(gy[k])),
                                            math.degrees(float(np.abs(rate[gap]).max())), math.degrees(added)),
                            strict=True)))
    fd.gap_yaw_ = gy
    return out


def gap_turn_row(record: dict, bout_of: Callable[[float], object]) -> dict:
    """Decisions L701 / L702: the turns.csv row (:func:`pdrlearn.track.clinical.turn_table`'s, without its number) of
    one ``info["waist_gap_turns"]`` record: the heading's turn at the gap (``angle_deg``), timed by the lower back's
    gated turn over it, ``n_rows`` 0 (its
    source: no stride holds it), ``mean_rate_dps`` 90 % of |angle| over the 5-95 % duration (a foot turn's, L229),
    ``carried`` false, ``bout`` ``bout_of(start_s)``."""
    t0, t1, angle = float(record["start_s"]), float(record["end_s"]), float(record["angle_deg"])
    dur = t1 - t0
    return {"start_s": t0, "end_s": t1, "duration_s": dur, "angle_deg": angle,
            "peak_rate_dps": float(record["peak_dps"]), "n_rows": 0, "bout": bout_of(t0),
            "mean_rate_dps": 0.9 * abs(angle) / dur if dur > 0 else np.nan, "carried": False}
