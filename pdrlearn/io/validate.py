"""Checks on raw sensor tables: each failure is a one-line :class:`DataError` naming the file and the fix."""

from __future__ import annotations

import logging
import math

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.sensors import SensorSpec

STANDARD_GRAVITY = 9.80665  # m/s^2 (thesis ch.4.2.1.1)

log = logging.getLogger(__name__)


def check_columns(df: pd.DataFrame, required: tuple[str, ...], where: str) -> None:
    missing = [c for c in required if c not in df.columns]
    if missing:
        raise DataError(
            f"{where}: missing column(s) {', '.join(missing)} (header is {','.join(map(str, df.columns))}; "
            f"expected {','.join(required)})"
        )


def check_numeric(df: pd.DataFrame, columns: tuple[str, ...], where: str, *, cut_mid_line: bool = False) -> np.ndarray:
    """Return ``df[columns]`` as float64, failing on non-numeric, NaN or infinite values. ``cut_mid_line``: the
    file does not end with a line break (decision B128): a bad last row is then said to be a line cut short."""
    out = df.loc[:, list(columns)].apply(pd.to_numeric, errors="coerce")
    arr = out.to_numpy(dtype=np.float64)
    bad = ~np.isfinite(arr)
    if bad.any():
        rows = np.flatnonzero(bad.any(axis=1))
        if cut_mid_line and rows[-1] == len(df) - 1:  # decision B128: a copy cut mid-line, not a bad value
            others = f" (and {len(rows) - 1} other row(s) with bad values, first at line {rows[0] + 2})" \
                if len(rows) > 1 else ""
            raise DataError(
                f"{where}: last line incomplete (line {len(df) + 1} stops mid-row, no line break at the end): file "
                f"truncated?{others} -- restore the whole file from the recording (deleting the line leaves a file "
                "cut short, decision B72)")
        raise DataError(
            f"{where}: {len(rows)} row(s) with non-numeric, NaN or infinite values (first at line {rows[0] + 2}); "
            "remove or repair those rows"
        )
    return arr


def ends_mid_line(path) -> bool:
    """Decision B128: whether a non-empty file's last byte is not a line break (a copy or download cut short)."""
    import os

    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            if f.tell() == 0:
                return False
            f.seek(-1, os.SEEK_END)
            return f.read(1) not in (b"\n", b"\r")
    except OSError:
        return False


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
    return (f"{where}: the timestamps jump back from {t[i]:.2f} s to {t[i + 1]:.2f} s at {at}{more}: a clock reset "
            "(the recorder restarted), not samples out of order, so sorting would interleave two recordings -- "
            f"{fix} (decision B73)")


def check_timestamps(t: np.ndarray, where: str, *, in_memory: bool = False, reset_fix: str | None = None,
                     lines: np.ndarray | None = None) -> None:
    """Timestamps must be strictly increasing (no duplicates, sorted). ``in_memory``: ``t`` is a
    :class:`~pdrlearn.io.Stream`'s (decision B49): the messages count samples and say how to fix the arrays.
    ``reset_fix``: the fix a clock reset's message gives instead of splitting the session by hand
    (``pdrlearn import`` names its ``--split-at-clock-reset``, decision B80). ``lines``: the file line of each
    sample (default: sample k on line k + 2, under a header line); import gives them for the rows it kept."""

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
        raise DataError(
            f"{where}: {dup.size} duplicate timestamp(s) (first at line {line(dup[0] + 1)}); drop the duplicated rows"
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
            "sort the file by timestamp"
        )


def _or(declare: str | None, default: str) -> str:
    """The alternative fix of a unit message: ``declare`` (``""``: none, decision B49) or ``default``."""
    if declare == "":
        return ""
    return ", or " + (declare or default)


#: decision B78: the accelerometer's unit is judged on the median |acc| of its quietest windows (the
#: :data:`QUIET_FRACTION` of windows of :data:`QUIET_WINDOW_S`, at least 3 samples, with the lowest sd of |acc|),
#: where a foot is in foot-flat and |acc| ~ g even in running (a running foot's whole-file median |acc| is
#: 30 m/s^2, trial of session 17), as well as on the whole file's median (a waist unit: |acc| averages g over the
#: gait cycle); a unit mistake (g, mg, counts) scales both alike.
QUIET_WINDOW_S, QUIET_FRACTION = 0.1, 0.1


def quiet_acc_norm(values: np.ndarray, t: np.ndarray | None = None) -> float:
    """Decision B78: the median |acc| over the samples of the quietest :data:`QUIET_FRACTION` (at least one) of
    the windows of ``t`` (s) :data:`QUIET_WINDOW_S` long, or 3 sample intervals when longer; without ``t`` (or
    with fewer than 3 samples) the whole file's median |acc|."""
    norm = np.linalg.norm(values, axis=1)
    if t is None or len(t) != len(norm) or len(norm) < 3:
        return float(np.median(norm))
    t = np.asarray(t, dtype=float)
    width = max(QUIET_WINDOW_S, 3.0 * float(np.median(np.diff(t))))
    idx = np.floor((t - t[0]) / width).astype(np.int64)
    cnt = np.bincount(idx)
    s1, s2 = np.bincount(idx, norm), np.bincount(idx, norm * norm)
    full = np.flatnonzero(cnt >= 3)
    if full.size == 0:
        return float(np.median(norm))
    m = s1[full] / cnt[full]
    sd = np.sqrt(np.maximum(s2[full] / cnt[full] - m * m, 0.0))
    k = max(1, int(np.ceil(QUIET_FRACTION * full.size)))
    quiet = full[np.argsort(sd, kind="stable")[:k]]
    return float(np.median(norm[np.isin(idx, quiet)]))


#: decision B97: a still accelerometer reads gravity; the median |acc| of its quietest windows (B78's
#: :func:`quiet_acc_norm`) over :data:`STANDARD_GRAVITY` must lie within [1 / this, this]. Seen on correctly scaled
#: units: 9.47-9.93 m/s^2 (-3.4 .. +1.2 %) on the 11 real foot and 12 lower-back recordings (datasets/real,
#: datasets/external), 9.58-10.26 (-2.3 .. +4.6 %) on the trial simulations of B78; but a foot with very short
#: foot-flats reads up to 1.30 g in its quietest windows (the hand-made feet of tests/test_steps_quiet*.py: 12.76-
#: 12.82 m/s^2), so a +-10 % band (the first candidate) refused correct files. A wrong full scale or counts-per-g
#: is a power of two (x0.5, x2, x2.048, ...), far outside x1.5; a 2.4 % slip (1024 counts/g read as mg) lies inside
#: the spread of correct units and cannot be told from them (decision B97, amended in the lead's merge).
GRAVITY_FACTOR_MAX = 1.5


def gravity_scale(rest_norm: float) -> float | None:
    """Decision B97: ``rest_norm`` (m/s^2, |acc| at rest) over gravity when it lies outside
    [1 / :data:`GRAVITY_FACTOR_MAX`, :data:`GRAVITY_FACTOR_MAX`], else ``None``."""
    scale = rest_norm / STANDARD_GRAVITY
    return scale if not 1.0 / GRAVITY_FACTOR_MAX <= scale <= GRAVITY_FACTOR_MAX else None


#: decision B97 (review of session 19): the mis-scales a wrong full scale or counts per g gives (powers of two,
#: 2048 or 4096 counts/g read as mg, g read as m/s^2 and back), named in the refusal instead of the measured ratio
#: when within 20 % of it: a waist walking without a pause has its quietest windows on the bounce's peaks (x0.5
#: measured as x0.593), so dividing by the measured ratio would leave the values 16 % off, inside B97's band
MISSCALES = tuple(sorted({2.0 ** k for k in range(-6, 7)} | {2.048, 1 / 2.048, 4.096, 1 / 4.096,
                                                              STANDARD_GRAVITY, 1 / STANDARD_GRAVITY}))


def likely_misscale(scale: float) -> float:
    """Decision B97: the :data:`MISSCALES` entry within 20 % of the measured ``scale`` (the nearest in log), else
    ``scale`` itself."""
    near = min(MISSCALES, key=lambda m: abs(math.log(scale / m)))
    return near if abs(math.log(scale / near)) <= math.log(1.2) else scale


#: decision B99: what an accelerometer file at rest reads per g in each common scale: MEMS sensitivities (LSB/g,
#: powers of two: 256 for the ADXL345 at +-16 g, thesis eq. 24; 2048 for an int16 at +-16 g; 16384 at +-2 g),
#: mg and mm/s^2
PER_G_SCALES = {**{2.0 ** k: f"a {2 ** k} LSB/g sensor" for k in range(6, 16)}, 1000.0: "mg",
                1000.0 * STANDARD_GRAVITY: "mm/s^2"}


def counts_per_g_hint(rest_norm: float) -> str:
    """Decision B99: how to convert an accelerometer file whose |acc| at rest is ``rest_norm`` (raw counts, mg or
    mm/s^2): at rest |acc| is 1 g, so ``rest_norm`` is the file's value per g; the :data:`PER_G_SCALES` entry
    within 5 % of it, if any, is named."""
    near = min(PER_G_SCALES, key=lambda k: abs(math.log(rest_norm / k))) if rest_norm > 0 else None
    guess = f" ({PER_G_SCALES[near]}?)" if near and abs(rest_norm / near - 1.0) <= 0.05 else ""
    return (f"at rest it reads about {rest_norm:.0f} per g{guess}: divide by the sensor's counts per g and multiply "
            f"by {STANDARD_GRAVITY} (mg: 1000 per g; mm/s^2: divide by 1000; thesis eq. 24's counts / 256 * 9.81 is "
            "the ADXL345 at +-16 g)")


def check_units(spec: SensorSpec, values: np.ndarray, where: str, declare: str | None = None,
                t: np.ndarray | None = None) -> None:
    """Detect values recorded in the wrong unit from their magnitudes and say how to convert.

    ``declare`` replaces the meta.json way of declaring the unit in the messages (``pdrlearn import``: its
    unit option, e.g. ``"pass --acc-unit g"``; decision B37); ``""`` leaves the conversion as the only fix
    (a :class:`~pdrlearn.io.Stream` built in Python, decision B49).

    The limits are physical: gravity dominates the median accelerometer norm; a MEMS gyroscope's
    full scale is 2000 deg/s = 34.9 rad/s (thesis Tables 5, 13); the Earth's field is 25-65 uT;
    ambient pressure is 300-1100 hPa (thesis Table 17). The accelerometer's magnitude is judged on its quietest
    windows of the timestamps ``t`` (s; decision B78, :func:`quiet_acc_norm`), so that vigorous motion (running)
    does not look like a unit mistake.
    """
    if values.size == 0:
        return
    if spec.kind == "accelerometer":
        check_gravity(values, where, t)
        whole = float(np.median(np.linalg.norm(values, axis=1)))
        med = quiet_acc_norm(values, t)  # B78: judged where the unit rests (|acc| ~ g), e.g. a running foot
        # B97: ~1 g at rest (quiet windows: a foot's foot-flat) or on the whole file's median (a waist that walks
        # without a pause: its quiet windows sit on the bounce's peaks, 11.7 m/s^2 for a +-2 m/s^2 sine)
        at_g = t is None or gravity_scale(med) is None or gravity_scale(whole) is None
        if 4.0 <= whole <= 25.0 and (at_g or not 4.0 <= med <= 25.0):
            return  # plausible on the whole file (before B78) and ~1 g at rest (B97; a quiet median off any scale
            # of g, gravity removed, is B30's / B36's)
        if 0.5 <= whole <= 2.0 or 0.5 <= med <= 2.0:  # the whole file's figure when it tells (as before B78)
            raise DataError(
                f"{where}: median |acc| is {whole if 0.5 <= whole <= 2.0 else med:.2f}, which looks like units of g; "
                f"multiply by {STANDARD_GRAVITY} to get m/s^2"
                + _or(declare, f"declare \"units\": {{\"{spec.name}\": \"g\"}} in meta.json")
            )
        if whole > 200 or med > 200:
            raise DataError(
                f"{where}: median |acc| is {whole if whole > 200 else med:.0f}, which looks like raw counts or mm/s^2; "
                f"convert to m/s^2: {counts_per_g_hint(med if t is not None else whole)}"
            )
        if not 4.0 <= med <= 25.0:
            raise DataError(f"{where}: median |acc| is {med:.2f} m/s^2 in its quietest windows "
                            "(gravity, 9.81 m/s^2, at rest), implausible for a body-worn unit; convert to m/s^2")
        scale = gravity_scale(med)
        if not at_g:
            suggest = likely_misscale(scale)  # decision B97: ~1 g at rest, else the values are mis-scaled
            raise DataError(
                f"{where}: at rest (its quietest windows) |acc| is {med:.2f} m/s^2, {scale:.3f} times gravity "
                f"({STANDARD_GRAVITY} m/s^2, x{1 / GRAVITY_FACTOR_MAX:.2f}-x{GRAVITY_FACTOR_MAX:g} allowed): "
                f"the values look {scale:.3f} times too "
                f"{'large' if scale > 1 else 'small'} (a wrong full scale or counts per g, e.g. counts at 2048/g read "
                f"as mg); divide them by {suggest:.4g}"
                + _or(declare, f"declare the unit that gives m/s^2 (\"units\": {{\"{spec.name}\": ...}}) in meta.json"))
    elif spec.kind == "gyroscope":
        p99 = float(np.percentile(np.abs(values), 99))
        if p99 > 40.0:
            raise DataError(
                f"{where}: 99th percentile |rate| is {p99:.0f}, beyond a 2000 deg/s gyroscope in rad/s; "
                f"the {'values look' if declare == '' else 'file looks'} like deg/s: multiply by pi/180"
                + _or(declare, f"declare \"units\": {{\"{spec.name}\": \"deg/s\"}} in meta.json")
            )
    elif spec.kind == "magnetometer":
        med = float(np.median(np.linalg.norm(values, axis=1)))
        if med < 1.0:
            raise DataError(f"{where}: median |B| is {med:.3f}; looks like gauss or tesla: convert to uT")
        if med > 5000.0:
            raise DataError(f"{where}: median |B| is {med:.0f}; looks like nT: divide by 1000 to get uT")
    elif spec.kind == "barometer":
        med = float(np.median(values))
        if med > 20000:
            raise DataError(f"{where}: median pressure {med:.0f} looks like Pa; divide by 100 to get hPa")
        if 30 <= med <= 110:
            raise DataError(f"{where}: median pressure {med:.1f} looks like kPa; multiply by 10 to get hPa")
        if not 300 <= med <= 1100:
            raise DataError(f"{where}: median pressure {med:.1f} hPa is outside 300-1100 hPa (thesis Table 17)")


#: largest ratio |mean acceleration vector| / median |acc| of an accelerometer file whose gravity has been removed
#: (decision B30). With gravity (the specific force of every IMU, README "Session folders") the mean vector is
#: gravity in the sensor frame and the ratio is 0.93-1.13 on every bundled, fetched and trial recording (foot and
#: lower back); gravity-removed ("linear acceleration", "free acceleration") exports average to ~0 in any unit:
#: 0.001-0.036 on the trial's foot and phone copies. 0.2 lies between (geometric middle 0.18).
GRAVITY_REMOVED_RATIO = 0.2


#: decision B45: what a user whose export holds linear acceleration can do (trial 12, finding 13)
GRAVITY_HINT = ("a phone export's 'total acceleration', or its linear acceleration plus its gravity columns, "
                "column by column")


#: decision B105: window (s) over which an accelerometer's mean vector is gravity in the unit's frame at that time
GRAVITY_WINDOW_S = 4.0


def _window_gravity(values: np.ndarray, t: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """Mean acceleration vector of each :data:`GRAVITY_WINDOW_S` window (or of each 200 samples without ``t``)
    and its start time (s from the first sample; NaN without ``t``)."""
    if t is not None and t.size == values.shape[0] and t[-1] > t[0]:
        idx = np.floor((t - t[0]) / GRAVITY_WINDOW_S).astype(np.int64)
    else:
        idx = np.arange(values.shape[0]) // 200
    cnt = np.bincount(idx)
    full = np.flatnonzero(cnt >= max(3, int(0.5 * np.median(cnt[cnt > 0]))))
    means = np.stack([np.bincount(idx, values[:, j])[full] / cnt[full] for j in range(3)], axis=1)
    start = full * GRAVITY_WINDOW_S if t is not None and t.size == values.shape[0] else np.full(full.size, np.nan)
    return means, start


def orientation_change(values: np.ndarray, t: np.ndarray | None = None) -> tuple[float, float] | None:
    """Decision B105: ``(time s, angle deg)``: the time of the largest turn of the gravity direction between
    consecutive :data:`GRAVITY_WINDOW_S` windows and the largest angle a window's gravity makes with the first's,
    when every window's mean vector is gravity (|mean| >= half the median |acc|, as in a recording with gravity:
    B30's 0.93-1.13) but the file's mean is not (B30's test fails): the unit was turned over during the session
    (a phone flipped in its holster), gravity was not removed. ``None`` when the windows' means are small too
    (gravity removed: B30's error stands)."""
    means, start = _window_gravity(values, t)
    if means.shape[0] < 2:
        return None
    med = float(np.median(np.linalg.norm(values, axis=1)))
    norms = np.linalg.norm(means, axis=1)
    if float(np.median(norms)) < 0.5 * med:
        return None
    u = means / np.maximum(norms, 1e-12)[:, None]
    ang = np.degrees(np.arccos(np.clip(np.sum(u[1:] * u[:-1], axis=1), -1.0, 1.0)))
    k = int(np.argmax(ang))
    # the angle: the largest any window's gravity makes with the first window's (a unit turned over and back, or a
    # turn spread over two windows, is not read as ~0 deg)
    return float(start[k + 1]), float(np.degrees(np.arccos(np.clip(float(np.min(u[1:] @ u[0])), -1.0, 1.0))))


def check_gravity(values: np.ndarray, where: str, t: np.ndarray | None = None) -> None:
    """Refuse an accelerometer file whose gravity has been removed (decision B30): its mean vector is ~0 in
    either unit (m/s^2 or g), while a specific force always averages to gravity (|mean| ~ median |acc|). Its
    median |acc| looked like units of g (0.80: "multiply by 9.80665", then +218 % distance) or passed (foot:
    -50 % distance without a word). A file whose every window holds gravity but whose gravity direction turned
    during the session (``t``: its times, s) is a unit turned over, not gravity removed: tracked, with one
    warning naming the time (decision B105, :func:`orientation_change`)."""
    if values.shape[0] < 10:
        return
    med = float(np.median(np.linalg.norm(values, axis=1)))
    mean = float(np.linalg.norm(values.mean(axis=0)))
    if med > 0 and mean < GRAVITY_REMOVED_RATIO * med:
        turned = orientation_change(values, t)
        if turned is not None:
            at = "" if math.isnan(turned[0]) else f" at about {turned[0]:.0f} s"
            log.warning("%s: the unit's orientation changed during the session%s (gravity turns by %.0f deg; "
                        "every %g s window holds it): tracked on, the heading and frame after it are less certain; "
                        "if the track looks wrong there, split the session at that time (decision B105)",
                        where, at, turned[1], GRAVITY_WINDOW_S)
            return
        raise DataError(
            f"{where}: the mean acceleration vector is {mean:.3g} against a median |acc| of {med:.3g}, so gravity has "
            "been removed (linear / free acceleration), or these columns are not an accelerometer (gyroscope "
            "columns?); pdrlearn needs the specific force: export the raw (total) accelerometer, gravity included"
            f" ({GRAVITY_HINT})"
        )


#: plausible native sampling rates of a body-worn sensor file (Hz): barometers log at >= 1 Hz, IMUs up to
#: a few hundred Hz (PLASYS 20 Hz, thesis ch.4.2.3; real recordings 100 and 204.8 Hz). Outside this band the
#: timestamps are in another unit than the reader assumed (docs/decisions/bad-input.md B9).
RATE_LIMITS_HZ = (0.5, 5000.0)


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


def time_unit_candidates(t_raw: np.ndarray, declared_rate_hz: float | None = None) -> list[tuple[str, float]]:
    """The units (``(unit, seconds per unit)``, ms first) in which raw timestamps give a plausible rate
    (:data:`RATE_LIMITS_HZ`) and, where ``meta.json`` declares a rate, that rate within 10 % (decision B22).
    Every unit when the timestamps say nothing (fewer than 3, or not increasing: :func:`check_timestamps`'s
    error)."""
    if t_raw.size < 3:
        return list(_TIME_UNITS)
    d = float(np.median(np.diff(t_raw)))
    if not np.isfinite(d) or d <= 0:
        return list(_TIME_UNITS)
    lo, hi = RATE_LIMITS_HZ
    return [(u, k) for u, k in _TIME_UNITS if lo <= 1.0 / (d * k) <= hi
            and (declared_rate_hz is None or abs(1.0 / (d * k) - declared_rate_hz) <= 0.1 * declared_rate_hz)]


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


def check_trajectory_times(t_raw: np.ndarray, scale: float, t_start: float, t_end: float, where: str) -> None:
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
    what = (f"{where}: its timestamps read as {unit} (the sensor files' unit) give {t0:.6g}-{t1:.6g} s at "
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
    if peaks.size == 0:
        return None
    best = int(peaks[np.argmax(ac[peaks])])
    if ac[best] < min_corr or best / fs >= RHYTHM_MIN_S:
        return None
    return best / fs


#: still stretches for :func:`check_imu_pair` (decision B36): |gyro| averaged over 0.25 s under 0.3 rad/s, at
#: least 1 s of them in all. Their median |acc| is 8.97-10.14 m/s^2 on every real recording (datasets/real,
#: gaitmap and mobgap, foot and lower back) and on simulated A-D, terrain, direction, rotations and standstill
#: (foot and waist, 20 and 100 Hz): with gravity a still sensor measures ~1 g. Outside 5-15 m/s^2 it is not a
#: specific force (gravity subtracted once as a vector, or a wrong unit).
STILL_GYRO_RAD_S, STILL_WINDOW_S, STILL_MIN_S = 0.3, 0.25, 1.0
STILL_ACC_RANGE = (5.0, 15.0)
#: a walking unit's gyroscope (|acc| varies, std > 0.5 m/s^2) turns faster than this at its 99th percentile
#: (rad/s): walking p99 |rate| is >= 4.75 (foot) and >= 0.57 (waist) on the real and simulated recordings above;
#: rad/s data read as deg/s is 57.3 times smaller (foot <= 0.22, lower back <= 0.04 on the same recordings).
WALKING_GYRO_P99 = {"foot": 0.5, "waist": 0.1}
WALKING_ACC_STD = 0.5


#: decision B40: the gyroscope's tilt rate against the accelerometer's. Both are averaged over 0.5 s (about one
#: step, so the step-frequency linear acceleration mostly cancels); the gravity direction g of the accelerometer
#: turns at |dg/dt| and the gyroscope predicts |w x g| (the part of the rotation that tilts; a turn about gravity
#: changes neither). Linear acceleration only adds to the accelerometer's side, so with the right unit the RMS ratio
#: acc/gyro is >= 1.16 on every real recording (datasets/real, datasets/external, /work/shared/data: gaitmap foot,
#: mobgap lower back, and the trial's 50 Hz and standing copies); deg/s read as rad/s divides it by 57.3: <= 0.074
#: on the same recordings. 0.3 lies between (geometric middle 0.29). Judged only when the gyroscope's tilt rate is
#: large (RMS over 0.5 rad/s = 29 deg/s): a still unit's gyroscope bias must not be compared with nothing.
TILT_WINDOW_S, TILT_RATIO_MIN, TILT_GYRO_RMS_MIN = 0.5, 0.3, 0.5


def tilt_rate_ratio(acc_t: np.ndarray, acc: np.ndarray, gyro_t: np.ndarray, gyro: np.ndarray) -> tuple[float, float]:
    """(RMS of the accelerometer's gravity-direction rate / RMS of the gyroscope's tilt rate, the latter in rad/s)
    over the recording, both averaged over :data:`TILT_WINDOW_S` (decision B40); ``(nan, nan)`` when too short."""
    fs = 1.0 / float(np.median(np.diff(gyro_t))) if gyro_t.size > 2 else 0.0
    w = int(round(TILT_WINDOW_S * fs)) if fs > 0 else 0
    if w < 2 or gyro.shape[0] < 4 * w:
        return float("nan"), float("nan")
    k = np.ones(w) / w
    a = np.column_stack([np.convolve(np.interp(gyro_t, acc_t, acc[:, j]), k, mode="valid") for j in range(3)])
    om = np.column_stack([np.convolve(gyro[:, j], k, mode="valid") for j in range(3)])
    norm = np.linalg.norm(a, axis=1)
    if not np.all(norm > 0):
        return float("nan"), float("nan")
    g = a / norm[:, None]
    dg = np.gradient(g, axis=0) * fs  # d g / dt of a world-fixed direction in the sensor frame = -w x g
    pred = np.cross(om, g)
    rms_g = float(np.sqrt(np.mean(np.sum(pred * pred, axis=1))))
    rms_a = float(np.sqrt(np.mean(np.sum(dg * dg, axis=1))))
    return (rms_a / rms_g if rms_g > 0 else float("nan")), rms_g


def check_imu_pair(acc_t: np.ndarray, acc: np.ndarray, gyro_t: np.ndarray, gyro: np.ndarray, placement: str,
                   where_acc: str, where_gyro: str, *, gyro_fix: str = "declare its unit",
                   acc_fix: str = "check its unit", gyro_big_fix: str = "declare its unit as deg/s") -> None:
    """One unit's accelerometer and gyroscope (SI) checked against each other (decisions B36, B37).

    B36: in still stretches (low gyro, measured in seconds) a sensor with gravity reads ~9.81 m/s^2; a median
    |acc| there outside :data:`STILL_ACC_RANGE` is refused (gravity removed although the mean vector passed
    B30, or a wrong unit). B37: a gyroscope whose 99th percentile |rate| is under
    :data:`WALKING_GYRO_P99` while the accelerometer shows movement is refused (rad/s data converted as deg/s).
    """
    if acc.shape[0] < 10 or gyro.shape[0] < 10:
        return
    an = np.linalg.norm(acc, axis=1)
    gn = np.linalg.norm(gyro, axis=1)
    if not (np.all(np.isfinite(an)) and np.all(np.isfinite(gn))):
        return
    p99 = float(np.percentile(gn, 99))
    astd = float(np.std(an))
    bound = WALKING_GYRO_P99.get(placement, 0.1)
    if astd > WALKING_ACC_STD and p99 < bound:
        raise DataError(
            f"{where_gyro}: the 99th percentile |rate| is {p99:.3g} rad/s while the accelerometer shows movement "
            f"(|acc| std {astd:.2g} m/s^2), far under a moving {placement}'s (over {bound:g} rad/s): the values "
            f"look like rad/s converted as deg/s (57.3 times too small); {gyro_fix}"
        )
    ratio, rms_tilt = tilt_rate_ratio(acc_t, acc, gyro_t, gyro)
    if rms_tilt > TILT_GYRO_RMS_MIN and ratio < TILT_RATIO_MIN:  # decision B40
        raise DataError(
            f"{where_gyro}: the gyroscope says the unit tilts at {rms_tilt:.3g} rad/s (RMS) but the accelerometer's "
            f"gravity direction turns {1 / ratio:.3g} times slower: the values look like deg/s read as rad/s "
            f"(57.3 times too large); {gyro_big_fix}"
        )
    fs = 1.0 / float(np.median(np.diff(gyro_t))) if gyro_t.size > 2 else 0.0
    if not fs > 0:
        return
    w = max(int(round(STILL_WINDOW_S * fs)), 1)
    smooth = np.convolve(gn, np.ones(w) / w, mode="same")
    still = smooth < STILL_GYRO_RAD_S
    if still.sum() / fs < STILL_MIN_S:
        return
    med = float(np.median(np.interp(gyro_t[still], acc_t, an)))
    lo, hi = STILL_ACC_RANGE
    if not lo <= med <= hi:
        raise DataError(
            f"{where_acc}: while the unit is still ({still.sum() / fs:.1f} s with |gyro| under "
            f"{STILL_GYRO_RAD_S:g} rad/s) the median |acc| is {med:.2f} m/s^2, not ~9.81 (gravity): gravity has been "
            "removed (linear / free acceleration), or the unit is wrong, or these columns are not an accelerometer "
            f"(gyroscope columns?); export the raw (total) accelerometer, gravity included ({GRAVITY_HINT}), "
            f"or {acc_fix}"
        )


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


#: decision B77: the smallest full scale of a body-worn accelerometer / gyroscope (2 g: MEMS ranges are +-2, 4, 8,
#: 16 g; 250 deg/s: +-250 ... 2000 deg/s, thesis Tables 5, 13). An axis's extreme value at or beyond it, held by
#: :data:`CLIP_RUN` or more consecutive samples, is a clipped (saturated) reading (3: a smooth peak sampled
#: symmetrically and rounded repeats its top value twice).
CLIP_LEVEL = {"accelerometer": 2.0 * STANDARD_GRAVITY, "gyroscope": float(np.deg2rad(250.0))}
CLIP_RUN = 3


def clipped_samples(values: np.ndarray, kind: str) -> tuple[int, float]:
    """Decision B77: (number of samples with a clipped axis, the largest clipped |value|) of an accelerometer
    or gyroscope file: on each axis, the samples equal to the axis's maximum (or minimum) over the file, where
    that extreme is at least :data:`CLIP_LEVEL` in magnitude, in runs of :data:`CLIP_RUN` or more equal
    consecutive samples (a sensor at its full scale repeats it; a real peak is not held)."""
    level = CLIP_LEVEL.get(kind)
    v = np.asarray(values, dtype=float)
    if level is None or v.ndim != 2 or v.shape[0] < CLIP_RUN:
        return 0, 0.0
    hit = np.zeros(v.shape[0], dtype=bool)
    top = 0.0
    for j in range(v.shape[1]):
        col = v[:, j]
        for ext in (col.max(), col.min()):
            if not abs(ext) >= level:
                continue
            at = col == ext
            # runs of equal extreme samples: a sample counts when its run is CLIP_RUN long or more
            edges = np.diff(np.concatenate([[0], at.astype(np.int8), [0]]))
            starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
            for a, b in zip(starts, ends, strict=True):
                if b - a >= CLIP_RUN:
                    hit[a:b] = True
                    top = max(top, abs(float(ext)))
    return int(hit.sum()), top


def saturation_warning(where: str, kind: str, n: int, total: int, top: float) -> str:
    """Decision B77's one line: the file, the fraction of clipped samples and what it does to the results."""
    unit = "m/s^2" if kind == "accelerometer" else "rad/s"
    rng = f"{top / STANDARD_GRAVITY:.3g} g" if kind == "accelerometer" else f"{np.rad2deg(top):.4g} deg/s"
    effect = ("the foot's integrated stride lengths and the step detector's impact peaks are cut short"
              if kind == "accelerometer" else "the integrated attitude and heading lose the rotation beyond it")
    return (f"{where}: {n} of {total} samples ({100.0 * n / total:.2g} %) are clipped at +-{top:.4g} {unit} (the "
            f"sensor's full scale, held for {CLIP_RUN}+ samples): {effect}, so distances and headings come out "
            f"wrong there; record with a range above +-{rng} (decision B77)")
