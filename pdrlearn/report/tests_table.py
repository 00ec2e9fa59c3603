"""Decision W296: the report's table of the clinical tests a track measured - the TUG time and its phases (W183,
W293), the chair transfers (W182) and the turns' durations (L200) - shown for `pdrlearn report`'s tracks
(summary.json) and track-all's sessions (sessions.csv) alike, only with the columns some row has a value in."""

from __future__ import annotations

import pandas as pd

from pdrlearn.track.corridor import KEYS as CORRIDOR_KEYS
from pdrlearn.track.walk_test import KEYS as TEN_M_WALK_KEYS
from pdrlearn.track.walk_test import T25FW_KEYS, TRIAL_KEYS
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


#: decision E152: the walk tests' columns (the corridor test L383, the 10 m walk L312, the T25FW L387), in order
WALK_TEST_COLUMNS = (*CORRIDOR_KEYS, *T25FW_KEYS, *TEN_M_WALK_KEYS, *TRIAL_KEYS)  # L531: trials and walkway (L524)
#: decision E152: the walk-test table's caption
WALK_TEST_CAPTION = ("walk tests: the corridor test (--corridor, laps.csv; per minute from the test's start), the "
                     "timed 25-foot walk and the 10 m walk (ten_m_walk_time_s is over the timed metres of "
                     "ten_m_walk_zones_m: acceleration / timed / deceleration m, L531); a note says why a time is "
                     "missing")
#: decision E152: the columns that make the walk-test table worth showing (a note alone does not)
_WALK_TRIGGER = ("n_laps", "walk_test_distance_m", "t25fw_time_s", "ten_m_walk_time_s")


def present_columns(df: pd.DataFrame, key: str, columns) -> list[str]:
    """``key`` and those of ``columns`` that ``df`` has with at least one value (shared by the report's optional
    tables)."""
    return [key] + [c for c in columns if c in df.columns and df[c].notna().any()]


def _table(df: pd.DataFrame, key: str, columns, trigger, caption: str, *, every_row: bool):
    """``(caption, table)`` of the ``columns`` some row has a value in, for the rows with a value in ``trigger`` (or
    all rows when ``every_row`` and one has); None when no row has one."""
    trigger = [c for c in trigger if c in df.columns]
    if not trigger:
        return None
    has = df[trigger].notna().any(axis=1)
    if not has.any():
        return None
    rows = df if every_row else df[has]
    return caption, rows[present_columns(rows, key, columns)].reset_index(drop=True)


def walk_test_table(df: pd.DataFrame, key: str) -> tuple[str, pd.DataFrame] | None:
    """Decision E152: ``(caption, table)`` of :data:`WALK_TEST_COLUMNS`, one row per track (summaries or
    sessions.csv, named by column ``key``) once a track has a walk-test value; None when none has one. A list
    (``walk_test_distance_per_minute_m``) shows as its values joined by " / "."""
    df = df.copy()
    for col, fmt in (("walk_test_distance_per_minute_m", "{:.1f}"), ("ten_m_walk_zones_m", "{:g}")):  # L531
        if col in df.columns:
            df[col] = [" / ".join(fmt.format(v) for v in x) if isinstance(x, list | tuple) else x for x in df[col]]
    return _table(df, key, WALK_TEST_COLUMNS, _WALK_TRIGGER, WALK_TEST_CAPTION, every_row=True)


def clinical_test_table(df: pd.DataFrame, key: str) -> tuple[str, pd.DataFrame] | None:
    """Decision W296: ``(caption, table)`` of :data:`CLINICAL_TEST_COLUMNS` for the rows of ``df`` (summaries or
    sessions.csv, named by column ``key``) that have a value in one of them; None when no row has a TUG time, a
    phase or a transfer count (a foot-only report shows no such table)."""
    return _table(df, key, CLINICAL_TEST_COLUMNS, _TRIGGER, CLINICAL_TEST_CAPTION, every_row=False)
