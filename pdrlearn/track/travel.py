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
    displacement's left component ``lateral_y`` (m, the foot's frame: y left; :func:`side_of`, review R2 F6: 0 or NaN
    none), None elsewhere."""
    from pdrlearn.kernels.travel import side_of

    return np.where(np.asarray(sideways, bool), side_of(lateral_y), None).astype(object)


def travel_labels(steps: pd.DataFrame) -> np.ndarray | None:
    """Decision L412: (n,) object, each foot stride's travel label (module docstring); None for a lower-back table
    (:func:`pdrlearn.track.evaluate.backward_travel` None: no facing per step)."""
    from pdrlearn.kernels.travel import travel_label_array
    from pdrlearn.track.evaluate import backward_travel
    from pdrlearn.track.flags import flag_values
    from pdrlearn.track.gait import sideways_rows

    back = backward_travel(steps)
    if back is None:
        return None
    column = "raw_length_m" if "raw_length_m" in steps else "length_m"
    # decision E317: the kernel the lean runtime's steps.csv labels its rows with
    return travel_label_array(
        pd.to_numeric(steps[column], errors="coerce").to_numpy(float), back, sideways_rows(steps),
        pd.to_numeric(steps["turn_angle_rad"], errors="coerce").to_numpy(float) if "turn_angle_rad" in steps else None,
        pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float) if "gap_s" in steps else None,
        flag_values(steps["impossible"]) if "impossible" in steps else None,
        steps["travel"].to_numpy(dtype=object) if "travel" in steps else None,
        pd.to_numeric(steps["lateral_m"], errors="coerce").to_numpy(float) if "lateral_m" in steps else None)  # E319


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
    from pdrlearn.kernels.backward import first_unjudged
    from pdrlearn.kernels.travel import classed_backward_lines
    from pdrlearn.track.flags import flag_values

    column = next((c for c in ("raw_length_m", "length_m") if c in steps), None)
    measured = np.full(len(steps), np.nan) if column is None else pd.to_numeric(steps[column], errors="coerce")
    warnings.extend(classed_backward_lines(  # decision E317: the kernel the lean runtime says them with
        steps["direction"].to_numpy(dtype=object),
        flag_values(steps["sideways"]) if "sideways" in steps else np.zeros(len(steps), bool),
        np.asarray(measured, dtype=float),
        travel_labels(steps),
        pd.to_numeric(steps["turn_angle_rad"], errors="coerce").to_numpy(float) if "turn_angle_rad" in steps else None,
        pd.to_numeric(steps["confidence"], errors="coerce").to_numpy(float) if "confidence" in steps else None,
        trained_side,
        first_unjudged(len(steps), steps["gap_s"].to_numpy(float) if "gap_s" in steps else None,
                       "pivot_rad" in steps)))  # decision E318: a stream's first stride (L505)
