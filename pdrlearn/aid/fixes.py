"""Absolute position fixes: the fix table, NMEA 0183 (GGA/RMC) and CSV readers.

A *fix table* is a pandas DataFrame with one row per fix:

``t`` (s, session clock), ``accuracy_m`` (m, reported horizontal accuracy: the radius that holds the true
position with 68 % probability, the Android convention), and ``lat``/``lon`` (degrees, WGS-84) and/or
``x``/``y`` (m, local ENU: east, north). :func:`to_local` adds ``x``/``y`` from ``lat``/``lon``.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.aid.geo import geodetic_to_enu
from pdrlearn.errors import DataError

log = logging.getLogger(__name__)

from pdrlearn.kernels.fixes import RADIUS68_PER_SIGMA, sigma_from_accuracy  # noqa: E402,F401  (D19)

#: User-equivalent range error (m) turning a GGA HDOP into an accuracy (decision, docs/decisions/aided.md).
DEFAULT_UERE_M = 4.0
#: Accuracy (m) given to an RMC fix that has no HDOP (no GGA at the same epoch).
DEFAULT_RMC_ACCURACY_M = 10.0


@dataclass
class FixLog:
    """Fixes read from a file plus what was skipped.

    Attributes
    ----------
    fixes : the fix table (see module docstring), sorted by ``t``
    stats : counters: ``lines``, ``sentences``, ``used``, ``bad_checksum``, ``empty`` (no position / invalid
        status), ``malformed``, ``unsupported`` (other sentence types)
    source : file the fixes came from
    """

    fixes: pd.DataFrame
    stats: dict = field(default_factory=dict)
    source: str = ""

    def __len__(self) -> int:
        return len(self.fixes)


# -- NMEA 0183 ------------------------------------------------------------------------------------------
def nmea_checksum(body: str) -> int:
    """XOR of the characters between ``$`` and ``*`` (NMEA 0183)."""
    c = 0
    for ch in body:
        c ^= ord(ch)
    return c


def _nmea_coord(value: str, hemi: str, deg_digits: int) -> float:
    if not value or not hemi:
        raise ValueError("empty coordinate")
    deg = float(value[:deg_digits])
    minutes = float(value[deg_digits:])
    if minutes >= 60.0:
        raise ValueError("minutes >= 60")
    out = deg + minutes / 60.0
    if hemi in ("S", "W"):
        out = -out
    elif hemi not in ("N", "E"):
        raise ValueError(f"bad hemisphere {hemi!r}")
    return out


def _nmea_time(value: str) -> float:
    if len(value) < 6:
        raise ValueError("short time")
    h, m, s = int(value[0:2]), int(value[2:4]), float(value[4:])
    if h > 23 or m > 59 or s >= 61:
        raise ValueError("bad time")
    return h * 3600.0 + m * 60.0 + s


def parse_nmea_lines(
    lines,
    *,
    uere_m: float = DEFAULT_UERE_M,
    rmc_accuracy_m: float = DEFAULT_RMC_ACCURACY_M,
    t0_s: float = 0.0,
    source: str = "<nmea>",
) -> FixLog:
    """Parse NMEA 0183 text lines into a :class:`FixLog`; never raises on a bad sentence.

    Parameters
    ----------
    lines : iterable of str
    uere_m : user-equivalent range error (m); accuracy = HDOP * ``uere_m`` for GGA fixes.
    rmc_accuracy_m : accuracy (m) of an RMC fix without a GGA at the same epoch.
    t0_s : session-clock time (s) given to the first valid fix; later fixes follow their UTC times.

    Notes
    -----
    GGA and RMC of the same UTC epoch merge into one fix (GGA position and HDOP). Sentences with a wrong
    or missing checksum, an invalid status (RMC ``V``, GGA quality 0) or empty position fields are skipped
    and counted in ``stats``.
    """
    stats = dict(lines=0, sentences=0, used=0, bad_checksum=0, empty=0, malformed=0, unsupported=0)
    epochs: dict[float, dict] = {}
    order: list[float] = []
    last_tod = None
    rollover = 0.0
    for raw in lines:
        stats["lines"] += 1
        line = raw.strip()
        i = line.find("$")
        if i < 0:
            continue
        line = line[i + 1 :]
        stats["sentences"] += 1
        if "*" not in line:
            stats["bad_checksum"] += 1
            continue
        body, _, cks = line.partition("*")
        try:
            ok = int(cks[:2], 16) == nmea_checksum(body)
        except ValueError:
            ok = False
        if not ok:
            stats["bad_checksum"] += 1
            continue
        f = body.split(",")
        kind = f[0][-3:]
        if kind not in ("GGA", "RMC"):
            stats["unsupported"] += 1
            continue
        try:
            if kind == "GGA":
                if len(f) < 9:
                    raise ValueError("short GGA")
                if not f[2] or not f[4] or f[6] in ("", "0"):
                    stats["empty"] += 1
                    continue
                tod = _nmea_time(f[1])
                lat, lon = _nmea_coord(f[2], f[3], 2), _nmea_coord(f[4], f[5], 3)
                hdop = float(f[8]) if f[8] else float("nan")
                rec = dict(lat=lat, lon=lon, accuracy_m=hdop * uere_m if hdop > 0 else float("nan"))
            else:
                if len(f) < 10:
                    raise ValueError("short RMC")
                if f[2] != "A" or not f[3] or not f[5]:
                    stats["empty"] += 1
                    continue
                tod = _nmea_time(f[1])
                lat, lon = _nmea_coord(f[3], f[4], 2), _nmea_coord(f[5], f[6], 3)
                rec = dict(lat=lat, lon=lon, rmc=True)
        except (ValueError, IndexError):
            stats["malformed"] += 1
            continue
        if not (abs(lat) <= 90.0 and abs(lon) <= 180.0):
            stats["malformed"] += 1
            continue
        # time of day -> continuous seconds (midnight rollover when the time jumps back by > 12 h)
        if last_tod is not None and tod < last_tod - 43200.0:
            rollover += 86400.0
        last_tod = tod
        key = round(tod + rollover, 3)
        if key not in epochs:
            epochs[key] = {}
            order.append(key)
        e = epochs[key]
        if kind == "GGA" or "lat" not in e:
            keep_acc = e.get("accuracy_m")
            e.update(rec)
            if kind == "RMC" and keep_acc is not None:
                e["accuracy_m"] = keep_acc
        if kind == "RMC":
            e["rmc"] = True
    rows = []
    for k in order:
        e = epochs[k]
        acc = e.get("accuracy_m", float("nan"))
        if not np.isfinite(acc):
            acc = rmc_accuracy_m
        rows.append((k, e["lat"], e["lon"], acc))
    df = pd.DataFrame(rows, columns=["tabs", "lat", "lon", "accuracy_m"])
    if len(df):
        df = df.sort_values("tabs", kind="stable")
        df.insert(0, "t", df["tabs"] - df["tabs"].iloc[0] + t0_s)
        df = df.drop(columns="tabs").reset_index(drop=True)
    else:
        df = pd.DataFrame(columns=["t", "lat", "lon", "accuracy_m"], dtype=float)
    stats["used"] = int(len(df))
    stats["first_utc_s"] = float(order[0]) if order else None
    stats["time_base"] = "utc_day"  # decision D38: UTC seconds of day, placed on the session clock by aid_track
    skipped = stats["bad_checksum"] + stats["empty"] + stats["malformed"]
    if skipped:
        log.info(
            "%s: skipped %d sentence(s) (%d bad checksum, %d empty fix, %d malformed)",
            source,
            skipped,
            stats["bad_checksum"],
            stats["empty"],
            stats["malformed"],
        )
    return FixLog(df, stats, source)


def read_nmea(path, **kwargs) -> FixLog:
    """Read an NMEA 0183 log (GGA/RMC); see :func:`parse_nmea_lines` for the options."""
    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: no such NMEA file; pass the path of a .nmea/.txt log")
    with open(path, encoding="ascii", errors="replace") as fh:
        out = parse_nmea_lines(fh, source=str(path), **kwargs)
    if not len(out):
        raise DataError(
            f"{path}: no valid GGA/RMC fix in {out.stats['sentences']} sentence(s) "
            f"({out.stats['bad_checksum']} bad checksum, {out.stats['empty']} empty); "
            "check that the file is an NMEA 0183 log with a position fix, or pass a GPX file (.gpx) or a fix CSV "
            f"with {CSV_NEEDS} (decision D37)"
        )
    return out


# -- CSV ---------------------------------------------------------------------------------------------
def validate_fix_table(df: pd.DataFrame, source: str = "fix table") -> pd.DataFrame:
    """Check a fix table (columns, finiteness, positive accuracy); return it sorted by ``t``."""
    cols = set(df.columns)
    has_geo, has_xy = {"lat", "lon"} <= cols, {"x", "y"} <= cols
    missing = [c for c in ("t", "accuracy_m") if c not in cols]
    if missing or not (has_geo or has_xy):
        need = missing + ([] if has_geo or has_xy else ["lat+lon (or x+y)"])
        raise DataError(
            f"{source}: missing column(s) {', '.join(need)}; a fix CSV needs {CSV_NEEDS}; it has: "
            f"{', '.join(map(str, df.columns))}"
        )
    use = ["t", "accuracy_m"] + (["lat", "lon"] if has_geo else []) + (["x", "y"] if has_xy else [])
    try:
        vals = df[use].astype(float)
    except (TypeError, ValueError):
        raise DataError(f"{source}: non-numeric values in {', '.join(use)}; fix or remove those rows") from None
    bad = ~np.isfinite(vals.to_numpy()).all(axis=1)
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise DataError(
            f"{source}: {int(bad.sum())} row(s) with NaN/inf (first: data row {row + 1}); "
            "drop fixes without a position or accuracy"
        )
    if (vals["accuracy_m"] <= 0).any():
        raise DataError(f"{source}: accuracy_m must be > 0 m (a 68 % radius); found {float(vals['accuracy_m'].min())}")
    if has_geo and ((vals["lat"].abs() > 90) | (vals["lon"].abs() > 180)).any():
        raise DataError(f"{source}: lat/lon out of range; give degrees (WGS-84), not radians or metres")
    out = df.copy()
    out[use] = vals
    return out.sort_values("t", kind="stable").reset_index(drop=True)


#: decision D37: column names a fix CSV may use for each field (case-insensitive), first found wins
CSV_ALIASES = {
    "t": ("t", "time", "timestamp", "utc", "datetime", "time_utc"),
    "lat": ("lat", "latitude"),
    "lon": ("lon", "lng", "long", "longitude"),
    "accuracy_m": ("accuracy_m", "accuracy", "horizontal_accuracy_m", "hacc"),
    "hdop": ("hdop",),
}
#: decision D37: what a fix CSV needs, for the error lines
CSV_NEEDS = ("t (session seconds, or ISO 8601 UTC times such as 2026-03-15T10:00:00Z), lat, lon (or x, y in m), and "
             "accuracy_m (m, 68 % radius) or hdop (accuracy = HDOP x 4 m)")


def _rename_aliases(df: pd.DataFrame) -> pd.DataFrame:
    """Decision D37: the fix CSV's columns under their canonical names (:data:`CSV_ALIASES`), case-insensitive."""
    lower = {str(c).strip().lower(): c for c in df.columns}
    ren = {}
    for canon, names in CSV_ALIASES.items():
        if canon in df.columns:
            continue
        for n in names:
            if n in lower and lower[n] not in ren:
                ren[lower[n]] = canon
                break
    return df.rename(columns=ren)


def _epoch_seconds(num: pd.Series, source: str) -> np.ndarray | None:
    """Decision D46: a numeric ``t`` column (NaN for a blank cell) is session seconds (None) unless its values reach
    B39's :data:`~pdrlearn.io.validate.EPOCH_START` (1e9 s, 31 years: no session's clock): wholly in
    [EPOCH_START, EPOCH_END) they are epoch seconds (UTC, returned as such); beyond EPOCH_END (epoch ms or finer), or
    a column mixing epoch and session seconds, is refused in one line."""
    from pdrlearn.io.validate import EPOCH_END, EPOCH_START

    v = num.to_numpy(float)
    seen = v[np.isfinite(v)]
    if not len(seen) or (np.abs(seen) < EPOCH_START).all():
        return None
    if ((seen >= EPOCH_START) & (seen < EPOCH_END)).all():
        return v
    lo, hi = float(seen.min()), float(seen.max())
    what = ("epoch milliseconds or finer? divide them by 1000 to epoch seconds" if hi >= EPOCH_END else
            f"epoch seconds (from {EPOCH_START:g}) mixed with session seconds")
    raise DataError(f"{source}: t runs from {lo:.15g} to {hi:.15g}: {what}; give t as session seconds, epoch seconds "
                    "or ISO 8601 UTC date-times (e.g. 2026-03-15T10:00:00Z) (decision D46)")


def _numeric_cells(values: pd.Series) -> tuple[pd.Series, pd.Series]:
    """A ``t`` column's cells as numbers (NaN where none) and its blank cells (empty, only spaces or NaN)."""
    return pd.to_numeric(values, errors="coerce"), values.isna() | values.astype(str).str.strip().eq("")


def _numeric_t(values: pd.Series) -> bool:
    """Decision D47: whether a ``t`` column holds only numbers (and blank cells), not ISO 8601 date-times."""
    num, blank = _numeric_cells(values)
    return bool((num.notna() | blank).all())


def _utc_seconds(values: pd.Series, source: str) -> np.ndarray | None:
    """Decision D37: ISO 8601 date-times -> seconds since the epoch (UTC; a time without an offset is read as UTC,
    as GPX and NMEA times are); None when the column is numeric (session seconds), except epoch seconds, returned
    as they are (decision D46, :func:`_epoch_seconds`). Decision D43: decided on the non-blank cells (a blank cell is
    no evidence of ISO times); a blank cell stays NaN, so :func:`validate_fix_table` names its row."""
    num, blank = _numeric_cells(values)
    if (num.notna() | blank).all():
        return _epoch_seconds(num, source)
    text = values[~blank].astype(str).str.strip()
    try:
        dt = pd.to_datetime(text, utc=True, format="ISO8601")
    except (ValueError, TypeError):  # D43: the first non-blank cell that is no ISO time
        unread = pd.to_datetime(text, utc=True, format="ISO8601", errors="coerce").isna()
        bad = values[~blank][unread].iloc[0] if unread.any() else values[num.isna() & ~blank].iloc[0]
        raise DataError(f"{source}: t value {bad!r} is neither a number (session seconds) nor an ISO 8601 date-time; "
                        f"a fix CSV needs {CSV_NEEDS}") from None
    out = np.full(len(values), np.nan)
    out[~blank.to_numpy()] = (dt - pd.Timestamp("1970-01-01", tz="UTC")).dt.total_seconds().to_numpy(float)
    return out


def _hdop_cells(values: pd.Series, source: str) -> tuple[np.ndarray, np.ndarray]:
    """Decision D44: a fix CSV's ``hdop`` column as floats and its blank cells (empty, only spaces or NaN: the
    receiver gave no HDOP, an unknown accuracy); any other cell that is no number is a one-line error naming its
    data row."""
    num = pd.to_numeric(values, errors="coerce").to_numpy(float)
    blank = (values.isna() | values.astype(str).str.strip().str.lower().isin(["", "nan"])).to_numpy()
    bad = np.isnan(num) & ~blank
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise DataError(f"{source}: hdop value {values.iloc[row]!r} in data row {row + 1} is not a number; give the "
                        "receiver's HDOP, or leave the cell blank for a fix of unknown accuracy (decision D44)")
    return num, blank


def read_fix_csv(path, *, uere_m: float = DEFAULT_UERE_M, accuracy_m: float = DEFAULT_RMC_ACCURACY_M) -> FixLog:
    """Read a fix CSV with columns ``t, lat, lon, accuracy_m`` (or ``t, x, y, accuracy_m``).

    Decision D37: ``latitude``/``longitude`` (and the other :data:`CSV_ALIASES`) name the same columns; ``t`` may be
    ISO 8601 UTC date-times (``stats['time_base'] == "utc"``, mapped onto the session clock like NMEA times by
    :func:`pdrlearn.aid.track.aid_track`); an ``hdop`` column stands for a missing ``accuracy_m`` (HDOP x ``uere_m``).
    Decision D44: a blank ``hdop`` cell (empty, spaces, NaN) is a fix of unknown accuracy, kept with ``accuracy_m``
    (a GPX point's without ``<hdop>``) and counted in ``stats['blank_hdop']``.
    """
    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: no such fix CSV; pass a file with columns t, lat, lon, accuracy_m")
    try:
        df = pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise DataError(
            f"{path}: not a readable CSV ({type(exc).__name__}); expected columns t, lat, lon, accuracy_m"
        ) from None
    df.columns = [str(c).strip() for c in df.columns]
    if not len(df):
        raise DataError(f"{path}: no fixes (empty table)")
    named_t = "t" in df.columns
    original = list(df.columns)
    df = _rename_aliases(df)
    stats = {"lines": int(len(df))}
    if "accuracy_m" not in df.columns and "hdop" in df.columns:  # decision D37: HDOP x UERE, as a GGA's
        hdop, blank = _hdop_cells(df["hdop"], str(path))
        df["accuracy_m"] = np.where(blank, accuracy_m, hdop * uere_m)  # decision D44: blank = unknown, the default
        stats["blank_hdop"] = int(blank.sum())
    epoch = _utc_seconds(df["t"], str(path)) if "t" in df.columns else None
    numeric = epoch is not None and _numeric_t(df["t"])  # decision D47: epoch seconds, not ISO date-times
    if epoch is None and "t" in df.columns and not named_t:  # decision D37: numbers only under t (session seconds)
        alias = original[list(df.columns).index("t")]
        raise DataError(f"{path}: column {alias!r} holds numbers, which could be seconds or milliseconds of any clock; "
                        "name it t when it is session seconds, or give ISO 8601 UTC date-times "
                        "(e.g. 2026-03-15T10:00:00Z)")
    if epoch is not None:
        df["t"] = epoch
    df = validate_fix_table(df, str(path))
    if epoch is not None:  # decision D37: times since the first fix; aid_track places them on the session clock
        stats["time_base"] = "utc"
        stats["first_epoch_s"] = float(df["t"].iloc[0])
        if numeric:  # decision D47: aid_track keeps them as session seconds on a session with an epoch clock
            stats["time_source"] = "epoch_seconds"
            stats["last_epoch_s"] = float(df["t"].iloc[-1])
        df["t"] = df["t"] - df["t"].iloc[0]
    stats["used"] = int(len(df))
    return FixLog(df, stats, str(path))


# -- GPX -------------------------------------------------------------------------------------------------
def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def read_gpx(path, *, uere_m: float = DEFAULT_UERE_M, accuracy_m: float = DEFAULT_RMC_ACCURACY_M) -> FixLog:
    """Read the track points (``<trkpt lat lon>`` with ``<time>``, optional ``<ele>``, ``<hdop>``) of a GPX 1.0/1.1
    file (decision D37; what handheld receivers export and what ``pdrlearn track`` writes as track.gpx).

    Times are UTC (GPX 1.1); ``t`` is seconds since the first point and ``stats['first_epoch_s']`` the first point's
    seconds since the epoch (``time_base`` ``"utc"``). Accuracy: HDOP x ``uere_m`` when the point has ``<hdop>``, else
    ``accuracy_m`` (a GPX point reports none; the default is an RMC fix's without HDOP). Points without a valid
    position or time are skipped and counted (``malformed``, ``no_time``).
    """
    import xml.etree.ElementTree as ET

    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: no such GPX file")
    stats = dict(points=0, used=0, malformed=0, no_time=0, no_hdop=0)
    rows = []
    try:
        for _, el in ET.iterparse(path, events=("end",)):
            if _local(el.tag) not in ("trkpt", "rtept"):
                continue
            stats["points"] += 1
            kids = {_local(c.tag): (c.text or "").strip() for c in el}
            try:
                lat, lon = float(el.get("lat", "nan")), float(el.get("lon", "nan"))
            except ValueError:
                lat = lon = float("nan")
            el.clear()  # a long track's points are not kept in the tree
            if not (abs(lat) <= 90.0 and abs(lon) <= 180.0):
                stats["malformed"] += 1
                continue
            when = pd.to_datetime(kids.get("time", ""), utc=True, errors="coerce", format="ISO8601")
            if pd.isna(when):
                stats["no_time"] += 1
                continue
            try:
                hdop = float(kids["hdop"]) if kids.get("hdop") else float("nan")
            except ValueError:
                hdop = float("nan")
            if not hdop > 0:
                stats["no_hdop"] += 1
            acc = hdop * uere_m if hdop > 0 else accuracy_m
            rows.append(((when - pd.Timestamp("1970-01-01", tz="UTC")).total_seconds(), lat, lon, acc))
    except ET.ParseError as exc:
        raise DataError(f"{path}: not a well-formed GPX (XML) file ({exc}); export the track again as GPX 1.1, or "
                        f"write a fix CSV with {CSV_NEEDS}") from None
    if not rows:
        why = (f"{stats['no_time']} without <time>" if stats["no_time"] else "")
        raise DataError(f"{path}: no GPX track point with a position and a UTC <time> in {stats['points']} point(s)"
                        + (f" ({why})" if why else "") + "; a track point needs lat, lon and <time> "
                        "(track.gpx has times only when the session gives its recording_start with a UTC offset)")
    df = pd.DataFrame(rows, columns=["tabs", "lat", "lon", "accuracy_m"]).sort_values("tabs", kind="stable")
    df = df.drop_duplicates("tabs", keep="last").reset_index(drop=True)
    stats["first_epoch_s"] = float(df["tabs"].iloc[0])
    stats["time_base"] = "utc"
    df.insert(0, "t", df["tabs"] - df["tabs"].iloc[0])
    df = df.drop(columns="tabs")
    stats["used"] = int(len(df))
    return FixLog(df, stats, str(path))


def fix_format(path) -> str:
    """Decision D37: ``"csv"``, ``"gpx"`` or ``"nmea"``: by extension (``.csv``, ``.gpx``), else by the first
    non-blank character (``<`` XML/GPX, ``$`` NMEA; anything else is read as a CSV when its first line has a comma
    and no ``$``)."""
    path = Path(path)
    ext = path.suffix.lower()
    if ext in (".csv", ".gpx"):
        return ext[1:]
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            head = fh.read(4096).lstrip("\ufeff \t\r\n")
    except OSError:
        return "nmea"
    if head.startswith("<"):
        return "gpx"
    first = head.splitlines()[0] if head else ""
    if "$" not in head and "," in first:
        return "csv"
    return "nmea"


def read_fixes(path, **nmea_options) -> FixLog:
    """Read fixes from a CSV, a GPX or an NMEA 0183 log (:func:`fix_format`, decision D37)."""
    kind = fix_format(path)
    if kind == "csv":
        return read_fix_csv(path)
    if kind == "gpx":
        return read_gpx(path)
    return read_nmea(path, **nmea_options)


def to_local(fixes: pd.DataFrame, origin: tuple[float, float] | None = None) -> tuple[pd.DataFrame, tuple]:
    """Return the fix table with ``x``/``y`` (m, ENU) and the origin used.

    Fixes that already carry ``x``/``y`` are returned unchanged. Otherwise ``lat``/``lon`` are projected on
    the tangent plane at ``origin`` (lat, lon in degrees); by default the first fix.
    """
    if {"x", "y"} <= set(fixes.columns):
        return fixes, origin
    if not len(fixes):
        return fixes.assign(x=np.zeros(0), y=np.zeros(0)), origin
    if origin is None:
        origin = (float(fixes["lat"].iloc[0]), float(fixes["lon"].iloc[0]))
    x, y = geodetic_to_enu(fixes["lat"].to_numpy(), fixes["lon"].to_numpy(), *origin)
    return fixes.assign(x=x, y=y), origin
