"""Unit and plausibility checks of accelerometer and gyroscope values, numpy only (decisions B30, B78, B97, B99,
B105; B91's swing rule): run by :mod:`pdrlearn.io.validate` on session files and sessions in memory and by the
streaming :class:`pdrlearn.runtime.Tracker` on the first seconds of a stream (decision B119), one implementation."""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING

import numpy as np

from pdrlearn.errors import DataError, GravityRemovedError

if TYPE_CHECKING:
    from pdrlearn.io.sensors import SensorSpec

STANDARD_GRAVITY = 9.80665  # m/s^2 (thesis ch.4.2.1.1)

log = logging.getLogger(__name__)

#: decision B37: a unit moves when the sd of its |acc| exceeds this (m/s^2; B119: a gyroscope's unit is judged
#: on a window of movement)
WALKING_ACC_STD = 0.5


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


def count_unit(rest_norm: float) -> str:
    """Decision B314: the declared unit (meta.json ``units``, ``import --acc-unit``; B100's count size) that reads an
    accelerometer file whose |acc| at rest is ``rest_norm`` as m/s^2: ``"mg"``, ``"0.001 m/s^2"`` (mm/s^2) or
    ``"1/N g"`` with N the :data:`PER_G_SCALES` sensitivity within 5 % of it, else N the reading itself."""
    near = min(PER_G_SCALES, key=lambda k: abs(math.log(rest_norm / k))) if rest_norm > 0 else None
    if near is not None and abs(rest_norm / near - 1.0) <= 0.05:
        if near == 1000.0:
            return "mg"
        if near == 1000.0 * STANDARD_GRAVITY:
            return "0.001 m/s^2"
        return f"1/{near:.0f} g"
    return f"1/{rest_norm:.0f} g"


#: the 99th percentile |rate| over which a gyroscope in rad/s is read as deg/s: a 2000 deg/s sensor's full scale is
#: 34.9 rad/s (thesis Tables 5, 13)
GYRO_RAD_S_MAX = 40.0
#: decision E298: this many samples over GYRO_RAD_S_MAX (any axis) in a gyroscope's window so far are deg/s, before
#: the window is whole: a foot in deg/s swings past 40 in its first stride while a standing start keeps the window's
#: 99th percentile low; three, so that one or two corrupt samples (B425's) do not decide it
GYRO_EARLY_SAMPLES = 3


def gyro_in_deg(values: np.ndarray) -> str:
    """Decision E298: the reason a gyroscope window so far is deg/s (:data:`GYRO_EARLY_SAMPLES` samples or more
    with an axis over :data:`GYRO_RAD_S_MAX`), or ``""``."""
    over = np.abs(values).max(axis=1) > GYRO_RAD_S_MAX if values.ndim == 2 else np.abs(values) > GYRO_RAD_S_MAX
    n = int(np.count_nonzero(over))
    if n < GYRO_EARLY_SAMPLES:
        return ""
    return (f"{n} samples turn faster than {GYRO_RAD_S_MAX:g} (up to {float(np.abs(values).max()):.0f}), beyond a "
            "2000 deg/s gyroscope in rad/s; the values look like deg/s: multiply by pi/180 (decision E298)")


def check_units(spec: SensorSpec, values: np.ndarray, where: str, declare: str | None = None,
                t: np.ndarray | None = None, factor: float = 1.0) -> None:
    """Detect values recorded in the wrong unit from their magnitudes and say how to convert.

    ``declare`` replaces the meta.json way of declaring the unit in the messages (``pdrlearn import``: its
    unit option, e.g. ``"pass --acc-unit g"``; decision B37); ``""`` leaves the conversion as the only fix
    (a :class:`~pdrlearn.io.Stream` built in Python, decision B49).

    The limits are physical: gravity dominates the median accelerometer norm; a MEMS gyroscope's
    full scale is 2000 deg/s = 34.9 rad/s (thesis Tables 5, 13); the Earth's field is 25-65 uT;
    ambient pressure is 300-1100 hPa (thesis Table 17). The accelerometer's magnitude is judged on its quietest
    windows of the timestamps ``t`` (s; decision B78, :func:`quiet_acc_norm`), so that vigorous motion (running)
    does not look like a unit mistake. ``factor``: the declared unit's factor the file's values were multiplied
    by (``import --acc-unit``); the counts-per-g hint and the suggested declaration are worked out from the file's
    own values (decision B314 amended, review R2).
    """
    if values.size == 0:
        return
    if spec.kind == "accelerometer":
        check_gravity(values, where, t)
        whole = float(np.median(np.linalg.norm(values, axis=1)))
        med = quiet_acc_norm(values, t)  # B78: judged where the unit rests (|acc| ~ g), e.g. a running foot
        # B97: ~1 g at rest (quiet windows: a foot's foot-flat) or on the whole file's median (a waist that walks
        # without a pause: its quiet windows sit on the bounce's peaks, 11.7 m/s^2 for a +-2 m/s^2 sine)
        absent = rest_without_gravity(whole, med)  # decision B202: ~0 g at rest, before the g and scale readings
        if absent is not None:
            raise GravityRemovedError(gravity_absent_message(where, whole, med, absent))
        at_g = t is None or gravity_scale(med) is None or gravity_scale(whole) is None
        if 4.0 <= whole <= 25.0 and (at_g or not 4.0 <= med <= 25.0):
            return  # plausible on the whole file (before B78) and ~1 g at rest (B97; a quiet median off any scale
            # of g, gravity removed, is B30's / B202's, above)
        if 0.5 <= whole <= 2.0 or 0.5 <= med <= 2.0:  # the whole file's figure when it tells (as before B78)
            raise DataError(
                f"{where}: median |acc| is {whole if 0.5 <= whole <= 2.0 else med:.2f}, which looks like units of g; "
                f"multiply by {STANDARD_GRAVITY} to get m/s^2"
                + _or(declare, f"declare \"units\": {{\"{spec.name}\": \"g\"}} in meta.json")
            )
        if whole > 200 or med > 200:
            rest = (med if t is not None else whole) / abs(factor)  # B314 amended: the file's raw values
            guess = count_unit(rest)  # decision B314: the declaration that reads the file as it is
            raise DataError(
                f"{where}: median |acc| is {whole if whole > 200 else med:.0f}, which looks like raw counts or mm/s^2; "
                f"convert to m/s^2: {counts_per_g_hint(rest)}"
                + _or(declare, f"declare \"units\": {{\"{spec.name}\": \"{guess}\"}} in meta.json (decision B314)")
                + ("" if not declare else f" (here: {guess}; decision B314)" if f"| {guess})" in declare
                    else f" or \"{guess}\" (the unit of one count, decisions B313, B314)")
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
        if p99 > GYRO_RAD_S_MAX:
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
        def header(unit: str) -> str:  # decision B289: import converts a column whose header names its unit
            return ("" if not declare else f", or name the unit in the column's header, e.g. 'pressure ({unit})', "
                    f"which import converts (decision B289), or {declare}")

        if med > 20000:
            raise DataError(f"{where}: median pressure {med:.0f} looks like Pa; divide by 100 to get hPa"
                            + header("Pa"))
        if 30 <= med <= 110:
            raise DataError(f"{where}: median pressure {med:.1f} looks like kPa; multiply by 10 to get hPa"
                            + header("kPa"))
        if not 300 <= med <= 1100:
            raise DataError(f"{where}: median pressure {med:.1f} hPa is outside 300-1100 hPa (thesis Table 17)")


#: decision B202: the most an accelerometer reads at rest, in g, when its gravity has been removed. The rest reading is
#: B78's quietest windows' median |acc| (:func:`quiet_acc_norm`), in g in the unit the whole file's median |acc| fits
#: (D4's m/s^2 band 4-25; otherwise read as g, the larger reading). Correct units read 0.967-1.008 g at their
#: foot-flats (B133, 11 real feet) and -3.4 .. +4.6 % off 1 g in their quietest windows (B97); a x0.5 mis-scale
#: (B97's message) reads 0.5 g.
#: The trial `fuzz` copies with each axis's median subtracted read 0.079 g (sim D foot), 0.043 g (gaitmap foot) and
#: 0.035 g as m/s^2 (mobgap lower back; 0.34 if its 1.15 median were g), their mean vectors 0.35-0.58 of the median
#: |acc| (above B30's 0.2). 0.4 g lies between 0.35 and 0.5, and 4 m/s^2 is the floor of D4's m/s^2 band.
REST_G_MIN = 0.4


def rest_without_gravity(whole: float, quiet: float) -> float | None:
    """Decision B202: the rest reading in g (``quiet``, :func:`quiet_acc_norm`, over gravity in the unit the whole
    file's median |acc| ``whole`` fits: m/s^2 in 4-25; otherwise read as g, the larger of the two readings: a walk
    with long pauses has its whole median under 4 once gravity is removed) when it is under :data:`REST_G_MIN`: at
    rest an accelerometer reads gravity, so this one's has been removed. None otherwise, and for a file of zeros
    (B123's line)."""
    if not whole > 0:
        return None  # all zeros: B123's line
    rest = quiet / STANDARD_GRAVITY if 4.0 <= whole <= 25.0 else quiet  # else the larger reading (as g)
    return rest if rest < REST_G_MIN else None


def gravity_absent_message(where: str, whole: float, quiet: float, rest_g: float) -> str:
    """Decision B202's one line (B30's fix: what to export)."""
    as_g = "" if 4.0 <= whole <= 25.0 else f" (read as g; as m/s^2 {quiet / STANDARD_GRAVITY:.4f} g)"
    return (f"{where}: the accelerometer reads ~0 g at rest: {rest_g:.3f} g{as_g} in its quietest windows against a "
            f"median |acc| of {whole:.3g} over the file, where a still accelerometer reads 1 g: gravity removed "
            "(linear / free acceleration)? pdrlearn needs the specific force: record raw acceleration, gravity "
            f"included ({GRAVITY_HINT}), or check that these columns are an accelerometer (decision B202)")


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


def gravity_removed(values: np.ndarray, where: str, t: np.ndarray | None = None) -> tuple[float, float] | None:
    """Decision B30's test: ``(|mean acceleration vector|, median |acc|)`` of an accelerometer file whose gravity
    has been removed (the mean under :data:`GRAVITY_REMOVED_RATIO` of the median, and not a unit turned over,
    B105's :func:`orientation_change`, which warns here), else None. Shared by :func:`check_gravity` and
    ``pdrlearn import`` (decision B164, which names a phone app's files with gravity)."""
    if values.shape[0] < 10:
        return None
    med = float(np.median(np.linalg.norm(values, axis=1)))
    mean = float(np.linalg.norm(values.mean(axis=0)))
    if not (med > 0 and mean < GRAVITY_REMOVED_RATIO * med):
        return None
    turned = orientation_change(values, t)
    if turned is not None:
        at = "" if math.isnan(turned[0]) else f" at about {turned[0]:.0f} s"
        log.warning("%s: the unit's orientation changed during the session%s (gravity turns by %.0f deg; "
                    "every %g s window holds it): tracked on, the heading and frame after it are less certain; "
                    "if the track looks wrong there, split the session at that time (decision B105)",
                    where, at, turned[1], GRAVITY_WINDOW_S)
        return None
    return mean, med


def gravity_removed_message(where: str, mean: float, med: float, fix: str | None = None) -> str:
    """B30's one line for :func:`gravity_removed`'s numbers, ending with ``fix`` (default: what to export,
    :data:`GRAVITY_HINT`)."""
    return (f"{where}: the mean acceleration vector is {mean:.3g} against a median |acc| of {med:.3g}, so gravity has "
            "been removed (linear / free acceleration), or these columns are not an accelerometer (gyroscope "
            "columns?); pdrlearn needs the specific force: "
            + (fix or f"export the raw (total) accelerometer, gravity included ({GRAVITY_HINT})"))


def check_gravity(values: np.ndarray, where: str, t: np.ndarray | None = None) -> None:
    """Refuse an accelerometer file whose gravity has been removed (decision B30): its mean vector is ~0 in
    either unit (m/s^2 or g), while a specific force always averages to gravity (|mean| ~ median |acc|). Its
    median |acc| looked like units of g (0.80: "multiply by 9.80665", then +218 % distance) or passed (foot:
    -50 % distance without a word). A file whose every window holds gravity but whose gravity direction turned
    during the session (``t``: its times, s) is a unit turned over, not gravity removed: tracked, with one
    warning naming the time (decision B105, :func:`orientation_change`)."""
    removed = gravity_removed(values, where, t)
    if removed is not None:
        raise GravityRemovedError(gravity_removed_message(where, *removed))



#: decision B425: the largest |value| of one axis a sensor of each kind can report, in the SI unit of
#: :class:`~pdrlearn.io.sensors.SensorSpec` (``unit``), beyond any body-worn sensor's full scale: 2000 m/s^2
#: (204 g, above the +-200 g of a high-g MEMS accelerometer such as the ADXL375, 1961 m/s^2; the thesis's foot
#: ADXL345 measures +-16 g, thesis Table 3); 100 rad/s (5730 deg/s, above the +-4000 deg/s of the widest MEMS
#: gyroscopes; thesis Tables 5, 13: 2000 deg/s = 34.9 rad/s); 1e4 uT (100 gauss, above a MEMS magnetometer's
#: +-4900 uT; the Earth's field is 25-65 uT); 2000 hPa (ambient pressure is 300-1100 hPa, thesis Table 17); force
#: 1e7 (N, or a force sensor's counts: a 24-bit ADC's 8.4e6). A sample beyond these is a corrupt value, not a
#: reading: 1e308 overflowed the step detectors (trial T1 F3, session 42)
VALUE_LIMITS = {"accelerometer": 2000.0, "gyroscope": 100.0, "magnetometer": 1e4, "barometer": 2000.0,
                "force": 1e7}


def out_of_range(kind: str, values: np.ndarray, factor: float = 1.0) -> np.ndarray:
    """Decision B425: the rows of ``values`` (as written, before the declared unit's ``factor`` to SI) with an axis
    beyond :data:`VALUE_LIMITS` once converted; compared as ``|value| > limit / |factor|``, so that no product
    overflows (a non-finite value is B9's matter, not counted here)."""
    values = np.asarray(values, dtype=float)
    limit = VALUE_LIMITS.get(kind)
    if limit is None or values.size == 0 or not factor:
        return np.zeros(0, dtype=np.intp)
    big = (np.abs(values) > limit / abs(factor)) & np.isfinite(values)  # inf: B9's line (decision B431)
    return np.flatnonzero(big.any(axis=1) if big.ndim == 2 else big)


def out_of_range_message(where: str, spec: SensorSpec, values: np.ndarray, rows: np.ndarray, factor: float = 1.0,
                         first_line: int = 2, t: np.ndarray | None = None,
                         columns: tuple[str, ...] | None = None) -> str:
    """Decision B425's one line for :func:`out_of_range`'s ``rows`` of a sensor file ``where``: how many rows, the
    first row's line (``first_line``: the line of row 0) and value as written, and the limit. ``t``: the samples'
    timestamps (s) of a live push instead of a file (decision B435): the first sample's time instead of a line.
    ``columns``: the file's own names of the value columns (``pdrlearn import``'s export, decision B436), else the
    sensor's x, y, z."""
    row = int(rows[0])
    vals = np.asarray(values, dtype=float)
    vals = vals[row] if vals.ndim == 2 else vals[row:row + 1]
    axis = int(np.argmax(np.abs(vals)))
    conv = "" if factor == 1.0 else f" ({vals[axis]:g} x {factor:g} in {spec.unit})"
    what, at, fix = (("row(s)", f"line {row + first_line}", "remove or repair those rows") if t is None else
                     ("sample(s)", f"t = {float(t[row]):.3f} s", "drop those samples before pushing"))
    name = (columns or spec.columns)[axis]
    return (f"{where}: {rows.size} {what} with a value beyond any {spec.kind}'s range (first at {at}: "
            f"{name} = {vals[axis]:g}{conv}; the limit is {VALUE_LIMITS[spec.kind]:g} {spec.unit}, "
            f"decision B425): a corrupt sample; {fix}")



def data_row_lines(lines: list[str], header_lines: int = 1) -> list[int]:
    """The 1-based file line of each data row of a CSV's ``lines``: the non-blank lines after the ``header_lines``
    (the header, and a B66 ``sep=`` line before it), as pandas and the lean reader skip blank lines, so that B425's
    line is the line an editor shows (decision B431's counting, shared with the full reader: review R2 finding 4)."""
    return [i + 1 for i, line in enumerate(lines) if i >= header_lines and line.strip()]

#: B91: the percentile of |gyro| (rad/s) that tells a swinging foot from a waist
SWING_PERCENTILE = 99.0
#: B91: a foot unit whose percentile stays below this never swung (rad/s; walking feet measured >= 6.2)
FOOT_NO_SWING = 3.0
#: B91: a waist unit whose percentile exceeds this swung like a foot (rad/s; walking waists measured <= 2.4)
WAIST_SWINGS = 4.0
#: B91: relative tolerance of "the same data" (magnitudes, so that another declared frame does not hide it)
SAME_RTOL = 1e-6


def swing_rate(values: np.ndarray) -> float:
    """The 99th percentile of the gyroscope magnitude (rad/s) of an (n, 3) array; nan when empty."""
    v = np.asarray(values, dtype=float)
    if v.ndim != 2 or len(v) == 0:
        return float("nan")
    return float(np.nanpercentile(np.linalg.norm(v, axis=1), SWING_PERCENTILE))


def swapped_units(foot_rate: float, waist_rate: float) -> bool:
    """Decision B91: a foot unit that never swung (:func:`swing_rate` under :data:`FOOT_NO_SWING`) beside a waist
    unit that swung like a foot (over :data:`WAIST_SWINGS`): the two units' data are swapped."""
    return foot_rate < FOOT_NO_SWING and waist_rate > WAIST_SWINGS


#: decision B120: a 3-axis sensor whose consecutive samples are bit-identical on every axis for this long (s) has
#: frozen (a stuck driver or link re-sending its last value). A body-worn MEMS sensor's noise changes some axis
#: every sample: the longest identical run on the 11 real foot and 12 lower-back recordings (datasets/real,
#: datasets/external) is 3 samples (0.02 s), on simulated sessions (scenario D at 20 Hz, 30 s standing at 20 and
#: 100 Hz, the trial's calibration walks) 3 samples (0.05 s). 2 s is twice B11's 1 s gap, after which a stride
#: moves 0 m (a frozen sensor is a gap that looks like data), and leaves room for a coarsely quantised unit at rest.
FROZEN_S = 2.0


#: decision B120 (amended, review 2): a run of identical samples is a frozen sensor only while the unit moves, by its
#: other sensor's evidence: a coarsely quantised accelerometer at rest repeats its reading for seconds (10-bit
#: +-16 g, 31 mg/LSB, with 1.5 mg noise: runs up to 8.1 s), as a frozen one does; a moving unit changes every sensor
FROZEN_PARTNER = {"fAccelerometer": "fGyroscope", "fGyroscope": "fAccelerometer", "wAccelerometer": "wGyroscope",
                  "wGyroscope": "wAccelerometer", "wMagneticField": "wGyroscope"}
#: decision B405: the partner sensor must show movement on this many samples of a run for it to be a frozen sensor
#: (B77's count): one or two transient samples, such as a decimation filter's edge at a file's first or last sample,
#: are not motion, while a walking unit moves on dozens
FROZEN_MOVING_MIN = 3
#: decision B405 (amended): the partner's movement counts only this far (s) inside a run's ends: a coarsely quantised
#: unit starts and stops moving there, and a decimation filter's edge transient sits at a file's ends
FROZEN_EDGE_S = 0.5
#: a gyroscope sample shows movement over this rate (rad/s): above B36's still 0.3 rad/s and a standing body's sway
MOVING_RPS = 0.5
#: an accelerometer sample shows movement when |acc| is this far from gravity (m/s^2): twice B37's walking sd
#: (0.5), over 3 steps of a 31 mg/LSB accelerometer at rest
MOVING_ACC = 2 * WALKING_ACC_STD


def moving_samples(name: str, values, margin: float = 0.0) -> np.ndarray:
    """Decision B120: which samples of stream ``name`` (n, 3) show the unit moving (:data:`MOVING_RPS`,
    :data:`MOVING_ACC`, widened by ``margin``); a magnetometer shows none."""
    v = np.asarray(values, dtype=float)
    return np.asarray(moving_norm(name, np.linalg.norm(v.reshape(len(v), -1), axis=1), margin), dtype=bool)


def quantisation_margin(step: float) -> float:
    """Decision B405: the largest error rounding to a 3-axis sensor's ``step`` makes in a sample's norm
    (half a step on each axis: sqrt(3) / 2 steps)."""
    return 0.5 * math.sqrt(3.0) * step


def moving_norm(name: str, norm, margin: float = 0.0):
    """:func:`moving_samples` on the samples' norms (an array, or one float: the tracker's one-sample path);
    ``margin`` (decision B405) widens the thresholds by the sensor's own quantisation."""
    if name.endswith("Gyroscope"):
        return norm > MOVING_RPS + margin
    if name.endswith("Accelerometer"):
        return abs(norm - STANDARD_GRAVITY) > MOVING_ACC + margin
    return norm != norm  # a magnetometer: no evidence (False; NaN never comes, the push checks it)


def identical_runs(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Decision B120: the first and last row (inclusive) of every maximal run of bit-identical consecutive rows
    of ``values`` (n, k), a row unlike both neighbours a run of one; the one run splitting of
    :func:`frozen_spans` (offline) and :class:`pdrlearn.runtime.guard.FrozenWatch` (live, per push)."""
    v = np.asarray(values)
    n = v.shape[0]
    cut = np.flatnonzero(np.any(v[1:] != v[:-1], axis=1)) + 1  # rows that differ from the row before
    return np.concatenate(([0], cut)), np.concatenate((cut - 1, [n - 1]))


def frozen_spans(t: np.ndarray, values: np.ndarray, min_s: float = FROZEN_S) -> list[tuple[float, float, int]]:
    """Decision B120: ``(first time, last time, samples)`` of each run of bit-identical consecutive rows of
    ``values`` (n, k) lasting ``min_s`` seconds or more (by ``t``, s)."""
    v = np.asarray(values)
    if v.ndim != 2 or v.shape[0] < 2:
        return []
    starts, ends = identical_runs(v)
    keep = (ends > starts) & ((t[ends] - t[starts]) >= min_s)
    return [(float(t[a]), float(t[b]), int(b - a + 1)) for a, b in zip(starts[keep], ends[keep], strict=True)]


def frozen_message(where: str, first: float, last: float, n: int, values, ongoing: bool = False) -> str:
    """Decision B120's one line: the sensor, the span and the value it repeats."""
    vals = ", ".join(f"{x:.4g}" for x in np.asarray(values, dtype=float).ravel())
    span = (f"since {first:.2f} s ({last - first:.1f} s so far)" if ongoing
            else f"for {last - first:.1f} s ({first:.2f}-{last:.2f} s)")
    return (f"{where}: {n} identical consecutive samples ({vals}) {span}: the sensor looks frozen (stuck, no "
            f"noise; real sensors repeat at most a few samples), so the strides over it are wrong; check the sensor "
            f"and its link (decision B120)")


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


#: decision B40: the gyroscope's tilt rate against the accelerometer's. Both are averaged over 0.5 s (about one
#: step, so the step-frequency linear acceleration mostly cancels); the gravity direction g of the accelerometer
#: turns at |dg/dt| and the gyroscope predicts |w x g| (the part of the rotation that tilts; a turn about gravity
#: changes neither). Linear acceleration only adds to the accelerometer's side, so with the right unit the RMS ratio
#: acc/gyro is >= 1.16 on every real recording (datasets/real, datasets/external, /work/shared/data: gaitmap foot,
#: mobgap lower back, and the trial's 50 Hz and standing copies); deg/s read as rad/s divides it by 57.3: <= 0.074
#: on the same recordings. 0.3 lies between (geometric middle 0.29). Judged only when the gyroscope's tilt rate is
#: large (RMS over 0.5 rad/s = 29 deg/s): a still unit's gyroscope bias must not be compared with nothing.
TILT_WINDOW_S, TILT_RATIO_MIN, TILT_GYRO_RMS_MIN = 0.5, 0.3, 0.5


def tilt_rate_ratio(acc_t: np.ndarray, acc: np.ndarray, gyro_t: np.ndarray, gyro: np.ndarray, *,
                    block_rows: int = 1 << 16) -> tuple[float, float]:
    """(RMS of the accelerometer's gravity-direction rate / RMS of the gyroscope's tilt rate, the latter in rad/s)
    over the recording, both averaged over :data:`TILT_WINDOW_S` (decision B40); ``(nan, nan)`` when too short.
    Decision B476: summed over blocks of ``block_rows`` averaged samples (each with its neighbours, so the rates are
    those of the whole array), so that ``read_session`` of a day-long recording holds a block's arrays, not the
    day's."""
    fs = 1.0 / float(np.median(np.diff(gyro_t))) if gyro_t.size > 2 else 0.0
    w = int(round(TILT_WINDOW_S * fs)) if fs > 0 else 0
    if w < 2 or gyro.shape[0] < 4 * w:
        return float("nan"), float("nan")
    k = np.ones(w) / w
    m = gyro.shape[0] - w + 1  # averaged samples ("valid" convolution)
    sum_g = sum_a = 0.0
    for j0 in range(0, m, max(int(block_rows), 2)):
        j1 = min(j0 + max(int(block_rows), 2), m)
        e0, e1 = max(j0 - 1, 0), min(j1 + 1, m)  # one averaged neighbour each side: np.gradient's central difference
        sl = slice(e0, e1 + w - 1)
        a = np.column_stack([np.convolve(np.interp(gyro_t[sl], acc_t, acc[:, i]), k, mode="valid") for i in range(3)])
        om = np.column_stack([np.convolve(gyro[sl, i], k, mode="valid") for i in range(3)])
        norm = np.linalg.norm(a, axis=1)
        if not np.all(norm > 0):
            return float("nan"), float("nan")
        g = a / norm[:, None]
        dg = np.gradient(g, axis=0)[j0 - e0:j1 - e0] * fs  # d g / dt of a world-fixed direction = -w x g
        pred = np.cross(om[j0 - e0:j1 - e0], g[j0 - e0:j1 - e0])
        sum_g += float(np.sum(pred * pred))
        sum_a += float(np.sum(dg * dg))
    rms_g, rms_a = math.sqrt(sum_g / m), math.sqrt(sum_a / m)
    return (rms_a / rms_g if rms_g > 0 else float("nan")), rms_g


def check_tilt_rate(acc_t: np.ndarray, acc: np.ndarray, gyro_t: np.ndarray, gyro: np.ndarray, where: str,
                    fix: str) -> float:
    """Decision B40: refuse a gyroscope (``gyro``, read as rad/s) whose tilt rate is more than
    1 / :data:`TILT_RATIO_MIN` times the accelerometer's gravity-direction rate (:func:`tilt_rate_ratio`) while it
    tilts at over :data:`TILT_GYRO_RMS_MIN` rad/s RMS: deg/s read as rad/s. One line naming ``where`` and ``fix``.
    Import runs it (:func:`check_imu_pair`), and decision B476 ``read_session`` on a session folder's lower back.
    Returns the ratio (NaN when too short to judge)."""
    ratio, rms_tilt = tilt_rate_ratio(acc_t, acc, gyro_t, gyro)
    if rms_tilt > TILT_GYRO_RMS_MIN and ratio < TILT_RATIO_MIN:  # decision B40
        raise DataError(
            f"{where}: the gyroscope says the unit tilts at {rms_tilt:.3g} rad/s (RMS) but the accelerometer's "
            f"gravity direction turns {1 / ratio:.3g} times slower: the values look like deg/s read as rad/s "
            f"(57.3 times too large); {fix}"
        )
    return ratio


def check_imu_pair(acc_t: np.ndarray, acc: np.ndarray, gyro_t: np.ndarray, gyro: np.ndarray, placement: str,
                   where_acc: str, where_gyro: str, *, gyro_fix: str = "declare its unit",
                   acc_fix: str = "check its unit", gyro_big_fix: str = "declare its unit as deg/s") -> None:
    """One unit's accelerometer and gyroscope (SI) checked against each other (decisions B36, B37).

    B36: in still stretches (low gyro, measured in seconds) a sensor with gravity reads ~9.81 m/s^2; a median
    |acc| there outside :data:`STILL_ACC_RANGE` is refused (gravity removed although the mean vector passed
    B30, or a wrong unit). B37: a gyroscope whose 99th percentile |rate| is under
    :data:`WALKING_GYRO_P99` while the accelerometer shows movement is refused (rad/s data converted as deg/s);
    both figures are the whole recording's (B257's largest-block figures withdrawn: they refuse a still, noisy unit).
    """
    if acc.shape[0] < 10 or gyro.shape[0] < 10:
        return
    an = np.linalg.norm(acc, axis=1)
    gn = np.linalg.norm(gyro, axis=1)
    if not (np.all(np.isfinite(an)) and np.all(np.isfinite(gn))):
        return
    p99 = float(np.percentile(gn, 99))
    astd = float(np.std(an))  # whole-recording figures (decision B257: the largest 10 s block's withdrawn)
    bound = WALKING_GYRO_P99.get(placement, 0.1)
    if astd > WALKING_ACC_STD and p99 < bound:
        raise DataError(
            f"{where_gyro}: the 99th percentile |rate| is {p99:.3g} rad/s while the accelerometer shows movement "
            f"(|acc| std {astd:.2g} m/s^2), far under a moving {placement}'s (over {bound:g} rad/s): the values "
            f"look like rad/s converted as deg/s (57.3 times too small); {gyro_fix}"
        )
    check_tilt_rate(acc_t, acc, gyro_t, gyro, where_gyro, gyro_big_fix)  # decision B40
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
