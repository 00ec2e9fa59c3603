"""Decision E178 (session 35, trial T1 finding 5): copies of the CSV outputs that a decimal-comma Excel opens as they
are (``python -m pdrlearn.excel SRC DST``): ';', decimal commas in numbers only, UTF-8 with a BOM."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.common import write_table_csv
from pdrlearn.errors import DataError
from pdrlearn.excel import excel_copy, main
from pdrlearn.io.plasys import read_table


def _results(tmp_path):
    res = tmp_path / "Ergebnisse Müller"
    (res / "Gruppe Ältere").mkdir(parents=True)
    df = pd.DataFrame({"session": ["Gang 1", "Gang 2"], "subject": ["001", "Weiß; K."],
                       "speed_m_s": [1.0285355258315103, np.nan], "n_steps": [21, 9], "tiny": [2.5e-05, -0.5],
                       "start_time": ["2026-12-05T14:03:11.250+01:00", ""], "t_epoch": [1796475791.25, 1.0]})
    write_table_csv(df, res / "Gruppe Ältere" / "sessions.csv")
    return res, df


def test_copies_read_as_the_originals_with_semicolons_decimal_commas_and_a_bom(tmp_path):
    res, df = _results(tmp_path)
    written = excel_copy(res, tmp_path / "excel")
    assert written == [tmp_path / "excel" / "Gruppe Ältere" / "sessions.csv"]
    raw = written[0].read_bytes()
    assert raw.startswith(b"\xef\xbb\xbf") and b"\r\n" in raw
    text = raw.decode("utf-8-sig").splitlines()
    assert text[0] == "session;subject;speed_m_s;n_steps;tiny;start_time;t_epoch"
    assert text[1] == "Gang 1;001;1,028535526;21;0,000025;2026-12-05T14:03:11.250+01:00;1796475791,25"  # C103: plain
    assert text[2] == 'Gang 2;"Weiß; K.";;9;-0,5;;1'  # text cells as written, the ';' inside one quoted
    back = read_table(written[0], text_columns=("subject",))  # pdrlearn reads its own copy back (B24)
    orig = read_table(res / "Gruppe Ältere" / "sessions.csv", text_columns=("subject",))
    pd.testing.assert_frame_equal(back, orig)


def test_bad_folders_are_one_line(tmp_path, capsys):
    res, _ = _results(tmp_path)
    with pytest.raises(DataError, match="is the folder of the originals"):
        excel_copy(res, res)
    assert main([str(tmp_path / "nope"), str(tmp_path / "x")]) == 2
    assert capsys.readouterr().err.strip().endswith("no such folder or file; give a folder pdrlearn wrote (track "
                                                    "--out, track-all --out)")
    assert main([str(res), str(tmp_path / "x")]) == 0
    assert "1 CSV file(s) copied for Excel" in capsys.readouterr().out


def test_an_empty_results_folder_is_one_line_and_writes_nothing(tmp_path, capsys):
    """E178 (lead's closing check): a results folder with no CSV is refused in one line, no copy folder left."""
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main([str(empty), str(tmp_path / "x")]) == 2
    assert capsys.readouterr().err.strip().endswith("holds no .csv file to copy")
    assert not (tmp_path / "x").exists()
