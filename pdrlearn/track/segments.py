"""Totals per trip leg (``pdrlearn track DIR --segments LEGS.csv``; decisions L618, L619 in
docs/decisions/localization.md).

LEGS.csv lists a day's legs (from a travel diary or GPS): columns ``start_s`` and ``end_s``, seconds on the session's
clock as ``--window`` takes them (from the session's start), and an optional ``label`` (the mode, a place). The whole
session is tracked once and segments.csv gets one row per leg with periods.csv's totals (decision L277's row
mechanism, :func:`pdrlearn.track.periods.interval_rows`), where ``--window`` re-tracks the session per leg.

Decision L618: a bad LEGS.csv is one ``error:`` line naming the file and the fix before any tracking (the file's own
checks in :func:`read_legs`, once, before any session is read; the legs' extent against the tracked unit's recording
in :func:`check_legs`, before the session is tracked).

Decision L619: each leg is ``[start_s, end_s)`` when the next leg starts at its end (back-to-back legs: an instant
on the edge is counted once, in the later leg, as periods.csv's periods are), else ``[start_s, end_s]`` - so legs equal
to ``--per``'s periods give its totals row for row.

Decision L726: a column other than ``start_s``, ``end_s`` and ``label`` is one ``error:`` line naming it (a user's
``name`` column was dropped and segments.csv's label left empty, silently).

Decision D53: after a ``--common-span`` cut a leg is accounted from the first sample the session holds, as
periods.csv's periods (C185 amended): its ``start_s`` and ``duration_s`` say so, and the cut's seconds stay
``common_span_cut_s``, not "no steps"; a leg wholly before the cut is one ``error:`` line.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError

#: segments.csv's columns, in order (docs/columns.md): the leg's key, then periods.csv's totals after ``partial``
SEGMENT_KEY = ("session", "subject", "visit", "segment", "label", "start_s", "end_s", "duration_s")
#: decision L618: LEGS.csv's columns (decision L726: no other is accepted)
LEGS_COLUMNS = ("start_s", "end_s", "label")
LEGS_USAGE = ("give a CSV with a header start_s,end_s (and optionally label), one leg a row, seconds from the "
              "session's start as --window takes them, sorted and not overlapping, e.g. start_s,end_s,label / "
              "0,600,walk / 600,1500,bus (decision L618)")


def segment_columns() -> tuple[str, ...]:
    """segments.csv's columns: :data:`SEGMENT_KEY`, then :data:`~pdrlearn.track.periods.PERIOD_COLUMNS` after
    ``partial`` (decision L619: the same totals)."""
    from pdrlearn.track.periods import PERIOD_COLUMNS

    return (*SEGMENT_KEY, *PERIOD_COLUMNS[PERIOD_COLUMNS.index("partial") + 1:])


def read_legs(path: Path | str | None) -> pd.DataFrame | None:
    """Decision L618: LEGS.csv as a table (``start_s``, ``end_s`` floats, ``label`` text, empty when not given);
    None for None. One :class:`DataError` line naming the file and the fix for a missing or unreadable file, a
    missing column, an empty table, a value that is not a finite number, a negative start, an end at or before its
    start, and legs out of order or overlapping."""
    if path is None:
        return None
    path = Path(path)
    where = f"--segments {path}"
    if not path.is_file():
        raise DataError(f"{where}: no such file; {LEGS_USAGE}")
    try:
        legs = pd.read_csv(path, dtype={"label": str}, keep_default_na=False, na_values=[""])
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError, ValueError) as e:
        raise DataError(f"{where}: not a readable CSV ({str(e).splitlines()[0] if str(e) else type(e).__name__}); "
                        f"{LEGS_USAGE}") from None
    legs.columns = [str(c).strip() for c in legs.columns]
    missing = [c for c in ("start_s", "end_s") if c not in legs.columns]
    if missing:
        raise DataError(f"{where}: no column {', '.join(missing)} (it has {', '.join(legs.columns) or 'none'}); "
                        f"{LEGS_USAGE}")
    unread = [c for c in legs.columns  # a trailing comma's empty, unnamed column is no column of the user's
              if c not in LEGS_COLUMNS and not (c.startswith("Unnamed:") and legs[c].isna().all())]
    if unread:  # decision L726: a leg's name is `label`; another column was dropped silently before
        fix = ("drop it" if "label" in legs.columns else  # review R2 F6: a label column is there already
               f"a leg's name is the column label - rename {unread[0]} to label, or drop it")
        raise DataError(f"{where}: column {', '.join(unread)} is not read (--segments reads "
                        f"{', '.join(LEGS_COLUMNS)}): {fix} (decision L726); {LEGS_USAGE}")
    if not len(legs):
        raise DataError(f"{where}: no leg (a header alone); {LEGS_USAGE}")
    times = legs[["start_s", "end_s"]].apply(pd.to_numeric, errors="coerce").to_numpy(float)
    bad = np.flatnonzero(~np.isfinite(times).all(axis=1))
    if len(bad):
        k = int(bad[0])
        raise DataError(f"{where}: line {k + 2} has start_s / end_s {str(legs['start_s'].iloc[k])!r}, "
                        f"{str(legs['end_s'].iloc[k])!r}, not two finite numbers; {LEGS_USAGE}")
    start, end = times[:, 0], times[:, 1]
    checks = ((start < 0, "starts before the session's start (0 s)"),
              (end <= start, "ends at or before its start"),
              (np.r_[False, start[1:] < start[:-1]], "starts before the leg above it (sort the legs by start_s)"),
              (np.r_[False, start[1:] < end[:-1]], "starts before the leg above it ends (legs may not overlap)"))
    for mask, what in checks:
        if mask.any():
            k = int(np.flatnonzero(mask)[0])
            raise DataError(f"{where}: line {k + 2}, leg {start[k]:g},{end[k]:g} s {what}; {LEGS_USAGE}")
    labels = legs["label"].fillna("").astype(str).str.strip() if "label" in legs else pd.Series([""] * len(legs))
    return pd.DataFrame({"start_s": start, "end_s": end, "label": labels.to_numpy(object)})


def check_legs(legs: pd.DataFrame, session, unit: str | None, path) -> pd.DataFrame:
    """Decision L618: ``legs`` on the session's own clock (the recording's start + the given seconds, as
    :func:`pdrlearn.track.window.check_window`), before tracking; one :class:`DataError` line naming the file when
    a leg ends after the tracked ``unit``'s recording (B126's span)."""
    from pdrlearn.track.units import unit_span

    t0 = float(session.t_recording_start)  # B81: as --window's seconds count
    span = unit_span(session, unit) if unit is not None else None
    dur = float((span[1] if span is not None else session.t_end) - t0)
    late = np.flatnonzero(legs["end_s"].to_numpy(float) > dur + 1e-6)
    if len(late):
        k = int(late[0])
        whose = f" (the tracked {unit} unit's)" if span is not None else ""
        raise DataError(f"{session.where}: --segments {path}: line {k + 2}, leg {legs['start_s'].iloc[k]:g},"
                        f"{legs['end_s'].iloc[k]:g} s ends after the recording{whose}, which lasts {dur:.2f} s; "
                        f"end it at {dur:.2f} s or earlier, or drop it (decision L618)")
    held = float(session.t_start) - t0  # decision D53: after a --common-span cut, the first second the session holds
    cut = np.flatnonzero(legs["end_s"].to_numpy(float) <= held + 1e-9)
    if len(cut):
        k = int(cut[0])
        raise DataError(f"{session.where}: --segments {path}: line {k + 2}, leg {legs['start_s'].iloc[k]:g},"
                        f"{legs['end_s'].iloc[k]:g} s ends before {held:.2f} s, where --common-span's cut starts the "
                        f"session (its first {held:.2f} s are common_span_cut_s, B267); start it at {held:.2f} s or "
                        "later, or drop it (decision D53)")
    out = legs.copy()
    out["start_s"], out["end_s"] = out["start_s"] + t0, out["end_s"] + t0
    return out


def closed_legs(starts, ends) -> np.ndarray:
    """Decision L619: whether each leg (sorted, not overlapping) holds its end - every leg but one the next leg
    starts at (back-to-back legs share no instant, as periods.csv's periods: the last one closed)."""
    starts, ends = np.asarray(starts, float), np.asarray(ends, float)
    return np.r_[starts[1:] > ends[:-1], True]


def segment_table(result, session, legs: pd.DataFrame, *, unit: str | None, bouts: pd.DataFrame | None,
                  turns: pd.DataFrame | None, storey_height_m: float = 3.0) -> pd.DataFrame:
    """Decision L619: segments.csv of a whole-session track: one row per leg of ``legs`` (:func:`check_legs`'s, on
    the session's clock) with periods.csv's totals (:func:`pdrlearn.track.periods.interval_rows`); a leg holds its
    end unless the next leg starts there (module docstring)."""
    from pdrlearn.track.periods import held_starts, interval_rows

    a, b = legs["start_s"].to_numpy(float), legs["end_s"].to_numpy(float)
    # decision D53: as periods.csv (C185 amended), a leg is accounted from the first sample the session holds, so the
    # seconds a --common-span cut took are not "no steps" (check_legs refused a leg wholly before it)
    held, _ = held_starts(session, a, b)
    rows = interval_rows(result, session, held, b, closed_legs(a, b), unit=unit, bouts=bouts, turns=turns,
                         storey_height_m=storey_height_m)
    for k, (row, label) in enumerate(zip(rows, legs["label"], strict=True)):
        row["segment"], row["label"] = k + 1, label
    return pd.DataFrame(rows, columns=list(segment_columns()))
