"""Decision E169 (session 35): how track and run write their CSV tables (decisions E157, E164), a library module so
that :func:`pdrlearn.write_track` writes them without importing the CLI; ``pdrlearn.cli.common`` imports it."""

from __future__ import annotations

#: decision E157: the significant digits of the floats in track's and run's CSV files
CSV_FLOAT_FORMAT = "%.10g"
#: decision E164: a float column reaching this magnitude (an epoch time in seconds) is written with fixed decimals
WIDE_FLOAT_MIN = 1e6
#: decision E164: its decimals (microseconds of a time in seconds)
WIDE_FLOAT_DECIMALS = 6


def write_table_csv(df, path) -> None:
    """Decision E164: ``df`` as track / run write their tables: floats at :data:`CSV_FLOAT_FORMAT`'s 10 significant
    digits, except a float column whose largest finite magnitude reaches :data:`WIDE_FLOAT_MIN`, written with
    :data:`WIDE_FLOAT_DECIMALS` fixed decimals (trailing zeros dropped): 10 digits of an epoch time in seconds
    (1733400005.151) are whole seconds; in such a column each value is :func:`wide_float_text`'s (E164 amended:
    ``inf`` stays ``inf``, values under the bound keep their 10 digits). Columns below the bound are written as
    before, byte for byte."""
    import numpy as np

    wide = {}
    for c in _float_columns(df):
        v = np.asarray(df[c], dtype=float)
        ok = np.isfinite(v)
        if ok.any() and np.abs(v[ok]).max() >= WIDE_FLOAT_MIN:
            wide[c] = [None if x != x else wide_float_text(x) for x in v.tolist()]  # None: to_csv's NaN
    rest = df.drop(columns=list(wide)) if wide else df  # E308: no copy of the table when no column is wide
    wide.update(positional_columns(rest, digits=10))  # decision C103: no 1e-05
    (df.assign(**wide) if wide else df).to_csv(path, index=False, float_format=CSV_FLOAT_FORMAT)


#: decision C103: below this magnitude ``%g`` (and Python's repr) write a float in scientific notation
EXPONENT_BELOW = 1e-4


def float_text(x: float, digits: int | None = 10) -> str:
    """Decision C103: one float as every CSV table of pdrlearn writes it - ``digits`` significant digits (``%.10g``,
    E157; ``None``: Python's shortest round-trip repr, the full precision of track-all's sessions.csv), always in
    plain decimals: ``-0.00008067625715``, not ``-8.067625715e-05`` (R's readr and a spreadsheet read both, a
    reader's eye only one); the same value, and byte for byte the same text for every value %g writes without an
    exponent. NaN empty, ``inf`` / ``-inf`` as ``to_csv`` writes them."""
    from decimal import Decimal

    if x != x:
        return ""
    text = repr(float(x)) if digits is None else f"{x:.{digits}g}"
    return format(Decimal(text), "f") if "e" in text and abs(x) != float("inf") else text


def positional_columns(df, digits: int | None = 10) -> dict:
    """Decision C103: the float columns of ``df`` that ``%g`` / repr would write with an exponent somewhere (a finite
    non-zero value under :data:`EXPONENT_BELOW`, or of 1e15 or more), each as :func:`float_text` cells (None for NaN:
    ``to_csv``'s empty cell); ``df.assign(**...)`` writes them in plain decimals, the other columns unchanged."""
    import numpy as np

    out = {}
    for c in _float_columns(df):
        col = df[c]
        v = np.abs(np.asarray(col, dtype=float))
        ok = np.isfinite(v) & (v > 0)
        if ok.any() and ((v[ok] < EXPONENT_BELOW).any() or (v[ok] >= 1e15).any()):
            out[c] = [None if x != x else float_text(x, digits) for x in col.tolist()]
    return out


def _float_columns(df) -> list:
    """The names of ``df``'s float columns, in order, read from ``df.dtypes`` (E308: a pandas column taken out only
    when it is a float one; each take copies the table's ``attrs``)."""
    return [c for c, t in zip(df.columns, df.dtypes, strict=True) if t.kind == "f"]


def wide_float_text(x: float) -> str:
    """Decision E164 (amended, review R2): one value of a wide float column: NaN empty (as ``to_csv`` writes it),
    ``inf`` / ``-inf`` as ``to_csv`` writes them, a magnitude of :data:`WIDE_FLOAT_MIN` or more with
    :data:`WIDE_FLOAT_DECIMALS` fixed decimals (trailing zeros dropped), any other value at
    :data:`CSV_FLOAT_FORMAT` (a small non-zero value stays non-zero: ``0.000000001``, not ``0`` / ``-0``; C103: not
    ``1e-09``). The lean runtime's ``_num`` writes the same."""
    if x != x:
        return ""
    if abs(x) >= WIDE_FLOAT_MIN and abs(x) != float("inf"):
        return f"{x:.{WIDE_FLOAT_DECIMALS}f}".rstrip("0").rstrip(".")
    return float_text(x)  # decision C103: a small value in plain decimals


def table_text(df) -> dict:
    """Cohort C116: ``df`` as :func:`write_table_csv` writes it (``csv``, header included) with its column dtypes
    (``dtypes``), a JSON-able record that :func:`table_from_text` reads back; the file written from the read-back
    table is the file written from ``df``, byte for byte (floats at their 10 written digits read and written again)."""
    import io

    buf = io.StringIO()
    write_table_csv(df, buf)
    return {"csv": buf.getvalue(), "dtypes": {str(c): str(t) for c, t in df.dtypes.items()}}


def table_from_text(record: dict):
    """Cohort C116: the table of a :func:`table_text` record: numeric and boolean columns with their dtypes, every
    other column as the strings written (``001`` stays ``001``), empty cells missing."""
    import io

    import pandas as pd

    kept = {c: (t if t[:1] in ("f", "i", "u", "b", "I", "U", "F") else object) for c, t in record["dtypes"].items()}
    if not kept:
        return pd.DataFrame()
    return pd.read_csv(io.StringIO(record["csv"]), dtype=kept, keep_default_na=False,
                       na_values={c: [""] for c in kept})
