"""Trial `teaching` (session 19), findings 4 and 5: swapped foot/waist files and one file given as both units are
refused from the signals (B91); printed commands quote paths (B92); a raw export folder's hint names the foot
file for the foot unit, and `train` gives it too (B93)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.io.unit_check import unit_mixup

G = 9.80665


@pytest.fixture(scope="module")
def sim():
    from pdrlearn.sim import simulate

    return simulate("A", 1)


def _export(s, unit: str, path: Path) -> Path:
    """One unit as a vendor export: seconds, g, deg/s."""
    p = "f" if unit == "foot" else "w"
    a, w = s.streams[p + "Accelerometer"], s.streams[p + "Gyroscope"]
    df = pd.DataFrame({"Time (s)": a.t, **{f"Acc{c} (g)": a.values[:, i] / G for i, c in enumerate("XYZ")},
                       **{f"Gyro{c} (deg/s)": np.degrees(w.values[:, i]) for i, c in enumerate("XYZ")}})
    df.to_csv(path, index=False)
    return path


def _err(capsys) -> str:
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1, lines
    return lines[0]


def test_swapped_files_are_refused_at_import_merge(sim, tmp_path, capsys):
    out = tmp_path / "S"
    hip, foot = _export(sim, "waist", tmp_path / "hüfte.csv"), _export(sim, "foot", tmp_path / "fuss.csv")
    assert main(["import", str(hip), "--out", str(out), "--frames", "x=forward,y=up,z=right"]) == 0
    capsys.readouterr()
    assert main(["import", str(foot), "--out", str(out), "--unit", "waist", "--merge",
                 "--frames", "x=left,y=up,z=forward"]) == 2
    err = _err(capsys)
    assert "the foot and waist files look swapped" in err
    assert "import fuss.csv as the foot unit (--unit foot) and hüfte.csv with --unit waist --merge" in err
    assert "nothing written" in err
    assert not (out / "wGyroscope.csv").exists()


def test_one_file_as_both_units_is_refused(sim, tmp_path, capsys):
    out, foot = tmp_path / "S", _export(sim, "foot", tmp_path / "fuss.csv")
    assert main(["import", str(foot), "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["import", str(foot), "--out", str(out), "--unit", "waist", "--merge"]) == 2
    assert "the foot unit (fuss.csv) and the waist unit (fuss.csv) hold the same data" in _err(capsys)


def test_track_refuses_a_session_with_swapped_files(sim, tmp_path, capsys):
    good = tmp_path / "good"
    write_session(sim, good)
    assert unit_mixup(read_session(good)) is None  # correctly placed: clear
    bad = tmp_path / "bad"
    shutil.copytree(good, bad)
    for s in ("Accelerometer", "Gyroscope"):
        (bad / f"f{s}.csv").rename(bad / "tmp.csv")
        (bad / f"w{s}.csv").rename(bad / f"f{s}.csv")
        (bad / "tmp.csv").rename(bad / f"w{s}.csv")
    with pytest.raises(DataError, match="the foot and waist files look swapped.*swap the f\\* and w\\* files"):
        read_session(bad).require_frame("foot")
    assert main(["track", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "look swapped" in _err(capsys)
    assert not (tmp_path / "o").exists()


def test_printed_import_commands_quote_paths_with_spaces(sim, tmp_path, capsys):
    raw = tmp_path / "Messung 5 Rundgang"
    raw.mkdir()
    _export(sim, "foot", raw / "fuss.csv")
    _export(sim, "waist", raw / "hüfte.csv")
    assert main(["track", str(raw), "--out", str(tmp_path / "o")]) == 2
    err = _err(capsys)
    q = f"'{raw}/fuss.csv'"
    assert f"`pdrlearn import {q} --out SESSION` (the foot unit, by its name)" in err
    assert f"`pdrlearn import '{raw}/hüfte.csv' --unit waist --merge --out SESSION`" in err
    assert main(["train", str(raw), "--out", str(tmp_path / "m")]) == 2
    assert f"`pdrlearn import {q} --out SESSION`" in _err(capsys)
    out = tmp_path / "Sitzungen" / "Messung 5"
    assert main(["import", str(raw / "fuss.csv"), "--out", str(out)]) == 0
    assert f"check it with: pdrlearn info '{out}'" in capsys.readouterr().err
