"""Each foot stride's travel direction and the changes of it (decision L412, docs/decisions/localization.md).

A turn changes where the body faces (turns.csv, L200); a back-pedal after a forward run, or a side shuffle to the
left after one to the right, changes where the body travels without turning it (trial T3 finding 7: ``turn_count`` 0).
Each stride of a foot track gets steps.csv's ``travel`` label from what the track already decides, relative to the
foot's facing: ``backward`` = :func:`pdrlearn.track.evaluate.backward_travel` (L203, the strides
``n_backward_strides`` counts); ``left`` / ``right`` = a stride of a side-stepping run (L219 / L228's ``sideways``),
to the side its displacement points in the foot's frame (the offline tracker writes it; a streamed table, whose
runs are decided stride by stride, says ``side``); ``turn`` = a stride the foot turned through
:data:`pdrlearn.kernels.backward.BACKWARD_MAX_TURN_DEG` or more on a chord under
:data:`pdrlearn.kernels.backward.SPOT_MAX_CHORD_M` (L203's turn on the spot, L692: a longer turning stride travels
forward or backward of its mid-stride facing); empty = a foot-gap row
(L67), an ``impossible`` stride (L97) or one shorter than :data:`pdrlearn.kernels.sideways.SIDE_MIN_STRIDE_M`
(L219's shuffle on the spot: no direction to read); ``forward`` = every other stride. A change of travel direction is
a labelled stride (forward / backward / left / right / side) whose label differs from the previous labelled
stride's (``turn`` and empty rows skipped). Pure functions of the steps table.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L412: the labels that take part in a change of travel direction
DIRECTIONS = ("forward", "backward", "left", "right", "side")
#: decision L412: direction_changes.csv's columns
CHANGE_COLUMNS = ("change", "start_s", "from_travel", "to_travel", "row")


def side_labels(sideways, lateral_y) -> np.ndarray:
    """Decision L412: (n,) object, ``left`` / ``right`` for the ``sideways`` strides (L228) by the sign of their
    displacement's left component ``lateral_y`` (m, the foot's frame: y left), None elsewhere."""
    side = np.asarray(sideways, bool)
    return np.where(side, np.where(np.asarray(lateral_y, float) > 0, "left", "right"), None).astype(object)


def travel_labels(steps: pd.DataFrame) -> np.ndarray | None:
    """Decision L412: (n,) object, each foot stride's travel label (module docstring); None for a lower-back table
    (:func:`pdrlearn.track.evaluate.backward_travel` None: no facing per step)."""
    from pdrlearn.kernels.backward import on_the_spot
    from pdrlearn.kernels.sideways import SIDE_MIN_STRIDE_M
    from pdrlearn.track.evaluate import backward_travel
    from pdrlearn.track.flags import flag_values
    from pdrlearn.track.gait import sideways_rows

    back = backward_travel(steps)
    if back is None:
        return None
    n = len(steps)
    label = np.full(n, "forward", dtype=object)
    column = "raw_length_m" if "raw_length_m" in steps else "length_m"
    length = np.abs(pd.to_numeric(steps[column], errors="coerce").to_numpy(float))
    with np.errstate(invalid="ignore"):
        label[~(length >= SIDE_MIN_STRIDE_M)] = ""  # L219's shuffle on the spot (and a NaN length)
        if "turn_angle_rad" in steps:  # L203 amended, L692: a turn on the spot (a short chord)
            label[on_the_spot(pd.to_numeric(steps["turn_angle_rad"], errors="coerce"), length)] = "turn"
    side = sideways_rows(steps)
    given = steps["travel"].to_numpy(dtype=object) if "travel" in steps else np.full(n, None, dtype=object)
    label[side] = [g if g in ("left", "right") else "side" for g in given[side]]
    label[back] = "backward"
    drop = np.zeros(n, bool)
    if "gap_s" in steps:
        drop |= pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float) > 0
    if "impossible" in steps:
        drop |= flag_values(steps["impossible"])
    label[drop] = ""
    return label


def add_travel(steps: pd.DataFrame) -> None:
    """Decision L412: a foot table gets steps.csv's ``travel`` (:func:`travel_labels`), right after
    ``backward_travel`` (else at the end). In place; a lower-back table unchanged; idempotent (the offline tracker's
    ``left`` / ``right`` are kept)."""
    label = travel_labels(steps)
    if label is None:
        return
    from pdrlearn.track.table_columns import place_column

    place_column(steps, "travel", label, after=("backward_travel",))


def direction_change_table(steps: pd.DataFrame) -> pd.DataFrame | None:
    """Decision L412: direction_changes.csv (:data:`CHANGE_COLUMNS`): one row per labelled stride whose travel label
    differs from the previous labelled stride's (``row``: its steps.csv row, from 0; ``start_s`` its start); None for
    a lower-back table."""
    label = travel_labels(steps)  # idempotent on a table with add_travel's column
    if label is None:
        return None
    idx = [i for i, v in enumerate(label) if v in DIRECTIONS]
    rows = []
    for a, b in zip(idx, idx[1:], strict=False):
        if label[a] != label[b]:
            rows.append({"change": len(rows) + 1, "start_s": float(steps["start_s"].iloc[b]),
                         "from_travel": label[a], "to_travel": label[b], "row": int(b)})
    return pd.DataFrame(rows, columns=list(CHANGE_COLUMNS))


def travel_line(summary: dict) -> str | None:
    """The console's travel line of a foot track (decisions L412, L484): its backward and side strides with their
    distance (``n_backward_strides``, ``n_side_strides``, ``backward_distance_m``, ``side_distance_m`` of
    ``distance_m``) and its changes of travel direction; None when it has none of them (or is a lower-back track)."""
    back, side, changes = (summary.get(k) or 0 for k in ("n_backward_strides", "n_side_strides", "direction_changes"))
    parts = []
    if back or side:
        parts.append(f"{back} backward and {side} side stride(s) ({summary.get('backward_distance_m') or 0.0:.2f} m "
                     f"backward, {summary.get('side_distance_m') or 0.0:.2f} m sideways of "
                     f"{summary.get('distance_m') or 0.0:.2f} m)")
    if changes:
        parts.append(f"{changes} change(s) of travel direction between forward, backward, left and right strides")
    return "; ".join(parts) + " (steps.csv travel; direction_changes.csv)" if parts else None


def side_class_warning(steps: pd.DataFrame, warnings: list[str], trained_side: int | None = None) -> None:
    """Decision C137: one line when the direction model classed side steps (L219 / L486's ``sideways`` rows)
    backward - its calibration had none (a model classes forward / backward only). Their ``length_m`` keeps no
    negative sign (:func:`pdrlearn.kernels.stride.travel_sign`), ``direction`` keeps the model's class, and
    ``travel`` (left / right / side) says where they went. Decision L578: the same line for the strides of a turn
    on the spot (own turn of ``BACKWARD_MAX_TURN_DEG`` or more, travel = turn) the model classed backward. Appended
    to ``warnings``; nothing without a model. Decision C161: the side-step line says what the model was trained on -
    ``trained_side`` side-step strides (:func:`pdrlearn.classify.uncovered.trained_side_strides`; 0: none, None: its
    manifest does not say). Decision L652: the same line for the strides whose ``travel`` is forward
    (:func:`travel_labels`: measured forward, no side step, no turn on the spot) the model classed backward."""
    if "direction" not in steps:
        return
    from pdrlearn.kernels.backward import on_the_spot
    from pdrlearn.track.flags import flag_values

    side = flag_values(steps["sideways"]) if "sideways" in steps else np.zeros(len(steps), bool)
    if trained_side is None:  # decision C161: a model from before C161 or calibration sessions without kind
        why = ("the direction classes are forward / backward and its manifest does not say whether its calibration "
               "held side steps (retrain to record it), so its class does not apply to them")
    elif trained_side == 0:
        why = ("its calibration walks had no side steps (add a side-stepping walk to the calibration, its side steps "
               "labelled forward, for them to read forward), so its direction class does not apply to them")
    else:
        why = (f"its calibration walks held {trained_side} side-step strides labelled forward, yet it classed these "
               "backward, so its direction class does not apply to them")
    line = _classed_backward(steps, side, "side-step strides (steps.csv sideways)",
                             why + "; their length_m is counted positive (side travel, not backward), steps.csv "
                             "direction keeps the model's class and travel says the side", "C137")
    if line:
        warnings.append(line)
    if "turn_angle_rad" in steps:  # decision L578
        column = next((c for c in ("raw_length_m", "length_m") if c in steps), None)
        chord = np.nan if column is None else pd.to_numeric(steps[column], errors="coerce")  # NaN: not known
        spot = on_the_spot(pd.to_numeric(steps["turn_angle_rad"], errors="coerce"), chord) & ~side  # L692
        line = _classed_backward(steps, spot, "strides turning on the spot (steps.csv travel turn)",
                                 "a pivot stride's short chord points anywhere, so the class does not say the walker "
                                 "went backward; their length_m is counted positive, steps.csv direction keeps the "
                                 "model's class", "L578")
        if line:
            warnings.append(line)
    travel = travel_labels(steps)  # decision L652: a stride measured travelling forward, classed backward
    if travel is not None:
        measured = pd.to_numeric(steps["raw_length_m" if "raw_length_m" in steps else "length_m"], errors="coerce")
        with np.errstate(invalid="ignore"):
            ahead = (travel == "forward") & (measured.to_numpy(float) > 0)  # measured ahead
        line = _classed_backward(steps, ahead, "strides travelling forward (steps.csv travel forward)",
                                 "their measured displacement points forward (raw_length_m positive, no side step, "
                                 "no turn on the spot), against the class - a stride unlike the calibration's "
                                 "forward strides (e.g. one long stride from standing to standing) can read backward; "
                                 "their length_m is positive (its sign is the measured travel, L654), steps.csv "
                                 "direction keeps the model's class", "L652")
        if line:
            warnings.append(line)


def _classed_backward(steps: pd.DataFrame, rows: np.ndarray, what: str, why: str, decision: str) -> str | None:
    """Decisions C137 / L578: the line counting the ``rows`` (a kind of stride the direction classes do not cover)
    the model classed backward, with their confidence range; None when there is none."""
    back = rows & (steps["direction"].to_numpy(dtype=object) == "backward")
    if not back.any():
        return None
    conf = (pd.to_numeric(steps["confidence"], errors="coerce").to_numpy(float)[back] if "confidence" in steps
            else np.full(int(back.sum()), np.nan))
    seen = f" at confidence {np.nanmin(conf):.2f}-{np.nanmax(conf):.2f}" if np.isfinite(conf).any() else ""
    return (f"{int(back.sum())} of {int(rows.sum())} {what} were classed backward by the model{seen}: {why} - "
            f"count backward steps by travel / backward_travel, not direction (decision {decision})")
