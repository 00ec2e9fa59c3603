"""Steps per turn on a foot track (decision L749, docs/decisions/localization.md).

A foot track's turns.csv rows sum one foot's strides (``n_rows``), about half the steps of a turn. W398 counts the
clinical steps per turn on the lower back (its contacts inside the turn); L749 gives a foot track the same number:
with a lower-back unit (W418's ``info["trunk_contacts"]`` / ``info["trunk_yaw_turns"]``) the waist's contacts inside
the turn - its span widened to the waist's own yaw-rate turn (L210's match), as the waist pipeline times it - and
with a foot alone an estimate, 2 x the foot's strides whose contact lies inside the turn (W419's count), marked
``foot_x2`` in ``turn_steps_source``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L749: turns.csv ``turn_steps_source`` - the lower back's contacts / the foot's strides x 2 (estimate)
WAIST, FOOT_X2 = "waist", "foot_x2"


def contacts_in(event_s, spans: np.ndarray) -> np.ndarray:
    """W398's count: the contacts ``event_s`` inside each ``[start, end]`` row of ``spans`` (n x 2, s); 0 for a span
    with a non-finite end."""
    ev = np.sort(np.asarray(event_s, dtype=float))
    ev = ev[np.isfinite(ev)]
    a, b = spans[:, 0], spans[:, 1]
    counts = np.searchsorted(ev, b, side="right") - np.searchsorted(ev, a, side="left")
    return np.where(np.isfinite(a) & np.isfinite(b), counts, 0).astype(int)


def waist_spans(turns: pd.DataFrame, yaw_turns) -> np.ndarray:
    """Decision L749: each foot turn's span (``start_s``, ``end_s``) widened to the lower back's yaw-rate turn that
    L210's match (:func:`~pdrlearn.track.clinical.yaw_turn_match`: its peak inside the span, the same sign) gives it:
    the waist pipeline's turn times, which hold the first and the closing step the foot's 5-95 % heading times cut."""
    from pdrlearn.track.clinical import yaw_turn_times

    spans = turns[["start_s", "end_s"]].to_numpy(float).copy()
    yaw = pd.DataFrame(list(yaw_turns or []))
    if not len(yaw) or not {"peak_s", "angle_deg", "start_s", "end_s"} <= set(yaw):
        return spans
    for i, ang in enumerate(turns["angle_deg"].to_numpy(float)):
        lo, hi = spans[i]
        times = yaw_turn_times(lo, hi, ang, yaw) if np.isfinite(lo) and np.isfinite(hi) and ang else None
        if times is not None:
            spans[i] = (min(lo, times[0]), max(hi, times[1]))
    return spans


def foot_turn_steps(turns: pd.DataFrame, steps: pd.DataFrame, info: dict | None, *,
                    foot_estimate: bool = True) -> tuple[np.ndarray | None, str]:
    """Decision L749: a foot track's steps per turn and their source - the lower back's contacts
    (``info["trunk_contacts"]``) inside :func:`waist_spans` (``"waist"``), else 2 x the foot's strides whose
    contact (``event_s``) lies inside the turn (``"foot_x2"``, an estimate: the other foot is assumed to
    alternate; ``foot_estimate`` False leaves it empty, L749's alternative, a keyword: W413); ``(None, "")``
    without either (a foot table without contact times: ``pdrlearn run``'s)."""
    info = info or {}
    trunk = info.get("trunk_contacts")
    if trunk:
        rows = pd.DataFrame(list(trunk))
        col = "event_s" if "event_s" in rows else "start_s"
        return contacts_in(rows[col], waist_spans(turns, info.get("trunk_yaw_turns"))), WAIST
    if not foot_estimate or "event_s" not in steps or (len(steps) and not np.isfinite(
            steps["event_s"].to_numpy(float)).any()):
        return None, ""  # no contact times (pdrlearn run's foot strides): no count rather than a guessed one
    return 2 * contacts_in(steps["event_s"], turns[["start_s", "end_s"]].to_numpy(float)), FOOT_X2
