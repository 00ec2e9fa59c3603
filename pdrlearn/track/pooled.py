"""Decisions E163 / L422: track-all's pooled per-stride table ``strides.csv`` - every tracked session's steps.csv
rows, led by the session (sessions.csv's ``path`` and ``visit``, the session's name, the foot from meta.json) and
each row's turn in degrees and turn membership."""

from __future__ import annotations

import numpy as np
import pandas as pd

#: the columns leading strides.csv, before the session's own steps.csv columns
STRIDE_KEYS = ("path", "visit", "session", "subject", "foot", "turn_deg", "is_turn")  # C100: subject, as bouts.csv
#: decision L422: a row belongs to a turns.csv turn when their overlap is at least this share of the row's own span
#: or of the turn's (a turn inside one long stride; a stride wholly inside a turn)
TURN_OVERLAP_SHARE = 0.5


def turn_membership(start_s, end_s, turns: pd.DataFrame | None) -> np.ndarray:
    """Decision L422: (n,) bool, each row (``start_s``, ``end_s`` s) in one of ``turns`` (turns.csv: the turns of at
    least L200's 80 deg, their spans by the rule of L368-L371 that made them), by :data:`TURN_OVERLAP_SHARE`."""
    a, b = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    out = np.zeros(len(a), dtype=bool)
    if turns is None or not len(turns):
        return out
    for ta, tb in zip(turns["start_s"].to_numpy(float), turns["end_s"].to_numpy(float), strict=True):
        lap = np.clip(np.minimum(b, tb) - np.maximum(a, ta), 0.0, None)
        own = np.maximum(b - a, 0.0)
        out |= (lap > 0) & ((lap >= TURN_OVERLAP_SHARE * own) | (lap >= TURN_OVERLAP_SHARE * max(tb - ta, 0.0)))
    return out


def session_strides(steps: pd.DataFrame, turns: pd.DataFrame | None, *, path: str, visit, session,
                    foot: str | None, subject=None) -> pd.DataFrame:
    """One session's strides.csv rows: :data:`STRIDE_KEYS` then its steps.csv columns. ``turn_deg`` is a foot row's
    ``turn_angle_rad`` in degrees (empty on a lower-back table, which has no per-row turn of its own)."""
    lead = pd.DataFrame({"path": path, "visit": visit, "session": session, "subject": subject, "foot": foot},
                        index=steps.index)
    lead["turn_deg"] = (np.degrees(steps["turn_angle_rad"].to_numpy(float)) if "turn_angle_rad" in steps
                        else np.nan)
    lead["is_turn"] = turn_membership(steps["start_s"], steps["end_s"], turns)
    return pd.concat([lead, steps.drop(columns=[c for c in STRIDE_KEYS if c in steps])], axis=1)
