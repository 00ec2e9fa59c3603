"""Decisions B335-B337, E172 (session 35, trial T2 findings 4 and 5): MATLAB's files at ``pdrlearn import``.

A v5 MAT file is read (its N x 3 arrays as ``NAME_x, NAME_y, NAME_z``), a v7.3 one refused in one line, a folder
holding only a MAT file names the import; a headerless CSV (``writematrix``) is refused without ``--no-header``
instead of losing its first row, and read with it; a timetable's ``0.01 sec`` row times are read."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
import scipy.io

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.importer import duration_text, import_csv
from pdrlearn.io.plasys import read_table
from tests.sim_helpers import quiet_walk

G = 9.80665


@pytest.fixture(scope="module")
def walk():
    return quiet_walk("straight:12", 8420, seed=3)


def _lab(walk):
    """(t s, acc g, gyr deg/s) as the trial's lab packs them (data.acc in g, data.gyr in deg/s)."""
    a, g = walk["fAccelerometer"], walk["fGyroscope"]
    return a.t - a.t[0], a.values / G, np.degrees(g.values)


def _err(capsys) -> str:
    return capsys.readouterr().err


def test_v5_mat_file_is_imported_like_its_csv(tmp_path, walk, capsys):
    t, acc, gyr = _lab(walk)
    scipy.io.savemat(tmp_path / "trial.mat", {"data": {"acc": acc, "gyr": gyr, "fs": 100.0, "time": t[:, None]}})
    pd.DataFrame({"time": t, **{f"acc_{c}": acc[:, k] for k, c in enumerate("xyz")},
                  **{f"gyr_{c}": gyr[:, k] for k, c in enumerate("xyz")}}).to_csv(tmp_path / "trial.csv", index=False,
                                                                                    float_format="%.10g")
    units = ["--acc-unit", "g", "--gyro-unit", "deg/s"]
    assert main(["import", str(tmp_path / "trial.mat"), "--out", str(tmp_path / "m"), *units]) == 0
    assert main(["import", str(tmp_path / "trial.csv"), "--out", str(tmp_path / "c"), *units]) == 0
    m, c = read_session(tmp_path / "m"), read_session(tmp_path / "c")
    for name in ("fAccelerometer", "fGyroscope"):
        assert len(m[name]) == len(walk[name])
        np.testing.assert_allclose(m[name].values, c[name].values, atol=1e-6)
        np.testing.assert_allclose(m[name].t, c[name].t, atol=1e-6)
    rec = json.loads((tmp_path / "m" / "meta.json").read_text())["imported"]
    assert rec["mat"]["format"] == "MAT v5" and rec["streams"]["fAccelerometer"]["columns"] == ["acc_x", "acc_y",
                                                                                                 "acc_z"]


def test_mat_without_time_is_timed_by_fs_and_variables_name_three_columns(tmp_path, walk, capsys):
    _, acc, gyr = _lab(walk)
    scipy.io.savemat(tmp_path / "s.mat", {"S": {"A": acc, "W": gyr.T, "Fs": 50.0}})  # a 3 x N gyroscope too
    assert main(["import", str(tmp_path / "s.mat"), "--out", str(tmp_path / "o"), "--acc", "A", "--gyro", "W",
                 "--acc-unit", "g", "--gyro-unit", "deg/s"]) == 0
    assert "the MAT file's Fs" in _err(capsys)
    s = read_session(tmp_path / "o")
    assert s["fAccelerometer"].rate_hz == pytest.approx(50.0)
    np.testing.assert_allclose(s["fGyroscope"].values, np.radians(gyr), atol=1e-9)


def test_mat_struct_paths_are_not_taken_for_a_time(tmp_path, walk, capsys):
    """A Mobilise-D-standard data.mat: TimeMeasure1.Test5.Trial1.SU.LowerBack.{Acc,Gyr,Fs}; the field path
    starting with 'Time' is no time column, the nested Fs times the rows."""
    _, acc, gyr = _lab(walk)
    lb = {"Acc": acc, "Gyr": gyr, "Fs": 100.0}
    trial = {"Trial1": {"SU": {"LowerBack": lb}}}
    scipy.io.savemat(tmp_path / "data.mat", {"data": {"TimeMeasure1": {"Test5": trial}}})
    p = "TimeMeasure1.Test5.Trial1.SU.LowerBack"
    assert main(["import", str(tmp_path / "data.mat"), "--out", str(tmp_path / "o"), "--acc", f"{p}.Acc",
                 "--gyro", f"{p}.Gyr", "--acc-unit", "g", "--gyro-unit", "deg/s"]) == 0
    assert read_session(tmp_path / "o")["fAccelerometer"].rate_hz == pytest.approx(100.0)


def test_v73_mat_file_is_refused_in_one_line(tmp_path, capsys):
    f = tmp_path / "trial.mat"
    f.write_bytes(b"MATLAB 7.3 MAT-file, Platform: GLNXA64".ljust(512, b" ") + b"\x89HDF\r\n\x1a\n" + bytes(64))
    assert main(["import", str(f), "--out", str(tmp_path / "o")]) == 2
    err = _err(capsys)
    assert "v7.3 MAT file" in err and "-v7" in err and "writetable" in err and "UTF-8" not in err
    assert len(err.strip().splitlines()) == 1 and not (tmp_path / "o").exists()


def test_mat_read_as_text_says_what_it_is(tmp_path, walk):
    _, acc, gyr = _lab(walk)
    scipy.io.savemat(tmp_path / "steps.mat", {"acc": acc})
    with pytest.raises(DataError, match="MATLAB MAT file, not CSV text: import it with `pdrlearn import"):
        read_table(tmp_path / "steps.mat")


def test_folder_with_only_a_mat_file_names_the_import(tmp_path, walk):
    _, acc, gyr = _lab(walk)
    scipy.io.savemat(tmp_path / "trial.mat", {"data": {"acc": acc, "gyr": gyr, "fs": 100.0}})
    with pytest.raises(DataError, match=r"no sensor files found.*pdrlearn import .*trial\.mat --out SESSION"):
        read_session(tmp_path)


def _headerless(tmp_path, walk):
    t, acc, gyr = _lab(walk)
    path = tmp_path / "matrix.csv"
    np.savetxt(path, np.column_stack([t, acc, gyr]), delimiter=",", fmt="%.6f")  # MATLAB writematrix([t acc gyr])
    return path, len(t)


def test_headerless_csv_is_refused_naming_no_header(tmp_path, walk, capsys):
    path, n = _headerless(tmp_path, walk)
    first = path.read_text().splitlines()[0].split(",")
    # the trial's workaround, the first row's numbers as names, silently lost that row
    assert main(["import", str(path), "--out", str(tmp_path / "o"), "--time", first[0], "--acc",
                 ",".join(first[1:4]), "--gyro", ",".join(first[4:7])]) == 2
    err = _err(capsys)
    assert "the first line is all numbers" in err and "--no-header" in err and not (tmp_path / "o").exists()


def test_no_header_reads_every_row_in_the_default_and_given_order(tmp_path, walk, capsys):
    path, n = _headerless(tmp_path, walk)
    units = ["--acc-unit", "g", "--gyro-unit", "deg/s"]
    assert main(["import", str(path), "--no-header", "--out", str(tmp_path / "d"), *units]) == 0
    assert "default order (--no-header, B336)" in _err(capsys)
    assert main(["import", str(path), "--no-header", "--time", "0", "--acc", "1,2,3", "--gyro", "4,5,6",
                 "--out", str(tmp_path / "g"), *units]) == 0
    d, g = read_session(tmp_path / "d"), read_session(tmp_path / "g")
    assert len(d["fAccelerometer"]) == len(g["fAccelerometer"]) == n
    np.testing.assert_allclose(d["fGyroscope"].values, np.radians(_lab(walk)[2]), atol=1e-5)


def test_timetable_duration_text_is_read(tmp_path, walk, capsys):
    t, acc, gyr = _lab(walk)
    df = pd.DataFrame({"Time": [f"{v:g} sec" for v in np.round(t, 4)], **{f"acc_{k + 1}": acc[:, k] for k in range(3)},
                       **{f"gyr_{k + 1}": gyr[:, k] for k in range(3)}})
    df.to_csv(tmp_path / "tt.csv", index=False)
    opts = ["--acc", "acc_1,acc_2,acc_3", "--gyro", "gyr_1,gyr_2,gyr_3", "--acc-unit", "g", "--gyro-unit", "deg/s"]
    assert main(["import", str(tmp_path / "tt.csv"), "--out", str(tmp_path / "o"), *opts]) == 0
    s = read_session(tmp_path / "o")
    np.testing.assert_allclose(s["fAccelerometer"].t, np.round(t, 4), atol=1e-9)
    capsys.readouterr()
    assert main(["import", str(tmp_path / "tt.csv"), "--out", str(tmp_path / "p"), *opts, "--time-unit", "ms"]) == 2
    assert "leave --time-unit out" in _err(capsys)


def test_duration_text_units():
    v, u = duration_text(pd.Series(["0 min", "0.5 min", "1 min"]))
    assert u == "s" and list(v) == [0.0, 30.0, 60.0]
    assert duration_text(pd.Series(["10 ms", "20 ms"]))[1] == "ms"
    assert duration_text(pd.Series(["1 sec", "2 ms"])) is None  # two units: not one clock
    assert duration_text(pd.Series(["1 sec", "oops"])) is None


def test_no_header_on_a_mat_file_is_refused(tmp_path, walk):
    _, acc, gyr = _lab(walk)
    scipy.io.savemat(tmp_path / "t.mat", {"acc": acc, "gyr": gyr, "fs": 100.0})
    with pytest.raises(DataError, match="--no-header is for a CSV"):
        import_csv(tmp_path / "t.mat", no_header=True)


def test_unmapped_mat_file_names_its_arrays(tmp_path, walk, capsys):
    """Two trials of different lengths and names no guess reads: the error lists the N x 3 arrays to name."""
    _, acc, gyr = _lab(walk)
    trials = {"Trial1": {"Acc": acc, "Gyr": gyr}, "Trial2": {"Acc": acc[:500], "Gyr": gyr[:500]}}
    scipy.io.savemat(tmp_path / "data.mat", {"data": {"Test5": trials}})
    assert main(["import", str(tmp_path / "data.mat"), "--out", str(tmp_path / "o")]) == 2
    err = _err(capsys)
    assert "Test5.Trial1.Acc" in err and "Test5.Trial2.Gyr (500x3)" in err and "--acc NAME --gyro NAME" in err


def test_no_header_on_a_file_with_a_header_is_refused(tmp_path, walk, capsys):
    path, _ = _headerless(tmp_path, walk)
    named = tmp_path / "named.csv"
    named.write_text("time,acc_x,acc_y,acc_z,gyr_x,gyr_y,gyr_z\n" + path.read_text())
    assert main(["import", str(named), "--no-header", "--out", str(tmp_path / "o")]) == 2
    err = _err(capsys)
    assert "the first line is text (time, acc_x, acc_y, acc_z ...): a header line; leave --no-header out" in err
