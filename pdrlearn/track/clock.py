"""Wall-clock times of a session's events (decisions L298, L299, B254, B255; docs/decisions/localization.md).

Decision L298: a session's *recording start* is the clock time of its 0 s, read from its meta.json, first found of

1. ``recording_start``: an ISO 8601 date-time written by hand (``"2026-12-05T02:13:00+01:00"``; without an offset it
   is kept without one: a clock time as recorded, no zone made up);
2. ``imported``: ``pdrlearn import`` of a date-time column (decision B43): its ``time.origin_s`` (the export's time
   that became 0 s, s since the epoch) at the offset of its first date-time (``time.datetime.offset``; UTC when the
   text had none and no ``--time-zone`` was given). Numeric clocks and times of day without a date (B86) give none;
3. ``start_datetime``: the Mobilise-D converter's ISO start (``pdrlearn.io.external.mobgap``).

The simulator writes none. With a start, each event table's ``*_s`` instants (``start_s``, ``end_s``, ``peak_s``)
get ISO 8601 clock columns (``start_time``, ``end_time``, ``peak_time``) at the start's own offset (never the
machine's local zone; an offset change inside the recording, a DST night, is not followed: the instants are right,
shown at the start's offset), and summary.json ``recording_start``.
"""

from __future__ import annotations

import dataclasses
import math
import re
from datetime import UTC, datetime, timedelta, timezone

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError

#: ``track --per-align``: periods from the recording's start (the default), at the clock's whole periods (L299) or
#: from the first tracked step (L381: a walk test's minutes from "go")
PER_ALIGNS = ("start", "clock", "first-step")
#: meta.json's key for a recording start written by hand (decision L298)
START_KEY = "recording_start"
#: decision B447: the import's time units (``imported.time.unit``) whose numbers count from the Unix epoch when the
#: origin is at least B39's ``EPOCH_START`` (1e9 s, 2001-09-09): seconds, ms, us, ns - not sample numbers
EPOCH_UNITS = ("s", "ms", "us", "ns")
#: an event table's instant columns (s on the session's clock) -> their clock columns (decision L298)
CLOCK_COLUMNS = {"start_s": "start_time", "end_s": "end_time", "peak_s": "peak_time"}
#: what to do when a clock option meets a session without a start (decision B254)
NO_START_FIX = (f"import it from a date-time export with `pdrlearn import` (which keeps the first time), or write "
                f"\"{START_KEY}\": \"2026-12-05T02:13:00+01:00\" (the clock time of its 0 s) in its meta.json")


def _parse_iso(text: str) -> datetime | None:
    try:
        return datetime.fromisoformat(str(text).strip())
    except ValueError:
        return None


def _offset(text: str | None):
    """``"+01:00"`` -> a fixed :class:`timezone`; None for None or anything else."""
    m = re.fullmatch(r"([+-])(\d{2}):?(\d{2})", str(text or "").strip())
    if not m:
        return None
    d = timedelta(hours=int(m.group(2)), minutes=int(m.group(3)))
    return timezone(-d if m.group(1) == "-" else d)


#: decision E173: ``steps --time-origin``: --out times from the session's first sample, or on the export's clock
TIME_ORIGINS = ("session", "export")
#: decision E173: the instant columns (s on the session's clock) ``steps --time-origin export`` moves onto the
#: export's clock (plasys.DEFAULT_TIME_COLUMNS and the detections' ``event_s``)
INSTANT_COLUMNS = ("start_s", "end_s", "event_s", "ic_s", "tc_s", "pre_ic_s", "fc_s", "cycle_start_s")


def export_origin_s(meta: dict | None) -> float | None:
    """Decision E173: the time on the export's clock (s, in the unit the import read, e.g. 12.345 or s since the
    epoch) of the session's 0 s: ``meta.json`` ``imported.time.origin_s`` of ``pdrlearn import`` (a ``--merge``: the
    first import's, which the second shares); None for a session not imported."""
    imported = (meta or {}).get("imported") if isinstance(meta, dict) else None
    first = imported[0] if isinstance(imported, list) and imported else imported
    t = first.get("time") if isinstance(first, dict) else None
    v = t.get("origin_s") if isinstance(t, dict) else None
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) else None


def on_export_clock(table: pd.DataFrame, origin_s: float, columns: tuple[str, ...] = INSTANT_COLUMNS) -> pd.DataFrame:
    """Decision E173: ``table`` with its ``columns`` (default :data:`INSTANT_COLUMNS`) plus ``origin_s`` (the export's
    clock)."""
    out = table.copy()
    for c in columns:
        if c in out.columns:
            out[c] = (pd.to_numeric(out[c], errors="coerce") + origin_s).round(9)  # no float noise in the CSV
    return out


def _epoch_start() -> float:
    from pdrlearn.io.validate import EPOCH_START  # B39's threshold: a clock since the epoch

    return EPOCH_START


def recording_start(meta: dict | None, where: str = "meta.json") -> datetime | None:
    """Decision L298: the clock time of the session's 0 s from its ``meta`` (module docstring), or None. A
    ``recording_start`` that is not an ISO 8601 date-time is one :class:`DataError` line (decision B254); a JSON
    ``null`` (an exporter's "unknown") is read as absent (decision B258)."""
    meta = meta if isinstance(meta, dict) else {}
    if meta.get(START_KEY) is not None:  # decision B258: "recording_start": null is no start, not a bad one
        got = _parse_iso(meta[START_KEY]) if isinstance(meta[START_KEY], str) else None
        if got is None:
            key = f"{where} {START_KEY}" if str(where).endswith("meta.json") else f"{where}: meta.json {START_KEY}"
            raise DataError(f"{key} {meta[START_KEY]!r} is not an ISO 8601 date-time; write "
                            f"e.g. \"{START_KEY}\": \"2026-12-05T02:13:00+01:00\" (decision B254)")
        return got
    imported = meta.get("imported")
    first = imported[0] if isinstance(imported, list) and imported else imported  # a --merge: the first import's
    t = first.get("time") if isinstance(first, dict) else None
    dt = t.get("datetime") if isinstance(t, dict) else None
    if isinstance(dt, dict) and not dt.get("time_of_day") and isinstance(t.get("origin_s"), int | float) \
            and math.isfinite(t["origin_s"]):
        start = datetime.fromtimestamp(float(t["origin_s"]), tz=UTC)
        zone = _offset(dt.get("offset"))
        return start.astimezone(zone) if zone is not None else start
    if isinstance(t, dict) and t.get("unit") in EPOCH_UNITS and isinstance(t.get("origin_s"), int | float) \
            and not isinstance(t.get("origin_s"), bool) and math.isfinite(t["origin_s"]) \
            and t["origin_s"] >= _epoch_start():  # decision B447: an epoch-number time column's first time, UTC
        return datetime.fromtimestamp(float(t["origin_s"]), tz=UTC)
    text = meta.get("start_datetime")  # the Mobilise-D converter's
    return _parse_iso(text) if isinstance(text, str) and text.strip() else None


def require_start(meta: dict | None, where: str, option: str) -> datetime:
    """The recording start, or one :class:`DataError` line naming ``option`` and the fix (decision B254)."""
    start = recording_start(meta, where)
    if start is None:
        raise DataError(f"{where}: {option} needs the recording's clock time, which the session does not give "
                        f"(no meta.json {START_KEY}, no date-time import); {NO_START_FIX} (decision B254)")
    return start


def clock_texts(start: datetime, seconds) -> list[str | None]:
    """ISO 8601 texts (milliseconds, the start's own offset) of session times ``seconds``; None where missing, and
    (decision B296) where the time falls after 9999-12-31, which no ISO 8601 / Python date holds."""
    out = []
    for s in np.asarray(pd.to_numeric(pd.Series(seconds), errors="coerce"), dtype=float):
        try:
            out.append((start + timedelta(seconds=float(s))).isoformat(timespec="milliseconds")
                       if math.isfinite(s) else None)
        except OverflowError:
            out.append(None)
    return out


def with_clock_columns(table: pd.DataFrame, start: datetime | None) -> pd.DataFrame:
    """Decision L298: ``table`` with a clock column for each of its :data:`CLOCK_COLUMNS` instants, appended after
    its columns (bouts.csv's deprecated ``speed_m_s`` stays last, E98); ``table`` itself without a start."""
    if start is None or table is None:
        return table
    out = table.copy()
    last = [c for c in ("speed_m_s",) if c in out]
    for col, name in CLOCK_COLUMNS.items():
        if col in out and name not in out:
            out[name] = pd.Series(clock_texts(start, out[col]), index=out.index, dtype=object)
    return out[[c for c in out.columns if c not in last] + last]


def seconds_of_day(start: datetime) -> float:
    """The start's time of day (s since its own midnight, at its own offset)."""
    return start.hour * 3600.0 + start.minute * 60.0 + start.second + start.microsecond / 1e6


def clock_edges(t0: float, t1: float, per_s: float, start: datetime) -> np.ndarray:
    """Decision L299: period starts on the session's clock for ``--per-align clock``: ``t0`` and every instant in
    ``(t0, t1)`` whose clock time is a whole multiple of ``per_s`` since midnight (1h: the clock hours)."""
    s0 = seconds_of_day(start)  # clock time of day at the session's 0 s
    k = math.floor((t0 + s0) / per_s + 1e-9) + 1
    inner = np.arange(k * per_s - s0, t1, per_s)
    return np.r_[t0, inner[inner > t0 + 1e-9]]


@dataclasses.dataclass(frozen=True)
class ClockWindow:
    """``--window`` given as clock times (decision L299): two times of day (``02:10``, ``02:10:30``) or two ISO
    8601 date-times, resolved per session by :func:`window_seconds`."""

    text: str
    start: str
    end: str


_TIME_OF_DAY = re.compile(r"(\d{1,2}):(\d{2})(?::(\d{2}(?:\.\d+)?))?")


def _instant(text: str, after: datetime, start: datetime, window: str, where: str) -> datetime:
    """The clock time ``text`` (a time of day: its first occurrence at or after ``after``; or an ISO date-time)."""
    m = _TIME_OF_DAY.fullmatch(text)
    if m:
        h, mi, s = int(m.group(1)), int(m.group(2)), float(m.group(3) or 0)
        if h > 23 or mi > 59 or s >= 60:
            raise DataError(f"--window {window!r}: {text!r} is not a time of day (HH:MM or HH:MM:SS)")
        day = after.replace(hour=0, minute=0, second=0, microsecond=0)
        got = day + timedelta(hours=h, minutes=mi, seconds=s)
        return got if got >= after else got + timedelta(days=1)
    got = _parse_iso(text)
    if got is None:
        raise DataError(f"--window {window!r}: {text!r} is neither seconds, a time of day (02:10) nor an ISO 8601 "
                        "date-time (2026-12-05T02:10:00+00:00)")
    if (got.tzinfo is None) != (start.tzinfo is None):
        if start.tzinfo is None:  # decision B255: an offset cannot be compared with a start written without one
            raise DataError(f"{where}: --window {window!r} gives an offset, but the recording's start "
                            f"({start.isoformat()}) has none; give the times without an offset (decision B255)")
        got = got.replace(tzinfo=start.tzinfo)  # the recording's own offset, as a time of day is read
    return got


def no_start_window_line(window: ClockWindow, where: str) -> str | None:
    """Decision B291: the line for a clock ``window`` of two times of day on a session without a recording start -
    read as clock times (L299), with the seconds it gives read as minutes:seconds (``0:00,6:00`` -> ``0,360``;
    ``H:MM:SS`` as hours:minutes:seconds), the walk-test reading; None when a part is no time of day (ISO)."""
    secs = []
    for part in (window.start, window.end):
        m = _TIME_OF_DAY.fullmatch(part)
        if m is None:
            return None
        a, b, c = m.group(1), m.group(2), m.group(3)
        secs.append(int(a) * 3600 + int(b) * 60 + float(c) if c is not None else int(a) * 60 + int(b))
    return (f"{where}: --window {window.text} needs the recording's clock time, which the session does not give "
            f"(no meta.json {START_KEY}, no date-time import): it reads as two clock times of day (decision L299); for "
            f"a part of the walk counted from the session's start give seconds: --window {secs[0]:g},{secs[1]:g} (the "
            f"times read as minutes:seconds; decision B291); for clock times, {NO_START_FIX} (decision B254)")


def parse_clock_window(text: str) -> ClockWindow | None:
    """``"02:10,02:20"`` / ``"ISO,ISO"`` -> a :class:`ClockWindow`; None when the text gives no clock time (a
    ``:`` in neither part: seconds, :func:`pdrlearn.track.window.parse_window`'s)."""
    parts = [p.strip() for p in str(text).split(",")]
    if not any(":" in p for p in parts):
        return None
    if len(parts) != 2 or not all(":" in p for p in parts):
        raise DataError(f"--window {text!r}: give two clock times START,END (02:10,02:20 or two ISO 8601 "
                        "date-times) or two numbers of seconds, not a mix")
    return ClockWindow(str(text), parts[0], parts[1])


def window_seconds(window: ClockWindow, start: datetime, duration_s: float, t_rec: float,
                   where: str) -> tuple[float, float]:
    """Decision L299: a clock ``window`` as seconds from the recording's start (``t_rec`` on the session's clock,
    ``duration_s`` long): a time of day is its first occurrence at or after the recording's start (END: after
    START, so ``23:50,00:10`` crosses midnight). Decision B255: a START outside the recording is one line giving the
    recording's clock span."""
    rec0 = start + timedelta(seconds=t_rec)
    a = _instant(window.start, rec0, start, window.text, where)
    b = _instant(window.end, a, start, window.text, where)
    sa, sb = (a - rec0).total_seconds(), (b - rec0).total_seconds()
    rec1 = rec0 + timedelta(seconds=duration_s)
    if sa < 0 or sa >= duration_s:
        raise DataError(f"{where}: --window {window.text} starts at {a.isoformat(timespec='seconds')}, outside the "
                        f"recording ({rec0.isoformat(timespec='seconds')} to {rec1.isoformat(timespec='seconds')}); "
                        "give clock times inside it (decision B255)")
    if sb <= sa:
        raise DataError(f"--window {window.text!r}: END must be later than START; give START,END (decision B255)")
    if _TIME_OF_DAY.fullmatch(window.end) and b.date() > a.date() and sb > duration_s:
        # decision B259: a time-of-day END read on the next day AND past the recording's end is a reversed window
        raise DataError(f"{where}: --window {window.text} ends at {b.isoformat(timespec='seconds')}, after midnight "
                        f"and after the recording's end ({rec1.isoformat(timespec='seconds')}): END before START? "
                        "a time-of-day window (23:50,00:10) crosses midnight only inside the recording; give "
                        "START,END in order (decisions B255, B259)")
    return sa, sb
