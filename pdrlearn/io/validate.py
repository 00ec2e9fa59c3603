"""Checks on raw sensor tables: each failure is a one-line :class:`DataError` naming the file and the fix."""

from __future__ import annotations

import logging
import math

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.kernels.clipping import (  # noqa: F401 - re-exported: the clipping test is numpy only (E303)
    CLIP_COARSE,
    CLIP_LEVEL,
    CLIP_PINNED,
    CLIP_RUN,
    FOOT_ACCEL_CLIP_COST,
    FOOT_ACCEL_CLIP_NOISE,
    FOOT_ACCEL_RANGE_G,
    FOOT_GYRO_RANGE_DPS,
    FOOT_PEAK_DPS,
    FOOT_UNCLIPPED_PCT,
    MOVING_RAD_S,
    _pinned,
    axis_step,
    clipped_axes,
    clipped_samples,
    distinct_steps,
    foot_accel_cost,
    saturation_warning,
)
from pdrlearn.kernels.clock import batch_size, coarse_stamp_rate
from pdrlearn.kernels.units import (  # noqa: F401 - re-exported: the checks live in the numpy-only kernel (B119)
    GRAVITY_FACTOR_MAX,
    GRAVITY_HINT,
    GRAVITY_REMOVED_RATIO,
    GRAVITY_WINDOW_S,
    MISSCALES,
    PER_G_SCALES,
    QUIET_FRACTION,
    QUIET_WINDOW_S,
    STANDARD_GRAVITY,
    STILL_ACC_RANGE,
    STILL_GYRO_RAD_S,
    STILL_MIN_S,
    STILL_WINDOW_S,
    TILT_GYRO_RMS_MIN,
    TILT_RATIO_MIN,
    TILT_WINDOW_S,
    WALKING_ACC_STD,
    WALKING_GYRO_P99,
    _or,
    _window_gravity,
    check_gravity,
    check_imu_pair,
    check_units,
    counts_per_g_hint,
    gravity_removed,
    gravity_removed_message,
    gravity_scale,
    likely_misscale,
    orientation_change,
    quiet_acc_norm,
    tilt_rate_ratio,
)

log = logging.getLogger(__name__)


def check_columns(df: pd.DataFrame, required: tuple[str, ...], where: str) -> None:
    missing = [c for c in required if c not in df.columns]
    if missing:
        raise DataError(
            f"{where}: missing column(s) {', '.join(missing)} (header is "
            f"{','.join(map(str, df.attrs.get('header', df.columns)))}; "
            f"expected {','.join(required)})"
        )


def check_numeric(df: pd.DataFrame, columns: tuple[str, ...], where: str, *, cut_mid_line: bool = False,
                  command: str | None = None, row_line=None) -> np.ndarray:
    """Return ``df[columns]`` as float64, failing on non-numeric, NaN or infinite values. ``cut_mid_line``: the
    file does not end with a line break (decision B128): a bad last row is then said to be a line cut short, its
    ``--drop-partial-row`` fix naming ``command`` (decision B279; ``pdrlearn track FOLDER`` when None).
    ``row_line``: the file line of a data row (decision B437: a sensor file's, counted by B433's
    ``data_row_lines`` after a ``sep=`` line and blank lines, read only when refusing); one header line else."""
    out = df.loc[:, list(columns)].apply(pd.to_numeric, errors="coerce")
    arr = out.to_numpy(dtype=np.float64)
    bad = ~np.isfinite(arr)
    if bad.any():
        rows = np.flatnonzero(bad.any(axis=1))
        line = row_line or (lambda row: row + 2)
        if cut_mid_line and rows[-1] == len(df) - 1:  # decision B128: a copy cut mid-line, not a bad value
            others = f" (and {len(rows) - 1} other row(s) with bad values, first at line {line(rows[0])})" \
                if len(rows) > 1 else ""
            raise DataError(truncated_line_message(where, line(len(df) - 1), others, command=command))
        raise DataError(
            f"{where}: {len(rows)} row(s) with non-numeric, NaN or infinite values (first at line {line(rows[0])}); "
            "remove or repair those rows"
        )
    return arr


def truncated_line_message(where: str, line: int, others: str = "", what: str = "the recording",
                           command: str | None = None) -> str:
    """Decision B128's one line for a file whose last line ``line`` stops mid-row (B205: label tables too,
    ``what`` naming where to restore it from). Decision B266: a sensor file (``what`` the recording) may also end
    where the recording did - a unit whose battery died mid-row, with nothing to restore - so the line also names
    the two ways to drop that partial row: ``track --drop-partial-row`` and the shell command for the file.
    Decision B279: ``command`` is the command line that was run (``pdrlearn run BUNDLE SESSION``), which the
    ``--drop-partial-row`` fix names (``pdrlearn track FOLDER`` when None)."""
    from pathlib import Path

    from pdrlearn.errors import shell_quote

    dead = ""
    if what == "the recording":  # decision B266: a dead battery's last row
        command = command or f"pdrlearn track {shell_quote(Path(where).parent)}"  # decision B279: the one run
        # sed on a .csv.gz would damage the compressed file (review R4): only --drop-partial-row for it
        sed = "" if str(where).endswith(".gz") else f", or `sed -i '$ d' {shell_quote(where)}`"
        dead = (f"; if the recording itself ends there (a unit whose battery died mid-row), drop that row: "
                f"`{command} --drop-partial-row`{sed} (decision B266; B72 still refuses a file then shorter than "
                "its unit's others)")
    return (f"{where}: last line incomplete (line {line} stops mid-row, no line break at the end): file "
            f"truncated?{others} -- restore the whole file from {what} (deleting the line leaves a file "
            f"cut short, decision B72){dead}")


def check_last_row(df: pd.DataFrame, path, where: str) -> None:
    """Decision B205: a label table (steps.csv, trajectory.csv, ics.csv ...) cut mid-row. Its cut cells parse (a
    time cut to ``6`` is a number), so B128's bad-value test does not see it: a file without a line break at the
    end (:func:`ends_mid_line`) whose last row lacks a cell that every other row has (the fields after the cut) is
    refused with B128's line. A last row complete in its fields (cut inside its last cell) is not detected."""
    if len(df) < 2 or not ends_mid_line(path):
        return
    last, rest = df.iloc[-1], df.iloc[:-1]
    lost = [str(c) for c in df.columns if pd.isna(last[c]) and rest[c].notna().all()]
    if lost:
        raise DataError(truncated_line_message(
            where, len(df) + 1, f" (it has no {', '.join(lost[:3])}{' ...' if len(lost) > 3 else ''}, which every "
            "other row has; decision B205)", what="where the labels were made"))


def ends_mid_line(path) -> bool:
    """Decision B128: whether a non-empty file's last byte is not a line break (a copy or download cut short)."""
    import os

    from pdrlearn.textfile import is_gzip

    if is_gzip(path):  # decision B369: the last byte of the decompressed text
        return _gzip_ends_mid_line(path)
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            if f.tell() == 0:
                return False
            f.seek(-1, os.SEEK_END)
            return f.read(1) not in (b"\n", b"\r")
    except OSError:
        return False


def _gzip_ends_mid_line(path) -> bool:
    """:func:`ends_mid_line` of a ``*.gz`` file (decision B369): gzip cannot seek from the end, so the decompressed
    text is read through in blocks; a damaged file is left to the reader's own line."""
    import gzip
    import zlib

    last = b""
    try:
        with gzip.open(path, "rb") as f:
            while block := f.read(1 << 20):
                last = block[-1:]
    except (OSError, EOFError, zlib.error):
        return False
    return last not in (b"", b"\n", b"\r")


#: decision B73: a backward step of the timestamps larger than this (s) is a clock reset, not samples out of order:
#: B11's gap; no sensor buffers or re-sends a second of samples out of order
CLOCK_RESET_S = 1.0
#: decision B73: more such jumps than this is rows out of order (a shuffled file), not restarts of the recorder
MAX_CLOCK_RESETS = 3


def clock_resets(t: np.ndarray) -> np.ndarray:
    """Decision B73: the indices ``i`` where ``t`` jumps back from ``t[i]`` to ``t[i + 1]`` by more than
    :data:`CLOCK_RESET_S` when those are clock resets: 1 to :data:`MAX_CLOCK_RESETS` such jumps and no more than
    1 % of the other intervals going backwards (a shuffled file is rows out of order, not restarts). Empty
    otherwise. ``pdrlearn import --split-at-clock-reset`` cuts an export at these rows (decision B80)."""
    t = np.asarray(t, dtype=float)
    if t.size < 2:
        return np.empty(0, dtype=np.int64)
    dt = np.diff(t)
    back = np.flatnonzero(~(dt > 0))  # NaN intervals count as backwards
    reset = np.flatnonzero(dt < -CLOCK_RESET_S)
    if 1 <= reset.size <= MAX_CLOCK_RESETS and back.size - reset.size - np.count_nonzero(dt == 0) <= 0.01 * dt.size:
        return reset
    return np.empty(0, dtype=np.int64)


def clock_reset_message(t: np.ndarray, reset: np.ndarray, where: str, at: str, fix: str) -> str:
    """Decision B73's one line for the clock resets ``reset`` (:func:`clock_resets`) of ``t`` (s), the first
    at ``at`` (``line 1902``), ending with ``fix``."""
    i = int(reset[0])
    more = f" ({reset.size} such jumps)" if reset.size > 1 else ""
    from pdrlearn.errors import message_number as num  # decision B424: -1e308 printed 309 digits

    return (f"{where}: the timestamps jump back from {num(t[i])} s to {num(t[i + 1])} s at {at}{more}: a clock reset "
            "(the recorder restarted), not samples out of order, so sorting would interleave two recordings -- "
            f"{fix} (decision B73)")


#: decision B185: at most one tie per this many rows is restamped (:func:`restamp_isolated_ties`); more are refused
TIE_ROWS = 1000


def restamp_isolated_ties(t: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, int]:
    """Decision B185: a few isolated ties of jittered receive stamps rounded to 1 ms (+-15 ms at 100 Hz: one in
    9680 rows) refused the whole session. A tie of two rows whose values differ (not a repeated packet), with
    strictly increasing stamps on both sides, at most one per :data:`TIE_ROWS` rows, gets the later row's stamp moved
    halfway to the next row's (no sample is lost: the offline methods integrate with a fixed interval). Returns the
    new stamps and how many moved; ``(t, 0)`` (unchanged, refused by :func:`check_timestamps`) otherwise."""
    d = np.diff(t)
    dup = np.flatnonzero(d == 0)
    if not dup.size or dup.size > max(1, t.size // TIE_ROWS) or dup[-1] + 2 >= t.size:
        return t, 0
    if (np.diff(dup) < 2).any() or not (d[dup + 1] > 0).all():  # runs of ties, or stamps not increasing after
        return t, 0
    if (values[dup] == values[dup + 1]).all(axis=1).any():  # a repeated packet: refused as a duplicate
        return t, 0
    t = t.copy()
    t[dup + 1] = 0.5 * (t[dup] + t[dup + 2])
    return t, int(dup.size)


def check_timestamps(t: np.ndarray, where: str, *, in_memory: bool = False, reset_fix: str | None = None,
                     lines: np.ndarray | None = None, duplicate_fix: str = "drop the duplicated rows",
                     backward_fix: str = "sort the file by timestamp") -> None:
    """Timestamps must be strictly increasing (no duplicates, sorted). ``in_memory``: ``t`` is a
    :class:`~pdrlearn.io.Stream`'s (decision B49): the messages count samples and say how to fix the arrays.
    ``reset_fix``: the fix a clock reset's message gives instead of splitting the session by hand
    (``pdrlearn import`` names its ``--split-at-clock-reset``, decision B80). ``lines``: the file line of each
    sample (default: sample k on line k + 2, under a header line); import gives them for the rows it kept.
    ``duplicate_fix``: the fix a file's duplicate timestamps are given (import names its
    ``--drop-duplicate-timestamps``, decision B150); ``backward_fix``: the fix of a file's rows out of order (import
    names its ``--sort-timestamps``, decision B383)."""

    def line(k: int) -> int:
        return int(lines[k]) if lines is not None else k + 2

    if t.size == 0:
        raise DataError(f"{where}: no samples" + ("; drop the empty stream from the session" if in_memory else
                                                  " (empty file); record data or remove the file"))
    dt = np.diff(t)
    dup = np.flatnonzero(dt == 0)
    if dup.size:
        if in_memory:
            raise DataError(f"{where}: {dup.size} duplicate timestamp(s) (first at index {dup[0] + 1}); drop the "
                            "duplicated samples (keep = np.unique(t, return_index=True)[1])")
        k = batch_size(t)  # decision B186: regular groups on one stamp are batched samples, not repeated rows
        if k > 1:
            raise DataError(
                f"{where}: {dup.size} duplicate timestamp(s) (first at line {line(dup[0] + 1)}): the rows come in "
                f"groups of {k} on one timestamp (a Bluetooth notification's samples on its receive time?); re-time "
                f"them at the sensor's output rate with `pdrlearn import EXPORT --retime HZ` (decision B186) rather "
                f"than dropping {k - 1} of every {k}"
            )
        hz = coarse_stamp_rate(t)  # decision B468: whole-ms stamps of a 1125 Hz unit are samples, not repeats
        if hz is not None:
            raise DataError(
                f"{where}: {dup.size} duplicate timestamp(s) (first at line {line(dup[0] + 1)}): the stamps' steps "
                f"(>= {1e3 * float(np.diff(t)[np.diff(t) > 0].min()):.4g} ms) are coarser than the samples' own "
                f"interval ({1e3 / hz:.4g} ms, ~{hz:.5g} Hz): if the sensor's rate is about that (a high-rate unit "
                "stamped in whole ms), the repeats are real samples - re-time them with `pdrlearn import EXPORT "
                f"--retime HZ` rather than dropping them (decision B468); if the rows repeat a sample, {duplicate_fix}")
        raise DataError(
            f"{where}: {dup.size} duplicate timestamp(s) (first at line {line(dup[0] + 1)}); {duplicate_fix}"
            + _also_backwards(t, dt, line, backward_fix)
        )
    back = np.flatnonzero(~(dt > 0))  # NaN intervals count as backwards
    # decision B73: a clock reset (a few large backward jumps, increasing in between); sorting (the advice below)
    # interleaves two recordings. Shuffled rows (many backward steps, most of them small) keep the sort advice
    reset = clock_resets(t)
    if reset.size:
        i = int(reset[0])
        at = f"index {i + 1}" if in_memory else f"line {line(i + 1)}"
        split = ("split the arrays there into two sessions" if in_memory else reset_fix if reset_fix else
                 f"split the session into two there (this file before line {line(i + 1)} and from it on; every other "
                 "file and the labels where their own clock restarts)")
        raise DataError(clock_reset_message(t, reset, where, at, split))
    if back.size:
        if in_memory:
            raise DataError(f"{where}: timestamps are not increasing {back.size} time(s) (first at index "
                            f"{back[0] + 1}); sort the samples by time (order = np.argsort(t): t[order], "
                            "values[order])")
        raise DataError(
            f"{where}: timestamps go backwards {back.size} time(s) (first at line {line(back[0] + 1)}); "
            + backward_fix + _also_repeated(t, line, duplicate_fix)
        )


def _also_backwards(t: np.ndarray, dt: np.ndarray, line, backward_fix: str) -> str:
    """Decision B477: what a file's duplicate-timestamp line adds when its rows also go backwards (not at a clock
    reset, B73's own line): both repairs in one line, so that a batch is not re-run once per problem."""
    back = np.flatnonzero(dt < 0)
    if not back.size or clock_resets(t).size:
        return ""
    return (f"; the timestamps also go backwards {back.size} time(s) (first at line {line(back[0] + 1)}): "
            f"{backward_fix} too (decision B477)")


def _also_repeated(t: np.ndarray, line, duplicate_fix: str) -> str:
    """Decision B477: what a file's backward-timestamp line adds when, sorted, some rows repeat an earlier row's
    timestamp (duplicates the rows out of order keep apart): both repairs in one line."""
    finite = t[np.isfinite(t)]
    n = finite.size - np.unique(finite).size
    if not n:
        return ""
    _, first = np.unique(t, return_index=True)
    again = np.setdiff1d(np.flatnonzero(np.isfinite(t)), first)  # rows whose timestamp an earlier row has
    return (f"; {n} row(s) also repeat an earlier row's timestamp (first at line {line(int(again[0]))}): once "
            f"sorted, {duplicate_fix} too (decision B477)")


#: plausible native sampling rates of a body-worn sensor file (Hz): barometers log at >= 1 Hz, IMUs up to
#: a few hundred Hz (PLASYS 20 Hz, thesis ch.4.2.3; real recordings 100 and 204.8 Hz). Outside this band the
#: timestamps are in another unit than the reader assumed (docs/decisions/bad-input.md B9).
RATE_LIMITS_HZ = (0.5, 5000.0)
#: decision B144: the slowest plausible native rate of an accelerometer or gyroscope file (Hz). The slowest IMU the
#: project reads logs at 20 Hz (PLASYS, thesis ch.4.2.3) and a walking step (~2 Hz) needs several samples; with
#: B9's 5000 Hz ceiling the band spans under a factor 1000, so at most one of ms/us/ns (or s/ms) fits an IMU file
#: (a phone's epoch-ns clock at 1000 Hz read as us gave 0.996 Hz, plausible under the 0.5 Hz barometer floor).
IMU_MIN_RATE_HZ = 10.0
#: decision B160: the rate an accelerometer or gyroscope file is refused below (Hz), B144's 10 Hz less B22's 10 %
#: tolerance: a 10 Hz logger whose seconds read from text give a median step of 0.10000000000000142 s (9.99999 Hz)
#: or whose clock runs 1 % slow (101 ms) is a 10 Hz file; 5000 / 9 Hz still spans under a factor 1000
IMU_FLOOR_HZ = 0.9 * IMU_MIN_RATE_HZ
#: decision B144: a first timestamp read as after 2100-01-01 (epoch s) is in another unit (epoch ns read as us:
#: year ~56,900)
EPOCH_END = 4.1e9
#: decision B161: the fastest an accelerometer or gyroscope file is read in ms while its timestamps are also a
#: plausible sensor rate in seconds: a ms clock's whole steps reach 1000 Hz (plus B22's 10 % tolerance); the IMUs
#: the project reads log at 20-500 Hz (PLASYS 20 Hz, thesis ch.4.2.3; real 100, 204.8 Hz; phones up to 500 Hz). A
#: 4 Hz file in seconds read as ms is 4000 Hz, every time 1000x too short
IMU_MS_MAX_HZ = 1.1 * 1000.0


def check_rate(t: np.ndarray, where: str, *, in_memory: bool = False) -> None:
    """The median sample interval of ``t`` (s) must give a plausible rate; else name the likely unit.
    ``in_memory``: ``t`` is a :class:`~pdrlearn.io.Stream`'s, which must be seconds (decision B49); the message
    names the unit the values fit (:func:`time_unit_candidates`) and the factor."""
    if t.size < 3:
        return
    rate = 1.0 / float(np.median(np.diff(t)))
    lo, hi = RATE_LIMITS_HZ
    if in_memory and not lo <= rate <= hi:
        fits = [(u, k) for u, k in time_unit_candidates(t) if u != "s"]
        fix = (f"they look like {dict(_UNIT_NAMES)[fits[0][0]]}: divide by {1 / fits[0][1]:g}" if fits
               else "convert them to seconds")
        raise DataError(f"{where}: timestamps give {rate:.4g} Hz, implausible for a body-worn sensor "
                        f"({lo:g}-{hi:g} Hz); Stream.t must be seconds, {fix}")
    if rate > hi:
        raise DataError(
            f"{where}: timestamps give {rate:.0f} Hz, so they are not milliseconds (seconds?); convert them to ms "
            "or declare \"units\": {\"timestamp\": \"s\"} in meta.json"
        )
    if rate < lo:
        raise DataError(
            f"{where}: timestamps give {rate:.3g} Hz, so they are not milliseconds (micro- or nanoseconds?); "
            "convert them to ms or declare \"units\": {\"timestamp\": \"us\"} (or \"ns\") in meta.json"
        )


#: timestamp units a session that declares none may be in (B22), milliseconds first (the default)
_TIME_UNITS = (("ms", 1e-3), ("s", 1.0), ("us", 1e-6), ("ns", 1e-9))
_UNIT_NAMES = (("ms", "milliseconds"), ("s", "seconds"), ("us", "microseconds"), ("ns", "nanoseconds"))


def time_unit_candidates(t_raw: np.ndarray, declared_rate_hz: float | None = None, *,
                         inertial: bool = False) -> list[tuple[str, float]]:
    """The units (``(unit, seconds per unit)``, ms first) in which raw timestamps give a plausible rate
    (:data:`RATE_LIMITS_HZ`; from :data:`IMU_FLOOR_HZ` for an ``inertial`` file, decisions B144, B160) and, where
    ``meta.json`` declares a rate, that rate within 10 % (decision B22), and a first timestamp before
    :data:`EPOCH_END` (B144). Every unit when the timestamps say nothing (fewer than 3, or not increasing:
    :func:`check_timestamps`'s error)."""
    if t_raw.size < 3:
        return list(_TIME_UNITS)
    d = float(np.median(np.diff(t_raw)))
    if not np.isfinite(d) or d <= 0:
        return list(_TIME_UNITS)
    lo, hi = (IMU_FLOOR_HZ, RATE_LIMITS_HZ[1]) if inertial else RATE_LIMITS_HZ  # B144, B160
    t0 = abs(float(t_raw[0]))
    slow = inertial and slow_seconds_rate(t_raw) is not None  # B161: seconds of a slow logger, not fast ms
    return [(u, k) for u, k in _TIME_UNITS if lo <= 1.0 / (d * k) <= hi and t0 * k < EPOCH_END
            and not (slow and u == "ms")
            and (declared_rate_hz is None or abs(1.0 / (d * k) - declared_rate_hz) <= 0.1 * declared_rate_hz)]


def slow_seconds_rate(t_raw: np.ndarray) -> float | None:
    """Decision B161: the rate (Hz) of an accelerometer or gyroscope file's raw timestamps read as seconds when
    that reading is a plausible sensor rate (B9's 0.5 Hz floor, a start before 2100) under the IMU floor
    (:data:`IMU_FLOOR_HZ`) and the ms reading is faster than :data:`IMU_MS_MAX_HZ`: a slow logger in seconds
    (a phone app at 4-5 Hz), which B144 read as ms at 4000-5000 Hz, or refused as ms over 5000 Hz. None otherwise
    (fewer than 3 timestamps, not increasing, another case)."""
    t_raw = np.asarray(t_raw, dtype=float)
    if t_raw.size < 3:
        return None
    d = float(np.median(np.diff(t_raw)))
    if not np.isfinite(d) or d <= 0:
        return None
    rate = 1.0 / d
    ok = RATE_LIMITS_HZ[0] <= rate < IMU_FLOOR_HZ and 1000.0 * rate > IMU_MS_MAX_HZ
    return rate if ok and abs(float(t_raw[0])) < EPOCH_END else None


def slow_seconds_message(t_raw: np.ndarray, where: str, ms_fix: str) -> str | None:
    """Decision B161's one line for a file :func:`slow_seconds_rate` names (else None): the rate read as
    seconds (and the date they start on, when they are epoch seconds), why neither reading is an IMU's, and the
    fixes: record again at 10 Hz or more, or, if they are ms, ``ms_fix`` (import's ``--time-unit ms``,
    read_session's meta.json ``units.timestamp``)."""
    rate = slow_seconds_rate(t_raw)
    if rate is None:
        return None
    t0 = abs(float(np.asarray(t_raw, dtype=float)[0]))
    date = ""
    if EPOCH_START <= t0 < EPOCH_END:  # epoch seconds: the start date says they are seconds
        date = f", starting {pd.Timestamp(t0, unit='s'):%Y-%m-%d %H:%M} UTC"
    return (f"{where}: the timestamps read as seconds give {rate:.3g} Hz{date}, too slow for an accelerometer or "
            f"gyroscope ({IMU_FLOOR_HZ:g} Hz or more, decisions B144, B160), and read as ms {1000.0 * rate:.4g} Hz, "
            f"faster than an IMU clock in ms ({IMU_MS_MAX_HZ:g} Hz at most): record again at {IMU_MIN_RATE_HZ:g} Hz or "
            f"more (a phone app's rate setting); if they really are ms, {ms_fix} (decision B161)")


def check_label_times(table: pd.DataFrame, t_start: float, t_end: float, where: str) -> None:
    """Label times (s) must lie on the sensors' clock and look like real steps/events.

    Refused: most label times outside the recording (+-1 s), or intervals/events closer than 50 ms on
    median (a step lasts ~0.3-2 s; such values are seconds written into ``*_ms`` columns).
    """
    cols = [c for c in ("start_s", "end_s", "ic_s") if c in table.columns]
    if not cols or len(table) == 0:
        return
    times = table[cols].to_numpy(dtype=float)
    times = times[np.isfinite(times)]
    outside = int(np.sum((times < t_start - 1.0) | (times > t_end + 1.0)))
    if outside > times.size / 2:
        raise DataError(
            f"{where}: {outside} of {times.size} label times lie outside the recording ({t_start:.1f}-{t_end:.1f} s "
            "on the sensors' clock); *_ms columns must be milliseconds on the sensor files' time base"
        )
    if len(table) >= 3:
        if "start_s" in table.columns and "end_s" in table.columns:
            spacing = float(np.median(table["end_s"].to_numpy(float) - table["start_s"].to_numpy(float)))
        else:
            spacing = float(np.median(np.diff(np.sort(table[cols[0]].to_numpy(float)))))
        if 0 < spacing < 0.05:
            raise DataError(
                f"{where}: label intervals of {1e3 * spacing:.1f} ms on median are too short for steps; "
                "the *_ms columns look like seconds: multiply them by 1000"
            )


def check_trajectory_times(t_raw: np.ndarray, scale: float, t_start: float, t_end: float, where: str,
                           basis: str = "the sensor files' unit") -> None:
    """A ground-truth trajectory's timestamps (``t_raw``, in the file's unit; ``scale`` s per unit, the
    session's unit: declared, B22-inferred or ms) must lie on the sensors' clock (decision B25). Refused, one
    line naming the file and the fix: a rate implausible in that unit or most of the trajectory outside the
    recording (+-1 s, as :func:`check_label_times`), with the unit that would fit when one does (B22's
    :func:`time_unit_candidates`: a plausible rate and the recording covered), or the shift of the clocks."""
    t_raw = np.asarray(t_raw, dtype=float)
    if t_raw.size < 2 or not t_end > t_start:
        return

    def inside(k: float) -> float:
        t = t_raw * k
        return float(np.mean((t >= t_start - 1.0) & (t <= t_end + 1.0)))

    def covered(k: float) -> float:  # fraction of the recording the trajectory spans
        lo, hi = max(t_raw[0] * k, t_start), min(t_raw[-1] * k, t_end)
        return max(hi - lo, 0.0) / (t_end - t_start)

    plausible = dict(time_unit_candidates(t_raw))
    unit = next((u for u, k in _TIME_UNITS if math.isclose(k, scale)), f"{scale:g} s")
    ok_rate = unit in plausible or t_raw.size < 3
    fits = [u for u, k in plausible.items() if u != unit and inside(k) > 0.5 and covered(k) > 0.5]
    # in the session's unit: a plausible rate, most samples on the recording, and not a span squeezed into
    # a sliver of it when another unit spans it (s read as ms: 40 s of mocap inside the first 0.04 s)
    if ok_rate and inside(scale) > 0.5 and not (fits and covered(scale) < 0.05):
        return
    t0, t1 = t_raw[0] * scale, t_raw[-1] * scale
    rate = (1.0 / float(np.median(np.diff(t_raw)) * scale)) if t_raw.size >= 3 else float("nan")
    what = (f"{where}: its timestamps read as {unit} ({basis}) give {t0:.6g}-{t1:.6g} s at "
            f"{rate:.4g} Hz, but the sensors cover {t_start:.2f}-{t_end:.2f} s")
    if fits:
        u = fits[0]
        factor = plausible[u] / scale
        raise DataError(f"{what}; read as {u} they fit: write its timestamps in {unit} like the sensor files "
                        f"(multiply by {factor:g})")
    if not ok_rate:
        raise DataError(f"{what}; that rate is implausible ({RATE_LIMITS_HZ[0]:g}-{RATE_LIMITS_HZ[1]:g} Hz): write its "
                        f"timestamps in {unit} like the sensor files, on their time base")
    raise DataError(f"{what}; the trajectory does not lie on the sensors' clock: write its timestamps in {unit} "
                    f"on the sensor files' time base (shift by the offset between the two clocks)")


#: decision B39: timestamps at or above this are a clock since an epoch (epoch s >= 1e9 since 2001-09, epoch ms
#: ~1.6e12), not sample numbers counted from the start of a recording
EPOCH_START = 1e9


def sample_numbers(t_raw: np.ndarray) -> bool:
    """True when timestamps look like sample numbers (decision B39): integers stepping by exactly 1 (at least 95 %
    of the steps; dropped samples make a few larger integer steps), starting under :data:`EPOCH_START`. Read as
    ms they are a 1000 Hz clock, which a genuine 1000 Hz logger in ms since its start also writes; a clock since
    an epoch (1.6e12 ms) is not taken for sample numbers."""
    t = np.asarray(t_raw, dtype=float)
    if t.size < 3 or not np.all(np.isfinite(t)) or abs(float(t[0])) >= EPOCH_START:
        return False
    d = np.diff(t)
    if np.any(d <= 0) or np.any(t != np.round(t)):
        return False
    return bool(np.mean(d == 1.0) >= 0.95)


#: walking rhythm bounds (s) for :func:`implausible_rhythm` (decision B31): the shortest step of a walk or run
#: lasts ~0.25 s (cadence 240 steps/min), a stride up to ~2 s; D9's waist rhythm test looks at 0.3-1.0 s lags.
RHYTHM_MIN_S, RHYTHM_MAX_S = 0.25, 2.0


def implausible_rhythm(values: np.ndarray, fs: float, *, span_s: float = 120.0, min_corr: float = 0.3) -> float | None:
    """The lag (s) of the strongest repetition of ``|acc|`` read at ``fs`` Hz when it is faster than any gait
    (under :data:`RHYTHM_MIN_S`), else ``None`` (decision B31). The autocorrelation of the norm (mean removed,
    first ``span_s`` s) is searched for its highest local maximum between 20 ms and :data:`RHYTHM_MAX_S`; only
    a clear one (>= ``min_corr``) counts: a recording without walking says nothing. 100 Hz sample indices read as
    1000 Hz put the strides (~1.1 s) and steps (~0.5 s) at 0.11 s and 0.05 s."""
    x = np.linalg.norm(np.asarray(values, dtype=float), axis=1)[: int(span_s * fs)]
    x = x - x.mean()
    lo, hi = max(int(0.02 * fs), 1), min(int(RHYTHM_MAX_S * fs), x.size // 2)
    if hi < 2 * int(RHYTHM_MIN_S * fs) or not np.any(x):  # too short to see a repetition twice
        return None
    n = 1 << int(np.ceil(np.log2(2 * x.size)))
    f = np.fft.rfft(x, n)
    ac = np.fft.irfft(f * np.conj(f), n)[: hi + 2]
    ac = ac / ac[0]
    seg = ac[lo - 1: hi + 2]
    peaks = np.flatnonzero((seg[1:-1] > seg[:-2]) & (seg[1:-1] >= seg[2:])) + lo
    # decision B304: a repetition rises by min_corr (B31's clarity bar) above the lowest correlation before it; a
    # wiggle of the decay from lag 0 does not (a 1000 Hz foot recording of trial T3: a 93 ms peak at 0.63, 0.09
    # above its low, beat its 1.0 s stride's 0.59 and was named as a rhythm)
    peaks = peaks[ac[peaks] - np.minimum.accumulate(ac)[peaks] >= min_corr]
    if peaks.size == 0:
        return None
    best = int(peaks[np.argmax(ac[peaks])])
    if ac[best] < min_corr or best / fs >= RHYTHM_MIN_S:
        return None
    return best / fs


def check_samples(name: str, t: np.ndarray, values: np.ndarray, where: str) -> None:
    """Decision B50: the structure of one :class:`~pdrlearn.io.Stream` (``t`` float (n,), ``values`` float 2-D):
    one row of values per timestamp, the sensor's number of columns (values given transposed, (k, n), are named),
    no NaN or inf, timestamps strictly increasing. Cheap (O(n)); run when a Stream is built and when a session
    enters a public entry point (:func:`check_session`)."""
    from pdrlearn.io.sensors import SENSORS

    k = SENSORS[name].n_axes
    if t.ndim != 1:
        raise DataError(f"{where}: timestamps must be one-dimensional (n,), got shape {t.shape}; pass t.ravel()")
    n = t.shape[0]
    if values.shape == (k, n) and n != k:
        raise DataError(f"{where}: values have shape {values.shape}, one column per sample; a Stream holds one row "
                        f"per sample, shape ({n}, {k}): pass values.T")
    if values.ndim != 2 or values.shape[0] != n:
        rows = values.shape[0] if values.ndim else 0
        raise DataError(f"{where}: {n} timestamps but {rows} rows of values (shape {values.shape}); pass one row "
                        f"of {k} value(s) per timestamp, shape ({n}, {k})")
    if values.shape[1] != k:
        raise DataError(f"{where}: expected {k} value columns ({', '.join(SENSORS[name].columns)}), got "
                        f"{values.shape[1]}")
    if n and not np.isfinite(values).all():
        rows = np.flatnonzero(~np.isfinite(values).all(axis=1))
        raise DataError(f"{where}: {rows.size} sample(s) with NaN or infinite values (first at index {rows[0]}); "
                        "drop or interpolate those samples")
    if n and not np.isfinite(t).all():
        bad = np.flatnonzero(~np.isfinite(t))
        raise DataError(f"{where}: {bad.size} NaN or infinite timestamp(s) (first at index {bad[0]}); drop "
                        "those samples")
    if n > 1:
        check_timestamps(t, where, in_memory=True)


def check_session(session) -> None:
    """Decision B49: what :func:`pdrlearn.io.read_session` checks in each sensor file, on every stream of a
    session as it is in memory (built in Python, or read and then changed): :func:`check_samples`, the
    timestamps' rate (:func:`check_rate`: ``Stream.t`` in seconds) and, unless ``session.check_units`` is
    False, the values' units (:func:`check_units`, with B30's gravity). Each failure is one :class:`DataError`
    naming the session and the stream and saying how to fix the arrays. Run once per call of a public entry
    point (:func:`pdrlearn.io.session.session_entry`)."""
    from pdrlearn.io.sensors import SENSORS
    from pdrlearn.io.session import Stream

    if not isinstance(session.streams, dict):
        raise DataError(f"{session.where}: streams is a {type(session.streams).__name__}; it must be a dict of sensor "
                        "name -> pdrlearn.io.Stream")
    for key, s in session.streams.items():
        where = f"{session.where}, stream {key}"
        if not isinstance(s, Stream):
            raise DataError(f"{where}: is a {type(s).__name__}, not a pdrlearn Stream; build it with "
                            f"pdrlearn.io.Stream({key!r}, t_seconds, values)")
        if key != s.name:
            raise DataError(f"{where}: holds a Stream named {s.name!r}; key session.streams by the Stream's name")
        check_samples(s.name, s.t, s.values, where)
        if len(s) == 0:
            raise DataError(f"{where}: no samples; drop the empty stream from session.streams")
        check_rate(s.t, where, in_memory=True)
        if session.check_units:
            check_units(SENSORS[s.name], s.values, where, declare="", t=s.t)


def foot_accel_clip_g(session) -> float | None:
    """Decision L688: the full scale (g) of the session's foot accelerometer where B77 / B311 call it clipped
    (:func:`clipped_samples`), else None (no foot accelerometer, or none clipped)."""
    if session is None or "fAccelerometer" not in session.streams:
        return None
    from pdrlearn.io.plasys import declared_full_scales  # decision B456: at a declared full scale

    n, top = clipped_samples(session.streams["fAccelerometer"].values, "accelerometer",
                             declared_full_scales(session).get("fAccelerometer"))
    return top / STANDARD_GRAVITY if n else None


#: decision B412: a stream's smallest step is a resolution only when the values lie on a grid: at least this share of
#: an axis's steps between distinct values are whole multiples of the smallest, within :data:`GRID_TOLERANCE` of it
#: (float noise of converted values, e.g. 9.1e-17 rad/s, gives multiples with random fractions)
GRID_SHARE = 0.9
GRID_TOLERANCE = 0.05


def _on_grid(steps: np.ndarray) -> bool:
    """Decision B412: whether one axis's :func:`distinct_steps` (non-empty) are whole multiples of the smallest."""
    r = steps / steps.min()
    return float(np.mean(np.abs(r - np.round(r)) <= GRID_TOLERANCE)) >= GRID_SHARE


def resolution(values: np.ndarray, *, grid: bool = False) -> float | None:
    """Decision B406: a stream's resolution: the smallest :func:`axis_step` over its axes that have one (0.0 when
    no axis changes). ``grid=True`` (decision B412, what `info` prints): None unless some axis changes and every
    changing axis lies on the grid of its smallest step (`info` prints "-", null in --json): the smallest gap
    between converted floats is no sensor step."""
    v = np.asarray(values, dtype=float)
    steps = [d for d in (distinct_steps(c) for c in v.reshape(len(v), -1).T) if d.size]
    if grid and not (steps and all(_on_grid(d) for d in steps)):
        return None
    return min((float(d.min()) for d in steps), default=0.0)


#: decision B403: an accelerometer axis needs this many peaks (strides) at or above B77's 2 g floor to be judged for
#: a ceiling; standard MEMS full scales (g) the pinned peaks must sit just under (2 g is caught by B77 at every rate,
#: trial T2); the band under the scale (90-100 %) and the largest spread of the 10 highest peaks (7 %) that make a
#: ceiling: all stated in decision B403 before it was measured
CEILING_MIN_PEAKS = 20
CEILING_SCALES_G = (4.0, 8.0, 16.0)
CEILING_BAND = 0.90
CEILING_SPREAD = 0.07
CEILING_TAIL = 10


def ceiling_clip(values: np.ndarray) -> float:
    """Decision B403: the full scale (m/s^2) an accelerometer file's impact peaks are pinned under (a converter that
    saturated before the sensor's own decimation filter: the filter smooths each flat top into a peak just below the
    scale), or 0.0. On each axis and sign: the local maxima at or above :data:`CLIP_LEVEL`; with
    :data:`CEILING_MIN_PEAKS` or more, a ceiling when the largest lies within :data:`CEILING_BAND`-100 % of one of
    :data:`CEILING_SCALES_G` and the :data:`CEILING_TAIL`-th largest within :data:`CEILING_SPREAD` of it.

    Not adopted as a warning (decision B411: unclipped real gait with its dynamics x1.2 / x1.3,
    datasets/external/gaitmap_ms_right, is called pinned under 8 g too); decision B415: no pipeline calls it (no
    switch), it is a check to run on a suspect accelerometer file, ``ceiling_clip(session.streams[
    "fAccelerometer"].values)`` (0.0: no ceiling found)."""
    v = np.asarray(values, dtype=float)
    if v.ndim != 2 or v.shape[0] < 3:
        return 0.0
    floor = CLIP_LEVEL["accelerometer"]
    found = 0.0
    for col in (*v.T, *(-v).T):
        inner = col[1:-1]
        peaks = np.sort(inner[(inner > col[:-2]) & (inner >= col[2:]) & (inner >= floor)])[::-1]
        if peaks.size < CEILING_MIN_PEAKS:
            continue
        top = float(peaks[0])
        if (top - float(peaks[CEILING_TAIL - 1])) > CEILING_SPREAD * top:
            continue
        for scale in CEILING_SCALES_G:
            full = scale * STANDARD_GRAVITY
            if CEILING_BAND * full <= top <= full:
                found = max(found, full)
    return found


