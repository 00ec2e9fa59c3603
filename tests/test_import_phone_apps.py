"""Phone apps' exports in their own layouts (decisions B162-B166): phyphox (``Time (s)``, ``Acceleration x (m/s^2)``,
``Gyroscope x (rad/s)``, ``Linear Acceleration x (m/s^2)``; one CSV per sensor, or one table) and Sensor Logger
(``time`` epoch ns, ``seconds_elapsed``, ``z``, ``y``, ``x``; ``Accelerometer.csv`` without gravity beside
``TotalAcceleration.csv`` on Android, ``Gravity.csv`` on iOS, whose signs are Core Motion's, -1 g)."""

from __future__ import annotations

import shlex
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.test_import_phone import EPOCH_NS, T5, _quiet_read


@pytest.fixture(scope="module")
def walk():
    """HA001 Test5 T1's waist streams (100 Hz, lower back), the accelerometer split into a gravity part (its 1 s
    moving mean) and the rest (what a phone's 'linear acceleration' holds)."""
    s = _quiet_read(T5)
    acc, gyr = s["wAccelerometer"], s["wGyroscope"]
    k = 100
    pad = np.pad(acc.values, ((k // 2, k - k // 2 - 1), (0, 0)), mode="edge")
    gravity = np.stack([np.convolve(pad[:, j], np.ones(k) / k, mode="valid") for j in range(3)], axis=1)
    return {"t": acc.t - acc.t[0], "acc": acc.values, "gravity": gravity, "linear": acc.values - gravity,
            "gt": gyr.t - acc.t[0], "gyr": gyr.values}


def _phyphox(path: Path, t, values, name: str, unit: str, absolute: str, *, sep: str = ",",
             decimal: str = ".") -> Path:
    """One phyphox export table: ``Time (s)``, ``NAME x (UNIT)`` ... and phyphox's absolute-value column."""
    cols = {"Time (s)": t, **{f"{name} {a} ({unit})": values[:, i] for i, a in enumerate("xyz")},
            absolute: np.linalg.norm(values, axis=1)}
    pd.DataFrame(cols).to_csv(path, index=False, sep=sep, decimal=decimal)
    return path


def _sensor_logger(path: Path, t, values) -> Path:
    """One Sensor Logger file: time (epoch ns), seconds_elapsed, z, y, x."""
    pd.DataFrame({"time": EPOCH_NS + np.round(t * 1e9).astype(np.int64), "seconds_elapsed": t,
                  "z": values[:, 2], "y": values[:, 1], "x": values[:, 0]}).to_csv(path, index=False)
    return path


@pytest.mark.parametrize("sep,decimal", [(",", "."), (";", ",")])
def test_phyphox_per_sensor_files_import_as_they_are(walk, tmp_path, capsys, sep, decimal):
    """Decision B162: phyphox's per-sensor CSVs (its 'Comma, decimal point' and 'Semicolon, decimal comma'
    formats) import with no option: the columns and units are read from the names, the absolute-value column is
    left unused; the session holds the recording's values."""
    acc = _phyphox(tmp_path / "Accelerometer.csv", walk["t"], walk["acc"], "Acceleration", "m/s^2",
                   "Absolute acceleration (m/s^2)", sep=sep, decimal=decimal)
    gyr = _phyphox(tmp_path / "Gyroscope.csv", walk["gt"], walk["gyr"], "Gyroscope", "rad/s", "Absolute (rad/s)",
                   sep=sep, decimal=decimal)
    out = tmp_path / "s"
    assert main(["import", str(acc), "--unit", "waist", "--out", str(out)]) == 0
    assert main(["import", str(gyr), "--unit", "waist", "--merge", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "column 'Time (s)' in s (guessed column, unit header)" in err
    assert ("wAccelerometer: Acceleration x (m/s^2),Acceleration y (m/s^2),Acceleration z (m/s^2) (guessed) in "
            "m/s2") in err
    assert "wGyroscope: Gyroscope x (rad/s),Gyroscope y (rad/s),Gyroscope z (rad/s) (guessed) in rad/s" in err
    assert "unused columns: Absolute acceleration (m/s^2)" in err
    s = _quiet_read(out)
    assert np.allclose(s["wAccelerometer"].values, walk["acc"]) and np.allclose(s["wGyroscope"].values, walk["gyr"])


def test_a_phyphox_table_of_both_sensors_imports_in_one_step(walk, tmp_path, capsys):
    """Decision B162: one phyphox table with one time column and both sensors (a custom experiment's export)."""
    t = walk["t"]
    gyr = np.column_stack([np.interp(t, walk["gt"], walk["gyr"][:, j]) for j in range(3)])
    df = pd.DataFrame({"Time (s)": t, **{f"Acceleration {a} (m/s^2)": walk["acc"][:, i] for i, a in enumerate("xyz")},
                       **{f"Gyroscope {a} (rad/s)": gyr[:, i] for i, a in enumerate("xyz")}})
    df.to_csv(tmp_path / "Raw Data.csv", index=False)
    assert main(["import", str(tmp_path / "Raw Data.csv"), "--unit", "waist", "--out", str(tmp_path / "s")]) == 0
    s = _quiet_read(tmp_path / "s")
    assert s.has("wAccelerometer") and s.has("wGyroscope") and len(s["wGyroscope"]) == t.size


@pytest.mark.parametrize("with_gyro", [False, True])
def test_phyphox_linear_acceleration_is_refused_in_one_line(walk, tmp_path, capsys, with_gyro):
    """Decision B163: phyphox's 'Acceleration (without g)' export (``Linear Acceleration x (m/s^2)``) was "no
    accelerometer/gyroscope columns recognised ... map them with --acc", which led to B30's refusal; with a
    gyroscope beside it the gyroscope alone was imported. Now one line names the columns and the exports with
    gravity; nothing is written."""
    path = _phyphox(tmp_path / "Linear Acceleration.csv", walk["t"], walk["linear"], "Linear Acceleration", "m/s^2",
                    "Absolute acceleration (m/s^2)")
    if with_gyro:
        df = pd.read_csv(path)
        for i, a in enumerate("xyz"):
            df[f"Gyroscope {a} (rad/s)"] = np.interp(walk["t"], walk["gt"], walk["gyr"][:, i])
        df.to_csv(path, index=False)
    out = tmp_path / "s"
    assert main(["import", str(path), "--unit", "waist", "--out", str(out)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in lines[0]
    assert "Linear Acceleration x (m/s^2), Linear Acceleration y (m/s^2), Linear Acceleration z (m/s^2) hold " \
           "acceleration without gravity" in lines[0]
    assert "phyphox's 'Acceleration with g' experiment" in lines[0] and "(decision B163)" in lines[0]
    assert not out.exists()


@pytest.fixture()
def sensor_logger(walk, tmp_path):
    """Sensor Logger folders: Android (Accelerometer.csv without gravity, TotalAcceleration.csv, Gravity.csv,
    Gyroscope.csv) and iOS (Accelerometer.csv without gravity and Gravity.csv, both with Core Motion's sign)."""
    android, ios = tmp_path / "android", tmp_path / "ios"
    android.mkdir()
    ios.mkdir()
    t = walk["t"]
    _sensor_logger(android / "Accelerometer.csv", t, walk["linear"])
    _sensor_logger(android / "TotalAcceleration.csv", t, walk["acc"])
    _sensor_logger(android / "Gravity.csv", t, walk["gravity"])
    _sensor_logger(ios / "Accelerometer.csv", t, -walk["linear"])
    _sensor_logger(ios / "Gravity.csv", t, -walk["gravity"])
    for d in (android, ios):
        _sensor_logger(d / "Gyroscope.csv", walk["gt"], walk["gyr"])
    return android, ios


def test_a_sensor_logger_accelerometer_without_gravity_names_the_file_with_it(sensor_logger, tmp_path, capsys):
    """Decision B164: Sensor Logger's Accelerometer.csv holds acceleration without gravity; B30 refused it with a
    generic advice. Now the line names TotalAcceleration.csv beside it (Android), else --add-gravity Gravity.csv
    (iOS), else the apps' exports with gravity; one line, nothing written."""
    android, ios = sensor_logger
    lone = tmp_path / "lone"
    lone.mkdir()
    (lone / "Accelerometer.csv").write_bytes((android / "Accelerometer.csv").read_bytes())
    for folder, fix in ((android, f"import {android / 'TotalAcceleration.csv'} instead"),
                        (ios, f"--add-gravity {ios / 'Gravity.csv'} (Sensor Logger on iOS"),
                        (lone, "Sensor Logger's TotalAcceleration.csv (Android)")):
        out = tmp_path / f"s_{folder.name}"
        assert main(["import", str(folder / "Accelerometer.csv"), "--unit", "waist", "--acc", "x,y,z",
                     "--out", str(out)]) == 2
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and "so gravity has been removed" in lines[0], lines
        assert fix in lines[0] and "(decision B164)" in lines[0] and not out.exists()


def test_info_recipe_takes_total_acceleration_or_adds_gravity_and_it_works(sensor_logger, walk, tmp_path, capsys):
    """Decision B165: B147's `info` recipe took the shortest accelerometer name, Sensor Logger's Accelerometer.csv
    (without gravity). Now TotalAcceleration.csv when there is one, else Accelerometer.csv with --add-gravity
    Gravity.csv (B166); the printed commands run, and the iOS import names Core Motion's sign."""
    android, ios = sensor_logger
    for folder in (android, ios):
        assert main(["info", str(folder)]) == 2
        err = capsys.readouterr().err
        cmds = [shlex.split(c) for c in err.split("`")[1::2] if c.startswith("pdrlearn import")]
        assert len(cmds) == 2
        acc_cmd = cmds[0]
        if folder is android:
            assert acc_cmd[2] == str(android / "TotalAcceleration.csv") and "--add-gravity" not in acc_cmd
        else:
            assert acc_cmd[2] == str(ios / "Accelerometer.csv")
            assert acc_cmd[acc_cmd.index("--add-gravity") + 1] == str(ios / "Gravity.csv")
        out = tmp_path / f"s_{folder.name}"
        for c in cmds:
            assert main([a if a != "SESSION" else str(out) for a in c[1:]]) == 0
        err = capsys.readouterr().err
        assert ("reports gravity as -1 g" in err) == (folder is ios)
        s = _quiet_read(out)
        assert np.allclose(np.abs(s["wAccelerometer"].values), np.abs(walk["acc"]), atol=1e-9)


def test_add_gravity_rebuilds_the_specific_force_and_refuses_what_it_cannot(sensor_logger, walk, tmp_path, capsys):
    """Decision B166: --add-gravity Gravity.csv adds the gravity file to the accelerometer columns sample by sample
    (negated with them: --acc=-x,-y,-z gives the iPhone's specific force back); an accelerometer that already holds
    gravity, a gravity file of another recording and a missing one are one line each, nothing written."""
    _, ios = sensor_logger
    acc, grav = ios / "Accelerometer.csv", ios / "Gravity.csv"
    out = tmp_path / "s"
    assert main(["import", str(acc), "--unit", "waist", "--acc=-x,-y,-z", "--add-gravity", str(grav),
                 "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "plus the gravity of Gravity.csv (--add-gravity)" in err and "reports gravity as -1 g" not in err
    assert np.abs(_quiet_read(out)["wAccelerometer"].values - walk["acc"]).max() < 1e-9
    (tmp_path / "late").mkdir()
    late = _sensor_logger(tmp_path / "late" / "Gravity.csv", walk["t"] + 30.0, -walk["gravity"])
    total = _sensor_logger(tmp_path / "TotalAcceleration.csv", walk["t"], walk["acc"])
    for csv, gravity, said in ((total, grav, "already holds gravity"), (acc, late, "give the gravity file of the "
                                                                        "same recording"),
                               (acc, tmp_path / "none.csv", "no such file")):
        bad = tmp_path / "bad"
        assert main(["import", str(csv), "--unit", "waist", "--acc", "x,y,z", "--add-gravity", str(gravity),
                     "--out", str(bad)]) == 2
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and said in lines[0] and not bad.exists(), lines
