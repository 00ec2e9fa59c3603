"""``track --at-times FILE``: the track's position at given times (decision L638; trial T3 finding F7: an IPIN
competitor is scored at timed waypoints).

A times file is a CSV with one column ``t`` (seconds on the session's clock, from its first sample) or ``time``
(ISO 8601 date-times, which need the session's recording start, L298 / B447). Each time gets the trajectory's
numeric columns at that instant: a row holds until the next step starts, then linear to that step's end (a pause
holds its place); the start pose from the session's first sample up to the first step (the standstill before the
first stride, where the walker stands at the start); the last row from there to the recording's end. A floor (an
integer column, or one named ``floor`` / ``*_floor``) takes the row at or before the time; trajectory.csv's
``z_rides`` and ``floor`` (L630, L631) are computed at the time itself (review R1 F2). A time outside the recording
(with ``--window``, outside the window as tracked: review R1 F4) is one ``error:`` line naming the file, the row and
the span, before any tracking.
"""

from __future__ import annotations

from datetime import datetime
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError

#: decision L638: the columns the times file may give (one of them; decision E332: ``t_s``, read as ``t``)
TIME_COLUMNS = ("t", "t_s", "time")
#: decision L638: trajectory columns that are not a place to interpolate (the times; L623's ride index of a line)
NOT_POSITIONS = ("t", "time", "ride")


def read_times(path: Path) -> pd.DataFrame:
    """The times file read once, before any session (L638): a CSV with a ``t`` or ``time`` column and at least one
    row; ``t`` finite numbers. One line naming the file and the fix otherwise."""
    path = Path(path)
    if not path.is_file():
        raise DataError(f"--at-times {path}: no such file; pass a CSV with a column t (seconds from the session's "
                        "start) or time (ISO 8601 date-times)")
    try:
        table = pd.read_csv(path, dtype=str, keep_default_na=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError, OSError) as exc:
        raise DataError(f"--at-times {path}: cannot read it as a CSV ({type(exc).__name__}); pass a CSV with a "
                        "column t or time") from None
    table.columns = [str(c).strip() for c in table.columns]
    given = [c for c in TIME_COLUMNS if c in table.columns]
    if len(given) != 1 or not len(table):
        raise DataError(f"--at-times {path}: needs exactly one column t or t_s (seconds from the session's start) or "
                        f"time (ISO 8601 date-times) and at least one row; it has columns {', '.join(table.columns)} "
                        f"and {len(table)} row(s)")
    col = given[0]
    if col == "t_s":  # decision E332: the seconds under run's checkpoint name, the same as t
        table, col = table.rename(columns={"t_s": "t"}), "t"
    if col == "t":
        t = pd.to_numeric(table["t"].str.strip(), errors="coerce").to_numpy(float)
        bad = np.flatnonzero(~np.isfinite(t))
        if bad.size:
            raise DataError(f"--at-times {path}: row {int(bad[0]) + 2} t {table['t'].iloc[bad[0]]!r} is not a finite "
                            "number of seconds; fix that row")
    return table[[col]].copy()


def times_argument(text: str) -> tuple[pd.DataFrame, str]:
    """Decision E332: ``run --at-times``'s value read before any replay: a times file (:func:`read_times`), or, when no
    such file exists, a comma list of seconds (``60,125.5,300``). Returns the times table and the words naming it in
    an error line (the file, or the list quoted)."""
    text = str(text).strip()
    items = [x.strip() for x in text.split(",")]
    if Path(text).is_file() or not all(items) or not all(_is_number(x) for x in items):
        if not Path(text).is_file() and "," in text:
            raise DataError(f"--at-times {text!r}: neither a file nor a comma list of seconds (an item "
                            f"{next(x for x in items if not _is_number(x))!r} is no number); give e.g. 60,125.5,300 "
                            "or a CSV with a column t_s")
        return read_times(Path(text)), text
    return pd.DataFrame({"t": items}), f"'{text}'"


def _is_number(text: str) -> bool:
    try:
        return bool(np.isfinite(float(text)))
    except ValueError:
        return False


def check_forward(t, path="--at-times") -> np.ndarray:
    """Decision E332: the times ``t`` (s) in increasing order (equal ones allowed), or one line naming the first
    row before its predecessor (a live track is read forward; ``run --at-times``)."""
    t = np.asarray(t, dtype=float)
    back = np.flatnonzero(np.diff(t) < 0)
    if back.size:
        k = int(back[0]) + 1
        raise DataError(f"--at-times {path}: time {k + 1} ({t[k]:.3f} s) comes before time {k} ({t[k - 1]:.3f} s); "
                        "the live position is read forward in time - sort the times (decision E332)")
    return t


def session_seconds(times: pd.DataFrame, path, start: datetime | None, where: str) -> np.ndarray:
    """The times in session seconds: ``t`` as it is, ``time`` less the recording start (L298); a ``time`` column on
    a session without a start, or a cell that is no ISO 8601 date-time, is one line."""
    if "t" in times:
        return pd.to_numeric(times["t"], errors="coerce").to_numpy(float)
    if start is None:
        from pdrlearn.track.clock import NO_START_FIX

        raise DataError(f"--at-times {path}: its time column needs the recording's clock time, which {where} does "
                        f"not give; give t in seconds instead, or {NO_START_FIX}")
    out = np.empty(len(times))
    for i, text in enumerate(times["time"]):
        try:
            when = datetime.fromisoformat(str(text).strip())
        except ValueError:
            when = None
        if when is None or (when.tzinfo is None) != (start.tzinfo is None):
            raise DataError(f"--at-times {path}: row {i + 2} time {text!r} is not an ISO 8601 date-time "
                            f"{'with a UTC offset ' if start.tzinfo is not None else ''}like the recording start "
                            f"{start.isoformat()}; fix that row")
        out[i] = (when - start).total_seconds()
    return out


def check_span(t, span: tuple[float, float], path="--at-times", what: str = "the recording") -> np.ndarray:
    """The times ``t`` (session s) inside the recording ``span`` (first and last sample, s), or one line naming the
    first row outside it (decision L638; checked before tracking). ``what`` names the span (review R1 F4: a
    ``--window``'s, which is all the track covers)."""
    t = np.asarray(t, dtype=float)
    lo, hi = span
    out_of = np.flatnonzero((t < lo - 1e-9) | (t > hi + 1e-9))
    if out_of.size:
        k = int(out_of[0])
        raise DataError(f"--at-times {path}: row {k + 2} ({t[k]:.3f} s) lies outside {what} ({lo:.3f} to "
                        f"{hi:.3f} s on the session's clock); {out_of.size} time(s) outside - drop them or fix the "
                        "times")
    return t


def positions_at(trajectory: pd.DataFrame, t: np.ndarray, span: tuple[float, float], path="--at-times",
                 step_starts=None) -> pd.DataFrame:
    """The trajectory's numeric columns at session times ``t`` (decision L638, module docstring); ``span`` the
    recording's first and last sample (s). With ``step_starts`` (the steps' ``start_s``, one per trajectory row
    after the first) a row's position holds until the next step starts. A time outside ``span`` is one line naming
    the row."""
    t = check_span(t, span, path)
    tr = trajectory.sort_values("t", kind="stable").reset_index(drop=True)
    rt = tr["t"].to_numpy(float)
    if step_starts is not None and len(step_starts) + 1 == len(tr):  # held until each step starts (a pause, the
        s = np.maximum(np.asarray(step_starts, float), rt[:-1])  # standstill before the first stride: no smear)
        tr = tr.iloc[np.r_[0, np.repeat(np.arange(1, len(tr)), 2)] - np.r_[0, np.tile([1, 0], len(tr) - 1)]]
        tr = tr.reset_index(drop=True)
        rt = np.r_[rt[0], np.ravel(np.c_[s, rt[1:]])]
    out = pd.DataFrame({"t": t})
    for c in tr.columns:
        if c in NOT_POSITIONS or not pd.api.types.is_numeric_dtype(tr[c]) or pd.api.types.is_bool_dtype(tr[c]):
            continue
        v = tr[c].to_numpy(float)
        ok = np.isfinite(v)
        if not ok.any():
            out[c] = np.nan
            continue
        if pd.api.types.is_integer_dtype(tr[c]) or c == "floor" or c.endswith("_floor"):  # a floor: the row before
            idx = np.clip(np.searchsorted(rt[ok], t, side="right") - 1, 0, ok.sum() - 1)
            out[c] = v[ok][idx]
        else:  # np.interp holds the first / last row outside them: the start pose, the last position
            out[c] = np.interp(t, rt[ok], v[ok])
    return out


def live_positions(trajectory: pd.DataFrame, t, start: datetime | None = None, *, returned_s) -> pd.DataFrame:
    """Decision E332, amended by E344: ``run --at-times``' table: per time ``t`` (s, increasing), the streamed
    ``trajectory``'s row the live device had been returned by then - the last row whose stride's push reached
    ``returned_s`` (one per row after the start row, in the rows' order: E288's push time, s) at or before ``t``, the
    start row before that - held, not interpolated; with ``stride_end_s`` (that row's time) and ``returned_s`` (its
    push's time), both empty for the start row; its numeric columns but the times and L623's ride index; ``time``
    (L298's form) with a recording start."""
    from pdrlearn.track.clock import clock_texts

    t = np.asarray(t, dtype=float)
    tr = trajectory.reset_index(drop=True)
    ret = np.asarray(returned_s, dtype=float).ravel()
    if len(ret) != max(len(tr) - 1, 0):
        raise ValueError(f"live_positions: {len(ret)} return time(s) for {len(tr)} trajectory row(s) (one per stride "
                         "row after the start row)")
    shown = np.maximum.accumulate(np.r_[-np.inf, ret])[: len(tr)]  # decision E344: when each row reached the device
    idx = np.clip(np.searchsorted(shown, t + 1e-9, side="right") - 1, 0, max(len(tr) - 1, 0))
    stride = (idx > 0) if len(tr) else np.zeros(len(t), bool)
    rt = tr["t"].to_numpy(float)
    out = pd.DataFrame({"t": t, "stride_end_s": np.where(stride, rt[idx] if len(tr) else np.nan, np.nan),
                        "returned_s": np.where(stride, shown[idx] if len(tr) else np.nan, np.nan)})
    for c in tr.columns:
        if c in NOT_POSITIONS or not pd.api.types.is_numeric_dtype(tr[c]) or pd.api.types.is_bool_dtype(tr[c]):
            continue
        out[c] = tr[c].to_numpy()[idx] if len(tr) else np.nan
    if start is not None:
        out["time"] = clock_texts(start, out["t"])
    return out


def times_in_session(times: pd.DataFrame, path, session, start: datetime | None) -> np.ndarray:
    """Decision L638: the times file's times in session seconds, inside the session's recording, checked before
    tracking (a ``time`` column without a recording start, or a time outside, is one line)."""
    t = session_seconds(times, path, start, str(session.where))
    return check_span(t, (float(session.t_recording_start), float(session.t_end)), path)


def at_times_table(trajectory: pd.DataFrame, t, start: datetime | None, steps: pd.DataFrame | None = None,
                   result=None, storey_height_m: float | None = None) -> pd.DataFrame:
    """OUT/at_times.csv (decision L638): ``t`` (:func:`times_in_session`) in the file's order, the trajectory's
    columns there (held until each of ``steps`` starts), and ``time`` (L298's form) with a recording start. With the
    track's ``result`` and a trajectory with ``z_rides`` / ``floor`` (L630, L631), those two are computed at the times
    themselves (review R1 F2: a ride before the first stride or after the last counts from its end, not the row's)."""
    from pdrlearn.track.clock import clock_texts

    out = positions_at(trajectory, t, (-np.inf, np.inf), step_starts=None if steps is None else steps["start_s"])
    if result is not None and {"z_rides", "floor", "z"} <= set(out.columns):
        from pdrlearn.track.floor_column import floor_at_times

        out["z_rides"], out["floor"] = floor_at_times(trajectory, out["t"], out["z"], result, storey_height_m)
    if start is not None:
        out["time"] = clock_texts(start, out["t"])
    return out
