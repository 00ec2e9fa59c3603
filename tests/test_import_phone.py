"""Session 22's phone trial: smartphone exports (Sensor Logger: Accelerometer.csv / Gyroscope.csv, columns
``time`` (epoch ns), ``seconds_elapsed``, ``z``, ``y``, ``x``) imported as a waist unit, one file per sensor
(decisions B145-B149)."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session

ROOT = Path(__file__).resolve().parents[1]
T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"
EPOCH_NS = 1_733_216_400_000_000_000  # 2024-12-03 09:00 UTC


def _quiet_read(path: Path):
    logging.disable(logging.WARNING)
    try:
        return read_session(path)
    finally:
        logging.disable(logging.NOTSET)


def _sensor_file(folder: Path, stream, name: str, *, start_s: float = 0.0) -> Path:
    """One phone sensor file in Sensor Logger's layout (columns time, seconds_elapsed, z, y, x), from
    ``start_s`` s into the stream."""
    keep = stream.t >= stream.t[0] + start_s
    t = stream.t[keep] - stream.t[0]
    v = stream.values[keep]
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.csv"
    pd.DataFrame({"time": EPOCH_NS + np.round(t * 1e9).astype(np.int64), "seconds_elapsed": t,
                  "z": v[:, 2], "y": v[:, 1], "x": v[:, 0]}).to_csv(path, index=False)
    return path


def _opt(kind: str, value: str) -> list[str]:
    """``--acc x,y,z`` as two arguments; ``=-x,...`` (a negated first column) as ``--acc=-x,...``."""
    return [f"--{kind}{value}"] if value.startswith("=") else [f"--{kind}", value]


@pytest.fixture(scope="module")
def phone(tmp_path_factory) -> Path:
    s = _quiet_read(T5)
    d = tmp_path_factory.mktemp("phone")
    _sensor_file(d, s["wAccelerometer"], "Accelerometer")
    _sensor_file(d, s["wGyroscope"], "Gyroscope")
    _sensor_file(d, s["wMagneticField"], "Magnetometer")
    return d


@pytest.mark.parametrize("acc,gyro", [("z,y,x", "z,y,x"), ("y,x,z", "y,x,z"), ("=-z,-y,-x", "z,y,x")])
def test_an_odd_column_order_is_refused_in_one_line(phone, tmp_path, capsys, acc, gyro):
    """Decision B145 (trial finding 3): ``--acc z,y,x --gyro z,y,x`` (Sensor Logger's column order typed as the
    axis order) mirrored every turn silently (112 steps for 106, final (-2.57, 2.11) for (-0.96, -0.97))."""
    out = tmp_path / "s"
    assert main(["import", str(phone / "Accelerometer.csv"), "--unit", "waist", *_opt("acc", acc),
                 *_opt("gyro", gyro), "--out", str(out)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "mirror-image order" in err[0] and "nothing written" in err[0] and not out.exists()
    assert "--acc x,y,z" in err[0] or "--acc=-x,-y,-z" in err[0]


@pytest.mark.parametrize("acc", ["x,y,z", "y,z,x", "=-x,-y,-z", "=x,-y,z"])
def test_a_rotation_a_sign_convention_or_a_deliberate_negation_is_accepted(phone, tmp_path, acc):
    """B145 refuses a bare odd permutation only: a cyclic order is a rotation, all three accelerometer columns
    negated is iOS's convention (B48), one negated column is L71's own fix for a mirrored export."""
    assert main(["import", str(phone / "Accelerometer.csv"), "--unit", "waist", *_opt("acc", acc),
                 "--out", str(tmp_path / "s")]) == 0


def test_an_accelerometer_in_g_at_the_waist_names_the_ios_sign(tmp_path, capsys):
    """Decision B146 (trial finding 2): an iPhone export (gravity -1 g) imported without negation tracked a
    mirrored path (final (9.83, -14.54) for (9.76, 15.00)), and no check can see it (B48: D11 is blind to the
    accelerometer's sign), so import says it when the accelerometer is in g and not negated."""
    s = _quiet_read(T5)
    a = s["wAccelerometer"]
    from pdrlearn.io.session import Stream
    _sensor_file(tmp_path / "ios", Stream(a.name, a.t, -a.values / 9.80665), "Accelerometer")
    csv = str(tmp_path / "ios" / "Accelerometer.csv")
    note = "iPhone (Core Motion) export"
    assert main(["import", csv, "--unit", "waist", "--acc", "x,y,z", "--acc-unit", "g",
                 "--out", str(tmp_path / "a")]) == 0
    err = capsys.readouterr().err
    assert err.count(note) == 1 and "--acc=-x,-y,-z" in err
    assert main(["import", csv, "--unit", "waist", "--acc=-x,-y,-z", "--acc-unit", "g",
                 "--out", str(tmp_path / "b")]) == 0
    assert note not in capsys.readouterr().err
    assert main(["import", str(tmp_path / "ios" / "Accelerometer.csv"), "--unit", "waist", "--acc", "x,y,z",
                 "--out", str(tmp_path / "c")]) != 0  # in g read as m/s2: B45's refusal, no note
    assert note not in capsys.readouterr().err


def test_info_on_phone_sensor_files_gives_the_merge_recipe_and_it_works(phone, tmp_path, capsys):
    """Decision B147 (trial finding 6): ``info`` on Accelerometer.csv / Gyroscope.csv / Magnetometer.csv advised
    'pdrlearn import FOOT.csv' for the foot unit; it names the per-sensor waist imports with --merge."""
    assert main(["info", str(phone)]) != 0
    err = capsys.readouterr().err
    assert "FOOT.csv" not in err and "a phone's per-sensor files become one waist unit" in err
    cmds = [c for c in err.split("`") if c.startswith("pdrlearn import")]
    assert len(cmds) == 3 and "Accelerometer.csv --unit waist --acc x,y,z --out SESSION" in cmds[0]
    assert "Gyroscope.csv --unit waist --gyro x,y,z --merge" in cmds[1] and "Magnetometer.csv" in cmds[2]
    out = tmp_path / "s"
    for c in cmds:  # the recipe as printed (paths without spaces: no quoting to undo)
        assert main(c.replace("SESSION", str(out)).split()[1:]) == 0
    got = _quiet_read(out)
    assert {"wAccelerometer", "wGyroscope", "wMagneticField"} <= set(got.streams)


def test_seconds_elapsed_is_a_time_column(phone, tmp_path, capsys):
    """Decision B148 (trial finding 7): a file timed by Sensor Logger's ``seconds_elapsed`` alone was refused
    ("no timestamp column found ... name it with --time COLUMN"); beside ``time`` the epoch clock wins."""
    df = pd.read_csv(phone / "Accelerometer.csv").drop(columns="time")
    df.to_csv(tmp_path / "Accelerometer.csv", index=False)
    assert main(["import", str(tmp_path / "Accelerometer.csv"), "--unit", "waist", "--acc", "x,y,z",
                 "--out", str(tmp_path / "s")]) == 0
    assert "column 'seconds_elapsed' in s (guessed column" in capsys.readouterr().err
    assert _quiet_read(tmp_path / "s")["wAccelerometer"].rate_hz == pytest.approx(100.0, rel=0.01)
    assert main(["import", str(phone / "Accelerometer.csv"), "--unit", "waist", "--acc", "x,y,z",
                 "--out", str(tmp_path / "t")]) == 0
    assert "column 'time' in ns" in capsys.readouterr().err


def test_a_gyroscope_that_started_late_names_common_span(tmp_path, capsys):
    """Decision B149 (trial finding 7): a phone gyroscope starting 1.5 s after the accelerometer (both to the end)
    was "cut short (a truncated copy?)"; it is named as started late, with --common-span first (a file that lost
    its end keeps B72's message: tests/test_stream_spans*)."""
    s = _quiet_read(T5)
    d = tmp_path / "late"
    _sensor_file(d, s["wAccelerometer"], "Accelerometer")
    _sensor_file(d, s["wGyroscope"], "Gyroscope", start_s=1.5)
    out = tmp_path / "s"
    assert main(["import", str(d / "Accelerometer.csv"), "--unit", "waist", "--acc", "x,y,z", "--out", str(out)]) == 0
    assert main(["import", str(d / "Gyroscope.csv"), "--unit", "waist", "--gyro", "x,y,z", "--merge",
                 "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["track", str(out), "--out", str(tmp_path / "t")]) != 0
    err = capsys.readouterr().err
    assert "wGyroscope.csv: starts 1.50 s after the other 1 waist stream(s)" in err and "--common-span" in err
    assert "truncated copy" not in err
    assert main(["track", "--no-plot", str(out), "--out", str(tmp_path / "t"), "--common-span"]) == 0


def test_drop_duplicate_timestamps_keeps_the_first_row_of_each(phone, tmp_path, capsys):
    """Decision B150 (trial finding 7): a phone app's repeated timestamps were refused with no import option."""
    df = pd.read_csv(phone / "Accelerometer.csv")
    rep = df.iloc[[100, 200, 300, 400, 500]].assign(x=0.0)  # the repeats carry other values: the first is kept
    dup = pd.concat([df, rep]).sort_values("time", kind="stable")
    csv = tmp_path / "Accelerometer.csv"
    dup.to_csv(csv, index=False)
    args = ["import", str(csv), "--unit", "waist", "--acc", "x,y,z", "--out", str(tmp_path / "s")]
    assert main(args) != 0
    err = capsys.readouterr().err
    assert "5 duplicate timestamp(s)" in err and "pass --drop-duplicate-timestamps" in err
    assert main([*args, "--drop-duplicate-timestamps"]) == 0
    assert "5 rows repeating a timestamp dropped" in capsys.readouterr().err
    got = _quiet_read(tmp_path / "s")["wAccelerometer"]
    assert len(got) == len(df) and np.allclose(got.values[:, 0], df["x"].to_numpy())
