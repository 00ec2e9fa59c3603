"""Decision B433 and review R2 finding 4 (docs/decisions/bad-input.md, session 42): ``check_units=False`` reads a
whole file in another unit (deg/s) as written while a corrupt sample in an SI file is still B425's line; B425's line
is the file's real line after a B66 ``sep=`` line or blank lines, in the full and the lean reader alike."""

from __future__ import annotations

import re

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.kernels.units import data_row_lines
from pdrlearn.runtime.replay import _read_csv
from tests.test_sensor_csv_s42_b425_b426 import _session, _set


def _line_named(exc) -> int:
    return int(re.search(r"first at line (\d+)", str(exc)).group(1))


def _bad_line(path) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if "1e+308" in line)


def test_check_units_false_reads_a_file_in_deg_s_but_not_a_corrupt_sample_b433(tmp_path):
    d = _session(tmp_path, gyr=np.degrees)
    with pytest.raises(DataError, match="looks like deg/s"):
        read_session(d)
    g = read_session(d, check_units=False).streams["fGyroscope"].values
    assert np.abs(g).max() > 100.0  # read as written, for the caller to convert
    d2 = _session(tmp_path, gyr=_set(100, 1e308), name="s2")
    with pytest.raises(DataError, match="corrupt sample"):
        read_session(d2, check_units=False)


@pytest.mark.parametrize("edit", ["sep", "blank", "both"])
def test_b425_names_the_real_line_in_both_readers_finding4(tmp_path, edit):
    d = _session(tmp_path, gyr=_set(100, 1e308))
    f = d / "fGyroscope.csv"
    lines = f.read_text().splitlines()
    if edit in ("blank", "both"):
        lines[50:50] = ["", "   "]
    if edit in ("sep", "both"):
        lines.insert(0, "sep=,")
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError, match="B425") as full:
        read_session(d)
    assert _line_named(full.value) == _bad_line(f)
    if edit != "blank":
        return  # the lean reader takes no sep= line
    with pytest.raises(DataError, match="B431|B425") as lean:
        _read_csv(f, "fGyroscope", 1e-3)
    assert _line_named(lean.value) == _bad_line(f)


def test_data_row_lines_skips_the_header_and_blank_lines():
    assert data_row_lines(["t,x", "1,2", "", "3,4"]) == [2, 4]
    assert data_row_lines(["sep=,", "t,x", " ", "1,2"], header_lines=2) == [4]
