"""Decision B379: split a long session (a whole-day recording) into parts that are sessions of their own.

Every CSV of the session folder is read in chunks (``pandas.read_csv(chunksize=...)``), so the peak memory is
that of a chunk and of the search windows around the cuts, not of the file: ``pdrlearn track`` holds the whole
session in memory (decision E195: 0.3-0.4 GB per recorded hour), which a day of two units cannot fit. The parts
are cut near every ``max_minutes`` boundary at a standstill common to every unit (the same cut time for all
units), so each part starts and ends at rest like a recording of its own. Rows are copied as written (text, not
re-formatted numbers) and keep the session's absolute time; label tables are sliced by their time columns.
"""

from __future__ import annotations

import gzip
import io
import json
import logging
import math
import os
from collections.abc import Iterator
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.sensors import SENSORS, UNIT_IMU
from pdrlearn.kernels.order import first_out_of_order
from pdrlearn.textfile import GZ_CSV, csv_stem, is_gzip, read_json, session_csv, session_csvs

log = logging.getLogger(__name__)

#: rows per chunk read (decision B379); the output does not depend on it (tests/test_split_b379.py)
CHUNK_ROWS = 100_000
#: decision B379: how far from a boundary the common standstill is searched (either side), at most; shorter
#: parts search a quarter of their length, so that two cuts never cross
SEARCH_S = 300.0
#: decision B379: the shortest common standstill cut in two, so that each part keeps the thesis' 2 s setup
#: standstill (thesis ch.7.2; the standstill calibration's ``min_s``) at its end or start
MIN_REST_S = 4.0
#: decision B380: the shortest part: the 2 s standstill at each end (thesis ch.7.2) and room for walking; a
#: shorter --max-minutes is refused, a shorter last piece is kept with the part before it
MIN_PART_S = 30.0
#: meta.json keys that count or measure the whole session: moved under ``split.whole_session`` in a part's
#: meta.json, where no command reads them as the part's own (distance_m scores a track's distance)
WHOLE_SESSION_KEYS = ("distance_m", "n_ics", "n_strides", "n_steps", "n_turns", "terrain_counts", "duration_s",
                      "n_samples", "dropped_samples", "activity_seconds")


#: decision B386: an interval between two rows of an accelerometer or gyroscope file longer than this (s) is a gap
#: of the recording: a part's sensor span ends before it and its label rows are judged by that span
GAP_S = 1.0


@dataclass
class Cut:
    """One cut between two parts: its time (s, the session clock) and whether it lies in a common standstill (or,
    decision B386, in a gap of every unit's rows: ``in_gap``)."""

    t: float
    at_rest: bool
    boundary: float
    in_gap: bool = False


@dataclass
class _Window:
    """Rows of one sensor file within a search window: timestamps (s) and values."""

    t: list = field(default_factory=list)
    v: list = field(default_factory=list)

    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        if not self.t:
            return np.zeros(0), np.zeros((0, 3))
        return np.concatenate(self.t), np.concatenate(self.v)


def rest_cut(t: np.ndarray, still: np.ndarray, boundary: float, *, min_rest_s: float = MIN_REST_S) -> float | None:
    """The middle of the standstill run (``still`` at the times ``t``, s) of at least ``min_rest_s`` whose middle
    lies nearest to ``boundary``; ``None`` when there is none (decision B379)."""
    from pdrlearn.signal.conditioning import runs

    best = None
    for i, j in runs(still):
        t0, t1 = float(t[i]), float(t[j - 1])
        if t1 - t0 < min_rest_s:
            continue
        mid = 0.5 * (t0 + t1)
        if best is None or abs(mid - boundary) < abs(best - boundary):
            best = mid
    return best


def _unit_still(acc: tuple[np.ndarray, np.ndarray], gyr: tuple[np.ndarray, np.ndarray],
                grid: np.ndarray) -> np.ndarray | None:
    """One unit's standstill (pdrlearn.signal's detector) on ``grid``; ``None`` when the unit has no samples there.
    The gyroscope is interpolated to the accelerometer's timestamps; a grid point farther than 1.5 sample periods
    from the unit's samples (a gap) is not still."""
    from pdrlearn.signal.conditioning import standstill_mask

    (ta, va), (tg, vg) = acc, gyr
    if ta.size < 3 or tg.size < 3:
        return None
    fs = 1.0 / float(np.median(np.diff(ta)))
    g = np.column_stack([np.interp(ta, tg, vg[:, k]) for k in range(vg.shape[1])])
    still = standstill_mask(va, g, fs)
    k = np.clip(np.searchsorted(ta, grid), 1, ta.size - 1)
    near = np.where(np.abs(ta[k - 1] - grid) <= np.abs(ta[k] - grid), k - 1, k)
    # decision B386: a grid point in a gap of the unit's rows (no sample within 1.5 periods) is no obstacle to a
    # cut either: nothing of the unit is cut there
    return still[near] | (np.abs(ta[near] - grid) > 1.5 / fs)


def _segments(t: np.ndarray) -> list[tuple[float, float]]:
    """Decision B386: the runs of timestamps ``t`` (s, sorted) without a gap over :data:`GAP_S`, as (first, last)."""
    breaks = np.flatnonzero(np.diff(t) > GAP_S)
    starts, ends = np.r_[0, breaks + 1], np.r_[breaks, t.size - 1]
    return [(float(t[a]), float(t[b])) for a, b in zip(starts, ends, strict=True)]


def sensor_spans(segments: list[tuple[float, float]], edges: list[float]) -> list[tuple[float, float] | None]:
    """Decision B386: each part's sensor span (``edges``: its start and end times, s) - from its first to its last
    accelerometer/gyroscope row, as far as ``segments`` (runs of rows without a gap) tell - or None for a part
    without any such row."""
    out = []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        inside = [(max(s0, a), min(s1, b)) for s0, s1 in segments if s1 >= a and s0 < b]
        out.append((min(x for x, _ in inside), max(y for _, y in inside)) if inside else None)
    return out


class _ChunkReader:
    """The chunks of one CSV of a session folder: text cells as written, plus their times in seconds."""

    def __init__(self, path: Path, scale: float, chunk_rows: int):
        from pdrlearn.io.plasys import _csv_dialect

        self.path, self.scale, self.chunk_rows = path, scale, chunk_rows
        self.dialect = _csv_dialect(path)
        self.sep = self.dialect.get("sep") or ","
        self.comma = self.dialect.get("decimal") == ","  # decision B24: a ';' file with decimal commas
        self._held: tuple[tuple[pd.DataFrame, int] | None, Iterator] | None = None  # decision B388: head's read

    def numbers(self, cells: pd.Series) -> pd.Series:
        """Text cells as numbers (NaN where a cell is blank or no number), a decimal comma read as a point."""
        cells = cells.str.strip()
        return pd.to_numeric(cells.str.replace(",", ".", regex=False) if self.comma else cells, errors="coerce")

    def chunks(self) -> Iterator[tuple[pd.DataFrame, int]]:
        """``(chunk, line of its first row)``: every cell a string (empty cells stay empty). Decision B388: after
        :meth:`head` the read it began goes on (its rows first), so the file is not opened again."""
        held, self._held = self._held, None
        if held is None:
            yield from self._read(None)
            return
        first, rest = held
        if first is not None:
            yield first
        yield from rest

    def head(self, rows: int) -> pd.DataFrame | None:
        """Decision B388: the file's first ``rows`` rows (None without a row), its read held for :meth:`chunks`
        (:meth:`close` ends it when no :meth:`chunks` follows)."""
        self.close()
        rest = self._read(rows)
        first = next(rest, None)
        self._held = (first, rest)
        return None if first is None else first[0]

    def close(self) -> None:
        """End a read :meth:`head` began and :meth:`chunks` did not take."""
        held, self._held = self._held, None
        if held is not None:
            held[1].close()

    def _read(self, first_rows: int | None) -> Iterator[tuple[pd.DataFrame, int]]:
        """The chunks of one read of the file (the first ``first_rows`` rows long when given)."""
        line = 2
        try:
            reader = pd.read_csv(self.path, dtype=str, keep_default_na=False, chunksize=self.chunk_rows,
                                 **self.dialect)
            with reader:
                while True:
                    try:
                        chunk = reader.get_chunk(first_rows)
                    except StopIteration:
                        return
                    first_rows = None
                    chunk.columns = [str(c).strip() for c in chunk.columns]
                    yield chunk, line
                    line += len(chunk)
        except pd.errors.EmptyDataError:
            raise DataError(f"{self.path}: file is empty (not even a header line); re-export or remove it") from None
        except pd.errors.ParserError as exc:
            first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise DataError(f"{self.path}: not a valid CSV ({first}); fix or re-export the file") from None
        except UnicodeError:
            raise DataError(f"{self.path}: not UTF-8 text; save it as UTF-8 (decision B221)") from None

    def time_columns(self, columns) -> list[tuple[str, float]]:
        """The time columns of a header and their seconds per unit: ``timestamp`` in the session's unit, ``*_ms``
        (``t_ms``, ``start_ms`` ...) in ms (decision D1)."""
        out = []
        for c in columns:
            low = c.lower()
            if low == "timestamp":
                out.append((c, self.scale))
            elif low.endswith("_ms"):
                out.append((c, 1e-3))
        return out

    def times(self, chunk: pd.DataFrame, cols: list[tuple[str, float]], line: int, *, required: bool) -> np.ndarray:
        """(n, len(cols)) times in s; a blank cell is NaN; a cell that is no number is one line (``required``:
        a blank one too)."""
        out = np.empty((len(chunk), len(cols)))
        for k, (c, scale) in enumerate(cols):
            cells = chunk[c].str.strip()
            vals = self.numbers(cells)
            bad = vals.isna() & ((cells != "") | required)
            if bad.any():
                first = int(np.flatnonzero(bad.to_numpy())[0])
                raise DataError(f"{self.path}: column {c} holds {cells.iloc[first]!r} at line {line + first}, not a "
                                "number; fix or remove that row (decision B380)")
            out[:, k] = vals.to_numpy(dtype=float) * scale
        return out


def _check_sorted(path: Path, t: np.ndarray, last: float, line: int) -> None:
    """Decision B380 (D3 while streaming): a timestamp below the one before it is one line naming its line."""
    i = first_out_of_order(t, last, strict=False)
    if i is not None:
        raise DataError(f"{path}: timestamps are not sorted (line {line + i} is earlier than the line "
                        "before it); sort the file by timestamp or fix the logger, then split (decisions D3, B380)")


def _numeric_times(r: _ChunkReader, chunk: pd.DataFrame, line: int) -> tuple[np.ndarray, list[str]]:
    """An accelerometer or gyroscope chunk's times (s) and its timestamp,x,y,z columns, or one line."""
    cols = [c for c in chunk.columns if c.lower() in ("timestamp", "x", "y", "z")]
    if [c.lower() for c in cols] != ["timestamp", "x", "y", "z"]:
        raise DataError(f"{r.path}: needs the columns timestamp,x,y,z (has {','.join(chunk.columns)}); fix the "
                        "header (thesis ch.4.3.3)")
    return r.times(chunk, [(cols[0], r.scale)], line, required=True)[:, 0], cols


def _numeric_chunks(r: _ChunkReader) -> Iterator[tuple[np.ndarray, pd.DataFrame, list[str]]]:
    """An accelerometer or gyroscope file's chunks as (times in s, the chunk, its timestamp,x,y,z columns); unsorted
    timestamps are one line (decision B380)."""
    last = -math.inf
    for chunk, line in r.chunks():
        t, cols = _numeric_times(r, chunk, line)
        _check_sorted(r.path, t, last, line)
        if t.size:
            last = float(t[-1])
            yield t, chunk, cols


#: decision B385: rows of each sensor file the timestamp unit is inferred from (B22 reads the median interval and
#: the first timestamp, which the first rows give)
HEAD_ROWS = 1000


def _head(r: _ChunkReader) -> np.ndarray | None:
    """The first :data:`HEAD_ROWS` rows of a sensor file as numbers, the timestamp first (NaN where a cell is no
    number); None when it holds no row or no timestamp column. Decision B388: the read is held for the scan."""
    chunk = r.head(HEAD_ROWS)
    if chunk is None:
        return None
    cols = r.time_columns(chunk.columns)[:1]
    if not cols or chunk.empty:
        return None
    rest = [c for c in chunk.columns if c != cols[0][0]]
    return np.column_stack([r.numbers(chunk[c]).to_numpy(float) for c in [cols[0][0], *rest]])


def session_time_scale(readers: dict[str, _ChunkReader], meta: dict, folder: Path,
                       meta_path: Path) -> tuple[float, str | None]:
    """Decision B385: seconds per timestamp unit as the session reader finds it (``_group_time_scale``: the
    declared unit, B16; else the unit every sensor file's rate allows, B22; else sample indices at ``rate_hz``,
    B31), from each sensor file's first rows (``readers``: the session's sensor files by name); and the unit read
    when meta.json declares none (None: ms)."""
    from pdrlearn.io.plasys import _group_time_scale, meta_rate

    raw = {name: h for name, r in readers.items() if (h := _head(r)) is not None}
    return _group_time_scale(raw, meta, meta_rate(meta, meta_path), folder, meta_path)


def first_time(r: _ChunkReader) -> float | None:
    """The first timestamp (s) of a sensor file, read from the first row :meth:`_ChunkReader.head` holds (decision
    B388: not a read of its own)."""
    if r._held is None or r._held[0] is None or r._held[0][0].empty:
        return None
    chunk, line = r._held[0]
    return float(_numeric_times(r, chunk.iloc[:1], line)[0][0])


class _UnitScan:
    """Decision B379: one unit's accelerometer and gyroscope files streamed side by side, keeping only the rows
    within ``span`` of each boundary ``t0 + k * part_s`` until both files have passed it; then the unit's
    standstill on the boundary's search grid replaces the rows (the memory: a chunk and one window per file)."""

    def __init__(self, readers: tuple[_ChunkReader, _ChunkReader], t0: float, part_s: float, span: float):
        self.readers, self.t0, self.part_s, self.span = readers, t0, part_s, span
        self.masks: dict[int, np.ndarray | None] = {}
        self.last = -math.inf
        self.segments: list[tuple[float, float]] = []  # decision B386: where the unit has rows

    def grid(self, k: int) -> np.ndarray:
        b = self.t0 + k * self.part_s
        return b + np.arange(-self.span, self.span + 1e-9, 0.01)  # 100 Hz: finer than the detector's 0.25 s

    def run(self) -> None:
        its = [_numeric_chunks(r) for r in self.readers]
        last = [-math.inf, -math.inf]
        done = [False, False]
        windows: list[dict[int, _Window]] = [{}, {}]
        while not all(done):
            i = min((j for j in (0, 1) if not done[j]), key=lambda j: last[j])
            got = next(its[i], None)
            if got is None:
                done[i] = True
            else:
                t, chunk, cols = got
                self.segments += _segments(np.r_[last[i], t] if math.isfinite(last[i]) else t)
                last[i] = float(t[-1])
                self._keep(t, chunk, cols, windows[i], self.readers[i])
            ready = [k for k in {*windows[0], *windows[1]}
                     if all(done[j] or last[j] > self.t0 + k * self.part_s + self.span for j in (0, 1))]
            for k in ready:
                acc, gyr = (windows[j].pop(k, _Window()).arrays() for j in (0, 1))
                self.masks[k] = _unit_still(acc, gyr, self.grid(k))
        self.last = max(last)

    def _keep(self, t: np.ndarray, chunk: pd.DataFrame, cols: list[str], windows: dict, r: _ChunkReader) -> None:
        k_lo = max(1, math.ceil((t[0] - self.t0 - self.span) / self.part_s))
        k_hi = math.floor((t[-1] - self.t0 + self.span) / self.part_s)
        for k in range(k_lo, k_hi + 1):
            b = self.t0 + k * self.part_s
            sel = (t >= b - self.span) & (t <= b + self.span)
            if not sel.any():
                continue
            vals = np.column_stack([r.numbers(chunk.loc[sel, c]).to_numpy(float) for c in cols[1:4]])
            if not np.isfinite(vals).all():
                raise DataError(f"{r.path}: non-numeric or non-finite values near {b:.0f} s; fix or remove those rows "
                                "(decision B380)")
            w = windows.setdefault(k, _Window())
            w.t.append(t[sel])
            w.v.append(vals)


def _in_gap(t: float, segments: list[tuple[float, float]]) -> bool:
    return not any(s0 <= t <= s1 for s0, s1 in segments)


def _merge_empty(cuts: list[Cut], t0: float, t_end: float, segments: list[tuple[float, float]]) -> list[Cut]:
    """Decision B386: no part without accelerometer/gyroscope rows (a part inside a data gap): such a part is merged
    into the part before it (the cut at its start removed; the first part into the one after it)."""
    while len(cuts) > 0:
        spans = sensor_spans(segments, [t0, *(c.t for c in cuts), t_end])
        empty = next((k for k, sp in enumerate(spans) if sp is None), None)
        if empty is None:
            break
        del cuts[max(empty - 1, 0)]
    return cuts


def scan_cuts(units: list[tuple[_ChunkReader, _ChunkReader]], t0: float, part_s: float,
              span: float) -> tuple[list[Cut], float, list[tuple[float, float]]]:
    """Decision B379: the cuts of a session whose units' (accelerometer, gyroscope) files are ``units``: near each
    boundary ``t0 + k * part_s`` in the middle of the standstill common to every unit with samples there (B386: or
    of a gap in their rows), else at the boundary; B386: a part without rows merged into its neighbour. Returns the
    cuts, the units' last timestamp (s) and where the units have rows (:func:`_segments`)."""
    scans = [_UnitScan(r, t0, part_s, span) for r in units]
    for s in scans:
        s.run()
    t_end = max(s.last for s in scans)
    segments = sorted(seg for s in scans for seg in s.segments)
    cuts = []
    k = 1
    while t0 + k * part_s < t_end - MIN_PART_S:  # a last piece shorter than MIN_PART_S stays with the part before
        b = t0 + k * part_s
        masks = [m for s in scans if (m := s.masks.get(k)) is not None]
        t_cut = None
        if masks:
            t_cut = rest_cut(scans[0].grid(k), np.logical_and.reduce(masks), b)
        t = b if t_cut is None else t_cut
        gap = _in_gap(t, segments)
        cuts.append(Cut(t, t_cut is not None and not gap, b, gap))
        k += 1
    return _merge_empty(cuts, t0, t_end, segments), t_end, segments


class _PartFiles:
    """One CSV's output file in each part folder, opened at its first row (a ``.csv.gz`` is written gzip-compressed,
    with no time stamp in the gzip header, so equal rows give equal bytes)."""

    def __init__(self, stack: ExitStack, parts: list[Path], name: str, header: str):
        self.stack, self.parts, self.name, self.header = stack, parts, name, header
        self.files: dict[int, io.TextIOBase] = {}

    def get(self, k: int):
        f = self.files.get(k)
        if f is None:
            raw = self.stack.enter_context(open(self.parts[k] / self.name, "wb"))
            if self.name.lower().endswith(GZ_CSV):
                raw = self.stack.enter_context(gzip.GzipFile(filename="", mode="wb", fileobj=raw, mtime=0))
            f = self.stack.enter_context(io.TextIOWrapper(raw, encoding="utf-8", newline=""))
            f.write(self.header + "\n")
            self.files[k] = f
        return f


@dataclass
class SplitResult:
    """What :func:`split_session` wrote: the part folders, the cuts, and the label rows left out at the cuts."""

    parts: list[Path]
    cuts: list[Cut]
    t_start: float
    t_end: float
    dropped: dict[str, int]
    copied_whole: list[str]


def _route(cut_times: np.ndarray, times: np.ndarray,
           spans: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Each row's part (by its earliest time) and whether the row fits in it (its latest time before the part's end
    and some time given). A row spanning a cut (a stride or bout across it) does not fit; decision B386: with
    ``spans`` (each part's sensor span, (parts, 2) s) neither does a row outside its part's span (in a data gap)."""
    has = np.isfinite(times).any(axis=1)
    lo = np.where(has, np.nanmin(np.where(np.isfinite(times), times, np.inf), axis=1), 0.0)
    hi = np.where(has, np.nanmax(np.where(np.isfinite(times), times, -np.inf), axis=1), 0.0)
    part = np.searchsorted(cut_times, lo, side="right")
    end = np.append(cut_times, np.inf)[part]
    fits = has & (hi < end)
    if spans is not None:
        fits &= (lo >= spans[part, 0]) & (hi <= spans[part, 1])
    return part, fits


def _write_file(r: _ChunkReader, cut_times: np.ndarray, parts: list[Path], result: SplitResult,
                spans: np.ndarray) -> None:
    """Stream one CSV of the session into the part folders (decision B379). Sensor files: every row by its
    timestamp, which must be sorted (B380); a part without rows of it gets no such file. Other CSVs with time
    columns (``timestamp``, ``*_ms``): each row into the part of its earliest time, a row spanning a cut left out
    and counted; every part gets the file (a header alone: labelled, nothing in that part). CSVs without a time
    column are copied whole into every part. Decision B388: a sensor file's read :meth:`_ChunkReader.head` began
    goes on here when the scan did not take it (a barometer: one read)."""
    path = r.path
    sensor = csv_stem(path) in SENSORS
    last = -math.inf
    with ExitStack() as stack:
        out = None
        for chunk, line in r.chunks():
            if out is None:
                out = _PartFiles(stack, parts, path.name, r.sep.join(chunk.columns))
                cols = r.time_columns(chunk.columns)
                if sensor:
                    cols = cols[:1]
                    if not cols:
                        raise DataError(f"{path}: no timestamp column (has {','.join(chunk.columns)}); fix the header "
                                        "(thesis ch.4.3.3)")
                elif not cols:
                    result.copied_whole.append(path.name)
                if not sensor:
                    for k in range(len(parts)):
                        out.get(k)
            if not cols:
                for k in range(len(parts)):
                    chunk.to_csv(out.get(k), header=False, index=False, sep=r.sep, lineterminator="\n")
                continue
            times = r.times(chunk, cols, line, required=sensor)
            if sensor:
                _check_sorted(path, times[:, 0], last, line)
                if len(times):
                    last = float(times[-1, 0])
            part, fits = _route(cut_times, times, None if sensor else spans)
            if not fits.all():
                result.dropped[path.name] = result.dropped.get(path.name, 0) + int((~fits).sum())
            for k in np.unique(part[fits]):
                rows = chunk[fits & (part == k)]
                rows.to_csv(out.get(int(k)), header=False, index=False, sep=r.sep, lineterminator="\n")
        if out is None:
            raise DataError(f"{path}: file is empty; re-export or remove it")


def _refuse(folder: Path, meta: dict) -> None:
    """Decision B380: what split cannot cut alike for every unit, in one line."""
    if meta.get("clocks") or any(float(meta.get(k) or 0.0) != 0.0 for k in ("clock_offset_s", "clock_drift_ppm")
                                 if isinstance(meta.get(k), int | float)):
        raise DataError(f"{folder}/meta.json: the units have clocks of their own (clocks, clock_offset_s or "
                        "clock_drift_ppm), so one cut time is not the same instant for every unit; split reads one "
                        "session clock -- write the session once on one clock first (read_session, apply_alignment, "
                        "write_session: docs/data.md#units-on-one-clock-before-split), then split (decisions B380, "
                        "B428)")


def check_max_minutes(max_minutes: float) -> float:
    """Decision B380: --max-minutes as a part length in seconds, or one line."""
    try:
        v = float(max_minutes)
    except (TypeError, ValueError):
        v = math.nan
    if not math.isfinite(v) or v <= 0:
        raise DataError(f"--max-minutes {max_minutes}: give a positive number of minutes, e.g. --max-minutes 60 "
                        "(decision B380)")
    if v * 60.0 < MIN_PART_S:
        raise DataError(f"--max-minutes {max_minutes}: parts of {v * 60.0:g} s are shorter than the {MIN_PART_S:g} s "
                        "a part needs (a 2 s standstill at each end, thesis ch.7.2, and walking between); give "
                        f"--max-minutes {MIN_PART_S / 60.0:g} or more (decision B380)")
    return v * 60.0


def split_session(session: str | os.PathLike, out: str | os.PathLike, *, max_minutes: float = 60.0,
                  chunk_rows: int = CHUNK_ROWS) -> SplitResult:
    """Decision B379: split the session folder ``session`` into ``out/part_000``, ``out/part_001`` ..., each a
    session of at most about ``max_minutes`` (plus the search span), cut at a standstill common to every unit.

    The files are read ``chunk_rows`` rows at a time, so the memory does not grow with the recording. The output is
    written atomically (a temporary sibling folder renamed into place). Returns the parts, the cuts and the label
    rows left out because they span a cut."""
    from pdrlearn.io.archive import is_archive

    folder = Path(session)
    part_s = check_max_minutes(max_minutes)
    if is_archive(folder):
        raise DataError(f"{folder}: split reads a session folder, not a zip archive (a whole day is not unpacked in "
                        "memory); unzip it first (`unzip -d DIR FILE`), then split DIR (decision B380)")
    if not folder.is_dir():
        raise DataError(f"{folder}: no such session folder; give a folder holding fAccelerometer.csv ... and "
                        "meta.json (decision B380)")
    meta_path = folder / "meta.json"
    meta = {}
    if meta_path.is_file():
        try:
            meta = read_json(meta_path)
        except ValueError as exc:
            raise DataError(f"{meta_path}: not valid JSON ({exc}); fix it (decision B380)") from None
        if not isinstance(meta, dict):
            raise DataError(f"{meta_path}: must hold a JSON object; fix it (decision B380)")
    _refuse(folder, meta)
    with ExitStack() as held:  # decision B388: each sensor file's head read goes on into the scan, else is ended
        readers = {name: _ChunkReader(p, 1.0, chunk_rows) for name in SENSORS
                   if (p := session_csv(folder, name)).is_file()}
        for r in readers.values():
            held.callback(r.close)
        scale, unit = session_time_scale(readers, meta, folder, meta_path)
        if unit is not None:  # decision B385: said once, and written into every part's meta.json (below)
            log.warning("%s: declares no timestamp unit: the timestamps are read as %s (decision B22), and each part's "
                        "meta.json declares \"units\": {\"timestamp\": \"%s\"}", meta_path, unit, unit)
        for r in readers.values():
            r.scale = scale
        result, parts = _split(folder, out, meta, readers, scale, unit, part_s, max_minutes, chunk_rows)
    result.parts = [Path(out) / p.name for p in parts]
    if result.dropped:
        log.warning("%s: %s label row(s) span a cut or lie in a gap of the sensor rows and are in no part (%s; "
                    "decisions B379, B386)", folder,
                    sum(result.dropped.values()), ", ".join(f"{n}: {k}" for n, k in result.dropped.items()))
    if result.copied_whole:
        log.warning("%s: %s have no time column and were copied whole into every part (decision B379)", folder,
                    ", ".join(result.copied_whole))
    return result


def _split(folder: Path, out, meta: dict, readers: dict[str, _ChunkReader], scale: float, unit: str | None,
           part_s: float, max_minutes: float, chunk_rows: int) -> tuple[SplitResult, list[Path]]:
    """:func:`split_session` once the time unit is read: the scan (each accelerometer and gyroscope file's head
    read going on, decision B388), then the parts written (a second read of every file)."""
    from pdrlearn.atomic import atomic_directory

    units = [(readers[acc], readers[gyr]) for acc, gyr in UNIT_IMU.values() if acc in readers and gyr in readers]
    if not units:
        raise DataError(f"{folder}: not a session split can cut: it needs a unit's accelerometer and gyroscope "
                        "(fAccelerometer.csv + fGyroscope.csv or wAccelerometer.csv + wGyroscope.csv) to find the "
                        "standstills (decision B380)")
    starts = [t for pair in units for r in pair if (t := first_time(r)) is not None]
    if not starts:
        raise DataError(f"{folder}: the accelerometer and gyroscope files hold no rows; nothing to split "
                        "(decision B380)")
    t0 = min(starts)
    span = min(SEARCH_S, part_s / 4.0)
    cuts, t_end, segments = scan_cuts(units, t0, part_s, span)
    for c in cuts:
        if not c.at_rest and not c.in_gap:
            log.warning("%s: no standstill of %g s common to the units within %g s of %.1f s: cut there, in "
                        "motion (its part's meta.json says so; decision B379)", folder, MIN_REST_S, span, c.boundary)
    cut_times = np.array([c.t for c in cuts])
    result = SplitResult([], cuts, t0, t_end, {}, [])
    edges = [t0, *cut_times.tolist(), t_end]
    # decision B386: a label row outside its part's accelerometer/gyroscope rows (in a data gap) is in no part
    spans = np.array(sensor_spans(segments, edges), dtype=float)
    files = [p for p in session_csvs(folder) if is_gzip(p) or p.suffix.lower() == ".csv"]
    with atomic_directory(out) as tmp:
        parts = [tmp / f"part_{k:03d}" for k in range(len(cuts) + 1)]
        for p in parts:
            p.mkdir()
        by_path = {r.path: r for r in readers.values()}
        for path in files:
            _write_file(by_path.get(path) or _ChunkReader(path, scale, chunk_rows), cut_times, parts, result, spans)
        kinds = ["session start", *("rest" if c.at_rest else "gap" if c.in_gap else "boundary, in motion"
                                    for c in cuts), "session end"]
        whole = {k: meta[k] for k in WHOLE_SESSION_KEYS if k in meta}
        for k, p in enumerate(parts):
            part_meta = {key: v for key, v in meta.items() if key not in WHOLE_SESSION_KEYS}
            # each part a session of its own name, so that track-all's pooled tables tell the parts apart
            if unit is not None:  # decision B385: a part is read in the unit the whole was read in
                part_meta["units"] = {**(meta.get("units") if isinstance(meta.get("units"), dict) else {}),
                                      "timestamp": unit}
            part_meta["session"] = f"{meta.get('session') or folder.name}_part_{k:03d}"
            part_meta["split"] = {"source": str(folder.resolve()), "part": k, "parts": len(parts),
                                  "start_s": round(edges[k], 6), "end_s": round(edges[k + 1], 6),
                                  "start_cut": kinds[k], "end_cut": kinds[k + 1], "whole_session": whole}
            (p / "meta.json").write_text(json.dumps(part_meta, indent=2) + "\n", encoding="utf-8")
        summary = {"source": str(folder.resolve()), "max_minutes": float(max_minutes), "search_s": span,
                   "min_rest_s": MIN_REST_S, "t_start_s": round(t0, 6), "t_end_s": round(t_end, 6),
                   "cuts": [{"t_s": round(c.t, 6), "boundary_s": round(c.boundary, 6), "at_rest": c.at_rest,
                             "in_gap": c.in_gap}
                            for c in cuts],
                   "label_rows_spanning_a_cut": result.dropped, "copied_whole": result.copied_whole}
        (tmp / "split.json").write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    return result, parts
