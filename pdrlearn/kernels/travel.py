"""The walked distance and each foot stride's travel label, one definition for the full tracks and the lean runtime
(decisions E316, E317; L412, L484, L654).

A stride's ``length_m`` carries the sign of its measured travel (decision L654: negative for a backward stride), so
a signed sum nets a back-pedal out of the distance: the walked distance is the sum of |``length_m``|
(:func:`walked_distance`; ``TrackResult.distance_m``, so ``track``'s and ``pdrlearn run``'s ``distance_m``, and the
lean ``python -m pdrlearn.runtime``'s, decision E316). :func:`travel_label_array` is steps.csv's ``travel`` label
(decision L412: backward, left / right / side, turn, empty, forward) from arrays; :mod:`pdrlearn.track.travel`
reads it from a pandas table, :func:`travel_rows` from the lean runtime's row dicts (decision E317).
Standard library and numpy only.
"""

from __future__ import annotations

import math

import numpy as np


def walked_distance(length_m) -> float:
    """Decision E316: the distance (m) walked over strides of signed lengths ``length_m`` - the sum of their
    absolute values (NaN rows count 0, as pandas' ``abs().sum()``): a backward stride (negative, L654) adds its
    length, as L484's ``backward_distance_m`` counts it within ``distance_m``."""
    length = np.abs(np.asarray(length_m, dtype=float))
    return float(np.nansum(length)) if length.size else 0.0


def loop_closure(x_m, y_m, distance_m: float) -> tuple[float | None, float | None]:
    """Decision L771 (trial s50t1 F8): the horizontal distance (m) of a track's last position ``x_m[-1], y_m[-1]``
    from its first, and that distance as % of the walked ``distance_m`` (None without a distance). Meaningful only
    when the walk returns to its start (a loop, an out-and-back mission): then it is the track's closure error
    without ground truth; on any other walk it is just the start-to-end distance. (None, None) without positions."""
    x, y = np.asarray(x_m, dtype=float), np.asarray(y_m, dtype=float)
    if not x.size or not np.isfinite([x[0], x[-1], y[0], y[-1]]).all():
        return None, None
    gap = float(math.hypot(x[-1] - x[0], y[-1] - y[0]))
    return gap, (100.0 * gap / float(distance_m) if distance_m and distance_m > 0 else None)


def side_of(lateral_m) -> np.ndarray:
    """Decisions L412, E319 (review R2 F6): (n,) object, ``left`` where the displacement's left component
    ``lateral_m`` (m, the foot's frame: y left) is > 0, ``right`` where < 0, None where it is 0 or NaN (no side)."""
    lateral = np.asarray(lateral_m, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(lateral > 0, "left", np.where(lateral < 0, "right", None)).astype(object)


def travel_label_array(length_m, back, side, turn_angle_rad=None, gap_s=None, impossible=None,
                       given=None, lateral_m=None) -> np.ndarray:
    """Decision L412: (n,) object, each foot stride's ``travel`` label: ``backward`` where ``back`` (L203's
    backward travel), a ``side`` row (L228's whole runs) its ``given`` ``left`` / ``right`` else ``side``, ``turn``
    for a turn on the spot (L692), empty for a shuffle under ``SIDE_MIN_STRIDE_M`` (L219), a NaN length, a gap row
    (``gap_s`` > 0, L67) or an ``impossible`` stride (L97), ``forward`` otherwise. ``length_m`` the measured (raw)
    signed lengths; each other argument (n,) or None (not known). Decision E319: a side row without a ``given``
    side is left / right by the sign of its ``lateral_m`` (a streamed table's; > 0 left), ``side`` without one."""
    from pdrlearn.kernels.backward import on_the_spot
    from pdrlearn.kernels.sideways import SIDE_MIN_STRIDE_M

    length = np.abs(np.asarray(length_m, dtype=float))
    n = len(length)
    label = np.full(n, "forward", dtype=object)
    with np.errstate(invalid="ignore"):
        label[~(length >= SIDE_MIN_STRIDE_M)] = ""  # L219's shuffle on the spot (and a NaN length)
        if turn_angle_rad is not None:  # L203 amended, L692: a turn on the spot (a short chord)
            label[on_the_spot(np.asarray(turn_angle_rad, dtype=float), length)] = "turn"
    side = np.asarray(side, dtype=bool)
    given = np.full(n, None, dtype=object) if given is None else np.asarray(given, dtype=object)
    if lateral_m is not None:  # decision E319: a streamed side step's side, as offline's side_labels
        given = np.where([g in ("left", "right") for g in given], given, side_of(lateral_m)).astype(object)
    label[side] = [g if g in ("left", "right") else "side" for g in given[side]]
    label[np.asarray(back, dtype=bool)] = "backward"
    drop = np.zeros(n, bool)
    if gap_s is not None:
        with np.errstate(invalid="ignore"):
            drop |= np.asarray(gap_s, dtype=float) > 0
    if impossible is not None:
        drop |= np.asarray(impossible, dtype=bool)
    label[drop] = ""
    return label


def row_values(rows: list[dict], key: str) -> list[float]:
    """The float ``key`` of each row dict (NaN where missing or None)."""
    return [math.nan if r.get(key) is None else float(r[key]) for r in rows]


def travel_rows(rows: list[dict]) -> list[str]:
    """Decision E317: :func:`travel_label_array` of a streamed steps table given as row dicts (the lean runtime's
    steps.csv), each row's backward travel from :func:`pdrlearn.kernels.backward.backward_rows` and its side run
    read whole (L243): the ``travel`` column ``pdrlearn run`` writes for the same rows."""
    from pdrlearn.kernels.backward import backward_rows
    from pdrlearn.kernels.sideways import side_rows

    streamed = any("pivot_rad" in r for r in rows)
    side = side_rows([bool(r.get("sideways") or False) for r in rows], row_values(rows, "gap_s"), streamed=streamed)
    turn = row_values(rows, "turn_angle_rad") if any("turn_angle_rad" in r for r in rows) else None
    return travel_label_array(row_values(rows, "length_m"), backward_rows(rows), side, turn,
                              row_values(rows, "gap_s"), [bool(r.get("impossible") or False) for r in rows],
                              lateral_m=row_values(rows, "lateral_m")).tolist()  # decision E319


def classed_backward_lines(direction, sideways, measured, travel, turn_angle_rad=None, confidence=None,
                           trained_side: int | None = None, unjudged=None) -> list[str]:
    """Decisions C137, L578, L652 (:func:`pdrlearn.track.travel.side_class_warning`'s lines, decision E317: also the
    lean runtime's): one line each when the direction model classed backward side-step strides (``sideways``),
    strides turning on the spot (``turn_angle_rad`` and the ``measured`` chord, L692) or strides travelling forward
    (``travel`` forward, ``measured`` > 0; ``travel`` None: a lower-back table). ``direction`` the model's classes,
    ``confidence`` their confidence (None: not known); ``trained_side`` the side-step strides the model was trained
    on (C161; None: its manifest does not say). ``unjudged``: (n,) bool, the rows no travel was judged for (a
    stream's first measured stride, L505 / E318: its positive length is no measured forward travel), left out of
    L652's line."""
    from pdrlearn.kernels.backward import on_the_spot

    direction = np.asarray(direction, dtype=object)
    side = np.asarray(sideways, dtype=bool)
    measured = np.asarray(measured, dtype=float)
    conf = None if confidence is None else np.asarray(confidence, dtype=float)
    if trained_side is None:  # decision C161: a model from before C161 or calibration sessions without kind
        why = ("the direction classes are forward / backward and its manifest does not say whether its calibration "
               "held side steps (retrain to record it), so its class does not apply to them")
    elif trained_side == 0:
        why = ("its calibration walks had no side steps (add a side-stepping walk to the calibration, its side steps "
               "labelled forward, for them to read forward), so its direction class does not apply to them")
    else:
        why = (f"its calibration walks held {trained_side} side-step strides labelled forward, yet it classed these "
               "backward, so its direction class does not apply to them")
    lines = [_classed_backward(direction, conf, side, "side-step strides (steps.csv sideways)",
                               why + "; their length_m is counted positive (side travel, not backward), steps.csv "
                               "direction keeps the model's class and travel says the side", "C137")]
    if turn_angle_rad is not None:  # decision L578
        spot = on_the_spot(np.asarray(turn_angle_rad, dtype=float), measured) & ~side  # L692
        lines.append(_classed_backward(direction, conf, spot, "strides turning on the spot (steps.csv travel turn)",
                                       "a pivot stride's short chord points anywhere, so the class does not say the "
                                       "walker went backward; their length_m is counted positive, steps.csv "
                                       "direction keeps the model's class", "L578"))
    if travel is not None:  # decision L652: a stride measured travelling forward, classed backward
        with np.errstate(invalid="ignore"):
            ahead = (np.asarray(travel, dtype=object) == "forward") & (measured > 0)  # measured ahead
        if unjudged is not None:
            ahead &= ~np.asarray(unjudged, dtype=bool)  # decision E318
        lines.append(_classed_backward(direction, conf, ahead, "strides travelling forward (steps.csv travel forward)",
                                       "their measured displacement points forward (raw_length_m positive, no side "
                                       "step, no turn on the spot), against the class - a stride unlike the "
                                       "calibration's forward strides (e.g. one long stride from standing to "
                                       "standing) can read backward; their length_m is positive (its sign is the "
                                       "measured travel, L654), steps.csv direction keeps the model's class", "L652"))
    return [line for line in lines if line]


def _classed_backward(direction, conf, rows, what: str, why: str, decision: str) -> str | None:
    """Decisions C137 / L578: the line counting the ``rows`` (a kind of stride the direction classes do not cover)
    the model classed backward, with their confidence range; None when there is none."""
    rows = np.asarray(rows, dtype=bool)
    back = rows & (direction == "backward")
    if not back.any():
        return None
    got = np.full(int(back.sum()), np.nan) if conf is None else conf[back]
    seen = f" at confidence {np.nanmin(got):.2f}-{np.nanmax(got):.2f}" if np.isfinite(got).any() else ""
    return (f"{int(back.sum())} of {int(rows.sum())} {what} were classed backward by the model{seen}: {why} - "
            f"count backward steps by travel / backward_travel, not direction (decision {decision})")
