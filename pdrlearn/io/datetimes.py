"""Date-time columns of a lab export read exactly (decision B341) and local times around a daylight-saving change
(decision B342): the kernels behind :func:`pdrlearn.io.importer._datetime_seconds`."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError

_NS = 10**9
#: decision B342: a jump of the wall clock by one hour is a daylight-saving change (every zone that has one moves by
#: an hour, except Lord Howe's half hour), read as such when it lies within this many sample periods of the
#: interval the recording had (the next sample one period after the last in real time; a sample lost beside it)
DST_TOLERANCE_PERIODS = 2.0
DST_SHIFT_S = 3600.0


def exact_seconds(dt: pd.Series) -> tuple[np.ndarray, float]:
    """Decision B341: (seconds since ``base``, ``base``) of tz-aware date-times, ``base`` the whole second (s since
    the epoch, exact in float64) at or before the first one. The differences are taken in integer nanoseconds, so
    ``…11,250`` is 0.25 s and 10 s later 10.25 s exactly: as float epoch seconds (1.8e9 s, float64 steps of
    0.24 us) the times carried noise (9.9999904629999996 for 10) that moved a step and split a walking bout."""
    ns = (dt.dt.tz_convert("UTC") - pd.Timestamp(0, tz="UTC")).to_numpy(dtype="timedelta64[ns]")
    nat = np.isnat(ns)
    ints = ns.astype(np.int64)
    first = int(ints[~nat][0]) if (~nat).any() else 0
    base = first - first % _NS  # floor, also before 1970
    secs = (ints - base) / 1e9  # exact integers up to 2**53 ns (104 days) before the one rounding
    secs[nat] = np.nan
    return secs, base / 1e9


def offset_text(ts: pd.Timestamp) -> str:
    """``+01:00`` of a tz-aware time (decision L298's form)."""
    mins = int(ts.utcoffset().total_seconds() // 60)
    return f"{'-' if mins < 0 else '+'}{abs(mins) // 60:02d}:{abs(mins) % 60:02d}"


def localize(dt: pd.Series, zone: str, text: pd.Series, where: str, first_line: int) -> pd.Series:
    """Decision B342: naive date-times ``dt`` (their texts ``text``; data row i on file line i + ``first_line``) as
    local times of ``zone``. The hour repeated when the clocks go back is told apart by the rows' order (pandas'
    ``ambiguous="infer"``: monotonic local times of a recording that crosses the change); a time that cannot be
    told apart, or one the clocks skipped, is refused naming the line and the fixed offset that reads it. An unknown
    zone is refused as before."""
    try:
        pd.Timestamp("2000-01-01").tz_localize(zone)
    except Exception:  # noqa: BLE001 - pandas/zoneinfo raise several kinds for an unknown zone
        raise DataError(f"import: --time-zone {zone!r} is not a time zone (write +01:00 or Europe/Berlin)") from None
    try:
        return dt.dt.tz_localize(zone, ambiguous="infer", nonexistent="raise")
    except (ValueError, TypeError):
        pass
    nonexistent = (dt.dt.tz_localize(zone, ambiguous=False, nonexistent="NaT").isna() & dt.notna()).to_numpy()
    bad = nonexistent if nonexistent.any() else (
        dt.dt.tz_localize(zone, ambiguous="NaT", nonexistent="shift_forward").isna() & dt.notna()).to_numpy()
    if not bad.any():
        raise DataError(f"{where}: the date-times cannot be read as local times of {zone}; give a fixed offset such as "
                        "--time-zone +01:00 (decision B342)")
    i = int(np.flatnonzero(bad)[0])
    value, line = str(text.iloc[i]).strip(), i + first_line
    if nonexistent.any():  # the clocks skipped this time (spring): the recorder kept its winter offset
        before = (dt.iloc[i] - pd.Timedelta(hours=2)).tz_localize(zone)
        raise DataError(f"{where}: the local time {value!r} (line {line}) does not exist in {zone}: the clocks "
                        "skipped that hour (daylight saving time began), so the recorder's clock did not change; "
                        f"give the offset it kept, --time-zone {offset_text(before)} (decision B342)")
    summer, winter = (dt.iloc[i].tz_localize(zone, ambiguous=a) for a in (True, False))
    raise DataError(f"{where}: the local time {value!r} (line {line}) occurs twice in {zone} (the clocks went back an "
                    "hour) and the rows do not show which of the two it is; give the offset, --time-zone "
                    f"{offset_text(summer)} (summer time) or {offset_text(winter)} (standard time) (decision B342)")


def dst_jump(secs: np.ndarray) -> int | None:
    """Decision B342: the index ``i`` where local times read without a zone jump by one hour from ``secs[i]`` to
    ``secs[i + 1]`` beyond the recording's sample period (a daylight-saving change: forward in spring, back in
    autumn), within :data:`DST_TOLERANCE_PERIODS` periods; None when there is none."""
    d = np.diff(np.asarray(secs, dtype=float))
    ok = np.isfinite(d) & (d > 0)
    if d.size < 2 or not ok.any():
        return None
    period = float(np.median(d[ok]))
    hit = np.flatnonzero(np.abs(np.abs(d - period) - DST_SHIFT_S) <= DST_TOLERANCE_PERIODS * period)
    return int(hit[0]) if hit.size else None


def dst_message(secs: np.ndarray, i: int, text: pd.Series, where: str, column: str, first_line: int) -> str:
    """Decision B342: the refusal of a one-hour jump of local times read as UTC (:func:`dst_jump`)."""
    back = secs[i + 1] < secs[i]
    way = "back" if back else "forward"
    clocks = "went back as daylight saving time ended" if back else "went forward as daylight saving time began"
    not_ = "a clock reset" if back else "an hour without samples"
    return (f"{where}: column '{column}' jumps {way} by one hour at line {i + 1 + first_line} "
            f"({str(text.iloc[i]).strip()!r} -> {str(text.iloc[i + 1]).strip()!r}): this looks like a daylight-saving "
            f"change (the clocks {clocks}), not {not_}; the text has no zone and was taken as UTC: pass --time-zone "
            "with the recording's zone, e.g. --time-zone Europe/Berlin, to read the local times exactly (or a fixed "
            "offset such as --time-zone +01:00 if the clock really jumped; decision B342)")
