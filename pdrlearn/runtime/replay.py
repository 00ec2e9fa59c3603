"""Replaying a recorded session through the runtime with numpy alone (decision E76).

:func:`replay_chunks` cuts recorded streams into pushes (decision E28; ``pdrlearn run`` and the lean command
``python -m pdrlearn.runtime`` use it). :func:`read_streams` reads the sensor files of a PLASYS session folder
(``<sensor>.csv``: ``timestamp,x,y,z``, thesis ch.4.3.3, the columns found by name in any order and case, decision
B222; UTF-8, decision B221; timestamps in ms unless ``meta.json`` declares ``units.timestamp`` s, us or ns, decision
D1) without pandas; a value beyond any sensor's range is refused as the full reader refuses it (decision B431, the
kernel of B425). It reads sessions as ``pdrlearn simulate``,
``import-csv`` and ``write_session`` write them; it repairs nothing: a file the full reader would have to fix
(decimal commas, a sample-counter clock, per-unit clocks, other value units) is refused in one line that
names the full install's ``pdrlearn run``.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import NamedTuple

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.install import INSTALL_EVERYTHING
from pdrlearn.kernels.units import VALUE_LIMITS, check_units, data_row_lines, out_of_range, out_of_range_message
from pdrlearn.textfile import compressed_hint, duplicate_message, header_names, read_json, read_text, session_csv

log = logging.getLogger(__name__)

#: Step table columns in the order of ``pdrlearn track`` (decision B14); the runtime's extra columns follow
#: (``pdrlearn run`` and ``python -m pdrlearn.runtime`` write them so)
STEP_COLUMNS = ("start_s", "end_s", "event_s", "length_m", "heading_rad", "dz_m", "terrain", "direction",
                "backward_travel", "travel", "length_class")  # backward_travel: decision L224, right after
# direction; travel (decisions L412, E317) after it, as run's steps.csv

#: a sample this close to a chunk boundary (in chunk lengths) belongs to the chunk the boundary starts (E28)
CHUNK_TOLERANCE = 1e-9

#: seconds per timestamp unit of meta.json's ``units.timestamp`` (its first word; decision D1: default ms)
TIME_SCALES = {"ms": 1e-3, "s": 1.0, "us": 1e-6, "ns": 1e-9}

#: what a refusal of the lean reader suggests (decision E76)
FULL_READER = f"replay it with the full install's `pdrlearn run` ({INSTALL_EVERYTHING}), which reads and repairs more"


def replay_chunks(streams: dict, chunk_s: float):
    """The replay of decision E28: ``{sensor: (t, values)}`` cut into pushes of ``chunk_s`` seconds, one per
    chunk index ``k = floor((t - t0) / chunk_s + CHUNK_TOLERANCE)`` from the earliest sample ``t0`` of any
    stream, so every sample is in exactly one push (bounds ``t0 + k * chunk_s`` computed per chunk put a sample
    on a rounded boundary into two). Every chunk, empty or not, holds every stream."""
    streams = {n: (np.asarray(t, dtype=np.float64), v) for n, (t, v) in streams.items()}
    ts = [t for t, _ in streams.values() if len(t)]
    if not ts:
        return
    t0 = min(float(t[0]) for t in ts)
    idx = {n: np.floor((t - t0) / chunk_s + CHUNK_TOLERANCE).astype(np.int64) for n, (t, _) in streams.items()}
    n_chunks = max(int(i[-1]) for i in idx.values() if len(i)) + 1
    ks = np.arange(n_chunks + 1)
    cuts = {n: np.searchsorted(i, ks, side="left") for n, i in idx.items()}  # first sample of each chunk
    for k in range(n_chunks):
        yield {n: (t[cuts[n][k]:cuts[n][k + 1]], v[cuts[n][k]:cuts[n][k + 1]]) for n, (t, v) in streams.items()}


def read_meta(folder: Path) -> dict:
    """The session's ``meta.json`` (``{}`` without one); refused in one line when it is not a JSON object."""
    path = folder / "meta.json"
    if not path.is_file():
        return {}
    try:
        meta = read_json(path)
    except DataError:  # decision B221: not UTF-8, its own line
        raise
    except (ValueError, UnicodeDecodeError) as exc:
        raise DataError(f"{path}: not valid JSON ({str(exc).splitlines()[0]}); fix it or remove it") from None
    if not isinstance(meta, dict):
        raise DataError(f"{path}: must be a JSON object such as {{\"units\": {{\"timestamp\": \"ms\"}}}}; fix it")
    return meta


def _time_scale(meta: dict, where: Path) -> float:
    units = meta.get("units", {})
    if meta.get("clocks"):
        raise DataError(f"{where}: declares per-unit \"clocks\" (decision B115), which the lean reader does not "
                        f"apply; {FULL_READER}")
    word = (str(units.get("timestamp", "ms")).split() or ["ms"])[0] if isinstance(units, dict) else None
    if word not in TIME_SCALES:
        raise DataError(f"{where}: units.timestamp {units.get('timestamp') if isinstance(units, dict) else units!r} "
                        f"is not ms, s, us or ns (the lean reader's units); {FULL_READER}")
    return TIME_SCALES[word]


#: a PLASYS sensor file's value columns by their number (thesis ch.4.3.3: ``timestamp,x,y,z``; force and barometer
#: files ``timestamp,x``)
VALUE_COLUMNS = {1: ("x",), 3: ("x", "y", "z")}

#: each sensor's kind and SI unit, as ``pdrlearn.io.sensors.SENSORS[name]`` (thesis ch.4.3.3; not imported:
#: ``pdrlearn.io`` imports pandas, the runtime numpy only), for B425's range check (decision B431)
SENSOR_KINDS = {"fAccelerometer": ("accelerometer", "m/s^2"), "fGyroscope": ("gyroscope", "rad/s"),
                "fForceA": ("force", "N"), "fForceB": ("force", "N"), "wAccelerometer": ("accelerometer", "m/s^2"),
                "wGyroscope": ("gyroscope", "rad/s"), "wMagneticField": ("magnetometer", "uT"),
                "wBarometer": ("barometer", "hPa")}


class _Spec(NamedTuple):
    """What :func:`~pdrlearn.kernels.units.check_units` and :func:`~pdrlearn.kernels.units.out_of_range_message`
    read of a :class:`~pdrlearn.io.sensors.SensorSpec`."""

    name: str
    kind: str
    unit: str
    columns: tuple[str, ...]


def range_spec(name: str, width: int) -> _Spec:
    """The sensor ``name``'s kind, SI unit and value columns (``width`` values a sample), for B425's line."""
    return _Spec(name, *SENSOR_KINDS[name], VALUE_COLUMNS[width])


#: decision B425's limit per streamed sensor (SI), for :func:`refuse_pushed_out_of_range`
PUSH_LIMITS = {n: VALUE_LIMITS[kind] for n, (kind, _) in SENSOR_KINDS.items()}


def refuse_pushed_out_of_range(who: str, checked: dict, guard=None, fast: dict | None = None) -> None:
    """Decisions B435 / B442: B425's range check on a live push (offline's one line, the sample's time for its
    line), so that a 1e308 pushed live is refused, not tracked into NaN - the foot :class:`~pdrlearn.runtime.Tracker`'s
    and the lean :class:`~pdrlearn.runtime.waist.WaistTracker`'s one check. ``checked``: ``{sensor: (t, values)}``;
    ``fast``: ``{sensor: (t0, values)}`` of one-sample (E17) sensors; ``who``: the class named in the line. Called
    after B119's ``guard`` has judged the push, and for a stream it still judges after its unit checks on what it
    holds with this push (:meth:`~pdrlearn.runtime.guard.UnitGuard.units_first`): a stream in another unit keeps its
    wrong-unit line. Per push: a comparison per one-sample sensor, a max |value| per array. Changes nothing."""
    bad = None
    for name, (t0, vals) in (fast or {}).items():
        lim = PUSH_LIMITS.get(name)
        if lim is not None and (max(vals) > lim or min(vals) < -lim):
            bad = name, np.array([t0]), np.array([vals])
            break
    else:
        for name, (t, v) in checked.items():
            lim = PUSH_LIMITS.get(name)
            if lim is not None and float(np.abs(v).max()) > lim:
                bad = name, t, v
                break
    if bad is None:
        return
    name, t, v = bad
    if guard is not None:
        guard.units_first(name, (t, v))
    spec = range_spec(name, v.shape[1])
    raise DataError(out_of_range_message(f"{name} (pushed to the {who})", spec, v, out_of_range(spec.kind, v), t=t))


def _refuse_out_of_range(path: Path, name: str, t: np.ndarray, values: np.ndarray, lines: np.ndarray) -> None:
    """Decision B431: B425's range check (:func:`~pdrlearn.kernels.units.out_of_range`, the full reader's kernel)
    on a sensor file the lean reader read (SI values: it takes no other unit). A whole file in another unit keeps
    B30's wrong-unit line, checked first as the full reader does (its medians and percentiles are not moved by a few
    corrupt rows; their squares may overflow there, silently); ``lines``: each row's line in the file."""
    rows = out_of_range(SENSOR_KINDS[name][0], values)
    if not rows.size:
        return
    spec = range_spec(name, values.shape[1])
    with np.errstate(over="ignore", invalid="ignore"):
        check_units(spec, values, str(path), declare="", t=t)  # "": the lean reader takes no declared unit
    raise DataError(out_of_range_message(str(path), spec, values, rows, first_line=int(lines[rows[0]]) - int(rows[0])))


def _columns(path: Path, name: str, head: str) -> tuple[list[str], list[int]]:
    """The header ``head``'s column names and the order taking them to ``timestamp,x[,y,z]`` (decision B222), or
    one line naming ``path``."""
    n_values = 1 if name.startswith(("fForce", "wBarometer")) else 3
    names, want = header_names(head), ("timestamp", *VALUE_COLUMNS[n_values])
    dup = duplicate_message(path, names, head)
    if dup:
        raise DataError(dup)
    if "timestamp" not in names:
        raise DataError(f"{path}: the first line is {head[:40]!r}, not the header 'timestamp,x,...' of a PLASYS "
                        f"sensor file; {FULL_READER}")
    if sorted(names) != sorted(want):
        raise DataError(f"{path}: columns {','.join(names)}, expected {','.join(want)} (in any order); {FULL_READER}")
    return names, [names.index(c) for c in want]


def _parse(path: Path, rows: list[str], names: list[str], order: list[int]) -> np.ndarray:
    """The data ``rows`` of ``path`` as a float array in ``timestamp,x[,y,z]`` order (decision B222), or one line."""
    try:
        a = np.loadtxt(rows, delimiter=",", ndmin=2, dtype=np.float64)
    except ValueError as exc:
        raise DataError(f"{path}: {str(exc).splitlines()[0]} (the lean reader reads plain comma-separated numbers); "
                        f"{FULL_READER}") from None
    if a.shape[1] != len(names):
        raise DataError(f"{path}: {a.shape[1]} values per row under a header of {len(names)} columns (decimal "
                        f"commas in a comma-separated file?); {FULL_READER}")
    if order != list(range(len(order))):  # decision B222: by name, as the full reader (C order kept, as loadtxt's)
        a = np.ascontiguousarray(a[:, order])
    return a


def _read_csv(path: Path, name: str, scale: float) -> tuple[np.ndarray, np.ndarray]:
    """One sensor file's ``(t_s, values)``, its columns taken by name in any order (decision B222: a file written
    ``timestamp,z,x,y`` had been read by position, its z as x, and tracked 38.7 m of an 89.9 m walk); a value
    beyond any sensor's range refused (decision B431)."""
    lines = read_text(path).splitlines()  # decision B221: UTF-8 (a BOM accepted), else one line
    names, order = _columns(path, name, lines[0] if lines else "")
    kept = data_row_lines(lines)  # 1-based, blank lines skipped (shared with the full reader's B425 line)
    rows = [lines[i - 1] for i in kept]
    if not rows:
        raise DataError(f"{path}: no data rows under the header; re-record the file or remove it")
    a = _parse(path, rows, names, order)
    t = a[:, 0] * scale
    _refuse_out_of_range(path, name, t, a[:, 1:], np.asarray(kept))  # decision B431: line numbers from 1
    return t, a[:, 1:]


def read_streams(folder, bundle) -> tuple[dict, dict]:
    """``({sensor: (t_s, values)}, meta)`` of the sensors of ``bundle`` (required and optional) that the PLASYS
    session ``folder`` holds (the Tracker's ``sensors=`` then checks the required ones, decision E55)."""
    folder = Path(folder)
    meta, scale, files = session_files(folder, bundle)
    return {name: _read_csv(path, name, scale) for name, path in files()}, meta


def session_files(folder: Path, bundle):
    """``(meta, scale, files)`` of the PLASYS session ``folder``: its ``meta.json``, the seconds per timestamp unit,
    and ``files()``, an iterator of ``(sensor, path)`` over the bundle's sensors the folder holds, in the bundle's
    order, each checked against the unit ``meta.json`` declares for it as it comes (so a bad file is said when it is
    reached, as before); one line naming the folder when it holds none. Shared by :func:`read_streams` and the
    chunked replay (decision E274)."""
    if not folder.is_dir():
        raise DataError(f"{folder}: session folder not found; give a folder of <sensor>.csv files (PLASYS layout)")
    meta = read_meta(folder)
    scale = _time_scale(meta, folder / "meta.json")
    declared = meta.get("units") if isinstance(meta.get("units"), dict) else {}
    required, optional = bundle.sensors_of()

    def files():
        found = False
        for name in [*required, *optional]:
            path = session_csv(folder, name)  # decision B369: X.csv or X.csv.gz (gzip: the standard library)
            if not path.is_file():
                continue
            si = bundle.manifest["units"].get(name)
            if name in declared and si is not None and str(declared[name]).split()[:1] != [si]:
                raise DataError(f"{folder / 'meta.json'}: units.{name} {declared[name]!r} is not {si}, the unit the "
                                f"lean reader takes; {FULL_READER}")
            found = True
            yield name, path
        if not found:
            raise MissingSensorError(f"{folder}: no sensor file the bundle reads ({', '.join([*required, *optional])})"
                                     f"{compressed_hint(folder, [*required, *optional])}")

    return meta, scale, files


def session_frames(meta: dict, bundle, units, where: str) -> dict:
    """Each body unit's axis frame: the one the session's ``meta.json`` declares (``frames``, decision D2),
    else the bundle's (its training sessions'), with one warning. The lean path does not check a declared frame
    against the data nor infer one (decisions D8, D10 need the full install)."""
    declared = meta.get("frames") if isinstance(meta.get("frames"), dict) else {}
    frames = dict(bundle.manifest["frames"])
    for unit in units:
        if unit in declared:
            frames[unit] = declared[unit]
        elif unit in frames:
            log.warning("%s declares no %s frame; using the bundle's %s (the lean reader infers none: declare "
                        "\"frames\" in meta.json)", where, unit, frames[unit])
    return frames


def travel_table(rows: list[dict]) -> list[dict]:
    """Decisions L224, E317: a foot replay's step rows (``Step.to_dict``) with steps.csv's ``backward_travel`` and
    ``travel`` (:func:`pdrlearn.kernels.travel.travel_rows`), the columns ``pdrlearn run`` writes for the same rows;
    a table without ``turn_angle_rad`` (no foot replay) unchanged."""
    if not rows or not all("turn_angle_rad" in r for r in rows):
        return rows
    from pdrlearn.kernels.backward import backward_rows
    from pdrlearn.kernels.travel import travel_rows

    return [{**r, "backward_travel": b, "travel": t}
            for r, b, t in zip(rows, backward_rows(rows), travel_rows(rows), strict=True)]


def travel_warnings(rows: list[dict], bundle, where: str) -> list[str]:
    """Decision E317: ``pdrlearn run``'s C137 / L578 / L652 lines (the side-step, turn-on-the-spot and
    forward-travelling strides the direction model classed backward;
    :func:`pdrlearn.kernels.travel.classed_backward_lines`, the kernel of ``track.travel.side_class_warning``) on
    a foot replay's ``rows`` (:func:`travel_table`'s), logged as the runtime's warnings (``where: line``) and
    returned; C161's count of trained side steps from the bundle's manifest."""
    if not rows or not all("direction" in r and "turn_angle_rad" in r for r in rows):
        return []
    from pdrlearn.classify.uncovered import trained_side_strides
    from pdrlearn.kernels.backward import first_unjudged
    from pdrlearn.kernels.travel import classed_backward_lines, row_values

    lines = classed_backward_lines([r["direction"] for r in rows], [bool(r.get("sideways")) for r in rows],
                                   row_values(rows, "length_m"), [r.get("travel") for r in rows],
                                   row_values(rows, "turn_angle_rad"),
                                   row_values(rows, "confidence") if all("confidence" in r for r in rows) else None,
                                   trained_side_strides(bundle),
                                   first_unjudged(len(rows), row_values(rows, "gap_s")))  # decision E318
    for line in lines:
        log.warning("%s: %s", where, line)
    return lines
