"""Decision B369 (session 36, trial T2 finding 6): a session folder's files compressed with gzip
(``fAccelerometer.csv.gz``, ``steps.csv.gz`` ...) are read in place by the full reader, the lean runtime, ``info``
and ``track-all``'s search for sessions, exactly as the plain CSVs; a folder holding both ``X.csv`` and
``X.csv.gz`` is one line naming both."""

from __future__ import annotations

import gzip
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def plain(tmp_path_factory):
    sim = tmp_path_factory.mktemp("b369") / "plain"
    assert main(["simulate", "--route", "straight:15,turn:90,straight:10", "-u", "8900", "-o", str(sim)]) == 0
    return sim


def _gzipped(plain: Path, out: Path, keep_plain: tuple[str, ...] = ()) -> Path:
    shutil.copytree(plain, out)
    for p in sorted(out.glob("*.csv")):
        (out / f"{p.name}.gz").write_bytes(gzip.compress(p.read_bytes()))
        if p.stem not in keep_plain:
            p.unlink()
    return out


def test_gzip_session_reads_as_the_plain_one_b369(plain, tmp_path):
    from pdrlearn.io import read_session
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.replay import read_streams

    gz = _gzipped(plain, tmp_path / "gz")
    assert not list(gz.glob("*.csv")) and (gz / "fAccelerometer.csv.gz").is_file()
    a, b = read_session(plain), read_session(gz)
    assert set(a.streams) == set(b.streams) and len(a.streams) >= 4
    for n in a.streams:
        np.testing.assert_array_equal(a.streams[n].t, b.streams[n].t)
        np.testing.assert_array_equal(a.streams[n].values, b.streams[n].values)
    pd.testing.assert_frame_equal(a.steps, b.steps)
    pd.testing.assert_frame_equal(a.trajectory, b.trajectory)
    bundle = load_bundle(SHIPPED)
    la, lb = read_streams(plain, bundle)[0], read_streams(gz, bundle)[0]
    assert set(la) == set(lb)
    for n in la:
        np.testing.assert_array_equal(la[n][0], lb[n][0])
        np.testing.assert_array_equal(la[n][1], lb[n][1])


def test_info_and_track_read_a_gzip_session_b369(plain, tmp_path, capsys):
    gz = _gzipped(plain, tmp_path / "gz")
    capsys.readouterr()
    assert main(["info", str(gz), "--json"]) == 0
    files = {n: d["file"] for n, d in json.loads(capsys.readouterr().out)["sensors"].items()}
    assert files["fAccelerometer"] == "fAccelerometer.csv.gz" and files["wGyroscope"] == "wGyroscope.csv.gz"
    assert main(["info", str(gz)]) == 0
    assert "gzip-compressed, read in place: fAccelerometer.csv.gz" in capsys.readouterr().out
    assert main(["track", "--no-plot", str(plain), "--out", str(tmp_path / "ta")]) == 0
    assert main(["track", "--no-plot", str(gz), "--out", str(tmp_path / "tb")]) == 0
    ta, tb = (pd.read_csv(tmp_path / t / "steps.csv") for t in ("ta", "tb"))
    pd.testing.assert_frame_equal(ta, tb)
    from pdrlearn.cohort import is_session_dir

    assert is_session_dir(gz)  # track-all / train-all find it


def test_plain_and_gzip_copy_of_one_file_is_one_line_b369(plain, tmp_path, capsys):
    from pdrlearn.io import read_session
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.replay import read_streams

    both = _gzipped(plain, tmp_path / "both", keep_plain=("fAccelerometer",))
    msg = r"holds both fAccelerometer.csv and fAccelerometer.csv.gz; keep one of them .*B369"
    with pytest.raises(DataError, match=msg):
        read_session(both)
    with pytest.raises(DataError, match=msg):
        read_streams(both, load_bundle(SHIPPED))
    capsys.readouterr()
    assert main(["track", str(both), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip()
    assert "holds both fAccelerometer.csv" in err and "Traceback" not in err and not (tmp_path / "t").exists()


def test_damaged_gzip_file_is_one_line_b369(plain, tmp_path):
    from pdrlearn.io import read_session

    gz = _gzipped(plain, tmp_path / "gz")
    data = (gz / "fGyroscope.csv.gz").read_bytes()
    (gz / "fGyroscope.csv.gz").write_bytes(data[: len(data) // 2])  # a download cut short
    with pytest.raises(DataError, match=r"fGyroscope.csv.gz: not a readable gzip file .*B369"):
        read_session(gz)
