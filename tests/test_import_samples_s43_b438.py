"""Decisions B438, B439 (session 43, trial T1 finding F4): mobgap's own CSV export (``samples,acc_x..gyr_z``, acc in g,
gyr in deg/s) had been refused three times in a row, one problem per run. A column named as sample numbers asks for
the rate only (B439), and every problem one option fixes is said in one line with the corrected command (B438)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.import_fixes import corrected_command
from pdrlearn.io import read_session

WAIST = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"  # 100 Hz


@pytest.fixture(scope="module")
def waist():
    if not WAIST.is_dir():
        pytest.skip("datasets/real/mobgap_HA001_Test5_Trial1 not present")
    return read_session(WAIST)


def _mobgap_csv(s, path: Path, tname: str = "samples") -> Path:
    """The session as mobgap's data_csv writes it: sample numbers, acc in g, gyr in deg/s."""
    a, w = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    df = pd.DataFrame({tname: np.arange(len(a)), **{f"acc_{c}": a.values[:, i] / 9.80665 for i, c in enumerate("xyz")},
                       **{f"gyr_{c}": np.degrees(w.values[:, i]) for i, c in enumerate("xyz")}})
    df.to_csv(path, index=False, float_format="%.15g")
    return path


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


def test_mobgap_csv_every_problem_in_one_line_b438(waist, tmp_path, capsys):
    csv = _mobgap_csv(waist, tmp_path / "trial.csv")
    out = tmp_path / "s"
    assert main(["import", str(csv), "--unit", "waist", "--out", str(out)]) == 2
    err = _err(capsys)
    assert "3 problems, each fixed by an option" in err
    assert "(1) column 'samples' holds sample numbers" in err and "(2) acc_x, acc_y, acc_z as m/s2" in err
    assert "(3) gyr_x, gyr_y, gyr_z as rad/s" in err
    assert (f"run: pdrlearn import {csv} --unit waist --out {out} --rate HZ --acc-unit g --gyro-unit deg/s "
            "(HZ: the sampling rate in Hz) (decision B438)") in err
    assert not out.exists()  # nothing written
    # a given option's wrong value is replaced in the command, and a known rate is kept
    assert main(["import", str(csv), "--unit", "waist", "--out", str(out), "--rate", "100", "--acc-unit=mg"]) == 2
    err = _err(capsys)
    assert "2 problems" in err and "--rate 100 --acc-unit=g --gyro-unit deg/s (decision B438)" in err
    # the printed command imports it, with the samples column read as sample numbers at the rate (B439)
    assert main(["import", str(csv), "--unit", "waist", "--out", str(out), "--rate", "100", "--acc-unit", "g",
                 "--gyro-unit", "deg/s"]) == 0
    got = read_session(out)
    assert got.meta["imported"]["time"]["column"] == "samples"
    assert got.streams["wAccelerometer"].rate_hz == pytest.approx(100.0)
    np.testing.assert_allclose(got.streams["wAccelerometer"].values, waist.streams["wAccelerometer"].values,
                               rtol=1e-9, atol=1e-9)


def test_one_problem_keeps_its_own_line_b438(waist, tmp_path, capsys):
    csv = _mobgap_csv(waist, tmp_path / "trial.csv")
    assert main(["import", str(csv), "--unit", "waist", "--out", str(tmp_path / "s"), "--rate", "100",
                 "--acc-unit", "g"]) == 2
    err = _err(capsys)
    assert "fixed by an option" not in err and "looks like deg/s" in err and "--gyro-unit (rad/s | deg/s)" in err


def test_sample_named_column_asks_for_the_rate_only_b439(waist, tmp_path, capsys):
    csv = _mobgap_csv(waist, tmp_path / "trial.csv", tname="Sample Index")
    assert main(["import", str(csv), "--unit", "waist", "--out", str(tmp_path / "s"), "--acc-unit", "g",
                 "--gyro-unit", "deg/s"]) == 2
    err = _err(capsys)
    assert "column 'Sample Index' holds sample numbers (0-" in err and "--rate HZ (decision B439)" in err
    assert "--time-unit ms" not in err
    # B39's question stands for consecutive integers in a column named like a time (ms or sample numbers?)
    csv = _mobgap_csv(waist, tmp_path / "t.csv", tname="timestamp")
    assert main(["import", str(csv), "--unit", "waist", "--out", str(tmp_path / "s"), "--acc-unit", "g",
                 "--gyro-unit", "deg/s"]) == 2
    err = _err(capsys)
    assert "holds consecutive integers" in err and "--time-unit ms" in err


def test_corrected_command_quotes_and_replaces_b438():
    argv = ["pdrlearn", "import", "my data.csv", "--out", "s", "--acc-unit", "mg"]
    assert corrected_command(argv, {"--acc-unit": "g", "--rate": None}) == \
        "pdrlearn import 'my data.csv' --out s --acc-unit g --rate HZ"
