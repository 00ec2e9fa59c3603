"""PLASYS folder format (thesis ch.4.3.3): reader and writer.

A session folder holds one CSV per sensor (``fAccelerometer.csv`` ... ``wBarometer.csv``) with header
``timestamp,x,y,z`` (single-valued sensors: ``timestamp,x``), plus optional ``steps.csv``,
``trajectory.csv``, other label CSVs (``ics.csv``, ``bouts.csv``, ``turns.csv`` ...) and ``meta.json``.

Decision (docs/decisions.md D1): on disk, ``timestamp`` and every ``*_ms`` label column are
**milliseconds**, as in the converted real recordings; in memory they are seconds (``*_s``). A
``meta.json`` may declare ``"units": {"timestamp": "s ..."}`` (or ``"ns ..."``) for other files, and
``"clocks"`` a unit's own rate, timestamp unit and clock offset (decision B115, :mod:`pdrlearn.io.clocks`).
"""

from __future__ import annotations

import json
import logging
import math
import os
import re
import zlib
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.atomic import atomic_directory
from pdrlearn.errors import DataError, GravityRemovedError, shell_quote
from pdrlearn.io.clocks import apply_offsets, one_unit_counting, unit_clocks, unit_groups
from pdrlearn.io.frames import frames_from_meta
from pdrlearn.io.present import check_readable, present
from pdrlearn.io.sensors import SENSORS, UNIT_IMU, VALUE_UNITS, parse_value_unit
from pdrlearn.io.session import MAX_BRIDGED_S, STEP_COLUMNS, Session, Stream
from pdrlearn.io.validate import (
    TIE_ROWS,
    check_columns,
    check_label_times,
    check_last_row,
    check_numeric,
    check_rate,
    check_timestamps,
    check_trajectory_times,
    check_units,
    ends_mid_line,
    implausible_rhythm,
    restamp_isolated_ties,
    sample_numbers,
    slow_seconds_message,
    time_unit_candidates,
)
from pdrlearn.kernels.clock import stamp_jitter_s
from pdrlearn.kernels.gaps import DROPS_CAUSE, gap_turn, streamed_drops_line  # decision E230: shared with the runtime
from pdrlearn.kernels.rate_change import change_text, rate_changes
from pdrlearn.kernels.units import check_tilt_rate, data_row_lines, out_of_range, out_of_range_message
from pdrlearn.textfile import (
    compressed_hint,
    csv_stem,
    decode,
    duplicate_message,
    is_gzip,
    open_text,
    read_bytes,
    read_json,
    session_csv,
    session_csvs,
)

log = logging.getLogger(__name__)

LABEL_FILES = ("steps", "trajectory")
#: decision B41: the extra label tables the commands read, with the columns each needs (bouts.csv's length_m is
#: optional: its absence is a warning where the bout distance is scored); other CSVs are kept but read by nothing
LABEL_TABLES: dict[str, tuple[str, ...]] = {
    "ics": ("ic_ms",), "ics_stereophoto": ("ic_ms",), "ics_untimed": ("after_ms", "before_ms"),
    "bouts": ("start_ms", "end_ms"), "turns": ("start_ms", "end_ms", "angle_deg"),
}


def check_label_table(df: pd.DataFrame, name: str, where: str) -> None:
    """Decision B41: a known label table (:data:`LABEL_TABLES`) must have the columns its readers need: an
    ``ics.csv`` with ``contact_ms`` instead of ``ic_ms`` was read and then ignored (no step F1, no warning)."""
    need = LABEL_TABLES.get(name)
    if need is None:
        return
    missing = [c for c in need if c not in df.columns]
    if missing:
        spare = [str(c) for c in df.columns if str(c).endswith("_ms") and c not in need]
        fix = (f"rename {spare[0]} to {missing[0]}" if len(missing) == 1 and len(spare) == 1
               else f"rename the column(s) to {', '.join(missing)} (times in ms)")
        raise DataError(f"{where}: {name}.csv needs the column(s) {', '.join(need)} but has "
                        f"{', '.join(map(str, df.columns))}; {fix}")
_TIME_SCALE = {"ms": 1e-3, "s": 1.0, "us": 1e-6, "ns": 1e-9}
_TIME_ALIASES = {"milliseconds": "ms", "millisecond": "ms", "msec": "ms", "seconds": "s", "second": "s", "sec": "s",
                 "microseconds": "us", "microsecond": "us", "\u00b5s": "us", "nanoseconds": "ns", "nanosecond": "ns",
                 "sample": "samples", "index": "samples", "indices": "samples", "sample_index": "samples"}
#: meta.json body measures (m) read by the waist pipelines: (name, largest plausible value in m). Beyond it
#: the number is centimetres (a 175 "m" subject); the limits are anatomy, not tuned (decision B16).
_BODY_FIELDS = (("height_m", 3.0), ("leg_length_m", 2.0), ("sensor_height_m", 2.0), ("foot_length_m", 0.5))


def _timestamp_declared(meta: dict) -> bool:
    units = meta.get("units", {}) if meta else {}
    return isinstance(units, dict) and "timestamp" in units


def _timestamp_scale(meta: dict, where: str = "meta.json", rate_hz: float | None = None) -> float:
    """Seconds per timestamp unit from ``units.timestamp`` (its first word: ms, s, us, ns; default ms; or
    ``samples``: sample indices at ``rate_hz``, decision B31). An unknown word is an error (decision B16):
    guessing ms would mis-time every sample by 1000x or more."""
    units = meta.get("units", {}) if meta else {}
    if not isinstance(units, dict):
        raise DataError(f"{where}: \"units\" must be an object such as {{\"timestamp\": \"ms\"}}; fix or remove it")
    text = str(units.get("timestamp", "ms")).strip()
    word = text.split()[0].lower() if text else "ms"
    unit = _TIME_ALIASES.get(word, word)
    if unit == "samples":
        if rate_hz is None:
            raise DataError(f"{where}: units.timestamp {text[:40]!r} (sample indices) needs the sampling rate: add "
                            "\"rate_hz\" (Hz) to meta.json")
        return 1.0 / rate_hz
    if unit not in _TIME_SCALE:
        raise DataError(f"{where}: units.timestamp {text[:40]!r} does not start with ms, s, us, ns or samples; write "
                        "the timestamps' unit first (e.g. \"ms since the first sample\")")
    return _TIME_SCALE[unit]


def _declares_integer_clock(meta: dict, meta_path: Path, rate: float | None) -> bool:
    """B116 amended (review): meta.json declares a timestamp unit (not samples) and a ``rate_hz`` whose period is
    that unit (``"ms"`` and 1000 Hz): consecutive integer timestamps are then that clock, not a counter to refuse."""
    units = meta.get("units") if isinstance(meta.get("units"), dict) else {}
    if rate is None or "timestamp" not in units or str(units["timestamp"]).split()[:1] == ["samples"]:
        return False
    return abs(rate * _timestamp_scale(meta, str(meta_path), rate) - 1.0) < 0.01


def _trajectory_scale(scales: dict[str, float], clocks: dict, meta: dict, meta_path: Path,
                      rate: float | None) -> tuple[float, str]:
    """Seconds per trajectory.csv timestamp and what decided it (for a refusal): the sensor files' unit (B25),
    also with per-unit ``"clocks"`` when every unit's files were read in one unit; a declared
    ``units.timestamp`` with clocks; else the default ms, which names the clocks (B115 amended, review)."""
    units = meta.get("units") if isinstance(meta.get("units"), dict) else {}
    same = set(scales.values())
    if scales and len(same) == 1 and not (clocks and "timestamp" in units):
        return same.pop(), "the sensor files' unit"
    if clocks and "timestamp" not in units and len(same) > 1:
        return (_timestamp_scale(meta, str(meta_path), rate),
                "the default, as the units' \"clocks\" read their files in different units; declare "
                "\"units\": {\"timestamp\": ...} for it")
    return _timestamp_scale(meta, str(meta_path), rate), "meta.json's units.timestamp"


def _value_unit(meta: dict, name: str, where: str) -> tuple[float, str | None]:
    """Factor to the SI unit and the declared unit of a sensor file's values, from ``units.<file stem>``
    (its first word, :data:`pdrlearn.io.sensors.VALUE_UNITS`, or a count's size and one, decision B100; parsed by
    :func:`pdrlearn.io.sensors.parse_value_unit`, which ``pdrlearn import``'s unit options share, B313):
    ``(1.0, None)`` when none is declared. An unknown unit is an error naming meta.json."""
    units = meta.get("units") if meta else None
    spec = SENSORS[name]
    table = VALUE_UNITS.get(spec.kind)
    if not isinstance(units, dict) or name not in units or table is None:
        return 1.0, None
    text = str(units[name]).strip()
    parsed = parse_value_unit(text, spec.kind)
    if parsed is None:
        raise DataError(f"{where}: units.{name} {text[:40]!r} does not start with a {spec.kind} unit pdrlearn "
                        f"converts from ({', '.join(dict.fromkeys(table))}), or a scale factor and one (a raw count "
                        f"as \"0.0047884 m/s^2\" or \"1/2048 g\"); write the unit first, e.g. \"{spec.unit}\", or "
                        "remove the entry")
    return parsed


def _check_body_fields(meta: dict, where: str) -> None:
    """Body measures in meta.json must be positive numbers in metres (decision B16): a text or a value in
    cm would otherwise be replaced by a default or scale every waist step length silently. Decision B174: the
    ``subject`` object's measures too (waist B155 and track L148 take them before the top level's)."""
    sub = meta.get("subject")
    for prefix, src in (("", meta), ("subject.", sub if isinstance(sub, dict) else {})):
        for name, most in _BODY_FIELDS:
            if name not in src or src[name] is None:
                continue
            v, key = src[name], prefix + name
            if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v <= 0:
                raise DataError(f"{where}: {key} {v!r} is not a positive number in m; fix it or remove the field")
            if v > most:
                raise DataError(f"{where}: {key} {v:g} m is implausible (over {most:g} m; centimetres?); give metres")


def read_table(path: str | os.PathLike, text_columns: tuple[str, ...] = (), *, header: bool = True,
               encoding: str | None = None, not_utf8_also: str = "") -> pd.DataFrame:
    """Read a CSV file with stripped column names; a missing, empty or malformed file is a one-line
    :class:`DataError`. ``text_columns``: columns kept as written (``007`` stays ``007``, not the number 7).
    ``header=False``: the file has no header line (MATLAB's ``writematrix``), its columns are named by their
    index from 0, ``"0"``, ``"1"`` ... (decision B336). ``encoding``: the file's text encoding (``pdrlearn import
    --encoding cp1252``, decision B344); default UTF-8 (a BOM accepted), else B221's line, ending with
    ``not_utf8_also``."""
    from pdrlearn.io.matfile import mat_message, mat_version

    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: file not found")
    no_header = {} if header else {"header": None}  # decision B336
    try:
        dialect = _csv_dialect(path, encoding, header=header)
        df = pd.read_csv(path, dtype=dict.fromkeys(text_columns, str) or None, **dialect, **no_header)
    except pd.errors.EmptyDataError:
        raise DataError(f"{path}: file is empty (not even a header line); re-export or remove it") from None
    except UnicodeError:
        version = mat_version(path)
        if version:  # decision B335: a MAT file read as text says what it is
            raise DataError(mat_message(path, version)) from None
        if encoding is not None:  # decision B344: not the encoding given
            raise DataError(f"{path}: not {encoding} text (--encoding {encoding}); give the encoding the file was "
                            "saved in (cp1252, latin-1, utf-16), or leave --encoding out for UTF-8") from None
        decode(path, read_bytes(path), not_utf8_also)  # decision B221: raises the one line naming the first byte
        raise DataError(f"{path}: not UTF-8 text; save it as UTF-8 (decision B221)") from None
    except pd.errors.ParserError as exc:
        first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise DataError(f"{path}: not a valid CSV ({first}); fix or re-export the file") from None
    except (OSError, EOFError, zlib.error) as exc:
        if not is_gzip(path):
            raise
        read_bytes(path)  # decision B369: a damaged .csv.gz, B369's one line
        raise DataError(f"{path}: not a readable gzip file ({exc}); re-compress it (decision B369)") from None
    names = [str(c).strip() for c in df.columns]
    if not df.index.equals(pd.RangeIndex(len(df))) and len(names) > 1 and not names[0].startswith("#"):
        # pandas took the extra fields of each row as an index (a one-name header, a comment line above the real
        # header, is left to the column checks, which name it)
        raise DataError(f"{path}: rows have more fields than the header's {len(df.columns)} names "
                        f"({','.join(names)}): decimal commas in a comma-separated file, "
                        "or a comma ending each row? quote the decimal-comma values or separate the fields with ';', "
                        "and remove commas at the ends of rows (decision B225)")
    df.columns = [str(c).strip() for c in df.columns]
    _refuse_us_thousands(df, path, comma=dialect.get("decimal") == ",")

    def text() -> pd.DataFrame:  # the cells as written, for decision B112 (read only when a column may need it)
        raw = pd.read_csv(path, dtype=str, **dialect, **no_header)
        raw.columns = df.columns
        return raw

    _decimal_comma_columns(df, text, comma=dialect.get("decimal") == ",")
    return _labels_as_written(df, path, text_columns, {**dialect, **no_header})


def _labels_as_written(df: pd.DataFrame, path: Path, text_columns: tuple[str, ...], options: dict) -> pd.DataFrame:
    """Decision C263: :func:`read_table`'s ``text_columns`` hold each cell as written - "NA", "null", "None", "nan"
    are names (a group folder "NA": pandas' missing-value words had made it NaN, and the report crashed); only an
    empty cell is missing."""
    at = [i for i, c in enumerate(df.columns) if c in text_columns]
    if not at or not len(df):
        return df
    raw = pd.read_csv(path, dtype=str, keep_default_na=False, **options)
    if raw.shape != df.shape:
        return df
    for i in at:
        cells = raw.iloc[:, i]
        df.isetitem(i, cells.mask(cells == ""))
    return df


def session_table(path: str | os.PathLike, widest: tuple[int, str] | None = None) -> pd.DataFrame:
    """:func:`read_table` for a session folder's files (sensor files, steps.csv, trajectory.csv, label tables):
    column names matched in any case (decision B222: ``TIMESTAMP,X,Y,Z`` and ``START_MS`` are read as the
    lower-case names, as the lean runtime and ``pdrlearn import`` read them), and a name given twice refused in
    one line (decision B223: ``timestamp,x,x,y,z`` had silently used the first ``x``). Decisions B426, B427: a
    header naming more columns than ``widest`` (the most and the rest of the refusal; default a label table's,
    :data:`MAX_TABLE_COLUMNS`) is refused before the body is read."""
    most, what = widest or (MAX_TABLE_COLUMNS, "a session's table may have (decision B427): keep the columns it "
                            "needs (docs/columns.md) and move the others to a file outside the session folder")
    width = _header_width(Path(path))
    if width > most:  # decisions B426, B427: before the body, which pandas would widen to every name
        raise DataError(f"{path}: the header names {width} columns, more than the {most} {what}")
    df = read_table(path)
    names = [str(c) for c in df.columns]
    if any(re.fullmatch(r"(.+)\.\d+", c) and re.fullmatch(r"(.+)\.\d+", c)[1] in names for c in names):
        # pandas renamed a repeated name (x, x.1): the header as written says which
        raw = pd.read_csv(path, header=None, nrows=1, dtype=str, keep_default_na=False, **_csv_dialect(Path(path)))
        names = [str(c).strip() for c in raw.iloc[0]]
    dup = duplicate_message(path, names, ",".join(names))
    if dup:
        raise DataError(dup)
    df.attrs["header"] = [str(c) for c in df.columns]  # as written, for the messages (check_columns)
    df.columns = [c.lower() for c in df.columns]
    return df


#: decision B225: a number whose commas group thousands as US spreadsheets write them (``1,000``, ``12,345.5``)
_US_GROUPED = r"[+-]?\d{1,3}(?:,\d{3})+(?:\.\d*)?"


def _refuse_us_thousands(df: pd.DataFrame, path: Path, *, comma: bool) -> None:
    """Decision B225: in a file whose numbers have decimal points (a column read as numbers with fractions), a
    text column whose values with a comma all group thousands (``"1,000"``, US Excel's ``#,##0``) is refused in
    one line naming it: B24 would read ``1,000`` as a decimal comma (1.0), and the advice was to sort the file."""
    if comma or all(t.kind in "biufc" for t in df.dtypes):  # E308: no text column, nothing to refuse
        return
    if not any(df[c].dtype.kind == "f" and (df[c].dropna() % 1 != 0).any() for c in df.columns):
        return
    for c in df.columns:
        if df[c].dtype.kind in "biufc":
            continue
        cells = df[c].dropna().astype(str).str.strip()
        grouped = cells[cells.str.contains(",", regex=False)]
        if len(grouped) and grouped.str.fullmatch(_US_GROUPED).all():
            line = int(np.flatnonzero(cells.index == grouped.index[0])[0]) + 2
            raise DataError(f"{path}: column {str(c).strip()} holds {grouped.iloc[0]!r} (line {line}) beside decimal "
                            "points in other columns: a comma grouping thousands (US spreadsheet format #,##0)? "
                            "save the column as plain numbers without thousands separators (decision B225)")


#: a number written with a decimal comma (or an integer): what a text column of a ';' / tab file must hold
#: throughout to be read as numbers (decision B24)
_DECIMAL_COMMA = r"[+-]?(?:\d+(?:,\d*)?|,\d+)(?:[eE][+-]?\d+)?"
#: decision B85: a decimal-comma number with points grouping its thousands (German Excel's ``#.##0,0``: ``1.002,3``)
_GROUPED_DECIMAL_COMMA = r"[+-]?(?:\d{1,3}(?:\.\d{3})+|\d+)(?:,\d*)?"


def _decimal_comma_columns(df: pd.DataFrame, text=None, *, comma: bool = False) -> None:
    """Decision B24, in place: a column read as text whose every value is a number written with a decimal
    comma (or an integer; decision B85: with points grouping its thousands, ``1.002,3``) becomes numbers: in a
    file separated by ';' or tabs whose first data line, which :func:`_csv_dialect` looks at, held integers only,
    and in a comma file whose values are quoted ("0,5", a spreadsheet's comma export in a decimal-comma locale).
    Decision B112, per file: when a column was read or written with a decimal comma (``comma``: the file was
    read with ``decimal=","``), the file's points group thousands, so a column of integers with grouping points
    (``#.##0``: ``1.012`` next to ``998``) is read as integers (:func:`_grouped_integer_columns`; ``text()`` gives
    the cells as written, for a column pandas already read as decimal points). Other text columns are kept;
    numeric columns cost nothing."""
    for c in df.columns:
        col = df[c]
        if col.dtype.kind in "biufc":
            continue
        text_c = col.dropna().astype(str).str.strip()
        if not (len(text_c) and text_c.str.contains(",", regex=False).any()):
            continue
        if text_c.str.fullmatch(_DECIMAL_COMMA).all():
            df[c] = pd.to_numeric(text_c.str.replace(",", ".", regex=False)).reindex(df.index)
            comma = True
        elif text_c.str.contains(".", regex=False).any() and text_c.str.fullmatch(_GROUPED_DECIMAL_COMMA).all():
            # B85: beside a decimal comma a point groups
            df[c] = pd.to_numeric(text_c.str.replace(".", "", regex=False).str.replace(",", ".", regex=False)
                                  ).reindex(df.index)
            comma = True
    if comma:
        _grouped_integer_columns(df, text)


#: decision B112: an integer with points grouping its thousands (``1.012``, ``12.345.678``), or without (``998``)
_GROUPED_INTEGER = r"[+-]?(?:[1-9]\d{0,2}(?:\.\d{3})+|\d+)"


def _grouped_integer_columns(df: pd.DataFrame, text=None) -> None:
    """Decision B112, in place, for a file that writes decimal commas: each column whose cells all read as
    integers, some with points grouping thousands (``1.012``, ``998``), becomes those integers. A text column is
    checked as it is; a column pandas read as decimal points (1.012, 998.0) only when every value could be such
    a cell (a multiple of 0.001, the fractions between 1 and 1000), on its cells as written (``text()``)."""
    raw = None
    for c in df.columns:
        col = df[c]
        if col.dtype.kind == "f":
            v = col.dropna().to_numpy(float)
            frac = v != np.round(v)
            if not (frac.any() and np.allclose(v * 1000, np.round(v * 1000), rtol=0, atol=1e-6)
                    and np.all((np.abs(v[frac]) > 1) & (np.abs(v[frac]) < 1000)) and text is not None):
                continue
            raw = text() if raw is None else raw
            col = raw[c]
        elif col.dtype.kind in "biuc":
            continue
        cells = col.dropna().astype(str).str.strip()
        if (len(cells) and cells.str.contains(".", regex=False).any()
                and cells.str.fullmatch(_GROUPED_INTEGER).all()):
            df[c] = pd.to_numeric(cells.str.replace(".", "", regex=False)).reindex(df.index)


def _csv_dialect(path: Path, encoding: str | None = None, *, header: bool = True) -> dict:
    """``pd.read_csv`` options for a CSV written with another separator (decision B24): a header line with
    no comma but semicolons (a spreadsheet in a decimal-comma locale) or tabs is read with that separator,
    and, when its first data line has commas and no point, with ``decimal=","`` (the fast path; a decimal-comma
    column it misses is converted by :func:`_decimal_comma_columns`). Comma files are untouched. An ``encoding``
    (decision B344) is read with and passed on. ``header=False`` (decision B351): the first line is data, so a
    ``;`` or tab in it is the separator and a digit,digit in it a decimal comma."""
    enc = {"encoding": encoding} if encoding is not None else {}
    return {**_separator_dialect(path, encoding or "utf-8", header), **enc}


def _separator_dialect(path: Path, encoding: str, has_header: bool = True) -> dict:
    """:func:`_csv_dialect`'s separator, ``sep=`` line and decimal comma."""
    try:
        with open_text(path, encoding=encoding, errors="replace") as f:  # decision B369: a .csv.gz too
            header, first = f.readline(), f.readline()
            declared = _sep_line(header)
            if declared is not None:  # decision B66: Excel's "sep=X" first line (Shimmer Consensys exports)
                header, first = first, f.readline()
    except OSError:
        return {}
    skip = {"skiprows": [0]} if declared is not None else {}
    if not has_header and not declared:  # decision B351: a headerless file's first line is a data line
        sep = ";" if ";" in header else "\t" if "\t" in header else None
        comma = sep is not None and re.search(r"\d,\d", header) is not None
        return {"sep": sep, **({"decimal": ","} if comma else {})} if sep else {}
    if declared:
        sep = declared
    elif "," in header:
        return skip
    else:
        sep = ";" if ";" in header else "\t" if "\t" in header else None
    if sep is None:
        return skip
    if sep == ",":
        return skip
    return {"sep": sep, **skip, **({"decimal": ","} if "," in first and "." not in first else {})}


def _sep_line(line: str) -> str | None:
    """Decision B66: the separator an Excel-style first line ``sep=X`` declares (``sep=\\t`` or a tab is a tab;
    the line may be quoted); ``""`` when the line is ``sep=`` with nothing recognisable after it (the
    separator is then detected from the header line); ``None`` when the line is not a ``sep=`` line."""
    text = line.rstrip("\r\n").lstrip("\ufeff").strip("\"'")
    if not text.lower().startswith("sep="):
        return None
    val = text[4:].strip("\"'")
    if val.startswith("\\t") or val.startswith("\t"):
        return "\t"
    return val[0] if val and val[0] in ",;|" else ""


def read_stream(path: str | os.PathLike, name: str | None = None, *, time_scale: float = 1e-3,
                check_unit: bool = True, value_scale: float = 1.0) -> Stream:
    """Read one sensor CSV into a :class:`Stream` (timestamps converted to seconds)."""
    path = path_arg(path, "read_stream", "a sensor CSV file")  # decision B349
    name, arr = _read_raw(path, name)
    return _to_stream(path, name, arr, time_scale, check_unit, (value_scale, None))


def _read_raw(path: str | os.PathLike, name: str | None = None, *,
              drop_partial_row: bool = False, command: str | None = None) -> tuple[str, np.ndarray]:
    """One sensor CSV's name and numeric array (timestamps in the file's unit, then the value columns).
    ``drop_partial_row`` (decision B266, ``track --drop-partial-row``): a file that does not end with a line break
    (B128: its last row may be cut mid-row, a unit whose battery died) loses its last line, with one warning.
    ``command``: the command line B128's refusal names with ``--drop-partial-row`` (decision B279)."""
    path = Path(path)
    name = name or csv_stem(path)  # decision B369: fAccelerometer.csv.gz is fAccelerometer
    if name not in SENSORS:
        raise DataError(f"{path}: unknown sensor file; expected one of {', '.join(s + '.csv' for s in SENSORS)}")
    spec = SENSORS[name]
    if not path.is_file():
        raise DataError(f"{path}: file not found")
    want = ("timestamp", *spec.columns)
    df = session_table(path, widest=(MAX_SENSOR_COLUMNS, f"a sensor file may have (it needs {','.join(want)}; "
                                     "decision B426): keep those columns and drop the others"))  # B222, B223, B426
    check_columns(df, want, str(path))
    _warn_extra_columns(df, want, path)  # decision B426
    cut = ends_mid_line(path)
    if drop_partial_row and cut and len(df) > 1:  # decision B266: the dead battery's last row, said once
        df = df.iloc[:-1]
        cut = False
        log.warning("%s: the last line (line %d) has no line break at the end, as a row cut when a battery died: "
                    "dropped (--drop-partial-row, decision B266)", path, len(df) + 2)
    _refuse_datetimes(df["timestamp"], path)
    return name, check_numeric(df, ("timestamp", *spec.columns), str(path), cut_mid_line=cut, command=command,
                               row_line=lambda row: _row_line(path, int(row)))  # decision B437: the real line


#: decision B426: the most columns a sensor file's header may name. A sensor file needs 2 or 4 (``timestamp,x,y,z``,
#: thesis ch.4.3.3); an export's extra columns (accuracy, temperature, a second clock) are a few. A header of 20 000
#: extra names took 26 s to read and 1 000 000 over 5 minutes and 9 GB (trial T1 F6, session 42): pandas gives
#: every row a cell under every name. The header is counted before the body is read
MAX_SENSOR_COLUMNS = 64
#: decision B427: the most columns a session folder's other tables (steps.csv, trajectory.csv, label tables) may
#: name: pdrlearn's own have under 20; a steps.csv with 20 000 extra names (17 rows) took `info` 36.95 s
MAX_TABLE_COLUMNS = 1000


def _header_width(path: Path) -> int:
    """Decision B426: the number of fields of a CSV's header line (after a B66 ``sep=`` line), its separators
    counted (a separator inside a quoted name counts too: a stricter count), without reading the body."""
    dialect = _csv_dialect(path)
    try:
        with open_text(path, errors="replace") as f:  # decision B369: a .csv.gz too
            line = f.readline()
            if dialect.get("skiprows"):  # decision B66: the header follows the sep= line
                line = f.readline()
    except (OSError, EOFError, zlib.error):  # read_table names the damage
        return 0
    return line.count(dialect.get("sep") or ",") + 1


def _warn_extra_columns(df: pd.DataFrame, want: tuple[str, ...], path: Path) -> None:
    """Decision B426: one warning naming a sensor file's columns besides ``want`` (read by name, B222), which are
    not read, so that a column the user meant (``acc_x`` beside ``x``) is not dropped without a word. An empty
    column without a name (a separator ending every line) is not named."""
    written = df.attrs.get("header", list(df.columns))
    extra = [str(w) for w, c in zip(written, df.columns, strict=True)
             if c not in want and not (str(c).startswith("unnamed:") and df[c].isna().all())]
    if extra:
        shown = ", ".join(repr(e) for e in extra[:3]) + (f" and {len(extra) - 3} more" if len(extra) > 3 else "")
        log.warning("%s: %d column(s) besides %s not read: %s (decision B426)", path, len(extra), ",".join(want),
                    shown)


def _refuse_datetimes(col: pd.Series, path: Path) -> None:
    """Decision B154: a timestamp column of date-times (``2026-03-29T00:59:50+01:00``, as the importer reads them,
    :func:`pdrlearn.io.importer._datetime_seconds`) is refused in one line saying so and how to convert, instead of
    "N row(s) with non-numeric values". Not converted here: a session folder's files, steps.csv and label tables
    share one clock of numbers in ms, which a date-time column would leave to a guess."""
    from pdrlearn.io.importer import _datetime_seconds

    if col.dtype.kind in "biufc":
        return
    bad = pd.to_numeric(col, errors="coerce").isna() & col.notna()
    if not bad.any():
        return
    first = int(np.flatnonzero(bad.to_numpy())[0])
    try:
        is_date = _datetime_seconds(col.iloc[first:first + 1].astype(str)) is not None
    except DataError:  # an ambiguous day/month: still a date
        is_date = True
    if is_date:
        raise DataError(f"{path}: column timestamp holds date-times ({col.iloc[first]!r} at line {first + 2}), not "
                        "numbers; write the times as numbers in ms (since the epoch or the recording's start, the "
                        "same clock as the session's other files and steps.csv), or turn a one-CSV export into a "
                        "session with `pdrlearn import FILE --out DIR`, which reads date-time columns (decision B154)")


def _unwrapped(raw: dict[str, np.ndarray], folder: Path) -> dict[str, np.ndarray]:
    """Decision B312: the sensor files whose timestamp counter wraps around (:func:`~pdrlearn.kernels.counter_wrap.
    counter_wraps`) with their timestamps unwrapped; one warning line for the files that wrap alike (every file of
    a recorder's counter), naming them and the first wrap."""
    from pdrlearn.kernels.counter_wrap import counter_wraps, unwrap, wrap_message

    out, alike = dict(raw), {}
    for name, arr in raw.items():
        bits, idx = counter_wraps(arr[:, 0])
        if bits:
            out[name] = np.column_stack([unwrap(arr[:, 0], bits, idx), arr[:, 1:]])
            alike.setdefault((bits, idx.size, float(arr[idx[0], 0])), []).append((name, arr, idx))
    for (bits, _, _), files in alike.items():
        name, arr, idx = files[0]
        names = ", ".join(session_csv(folder, n).name for n, _, _ in files)
        log.warning("%s", wrap_message(f"{folder}: {names}", arr[:, 0], bits, idx, "ticks", int(idx[0]) + 3))
    return out


def _to_stream(path: str | os.PathLike, name: str, arr: np.ndarray, time_scale: float, check_unit: bool,
               value_unit: tuple[float, str | None] = (1.0, None)) -> Stream:
    t = arr[:, 0] * time_scale
    factor, declared = value_unit
    _refuse_out_of_range(path, name, arr, t, check_unit, value_unit)  # decision B425
    t, moved = restamp_isolated_ties(t, arr[:, 1:])  # decision B185
    if moved:
        log.warning("%s: %d timestamp(s) equal to the previous row's, with other values (jittered stamps rounded?): "
                    "each moved halfway to the next row's (decision B185); more than one in %d rows is refused",
                    path, moved, TIE_ROWS)
    check_timestamps(t, str(path))
    check_rate(t, str(path))
    # B32: a declared unit, converted to SI. Decision E195: the values in an array of their own (same memory
    # order), so that the file's array, whose timestamp column t replaces, is freed (a whole-day session: 23 MB/h)
    values = arr[:, 1:] * factor if factor != 1.0 else arr[:, 1:].copy(order="K")
    if check_unit:
        _check_value_unit(path, name, values, t, declared)
    return Stream(name, t, values)


def check_tilt_rates(streams: dict[str, Stream], files: dict[str, Path], units: tuple[str, ...] = ("waist",)) -> None:
    """Decision B476: B40's tilt-rate test (:func:`pdrlearn.kernels.units.check_tilt_rate`, which ``pdrlearn import``
    runs) on each of ``units`` of a session folder with both an accelerometer and a gyroscope: a gyroscope file in
    deg/s without a declared unit is one line naming the file and the meta.json declaration that fixes it. The lower
    back by default: a walking foot's gyroscope in deg/s is B30's already (p99 |rate| over 40, a walking foot's p99 is
    >= 4.75 rad/s, B37), while the lower back's (0.57-2.35 rad/s) passes B30 until a turn."""
    for unit in units:
        acc_name, gyro_name = UNIT_IMU[unit]
        if acc_name in streams and gyro_name in streams:
            a, g = streams[acc_name], streams[gyro_name]
            check_tilt_rate(a.t, a.values, g.t, g.values, str(files[gyro_name]),
                            f"declare \"units\": {{\"{gyro_name}\": \"deg/s\"}} in meta.json (decisions B40, B476)")


def _check_value_unit(path, name: str, values: np.ndarray, t: np.ndarray, declared: str | None) -> None:
    """B30's unit checks of a sensor file's values (SI), naming meta.json's declared unit when there is one."""
    try:
        check_units(SENSORS[name], values, str(path), t=t)
    except DataError as exc:
        if declared is None or isinstance(exc, GravityRemovedError):  # B202: not a question of the unit
            raise
        raise DataError(f"{exc} (the values were converted from {declared!r}, the unit meta.json declares for "
                        "them: is that unit right?)") from None


def _refuse_out_of_range(path, name: str, arr: np.ndarray, t: np.ndarray, check_unit: bool,
                         value_unit: tuple[float, str | None]) -> None:
    """Decision B425: a sensor file with a value beyond any sensor's range (:data:`~pdrlearn.kernels.units.
    VALUE_LIMITS`; 1e308 had overflowed the step detectors into "0 strides" or "this is a bug") is one line naming
    the file, the line and the value. A whole file in another unit (counts, mm/s^2, deg/s) is B30's wrong-unit
    line, checked first: its statistics are medians and percentiles, which the few corrupt rows do not move (their
    squares may overflow there, silently). Decision B433: with ``check_unit`` False (``read_session(...,
    check_units=False)``, the documented opt-out of the unit rules) such a whole file is read as written, for the
    caller to convert, and only a file B30 passes is refused for its corrupt rows."""
    factor, declared = value_unit
    spec = SENSORS[name]
    rows = out_of_range(spec.kind, arr[:, 1:], factor)
    if not rows.size:
        return
    with np.errstate(over="ignore", invalid="ignore"):
        try:
            _check_value_unit(path, name, arr[:, 1:] * factor, t, declared)
        except DataError:
            if check_unit:
                raise
            return  # decision B433: another unit, which check_units=False leaves to the caller
    row = int(rows[0])
    raise DataError(out_of_range_message(str(path), spec, arr[:, 1:], rows, factor,
                                         first_line=_row_line(Path(path), row) - row))


def _row_line(path: Path, row: int) -> int:
    """The file line (from 1) of data row ``row`` of a sensor file read by :func:`read_table`: after the header and
    a B66 ``sep=`` line, blank lines skipped as pandas skips them (review R2 finding 4: B425 had named ``row + 2``,
    a line early after a ``sep=`` line or a blank line). Read again only for a refusal's line."""
    header_lines = 1 + len(_csv_dialect(path).get("skiprows", ()))
    try:
        with open_text(path, errors="replace") as f:  # decision B369: a .csv.gz too
            lines = data_row_lines(f.read().splitlines(), header_lines)
    except (OSError, EOFError, zlib.error):
        lines = []
    return lines[row] if row < len(lines) else row + 1 + header_lines


def imported_rate(meta: dict) -> float | None:
    """Decision B304: the accelerometer/gyroscope rate (Hz) that ``pdrlearn import`` recorded in meta.json's
    ``imported`` record(s) (``streams.<name>.rate_hz``) when every such stream has the same one (within 1 %), else
    None: a folder the import wrote at 1000 Hz, in integer ms, is then read as ms and not refused as sample counters
    (B98), as with a top-level ``rate_hz``."""
    recs = meta.get("imported")
    recs = recs if isinstance(recs, list) else [recs] if isinstance(recs, dict) else []
    rates = [v.get("rate_hz") for r in recs if isinstance(r, dict) and isinstance(r.get("streams"), dict)
             for n, v in r["streams"].items()
             if n in SENSORS and SENSORS[n].kind in ("accelerometer", "gyroscope") and isinstance(v, dict)]
    if not rates or not all(isinstance(r, int | float) and not isinstance(r, bool) and math.isfinite(r) and r > 0
                            for r in rates):
        return None
    return float(rates[0]) if max(rates) <= 1.01 * min(rates) else None


def meta_rate(meta: dict, meta_path: Path) -> float | None:
    """meta.json's ``rate_hz`` (Hz), else the rate ``pdrlearn import`` recorded (decision B304), else None; a
    ``rate_hz`` that is no positive number is one line."""
    rate = meta.get("rate_hz")
    if rate is not None and (isinstance(rate, bool) or not isinstance(rate, int | float) or not math.isfinite(rate)
                             or rate <= 0):
        raise DataError(f"{meta_path}: rate_hz {rate!r} is not a positive number of Hz; fix it or remove the field")
    return float(rate) if rate is not None else imported_rate(meta)  # decision B304: an import's own rate


def _session_time_unit(raw: dict[str, np.ndarray], rate_hz: float | None, meta_path: Path) -> str | None:
    """Decision B22: the one timestamp unit of a session whose meta.json declares none, from every sensor
    file at once (a unit every file's rate allows; the accelerometer and gyroscope files held to
    ``rate_hz``, the magnetometer, force and barometer files, which may log at their own rates, not).
    ``None`` = milliseconds (also when ms fits, or nothing decides: B9's checks follow)."""
    imu = {n for n in raw if SENSORS[n].kind in ("accelerometer", "gyroscope")}
    for n in sorted(imu):  # decision B161: seconds of a slow logger are neither an IMU's seconds nor its ms
        slow = slow_seconds_message(raw[n][:, 0], str(session_csv(meta_path.parent, n)),
                                    "declare \"units\": {\"timestamp\": \"ms\"} in meta.json")
        if slow:
            raise DataError(slow)
    cands = {n: time_unit_candidates(a[:, 0], rate_hz if n in imu else None, inertial=n in imu)  # B144's floor
             for n, a in raw.items()}
    common = [u for u, _ in time_unit_candidates(np.zeros(0)) if all(u in [c for c, _ in v] for v in cands.values())]
    if "ms" in common or len(common) > 1:
        return None
    if common:
        return common[0]
    single = {n: v[0][0] for n, v in cands.items() if len(v) == 1}
    if set(single.values()) - {"ms"}:  # the files contradict each other
        raise DataError(f"{meta_path}: declares no timestamp unit and the sensor files disagree (" + ", ".join(
            f"{n}: {single.get(n) or '/'.join(c for c, _ in v) or 'no unit at rate_hz'}" for n, v in cands.items())
            + "); write every file in ms or declare \"units\": {\"timestamp\": ...} in meta.json")
    return None


def _index_clock(raw: dict[str, np.ndarray]) -> bool:
    """True when every accelerometer/gyroscope file's timestamps are sample numbers (integers stepping by 1 from
    near 0, B39's :func:`~pdrlearn.io.validate.sample_numbers`; or a 1000 Hz clock in integer ms; decisions B31,
    B98)."""
    imu = [a[:, 0] for n, a in raw.items() if SENSORS[n].kind in ("accelerometer", "gyroscope")]
    return bool(imu) and all(sample_numbers(t) for t in imu)


def _index_unit(raw: dict[str, np.ndarray], rate_hz: float | None, folder: Path, meta_path: Path, *,
                declared: bool = False) -> str | None:
    """Decisions B31, B98, for a session whose IMU timestamps step by 1 and declare no unit: ``"samples"``
    when meta.json's ``rate_hz`` contradicts the 1000 Hz of an ms reading (by more than B22's 10 %), ``None``
    (ms) when it agrees; with no ``rate_hz`` a :class:`DataError`: sample counters (a 1024, 800 or 400 Hz
    counter) and a 1000 Hz clock in ms write the same numbers, and only ``rate_hz`` tells them apart (B98; the
    walking rhythm of :func:`pdrlearn.io.validate.implausible_rhythm`, B31, is named when it tells).
    ``declared``: meta.json declares the timestamps ms (a template's "ms since the first sample"); the fix then
    also names the ``samples`` unit."""
    if rate_hz is not None:
        return "samples" if abs(1000.0 - rate_hz) > 0.1 * rate_hz else None
    acc = next((n for n in raw if SENSORS[n].kind == "accelerometer"), None)
    name = acc or next(n for n in raw if SENSORS[n].kind == "gyroscope")
    lag = implausible_rhythm(raw[acc][:, 1:], 1000.0) if acc is not None else None
    t = raw[name][:, 0]
    rhythm = (f"; read as ms (1000 Hz) its walking rhythm repeats every {1e3 * lag:.0f} ms, faster than any gait"
              if lag is not None else "")
    unit = ("; and \"units\": {\"timestamp\": \"samples\"} instead of ms if they count samples" if declared
            else "")
    raise DataError(f"{session_csv(folder, name)}: its timestamps are consecutive integers "
                    f"({t[0]:.0f}-{t[-1]:.0f}): these look like sample counters, not ms{rhythm}; give the sampling "
                    f"rate in {meta_path.name}: \"rate_hz\": <Hz> (1000 if they are ms{unit}), or write each "
                    "sample's time in ms")


def _group_time_scale(raw: dict[str, np.ndarray], meta: dict, rate: float | None, folder: Path,
                      meta_path: Path) -> tuple[float, str | None]:
    """Seconds per timestamp unit of sensor files that share one clock (the whole session, or one unit of a
    session with per-unit ``clocks``, decision B115) and the unit read when meta.json declares none: the declared
    unit (B16), else the one every file's rate allows (B22), else sample indices at ``rate`` (B31) or, without
    ``rate``, the refusal of sample counters (B98)."""
    scale = _timestamp_scale(meta, str(meta_path), rate)
    declared = _timestamp_declared(meta)
    unit = _session_time_unit(raw, rate, meta_path) if raw and not declared else None
    # decisions B31, B98: sample counters, not ms (a declared ms unit too, unless rate_hz says which)
    if unit is None and raw and (not declared or (scale == 1e-3 and rate is None)) and _index_clock(raw):
        unit = _index_unit(raw, rate, folder, meta_path, declared=declared)
    if unit == "samples":
        scale = 1.0 / rate
    elif unit is not None:  # decision B22: one unit for every file, said once
        scale = _TIME_SCALE[unit]
    return scale, unit


def _check_declared_rate(streams: dict[str, Stream], rate_hz: float, meta_path: Path) -> None:
    """Decision B32: meta.json's ``rate_hz`` (the native rate of the accelerometer and gyroscope, what B22 reads
    the timestamp unit by) must agree with their timestamps within B22's 10 %; else one warning: the
    timestamps are used, the field is wrong or the timestamps are."""
    off = {n: s.rate_hz for n, s in streams.items() if s.kind in ("accelerometer", "gyroscope") and len(s) > 2
           and abs(s.rate_hz - rate_hz) > 0.1 * rate_hz}
    if off:
        log.warning("%s: rate_hz %g contradicts the timestamps (%s); the timestamps are used: correct rate_hz, or "
                    "the timestamps if they are the wrong ones", meta_path, rate_hz,
                    ", ".join(f"{n} {r:.4g} Hz" for n, r in off.items()))


#: decision B182: timestamps jittering by more than this fraction of the period (SD about a uniform clock,
#: :func:`pdrlearn.kernels.clock.stamp_jitter_s`; uniform +-0.35 periods) are warned once per session
WARN_STAMP_JITTER = 0.2


def _warn_jitter(streams: dict[str, Stream], folder: Path) -> None:
    """Decision B182: one warning naming the jittered accelerometers and gyroscopes (B33) whose stamps jitter by
    more than :data:`WARN_STAMP_JITTER` of the period: receive-time stamps (a BLE link, a phone app). Their rate is
    the sample count over the span and only intervals over the jitter's reach count as dropped samples."""
    bad = {}
    for name, s in streams.items():
        if s.kind in ("accelerometer", "gyroscope") and len(s) >= 10 and s.jittered:
            j = stamp_jitter_s(s.t) / s.period_s
            if j > WARN_STAMP_JITTER:
                bad[name] = (j, s)
    if bad:
        j, s = max(bad.values(), key=lambda v: v[0])
        log.warning("%s: %s timestamps jitter by up to %.0f %% of the sample period (SD about a uniform clock; "
                    "receive-time stamps of a Bluetooth link or a phone app?): the rate is the sample count over the "
                    "span (%s) and only an interval over %.1f periods counts as dropped samples (decision B182); "
                    "stamp the samples on the sensor's own clock if it has one", folder, ", ".join(bad), 100 * j,
                    ", ".join(f"{n} {v[1].rate_hz:.4g} Hz" for n, v in bad.items()),
                    s._gap_limit() / s.period_s)




def _uniform_clocks(streams: dict[str, Stream], folder: Path) -> None:
    """Decision B33, in place: an accelerometer or gyroscope whose sample intervals vary by more than
    :data:`MAX_JITTER` of its period (a phone's sensor events at irregular true times) is put on a uniform clock
    (:meth:`Stream.on_uniform_clock`), with one warning for the session."""
    done = []
    for name, s in streams.items():
        if s.kind in ("accelerometer", "gyroscope") and s.jittered:
            done.append(f"{name} {s.jitter:.0%}")
            streams[name] = s.on_uniform_clock()
    if done:
        s = streams[done[0].split()[0]]
        log.warning("%s: irregular sample times (interval SD / period: %s): interpolated onto a uniform %.4g Hz clock, "
                    "as the methods integrate with a fixed sample interval", folder, ", ".join(done), s.rate_hz)


def _rate_changes(streams: dict[str, Stream], folder: Path) -> None:
    """Decisions B457 (the line) and B458 (the clock, adopted), in place: each stream whose sample rate changed
    mid-recording (a unit's rate setting, not dropped samples) is put on a uniform clock at its fastest stretch's
    period (:meth:`Stream.on_uniform_clock`, bridging up to two of its slowest periods; longer gaps stay gaps), with
    one warning per set of streams that changed the same way at the same time (to 0.1 s)."""
    groups: dict[tuple, list[str]] = {}
    for name, s in list(streams.items()):
        ch = rate_changes(s.t)
        if ch:
            key = tuple((round(c.t_s, 1), f"{c.before_hz:.4g}", f"{c.after_hz:.4g}") for c in ch)
            groups.setdefault(key, []).append(name)
            fast = min(min(1.0 / c.before_hz, 1.0 / c.after_hz) for c in ch)
            slow = max(max(1.0 / c.before_hz, 1.0 / c.after_hz) for c in ch)
            streams[name] = s.on_uniform_clock(fast, 2.0 * slow)
    for key, names in groups.items():
        rate = max(max(float(a), float(b)) for _, a, b in key)
        log.warning("%s: %s: interpolated onto a uniform %.4g Hz clock, as the offline methods integrate with one "
                    "fixed sample interval - or record at one rate", folder, change_text(names, key), rate,
                    extra={"code": "B457"})


#: decision B183: the offline distance lost per fraction of the foot's samples dropped in short intervals (B64's
#: users 1-3: 1 % -> -1.1..-3.2 %, 3 % -> -4.5..-8.8 %; the BLE trial's 5 % in bursts: -8.5..-12 %)
DROP_DISTANCE_FACTOR = 2.0
#: intervals longer than this (s) are B11's gaps, warned by the pipelines (``track.gaps``); shorter unbridged ones
#: are warned here
_GAP_WARNED_S = 1.0


def _bridge_drops(streams: dict[str, Stream], folder: Path, bridge: bool, streamed: bool = False) -> None:
    """Decision B64, in place: with ``bridge``, every stream's intervals of dropped samples up to
    :data:`MAX_BRIDGED_S` are bridged (:meth:`Stream.bridged`, said at info level); one warning names the
    streams whose dropped-sample intervals up to 1 s are left as they are (all of them without ``bridge``),
    as the pipelines integrate with a fixed sample interval and each such interval shortens its stride.
    ``streamed``: the caller integrates on the timestamps (``pdrlearn run``, ``track --streaming``); the
    warning says what that does with them instead (:data:`STREAMED_DROPS`, decision L77)."""
    done, left, lost = [], [], {}
    for name, s in list(streams.items()):
        gaps = s.gaps()
        if not gaps:
            continue
        if bridge:
            b = s.bridged()
            if b is not s:
                n = sum(g.duration_s <= MAX_BRIDGED_S * (1.0 + 1e-9) for g in gaps)
                done.append((name, n, len(b) - len(s)))
                streams[name] = b
        short = [g for g in gaps if g.duration_s <= _GAP_WARNED_S
                 and (not bridge or g.duration_s > MAX_BRIDGED_S * (1.0 + 1e-9))]
        if short:
            left.append((name, len(short), max(g.duration_s for g in short)))
            miss = sum(max(round(g.duration_s / s.period_s) - 1, 1) for g in short)  # B183: samples in them
            lost[name] = miss / (len(s) + miss)
    if done:
        log.info("%s: dropped samples bridged by linear interpolation (decision B64): %s", folder,
                 ", ".join(f"{n} {k} interval(s), {m} sample(s)" for n, k, m in done))
    if left and streamed:  # decision L77: the streamed paths integrate on the timestamps (E36, L78)
        log.warning("%s: %s", folder, streamed_drops_line(left))  # decision E230: shared with the live tracker
        return
    if left:
        what = (f"of {MAX_BRIDGED_S:g}-1 s, not bridged" if bridge
                else "of 1 s or less, not bridged")
        counts = {k for _, k, _ in left}
        count = (str(left[0][1]) if len(counts) == 1
                 else "/".join(str(k) for _, k, _ in left) + " (in that order)")
        if not any(n in SENSORS and SENSORS[n].placement == "foot" for n, _, _ in left):
            # waist streams only: the foot's figure and `--streaming` (a foot option) do not apply
            log.warning(WAIST_DROPS + gap_turn(left), folder, ", ".join(n for n, _, _ in left), count,
                        what.removesuffix(", not bridged"), max(m for _, _, m in left))
            return
        frac = max(f for n, f in lost.items() if n in SENSORS and SENSORS[n].placement == "foot")
        log.warning("%s: %s have %s interval(s) of dropped samples %s (longest %.3f s): the offline methods "
                    "integrate with a fixed sample interval, so each shortens the stride it falls in (%.2g %% of the "
                    "foot's samples dropped in them: about %+.2g %% distance, %g x the fraction, decisions B64, "
                    "B183); `track --streaming` integrates on "
                    "the timestamps, as does the offline foot with a --params file holding {\"timestamps\": true} "
                    "(decision L83/B65, not the default) - or %s and re-record", folder,
                    ", ".join(n for n, _, _ in left), count, what, max(m for _, _, m in left), 100 * frac,
                    -100 * DROP_DISTANCE_FACTOR * frac, DROP_DISTANCE_FACTOR, DROPS_CAUSE,
                    extra={"code": "B64"})  # E170: its own decision, not L83 it quotes last


#: decision B64's warning when only waist streams drop samples: the waist pipelines interpolate them onto a
#: uniform clock themselves (decision W34, ``pdrlearn.waist.ahrs``), so the foot's fixed-interval loss and its
#: advice (`track --streaming`, a foot option that refuses a waist-only session) do not apply
WAIST_DROPS = ("%s: %s have %s interval(s) of dropped samples %s (longest %.3f s): the waist pipelines "
               "interpolate them onto a uniform clock (decision W34; the foot's loss of distance, B64, does not "
               "apply here) - if there are many, " + DROPS_CAUSE)


#: label time columns that must be filled in every row (the others, e.g. ``tc_ms``, may be blank = unknown)
REQUIRED_TIME_COLUMNS = ("start_ms", "end_ms", "ic_ms")

#: time columns (seconds) written back as ``*_ms`` when a table carries no record of its own.
DEFAULT_TIME_COLUMNS = ("start_s", "end_s", "ic_s", "tc_s", "pre_ic_s", "fc_s")


def _ms_to_s(df: pd.DataFrame, where: str) -> pd.DataFrame:
    """Rename ``*_ms`` columns to ``*_s`` (seconds); other columns are kept untouched.

    The converted names are recorded in ``df.attrs["time_columns"]`` so that the writer converts back
    exactly those (a column already called ``duration_s`` stays as it is).
    """
    out = df.copy()
    converted = []
    for col in list(out.columns):
        if col.endswith("_ms"):
            converted.append(col[:-3] + "_s")
            vals = pd.to_numeric(out[col], errors="coerce")
            if vals.isna().sum() > out[col].isna().sum():
                raise DataError(f"{where}: column {col} has non-numeric values; times must be numbers in ms")
            if col in REQUIRED_TIME_COLUMNS and vals.isna().any():
                # docs/decisions/bad-input.md: an event or interval without its time is unusable
                first = int(np.flatnonzero(vals.isna().to_numpy())[0]) + 2
                raise DataError(f"{where}: column {col} has {int(vals.isna().sum())} empty value(s) (first at "
                                f"line {first}); fill in the time or remove those rows")
            if not np.isfinite(vals.to_numpy(dtype=float)[vals.notna().to_numpy()]).all():
                raise DataError(f"{where}: column {col} has infinite values; times must be finite numbers in ms")
            out[col[:-3] + "_s"] = vals * 1e-3
            out = out.drop(columns=col)
    out = out[[c[:-3] + "_s" if c.endswith("_ms") else c for c in df.columns]]
    out.attrs["time_columns"] = converted
    return out


def _s_to_ms(df: pd.DataFrame) -> pd.DataFrame:
    """Inverse of :func:`_ms_to_s`, keeping the column order."""
    time_cols = df.attrs.get("time_columns", DEFAULT_TIME_COLUMNS)
    out = df.copy()
    names = []
    for col in df.columns:
        if col in time_cols:
            out[col] = np.round(pd.to_numeric(out[col], errors="coerce").to_numpy(dtype=float) * 1e3, 9)
            names.append(col[:-2] + "_ms")
        else:
            names.append(col)
    out.columns = names
    return out


def _read_steps(path: Path) -> pd.DataFrame:
    raw = session_table(path)  # decisions B222, B223
    check_last_row(raw, path, str(path))  # decision B205: a label table cut mid-row
    check_columns(raw, tuple(c[:-2] + "_ms" for c in STEP_COLUMNS), f"{path} (times in ms)")  # as written (B222)
    df = _ms_to_s(raw, str(path))
    se = check_numeric(df, STEP_COLUMNS, str(path))
    bad = np.flatnonzero(se[:, 1] < se[:, 0])
    if bad.size:
        raise DataError(f"{path}: {bad.size} step(s) end before they start (first at line {bad[0] + 2})")
    if "ic_s" in df:  # decision B169: an ic_ms column written in seconds lies outside every stride
        ic = pd.to_numeric(df["ic_s"], errors="coerce").to_numpy(float)
        ok = np.isfinite(ic)
        if ok.sum() >= 3 and not ((ic[ok] >= se[ok, 0]) & (ic[ok] <= se[ok, 1])).any():
            raise DataError(f"{path}: none of the {int(ok.sum())} ic_ms values lies within its own stride's "
                            f"[start_ms, end_ms] (ic {1e3 * ic[ok].min():g}-{1e3 * ic[ok].max():g} ms, strides "
                            f"{1e3 * se[:, 0].min():g}-{1e3 * se[:, 1].max():g} ms); ic_ms must be milliseconds on the "
                            "session clock, like start_ms (written in seconds? multiply by 1000)")
    return df


def _read_trajectory(path: Path, scale: float) -> pd.DataFrame:
    df = session_table(path)  # decisions B222, B223
    check_last_row(df, path, str(path))  # decision B205
    check_columns(df, ("timestamp", "x", "y", "z"), str(path))
    arr = check_numeric(df, ("timestamp", "x", "y", "z"), str(path))
    check_timestamps(arr[:, 0] * scale, str(path))
    out = pd.DataFrame({"t": arr[:, 0] * scale, "x": arr[:, 1], "y": arr[:, 2], "z": arr[:, 3]})
    for c in df.columns:
        if c not in ("timestamp", "x", "y", "z"):
            out[c] = df[c].to_numpy()
    return out


def _looks_like_export(path: Path) -> bool:
    """A CSV that may be a one-file lab export (decision D12): not a label table (``steps``/``trajectory``,
    or a header with ``*_ms`` columns) and at least four columns (a time and three channels)."""
    if path.stem in LABEL_FILES:
        return False
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            header = f.readline()
    except OSError:
        return False
    cols = re.split(r"[,;\t]", header.strip())
    return len(cols) >= 4 and not any(c.strip().endswith("_ms") for c in cols)


#: decision B93: words in an export's file name that say which unit it holds (the import hint only)
UNIT_NAME_WORDS = {"foot": ("foot", "feet", "fuss", "fuß", "fuesse", "füße", "shoe", "schuh", "ankle", "pied"),
                   "waist": ("waist", "hip", "hüfte", "huefte", "pelvis", "becken", "lumbar", "lowback", "lowerback",
                             "belt", "trunk", "sacrum", "taille", "hanche")}


#: decision B147: a phone app's per-sensor file names (lower case, letters only: ``Accelerometer.csv``,
#: ``Gyroscope.csv``, Android's ``gyroscope_uncalibrated.csv``), by the kind of channel they hold
PHONE_SENSOR_FILES = {"acc": ("accelerometer", "accel", "acc", "totalacceleration"),
                      "gyro": ("gyroscope", "gyro", "gyr"), "mag": ("magnetometer", "magneticfield", "mag")}


#: decision B164: the phone files, beside a gravity-free accelerometer file, that give the specific force
#: (Sensor Logger: TotalAcceleration.csv on Android; Gravity.csv to add on iOS, which writes no total)
TOTAL_ACC_FILE, GRAVITY_FILE = "TotalAcceleration.csv", "Gravity.csv"


def _letters(path: Path) -> str:
    return re.sub(r"[^a-z]", "", path.stem.lower())


def _phone_sensor_files(exports: list[Path]) -> dict[str, Path]:
    """Decision B147: kind -> the export whose file name names that one phone sensor (the shortest name when
    several do: ``Gyroscope.csv`` before ``GyroscopeUncalibrated.csv``). Decision B165: a ``TotalAcceleration``
    file is the accelerometer whenever there is one (Sensor Logger's ``Accelerometer.csv`` is without gravity)."""
    out: dict[str, Path] = {}
    for kind, words in PHONE_SENSOR_FILES.items():
        hits = [p for p in exports if any(_letters(p).startswith(w) for w in words)]
        if hits:
            out[kind] = min(hits, key=lambda p: (not _letters(p).startswith("totalacc"), len(p.stem), p.name))
    return out


def _phone_recipe(files: dict[str, Path]) -> str:
    """Decision B147: the commands that make one waist unit of a phone's per-sensor files, mapping the axes when
    the header names them plain ``x``, ``y``, ``z`` (Sensor Logger writes them in the order z, y, x)."""
    q = shell_quote

    def axes(kind: str, path: Path) -> str:
        try:
            with open(path, encoding="utf-8", errors="replace") as f:
                cols = {c.strip().strip('"').lower() for c in re.split(r"[,;\t]", f.readline())}
        except OSError:
            return ""
        return f" --{kind} x,y,z" if {"x", "y", "z"} <= cols else ""

    def gravity(kind: str, path: Path) -> str:  # decision B165: iOS Sensor Logger's accelerometer has no gravity
        g = path.parent / GRAVITY_FILE
        return (f" --add-gravity {q(g)}" if kind == "acc" and not _letters(path).startswith("totalacc")
                and g.is_file() else "")

    cmds = [f"pdrlearn import {q(p)} --unit waist{axes(k, p)}{gravity(k, p)}{' --merge' if i else ''} --out SESSION"
            for i, (k, p) in enumerate(files.items())]
    return (f"; a phone's per-sensor files become one waist unit: `{'` then `'.join(cmds)}` (one sensor per "
            "import, --merge adding each to the same unit; decision B147)")


def _mat_import_hint(folder: Path) -> str:
    """Decision B335: "; ..." naming the `pdrlearn import` command of a folder's MATLAB files, or ""."""
    from pdrlearn.io.matfile import V73_FIX, mat_version

    mats = sorted(p for p in folder.glob("*.mat") if p.is_file() and mat_version(p))
    if not mats:
        return ""
    more = f" (and {len(mats) - 1} more .mat)" if len(mats) > 1 else ""
    if mat_version(mats[0]) == "7.3":
        return f"; {shell_quote(mats[0].name)}{more} is a v7.3 MAT file (HDF5): {V73_FIX} (decision B335)"
    return (f"; a MATLAB file becomes a session with `pdrlearn import {shell_quote(mats[0])} --out SESSION`{more} "
            "(N x 3 arrays acc, gyr and a time vector or fs; --acc/--gyro name others; decision B335)")


def export_import_hint(folder: Path) -> str:
    """Decision B93 (D12's hint): "; ..." naming the `pdrlearn import` command(s) that turn the one-file lab
    exports in ``folder`` into a session (paths quoted, B92), or "" when it holds none. Two or more exports:
    the file whose name says foot (UNIT_NAME_WORDS) is imported as the foot unit, the one that says waist with
    ``--unit waist --merge``; names that say neither are listed with both commands left to the user."""
    gz = compressed_hint(folder, SENSORS)  # decision B224
    if gz:
        return gz
    exports = sorted((p for p in folder.glob("*.csv") if _looks_like_export(p)),
                     key=lambda p: (-p.stat().st_size, p.name))  # the largest first
    if not exports:
        return _mat_import_hint(folder)
    q = shell_quote
    phone = _phone_sensor_files(exports)
    if "acc" in phone and "gyro" in phone:  # decision B147: not a foot and a waist unit
        return _phone_recipe(phone)
    if len(exports) == 1:
        return (f"; a lab export in one CSV becomes a session with `pdrlearn import {q(exports[0])} --out SESSION` "
                "(the foot unit; add --unit waist for a waist unit's; decision D12)")

    def named(unit: str) -> list[Path]:
        return [p for p in exports if any(w in p.stem.lower() for w in UNIT_NAME_WORDS[unit])]

    foot, waist = named("foot"), named("waist")
    if len(foot) == 1 and len(waist) == 1 and foot != waist:
        return (f"; the lab exports here become one session with `pdrlearn import {q(foot[0])} --out SESSION` "
                f"(the foot unit, by its name) and `pdrlearn import {q(waist[0])} --unit waist --merge --out "
                f"SESSION` (the waist unit) (decisions D12, B93)")
    names = ", ".join(q(p.name) for p in exports[:4]) + (f" and {len(exports) - 4} more" if len(exports) > 4 else "")
    return (f"; lab exports ({names}) become a session with `pdrlearn import FOOT.csv --out SESSION` for the foot "
            f"unit and `pdrlearn import WAIST.csv --unit waist --merge --out SESSION` for the waist unit, with "
            f"the files of {q(folder)} (decisions D12, B93)")


#: decision B72: a stream whose span (last minus first timestamp) is shorter than the longest of its unit's by more than
#: this (s), plus one sample interval, was cut short: B11's gap and B21's missing end, so what is missing at a
#: stream's ends is already refused where it is interpolated; the spans, not the ends, as the two units' clocks may be
#: offset (decision B22); unit clock drift changes a span by 0.36 s per hour at 100 ppm
SPAN_TOLERANCE_S = 1.0


def waist_clock_offset(foot: tuple[float, float], waist: tuple[float, float]) -> float | None:
    """Decision B243: the waist clock's offset (s, ``--clock-offset``'s sign: t_waist = t_foot + offset) when the
    foot's and the waist's spans (first, last sample) are the same length shifted by a constant - their start and
    end offsets have one sign, agree within :data:`SPAN_TOLERANCE_S` (a clock drift of 100 ppm changes a span by
    0.36 s per hour) and exceed it - else None. The start offset is returned (the walk's start)."""
    start, end = waist[0] - foot[0], waist[1] - foot[1]
    if abs(start) <= SPAN_TOLERANCE_S or abs(end - start) > SPAN_TOLERANCE_S or start * end <= 0:
        return None
    return float(start)


def clock_offset_fix(offset: float, command: str) -> str:
    """Decision B243: the refusal's first way out for a waist clock ``offset`` s off (:func:`waist_clock_offset`):
    ``command`` (``pdrlearn track DIR``, ``pdrlearn run``) with ``--clock-offset``, named before cutting data."""
    return (f"the same length shifted by {offset:.2f} s, as a waist clock {abs(offset):.2f} s "
            f"{'late' if offset > 0 else 'early'} gives -- if both units recorded the whole walk, give the offset: "
            f"`{command} --clock-offset {offset:.2f}` (decision E111; --align-units estimates only offsets under "
            f"about 0.25 s, L162); if the waist unit really started {'later' if offset > 0 else 'earlier'}")


#: decision B264: the largest clock drift between the two units (ppm) that a refusal calls clock drift - a crystal's
#: is tens of ppm and the simulator's knob goes to thousands (trial s32's 2000 ppm); a unit stopping early gives far
#: more (a battery dead at half the walk: 500000 ppm)
MAX_CLOCK_DRIFT_PPM = 5000.0
#: decision B277: how far over :data:`MAX_CLOCK_DRIFT_PPM` a drift read from the spans is still the limit's (ppm):
#: the four ends are millisecond timestamps (B264's limit read from 5000 ppm simulated as 5000.0000000001), so the
#: end-to-start difference is known to about 2 ms, over the shortest foot span on which a 5000 ppm drift passes B21's
#: 1 s (200 s): 2 ms / 200 s = 10 ppm; 1.01 x the limit (5050 ppm) stays a unit that stopped early
CLOCK_DRIFT_TOLERANCE_PPM = 10.0


def waist_clock_drift(foot: tuple[float, float], waist: tuple[float, float]) -> tuple[float, float] | None:
    """Decision B264: ``(offset_s, drift)`` (``--clock-offset``'s and ``--clock-drift-ppm``'s model, t_waist =
    t_foot * (1 + drift) + offset, as the simulator's clocks) when the foot's and the waist's spans (first, last
    sample) differ at the end by more than :data:`SPAN_TOLERANCE_S` beyond their start offset and that difference is a
    drift of at most :data:`MAX_CLOCK_DRIFT_PPM` (+ :data:`CLOCK_DRIFT_TOLERANCE_PPM`, B277) over the foot's span
    (proportional to the duration: a 200 ppm drift over 2.28 h is 1.64 s) - else None (B243's constant shift, or a
    unit that stopped far too early for a clock)."""
    start, end = waist[0] - foot[0], waist[1] - foot[1]
    duration = foot[1] - foot[0]
    if abs(end - start) <= SPAN_TOLERANCE_S or not duration > 0:
        return None
    drift = (end - start) / duration  # t_waist - t_foot grows by drift x the time walked
    offset = start - foot[0] * drift  # the model's offset at t_foot = 0 (its clock's origin, as --clock-offset's)
    if abs(drift) * 1e6 > MAX_CLOCK_DRIFT_PPM + CLOCK_DRIFT_TOLERANCE_PPM:  # decision B277: the limit's reading
        return None
    return float(offset), float(drift)


def clock_drift_fix(offset: float, drift: float, command: str, unit: str = "foot") -> str:
    """Decision B264: the refusal's first way out for clocks that drift apart (:func:`waist_clock_drift`): the drift
    in ppm, then ``command`` with ``--clock-drift-ppm`` (and ``--clock-offset`` when the start is over
    :data:`SPAN_TOLERANCE_S` off), named before the ways that cut data; ``unit``: the one that stopped first."""
    ppm = drift * 1e6
    given = f"--clock-drift-ppm {ppm:.0f}" + (f" --clock-offset {offset:.2f}" if abs(offset) > SPAN_TOLERANCE_S
                                               else "")
    return (f"the ends differ in proportion to the duration, as a waist clock running {abs(ppm):.0f} ppm "
            f"{'fast' if ppm > 0 else 'slow'} gives (clock drift, decision B264) -- if both units recorded the whole "
            f"walk, give the drift: `{command} {given}` (decision B265, --clock-offset's mechanism, E111); if the "
            f"{unit} unit really stopped early")


def check_stream_spans(streams: dict[str, Stream], folder: Path, *, mode: str = "refuse") -> str | None:
    """Decision B72: refuse (``mode="refuse"``) or warn about (``"warn"``, ``pdrlearn info``) a stream whose span
    is shorter than the longest span of its unit's streams (foot, waist) by more than :data:`SPAN_TOLERANCE_S`
    plus the larger sample interval of the two (a file cut at a row boundary: 45.10 s of fAccelerometer beside
    75.14 s of the rest tracked -36.66 % without a word). Within a unit only: two units are two devices, which
    may stop apart (``pdrlearn import --merge`` of two exports; B21 refuses where a method needs one unit to
    cover the other). Returns the message (``None``: the spans agree); ``"off"`` checks nothing; ``"common"``
    returns it without a word (:func:`cut_to_common_span` decides, decision B81)."""
    if mode == "off":
        return None

    def period(s: Stream) -> float:
        p = s.period_s
        return p if math.isfinite(p) else 0.0

    for unit in ("foot", "waist"):
        spans = {n: s for n, s in streams.items() if len(s) >= 2 and SENSORS[n].placement == unit}
        if len(spans) < 2:
            continue
        longest = max(spans, key=lambda n: spans[n].duration_s)
        full = spans[longest].duration_s
        short = [n for n, s in spans.items()
                 if full - s.duration_s > SPAN_TOLERANCE_S + max(period(s), period(spans[longest]))]
        if not short:
            continue
        short.sort(key=lambda n: spans[n].duration_s)
        first = spans[short[0]]
        others = [n for n in spans if n not in short]
        o_lo = min(float(spans[n].duration_s) for n in others)
        o_span = f"{full:.2f} s" if full - o_lo < 0.005 else f"{o_lo:.2f}-{full:.2f} s"
        also = f" (also short: {', '.join(session_csv(folder, n).name for n in short[1:])})" if len(short) > 1 else ""
        o_t0 = min(float(spans[n].t[0]) for n in others)
        o_t1 = max(float(spans[n].t[-1]) for n in others)
        slack = SPAN_TOLERANCE_S + max(period(first), period(spans[longest]))
        if first.t[0] - o_t0 > slack and o_t1 - first.t[-1] <= slack:  # decision B149: it started late
            msg = (f"{session_csv(folder, short[0])}: starts {first.t[0] - o_t0:.2f} s after the other "
                   f"{len(others)} {unit} stream(s) and ends with them{also} (a sensor that started late, as a phone "
                   f"app's can): track the time every {unit} file covers with --common-span, or trim the other "
                   "files to its start (decisions B72, B81, B149)")
        else:
            msg = (f"{session_csv(folder, short[0])}: spans {first.duration_s:.2f} s ({first.t[0]:.2f}-"
                   f"{first.t[-1]:.2f} s) but the other {len(others)} {unit} stream(s) {o_span}{also}; the file was "
                   "cut short (a truncated copy?), so a track would cover only part of the walk its labels describe "
                   "-- restore the whole file from the recording, or re-record, or track only the time every "
                   f"{unit} file covers with --common-span (decisions B72, B81)")
        if mode == "common":  # decision B81: the caller cuts the session to this unit's common span
            return msg
        if mode == "warn":
            log.warning("%s", msg)
            return msg
        raise DataError(msg)
    return None


def common_span(streams: dict[str, Stream], folder: Path) -> tuple[float, float, list[str]] | None:
    """Decision B81: the time ``(t0, t1, units)`` every stream of the units that B72 refuses (``units``) covers:
    the latest first sample to the earliest last one; None when :func:`check_stream_spans` accepts the spans."""
    units = [u for u in ("foot", "waist")
             if check_stream_spans({n: s for n, s in streams.items() if SENSORS[n].placement == u}, folder,
                                   mode="common") is not None]
    if not units:
        units = units_apart(streams)  # decision B83: two devices started or stopped apart
        if units is None:
            return None
    cut = [s for n, s in streams.items() if SENSORS[n].placement in units and len(s)]
    return max(float(s.t[0]) for s in cut), min(float(s.t[-1]) for s in cut), units


def units_apart(streams: dict[str, Stream]) -> list[str] | None:
    """Decision B83: ``["foot", "waist"]`` when the session holds both units and one starts or stops more than
    :data:`SPAN_TOLERANCE_S` apart from the other (two devices switched on a few seconds apart: a method that
    needs one unit to cover the other refuses it, B21); else None."""
    ends = unit_ends(streams)
    if len(ends) < 2:
        return None
    (f0, f1), (w0, w1) = ends["foot"], ends["waist"]
    return ["foot", "waist"] if max(abs(f0 - w0), abs(f1 - w1)) > SPAN_TOLERANCE_S else None


def unit_ends(streams: dict[str, Stream]) -> dict[str, tuple[float, float]]:
    """Each unit's (first, last) sample time (s) over its streams of at least 2 samples (decisions B83, L162)."""
    ends = {}
    for unit in ("foot", "waist"):
        ts = [s for n, s in streams.items() if SENSORS[n].placement == unit and len(s) >= 2]
        if ts:
            ends[unit] = (min(float(s.t[0]) for s in ts), max(float(s.t[-1]) for s in ts))
    return ends


def apart_phrase(streams: dict[str, Stream]) -> str:
    """Decision L162: what a B83 cut does to two units' clocks - the waist unit's start and stop against the foot's,
    and that no offset is applied (each unit keeps its own clock)."""
    ends = unit_ends(streams)
    (f0, f1), (w0, w1) = ends["foot"], ends["waist"]
    return (f"the waist unit started {w0 - f0:+.2f} s and stopped {w1 - f1:+.2f} s from the foot unit; the cut applies "
            "no clock offset (0.00 s): each unit keeps its own clock, so a unit switched on later that counts from 0 "
            "stays that far off - `pdrlearn track --align-units` estimates an offset under a step period from the "
            "steps both units see (decision L162)")


def cut_to_common_span(streams: dict[str, Stream], folder: Path) -> tuple[float, float, str] | None:
    """Decision B81 (``read_session(spans="common")``, ``pdrlearn track --common-span``): instead of B72's refusal,
    cut every stream of the session to :func:`common_span` (in place; the other unit too, so that each method
    sees one walk and the labels cut alike by :func:`cut_labels_to_span` describe it). Returns ``(t0, t1,
    text, why)``, ``text`` naming the seconds dropped from each file, ``why`` what time was kept (B72's cut
    files, or B83's two units started or stopped apart), or None when the spans agree (nothing cut).
    A stream left with under 2 samples in that time is refused (the units do not overlap)."""
    found = common_span(streams, folder)
    if found is None:
        return None
    t0, t1, units = found
    why = ("the time every file of the unit(s) cut short covers (B72)" if check_stream_spans(
        {n: s for n, s in streams.items() if SENSORS[n].placement in units}, folder, mode="common") is not None
        else "the time both units have data: they started or stopped over "
             f"{SPAN_TOLERANCE_S:g} s apart (decision B83); " + apart_phrase(streams))
    if t1 - t0 < SPAN_TOLERANCE_S:
        raise DataError(f"{folder}: the {' and '.join(units)} files cover under {SPAN_TOLERANCE_S:g} s in common "
                        f"({t0:.2f}-{t1:.2f} s), nothing to track; --common-span cannot cut them to it -- restore the "
                        "whole files from the recording (decision B81)")
    dropped = []
    for n, s in list(streams.items()):
        keep = (s.t >= t0 - 1e-9) & (s.t <= t1 + 1e-9)
        if keep.all():
            continue
        if keep.sum() < 2:
            raise DataError(f"{session_csv(folder, n)}: holds no samples in {t0:.2f}-{t1:.2f} s, the time every "
                            f"{' and '.join(units)} file covers; --common-span cannot keep it -- move it out of the "
                            "session folder, or restore the files (decision B81)")
        gone = (float(s.t[keep][0]) - float(s.t[0])) + (float(s.t[-1]) - float(s.t[keep][-1]))
        dropped.append(f"{gone:.2f} s of {session_csv(folder, n).name}")
        streams[n] = Stream(n, s.t[keep], s.values[keep])
    return t0, t1, ", ".join(dropped), why


def cut_labels_to_span(table: pd.DataFrame | None, t0: float, t1: float, time_columns) -> tuple:
    """Decision B81: the rows of a label table that lie in ``t0``-``t1`` (s), and the number of rows dropped
    (``(None, 0)`` for no table): an interval (``start_s`` and ``end_s``) whose middle lies in it, so that a
    stride the recording holds most of counts, as the tracker completes it at the last foot-flat; otherwise a
    row whose filled ``time_columns`` all lie in it."""
    if table is None:
        return None, 0
    cols = [c for c in time_columns if c in table.columns]
    if {"start_s", "end_s"} <= set(table.columns):
        cols = ["mid"]
        table_t = ((pd.to_numeric(table["start_s"], errors="coerce") + pd.to_numeric(table["end_s"], errors="coerce"))
                   / 2).to_frame("mid")
    elif not cols:
        return table, 0
    else:
        table_t = table[cols]
    v = table_t.apply(pd.to_numeric, errors="coerce").to_numpy(float)
    inside = ((v >= t0 - 1e-9) & (v <= t1 + 1e-9)) | np.isnan(v)
    keep = inside.all(axis=1)
    out = table[keep].reset_index(drop=True)
    out.attrs = dict(table.attrs)
    return out, int((~keep).sum())


def _sensor_copy_of(stem: str) -> str | None:
    """Decision B74: the sensor whose file ``stem`` names a copy of (``fAccelerometer (1)``, ``Copy of fGyroscope``,
    ``wBarometer_old``): its letters, lower-cased, contain a sensor's name; else None."""
    letters = re.sub(r"[^a-z]", "", stem.lower())
    return next((n for n in sorted(SENSORS, key=len, reverse=True) if n.lower() in letters), None)


def _not_labels(path: Path, table: pd.DataFrame, folder: Path) -> bool:
    """Decision B74: True for a CSV that is not a label table and is left out of ``Session.extras`` with one
    warning: a copy of a sensor file identical to it, or a table whose columns are a sensor stream's
    (``timestamp`` + x,y,z or x, no ``*_ms`` column) under a name that does not say ``trajectory`` (the
    ground-truth ``trajectory.csv``, ``foot_trajectory.csv`` have those columns). A copy that differs from its
    sensor file (or has none beside it) is a :class:`DataError`: which one is the recording is not known."""
    copy_of = _sensor_copy_of(csv_stem(path))
    if copy_of is not None:
        original = session_csv(folder, copy_of)  # decision B369: either may be gzip-compressed
        if original.is_file() and read_bytes(original) == read_bytes(path):
            log.warning("%s: is a copy of %s (identical): ignored, not read as a label table; delete it", path,
                        original.name)
            return True
        if original.is_file():
            raise DataError(f"{path}: looks like a copy of {original.name} (its name) but differs from it; keep the "
                            f"right recording as {original.name} and move the other out of the session folder "
                            "(decision B74)")
        raise DataError(f"{path}: looks like a copy of {original.name} (its name), and there is no {original.name}; "
                        f"rename it to {original.name} if it is that recording, or move it out of the session "
                        "folder (decision B74)")
    cols = [c for c in table.columns if c != "timestamp"]
    stream_like = ("timestamp" in table.columns and not any(str(c).endswith("_ms") for c in table.columns)
                   and any(tuple(cols) == spec.columns for spec in SENSORS.values()))
    if stream_like and "trajectory" not in csv_stem(path).lower():
        log.warning("%s: its columns (%s) are a sensor stream's, not a label table's: ignored (nothing reads it); "
                    "name it after its sensor (%s) if it is one, or move it out of the session folder", path,
                    ",".join(map(str, table.columns)), ", ".join(SENSORS[n].filename for n in SENSORS))
        return True
    return False


def folder_arg(folder, caller: str) -> Path:
    """Decision B179: a session folder argument as a Path; anything but a str / os.PathLike (``read_session(42)``
    was a bare ``TypeError`` from pathlib) is one :class:`~pdrlearn.errors.NotASessionError` line."""
    from pdrlearn.errors import NotASessionError

    return path_arg(folder, caller, "a session folder", NotASessionError)


def path_arg(path, caller: str, expected: str, error: type[DataError] = DataError) -> Path:
    """Decisions B179, B349: a path argument as a Path; anything else is one ``error`` line naming ``caller``, what
    it ``expected`` and, for a file object (an upload in memory: ``import_csv(io.BytesIO(...))`` was a bare
    ``TypeError``), how to pass it."""
    if isinstance(path, str | os.PathLike):
        return Path(path)
    fix = ("; write it to a file first (e.g. tempfile.NamedTemporaryFile) and pass that file's path, or build the "
           "Session from arrays (decision B349)") if hasattr(path, "read") else ""
    raise error(f"{caller}({path!r}): expected {expected}, a str or pathlib.Path (got {type(path).__name__}){fix}")


def read_session(folder: str | os.PathLike, *, check_units: bool = True, uniform_clock: bool = False,
                 bridge_drops: bool | None = None, streamed: bool = False, spans: str = "refuse",
                 drop_partial_row: bool = False, command: str | None = None) -> Session:
    """Read a PLASYS session folder, or a zip archive of one: its path, bytes or a binary file object (decision
    B359, :func:`pdrlearn.io.archive.read_session_zip`, which also takes the archive's name and a size cap).
    ``uniform_clock``: interpolate jittered accelerometers and gyroscopes onto a
    uniform clock (decision B33; off: its adoption rule failed, experiments/results/jitter.md). ``bridge_drops``:
    True bridges intervals of dropped samples up to :data:`MAX_BRIDGED_S` by linear interpolation and warns about
    the longer ones up to 1 s (decision B64; not adopted: its adoption rule failed at 20 Hz,
    experiments/results/drops_31-36.md); None (the default) bridges none and warns about the intervals left as
    they are; ``False`` reads the samples as recorded, without the warning (``pdrlearn info`` lists the gaps
    itself). Decision E251: keywords, no module switches. ``streamed``: the caller integrates on the timestamps
    (``pdrlearn run``, ``track --streaming``): that warning says so (decision L77). ``spans``: a stream whose
    time span is over 1 s shorter than the others' (a file cut short) is refused (``"refuse"``), warned about
    (``"warn"``, ``pdrlearn info``) or not checked (``"off"``; decision B72); ``"common"`` (``pdrlearn track
    --common-span``) cuts every stream, and the label tables, to the time all the short unit's files cover, with
    one warning naming the seconds dropped from each file (decision B81). ``drop_partial_row``: a sensor file
    without a line break at the end loses its last (partial) row, with one warning (decision B266). ``command``: the
    command line (``pdrlearn run BUNDLE SESSION``) that a refused cut last row names with ``--drop-partial-row``
    (decision B279; ``pdrlearn track FOLDER`` when None).

    Raises
    ------
    DataError
        A missing folder, no sensor file, a malformed CSV, non-numeric/NaN values, unsorted or duplicate
        timestamps, implausible units, an empty file or a broken ``meta.json`` (one-line message).
    """
    from pdrlearn.io.archive import is_archive, read_session_zip
    from pdrlearn.warning_lines import captured_warnings

    if is_archive(folder):  # decision B359: a zip of a session folder (a path, its bytes or a binary file object)
        return read_session_zip(folder, check_units=check_units, uniform_clock=uniform_clock,
                                bridge_drops=bridge_drops, streamed=streamed, spans=spans,
                                drop_partial_row=drop_partial_row, command=command)
    with captured_warnings(echo=True) as logged:  # decision E154: the reading's warnings stay with the session
        session = _read_session(folder, check_units=check_units, uniform_clock=uniform_clock,
                                bridge_drops=bridge_drops, streamed=streamed, spans=spans,
                                drop_partial_row=drop_partial_row, command=command)
    session._read_warnings = list(logged)
    return session


def _read_session(folder, *, check_units, uniform_clock, bridge_drops, streamed, spans, drop_partial_row,
                  command) -> Session:
    """:func:`read_session` without E154's capture."""
    folder = folder_arg(folder, "read_session")  # decision B179
    if not folder.exists():
        check_readable(folder, "folder")  # decision B315: a dangling link names its target
        raise DataError(f"{folder}: session folder not found; pass a folder with fAccelerometer.csv etc.")
    if not folder.is_dir():
        raise DataError(f"{folder}: not a folder; pass the session folder, not a file")
    meta: dict = {}
    meta_path = folder / "meta.json"
    if present(meta_path):
        check_readable(meta_path)  # decision B315
        try:
            meta = read_json(meta_path)
        except json.JSONDecodeError as exc:
            why = "" if exc.pos else f": {exc.msg}"  # decision B423: nested too deep (no position)
            raise DataError(f"{meta_path}: invalid JSON (line {exc.lineno}{why}); fix or delete the file") from None
        if not isinstance(meta, dict):
            raise DataError(f"{meta_path}: must hold a JSON object")
        _check_body_fields(meta, str(meta_path))
    rate = meta_rate(meta, meta_path)
    clocks = unit_clocks(meta, meta_path)  # decision B115: per-unit rates and clock offsets
    raw = {}
    files = {name: session_csv(folder, name) for name in SENSORS}  # decision B369: X.csv or X.csv.gz, not both
    for name, p in files.items():
        if present(p):  # decision B315: a dangling link or a folder is there, unreadable: one line, not "missing"
            check_readable(p)
            raw[name] = _read_raw(p, name, drop_partial_row=drop_partial_row, command=command)[1]
    raw = _unwrapped(raw, folder)  # decision B312: a timestamp counter that wraps around
    if not clocks and not _declares_integer_clock(meta, meta_path, rate):
        one_unit_counting(raw, folder, meta_path)  # decision B116: a counter on one unit needs its own clock
    scales: dict[str, float] = {}
    read_as = []
    for names, r, m in unit_groups(raw, clocks, rate, meta):  # one clock for every file, or one per unit (B115)
        sc, unit = _group_time_scale({n: raw[n] for n in names}, m, r, folder, meta_path)
        scales.update(dict.fromkeys(names, sc))
        read_as.append((names, r, unit))
    scale, basis = _trajectory_scale(scales, clocks, meta, meta_path, rate)
    streams = {name: _to_stream(files[name], name, arr, scales[name], check_units,
                                _value_unit(meta, name, str(meta_path)))
               for name, arr in raw.items()}
    for names, r, unit in read_as:
        where = meta_path if not clocks else f"{meta_path} ({SENSORS[names[0]].placement} unit)"
        if unit == "samples":
            log.warning("%s: declares no timestamp unit and the accelerometer/gyroscope timestamps are consecutive "
                        "integers, %g times rate_hz %g read as ms: read as sample indices at %g Hz; write each "
                        "sample's time in ms, or add \"units\": {\"timestamp\": \"samples\"} to meta.json to say so",
                        where, 1000.0 / r, r, r)
        elif unit is not None:
            log.warning("%s: declares no timestamp unit and the timestamps are not milliseconds: read as %s "
                        "(%s); add \"units\": {\"timestamp\": \"%s\"} to meta.json to say so", where, unit,
                        ", ".join(f"{n} {streams[n].rate_hz:.4g} Hz" for n in names), unit)
        if r is not None:
            _check_declared_rate({n: streams[n] for n in names}, r, meta_path)
    apply_offsets(streams, clocks, meta_path)  # decision B115: each unit's clock onto the session's
    if check_units:
        check_tilt_rates(streams, files)  # decision B476: import's B40 test on the folder's units
    if spans not in ("refuse", "warn", "off", "common"):
        raise ValueError(f"spans={spans!r}: use 'refuse', 'warn', 'off' or 'common'")
    # decision B72: before a gap warning about a cut file; B81: "common" cuts the session instead of refusing
    t_uncut = min((float(s.t[0]) for s in streams.values() if len(s)), default=None)  # B81: before any cut
    ends_uncut = unit_ends(streams) if spans == "common" else None  # decision B267: before any cut
    cut = cut_to_common_span(streams, folder) if spans == "common" else check_stream_spans(streams, folder, mode=spans)
    _warn_jitter(streams, folder)  # decision B182
    _rate_changes(streams, folder)  # decision B457: before B64 calls a slower stretch dropped samples
    if uniform_clock:  # decision B33 (an option)
        _uniform_clocks(streams, folder)
    if bridge_drops is not False:
        _bridge_drops(streams, folder, bridge_drops is not None, streamed=streamed)  # decision B64 (an option)
    if not streams:
        inner = sorted(p.name for p in folder.iterdir()
                       if p.is_dir() and any(csv_stem(f) in SENSORS for f in session_csvs(p)))  # B369: .csv.gz too
        if inner:  # a folder of sessions (what `train` takes) given to a one-session command
            more = f" and {len(inner) - 3} more" if len(inner) > 3 else ""
            raise DataError(f"{folder}: holds session folders ({', '.join(inner[:3])}{more}), not one session's "
                            f"sensor files; pass one of them, e.g. {folder / inner[0]}")
        raise DataError(
            f"{folder}: no sensor files found; expected at least one of "
            f"{', '.join(s.filename for s in SENSORS.values())}{export_import_hint(folder)}"
        )
    steps_p, traj_p = session_csv(folder, "steps"), session_csv(folder, "trajectory")  # decision B369
    steps = _read_steps(steps_p) if steps_p.exists() else None
    traj = _read_trajectory(traj_p, scale) if traj_p.exists() else None
    extras = {}
    for p in session_csvs(folder):  # decision B369: label tables may be gzip-compressed too
        if csv_stem(p) in SENSORS or csv_stem(p) in LABEL_FILES:
            continue
        session_csv(folder, csv_stem(p))  # decision B369: not both plain and compressed
        table = session_table(p)  # decisions B222, B223
        if _not_labels(p, table, folder):  # decision B74: a copy of a sensor file, or a sensor stream
            continue
        check_label_table(table, csv_stem(p), str(p))
        check_last_row(table, p, str(p))  # decision B205
        extras[csv_stem(p)] = _ms_to_s(table, str(p))
    if spans == "common" and cut is not None:  # decision B81: the labels describe the walk that is kept
        t0, t1, dropped, why = cut
        labels = []
        steps, n = cut_labels_to_span(steps, t0, t1, ("start_s", "end_s"))
        labels += [f"{n} of {n + len(steps)} rows of steps.csv"] if n else []
        traj, n = cut_labels_to_span(traj, t0, t1, ("t",))
        labels += [f"{n} of {n + len(traj)} rows of trajectory.csv"] if n else []
        for k, table in list(extras.items()):
            extras[k], n = cut_labels_to_span(table, t0, t1, table.attrs.get("time_columns", DEFAULT_TIME_COLUMNS))
            labels += [f"{n} of {n + len(extras[k])} rows of {k}.csv"] if n else []
        log.warning("%s: --common-span: cut to %.2f-%.2f s, %s: dropped %s%s; the track and its reference cover "
                    "that time only (decision B81)", folder, t0, t1, why, dropped,
                    "; labels outside it dropped: " + ", ".join(labels) if labels else "")
    try:
        frames = frames_from_meta(meta)
    except DataError as exc:
        raise DataError(f"{meta_path}: {exc}") from None
    session = Session(name=str(meta.get("session", folder.name)), streams=streams, steps=steps,
                      trajectory=traj, extras=extras, meta=meta, frames=frames, folder=folder,
                      check_units=check_units)
    if spans == "common" and cut is not None:  # decision B81 / L105: --window counts from the uncut recording
        session._t_start_uncut = t_uncut
        session._unit_ends_uncut = ends_uncut
    session._valid = session._fingerprint()  # decision B49: the entry points need not repeat this function's checks
    for label, table in [*([("steps", steps)] if steps is not None else []), *extras.items()]:
        check_label_times(table, session.t_start, session.t_end, str(folder / f"{label}.csv"))
    if traj is not None:  # decision B25: on the sensors' clock, in their unit
        check_trajectory_times(traj["t"].to_numpy() / scale, scale, session.t_start, session.t_end,
                               str(folder / "trajectory.csv"), basis=basis)
    warn_low_rate(session)
    warn_saturation(session)
    warn_stuck(session)  # decision B455
    warn_frozen(session)  # decision B120
    for name, s in streams.items():
        gaps = s.gaps()
        if gaps:
            log.info("%s/%s: %d gap(s), longest %.3f s", folder, name, len(gaps), max(g.duration_s for g in gaps))
    return session


#: Lowest sampling rate (Hz) of a unit's accelerometer/gyroscope that the step detectors are validated at
#: (decision B23): the thesis system samples both units at 20 Hz (thesis ch.4.2.3, 4.3, 4.4: "sufficient to
#: include the frequencies in the signals induced by the user walk"), the simulator too; on the real
#: recordings resampled to 10-15 Hz the foot detector loses strides on every kind of walk
#: (experiments/results/low_rate.md).
MIN_VALIDATED_RATE_HZ = 20.0


def unit_rates(session: Session) -> dict[str, float]:
    """Each IMU unit's sampling rate (Hz): the slower of its accelerometer and gyroscope (NaN without either)."""
    return {unit: min((session.streams[n].rate_hz for n in names if n in session.streams
                       and len(session.streams[n]) > 1), default=float("nan"))
            for unit, names in UNIT_IMU.items()}


def warn_low_rate(session: Session) -> None:
    """One warning per unit whose accelerometer or gyroscope is sampled below :data:`MIN_VALIDATED_RATE_HZ`
    (decision B23): the detectors run, but lose steps (a 10 Hz foot recording: 16 of 29 strides). Decision B416
    (replacing B404's refusal under 15 Hz, which anti-aliased copies did not bear out): every command reads the session
    and warns alike; the line says the distance may come out short (experiments/results/low_rate_track.md)."""
    where = session.folder if session.folder is not None else f"session '{session.name}'"
    for unit, rate in unit_rates(session).items():
        if rate < MIN_VALIDATED_RATE_HZ * 0.99:  # D7: a nominal 20 Hz clock may read 19.9x Hz
            what = "strides" if unit == "foot" else "steps"
            log.warning("%s: the %s unit is sampled at %.3g Hz, below the %g Hz its step detectors are validated at "
                        "(thesis ch.4; docs/robustness.md): expect lost %s and a short distance (real recordings "
                        "copied to 10-15 Hz tracked up to 62 %% short, decision B416); record at %g Hz or more",
                        where, unit, rate, MIN_VALIDATED_RATE_HZ, what, MIN_VALIDATED_RATE_HZ)


def _stream_where(session: Session, name: str) -> str:
    """A stream's name in a warning: its file, or the in-memory session and stream."""
    return (str(session_csv(session.folder, name)) if session.folder is not None
            else f"session '{session.name}', stream {name}")


def declared_full_scales(session: Session) -> dict[str, float]:
    """Decision B456: meta.json's ``"full_scale"`` (stream name -> ``"4 g"``, ``"500 deg/s"``) in SI units, for the
    session's accelerometer / gyroscope streams; a one-line :class:`DataError` naming meta.json and the key for a value
    that is no full scale or a stream that is no accelerometer / gyroscope."""
    from pdrlearn.kernels.clipping import FULL_SCALE_KEY, parse_full_scale

    declared = (session.meta or {}).get(FULL_SCALE_KEY)
    if declared is None:
        return {}
    where = (f"{session.folder / 'meta.json'}" if session.folder is not None else f"session '{session.name}' meta")
    if not isinstance(declared, dict):
        raise DataError(f"{where}: {FULL_SCALE_KEY} is a {type(declared).__name__}; give an object of sensor name -> "
                        "range, e.g. {\"fAccelerometer\": \"4 g\", \"fGyroscope\": \"500 deg/s\"} (decision B456)")
    out = {}
    for name, text in declared.items():
        spec = SENSORS.get(name)
        if spec is None or spec.kind not in ("accelerometer", "gyroscope"):
            raise DataError(f"{where}: {FULL_SCALE_KEY}: {name!r} is no accelerometer or gyroscope file's name; use "
                            "one of " + ", ".join(n for n, sp in SENSORS.items() if sp.kind in ("accelerometer",
                                                                                          "gyroscope"))
                            + " (decision B456)")
        try:
            out[name] = parse_full_scale(text, spec.kind)
        except ValueError as exc:
            raise DataError(f"{where}: {FULL_SCALE_KEY}.{name}: {exc} (decision B456)") from None
    return out


def clipped_shares(session: Session) -> dict[str, float]:
    """Decision B456: the share of each accelerometer / gyroscope stream's samples that B77 / B311 (or, with a
    declared full scale, B456) call clipped (0.0: none): summary.json's ``info.clipped_share``."""
    from pdrlearn.kernels.clipping import clipped_samples

    scales = declared_full_scales(session)
    out = {}
    for name, s in session.streams.items():
        kind = SENSORS[name].kind
        if kind in ("accelerometer", "gyroscope") and len(s):
            out[name] = clipped_samples(s.values, kind, scales.get(name))[0] / len(s)
    return out


def warn_saturation(session: Session) -> None:
    """Decision B77: one warning per accelerometer / gyroscope file with clipped samples (runs of an axis's
    extreme value at a sensor's full scale), naming the file, the fraction clipped and the consequence. Decision
    B456: a stream with a declared full scale (meta.json ``full_scale``) is judged at it."""
    from pdrlearn.io.validate import MOVING_RAD_S, clipped_samples, saturation_warning

    scales = declared_full_scales(session)
    for name, s in session.streams.items():
        kind = SENSORS[name].kind
        n, top = clipped_samples(s.values, kind, scales.get(name))
        if n:
            where = _stream_where(session, name)
            gyro = kind == "gyroscope"  # decision B401: the share of the motion at full scale, and the foot's remedy
            moving = int(np.count_nonzero(np.linalg.norm(s.values, axis=1) >= MOVING_RAD_S)) if gyro else None
            waist = session.has("wAccelerometer", "wGyroscope") and session.has_frame("waist")  # decision L530
            log.warning("%s", saturation_warning(where, kind, n, len(s), top,
                                                 "waist" if name.startswith("w") else "foot",  # T3 finding 9
                                                 moving=moving, waist=waist, declared=name in scales))


def warn_stuck(session: Session) -> None:
    """Decision B455: one warning per axis of an accelerometer / gyroscope file with :data:`~pdrlearn.kernels.
    clipping.STUCK_MIN_RUNS` or more stuck runs (one axis held while the others move)."""
    from pdrlearn.kernels.clipping import STUCK_MIN_RUNS, stuck_message, stuck_runs

    scales = declared_full_scales(session)
    for name, s in session.streams.items():
        kind = SENSORS[name].kind
        if kind not in ("accelerometer", "gyroscope") or s.values.ndim != 2 or s.values.shape[1] != 3 or len(s) < 4:
            continue
        dt = float(np.median(np.diff(s.t)))
        for axis, runs in zip(SENSORS[name].columns, stuck_runs(s.values, dt, kind, scales.get(name)), strict=True):
            if len(runs) >= STUCK_MIN_RUNS:
                log.warning("%s", stuck_message(_stream_where(session, name), axis, runs, dt,
                                                float(s.t[runs[0][0]] - s.t[0])))


def warn_frozen(session: Session) -> None:
    """Decision B120: one warning per run of bit-identical consecutive samples of a 3-axis sensor file lasting
    :data:`~pdrlearn.kernels.units.FROZEN_S` or more while the unit's other sensor shows it moving (a frozen
    sensor; without that sensor, every such run), naming the file and the span."""
    from pdrlearn.io.validate import resolution
    from pdrlearn.kernels.units import (
        FROZEN_EDGE_S,
        FROZEN_MOVING_MIN,
        FROZEN_PARTNER,
        frozen_message,
        frozen_spans,
        moving_samples,
        quantisation_margin,
    )

    for name, s in session.streams.items():
        if s.values.ndim != 2 or s.values.shape[1] != 3:
            continue
        where = _stream_where(session, name)
        other = session.streams.get(FROZEN_PARTNER.get(name, ""))
        moved = None if other is None else other.t[moving_samples(  # B405: beyond the partner's own rounding
            other.name, other.values, quantisation_margin(resolution(other.values)))]
        for a, b, n in frozen_spans(s.t, s.values):
            inside = (moved > a + FROZEN_EDGE_S) & (moved < b - FROZEN_EDGE_S) if moved is not None else None
            if inside is not None and np.count_nonzero(inside) < FROZEN_MOVING_MIN:
                continue  # the unit rests (its other sensor shows no movement, B405: or a transient): quantised
            log.warning("%s", frozen_message(where, a, b, n, s.values[int(np.searchsorted(s.t, a))]))


def _stream_frame(s: Stream, scale: float) -> pd.DataFrame:
    data = {"timestamp": np.round(s.t / scale, 9)}
    for j, c in enumerate(s.spec.columns):
        data[c] = s.values[:, j]
    return pd.DataFrame(data)


def _write_float_csv(df: pd.DataFrame, path: Path) -> None:
    """``df.to_csv(path, index=False, float_format="%.17g")``, byte for byte, about 2.5x faster for the all-float,
    NaN-free frames a session's streams and trajectory are (session 41, lead; suite-time note of implementer I2: a
    2020 s simulated night's 8 streams 1.56 -> 0.58 s CPU). Anything else (a NaN, which pandas writes as an empty
    cell, a non-float column, a column name CSV would quote) goes through pandas."""
    arr = df.to_numpy() if all(dt.kind == "f" for dt in df.dtypes) else None
    if (arr is None or not np.isfinite(arr).all()
            or any(not isinstance(c, str) or any(ch in c for ch in ',"\n\r') for c in df.columns)):
        df.to_csv(path, index=False, float_format="%.17g")
        return
    row = ",".join(["%.17g"] * arr.shape[1])
    with open(path, "w", encoding="utf-8", newline="") as f:
        f.write(",".join(df.columns) + "\n")
        f.writelines(row % r + "\n" for r in map(tuple, arr.tolist()))


def write_session(session: Session, folder: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Write a session as a PLASYS folder, atomically (temporary folder + rename).

    Values are written with full float64 precision (``repr``), so reading back reproduces them exactly;
    timestamps are written in ms rounded to 1 ps.
    """
    folder = folder_arg(folder, "write_session")  # decision B179
    if folder.exists() and not overwrite:
        if any(folder.iterdir()):
            raise DataError(f"{folder}: already exists and is not empty; choose another --out or remove it")
    with atomic_directory(folder) as tmp:
        meta = dict(session.meta)
        meta.setdefault("session", session.name)
        clocks = meta.pop("clocks", None)  # decision B115: the times written are on the session's clock, in ms
        if isinstance(clocks, dict) and any(isinstance(c, dict) and "rate_hz" in c for c in clocks.values()):
            meta.pop("rate_hz", None)  # B115 amended (review): one unit's rate, not the session's, once in ms
        units = dict(meta.get("units", {}))
        units["timestamp"] = "ms since the first sample"
        for name in session.streams:  # B32: values are in memory in SI, whatever unit meta.json declared
            if name in units:
                try:
                    factor = _value_unit(units and {"units": units}, name, "meta.json")[0]
                except DataError:
                    factor = None
                if factor != 1.0:
                    units[name] = f"{SENSORS[name].unit} (converted when read, from {units[name]})"
        meta["units"] = units
        if session.frames:
            meta["frames"] = {p: f.to_dict() for p, f in session.frames.items()}
        scale = 1e-3
        for name, s in session.streams.items():
            _write_float_csv(_stream_frame(s, scale), tmp / f"{name}.csv")
        if session.steps is not None:
            _s_to_ms(session.steps).to_csv(tmp / "steps.csv", index=False)
        if session.trajectory is not None:
            tr = session.trajectory.copy()
            tr.insert(0, "timestamp", np.round(tr.pop("t").to_numpy() / scale, 9))
            _write_float_csv(tr, tmp / "trajectory.csv")
        for k, df in session.extras.items():
            _s_to_ms(df).to_csv(tmp / f"{k}.csv", index=False)
        (tmp / "meta.json").write_text(json.dumps(meta, indent=2, default=json_default) + "\n")
    return folder


def json_default(o):
    """``json.dumps(default=...)`` for numpy scalars and arrays and paths (the one shared converter)."""
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def json_safe(obj):
    """Replace NaN/inf by None recursively so the output is strict JSON."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, float | np.floating) and not np.isfinite(obj):
        return None
    return obj
