"""Decision B154: a sensor file whose timestamp column holds date-times (ISO 8601) is refused in one line that says so
and how to convert, instead of "N row(s) with non-numeric values"; other bad text keeps that message."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.plasys import read_stream


def _write(path, times):
    pd.DataFrame({"timestamp": times, "x": 0.1, "y": 9.8, "z": 0.2}).to_csv(path, index=False)


def test_iso_timestamps_are_named_as_date_times(tmp_path):
    f = tmp_path / "fAccelerometer.csv"
    _write(f, ["2026-03-29T00:59:50+01:00", "2026-03-29T00:59:50.050000+01:00", "2026-03-29T00:59:50.100000+01:00"])
    with pytest.raises(DataError) as e:
        read_stream(f)
    assert str(e.value) == (
        f"{f}: column timestamp holds date-times ('2026-03-29T00:59:50+01:00' at line 2), not numbers; write the "
        "times as numbers in ms (since the epoch or the recording's start, the same clock as the session's other "
        "files and steps.csv), or turn a one-CSV export into a session with `pdrlearn import FILE --out DIR`, which "
        "reads date-time columns (decision B154)")


def test_other_bad_text_keeps_the_row_message(tmp_path):
    f = tmp_path / "fAccelerometer.csv"
    _write(f, ["0", "oops", "100"])
    with pytest.raises(DataError, match=r"1 row\(s\) with non-numeric, NaN or infinite values \(first at line 3\)"):
        read_stream(f)
