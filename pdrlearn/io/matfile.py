"""MATLAB ``.mat`` files -> the table ``pdrlearn import`` maps (decision B335, reader E172).

A MAT file begins with a 116-byte text header, ``MATLAB 5.0 MAT-file`` (``save`` with ``-v6``/``-v7``, the
default up to R2006b and what ``scipy.io.savemat`` writes) or ``MATLAB 7.3 MAT-file`` (``-v7.3``: an HDF5 file
behind that header, which needs h5py, not a dependency of pdrlearn). :func:`mat_version` tells them by that
header; :func:`read_mat_table` reads a v5 file with ``scipy.io.loadmat`` and lays its per-sample arrays out as the
columns of a CSV export, so the import's own column mapping (``--acc/--gyro/--time/--rate`` and the guesses)
reads them: an N x 3 array ``acc`` becomes ``acc_x, acc_y, acc_z``, an N-vector ``time`` a column ``time``.
Fields of structs are named by their path below the file's one struct (``data.acc`` -> ``acc``; a file with
several variables keeps the variable's name: ``S.acc`` -> ``S.acc``); a scalar named like a sampling rate
(``fs``, ``Fs``, ``rate``, ``SamplingFrequency`` ...) is offered as the rate of a file without a time vector.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError

#: the text a MAT file's header starts with (MATLAB's MAT-file format, "Level 5 MAT-File Format")
MAT_MAGIC = b"MATLAB "
#: the HDF5 signature, at offset 512 of a v7.3 MAT file (HDF5 user block after MATLAB's text header)
HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"
#: decision B335: the one line for a v7.3 file (HDF5; h5py is not a dependency)
V73_FIX = "save it with -v7 (save(FILE, 'data', '-v7')) or export a CSV (writetable), then import that"
#: axis suffixes of an N x 3 array's columns
AXES = ("x", "y", "z")
#: lower-case names of a scalar field that gives the sampling rate in Hz
RATE_NAMES = ("fs", "rate", "samplingrate", "samplingfrequency", "sampling_rate", "sampling_frequency", "freq",
              "frequency", "hz", "srate")


def mat_version(path: str | os.PathLike) -> str | None:
    """``"5"`` or ``"7.3"`` for a MAT file (by its header text, and the HDF5 signature of a v7.3 file), else None."""
    try:
        with open(path, "rb") as f:
            head = f.read(520)
    except OSError:
        return None
    if not head.startswith(MAT_MAGIC) or b"MAT-file" not in head[:116]:
        return None
    if head[7:10] == b"7.3" or head[512:520] == HDF5_MAGIC:
        return "7.3"
    return "5"


def mat_message(path: str | os.PathLike, version: str) -> str:
    """Decision B335: the one line for a MAT file read as text (a CSV reader or a session file)."""
    if version == "7.3":
        return f"{path}: a v7.3 MAT file (HDF5), which pdrlearn does not read: {V73_FIX} (decision B335)"
    return (f"{path}: a MATLAB MAT file, not CSV text: import it with `pdrlearn import {Path(path).name} --out "
            "SESSION` (decision B335)")


def _flatten(value, name: str, out: dict[str, object]) -> None:
    """The numeric arrays and scalars below ``value`` (dicts of ``loadmat(simplify_cells=True)``), by path."""
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(v, f"{name}.{k}" if name else str(k), out)
        return
    if isinstance(value, bool | int | float) and not isinstance(value, bool):
        out[name] = float(value)
        return
    if isinstance(value, np.ndarray) and value.dtype.kind in "iuf" and value.size:
        out[name] = value


def _rows(a: np.ndarray) -> np.ndarray | None:
    """An array as N rows of 1 or 3 columns (a MATLAB row vector 1 x N or 3 x N transposed), else None."""
    a = np.asarray(a, dtype=float)
    if a.ndim == 1:
        return a[:, None]
    if a.ndim != 2:
        return None
    if a.shape[1] in (1, 3) and a.shape[0] > 3:
        return a
    if a.shape[0] in (1, 3) and a.shape[1] > 3:
        return a.T
    return None


def mat_variables(path: str | os.PathLike) -> dict[str, object]:
    """Path -> numeric array or scalar of a v5 MAT file (struct fields by their path below a lone struct)."""
    import scipy.io

    try:
        d = scipy.io.loadmat(path, simplify_cells=True)
    except Exception as exc:  # scipy raises ValueError/TypeError/OSError variants on a broken file
        raise DataError(f"{path}: cannot read the MAT file ({type(exc).__name__}: {str(exc)[:80]}); save it again "
                        "with -v7, or export a CSV (writetable) (decision B335)") from None
    top = {k: v for k, v in d.items() if not k.startswith("__")}
    out: dict[str, object] = {}
    if len(top) == 1 and isinstance(next(iter(top.values())), dict):  # one struct (data.acc ...): its fields
        _flatten(next(iter(top.values())), "", out)
    else:
        _flatten(top, "", out)
    return out


def read_mat_table(path: str | os.PathLike, wanted: list[str] = ()) -> tuple[pd.DataFrame, dict]:
    """Decision B335: a v5 MAT file's per-sample arrays as a table (N x 3 ``acc`` -> ``acc_x, acc_y, acc_z``;
    an N-vector ``time`` -> ``time``) and a record: ``variables`` (path -> shape text), ``rate`` (name, Hz) of a
    rate-like scalar, ``left_out`` (arrays of another length). N is the length of the ``wanted`` variables (the
    names the mapping options give, a 3-column name as its variable), else the longest arrays'."""
    v = mat_variables(path)
    arrays = {k: r for k, a in v.items() if isinstance(a, np.ndarray) and (r := _rows(a)) is not None}
    if not arrays:
        shown = ", ".join(f"{k} {np.shape(a)}" for k, a in list(v.items())[:8]) or "no numeric variables"
        raise DataError(f"{path}: no per-sample arrays (N x 3 or N values) in the MAT file ({shown}); save the "
                        "accelerometer and gyroscope as N x 3 arrays (decision B335)")
    lengths = [len(arrays[w]) for w in wanted if w in arrays]
    n = lengths[0] if lengths else max(len(a) for a in arrays.values())
    table, left = {}, []
    for k, a in arrays.items():
        if len(a) != n:
            left.append(f"{k} ({len(a)} rows)")
            continue
        if a.shape[1] == 1:
            table[k] = a[:, 0]
        else:
            table.update({f"{k}_{ax}": a[:, j] for j, ax in enumerate(AXES)})
    rates = [(k, float(s)) for k, s in v.items() if not isinstance(s, np.ndarray)
             and re.sub(r"[^a-z_]", "", k.rsplit(".", 1)[-1].lower()) in RATE_NAMES]
    record = {"format": "MAT v5", "variables": {k: "x".join(map(str, np.shape(a))) for k, a in v.items()
                                                if isinstance(a, np.ndarray)}}
    if len(rates) == 1 and np.isfinite(rates[0][1]) and rates[0][1] > 0:
        record["rate"] = {"name": rates[0][0], "hz": rates[0][1]}
    if left:
        record["left_out"] = left
    return pd.DataFrame(table), record


def mat_arrays_text(record: dict, most: int = 6) -> str:
    """Decision B335: the N x 3 arrays of a :func:`read_mat_table` record, ``NAME (N x 3)``, at most ``most``."""
    three = [f"{k} ({v})" for k, v in record.get("variables", {}).items() if re.fullmatch(r"\d+x3|3x\d+", v)]
    more = f" and {len(three) - most} more" if len(three) > most else ""
    return ", ".join(three[:most]) + more if three else "none"


def expand_columns(cols: list[str], header: list[str]) -> list[str]:
    """A mapping option's one name of an N x 3 MAT variable (``--acc acc``) as its three columns."""
    if len(cols) == 1 and cols[0].lstrip("-") not in header:
        neg = "-" if cols[0].startswith("-") else ""
        name = cols[0].lstrip("-")
        three = [f"{name}_{ax}" for ax in AXES]
        if all(c in header for c in three):
            return [neg + c for c in three]
    return cols
