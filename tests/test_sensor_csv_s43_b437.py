"""Decision B437 (session 43, implementer I3; docs/decisions/bad-input.md): B9's line for a sensor file's non-numeric,
NaN or infinite row names the file's real line after a B66 ``sep=`` line or blank lines (B433's ``data_row_lines``),
as B425's line does; it had named ``row + 2`` (one header line, no blank line)."""

from __future__ import annotations

import re

import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from tests.test_sensor_csv_s42_b425_b426 import _session


@pytest.mark.parametrize("edit", ["none", "sep", "blank"])
@pytest.mark.parametrize("bad", ["nan", "abc"])
def test_b9_names_the_real_line_b437(tmp_path, edit, bad):
    d = _session(tmp_path)
    f = d / "fGyroscope.csv"
    lines = f.read_text().splitlines()
    lines[101] = lines[101].split(",")[0] + f",{bad},0,0"
    if edit == "blank":
        lines[50:50] = ["", "   "]
    if edit == "sep":
        lines.insert(0, "sep=,")
    f.write_text("\n".join(lines) + "\n")
    want = next(i for i, line in enumerate(f.read_text().splitlines(), 1) if f",{bad}," in line)
    with pytest.raises(DataError, match="non-numeric, NaN or infinite") as e:
        read_session(d)
    assert int(re.search(r"first at line (\d+)", str(e.value)).group(1)) == want, str(e.value)
