"""One-CSV lab exports -> a session (decision D12 in docs/decisions.md): ``pdrlearn import``'s library side.

A lab export holds one timestamp column and several channel columns under names of its own (``Time (ms)``,
``AccX (g)``, ``gyr_x``, ``Accelerometer X`` ...). :func:`import_csv` reads it with the session reader's own
CSV reader (comma, semicolon or tab separated, decimal commas: decision B24), maps its columns to one unit's
sensor streams (given, or guessed from common names), converts time and values to the project's units
(given, from unit hints in the header, or for time from B22's inference) and returns a :class:`Session`
plus a record of every choice, which the command prints and writes to ``meta.json`` (``"imported"``).
Nothing is guessed silently: each guess is in that record, and a column that cannot be mapped is a one-line
error naming the columns the file has.
"""

from __future__ import annotations

import logging
import math
import os
import re
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError, OptionFixError
from pdrlearn.io.datetimes import dst_jump, dst_message, exact_seconds, localize, offset_text
from pdrlearn.io.frames import AxisFrame, right_handed
from pdrlearn.io.matfile import expand_columns, mat_arrays_text, mat_message, mat_version, read_mat_table
from pdrlearn.io.plasys import (
    _TIME_ALIASES,
    _TIME_SCALE,
    GRAVITY_FILE,
    TOTAL_ACC_FILE,
    _csv_dialect,
    path_arg,
    read_table,
)
from pdrlearn.io.sensors import PLACEMENTS, SENSORS, UNIT_IMU, parse_value_unit
from pdrlearn.io.session import Session, Stream
from pdrlearn.io.validate import (
    CLOCK_RESET_S,
    GRAVITY_HINT,
    IMU_FLOOR_HZ,
    IMU_MIN_RATE_HZ,
    STANDARD_GRAVITY,
    check_imu_pair,
    check_rate,
    check_timestamps,
    check_units,
    clock_reset_message,
    clock_resets,
    gravity_removed,
    gravity_removed_message,
    sample_numbers,
    slow_seconds_message,
    slow_seconds_rate,
    time_unit_candidates,
)
from pdrlearn.kernels.clock import RETIME_RATE_TOL, retimed
from pdrlearn.kernels.counter_wrap import counter_wraps, unwrap, wrap_message
from pdrlearn.kernels.frames import axes_dict
from pdrlearn.kernels.units import out_of_range, out_of_range_message

log = logging.getLogger(__name__)

#: channel kinds of the mapping (``--acc``, ``--gyro`` ...): kind -> (sensor suffix, number of columns)
KINDS: dict[str, tuple[str, int]] = {
    "acc": ("Accelerometer", 3), "gyro": ("Gyroscope", 3), "mag": ("MagneticField", 3), "baro": ("Barometer", 1),
    "heel": ("ForceA", 1), "toe": ("ForceB", 1),
}
#: the kinds held to decision B144's IMU rate floor
_INERTIAL = frozenset({"acc", "gyro"})
#: name stems (lower case, letters and digits only) that say a column is of a kind, followed by the axis
#: (decision B345: German names too, ``Beschl. X``, ``Beschleunigung X``, ``Drehrate X``, ``Magnetfeld X``)
_STEMS: dict[str, tuple[str, ...]] = {
    "acc": ("accelerometer", "acceleration", "accel", "acc", "a", "beschleunigung", "beschl", "beschleunigungssensor"),
    "gyro": ("gyroscope", "angularvelocity", "angularrate", "rotationrate", "gyro", "gyr", "g", "w", "drehrate",
             "winkelgeschwindigkeit", "gyroskop"),
    "mag": ("magnetometer", "magneticfield", "magnetic", "mag", "m", "magnetfeld", "magnetfeldstaerke"),
}
_SINGLE: dict[str, tuple[str, ...]] = {
    "baro": ("pressure", "barometer", "baro", "airpressure", "luftdruck", "druck"),
    "heel": ("forceheel", "heelforce", "heel", "forcea", "fsrheel"),
    "toe": ("forcetoe", "toeforce", "toe", "forceb", "fsrtoe", "forefoot", "forceforefoot"),
}
_TIME_NAMES = ("timestamp", "time", "t", "ts", "timems", "times", "seconds", "sec", "ms", "millis",
               "milliseconds", "elapsedtime", "sampletime", "epoch", "unixtime", "timeus", "timens",
               "datetime", "date", "utc", "timestamputc",
               "zeit", "zeitstempel", "uhrzeit", "datumuhrzeit", "datumzeit", "datum")  # decision B345: German
#: decision B439: names of a column of sample numbers (mobgap's CSV export: ``samples,acc_x,...,gyr_z``): the time
#: column when no column is named like a time, whose consecutive integers need only ``--rate`` (not B39's question)
_SAMPLE_NAMES = ("samples", "sample", "sampleindex", "samplenumber", "samplenr", "sampleno")

#: accepted unit words per kind -> factor to the project's unit (time: seconds per unit)
UNITS: dict[str, dict[str, float]] = {
    "acc": {"m/s2": 1.0, "g": STANDARD_GRAVITY, "mg": STANDARD_GRAVITY / 1000},  # thesis ch.4.2.1.1
    "gyro": {"rad/s": 1.0, "deg/s": math.pi / 180.0},
    "mag": {"uT": 1.0, "nT": 1e-3, "gauss": 100.0, "mT": 1e3},
    "baro": {"hPa": 1.0, "Pa": 0.01, "kPa": 10.0, "mbar": 1.0},
    # decision B286: force in N, kilogram-force (1 kgf = 9.80665 N, standard gravity) or unitless counts (raw ADC;
    # the force detectors are scale-free, B284 tares an offset); %BW needs the body mass, which import does not know
    "heel": {"N": 1.0, "kgf": STANDARD_GRAVITY, "counts": 1.0},
    "toe": {"N": 1.0, "kgf": STANDARD_GRAVITY, "counts": 1.0},
}
#: decision B286: the force units refused in one line (they need the walker's body mass to become N)
_BODY_WEIGHT_UNITS = {"%bw", "bw", "%bodyweight", "bodyweight", "xbw"}
_UNIT_ALIASES = {
    "m/s^2": "m/s2", "m/s²": "m/s2", "ms2": "m/s2", "ms^2": "m/s2", "m/s/s": "m/s2", "mps2": "m/s2",
    "rad/sec": "rad/s", "rads": "rad/s", "deg/sec": "deg/s", "dps": "deg/s", "°/s": "deg/s", "degs": "deg/s",
    "µt": "ut", "μt": "ut", "microtesla": "ut", "millibar": "mbar",
    "grad/s": "deg/s", "grad/sec": "deg/s",  # decision B345: German "Grad/s" (degrees; gradians are "gon")
    "kg": "kgf", "kgf": "kgf", "kp": "kgf", "newton": "n", "newtons": "n", "count": "counts", "adc": "counts",
}
#: the option that gives a kind's unit (the others: the --mapping file's "units")
_UNIT_OPTION = {"acc": "--acc-unit", "gyro": "--gyro-unit"}
#: decision B397: the options that give a force column's unit (B286's N, kgf or counts)
_FORCE_UNIT_OPTION = {"heel": "--heel-unit", "toe": "--toe-unit"}
_HINT = re.compile(r"[\(\[]\s*([^\)\]]+?)\s*[\)\]]\s*$")
#: unit suffixes of names such as ``acc_x_g``, ``gyr_x_dps``, ``time_ms`` (decision D12): suffix -> unit word
_SUFFIX_UNITS = {"g": "g", "mg": "mg", "ms2": "m/s2", "mps2": "m/s2", "dps": "deg/s", "degs": "deg/s",
                 "rads": "rad/s", "radps": "rad/s", "ms": "ms", "s": "s", "us": "us", "ns": "ns", "ut": "ut",
                 "hpa": "hpa", "pa": "pa", "kpa": "kpa",
                 # decision B397: force units as suffixes (heel_N, heel_kg, heel_adc), B286's words
                 "n": "n", "kg": "kgf", "kgf": "kgf", "kp": "kgf", "adc": "counts", "counts": "counts"}
#: suffixes that are also a name's own stem or axis (``x_g``, ``ax_g``?): read as a unit only after two parts
_SHORT_SUFFIXES = {"g", "s"}


def _suffix_unit(column: str) -> tuple[str, str] | None:
    """(name without the suffix, unit word) of ``acc_x_g`` / ``gyr_x_dps`` / ``time_ms``, else None."""
    parts = [p for p in re.split(r"[_\s.\-]+", column.strip()) if p]
    if len(parts) < 2:
        return None
    last = parts[-1].lower()
    if last not in _SUFFIX_UNITS:
        return None
    if last in _SHORT_SUFFIXES and len(parts) < 3 and last != "s":
        # decision B469: ``AccX_g`` / ``ax_g``: a g after an accelerometer axis's own name is its unit
        if last != "g" or _axis_of(re.sub(r"[^a-z0-9]", "", parts[0].lower()), "acc") is None:
            return None
    return "_".join(parts[:-1]), _SUFFIX_UNITS[last]


def _unit_word(text: str) -> str:
    w = text.strip().lower().replace(" ", "").replace("(", "").replace(")", "")  # m/(s^2): Shimmer's units row
    return _UNIT_ALIASES.get(w, w)


#: decision B66: a Shimmer Consensys name ``Shimmer_7A1F_Accel_LN_X_CAL``: the device prefix, the
#: calibration suffix and the accelerometer range tag (LN low noise, WR wide range) say nothing of the channel
_VENDOR_PREFIX = re.compile(r"^shimmer[_\s]*[0-9a-f]{2,}[_\s]+", re.IGNORECASE)
_VENDOR_SUFFIX = re.compile(r"[_\s]+(?:cal|uncal|raw)$", re.IGNORECASE)
_VENDOR_RANGE = re.compile(r"[_\s]+(?:ln|wr)(?=[_\s])", re.IGNORECASE)


def _vendor_name(column: str) -> str:
    """``Shimmer_7A1F_Accel_LN_X_CAL`` -> ``Accel_X``; other names unchanged (decision B66)."""
    if not _VENDOR_PREFIX.match(column):
        return column
    return _VENDOR_RANGE.sub("", _VENDOR_SUFFIX.sub("", _VENDOR_PREFIX.sub("", column.strip())))


def _stem(column: str) -> str:
    """A column name without a trailing unit hint ``(g)`` / ``[deg/s]``, lower case, letters and digits only."""
    name = _HINT.sub("", _vendor_name(column))
    if not _HINT.search(column) and _suffix_unit(name):
        name = _suffix_unit(name)[0]
    return re.sub(r"[^a-z0-9]", "", name.lower())


def _header_unit(column: str) -> str | None:
    m = _HINT.search(column)
    if m:
        return _unit_word(m.group(1))
    suf = _suffix_unit(column)
    return suf[1] if suf else None


def _axis_of(stem: str, kind: str) -> str | None:
    """``x``/``y``/``z`` when ``stem`` is one of the kind's stems followed (or preceded) by the axis."""
    for s in _STEMS[kind]:
        for axis in "xyz":
            if stem in (s + axis, axis + s, s + axis + "axis"):
                return axis
    return None


def _column_axis(column: str, kind: str) -> str | None:
    """The axis a column name says it holds: ``x`` (Sensor Logger, phyphox ``X (m/s^2)``) or a kind's name
    (``acc_x``, ``gyroZ``); None when the name does not say."""
    stem = _stem(column)
    return stem if stem in ("x", "y", "z") else _axis_of(stem, kind)


def mirrored_axis_order(kind: str, cols: list[str], signs: np.ndarray) -> str | None:
    """Decision B145: the reason a given column list of ``kind`` reads the device's axes as their mirror image
    (an odd permutation of the named axes x, y, z: B130's test, ``right_handed``, on the implied axis map), or
    None when it does not, the names do not say their axes, or a column is negated (a deliberate sign: L71's
    own fix for a mirrored export negates one axis). Negating all three accelerometer columns is iOS's sign
    convention (B48), not a deliberate mirror: it is taken out first."""
    if kind not in _STEMS or len(cols) != 3:  # a force sensor's one column has no axes
        return None
    axes = [_column_axis(c, kind) for c in cols]
    if None in axes or len(set(axes)) != 3:
        return None
    m = np.zeros((3, 3))
    for row, (axis, sign) in enumerate(zip(axes, signs, strict=True)):
        m[row, "xyz".index(axis)] = sign
    if kind == "acc" and np.all(np.asarray(signs) < 0):
        m = -m
    if (m < 0).any() or right_handed(m):
        return None
    given = ",".join(f"-{c}" if g < 0 else c for c, g in zip(cols, signs, strict=True))
    ordered = ",".join(f"-{c}" if g < 0 else c for _, c, g in sorted(zip(axes, cols, signs, strict=True)))
    option = f"--{kind}{'=' if given.startswith('-') else ' '}"
    return (f"{option}{given} lists the axes in a mirror-image order (an odd permutation of x, y, z; IMU axes are "
            f"right-handed), which mirrors every turn: give the columns of the x, y, z axes in that order, "
            f"{option}{ordered}, whatever the file's column order; if the device's data really are mirrored, "
            "negate one column as well (decision B145)")


def _axis_candidates(columns: list[str], kind: str) -> dict[str, list[str]]:
    """Axis -> the columns whose names say they are that axis of ``kind``, in the file's order."""
    found: dict[str, list[str]] = {}
    for c in columns:
        axis = _axis_of(_stem(c), kind)
        if axis:
            found.setdefault(axis, []).append(c)
    return found


def guess_columns(columns: list[str]) -> dict[str, list[str]]:
    """Kind -> the columns whose names say so (``acc_x``/``ax``/``AccX (g)``/``accelerometer_x`` ...), in
    x, y, z order; kinds with no complete set are left out. A name two kinds claim is used by neither."""
    out: dict[str, list[str]] = {}
    for kind in _STEMS:
        found = _axis_candidates(columns, kind)
        if all(len(found.get(a, [])) == 1 for a in "xyz"):
            out[kind] = [found[a][0] for a in "xyz"]
    for kind, names in _SINGLE.items():
        hits = [c for c in columns if _stem(c) in names]
        if len(hits) == 1:
            out[kind] = hits
    used: dict[str, int] = {}
    for cols in out.values():
        for c in cols:
            used[c] = used.get(c, 0) + 1
    return {k: v for k, v in out.items() if all(used[c] == 1 for c in v)}


def ambiguous_columns(columns: list[str]) -> dict[str, list[str]]:
    """Kind -> every column named like one of its axes, for the kinds :func:`guess_columns` leaves out because
    an axis has more than one candidate (a Shimmer3's low-noise ``Accel_LN_X`` and wide-range ``Accel_WR_X``):
    ``pdrlearn import`` names them instead of saying that none was recognised."""
    out: dict[str, list[str]] = {}
    for kind in _STEMS:
        found = _axis_candidates(columns, kind)
        if all(found.get(a) for a in "xyz") and any(len(found[a]) > 1 for a in "xyz"):
            out[kind] = [c for c in columns if any(c in found[a] for a in "xyz")]
    return out


def time_column_candidates(columns: list[str], *, mat: bool = False) -> list[str]:
    """The columns named like a time, by the first rule that names any: exactly a time name (``timestamp``,
    ``Time (ms)``, ``t``), else a name starting with ``time`` (``timestamp_ms``, ``time_since_start``), else one
    containing ``timestamp`` (B66: ``Shimmer_7A1F_Timestamp_Unix_CAL``), else one containing ``elapsed`` (B148:
    Sensor Logger's ``seconds_elapsed``, which its ``time`` column wins over), else one named as sample numbers
    (:data:`_SAMPLE_NAMES`, decision B439: mobgap's ``samples``). ``mat``: the names are MAT
    struct paths, judged by their last field (``TimeMeasure1.Test11.SU.Acc_x`` is no time; decision B335)."""
    if mat:
        last = {c: c.rsplit(".", 1)[-1] for c in columns}
        hits = set(time_column_candidates(list(dict.fromkeys(last.values()))))
        return [c for c in columns if last[c] in hits]
    for hits in ([c for c in columns if _stem(c) in _TIME_NAMES],
                 [c for c in columns if _stem(c).startswith("time")],
                 [c for c in columns if "timestamp" in _stem(c)],
                 [c for c in columns if "elapsed" in _stem(c)],
                 [c for c in columns if _stem(c) in _SAMPLE_NAMES]):  # decision B439
        if hits:
            return hits
    return []


def guess_time_column(columns: list[str], *, mat: bool = False) -> str | None:
    """The one time-like column (:func:`time_column_candidates`); None when there is none or several."""
    hits = time_column_candidates(columns, mat=mat)
    return hits[0] if len(hits) == 1 else None


#: decision B163: name stems of acceleration columns without gravity (phyphox's "Linear Acceleration x (m/s^2)",
#: Core Motion's "userAccelerationX", Xsens' "FreeAcc_X"): not an accelerometer's specific force
_GRAVITY_FREE = ("linearacc", "useracc", "freeacc")
#: decision B163/B164: where to get acceleration with gravity from the phone apps the README names
WITH_GRAVITY = (f"export the raw (total) accelerometer, gravity included ({GRAVITY_HINT}): phyphox's 'Acceleration "
                "with g' experiment (columns 'Acceleration x (m/s^2)' ...), Sensor Logger's TotalAcceleration.csv "
                "(Android) or its Accelerometer.csv with --add-gravity Gravity.csv (iOS)")


def gravity_free_columns(columns: list[str]) -> list[str]:
    """Decision B163: the columns named as acceleration without gravity (:data:`_GRAVITY_FREE`)."""
    return [c for c in columns if any(w in _stem(c) for w in _GRAVITY_FREE)]


def gravity_fix(path: Path) -> str:
    """Decision B164: the fix for an accelerometer file without gravity: the phone files beside it that hold it
    (Sensor Logger's :data:`TOTAL_ACC_FILE`, else its :data:`GRAVITY_FILE` to add), else :data:`WITH_GRAVITY`."""
    from pdrlearn.errors import shell_quote

    total, gravity = path.parent / TOTAL_ACC_FILE, path.parent / GRAVITY_FILE
    if total.is_file() and total.resolve() != path.resolve():
        return (f"import {shell_quote(total)} instead (a phone app's acceleration with gravity; Sensor Logger's "
                "Accelerometer.csv is without it)")
    if gravity.is_file() and gravity.resolve() != path.resolve():
        return (f"add the gravity file beside it, --add-gravity {shell_quote(gravity)} (Sensor Logger on iOS writes "
                "its accelerometer without gravity and the gravity apart)")
    return WITH_GRAVITY


def _resolve_unit(kind: str, given: str | None, columns: list[str], where: str,
                  row_units: dict[str, str] | None = None) -> tuple[str, float, str]:
    """(unit, factor, source) of a kind's values: the given unit, else the units row's (decision B66), else the
    header's hint, else SI."""
    table = UNITS[kind]
    by_word = {k.lower(): k for k in table}  # unit words are matched case-insensitively
    si = next(iter(table))
    if kind in ("heel", "toe"):  # decision B286: a force unit hint is never ignored
        _check_force_units(kind, given, columns, where, row_units, by_word)
    if given is not None:
        u = by_word.get(_unit_word(given))
        if u is not None:
            return u, table[u], "given"
        sensor = next((s.kind for s in SENSORS.values() if s.name[1:] == KINDS[kind][0]), "")
        counted = parse_value_unit(given, sensor)  # decision B313: meta.json's units parser, "1/2048 g" too
        if counted is None:
            raise DataError(f"{where}: {kind} unit {given!r} is not one of {', '.join(table)}"
                            + (", nor the size of one count and one of them (\"1/2048 g\", as meta.json's \"units\" "
                               "take; decision B313)" if kind in _UNIT_OPTION else ""))
        return counted[1], counted[0], "given"
    row = {by_word.get(_unit_word((row_units or {}).get(c) or "")) for c in columns} - {None}
    hints = set(row) or {by_word.get(_header_unit(c) or "") for c in columns} - {None}
    if len(hints) > 1:  # never one of them for all the columns: some would be converted wrongly
        raise DataError(f"{where}: the {kind} columns {', '.join(columns)} carry different units "
                        f"({', '.join(sorted(hints))}); convert them to one unit, or give it with "
                        f"{_UNIT_OPTION.get(kind) or _FORCE_UNIT_OPTION.get(kind, '--mapping units')}")
    if len(hints) == 1:
        u = hints.pop()
        return u, table[u], "units row" if row else "header"
    return si, 1.0, "default"


def _own_force_unit(kind: str, columns: list[str], units: dict, row_units: dict[str, str] | None) -> bool:
    """Whether a force kind's unit is said for it: given (option or --mapping units), a units row or a header hint."""
    return units.get(kind) is not None or any((row_units or {}).get(c) or _header_unit(c) for c in columns)


def _one_force_unit(columns: dict[str, list[str]], units: dict, where: str,
                    row_units: dict[str, str] | None) -> tuple[dict, dict[str, str]]:
    """Decision B407: heel and toe in one stored unit. A unit given for one of them (``--heel-unit counts``) is the
    other's too when the other says none of its own (it had been N by default: raw counts in the toe written as N);
    heel and toe that still resolve to different stored units (N and counts) are one :class:`DataError`, since the
    force features and C153/C155's check read heel + toe as one unit. Returns the units and {kind: the option its
    unit was taken from}."""
    if not {"heel", "toe"} <= set(columns):
        return units, {}
    units, shared = dict(units), {}
    own = {k: _own_force_unit(k, columns[k], units, row_units) for k in ("heel", "toe")}
    for kind, other in (("heel", "toe"), ("toe", "heel")):
        if not own[kind] and units.get(other) is not None:
            units[kind], shared[kind] = units[other], _FORCE_UNIT_OPTION[other]
    got = {k: _resolve_unit(k, units.get(k), columns[k], where, row_units) for k in ("heel", "toe")}
    stored = {k: "counts" if u == "counts" else "N" for k, (u, _, _) in got.items()}  # B286: kgf is stored as N
    if stored["heel"] != stored["toe"]:
        said = {k: f"{got[k][0]} ({shared.get(k) or got[k][2]})" for k in got}
        raise DataError(f"{where}: the heel force ({', '.join(columns['heel'])}) is in {said['heel']} and the toe "
                        f"({', '.join(columns['toe'])}) in {said['toe']}; the force features read heel + toe in one "
                        "unit: give both the same unit (--heel-unit U --toe-unit U) or convert one column "
                        "(decision B407)")
    return units, shared


def _check_force_units(kind: str, given: str | None, columns: list[str], where: str,
                       row_units: dict[str, str] | None, by_word: dict[str, str]) -> None:
    """Decision B286: a force column's unit (given, units row or header hint ``heel (kg)``) that is not N, kgf or
    counts is refused in one line (it had been ignored: ``heel (kg)`` was written as N, a 9.81x mislabel); %BW names
    the conversion it needs."""
    said = [(given, "given")] if given is not None else [
        ((row_units or {}).get(c) or _header_unit(c), c) for c in columns]
    for text, src in said:
        if not text:
            continue
        w = _unit_word(text)
        if w.replace("(", "").replace(")", "") in _BODY_WEIGHT_UNITS:
            raise DataError(f"{where}: {kind} unit {text!r} ({src}) is % body weight, and import does not know the "
                            "body mass: convert it to N (x mass_kg x 9.80665 / 100) or declare it as counts "
                            f"(unitless: the force detectors are scale-free) with {_FORCE_UNIT_OPTION[kind]} counts "
                            "or the --mapping file's \"units\" (decisions B286, B408)")
        if w not in by_word and src == "given":  # decision B408: not "give it with" the option just given
            raise DataError(f"{where}: {kind} unit {text!r} ({src}) is not a force unit; {_FORCE_UNIT_OPTION[kind]} "
                            "takes N, kgf (or kg, kp) or counts (raw ADC, unitless; no count size such as "
                            "'1/4 N': the detectors are scale-free, convert the column to N for the force "
                            "features) (decisions B286, B408)")
        if w not in by_word:
            raise DataError(f"{where}: {kind} unit {text!r} ({src}) is not one of {', '.join(by_word.values())}; "
                            "convert the column, rename its unit hint, or give its unit with "
                            f"{_FORCE_UNIT_OPTION[kind]} (decision B286)")


def _time_word(text: str) -> str:
    """A --time-unit word normalised (``Milliseconds`` -> ``ms``, ``sample`` -> ``samples``)."""
    w = text.strip().lower()
    return _TIME_ALIASES.get(w, w)


def _integers(t_raw: np.ndarray) -> bool:
    """Decision B444: every timestamp a whole number."""
    t = np.asarray(t_raw, dtype=float)
    return t.size > 1 and bool(np.all(np.isfinite(t)) and np.all(t == np.round(t)))


def _sample_steps(t_raw: np.ndarray) -> str:
    """Decision B444: how sample numbers step, for B439's line (``step 1``, ``step 2``, ``steps 1-2``, ``going back
    1 time(s)``)."""
    d = np.diff(np.asarray(t_raw, dtype=float))
    if (d <= 0).any():
        return f"going back {int((d <= 0).sum())} time(s)"
    return f"step {d[0]:.0f}" if np.all(d == d[0]) else f"steps {d.min():.0f}-{d.max():.0f}"


def _declared_time_unit(given: str | None, column: str, where: str,
                        row_unit: str | None = None) -> tuple[str, str] | None:
    """(unit, source) of the timestamps when declared: given (--time-unit), the units row under the header (B66) or
    the header's own unit; None when only B22's inference can tell."""
    if given is not None:
        u = _time_word(given)
        if u not in _TIME_SCALE:
            raise DataError(f"{where}: time unit {given!r} is not one of {', '.join(_TIME_SCALE)}")
        return u, "given"
    row = _time_word(row_unit) if row_unit else None
    if row in _TIME_SCALE:  # decision B66: the units row under the header
        return row, "units row"
    hint = _header_unit(column)
    hint = _TIME_ALIASES.get(hint, hint) if hint else None
    if hint in _TIME_SCALE:
        return hint, "header"
    return None


def _time_unit(t_raw: np.ndarray, given: str | None, column: str, where: str,
               row_unit: str | None = None, *, inertial: bool = False, guessed: bool = False) -> tuple[str, str]:
    """(unit, source) of the timestamps: given, the header's hint, else decision B22's inference (the units
    in which the timestamps give a plausible rate, from B144's IMU floor for an ``inertial`` file, and a date
    before 2100; ms when ms is one of them, as read_session does). When several fit, the source names the others
    and the --time-unit that forces one (B144). A column named as sample numbers asks for --rate (B439): always
    when it was ``guessed`` by that name and holds whole numbers (B444), else when they step by 1."""
    declared = _declared_time_unit(given, column, where, row_unit)
    if declared is not None:
        return declared
    named = _stem(column) in _SAMPLE_NAMES and (sample_numbers(t_raw) or (guessed and _integers(t_raw)))
    if named:  # decisions B439, B444: the name says which; a guessed one never reaches B22's inference
        raise OptionFixError(f"{where}: column '{column}' holds sample numbers ({t_raw[0]:.0f}-{t_raw[-1]:.0f}, "
                             f"{_sample_steps(t_raw)}): give the sampling rate with --rate HZ (decision B439)",
                             "--rate")
    if sample_numbers(t_raw):  # decision B39: never read as a 1000 Hz ms clock without being told
        raise DataError(f"{where}: column '{column}' holds consecutive integers ({t_raw[0]:.0f}-{t_raw[-1]:.0f}, "
                        "step 1): sample numbers, or a 1000 Hz clock in ms? They cannot be told apart: give the "
                        "sampling rate with --rate HZ if they are sample numbers, or pass --time-unit ms if they "
                        "are milliseconds")
    cands = [u for u, _ in time_unit_candidates(t_raw, inertial=inertial)]
    slow = slow_seconds_message(t_raw, f"{where} (column '{column}')", "pass --time-unit ms") if inertial else None
    if not cands and slow:  # decision B161
        raise DataError(slow)
    if not cands:
        raise DataError(f"{where}: the timestamps of column '{column}' give no plausible rate in ms, s, us or ns; "
                        "pass --time-unit")
    chosen = "ms" if "ms" in cands else cands[0]
    others = [c for c in cands if c != chosen]
    return chosen, "inferred (B22)" + (f"; also fits {', '.join(others)}: pass --time-unit {others[0]} if it is "
                                       f"in {others[0]}" if others else "")




def _check_import_rate(t: np.ndarray, t_raw: np.ndarray, t_unit: str, t_how: str, column: str, where: str,
                       *, inertial: bool = False) -> None:
    """check_rate with import's wording (decision B37): the unit the values look like and --time-unit, not
    meta.json (which import writes). An ``inertial`` stream under B144's floor is refused the same way."""
    try:
        check_rate(t, f"{where} ({column} as {t_unit})")
        slow = inertial and t.size >= 3 and 1.0 / float(np.median(np.diff(t))) < IMU_FLOOR_HZ  # B144, B160
    except DataError:
        slow = True
    if slow:
        rate = 1.0 / float(np.median(np.diff(t)))
        fits = [u for u, _ in time_unit_candidates(t_raw, inertial=inertial)]
        looks = (f"the values look like {' or '.join(fits)}: pass --time-unit {fits[0]}" if fits
                 else "no unit (ms, s, us, ns) gives a plausible rate: check the --time column")
        secs = slow_seconds_rate(t_raw) if inertial and not fits else None
        if secs is not None:  # decision B161: seconds of a slow logger
            looks = ("" if t_unit == "s" else f"read as seconds they give {secs:.3g} Hz, and ") + (
                f"an accelerometer or gyroscope needs {IMU_FLOOR_HZ:g} Hz or more (decisions B144, B160): record "
                f"again at {IMU_MIN_RATE_HZ:g} Hz or more (a phone app's rate setting; decision B161)")
        src = {"given": "given with --time-unit", "header": "the column name's unit"}.get(t_how, t_how)
        raise DataError(f"{where}: timestamps of column '{column}' read as {t_unit} ({src}) give {rate:.3g} Hz; "
                        f"{looks}") from None


def _whole_seconds(secs: np.ndarray) -> bool:
    """Decision B84: date-times that lost their fraction of a second (Excel's default cell format
    ``2026-11-03 10:15:02``): every value a whole second and over half of the rows repeating the one before."""
    return bool(secs.size >= 3 and np.all(secs == np.round(secs)) and np.mean(np.diff(secs) == 0) > 0.5)


def _whole_seconds_message(secs: np.ndarray, where: str, column: str, first) -> str:
    """Decision B84: the refusal of whole-second date-times without --rate, naming the rows per second."""
    counts = np.unique(secs, return_counts=True)[1]
    per_s = int(np.median(counts[1:-1] if counts.size > 2 else counts))
    return (f"{where}: column '{column}' holds whole seconds only ({first!r} ...), {per_s} rows in a typical "
            f"second, so {int(np.sum(np.diff(secs) == 0))} of {secs.size} rows repeat a timestamp: the export lost "
            "the milliseconds (Excel's default cell format), the rows are not duplicates -- export the time with "
            f"milliseconds, or pass --rate {per_s} (the sampling rate in Hz) to time the rows from the first "
            "date-time (decision B84)")


#: ``--rate`` on whole-second date-times (decisions B84, B111): the rows at the rate may disagree with their
#: date-times by this many sample periods beyond the date-times' truncation to the second before rows lost (or a
#: wrong rate) are the cause; the rows' fit to the second boundaries pins the start to about one sample
RATE_DRIFT_SAMPLES = 1.5


def rows_at_rate(secs: np.ndarray, rate: float, where: str, column: str, first_line: int) -> tuple[np.ndarray, float]:
    """Decisions B84, B111 (``import --rate HZ`` on whole-second date-times, :func:`_whole_seconds`): row ``i`` at
    ``origin + i / rate`` (s since the epoch) and the half-width (s) of the origins that fit. The date-times hold
    the true time cut down to the second, so the origins that fit are those for which every row's time cuts down
    to its date-time; the origin is their middle (within about one sample of the true start when the rows cross
    a second boundary; within half a second in a recording under a second). Rows lost shift every later row
    against its date-time: refused, naming the first line that no longer fits, once the shift exceeds
    :data:`RATE_DRIFT_SAMPLES` sample periods (a shorter gap, under ~2.5 samples, is not seen)."""
    i = np.arange(secs.size) / rate
    lo_k, hi_k = np.maximum.accumulate(secs - i), np.minimum.accumulate(secs + 1.0 - i)
    bad = np.flatnonzero(lo_k - hi_k > RATE_DRIFT_SAMPLES / rate)
    if bad.size:
        k = int(bad[0])
        lo, hi = float(lo_k[-1]), float(hi_k[-1])
        per_s = (secs.size - 1) / max(float(secs[-1] - secs[0]), 1.0)
        raise DataError(f"{where}: --rate {rate:g} does not fit the whole-second date-times of column '{column}' "
                        f"from line {k + first_line} on (at {rate:g} Hz the rows drift at least {lo - hi:.2f} s "
                        f"from them; the file holds about {per_s:.1f} rows per second): rows are missing before "
                        f"line {k + first_line} or the rate is wrong -- give the rate the device recorded at, or "
                        "export the time with milliseconds and leave --rate out (decision B111)")
    lo, hi = float(lo_k[-1]), float(hi_k[-1])
    return (lo + hi) / 2 + i, max(hi - lo, 0.0) / 2


#: a numeric date at the start of a text: d/m/y or m/d/y (``10/12/2020``, ``10.12.20``, ``10-12-2020``)
_NUMERIC_DATE = re.compile(r"^\s*(\d{1,2})([/.\-])(\d{1,2})\2(\d{2}|\d{4})\b")


def _date_formats(text: str) -> tuple[str, str]:
    """(day-first, month-first) strftime formats for a date-time text like ``10/12/2020 13:57:44.733``."""
    m = _NUMERIC_DATE.match(text)
    sep, year = m.group(2), "%Y" if len(m.group(4)) == 4 else "%y"
    rest = text[m.end():]
    frac = re.match(r"\s*\d{1,2}:\d{2}:\d{2}([.,])\d+", rest)  # a decimal comma in day-first locales
    clock = (f"%H:%M:%S{frac.group(1)}%f" if frac else "%H:%M:%S"
             if re.match(r"\s*\d{1,2}:\d{2}:\d{2}", rest) else "%H:%M" if re.match(r"\s*\d{1,2}:\d{2}", rest)
             else "")
    tail = f" {clock}" if clock else ""
    zone = re.search(r"(\s*)(?:Z|[+-]\d{2}:?\d{2})\s*$", rest) if clock else None
    if zone:  # a zone after the clock (``+0100``, ``+01:00``, ``Z``): the format must read it too
        tail += f"{zone.group(1)}%z"
    return f"%d{sep}%m{sep}{year}{tail}", f"%m{sep}%d{sep}{year}{tail}"


#: a time of day without a date (``10:15:02.123``, ``10:15:02,123``): decision B86
_TIME_OF_DAY = r"\s*\d{1,2}:\d{2}:\d{2}(?:[.,]\d+)?\s*"


def _time_of_day_seconds(text: pd.Series, zone: str | None) -> tuple[np.ndarray, dict]:
    """Decision B86: times of day without a date, as seconds since midnight (pandas gave them today's date, shown
    as the recording's date); a step back of over 12 h is the clock passing midnight."""
    secs = pd.to_timedelta(text.str.strip().str.replace(",", ".", regex=False)).dt.total_seconds().to_numpy(float)
    secs = secs + 86400.0 * np.r_[0, np.cumsum(np.diff(secs) < -43200.0)]
    info = {"order": "as times of day without a date: seconds since midnight, no date made up (decision B86)",
            "zone": "none (a time of day)" + (" (--time-zone not used)" if zone else ""), "time_of_day": True,
            "first": text.iloc[0].strip(), "last": text.iloc[-1].strip()}
    return secs, info


def _datetime_seconds(col: pd.Series, where: str = "", time_format: str | None = None,
                      zone: str | None = None, first_line: int = 2) -> tuple[np.ndarray, dict, float] | None:
    """Seconds since ``base`` of a column of date-time texts (ISO 8601 and the like), what was read
    (``{"order": ..., "zone": ..., "first": ISO, "last": ISO}``) and ``base`` (a whole second since the epoch; 0
    for times of day), or None when the column is not date-times. Decision B341: the seconds are exact to the
    text's resolution (``,250`` is 0.25 s), as :func:`pdrlearn.io.datetimes.exact_seconds` computes them.

    Decision B43: a numeric date whose day and month are both <= 12 in every row (``10/12/2020``) is refused
    unless ``time_format`` says which is which (pandas read it month first, but ``13/12/2020`` day first); an
    unambiguous one is read in the order its values show. Times without a zone are taken as ``zone`` (default
    UTC), and the record says so."""
    if col.dtype.kind in "biufc":
        return None
    text = col.astype(str)
    if time_format is None and len(text) and text.str.fullmatch(_TIME_OF_DAY).all():  # decision B86
        return (*_time_of_day_seconds(text, zone), 0.0)
    info: dict = {}
    try:
        if time_format is not None:
            try:
                dt = pd.to_datetime(text, format=time_format)
            except (ValueError, TypeError) as exc:
                raise DataError(f"{where}: the time column does not match --time-format {time_format!r} "
                                f"({str(exc).splitlines()[0][:120]}); first value: {text.iloc[0]!r}") from None
            info["order"] = f"--time-format {time_format}"
        else:
            m = _NUMERIC_DATE.match(text.iloc[0])
            dayfirst = False
            if m:
                dates = text.str.extract(_NUMERIC_DATE).dropna()
                a, b = dates[0].astype(int), dates[2].astype(int)
                if (a > 12).any():
                    dayfirst, info["order"] = True, "day first (a first field over 12)"
                elif (b > 12).any():
                    info["order"] = "month first (a second field over 12)"
                elif m.group(2) == ".":  # decision B346: dots are day first (German, most of Europe; US uses /)
                    dayfirst, info["order"] = True, "day first (a dotted date, dd.mm.yyyy; decision B346)"
                else:
                    dfmt, mfmt = _date_formats(text.iloc[0])
                    raise DataError(f"{where}: the dates ({text.iloc[0]!r} ...) could be day/month or month/day "
                                    "(both fields <= 12 in every row); say which with --time-format "
                                    f"'{dfmt}' (day first) or '{mfmt}' (month first)")
            dt = pd.to_datetime(text, errors="raise", format="mixed", dayfirst=dayfirst)
    except DataError:
        raise
    except (ValueError, TypeError):
        return None
    if getattr(dt.dt, "tz", None) is None:
        z = zone or "UTC"
        dt = localize(dt, z, text, where, first_line)  # decision B342: the hour repeated in autumn by the rows' order
        info["zone"] = f"{z} ({'given with --time-zone' if zone else 'none in the text: taken as UTC'})"
    else:
        info["zone"] = "from the text" + (" (--time-zone not used)" if zone else "")
    if dt.iloc[0].utcoffset() is not None:  # decision L298: the offset as recorded, for the clock columns (UTC below)
        info["offset"] = offset_text(dt.iloc[0])
    dt = dt.dt.tz_convert("UTC")
    info["first"], info["last"] = dt.iloc[0].isoformat(), dt.iloc[-1].isoformat()
    secs, base = exact_seconds(dt)  # decision B341: exact to the text's resolution, not float epoch seconds
    return secs, info, base


def parse_frame(text: str | dict | None, where: str = "--frames") -> AxisFrame | None:
    """An axis frame from ``{"x": "forward", ...}`` (dict or JSON text) or ``x=forward,y=up,z=right``."""
    if text is None:
        return None
    d = axes_dict(text, where)
    try:
        return AxisFrame.from_dict(d)
    except DataError as exc:
        raise DataError(f"{where}: {exc}") from None


def signed_columns(cols: list[str], header: list[str]) -> tuple[list[str], np.ndarray]:
    """Decision B48: a channel column written ``-NAME`` (``--acc=-ax,-ay,-az``, or in the --mapping JSON) is
    column ``NAME`` negated, when the file has no column called ``-NAME`` itself. Returns the column names and
    the sign (+1 / -1) of each; iOS Core Motion exports report gravity as -1 g (docs/external-data.md)."""
    names, signs = [], []
    for c in cols:
        neg = c.startswith("-") and c not in header and c[1:] in header
        names.append(c[1:] if neg else c)
        signs.append(-1.0 if neg else 1.0)
    return names, np.array(signs)


def _is_number(text) -> bool:
    t = str(text).strip()
    return bool(re.fullmatch(r"[+-]?(?:\d+(?:[.,]\d*)?|[.,]\d+)(?:[eE][+-]?\d+)?", t)) or t.lower() in ("nan", "inf")


def _bare_unit(cell: str) -> str:
    """Decision B343: a units-row cell without the brackets around it, as a header's unit hint is written
    (``[m/s²]`` -> ``m/s²``, ``[m/(s^2)]`` -> ``m/(s^2)``, ``(deg/s)`` -> ``deg/s``; ``m/(s^2)`` is kept)."""
    c = cell.strip()
    if len(c) > 2 and (c[0], c[-1]) in (("[", "]"), ("{", "}"), ("(", ")")):
        inner, depth = c[1:-1].strip(), 0
        for ch in inner:  # "(m)/(s^2)" is not one pair around the unit
            depth += {"(": 1, ")": -1}.get(ch, 0)
            if depth < 0:
                return c
        return inner if depth == 0 else c
    return c


def units_row(df: pd.DataFrame) -> dict[str, str] | None:
    """Decision B66: column -> text of the first row under the header when it is a units row (``ms``,
    ``m/(s^2)``, ``deg/s``, as Shimmer Consensys writes; ``[ms]`` without its brackets, B343): every non-empty
    cell of it is text that is not a number, and some column is numbers in every later row. Else None."""
    if len(df) < 2:
        return None
    first = df.iloc[0]
    cells = {c: _bare_unit(str(v)) for c, v in first.items() if pd.notna(v) and str(v).strip()}
    if not cells or any(_is_number(v) for v in cells.values()):
        return None
    rest = df.iloc[1:]
    if not any(rest[c].notna().all() and rest[c].map(_is_number).all() for c in rest.columns):
        return None
    return cells


def _drop_rows(df: pd.DataFrame, n: int) -> pd.DataFrame:
    """``df`` without its first ``n`` rows, text columns that are now all numbers read as numbers (B24's
    decimal commas too), as :func:`read_table` would have read the file without those rows."""
    from pdrlearn.io.plasys import _decimal_comma_columns

    out = df.iloc[n:].reset_index(drop=True).copy()
    _decimal_comma_columns(out)  # first: B112 reads "1.012" beside a decimal comma as text, before to_numeric
    for c in out.columns:
        col = out[c]
        if col.dtype.kind in "biufc":
            continue
        num = pd.to_numeric(col, errors="coerce")
        if num[col.notna()].notna().all():
            out[c] = num
    return out


def _text_cells(df: pd.DataFrame, i: int) -> list[str] | None:
    """The non-number cells of row ``i`` when they are at least half of its non-empty cells, else None."""
    cells = [str(v).strip() for v in df.iloc[i] if pd.notna(v) and str(v).strip()]
    texts = [v for v in cells if not _is_number(v)]
    return texts if texts and len(texts) * 2 >= len(cells) else None


def _units_row_hint(df: pd.DataFrame, row: int, first_line: int, skipped: int = 0) -> str:
    """Decision B66: for a bad value in the first data row, what that row looks like and the option;
    ``skipped`` rows were skipped already (``--skip-rows``): the option counts them and every text row on top
    (a row of CAL / RAW above the units row), so that following it gets past them all."""
    if row != 0 or len(df) < 2:
        return ""
    texts = _text_cells(df, 0)
    if texts is None:
        return ""
    n = 1
    while n < len(df) - 1 and _text_cells(df, n) is not None:
        n += 1
    show = ", ".join(texts[:4]) + (" ..." if len(texts) > 4 else "")
    where = (f"line {first_line} ({show}) looks like a units row or a second header" if n == 1 else
             f"lines {first_line}-{first_line + n - 1} (the first: {show}) look like units rows or more header rows")
    return (f"; {where}: pass --skip-rows {skipped + n} to skip {'it' if n == 1 else 'them'} (and "
            f"--acc-unit/--gyro-unit/--time-unit for the units {'it names' if n == 1 else 'they name'})")


#: decision B337: a duration written with its unit, as MATLAB's writetable writes a timetable's row times
#: ("0.01 sec", a duration's default format 's'; "1.5 min", "2 hr" for 'm', 'h'): the suffix -> a time unit
_DURATION = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*"
                       r"(sec|secs|s|ms|msec|min|mins|hr|hrs|h)\s*")
_DURATION_UNITS = {"sec": "s", "secs": "s", "s": "s", "ms": "ms", "msec": "ms", "min": "min", "mins": "min",
                   "hr": "h", "hrs": "h", "h": "h"}


def duration_text(col: pd.Series) -> tuple[np.ndarray, str] | None:
    """Decision B337: (numbers, time unit) of a column whose every value is a number followed by one time unit
    (``0.01 sec``, ``10 ms``, ``1.5 min``: MATLAB ``writetable`` of a timetable); None otherwise. Minutes and hours
    are converted to s (the importer's time units are ms, s, us, ns)."""
    text = col.astype(str)
    m = text.str.fullmatch(_DURATION.pattern)
    if col.isna().any() or not m.all():
        return None
    parts = text.str.extract(_DURATION.pattern)
    words = {_DURATION_UNITS[w] for w in parts[1]}
    if len(words) != 1:
        return None
    word = words.pop()
    values = parts[0].astype(float).to_numpy()
    scale = {"min": 60.0, "h": 3600.0}.get(word)  # minutes and hours in s
    return (values * scale, "s") if scale else (values, word)


#: decision B336: a headerless export's columns when none is mapped, by their count: MATLAB's
#: ``writematrix([t acc gyr])`` (7) and ``writematrix([acc gyr])`` (6, timed by --rate)
HEADERLESS_ORDER: dict[int, dict[str, tuple[int, ...]]] = {
    7: {"time": (0,), "acc": (1, 2, 3), "gyro": (4, 5, 6)},
    6: {"acc": (0, 1, 2), "gyro": (3, 4, 5)},
}


def _utf8_beyond_ascii(path: Path) -> bool:
    """Decision B344: ``path`` (not compressed) decodes as UTF-8 and holds characters beyond ASCII."""
    if path.suffix.lower() in (".gz", ".bz2", ".zip", ".xz", ".zst") or not path.is_file():
        return False
    data = path.read_bytes()
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return not data.isascii()


def label_encoding(path: Path, encoding: str | None) -> str | None:
    """Decision B344 (amended, review R2): the encoding a ``--steps`` / ``--labels`` table is read in: UTF-8 when it
    decodes as UTF-8 (a lab's ASCII or UTF-8 list beside a cp1252 or utf-16 export), else import's ``--encoding``."""
    if encoding is None or not path.is_file():
        return None
    try:
        path.read_bytes().decode("utf-8")
    except UnicodeDecodeError:
        return encoding
    return None


#: decision B344: import's further fix for a CSV that is not UTF-8 (German Excel's plain "CSV" type is cp1252)
NOT_UTF8_IMPORT = ", or read it as it is with --encoding cp1252 (Windows-1252, what Excel's plain 'CSV' type writes)"

#: decision B323: the time "column" of a fixed-rate export without one: its rows numbered 0, 1, 2 ... at --rate
ROW_INDEX = "(row index)"

#: decision B321: the feet ``import --foot`` writes to meta.json ``foot`` (the key :func:`pdrlearn.track.bilateral
#: .session_foot` reads first)
FEET = ("left", "right")


#: decision B390: the leg length (m) `import --leg-length` accepts: a toddler's 0.3 m to a very tall adult's 1.3 m
#: (the simulator's S38 range, 0.35-0.6 x its 0.7-2.2 m heights, widened to the measured leg of any walker)
LEG_LENGTH_RANGE_M = (0.3, 1.3)


def check_leg_length(leg_length_m, height_m=None, option: str = "--leg-length",
                     height_option: str = "--subject-height") -> float:
    """Decision B390: ``leg_length_m`` as a float in metres, or one DataError line naming ``option`` (the CLI
    option, or the mapping file's key, decision B394) and the fix: not a number (``true`` included), outside
    :data:`LEG_LENGTH_RANGE_M`, or, with a ``height_m``, outside S38's leg/height range (0.35-0.6 x the height,
    the rule `simulate --leg-length` applies; decision B394)."""
    from pdrlearn.cli.simulate import LEG_PER_HEIGHT_RANGE  # decision S38's rule (numpy-free module)

    lo, hi = LEG_LENGTH_RANGE_M
    try:
        leg = float("nan") if isinstance(leg_length_m, bool) else float(leg_length_m)
    except (TypeError, ValueError):
        leg = float("nan")
    if not (math.isfinite(leg) and lo <= leg <= hi):
        raise DataError(f"import: {option} {leg_length_m!r} is not a leg length in m ({lo:g}-{hi:g} m, the "
                        "greater trochanter's height above the floor: 0.62, not 62)")
    try:
        h = float("nan") if height_m is None or isinstance(height_m, bool) else float(height_m)
    except (TypeError, ValueError):
        h = float("nan")  # a bad height is refused by its own check
    if math.isfinite(h) and not (LEG_PER_HEIGHT_RANGE[0] * h <= leg <= LEG_PER_HEIGHT_RANGE[1] * h):
        raise DataError(f"import: {option} {leg:g} m does not fit {height_option} {h:g} m: the leg "
                        f"(greater-trochanter height) is {LEG_PER_HEIGHT_RANGE[0]:g}-{LEG_PER_HEIGHT_RANGE[1]:g} x "
                        f"the height ({LEG_PER_HEIGHT_RANGE[0] * h:.2f}-{LEG_PER_HEIGHT_RANGE[1] * h:.2f} m here; "
                        "decisions S38, B394)")
    return leg


def import_csv(path: str | os.PathLike, *, unit: str = "foot", columns: dict[str, list[str]] | None = None,
               time_column: str | None = None, time_unit: str | None = None, units: dict[str, str] | None = None,
               frame=None, sensor_height_m: float | None = None, name: str | None = None,
               origin_s: float | None = None, guess: bool = True,
               subject_height_m: float | None = None, rate_hz: float | None = None,
               time_format: str | None = None, time_zone: str | None = None,
               skip_rows: int | None = None, drop_duplicate_timestamps: bool = False,
               sort_timestamps: bool = False, add_gravity: str | os.PathLike | None = None,
               retime_hz: float | None = None,
               foot: str | None = None, no_header: bool = False, encoding: str | None = None,
               subject: str | None = None, visit: str | None = None,
               leg_length_m: float | None = None) -> tuple[Session, dict]:
    """Read a one-CSV lab export into a session of one unit.

    Parameters
    ----------
    path : the CSV (comma, semicolon or tab separated; decimal commas allowed, decision B24)
    unit : ``"foot"`` or ``"waist"``: which unit's sensor files the channels become
    columns : kind (``acc``, ``gyro``, ``mag``, ``baro``, ``heel``, ``toe``) -> column names (x, y, z order
        for 3-axis kinds); kinds not given are guessed from the names when ``guess``
    time_column : the timestamp column (default: the one column named like a time)
    time_unit : ``ms``, ``s``, ``us`` or ``ns``; default: the header's hint (``Time (ms)``), else B22's inference
        (consecutive integers from near 0 are refused: sample numbers or a 1000 Hz ms clock, decision B39)
    rate_hz : the time column holds sample numbers at this rate (decision B39)
    time_format : a strftime format of a date-time text column (``%d/%m/%Y %H:%M:%S``); needed when the
        day and month cannot be told apart (decision B43)
    time_zone : the zone of date-time texts without one (default UTC, said in the record; decision B43)
    skip_rows : rows directly under the header that are not data (decision B66); default: a units row
        (every cell text, e.g. ``ms``, ``m/(s^2)``, ``deg/s``) is recognised, skipped and read for the units
    drop_duplicate_timestamps : keep the first of rows with the same timestamp (a phone app's batched samples,
        decision B150; counted in ``record["duplicate_rows"]``); refused otherwise
    sort_timestamps : sort the rows by their timestamp first (a phone app's batched log writes rows out of order;
        decision B383; the rows that moved counted in ``record["sorted_rows"]``); refused otherwise (D3). Not with a
        clock reset (B73: sorting would interleave two recordings)
    add_gravity : a gravity file of the same recording (Sensor Logger's ``Gravity.csv``), added sample by sample
        to the accelerometer columns, which hold acceleration without gravity (decision B166): its columns of the
        same names, read with the same time column and units, interpolated onto the accelerometer's times
    retime_hz : the sensor's output rate (Hz): the samples are re-timed at it, anchored to their stamps
        (:func:`pdrlearn.kernels.clock.retimed`, decision B186: a Bluetooth IMU's notifications carry several samples
        on one receive time); counted in ``record["retimed"]``
    units : kind -> unit of its values (``acc``: ``m/s2`` | ``g``; ``gyro``: ``rad/s`` | ``deg/s``; ``mag``:
        ``uT`` | ``nT`` | ``gauss``; ``baro``: ``hPa`` | ``Pa`` | ``kPa``); default: the header's hint, else SI
    frame : the unit's axis frame (:func:`parse_frame` input or :class:`AxisFrame`), written to ``frames``
    sensor_height_m : the waist unit's height above the ground (m), written to ``meta.json`` (refused for a foot
        unit, B175)
    subject_height_m : the subject's height (m), written to ``meta.json`` ``height_m``
    leg_length_m : the subject's leg length (m, greater-trochanter height), written to ``meta.json``
        ``leg_length_m`` (decision B390: a child's measured leg; L148 scales the walking range by it)
    name : session name (default: the CSV's stem)
    encoding : the CSV's text encoding (``cp1252``: German Excel's plain "CSV" save type; decision B344); default
        UTF-8, a byte order mark accepted (B221)
    subject : the subject's id, written to ``meta.json`` ``subject`` (decision B345)
    visit : the visit's name, written to ``meta.json`` ``visit`` (decision B364; track-all pairs visits, C22)
    origin_s : the export's time (s, on its clock) that becomes 0 (default: its first timestamp); the
        session's files hold "ms since the first sample" (D1), ``record["time"]["origin_s"]`` keeps the origin
        so that labels on the export's clock can be shifted alike (and ``--merge`` puts a second export of
        the same clock on the same origin)
    no_header : the CSV has no header line (MATLAB ``writematrix``/``csvwrite``): its columns are named by their
        index from 0 (``--time 0 --acc 1,2,3``); unmapped, they are read in :data:`HEADERLESS_ORDER` (decision
        B336). A CSV whose header line is all numbers is refused without it.

    A MATLAB v5 MAT file (``path`` ending anywhere; told by its header) is read as a table of its per-sample arrays
    (:func:`pdrlearn.io.matfile.read_mat_table`: ``acc`` N x 3 -> ``acc_x, acc_y, acc_z``; ``--acc acc`` names
    the three), timed by its time vector or, without one, its ``fs`` scalar; a v7.3 file is refused in one line
    (decision B335).

    Returns
    -------
    (session, record): ``record`` holds the columns, units and their sources (given / header / guessed /
    inferred), the columns left unused and the rows dropped, as written to ``meta.json["imported"]``.
    """
    kw = dict(locals())
    return _import_parts(kw.pop("path"), False, **kw)[0]


def _refuse_out_of_range(spec, raw: np.ndarray, rows: np.ndarray, t: np.ndarray, factor: float, cols: list[str],
                         unit: str, where: str, lines: np.ndarray, declare: str | None, kind: str = "") -> None:
    """Decision B436: B425's one line for an export's rows (``raw``, as written) with a value beyond any sensor's
    range once converted (``factor``), naming the export, the file line (``lines``: each row's) and the export's own
    column. The unit checks (``declare``: the import's unit option) first, as B425's reader does, so that a whole
    column in another unit keeps its unit line (its corrupt rows' squares may overflow there, silently); none for the
    accelerometer of an ``--add-gravity`` import (``declare`` None: its acceleration has no gravity yet, B166; B443:
    its other sensors keep their unit checks). ``kind``: the import's channel
    kind, whose option the unit line carries when another unit fits (decision B438)."""
    if declare is not None:
        try:
            with np.errstate(over="ignore", invalid="ignore"):
                check_units(spec, raw * factor, f"{where} ({', '.join(cols)} as {unit})", declare=declare, t=t,
                            factor=factor)
        except DataError as exc:
            fits = _fitting_unit(kind, spec.name, raw, t, unit)  # decision B438
            if fits is None:
                raise
            raise OptionFixError(str(exc), _UNIT_OPTION[kind], fits) from None
    r = int(rows[0])
    raise DataError(out_of_range_message(where, spec, raw, rows, factor, first_line=int(lines[r]) - r,
                                         columns=tuple(cols)) + "; nothing written")


def import_csv_parts(path: str | os.PathLike, **kwargs) -> list[tuple[Session, dict]]:
    """Decision B80 (``pdrlearn import --split-at-clock-reset``): :func:`import_csv` (the same keywords but
    ``origin_s``) cut at the export's clock resets (decision B73's :func:`~pdrlearn.io.validate.clock_resets`),
    one ``(session, record)`` per recording in file order (one when there is no reset). Each part starts its
    clock at its own first sample, is named ``NAME_partK`` (K from 1), has ``record["part"]`` (its number, the
    count, its lines) and is checked as a whole export is; a part under 1 s (or 3 rows) is refused."""
    return _import_parts(path, True, **kwargs)


def _import_parts(path: str | os.PathLike, split: bool, *, unit: str = "foot",
                  columns: dict[str, list[str]] | None = None,
                  time_column: str | None = None, time_unit: str | None = None, units: dict[str, str] | None = None,
                  frame=None, sensor_height_m: float | None = None, name: str | None = None,
                  origin_s: float | None = None, guess: bool = True,
                  subject_height_m: float | None = None, rate_hz: float | None = None,
                  time_format: str | None = None, time_zone: str | None = None,
                  skip_rows: int | None = None, drop_duplicate_timestamps: bool = False,
                  sort_timestamps: bool = False, add_gravity: str | os.PathLike | None = None,
                  retime_hz: float | None = None,
                  foot: str | None = None, no_header: bool = False, encoding: str | None = None,
                  subject: str | None = None, visit: str | None = None,
                  leg_length_m: float | None = None) -> list[tuple[Session, dict]]:
    """:func:`import_csv`'s body: the whole export (``split`` False; a clock reset is refused) or one part per
    recording between its clock resets (decision B80)."""
    path = path_arg(path, "import_csv_parts" if split else "import_csv", "a CSV or MAT file")  # decision B349
    where = str(path)
    if retime_hz is not None:  # decision B186
        if not (isinstance(retime_hz, int | float) and math.isfinite(retime_hz) and 0 < retime_hz <= 10000):
            raise DataError(f"import: --retime {retime_hz!r} is not a sampling rate in Hz (the sensor's output rate, "
                            "e.g. 104)")
        if drop_duplicate_timestamps or rate_hz is not None:
            raise DataError("import: --retime places every sample at the sensor's rate by its stamps; leave out "
                            + ("--drop-duplicate-timestamps, which would drop the samples it spreads" if
                               drop_duplicate_timestamps else "--rate (a column of sample numbers needs no re-timing)")
                            + " (decision B186)")
    if unit not in PLACEMENTS:
        raise DataError(f"import: unit {unit!r} is not one of {', '.join(PLACEMENTS)}")
    if foot is not None:  # decision B321
        foot = str(foot).strip().lower()
        if foot not in FEET:
            raise DataError(f"import: --foot {foot!r} is not left or right (the foot the unit is on)")
        if unit != "foot":
            raise DataError("import: --foot names the foot a foot unit is on, and this is a --unit waist import; "
                            "drop --foot, or import the foot unit's file with it (decision B321)")
    if encoding is not None:  # decision B344
        import codecs

        try:
            encoding = codecs.lookup(str(encoding)).name
        except LookupError:
            raise DataError(f"import: --encoding {encoding!r} is not a text encoding (cp1252 for German Excel's "
                            "'CSV (Trennzeichen-getrennt)', latin-1, utf-16; default utf-8)") from None
        if not encoding.startswith("utf") and _utf8_beyond_ascii(path):  # read as cp1252, "m/s²" is "m/sÂ²"
            raise DataError(f"{where}: --encoding {encoding}, but the file is UTF-8 text (its bytes beyond ASCII are "
                            "UTF-8's), which the option would misread; leave --encoding out (decision B344)")
    mat = mat_version(path)  # decision B335: a MAT file, by its header
    mat_record = None
    if mat == "7.3":
        raise DataError(mat_message(path, mat))
    if mat:
        if no_header:
            raise DataError(f"{where}: --no-header is for a CSV without a header line, and this is a MAT file "
                            "(its variables name the columns); leave --no-header out (decision B335)")
        if encoding is not None:  # decision B344 (amended, review R2): a MAT file has no text encoding
            raise DataError(f"{where}: --encoding is for a CSV's text, and this is a MAT file (binary, its own "
                            "encoding); leave --encoding out (decision B344)")
        wanted = [c.lstrip("-") for v in (columns or {}).values() for c in v] + [time_column or ""]
        df, mat_record = read_mat_table(path, wanted)
        dialect = {}
        columns = {k: expand_columns(list(v), list(df.columns)) for k, v in (columns or {}).items()}
    else:
        # B24: ';' / tab separators and decimal commas, as every session file; B344: a cp1252 file named, or read
        df = read_table(path, header=not no_header, encoding=encoding, not_utf8_also=NOT_UTF8_IMPORT)
        dialect = _csv_dialect(path, encoding, header=not no_header)
    header = list(df.columns)
    have = ", ".join(header)
    if not mat and not no_header and header and all(_is_number(c) for c in header):  # decision B336
        raise DataError(f"{where}: the first line is all numbers ({', '.join(header[:4])}"
                        f"{' ...' if len(header) > 4 else ''}): a CSV without a header line (MATLAB writematrix / "
                        "csvwrite)? pass --no-header; its columns are then named 0, 1, 2 ... (--time 0 --acc 1,2,3 "
                        "--gyro 4,5,6; unmapped, 7 columns are read as time, acc, gyro; decision B336)")
    first_row = [str(v).strip() for v in df.iloc[0]] if no_header and len(df) else []
    if first_row and not any(_is_number(v) for v in first_row if v and v.lower() != "nan"):  # decision B336
        raise DataError(f"{where}: --no-header, but the first line is text ({', '.join(first_row[:4])}"
                        f"{' ...' if len(first_row) > 4 else ''}): a header line; leave --no-header out "
                        "(decision B336)")
    # decision B66: the file line of data row i is i + first_line (a "sep=" line and skipped rows above it);
    # a MAT file's "line" is its row (from 1)
    first_line = (1 if mat or no_header else 2) + len(dialect.get("skiprows", ()))
    row_units: dict[str, str] = {}
    skipped: dict | None = None
    if skip_rows is not None:
        n = int(skip_rows)
        if n < 0 or n >= len(df):
            raise DataError(f"{where}: --skip-rows {skip_rows} leaves no data rows (the file has {len(df)} under "
                            "its header)")
        if n:
            df, first_line = _drop_rows(df, n), first_line + n
            skipped = {"rows": n, "source": "given (--skip-rows)"}
    else:
        found = units_row(df)
        if found is not None:
            row_units = found
            df, first_line = _drop_rows(df, 1), first_line + 1
            skipped = {"rows": 1, "source": "units row", "line": first_line - 1, "units": row_units}
    if len(df) == 0:
        raise DataError(f"{where}: no data rows under the header ({have}); re-export the file")
    # decision B62: pandas renames a repeated name ('ax', 'ax.1'), so the header line itself is checked
    # (unnamed columns, e.g. of a header line ending in ',,', are not names)
    raw = header if mat or no_header else [
        c for c in (str(c).strip() for c in pd.read_csv(path, header=None, nrows=1, dtype=str,
                                                         keep_default_na=False, **dialect).iloc[0]) if c]
    if len(set(raw)) != len(raw):
        dup = sorted({c for c in raw if raw.count(c) > 1})
        raise DataError(f"{where}: column name(s) {', '.join(dup)} appear twice; rename them")
    columns = {k: list(v) for k, v in (columns or {}).items()}
    signs = {}
    for kind in list(columns):  # B48: -NAME = NAME negated
        columns[kind], signs[kind] = signed_columns(columns[kind], header)
    for kind, cols in columns.items():
        if kind not in KINDS:
            raise DataError(f"import: unknown channel kind {kind!r}; use {', '.join(KINDS)}")
        n = KINDS[kind][1]
        if len(cols) != n:
            raise DataError(f"import: {kind} needs {n} column name(s) (got {len(cols)}: {','.join(cols)})")
        missing = [c for c in cols if c not in header]
        if missing:
            raise DataError(f"{where}: no column {', '.join(repr(c) for c in missing)} for {kind}; the file's columns "
                            f"are: {have}")
        mirrored = mirrored_axis_order(kind, cols, signs[kind])
        if mirrored:
            raise DataError(f"{where}: {mirrored}; nothing written")
    sources = {k: "given" for k in columns}
    headerless_time = None
    if no_header and guess:  # decision B336: the documented order of a headerless export's unmapped columns
        order = HEADERLESS_ORDER.get(len(header), {})
        taken = {c for v in columns.values() for c in v} | {time_column}
        for kind, idx in order.items():
            cols = [str(i) for i in idx]
            if kind == "time" and time_column is None and not taken & set(cols):
                time_column = headerless_time = cols[0]
            elif kind != "time" and kind not in columns and not taken & set(cols):
                columns[kind], sources[kind] = cols, "default order (--no-header, B336)"
    if guess:
        for kind, cols in guess_columns(header).items():
            if kind not in columns and not set(cols) & {c for v in columns.values() for c in v}:
                columns[kind], sources[kind] = cols, "guessed"
    if not columns and mat_record is not None:  # decision B335: name the MAT file's variables, not its columns
        raise DataError(f"{where}: no accelerometer/gyroscope recognised among the MAT file's N x 3 arrays "
                        f"({mat_arrays_text(mat_record)}); name them with --acc NAME --gyro NAME (decision B335)")
    if time_column is None:
        time_column = guess_time_column(header, mat=bool(mat))
        t_source = "guessed"
        if time_column is None:
            several = time_column_candidates(header, mat=bool(mat))
            if several:  # decision B70: say which columns compete (a Shimmer's Timestamp_Unix and TimestampSync_Unix)
                raise DataError(f"{where}: several columns look like the time: {', '.join(several)}; name the one "
                                "to use with --time COLUMN")
            if rate_hz is None and mat_record and "rate" in mat_record:  # decision B335: the MAT file's fs
                rate_hz = mat_record["rate"]["hz"]
                mat_record["rate"]["used"] = True
            if rate_hz is None:  # decision B438: --rate is this refusal's fix (its value the user's)
                raise OptionFixError(f"{where}: no timestamp column found among: {have}; name it with --time "
                                     "COLUMN, or pass --rate HZ to time the rows by their number (a fixed-rate "
                                     "export, B323)", "--rate")
            time_column = ROW_INDEX  # decision B323: a fixed-rate export (gaitmap / NilsPod style): rows at --rate
            t_source = "none"
    else:
        # decision B336: the time column of --no-header's default order (NU #13: said as a phrase, not "... column")
        t_source = "first in the default order (--no-header, B336)" if time_column == headerless_time else "given"
        if time_column not in header:
            raise DataError(f"{where}: no time column {time_column!r}; the file's columns are: {have}")
    if time_column in {c for v in columns.values() for c in v}:
        raise DataError(f"{where}: column {time_column!r} is mapped as time and as a channel; map it once")
    prefix = "f" if unit == "foot" else "w"
    for kind in list(columns):
        sensor = prefix + KINDS[kind][0]
        if sensor not in SENSORS and sources[kind] == "guessed":  # B66: a Shimmer's Mag_X on a foot unit: unused
            del columns[kind]
            continue
        if sensor not in SENSORS:
            raise DataError(f"import: the {unit} unit has no {kind} sensor (the {unit} unit's files: "
                            f"{', '.join(n for n, s in SENSORS.items() if s.placement == unit)})")
    free = [c for c in gravity_free_columns(header) if c not in {c for v in columns.values() for c in v}]
    if "acc" not in columns and free and all(v == "guessed" for v in sources.values()):  # decision B163
        raise DataError(f"{where}: column(s) {', '.join(free)} hold acceleration without gravity (linear / user / free "
                        f"acceleration), which pdrlearn cannot use (decision B30); {WITH_GRAVITY} (decision B163); "
                        "nothing written")
    if not columns:
        raise DataError(f"{where}: no accelerometer/gyroscope columns recognised among: {have}; map them with "
                        "--acc X,Y,Z --gyro X,Y,Z (or --mapping FILE.json)")

    tcol = pd.Series(np.arange(len(df)), name=ROW_INDEX) if time_column == ROW_INDEX else df[time_column]
    t_duration = None
    parsed = None if time_column == ROW_INDEX else _datetime_seconds(tcol, where, time_format, time_zone, first_line)
    secs = None if parsed is None else parsed[0]
    base = 0.0 if parsed is None else parsed[2]  # decision B341: date-times are seconds since this whole second
    if parsed is not None and time_zone is None and "taken as UTC" in parsed[1]["zone"]:
        jump = dst_jump(secs)  # decision B342: local times with a daylight-saving change, before B73's clock reset
        if jump is not None:
            raise DataError(dst_message(secs, jump, tcol, where, time_column, first_line))
    if parsed is not None:
        t_num, t_unit, t_how = secs, "s", "date-time text"
    elif time_format is not None or time_zone is not None:
        raise DataError(f"{where}: --time-format/--time-zone read date-time text, but column '{time_column}' holds "
                        f"numbers ({tcol.iloc[0]} ...); leave them out")  # B63: not np.float64(0.0)
    else:
        t_num = pd.to_numeric(tcol, errors="coerce").to_numpy(dtype=float)
        dur = duration_text(tcol) if np.isnan(t_num).any() else None
        if dur is not None:  # decision B337: MATLAB duration text, "0.01 sec"
            t_num, word = dur
            if time_unit is not None and _time_word(time_unit) != word:
                raise DataError(f"{where}: column {time_column!r} writes its unit ({tcol.iloc[0]!r} ...: {word}), "
                                f"and --time-unit says {time_unit}; leave --time-unit out (decision B337)")
            time_unit = word
            t_duration = word
        bad = np.flatnonzero(~np.isfinite(t_num))
        if bad.size:
            raise DataError(f"{where}: column {time_column!r} has {bad.size} non-numeric or empty value(s) (first at "
                            f"line {bad[0] + first_line}); timestamps must be numbers (or date-times) in every row"
                            + _units_row_hint(df, bad[0], first_line, (skipped or {}).get("rows", 0)))
        try:  # decision B450: the tick, when declared (a unit not one of them is refused below, as before)
            declared = None if rate_hz is not None else _declared_time_unit(time_unit, time_column, where,
                                                                             row_units.get(time_column))
        except DataError:
            declared = None
        tick = None if declared is None else _TIME_SCALE[declared[0]]
        bits, wraps = counter_wraps(t_num, tick)  # decision B312 (B450: a gap across it, the tick known), unwrapped
        if bits:
            word = time_unit or (declared[0] if declared else "ticks")
            log.warning("%s", wrap_message(f"{where} ({time_column})", t_num, bits, wraps, word,
                                           int(wraps[0]) + 1 + first_line))
            t_num = unwrap(t_num, bits, wraps)
        if rate_hz is None and time_unit is not None and _time_word(time_unit) == "samples":
            raise DataError(f"{where}: --time-unit samples needs the sampling rate: pass --rate HZ")
        if rate_hz is None:
            t_unit, t_how = _time_unit(t_num, time_unit, time_column, where, row_units.get(time_column),
                                       inertial=bool(_INERTIAL & set(columns)), guessed=t_source == "guessed")
            if t_duration:  # decision B337
                t_how = f"written after each value ({tcol.iloc[0]!r} ...: MATLAB duration text, B337)"
    if secs is not None and rate_hz is None and _whole_seconds(secs):  # decision B84: not duplicated rows
        raise DataError(_whole_seconds_message(secs, f"{where}", time_column, tcol.iloc[0]))
    if rate_hz is not None:  # decision B39: the time column holds sample numbers at rate_hz
        r = float(rate_hz)
        if not (math.isfinite(r) and r > 0):
            raise DataError(f"import: --rate {rate_hz!r} is not a sampling rate in Hz")
        if secs is None and np.any(t_num != np.round(t_num)):
            raise DataError(f"{where}: --rate says column '{time_column}' holds sample numbers, but it holds "
                            "fractions; leave --rate out")
        if time_unit is not None and _time_word(time_unit) != "samples":
            raise DataError(f"import: --rate reads the time column as sample numbers; leave --time-unit "
                            f"{time_unit} out")
        if secs is not None and not _whole_seconds(secs):  # decision B111: they time the rows themselves
            raise DataError(f"{where}: column '{time_column}' holds date-times with fractions of a second "
                            f"({tcol.iloc[0]!r} ...): the date-times already time the rows; leave --rate out "
                            "(decision B111)")
        if secs is not None:  # decision B84: rows at r Hz, placed by the whole-second date-times
            t_num, half = rows_at_rate(secs, r, where, time_column, first_line)
            t_how = (f"rows at {r:g} Hz (given with --rate) from the whole-second date-time text (the start "
                     f"placed to +/-{half * 1000:.0f} ms)")
        elif time_column == ROW_INDEX:  # decision B323
            given = (f"the MAT file's {mat_record['rate']['name']}, decision B335"
                     if mat_record and mat_record.get("rate", {}).get("used") else "given with --rate")
            t_unit, t_how = "samples", f"the row index at {r:g} Hz ({given}, decision B323)"
        else:
            t_unit, t_how = "samples", f"sample numbers at {r:g} Hz (given with --rate)"
    # the origin is taken off in the file's own unit: epoch milliseconds keep their exact 10 ms steps
    scale = 1.0 / float(rate_hz) if t_unit == "samples" else _TIME_SCALE[t_unit]
    # decision B73 on the export's rows (all of them share the time column), in s; B80: split there on request
    resets = clock_resets(t_num * scale)
    fix = (f"pass --split-at-clock-reset to write one session per recording, or split the export at line "
           f"{int(resets[0]) + 1 + first_line} into two files" if resets.size else "")
    if resets.size and not split:
        raise DataError(clock_reset_message(t_num * scale + base, resets, f"{where} ({time_column})",
                                            f"line {int(resets[0]) + 1 + first_line}", fix))
    sorted_rows = 0
    if sort_timestamps:  # decision B383: rows out of time order sorted (stable: equal stamps keep their order)
        if resets.size:
            raise DataError(f"{where}: --sort-timestamps would interleave the recordings on both sides of the clock "
                            "reset; split the export first (--split-at-clock-reset, without --sort-timestamps) "
                            "(decision B383)")
        order = np.argsort(t_num, kind="stable")
        sorted_rows = int((order != np.arange(order.size)).sum())
        if sorted_rows:
            df, t_num = df.iloc[order].reset_index(drop=True), t_num[order]
    if split and origin_s is not None:
        raise DataError("import: --split-at-clock-reset starts each part's clock at its own first sample; it "
                        "cannot share an origin with another export (--merge)")
    bounds = [0, *(int(i) + 1 for i in resets), len(df)]
    full_df, full_t, line0 = df, t_num, first_line
    parts: list[tuple[Session, dict]] = []
    n_parts = len(bounds) - 1
    for part, (a, b) in enumerate(zip(bounds[:-1], bounds[1:], strict=True), start=1):
        df, t_num, first_line = full_df.iloc[a:b].reset_index(drop=True), full_t[a:b], line0 + a
        lines = f"lines {first_line}-{first_line + b - a - 1}"
        if n_parts > 1:  # decision B80: each part must be a recording of its own
            span = (float(t_num[-1]) - float(t_num[0])) * scale
            if b - a < 3 or span < CLOCK_RESET_S:
                raise DataError(f"{where}: part {part} of {n_parts} ({lines}, between clock resets) holds {b - a} "
                                f"row(s) over {span:.2f} s, too short to be a recording; delete those rows and import "
                                "again (nothing written)")
        origin_raw = float(t_num[0]) if origin_s is None else (float(origin_s) - base) / scale
        if parsed is not None and origin_s is not None:  # decision B341: a shared origin, stored as float epoch
            origin_raw = round(origin_raw * 1e6) / 1e6  # seconds (0.24 us steps), is exact to the microsecond
        t_all = (t_num - origin_raw) * scale
        origin = origin_raw * scale + base  # decision B341: on the export's clock (s since the epoch for date-times)
        record: dict = {"file": path.name, "unit": unit,
                        "time": {"column": time_column, "unit": t_unit,
                                 "source": t_how if time_column == ROW_INDEX else
                                 f"{t_source}{' column' if t_source in ('given', 'guessed') else ''}, unit {t_how}",
                                 "origin_s": origin},
                        "streams": {}, "dropped_rows": {}}
        if skipped is not None:  # decision B66
            record["skipped_rows"] = skipped
        if sorted_rows:  # decision B383
            record["sorted_rows"] = sorted_rows
        if mat_record is not None:  # decision B335
            record["mat"] = mat_record
        if no_header:  # decision B336
            record["no_header"] = True
        if parsed is not None:  # decision B43: what the date-time text was read as, for the summary
            record["time"]["datetime"] = parsed[1]
        streams: dict[str, Stream] = {}
        units = {k: v for k, v in (units or {}).items() if v is not None}
        units, shared_unit = _one_force_unit(columns, units, where, row_units)  # decision B407
        for kind, cols in columns.items():
            sensor = prefix + KINDS[kind][0]
            vals = df[cols].apply(pd.to_numeric, errors="coerce").to_numpy(dtype=float)
            finite = np.isfinite(vals)
            keep = finite.all(axis=1)
            partial = np.flatnonzero(finite.any(axis=1) & ~keep)
            if partial.size:
                raise DataError(f"{where}: {partial.size} row(s) with some of {', '.join(cols)} empty or not numeric "
                                f"(first at line {partial[0] + first_line}); repair or remove them"
                                + _units_row_hint(df, partial[0], first_line,
                                                   (skipped or {}).get("rows", 0)))
            if not keep.any():
                text = df[cols[0]].dropna().astype(str)
                shown = (f" (first value {text.iloc[0]!r}); write them as numbers, 1002.3 or 1002,3 (points group "
                         "thousands only beside a decimal comma, 1.002,3; decision B85)" if len(text) else "")
                raise DataError(f"{where}: columns {', '.join(cols)} ({kind}) hold no numbers{shown}")
            if (~keep).any():  # a multi-rate export leaves a slower sensor's cells empty between its samples
                record["dropped_rows"][sensor] = int((~keep).sum())
            if drop_duplicate_timestamps:  # decision B150: the first of each run of equal timestamps is kept
                rows = np.flatnonzero(keep)
                again = rows[1:][np.diff(t_all[rows]) == 0]
                keep[again] = False
                if again.size:
                    record.setdefault("duplicate_rows", {})[sensor] = int(again.size)
            u, factor, u_src = _resolve_unit(kind, units.get(kind), cols, where, row_units)
            if kind in shared_unit:  # decision B407: the other force column's given unit
                u_src = f"given with {shared_unit[kind]}, B407"
            t = t_all[keep]
            if retime_hz is not None:  # decision B186: batched receive stamps spread at the sensor's rate
                t = _retimed(t, float(retime_hz), where, time_column, record, sensor)
            check_timestamps(t, f"{where} ({time_column})", reset_fix=fix or None,
                             lines=np.flatnonzero(keep) + first_line,  # B80: the file's lines, in any part
                             duplicate_fix="drop the duplicated rows, or pass --drop-duplicate-timestamps to keep "
                             "the first of each (a phone app's batched samples; decision B150)",
                             backward_fix="sort the file by timestamp, or pass --sort-timestamps to sort the rows "
                             "on import (decision B383)")
            _check_import_rate(t, t_num[keep], t_unit, t_how, time_column, where, inertial=kind in _INERTIAL)
            sign = signs.get(kind, np.ones(len(cols)))
            corrupt = out_of_range(SENSORS[sensor].kind, vals[keep], factor)  # decision B436: B425's range check
            with np.errstate(over="ignore"):  # a corrupt 1e308 times its unit's factor (B436 refuses it below)
                values = vals[keep] * factor * sign
            opt = _UNIT_OPTION.get(kind) or _FORCE_UNIT_OPTION.get(kind, "--mapping units")
            declare = f"give the unit with {opt} ({' | '.join(UNITS[kind])})"
            if corrupt.size:  # decision B436: refused here, before anything is written (the next read refused it)
                _refuse_out_of_range(SENSORS[sensor], vals[keep], corrupt, t, factor, cols, u, where,
                                     np.flatnonzero(keep) + first_line,  # B443: only the acceleration lacks
                                     None if add_gravity is not None and kind == "acc" else declare, kind)  # gravity
            if kind == "acc" and add_gravity is not None:  # decision B166
                if gravity_removed(values, where, t) is None:
                    med = float(np.median(np.linalg.norm(values, axis=1)))
                    raise DataError(f"{where} ({', '.join(cols)}): already holds gravity (mean acceleration vector "
                                    f"{np.linalg.norm(values.mean(axis=0)):.3g} against a median |acc| of {med:.3g}): "
                                    "adding it again doubles it; leave --add-gravity out (decision B166)")
                values = values + sign * _gravity_at(Path(add_gravity), t, cols, time_column,
                                                     None if parsed is not None else t_unit, u, unit, origin,
                                                     drop_duplicate_timestamps, encoding)
            elif add_gravity is not None and "acc" not in columns:
                raise DataError(f"import: --add-gravity adds gravity to the accelerometer columns, and {where} has "
                                "none mapped; map them with --acc X,Y,Z (decision B166)")
            stream = Stream(sensor, t, values)
            try:
                check_units(SENSORS[sensor], stream.values, f"{where} ({', '.join(cols)} as {u})",
                            declare=declare, t=t, factor=factor)
            except DataError as exc:
                removed = gravity_removed(stream.values, where, t) if kind == "acc" else None
                if removed is not None:  # decision B164: name the phone files that hold gravity
                    raise DataError(gravity_removed_message(f"{where} ({', '.join(cols)} as {u})", *removed,
                                                            gravity_fix(path)) + " (decision B164)") from None
                fits = _fitting_unit(kind, sensor, vals[keep] * sign, t, u)  # decision B438: the one that reads
                if factor == 1.0:
                    if fits is None:
                        raise
                    raise OptionFixError(str(exc), opt, fits) from None
                try:  # decision B45: the values are plausible as they are, so the conversion is the mistake
                    check_units(SENSORS[sensor], vals[keep], where, t=t)
                except DataError:
                    if fits is None:
                        raise exc from None
                    raise OptionFixError(str(exc), opt, fits) from None  # decision B438: another unit reads them
                si = next(iter(UNITS[kind]))
                fix = (f"drop {opt} {u} (or pass {opt} {si})" if u_src.startswith("given")
                       else f"the column names say {u}, but the values are not: pass {opt} {si}")
                msg = f"{exc}; read without the conversion from {u} they are plausible {si}: {fix}"
                raise (DataError(msg) if fits is None else OptionFixError(msg, opt, fits)) from None
            streams[sensor] = stream
            record["streams"][sensor] = {"columns": cols, "columns_source": sources[kind], "unit": u,
                                         "unit_source": u_src, "factor": factor,
                                         "rate_hz": round(float(stream.rate_hz), 4), "samples": len(stream)}
            if kind == "acc" and add_gravity is not None:  # decision B166
                record["streams"][sensor]["gravity_added"] = Path(add_gravity).name
            if (sign < 0).any():  # B48
                record["streams"][sensor]["negated"] = [c for c, g in zip(cols, sign, strict=True) if g < 0]
        acc_name, gyro_name = UNIT_IMU[unit]
        if acc_name in streams and gyro_name in streams:  # decisions B36, B37: the two judged together
            a, g = record["streams"][acc_name], record["streams"][gyro_name]
            gfix = ("drop --gyro-unit deg/s (or the declared unit)" if g["unit"] == "deg/s"
                    else "check the gyroscope's unit (--gyro-unit rad/s | deg/s)")
            check_imu_pair(streams[acc_name].t, streams[acc_name].values, streams[gyro_name].t,
                           streams[gyro_name].values, unit, f"{where} ({', '.join(a['columns'])} as {a['unit']})",
                           f"{where} ({', '.join(g['columns'])} as {g['unit']})", gyro_fix=gfix,
                           acc_fix="give the right --acc-unit (m/s2 | g | mg)",
                           gyro_big_fix=("pass --gyro-unit deg/s" if g["unit"] != "deg/s"
                                         else "check the gyroscope's unit (--gyro-unit rad/s | deg/s)"))
        used = {time_column, *(c for v in columns.values() for c in v)}
        ambiguous = {k: v for k, v in ambiguous_columns(header).items() if k not in columns and not set(v) & used}
        if guess and ambiguous:  # several candidate sets for a kind: none was guessed, the import names them
            record["ambiguous_columns"] = ambiguous
        # an unnamed empty column (a tab or comma ending every line, as Shimmer writes) is no column (B66)
        record["unused_columns"] = [c for c in header if c not in used
                                    and not (c.startswith("Unnamed: ") and df[c].isna().all())]
        stem = name or path.stem
        meta: dict = {"session": f"{stem}_part{part}" if n_parts > 1 else stem, "placement": unit,
                      "units": {s: f"{'counts' if r['unit'] == 'counts' else SENSORS[s].unit} (source {r['unit']}, "
                                   f"x {r['factor']:.10g})"
                                for s, r in record["streams"].items()},
                      "imported": record}
        if sensor_height_m is not None:
            h = float(sensor_height_m)
            if not (math.isfinite(h) and 0 < h <= 2.0):  # as meta.json's sensor_height_m (B16): metres, anatomy
                raise DataError(f"import: sensor height {sensor_height_m!r} is not a height in m (0-2 m)")
            if unit == "foot":  # decision B175: meta.json's sensor_height_m is the waist unit's (W10, B155, L148)
                raise DataError("import: --sensor-height is the waist unit's height above the ground (the waist "
                                "pendulum's leg length, and the leg by which the walking range is scaled), and this "
                                "is a foot unit's import (the default --unit foot): for a waist unit add --unit "
                                "waist; for a foot unit drop it (the walker's leg: meta.json leg_length_m; "
                                "decision B175)")
            meta["sensor_height_m"] = h
        if subject_height_m is not None:
            h = float(subject_height_m)
            if not (math.isfinite(h) and 0.5 <= h <= 2.5):  # a person's height in m (meta.json height_m, B16)
                raise DataError(f"import: subject height {subject_height_m!r} is not a person's height in m "
                                "(0.5-2.5 m; 1.75, not 175)")
            meta["height_m"] = h
        if leg_length_m is not None:  # decision B390
            meta["leg_length_m"] = check_leg_length(leg_length_m, subject_height_m)
        if foot is not None:  # decision B321: `pdrlearn gait` checks the side given against it (L260)
            meta["foot"] = foot
        from pdrlearn.io.meta_keys import label_option

        for key, given, what, example, decision in (("subject", subject, "subject's id", "P07", "B345"),
                                                    ("visit", visit, "visit's name", "visit1", "B364")):
            text = label_option(given, "import", f"--{key}", what, example, decision)  # sessions.csv groups by it
            if text is not None:  # (cohort C22): the subject's, and its visits paired (B364)
                meta[key] = text
        frames = {}
        f = frame if isinstance(frame, AxisFrame) or frame is None else parse_frame(frame)
        if f is not None:
            frames[unit] = f
        if n_parts > 1:  # decision B80: where this part lies in the export
            record["part"] = {"part": part, "of": n_parts, "lines": lines}
        parts.append((Session(name=meta["session"], streams=streams, meta=meta, frames=frames), record))
    return parts


def _fitting_unit(kind: str, sensor: str, raw: np.ndarray, t: np.ndarray, unit: str) -> str | None:
    """Decision B438: the one unit word of ``kind`` (acc, gyro: :data:`_UNIT_OPTION`'s kinds) other than ``unit`` in
    which the file's values ``raw`` pass :func:`~pdrlearn.kernels.units.check_units` (the same check that refused
    them), so the import can say its option and value; None when none or several do, or for any other kind."""
    if kind not in _UNIT_OPTION:
        return None
    fits = []
    for word, factor in UNITS[kind].items():
        if word == unit:
            continue
        try:
            check_units(SENSORS[sensor], raw * factor, "", t=t, factor=factor)
        except DataError:
            continue
        fits.append(word)
    return fits[0] if len(fits) == 1 else None


def _retimed(t: np.ndarray, hz: float, where: str, time_column: str, record: dict, sensor: str) -> np.ndarray:
    """Decision B186: ``t`` (s) re-timed at ``hz`` (:func:`pdrlearn.kernels.clock.retimed`), its summary kept in
    ``record["retimed"][sensor]``; refused when the stamps' own rate differs from ``hz`` by more than
    :data:`~pdrlearn.kernels.clock.RETIME_RATE_TOL` (every stride would scale by the difference)."""
    if t.size > 1 and not (np.diff(t) >= 0).all():
        return t  # not sorted: check_timestamps names the line
    new, info = retimed(t, hz)
    if abs(info["stamp_rate_hz"] / hz - 1.0) > RETIME_RATE_TOL:
        raise DataError(f"{where} ({time_column}): --retime {hz:g} Hz, but the stamps hold {info['stamp_rate_hz']:.4g} "
                        f"samples a second over their span ({info['lost']} counted as lost): give the sensor's "
                        f"output rate (--retime {info['stamp_rate_hz']:.4g}?), or check the stamps' unit (decision "
                        "B186)")
    record.setdefault("retimed", {})[sensor] = {k: round(v, 4) if isinstance(v, float) else v
                                                for k, v in info.items()}
    return new


def _gravity_at(path: Path, t: np.ndarray, cols: list[str], time_column: str, time_unit: str | None, acc_unit: str,
                unit: str, origin_s: float, drop_duplicate_timestamps: bool = False,
                encoding: str | None = None) -> np.ndarray:
    """Decision B166: the gravity file ``path`` (columns ``cols``, read as :func:`import_csv` reads an
    accelerometer: the same time column, unit, origin and B150 option, the accelerometer's unit) interpolated onto the
    accelerometer's times ``t`` (s). Refused when it does not cover them (another recording) or is not gravity
    (B30's check on it: a mean vector near zero)."""
    if not path.is_file():
        raise DataError(f"--add-gravity {path}: no such file; give the gravity file of the same recording "
                        "(Sensor Logger's Gravity.csv beside Accelerometer.csv)")
    g, _ = import_csv(path, unit=unit, columns={"acc": list(cols)}, time_column=time_column, time_unit=time_unit,
                      units={"acc": acc_unit}, origin_s=origin_s, guess=False,
                      drop_duplicate_timestamps=drop_duplicate_timestamps, encoding=encoding)
    acc_name = UNIT_IMU[unit][0]
    gt, gv = g[acc_name].t, g[acc_name].values
    tol = 1.5 * float(np.median(np.diff(gt))) if gt.size > 1 else 0.0
    if gt[0] > t[0] + tol or gt[-1] < t[-1] - tol:
        raise DataError(f"--add-gravity {path}: covers {gt[0]:.2f}-{gt[-1]:.2f} s and the accelerometer "
                        f"{t[0]:.2f}-{t[-1]:.2f} s (on the accelerometer file's clock): give the gravity file of the "
                        "same recording (decision B166); nothing written")
    return np.column_stack([np.interp(t, gt, gv[:, j]) for j in range(gv.shape[1])])


def merge_sessions(base: Session, add: Session) -> Session:
    """``base`` with ``add``'s streams, frames and import record (one unit added, decision D12); a sensor
    that both have is an error, so an import never replaces recorded data."""
    both = sorted(set(base.streams) & set(add.streams))
    if both:
        raise DataError(f"session '{base.name}' already has {', '.join(both)}; --merge adds the other unit "
                        "(use --unit foot|waist for the one it lacks)")
    meta = dict(base.meta)
    units = dict(meta.get("units", {})) if isinstance(meta.get("units"), dict) else {}
    units.update(add.meta.get("units", {}))
    meta["units"] = units
    imported = meta.get("imported")
    rec = add.meta.get("imported")
    meta["imported"] = ([*imported] if isinstance(imported, list) else [imported] if imported else []) + [rec]
    placement = meta.get("placement")
    if placement and placement != add.meta.get("placement"):
        meta["placement"] = "foot+waist"
    for key in ("sensor_height_m", "height_m", "leg_length_m", "foot", "subject", "visit"):  # B394: the leg too
        if key in add.meta:
            meta[key] = add.meta[key]
    if "leg_length_m" in meta:  # decision B394: the leg against the merged session's height, as without --merge
        check_leg_length(meta["leg_length_m"], meta.get("height_m"), "the merged session's leg_length_m",
                         "its height_m")
    return Session(name=base.name, streams={**base.streams, **add.streams},
                   steps=base.steps if base.steps is not None else add.steps,
                   trajectory=base.trajectory, extras={**add.extras, **base.extras}, meta=meta,
                   frames={**base.frames, **add.frames})


#: ``--merge`` warns when the added unit's time span and the session's share less than this fraction of the
#: longer of the two (decision D12, second amendment: trial 2 finding 11, a 137.6 s lower-back export merged
#: into a 38.7 s foot session; "half of the shorter" would have missed it, the shorter lying inside the longer).
MERGE_MIN_OVERLAP = 0.5


def _span(session: Session) -> tuple[float, float] | None:
    ts = [(float(st.t[0]), float(st.t[-1])) for st in session.streams.values() if len(st.t)]
    return (min(a for a, _ in ts), max(b for _, b in ts)) if ts else None


def merge_span_warning(base: Session, add: Session) -> str | None:
    """The ``--merge`` warning when ``add``'s time span (s, on the session's clock) and ``base``'s overlap by
    less than :data:`MERGE_MIN_OVERLAP` of the longer span (decision D12, second amendment); else ``None``.
    A warning, not a refusal: two units' clocks can legitimately differ (:func:`pdrlearn.steps.align_units`
    estimates an offset of up to ``max_offset_s``, 2 s by default; ``pdrlearn track --align-units``, decision L162)."""
    sa, sb = _span(add), _span(base)
    if sa is None or sb is None:
        return None
    overlap = max(0.0, min(sa[1], sb[1]) - max(sa[0], sb[0]))
    longer = max(sa[1] - sa[0], sb[1] - sb[0])
    if longer <= 0 or overlap >= MERGE_MIN_OVERLAP * longer:
        return None
    unit = add.meta.get("placement", "added")
    return (f"the added {unit} unit spans {sa[0]:.1f}-{sa[1]:.1f} s ({sa[1] - sa[0]:.1f} s) but the session's "
            f"{', '.join(sorted(base.streams))} span {sb[0]:.1f}-{sb[1]:.1f} s ({sb[1] - sb[0]:.1f} s): they overlap "
            f"{overlap:.1f} s, under half of the longer (decision D12); check that both exports record the same "
            "walk (clocks up to 2 s apart: `pdrlearn track --align-units`, decision L162)")


def merge_offset_note(base: Session, add: Session) -> str | None:
    """Decision B83: the ``--merge`` note when the added unit starts or stops more than
    :data:`~pdrlearn.io.plasys.SPAN_TOLERANCE_S` apart from the session's (two devices switched on a few seconds
    apart): ``track`` refuses such a session (B21) and ``--common-span`` tracks the time both have data."""
    from pdrlearn.io.plasys import SPAN_TOLERANCE_S

    sa, sb = _span(add), _span(base)
    if sa is None or sb is None or max(abs(sa[0] - sb[0]), abs(sa[1] - sb[1])) <= SPAN_TOLERANCE_S:
        return None
    unit = add.meta.get("placement", "added")
    lo, hi = max(sa[0], sb[0]), min(sa[1], sb[1])
    return (f"the added {unit} unit covers {sa[0]:.2f}-{sa[1]:.2f} s, the session's other files {sb[0]:.2f}-"
            f"{sb[1]:.2f} s (started {sa[0] - sb[0]:+.2f} s, stopped {sa[1] - sb[1]:+.2f} s apart); track the "
            f"{lo:.2f}-{hi:.2f} s both cover with `pdrlearn track --common-span` (decision B83); if each unit's clock "
            "counted from its own power-on, the import made both start at 0 and the difference in their stops may be "
            "a power-on offset --common-span keeps: `pdrlearn track --align-units` estimates an offset under a step "
            "period (decision L162)")


def _shifted_table(path: Path, origin_s: float, encoding: str | None = None) -> pd.DataFrame:
    """A label table of ``path`` with its ``*_ms`` columns (ms on the export's clock) moved onto the session's
    clock (``origin_s`` taken off) and read as seconds (``*_s``), as ``read_session`` reads label files; read with
    ``encoding`` as :func:`label_encoding` says (decision B344)."""
    from pdrlearn.io.plasys import _ms_to_s

    df = read_table(path, encoding=label_encoding(path, encoding), not_utf8_also=NOT_UTF8_IMPORT)
    for c in df.columns:
        if c.endswith("_ms"):
            v = pd.to_numeric(df[c], errors="coerce")
            df[c] = np.where(v.notna(), v - origin_s * 1e3, v) if v.notna().any() else df[c]
    return _ms_to_s(df, str(path))


def _label_origin(session: Session, origin_s: float, relative: bool) -> float:
    """What is taken off a label table's times (s) to put them on the session's clock: the export's origin, or
    with ``relative`` (decision B42, times from the recording's first sample) minus where this export's first
    sample lies on the session's clock: 0 for a first import, not with --merge onto another export's origin."""
    return -session.t_start if relative else origin_s


def _check_shifted_labels(table: pd.DataFrame, path: Path, session: Session, origin_s: float,
                          relative: bool) -> None:
    """check_label_times for a label table moved onto the session's clock (decision D12); when its times lie
    outside the recording but would fit on the other reading (ms from the recording's start instead of the
    export's clock, or the reverse), the error says so and names ``--labels-relative`` (decision B42)."""
    from pdrlearn.io.validate import check_label_times

    try:
        check_label_times(table, session.t_start, session.t_end, str(path))
    except DataError as exc:
        # the other reading's times: the table's plus the origin used, minus the other one's
        shift = _label_origin(session, origin_s, not relative) - _label_origin(session, origin_s, relative)
        if "outside the recording" not in str(exc):
            raise
        if not shift:
            raise DataError(f"{exc}; {OTHER_CLOCK_HINT}") from None
        cols = [c for c in ("start_s", "end_s", "ic_s") if c in table.columns]

        def fits(shift: float) -> bool:
            other = table.copy()
            other[cols] = other[cols].to_numpy(float) - shift
            try:
                check_label_times(other, session.t_start, session.t_end, str(path))
            except DataError:
                return False
            return True

        if fits(shift):  # undo the one reading, apply the other
            hint = ("they fit as ms on the export's clock: leave out --labels-relative" if relative else
                    "they fit as ms from the recording's start (its first sample = 0): pass --labels-relative "
                    "(or add the export's first timestamp to them)")
            raise DataError(f"{exc}; {hint}") from None
        rec = session.meta.get("imported")
        zone = (rec or {}).get("time", {}).get("datetime", {}).get("zone", "") if isinstance(rec, dict) else ""
        hours = [h for h in range(-14, 15) if h and fits(-3600.0 * h)] if "taken as UTC" in zone else []
        if hours:  # decision B43: a local time read as UTC
            h = hours[0]
            raise DataError(f"{exc}; moved {abs(h)} h {'later' if h > 0 else 'earlier'} they fit: the export's "
                            "date-time text has no zone and was taken as UTC: give its zone, e.g. --time-zone "
                            f"{'+' if h > 0 else '-'}{abs(h):02d}:00") from None
        raise DataError(f"{exc}; {OTHER_CLOCK_HINT}") from None


#: steps decision 56: the end of the "outside the recording" line at import (trial T2 finding 1)
OTHER_CLOCK_HINT = ("labels on another clock (a motion-capture system's): pass --labels-offset SECONDS, that clock "
                    "minus the export's (decision steps 56)")


def import_labels(paths, session: Session, origin_s: float, *, taken=(),
                  relative: bool = False, offset_s: float = 0.0,
                  encoding: str | None = None) -> tuple[Session, dict[str, int]]:
    """``session`` with the extra label tables of ``paths`` (``ics.csv``, ``bouts.csv``, ``turns.csv`` ...:
    ``*_ms`` columns in ms on the export's clock), each kept under its file name (``ics.csv`` -> the
    session's ``ics.csv``), moved onto the session's clock exactly as :func:`import_steps` moves the steps
    and checked as ``read_session`` checks them. ``taken``: label names the session already has (--merge).
    ``relative``: the times are ms from the recording's first sample, not on the export's clock (decision B42).
    ``offset_s``: the labels' clock minus the export's (s; a motion-capture clock): each time t is taken at
    t - ``offset_s`` (``--labels-offset``, the sign of steps decision 56's ``--ref-offset``). ``encoding``: import's
    ``--encoding``, for a table that is not UTF-8 (:func:`label_encoding`, decision B344).
    Returns the session and name -> rows."""
    from pdrlearn.io.plasys import LABEL_FILES, LABEL_TABLES, check_label_table
    from pdrlearn.io.sensors import SENSORS

    extras, rows = dict(session.extras), {}
    for p in map(Path, paths):
        name = p.stem
        if p.suffix.lower() != ".csv":
            raise DataError(f"{p}: --labels takes CSV label tables (ics.csv, bouts.csv ...); convert it to CSV")
        if name in LABEL_FILES or name in SENSORS:
            hint = "pass labelled steps with --steps" if name == "steps" else "rename the file"
            raise DataError(f"{p}: '{name}.csv' is not an extra label table a session can take; {hint}")
        if name in rows or name in taken:
            raise DataError(f"{p}: the session already has {name}.csv; pass one file per name (rename one)")
        raw = read_table(p, encoding=label_encoding(p, encoding), not_utf8_also=NOT_UTF8_IMPORT)
        if name in LABEL_TABLES:  # decision B41
            check_label_table(raw, name, str(p))
        elif not any(str(c).endswith("_ms") for c in raw.columns):
            raise DataError(f"{p}: no *_ms time column (ic_ms, start_ms, end_ms ...); label times must be "
                            "milliseconds on the export's clock")
        else:
            log.warning("%s: no command reads a label table named %s.csv (they read %s); it is copied into the "
                        "session but not used: rename it if it is one of those", p, name,
                        ", ".join(f"{n}.csv ({', '.join(c)})" for n, c in LABEL_TABLES.items()))
        table = _shifted_table(p, _label_origin(session, origin_s, relative) + offset_s, encoding)
        _check_shifted_labels(table, p, session, origin_s, relative)
        extras[name], rows[name] = table, len(table)
    return Session(name=session.name, streams=session.streams, steps=session.steps, trajectory=session.trajectory,
                   extras=extras, meta=session.meta, frames=session.frames), rows


#: decision D51: the side column of a footfall list (a walkway's one row per footfall) and its values' spellings
SIDE_COLUMNS = ("foot", "side")
SIDE_WORDS = {"l": "left", "left": "left", "r": "right", "right": "right"}
#: decision D51: the per-footfall columns an IC list's strides keep (:func:`pdrlearn.io.ic_reference.ic_strides`)
FOOTFALL_COLUMNS = ("tc_s", "length_m")


def _footfall_sides(table: pd.DataFrame, path: Path) -> pd.Series | None:
    """Decision D51 (B338's ``foot``): the side of each footfall, ``left`` / ``right``, from the table's ``foot`` or
    ``side`` column (L / R accepted, any case); None without one. Two such columns, or another value, is one line."""
    cols = [c for c in table.columns if str(c).strip().lower() in SIDE_COLUMNS]
    if not cols:
        return None
    if len(cols) > 1:
        raise DataError(f"{path}: both {' and '.join(cols)} columns; keep one side column (foot or side: left / "
                        "right, L / R; decision D51)")
    raw = table[cols[0]].astype(str).str.strip().str.lower()
    sides = raw.map(SIDE_WORDS)
    if sides.isna().any():
        bad = sorted(set(raw[sides.isna()]))[:3]
        raise DataError(f"{path}: column {cols[0]} has {', '.join(map(repr, bad))}; a footfall's side is left / right "
                        "(or L / R) (decision D51)")
    return sides


def _ic_list_strides(table: pd.DataFrame, path: Path, foot: str | None, unit: str = "foot") -> pd.DataFrame:
    """Decision B338: an IC list (``ic_ms``, optionally ``foot``) as G2 strides of the instrumented foot. Decision
    D51: a walkway's per-footfall table (side as ``foot`` or ``side``, L / R too; ``tc_ms``, ``length_m``) gives
    the strides their toe-off and length (:func:`pdrlearn.io.ic_reference.ic_strides`); any other column is named
    in one warning line as not read."""
    from pdrlearn.io.ic_reference import ic_strides

    sides = _footfall_sides(table, path)
    if sides is not None:
        found = sorted(set(sides))
        if unit == "waist" and len(found) > 1:  # decision B352: --foot is refused there (B321)
            raise DataError(f"{path}: an initial-contact list of {' and '.join(found)} contacts, the lower back's "
                            "reference: pass it as --labels ics.csv (ic_ms,foot; the file named ics.csv) instead of "
                            "--steps, which labels one foot's strides (decision B352)")
        if foot is None and len(found) > 1:
            raise DataError(f"{path}: an initial-contact list of {' and '.join(found)} contacts; pass --foot "
                            "left|right, the foot this unit is on, to take its contacts (decision B338)")
        if foot is not None:
            table = table[sides == foot]
            if table.empty:
                raise DataError(f"{path}: no {foot} contacts in its side column ({', '.join(found)}); check --foot "
                                "(decision B338)")
    kept = [c for c in FOOTFALL_COLUMNS
            if c in table.columns and pd.to_numeric(table[c], errors="coerce").notna().any()]
    side_cols = {c for c in table.columns if str(c).strip().lower() in SIDE_COLUMNS}
    unread = [c for c in table.columns if c not in {"ic_s", *kept} | side_cols]
    times = set(table.attrs.get("time_columns", ()))

    def name(c) -> str:  # the column as the file spells it (a time column was read in ms)
        return f"{c[:-2]}_ms" if c in times else str(c)

    if unread:  # decision D51: named, not dropped without a word (trial T3 finding F3)
        # D51 amended (review R2 finding 6): a tc_ms / length_m without one number is named too, as not numeric
        names = [name(c) + (" (no number in it)" if c in FOOTFALL_COLUMNS else "") for c in unread]
        log.warning("%s: column(s) %s not read: an initial-contact list's strides keep ic_ms, the side and tc_ms, "
                    "length_m (decision D51)", path, ", ".join(names))
    out = ic_strides(table["ic_s"], **{c: pd.to_numeric(table[c], errors="coerce").to_numpy(float) for c in kept})
    given, got = int(out.attrs.get("tc_given", 0)), int(out["tc_s"].notna().sum()) if "tc_s" in out else 0
    if got < given:  # D51 amended (review R2 finding 6): toe-offs dropped are said, with how many
        log.warning("%s: %s: %d of %d toe-off(s) lie outside the stride their footfall opens (after it, before the "
                    "next %scontact) and are not kept; decision D51 reads a footfall's own toe-off - check the "
                    "walkway's toe-off convention and that %s counts on the ic_ms clock (--labels-offset moves "
                    "both)", path, name("tc_s"), given - got, given, "same-side " if sides is not None else "",
                    name("tc_s"))
    if out.empty:
        raise DataError(f"{path}: {len(table)} initial contact(s) and no two consecutive ones within a stride (3 s): "
                        "no stride to label; a foot reference needs each contact of the walk (decision B338)")
    out.attrs["from_ics"] = int(len(table))
    out.attrs["footfall_columns"] = {c: int(out[c].notna().sum()) for c in kept}  # D51: for import's steps line
    return out


def import_steps(path: str | os.PathLike, session: Session, origin_s: float, *, relative: bool = False,
                 foot: str | None = None, offset_s: float = 0.0, unit: str = "foot",
                 encoding: str | None = None) -> Session:
    """``session`` with the labelled steps of ``path`` (``start_ms,end_ms`` and ``terrain`` ... as the
    session's ``steps.csv``, times in ms on the export's clock), moved onto the session's clock (``origin_s``
    and ``offset_s``, as :func:`import_labels`, taken off) and checked as ``read_session`` checks them (decision
    D12). A table of initial contacts only (``ic_ms``, and ``foot``: those of ``foot``) becomes strides the G2
    way (decision B338, :func:`pdrlearn.io.ic_reference.ic_strides`); ``steps.attrs["from_ics"]`` counts its
    contacts; on a ``unit="waist"`` import both feet's contacts are refused, naming ``--labels ics.csv`` (decision
    B352). ``encoding``: as :func:`import_labels`."""
    from pdrlearn.io.session import STEP_COLUMNS
    from pdrlearn.io.validate import check_columns, check_numeric

    path = Path(path)
    steps = _shifted_table(path, _label_origin(session, origin_s, relative) + offset_s, encoding)
    if "ic_s" in steps.columns and not {"start_s", "end_s"} & set(steps.columns):  # decision B338
        steps = _ic_list_strides(steps, path, foot, unit)
    check_columns(steps, STEP_COLUMNS, f"{path} (times in ms on the export's clock: start_ms,end_ms)")
    check_numeric(steps, STEP_COLUMNS, str(path))
    _check_shifted_labels(steps, path, session, origin_s, relative)
    from pdrlearn.classify.labels import import_label_warnings

    for line in import_label_warnings(session, steps, str(path)):  # decision C46: not first at train
        log.warning("%s", line)
    return Session(name=session.name, streams=session.streams, steps=steps, trajectory=session.trajectory,
                   extras=session.extras, meta=session.meta, frames=session.frames)

