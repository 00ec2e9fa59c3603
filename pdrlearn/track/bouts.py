"""The detected walking bouts of a track, one row each (decision L124, docs/decisions/localization.md): what
``track`` writes as ``OUT/bouts.csv`` for the foot and the lower-back pipelines alike.

A bout is L104's walking bout (:mod:`pdrlearn.track.clinical`): the rows of ``steps.csv`` between two pauses,
a pause being a row-to-row interval at least ``break_s`` longer than the walk's median interval (the walker's
own rhythm; a turn across the interval takes its time first, L119). ``break_s`` defaults to L104's
:data:`~pdrlearn.track.clinical.PAUSE_MIN_S` (1 s), so the default table has ``n_walking_bouts`` rows. A bout
with fewer than ``min_strides`` strides is left out of the table (its steps stay in the track's totals);
default 0 (every bout, as L104 counts them). Mobilise-D's walking-bout rules as mobgap 1.2.0 implements them
(``WbAssembly``: ``MaxBreakCriteria(max_break_s=3)``, ``NStridesCriteria(min_strides=4)``; decision W-gait
rules in docs/decisions/waist.md, cited from mobgap's ``wba`` source - no seed paper holds them) are close to
``break_s=3, min_strides=4``: mobgap's break is the time from one stride's end to the next one's start, ours the
interval beyond the walker's rhythm, which is the same standing time when the rhythm's own stance is short.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.track.clinical import PAUSE_MIN_S, TURN_COUNT_MIN_DEG, bout_rows, turn_rows

#: bouts.csv's columns, in order (docs/localization.md)
BOUT_COLUMNS = ("bout", "start_s", "end_s", "duration_s", "n_steps", "n_strides", "distance_m", "speed_m_s",
                "cadence_spm", "n_turns", "altitude_change_m")


@dataclass(frozen=True)
class BoutRule:
    """Decision L124: the walking-bout definition. ``break_s``: a pause of at least this (s, beyond the walk's
    rhythm) ends a bout (L104's 1 s by default); ``min_strides``: a bout needs at least this many strides (0:
    every bout)."""

    break_s: float = PAUSE_MIN_S
    min_strides: int = 0

    def __post_init__(self):
        if not (np.isfinite(self.break_s) and self.break_s > 0):
            raise DataError(f"--bout-break-s {self.break_s:g}: a pause length in s must be a positive number, "
                            f"e.g. {PAUSE_MIN_S:g} (the default) or 3 (Mobilise-D's break)")
        if self.min_strides < 0:
            raise DataError(f"--bout-min-strides {self.min_strides}: give 0 (every bout, the default) or more, "
                            "e.g. 4 (mobgap's Mobilise-D rule)")

    def record(self) -> dict:
        """The definition as summary.json's ``bout_definition``."""
        return asdict(self)


def bout_rule(break_s: float | None = None, min_strides: int | None = None) -> BoutRule:
    """The rule of ``--bout-break-s`` / ``--bout-min-strides`` (None: the default), checked once before any
    tracking (decision L124; ``track``, ``track-all`` and ``run`` read the options with this, decision L130)."""
    return BoutRule(**{k: v for k, v in (("break_s", break_s), ("min_strides", min_strides)) if v is not None})


def _is_foot(steps: pd.DataFrame) -> bool:
    return "unit" in steps and len(steps) > 0 and bool((steps["unit"].astype(str) == "foot").all())


def detected_bouts(steps: pd.DataFrame, rule: BoutRule | None = None) -> pd.DataFrame:
    """One row per detected walking bout of a track's step table (:data:`BOUT_COLUMNS`, module docstring).

    ``n_steps``: steps of both feet, as summary.json's ``n_steps_both_feet`` (decision L103: a foot track's
    2 per stride of the tracked foot, an estimate; a lower-back track's detected steps); ``n_strides``: a foot
    track's strides (rows that are no foot-data gap, L67), a lower-back track's strides from contact k to
    k + 2 as mobgap forms them (its rows are its contacts, the last one a 0 m row: ``n_steps`` - 2);
    ``distance_m``: the rows' summed |length_m| (the track's
    ``distance_m`` sums the same); ``start_s`` / ``end_s``: the first row's start and the last row's end,
    ``duration_s`` their difference; ``speed_m_s`` = distance / duration; ``cadence_spm``: steps per minute between
    the bout's first and last initial contact (``event_s``; 2 steps per stride of a tracked foot, L66; NaN with
    fewer than 2 contacts); ``n_turns``: the track's turns of at least ``turn_count_min_deg`` (L104) whose first turning
    interval ends in the bout (a turn after a pause counts in the bout it starts); ``altitude_change_m``: the
    rows' summed ``dz_m`` (NaN without that column)."""
    rule = rule or BoutRule()
    out = pd.DataFrame(columns=list(BOUT_COLUMNS))
    if not len(steps) or "start_s" not in steps:
        return out
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    foot = _is_foot(st)
    gap = st["gap_s"].to_numpy(float) > 0 if "gap_s" in st else np.zeros(len(st), bool)
    length = st["length_m"].abs().to_numpy(float) if "length_m" in st else np.zeros(len(st))
    ic = st["event_s"].to_numpy(float) if "event_s" in st else st["start_s"].to_numpy(float)
    dz = st["dz_m"].to_numpy(float) if "dz_m" in st else np.full(len(st), np.nan)
    angles, first = turn_rows(st)
    turn_row = first[np.abs(angles) >= TURN_COUNT_MIN_DEG]
    rows = []
    for a, b in bout_rows(st, min_s=rule.break_s):
        n_strides = int((~gap[a:b]).sum()) if foot else max(b - a - 2, 0)
        if n_strides < rule.min_strides:
            continue
        n_steps = 2 * n_strides if foot else b - a
        t0, t1 = float(st["start_s"].iloc[a]), float(st["end_s"].iloc[b - 1])
        dur = t1 - t0
        dist = float(length[a:b].sum())
        c = ic[a:b][np.isfinite(ic[a:b])]
        span = float(c[-1] - c[0]) if len(c) >= 2 else 0.0
        cadence = 60.0 * (2 if foot else 1) * (len(c) - 1) / span if span > 0 else np.nan
        rows.append({"bout": len(rows) + 1, "start_s": t0, "end_s": t1, "duration_s": dur, "n_steps": n_steps,
                     "n_strides": n_strides, "distance_m": dist,
                     "speed_m_s": dist / dur if dur > 0 else np.nan,
                     "cadence_spm": cadence,
                     "n_turns": int(((turn_row >= a) & (turn_row < b)).sum()),
                     "altitude_change_m": float(dz[a:b].sum())})
    return pd.DataFrame(rows, columns=list(BOUT_COLUMNS)) if rows else out


#: a track's walking-bout totals (cohort C25): sessions.csv's columns, summed per subject in subjects.csv
BOUT_TOTALS = ("bouts_distance_m", "bouts_time_s", "bouts_n_steps", "bouts_n_strides")


def bout_totals(table: pd.DataFrame) -> dict:
    """The totals of :func:`detected_bouts`'s ``table`` (cohort C25): ``bouts_distance_m`` (summed ``distance_m``),
    ``bouts_time_s`` (summed ``duration_s``: the walking time in bouts), ``bouts_n_steps`` and ``bouts_n_strides``
    (summed counts); zeros for a track without bouts."""
    return {"bouts_distance_m": float(table["distance_m"].sum()), "bouts_time_s": float(table["duration_s"].sum()),
            "bouts_n_steps": int(table["n_steps"].sum()), "bouts_n_strides": int(table["n_strides"].sum())}


def bouts_summary(steps: pd.DataFrame, rule: BoutRule | None = None, table: pd.DataFrame | None = None) -> dict:
    """summary.json's keys (decision L124): ``n_bouts`` (the rows :func:`detected_bouts` gives) and
    ``bout_definition``. ``table``: :func:`detected_bouts`'s table of ``steps`` under ``rule`` when the caller has
    it already (``track`` and ``run`` write it as bouts.csv; decision E73: the bouts are detected once)."""
    rule = rule or BoutRule()
    if table is None:
        table = detected_bouts(steps, rule)
    return {"n_bouts": int(len(table)), "bout_definition": rule.record()}
