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
    for c in df.columns:
        if df[c].dtype.kind == "f":
            v = np.asarray(df[c], dtype=float)
            ok = np.isfinite(v)
            if ok.any() and np.abs(v[ok]).max() >= WIDE_FLOAT_MIN:
                wide[c] = [None if x != x else wide_float_text(x) for x in v.tolist()]  # None: to_csv's NaN
    (df.assign(**wide) if wide else df).to_csv(path, index=False, float_format=CSV_FLOAT_FORMAT)


def wide_float_text(x: float) -> str:
    """Decision E164 (amended, review R2): one value of a wide float column: NaN empty (as ``to_csv`` writes it),
    ``inf`` / ``-inf`` as ``to_csv`` writes them, a magnitude of :data:`WIDE_FLOAT_MIN` or more with
    :data:`WIDE_FLOAT_DECIMALS` fixed decimals (trailing zeros dropped), any other value at
    :data:`CSV_FLOAT_FORMAT` (a small non-zero value stays non-zero: ``1e-09``, not ``0`` / ``-0``). The lean
    runtime's ``_num`` writes the same."""
    if x != x:
        return ""
    if abs(x) >= WIDE_FLOAT_MIN and abs(x) != float("inf"):
        return f"{x:.{WIDE_FLOAT_DECIMALS}f}".rstrip("0").rstrip(".")
    return CSV_FLOAT_FORMAT % x
