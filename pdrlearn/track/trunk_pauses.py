"""Decision L687: a foot + lower-back track's pauses, judged against the walker's stride the lower back sees.

One foot unit cannot tell a rest from a slow stride: on a step-to stair with a rest on each stair the other foot
steps up, then both stand, and all of it lies inside the tracked foot's stride. The lower back sees both feet, so
a two-unit track (W418's ``info["trunk_contacts"]``, the waist-pendulum pipeline's walking contacts) judges each foot
row's interval against the walker's stride - two of the lower back's median contact intervals, one step of each foot,
or L500's movement window of the foot when shorter - not against L605's slow-foot rhythm, and marks the excess of a
pause (steps.csv ``trunk_pause_s``); L104's pause rule reads that column on such a table, and a stride holding a
pause is left out of the summary's median stride time and cadence (a stride time across a stop is no rhythm, as
L80's cap says for longer ones). Lower-back contacts too dense to be steps (L605's 2.5 s-step walker) leave the
foot's own rule.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L687: steps.csv's column of a two-unit foot track (s of lower-back pause inside each foot stride)
COLUMN = "trunk_pause_s"


#: decision L687 (second rule): the lower back's stride is used only when it is at least this share of the foot's
#: 10th-percentile stride time (shorter: it counts spurious contacts, as on L605's 2.5 s-step walker, 0.3 s apart)
MIN_STRIDE_SHARE = 0.5


def trunk_pause_seconds(steps: pd.DataFrame, trunk_contacts_s, *,
                        min_share: float = MIN_STRIDE_SHARE) -> np.ndarray | None:
    """(N,) for each row of the foot table ``steps`` (rows in time order) the excess (s) of the interval from the
    previous row's ``start_s`` over the walker's stride when at least L104's ``PAUSE_MIN_S``, else 0; the stride is
    the lower back's (two of its median contact intervals ``trunk_contacts_s``, one step of each foot) or, when
    shorter, L500's median movement window of the foot (the lower back's median grows where it misses contacts, as
    on stairs). None (the foot's own rule stays) with fewer than 3 lower-back contacts or 2 foot rows, without a
    stride time, or when the lower back's stride is under ``min_share`` (:data:`MIN_STRIDE_SHARE`) of the foot's
    10th-percentile stride time (decision L766's 0.75, not adopted, is this option)."""
    from pdrlearn.track.clinical import PAUSE_MIN_S, movement_windows

    w = np.sort(np.asarray(trunk_contacts_s, dtype=float))
    w = w[np.isfinite(w)]
    st = pd.to_numeric(steps["stride_time_s"], errors="coerce").to_numpy(float) if "stride_time_s" in steps \
        else np.zeros(0)
    st = st[np.isfinite(st)]
    if len(steps) < 2 or len(w) < 3 or not len(st):
        return None
    stride = 2.0 * float(np.median(np.diff(w)))
    if stride < min_share * float(np.percentile(st, 10)):
        return None
    window = movement_windows(steps)
    if window.size:
        stride = min(stride, float(np.median(window)))
    out = np.zeros(len(steps))
    with np.errstate(invalid="ignore"):
        excess = np.diff(steps["start_s"].to_numpy(float)) - stride
        out[1:] = np.where(np.nan_to_num(excess) >= PAUSE_MIN_S, excess, 0.0)
    return out


def add_trunk_pauses(result) -> None:
    """Decision L687: a two-unit foot track ``result`` (``info["trunk_contacts"]`` set, a foot table in time order)
    gets steps.csv's :data:`COLUMN` (:func:`trunk_pause_seconds`); nothing otherwise."""
    from pdrlearn.track.clinical import is_foot_table

    steps, rows = result.steps, result.info.get("trunk_contacts")
    if rows is None or not is_foot_table(steps) or COLUMN in steps or not steps["start_s"].is_monotonic_increasing:
        return
    contacts = pd.DataFrame(rows, columns=["start_s", "end_s", "event_s"])["start_s"].to_numpy(float)
    pause = trunk_pause_seconds(steps, contacts)
    if pause is None:  # the lower back's contacts cannot judge the foot's rests: the foot's own rule stays
        return
    at = steps.columns.get_loc("gap_s") if "gap_s" in steps else len(steps.columns)
    steps.insert(at, COLUMN, pause)


def stop_rows(steps: pd.DataFrame) -> np.ndarray:
    """Decision L687: (N,) bool, the rows of a foot table whose stride holds a lower-back pause of at least L104's
    ``PAUSE_MIN_S`` (:data:`COLUMN`): their stride time spans a stop, so the summary's median stride time, cadence
    and speed leave them out (steps.csv keeps the measured stride time); all False without the column."""
    from pdrlearn.track.clinical import PAUSE_MIN_S

    if COLUMN not in steps:
        return np.zeros(len(steps), bool)
    return np.nan_to_num(pd.to_numeric(steps[COLUMN], errors="coerce").to_numpy(float)) >= PAUSE_MIN_S


def trunk_pauses(st: pd.DataFrame) -> np.ndarray | None:
    """Decision L687: (N,) :data:`COLUMN` of a foot table in ``start_s`` order (NaN read as 0), None without it."""
    from pdrlearn.track.clinical import is_foot_table

    if COLUMN not in st or not is_foot_table(st):
        return None
    return np.nan_to_num(pd.to_numeric(st[COLUMN], errors="coerce").to_numpy(float))
