"""Decision W296: the report's table of the clinical tests a track measured - the TUG time and its phases (W183,
W293), the chair transfers (W182) and the turns' durations (L200) - shown for `pdrlearn report`'s tracks
(summary.json) and track-all's sessions (sessions.csv) alike, only with the columns some row has a value in."""

from __future__ import annotations

import pandas as pd

from pdrlearn.waist.tug_phases import TUG_PHASE_KEYS

#: decision W296: the columns, in order (the first, the row's name, is given by the caller)
CLINICAL_TEST_COLUMNS = ("tug_time_s", *TUG_PHASE_KEYS, "n_tug_trials", "tug_trials_median_s",  # W325
                         "n_sit_to_stand", "n_stand_to_sit", "median_sit_to_stand_s",
                         "median_stand_to_sit_s", "n_lie_down", "n_get_up", "turn_count", "median_turn_duration_s",
                         "turn_time_s")
#: decision W296: the table's caption
CLINICAL_TEST_CAPTION = ("TUG, its phases (tug_phases.csv), TUG trials (tug_trials.csv), chair transfers "
                         "(transfers.csv) and turns (turns.csv); an empty cell: not measured")
#: decision W296: the columns that make the table worth showing (turns alone are in the gait table's turn_count)
_TRIGGER = ("tug_time_s", *TUG_PHASE_KEYS, "n_sit_to_stand", "n_stand_to_sit", "n_lie_down", "n_get_up")


def present_columns(df: pd.DataFrame, key: str, columns) -> list[str]:
    """``key`` and those of ``columns`` that ``df`` has with at least one value (shared by the report's optional
    tables)."""
    return [key] + [c for c in columns if c in df.columns and df[c].notna().any()]


def clinical_test_table(df: pd.DataFrame, key: str) -> tuple[str, pd.DataFrame] | None:
    """Decision W296: ``(caption, table)`` of :data:`CLINICAL_TEST_COLUMNS` for the rows of ``df`` (summaries or
    sessions.csv, named by column ``key``) that have a value in one of them; None when no row has a TUG time, a
    phase or a transfer count (a foot-only report shows no such table)."""
    trigger = [c for c in _TRIGGER if c in df.columns]
    if not trigger:
        return None
    rows = df[df[trigger].notna().any(axis=1)]
    if not len(rows):
        return None
    return CLINICAL_TEST_CAPTION, rows[present_columns(rows, key, CLINICAL_TEST_COLUMNS)].reset_index(drop=True)
