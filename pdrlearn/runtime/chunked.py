"""Replaying a long recording through the runtime in bounded memory (decision E274 in docs/decisions/export.md).

:func:`pdrlearn.runtime.replay.read_streams` holds every sensor file of a session whole (trial T2, F3: the lean
command grew ~135 MB per recorded hour; a 16 h day at 100 Hz about 2.2 GB), while the Tracker itself stays ~100 MB.
:func:`open_session` reads each sensor file twice, :data:`BLOCK_ROWS` data rows at a time: a first pass checks it
(header, numbers, B431's range) and keeps only its timestamps, one file at a time, for the rate and the end the
Tracker is given (``nominal_period_s``, as before); :meth:`ChunkedSession.chunks` then merges the files by time into
E28's pushes (:func:`pdrlearn.runtime.replay.replay_chunks`' chunk index, sample by sample), so the pushes and every
output are the same as the whole-file replay's. A file the first pass finds anything unusual in (bad text, a value out
of range, timestamps not in order) makes :func:`open_session` return None: the caller reads the session whole, which
says what is wrong in its usual line (or replays it as before).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.clock import nominal_period_s
from pdrlearn.kernels.units import out_of_range
from pdrlearn.runtime.replay import CHUNK_TOLERANCE, SENSOR_KINDS, _columns, _parse, session_files
from pdrlearn.textfile import ENCODING, open_text

#: decision E274: data rows parsed at a time (8192 rows of 4 numbers: 0.26 MB of float64)
BLOCK_ROWS = 8192


class _Unusual(Exception):
    """A file the whole-file reader should judge (decision E274)."""


def _blocks(path: Path, name: str, scale: float, rows: int):
    """``(t_s, values)`` of ``path``'s data rows, ``rows`` at a time, parsed as the whole-file reader parses them
    (:func:`~pdrlearn.runtime.replay._parse`, blank lines skipped); :class:`_Unusual` on anything it would refuse."""
    try:
        with open_text(path, encoding=ENCODING) as f:
            names, order = _columns(path, name, f.readline().rstrip("\r\n"))
            buf: list[str] = []
            for line in f:
                if line.strip():
                    buf.append(line)
                if len(buf) >= rows:
                    yield _block(path, name, scale, buf, names, order)
                    buf = []
            if buf:
                yield _block(path, name, scale, buf, names, order)
    except (DataError, UnicodeDecodeError, OSError, EOFError, ValueError) as exc:
        raise _Unusual(str(exc)) from None


def _block(path, name, scale, buf, names, order):
    a = _parse(path, buf, names, order)
    if out_of_range(SENSOR_KINDS[name][0], a[:, 1:]).size:  # decision B431: the whole file's line says it
        raise _Unusual(f"{path}: a value out of range")
    return a[:, 0] * scale, a[:, 1:]


class ChunkedSession:
    """A session's sensor files, checked, with each stream's ``periods`` (s, ``nominal_period_s``) and ``ends`` (its
    last timestamp, s); :meth:`chunks` reads them again as E28's pushes."""

    def __init__(self, files: dict, scale: float, rows: int):
        self.files, self.scale, self.rows = files, scale, rows
        self.periods: dict[str, float] = {}
        self.ends: dict[str, float] = {}
        self.firsts: dict[str, float] = {}

    def scan(self) -> None:
        """The first pass: every file read block by block, its timestamps kept while it is read (one file at a
        time); :class:`_Unusual` when a file is empty, refused, or its timestamps go back."""
        for name, path in self.files.items():
            t = np.concatenate([b[0] for b in _blocks(path, name, self.scale, self.rows)] or [np.zeros(0)])
            if not len(t) or not bool(np.all(t[1:] >= t[:-1])):
                raise _Unusual(f"{path}: no rows, or timestamps not in order")
            self.periods[name], self.ends[name], self.firsts[name] = nominal_period_s(t), float(t[-1]), float(t[0])

    def chunks(self, chunk_s: float):
        """:func:`pdrlearn.runtime.replay.replay_chunks` of the whole streams, read block by block: the same chunk
        index per sample (``floor((t - t0) / chunk_s + CHUNK_TOLERANCE)`` from the earliest first sample), every
        chunk holding every stream."""
        t0 = min(self.firsts.values())
        index = lambda t: np.floor((t - t0) / chunk_s + CHUNK_TOLERANCE).astype(np.int64)  # noqa: E731 (as E28's)
        n_chunks = max(int(index(np.array([e]))[0]) for e in self.ends.values()) + 1
        its = {n: _blocks(p, n, self.scale, self.rows) for n, p in self.files.items()}
        held = {}
        for n, it in its.items():
            t, v = next(it)
            held[n] = (t, v, index(t))
        for k in range(n_chunks):
            push = {}
            for n, it in its.items():
                parts = []
                while True:
                    t, v, i = held[n]
                    cut = int(np.searchsorted(i, k + 1, side="left"))
                    parts.append((t[:cut], v[:cut]))
                    held[n] = (t[cut:], v[cut:], i[cut:])
                    if cut < len(t):
                        break
                    nxt = next(it, None)
                    if nxt is None:
                        break
                    held[n] = (nxt[0], nxt[1], index(nxt[0]))
                push[n] = parts[0] if len(parts) == 1 else (np.concatenate([p[0] for p in parts]),
                                                            np.concatenate([p[1] for p in parts]))
            yield push


def open_session(folder, bundle, *, rows: int = BLOCK_ROWS) -> tuple[ChunkedSession | None, dict]:
    """``(session, meta)``: the session ``folder``'s sensor files the bundle reads, checked block by block
    (:meth:`ChunkedSession.scan`), or ``(None, meta)`` when a file needs the whole-file reader's judgement
    (:func:`pdrlearn.runtime.replay.read_streams`: its line, or its replay). The folder's own refusals (no folder,
    a bad ``meta.json``) are raised here, as the whole-file reader raises them."""
    folder = Path(folder)
    meta, scale, files = session_files(folder, bundle)
    try:
        session = ChunkedSession(dict(files()), scale, rows)  # a unit refused: said in the whole reader's order
        session.scan()
    except (_Unusual, DataError):
        return None, meta
    return session, meta
