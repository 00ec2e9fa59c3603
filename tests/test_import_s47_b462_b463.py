"""Session 47, trial T1 findings F8 and F9: ``import --sensor-height`` dropped in silence behind ``--leg-length``
(decision B462), and a waist session written without its accelerometer with only a note (decision B463)."""
from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main


def _export(path, acc_names=("AccX_g", "AccY_g", "AccZ_g"), gyro=True, acc=True):
    n = 600
    rng = np.random.default_rng(3)
    cols = {"Time_s": np.arange(n) / 100}
    if acc:
        cols.update(zip(acc_names, (rng.normal(0, .05, n), rng.normal(0, .05, n), 1 + rng.normal(0, .05, n)),
                        strict=True))
    if gyro:
        cols.update({f"Gyr{a}_dps": rng.normal(0, 1, n) for a in "XYZ"})
    pd.DataFrame(cols).to_csv(path, index=False)
    return path


def test_b462_sensor_height_behind_leg_length_is_said_at_import(tmp_path, capsys):
    csv = _export(tmp_path / "lb.csv")
    assert main(["import", str(csv), "--unit", "waist", "--sensor-height", "0.62", "--leg-length", "0.68",
                 "--subject-height", "1.30", "--out", str(tmp_path / "s")]) == 0
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "decision B462" in ln]
    assert len(lines) == 1 and lines[0].startswith("warning: ")
    assert "leg_length_m 0.68 m" in lines[0] and "sensor_height_m 0.62 m" in lines[0] and "not used" in lines[0]
    assert "crouched walker" in lines[0] and "--pipeline waist-pendulum --distance 10" in lines[0]
    # one value, or both the same: nothing dropped, no line
    assert main(["import", str(csv), "--unit", "waist", "--leg-length", "0.68", "--out", str(tmp_path / "a")]) == 0
    assert main(["import", str(csv), "--unit", "waist", "--sensor-height", "0.68", "--leg-length", "0.68",
                 "--out", str(tmp_path / "b")]) == 0
    assert "decision B462" not in capsys.readouterr().err


def test_b462_help_says_the_leg_is_taken_first(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "160")
    assert main(["import", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.replace("│", " ").split())
    assert "leg length (W10) only without --leg-length, which is taken first" in text


def test_b463_a_waist_session_without_an_accelerometer_is_refused(tmp_path, capsys):
    csv = _export(tmp_path / "lb.csv", acc_names=("Ax_raw", "Ay_raw", "Az_raw"))  # not guessed
    out = tmp_path / "s"
    assert main(["import", str(csv), "--unit", "waist", "--out", str(out)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and "decision B463" in err[0]
    assert "Ax_raw, Ay_raw, Az_raw" in err[0] and "--no-acc" in err[0] and not out.exists()
    gyro_only = _export(tmp_path / "gyro.csv", acc=False)  # a phone's gyroscope file first, when asked for
    assert main(["import", str(gyro_only), "--unit", "waist", "--no-acc", "--out", str(out)]) == 0
    assert (out / "wGyroscope.csv").exists() and not (out / "wAccelerometer.csv").exists()
    acc_only = _export(tmp_path / "acc.csv", gyro=False)
    assert main(["import", str(acc_only), "--unit", "waist", "--merge", "--out", str(out)]) == 0
    assert (out / "wAccelerometer.csv").exists()
    # an accelerometer without a gyroscope stays a note (W130: 'steps --detector pll' finds its contacts)
    assert main(["import", str(acc_only), "--unit", "waist", "--out", str(tmp_path / "a")]) == 0


def test_b463_no_acc_is_the_lower_backs_only(tmp_path, capsys):
    gyro_only = _export(tmp_path / "gyro.csv", acc=False)
    assert main(["import", str(gyro_only), "--no-acc", "--out", str(tmp_path / "s")]) != 0  # the default foot unit
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--no-acc" in err[0] and "--unit waist" in err[0] and not (tmp_path / "s").exists()


def test_b463_names_the_streams_it_would_write_r1_f5(tmp_path, capsys):
    """Review R1 F5 (session 48): a magnetometer-only waist file is not called a gyroscope."""
    n = 300
    csv = tmp_path / "mag.csv"
    pd.DataFrame({"Time_s": np.arange(n) / 100, **{f"Mag{a}_uT": np.full(n, 20.0) for a in "XYZ"}}).to_csv(csv,
                                                                                                          index=False)
    assert main(["import", str(csv), "--unit", "waist", "--mag", "MagX_uT,MagY_uT,MagZ_uT", "--out",
                 str(tmp_path / "s")]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "decision B463" in err[0], err
    assert "write the magnetometer now" in err[0] and "gyroscope" not in err[0]
