"""Decision B22 (docs/decisions/bad-input.md): a session whose meta.json declares no timestamp unit and whose
timestamps are not milliseconds is read in the one other unit that gives a plausible rate, with a warning; a
declared unit always wins (a contradiction is the one-line error of B9)."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.validate import time_unit_candidates

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _copy(tmp_path: Path, factor: float, units: str | None, files=None) -> Path:
    dst = tmp_path / "s"
    shutil.copytree(SRC, dst)
    meta = json.loads((dst / "meta.json").read_text())
    if units is None:
        meta["units"].pop("timestamp", None)
    else:
        meta["units"]["timestamp"] = units
    (dst / "meta.json").write_text(json.dumps(meta))
    for p in dst.glob("w*.csv"):
        if files is None or p.name in files:
            df = pd.read_csv(p)
            df["timestamp"] = df["timestamp"] * factor
            df.to_csv(p, index=False)
    return dst


@pytest.mark.parametrize("factor,unit", [(1e-3, "s"), (1e3, "us"), (1e6, "ns")])
def test_undeclared_unit_is_inferred_and_said(tmp_path, caplog, factor, unit):
    ref = read_session(SRC)
    with caplog.at_level(logging.WARNING):
        s = read_session(_copy(tmp_path, factor, None))
    for name, st in ref.streams.items():
        np.testing.assert_allclose(s.streams[name].t, st.t, rtol=1e-9, atol=1e-9)
    msg = [r.getMessage() for r in caplog.records if "timestamp unit" in r.getMessage()]
    assert len(msg) == 1 and f'"timestamp": "{unit}"' in msg[0] and "meta.json" in msg[0]


def test_milliseconds_are_not_touched(tmp_path, caplog):
    with caplog.at_level(logging.WARNING):
        s = read_session(_copy(tmp_path, 1.0, None))
    assert not [r for r in caplog.records if "timestamp unit" in r.getMessage()]
    assert s.streams["wAccelerometer"].rate_hz == pytest.approx(100.0)


def test_a_declared_unit_wins(tmp_path):
    with pytest.raises(DataError, match="not milliseconds"):
        read_session(_copy(tmp_path, 1e-3, "ms since the first sample"))


def test_files_in_different_units_are_refused(tmp_path):
    with pytest.raises(DataError, match="disagree"):
        read_session(_copy(tmp_path, 1e-3, None, files={"wAccelerometer.csv"}))


def test_the_declared_rate_must_match():
    t = np.arange(100) * 0.01  # 100 Hz in seconds
    assert time_unit_candidates(t) == [("s", 1.0)]
    assert time_unit_candidates(t, declared_rate_hz=100.0) == [("s", 1.0)]
    assert time_unit_candidates(t, declared_rate_hz=20.0) == []
    assert time_unit_candidates(np.arange(100) * 10.0) == [("ms", 1e-3)]  # milliseconds


def _phone_export(path: Path, rate: float, sensor: str, jitter_ns: float = 0.0) -> Path:
    """HA001 Test5 T1's waist stream resampled at ``rate`` Hz, timed by a phone's epoch-ns clock (Sensor Logger's
    ``time`` column, 2024-12-03), the median interval ``jitter_ns`` off the nominal one (decision B144)."""
    s = read_session(SRC)
    st = s[sensor]
    dt_ns = 1e9 / rate + jitter_ns
    t = np.arange(st.t[0], st.t[-1], dt_ns * 1e-9)
    vals = np.column_stack([np.interp(t, st.t, st.values[:, i]) for i in range(3)])
    ns = 1_733_216_400_000_000_000 + np.round(np.arange(t.size) * dt_ns).astype(np.int64)
    df = pd.DataFrame({"time": ns, "x": vals[:, 0], "y": vals[:, 1], "z": vals[:, 2]})
    df.to_csv(path, index=False)
    return path


@pytest.mark.parametrize("rate,jitter_ns,sensor,kind", [(1000.0, 0.0, "wAccelerometer", "--acc"),
                                                         (500.0, 256.0, "wAccelerometer", "--acc"),
                                                         (500.0, -128.0, "wGyroscope", "--gyro")])
def test_a_phone_epoch_ns_clock_at_500_hz_and_up_is_nanoseconds(tmp_path, capsys, rate, jitter_ns, sensor, kind):
    """Decision B144 (trial "phone" finding 1): epoch-ns timestamps at 1000 Hz were read as us (0.996 Hz, year
    ~56,900, exit 0), and at 500 Hz a gyroscope 128 ns short of 2 ms was read as us (0.4971 Hz was under the
    0.5 Hz floor, 0.5001 Hz over it): an IMU file is held to 10 Hz and a date before 2100."""
    from pdrlearn.cli import main

    csv = _phone_export(tmp_path / "Sensor.csv", rate, sensor, jitter_ns)
    out = tmp_path / "s"
    no_acc = ["--no-acc"] if kind == "--gyro" else []  # decision B463: a waist file without an accelerometer
    assert main(["import", str(csv), "--unit", "waist", kind, "x,y,z", *no_acc, "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "column 'time' in ns" in err and "2024-12-03" in err
    logging.disable(logging.WARNING)
    try:
        got = read_session(out)[sensor]
    finally:
        logging.disable(logging.NOTSET)
    assert got.rate_hz == pytest.approx(rate, rel=0.01)


def test_an_imu_file_is_held_to_10_hz_and_a_date_before_2100():
    step = np.arange(100) * 1e6  # 1000 Hz in ns (1 Hz in us)
    assert [u for u, _ in time_unit_candidates(1.7332164e18 + step)] == ["ns"]  # us: a date after 2100
    assert [u for u, _ in time_unit_candidates(5e12 + step)] == ["us", "ns"]  # a clock since boot: no date
    assert [u for u, _ in time_unit_candidates(5e12 + step, inertial=True)] == ["ns"]  # 1 Hz is no IMU rate


def test_an_ambiguous_unit_names_the_option_that_forces_the_other(tmp_path, capsys):
    """B144: a magnetometer file (no IMU floor) timed by ns since boot at 1000 Hz fits us (1 Hz) and ns; the
    summary names the one chosen and the --time-unit of the other."""
    from pdrlearn.cli import main

    n = 50
    df = pd.DataFrame({"time": 5_000_000_000_000 + np.arange(n) * 1_000_000, "mag_x": np.full(n, 20.0),
                       "mag_y": np.full(n, -5.0), "mag_z": np.full(n, 40.0)})
    df.to_csv(tmp_path / "Magnetometer.csv", index=False)
    assert main(["import", str(tmp_path / "Magnetometer.csv"), "--unit", "waist", "--no-acc",  # B463
                 "--out", str(tmp_path / "s")]) == 0
    assert "in us (guessed column, unit inferred (B22); also fits ns: pass --time-unit ns if it is in ns)" in \
        capsys.readouterr().err


@pytest.mark.parametrize("step_s, ok", [(0.1, True), (0.101, True), (0.2, False)])
def test_a_10_hz_imu_file_is_within_the_floor(tmp_path, capsys, step_s, ok):
    """B160: B144's 10 Hz floor refused a 10 Hz accelerometer whose seconds, read from text, give a median step of
    0.10000000000000142 s (600 rows: "no plausible rate"; with --time-unit s: "give 10 Hz"), and one whose clock
    runs 1 % slow; 5 Hz is still refused."""
    from pdrlearn.cli import main

    n = 600
    t = [float(f"{i * step_s:.3f}") for i in range(n)]
    assert 1.0 / np.median(np.diff(t)) < 10.0  # every case is under 10.000 Hz
    df = pd.DataFrame({"time": t, "acc_x": np.full(n, 0.1), "acc_y": np.full(n, 0.2), "acc_z": np.full(n, 9.8)})
    df.to_csv(tmp_path / "Accelerometer.csv", index=False)
    args = ["import", str(tmp_path / "Accelerometer.csv"), "--unit", "foot"]
    assert main([*args, "--time-unit", "s", "--out", str(tmp_path / "given")]) == (0 if ok else 2)
    assert "give 5 Hz" in capsys.readouterr().err or ok
    if ok:  # the unit inferred: seconds, the one unit that fits
        assert main([*args, "--out", str(tmp_path / "inferred")]) == 0
        assert read_session(tmp_path / "inferred").streams["fAccelerometer"].t[-1] == pytest.approx(t[-1])


def _slow_file(path: Path, rate: float, start_s: float = 0.0, n: int = 600) -> Path:
    t = [start_s + float(f"{i / rate:.4f}") for i in range(n)]
    pd.DataFrame({"time": t, "acc_x": np.full(n, 0.1), "acc_y": np.full(n, 0.2),
                  "acc_z": np.full(n, 9.8)}).to_csv(path, index=False)
    return path


@pytest.mark.parametrize("rate,start_s", [(4.0, 0.0), (5.0, 0.0), (4.0, 1_733_216_400.0), (2.0, 0.0)])
def test_a_slow_file_in_seconds_is_refused_not_read_as_ms(tmp_path, capsys, rate, start_s):
    """Decision B161 (review of B144): a 4 Hz accelerometer in seconds was read as ms at 4000 Hz (every time 1000x
    too short, exit 0); at 5 Hz the refusal said "read as ms give 5e+03 Hz; the values look like ms: pass
    --time-unit ms". Now one line names the file, both readings, the start date of epoch seconds and both fixes;
    nothing is written."""
    from pdrlearn.cli import main

    csv = _slow_file(tmp_path / "Accelerometer.csv", rate, start_s)
    out = tmp_path / "s"
    assert main(["import", str(csv), "--unit", "foot", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0]
    line = err[0]
    assert str(csv) in line and f"read as seconds give {rate:g} Hz" in line and f"read as ms {1000 * rate:g} Hz" in line
    assert "record again at 10 Hz or more" in line and "pass --time-unit ms" in line and "decision B161" in line
    assert ("starting 2024-12-03 09:00 UTC" in line) == (start_s > 0)
    assert not out.exists()
    # told it is seconds: the rate is named with the fix; told it is ms: the user's word is taken
    assert main(["import", str(csv), "--unit", "foot", "--time-unit", "s", "--out", str(out)]) == 2
    assert "an accelerometer or gyroscope needs 9 Hz or more" in capsys.readouterr().err and not out.exists()
    if rate < 5.0:  # 5000.000x Hz in ms is over B9's ceiling: refused, naming the seconds' rate
        assert main(["import", str(csv), "--unit", "foot", "--time-unit", "ms", "--out", str(out)]) == 0
    else:
        assert main(["import", str(csv), "--unit", "foot", "--time-unit", "ms", "--out", str(out)]) == 2
        assert "read as seconds they give 5 Hz, and an accelerometer" in capsys.readouterr().err


def test_a_session_file_in_slow_seconds_names_the_meta_json_unit(tmp_path):
    """B161 in read_session: a session's accelerometer at 4 Hz in seconds, meta.json declaring no unit, was read
    as ms at 4000 Hz; now refused naming the file and meta.json's units.timestamp; declared ms is read as told."""
    d = tmp_path / "walk"
    d.mkdir()
    t = np.arange(600) / 4.0
    pd.DataFrame({"timestamp": t, "x": 0.1, "y": 0.2, "z": 9.8}).to_csv(d / "fAccelerometer.csv", index=False)
    (d / "meta.json").write_text(json.dumps({"session": "walk"}))
    with pytest.raises(DataError, match=r"fAccelerometer.csv: the timestamps read as seconds give 4 Hz.*declare "
                                        r"\"units\": \{\"timestamp\": \"ms\"\} in meta.json \(decision B161\)"):
        read_session(d)
    (d / "meta.json").write_text(json.dumps({"session": "walk", "units": {"timestamp": "ms"}}))
    assert read_session(d)["fAccelerometer"].rate_hz == pytest.approx(4000.0)


@pytest.mark.parametrize("step,start", [(2.0, 0.0), (1.0, 1.7332164e12), (0.5, 1.7332164e12), (0.95, 5e6)])
def test_fast_ms_clocks_are_still_ms(step, start):
    """B161 leaves ms alone where seconds are no sensor rate or no date: 500 Hz from 0 (seconds: 0.5 Hz), 1000 and
    2000 Hz epoch ms (seconds after 2100), 1053 Hz since boot (under 1100 Hz in ms)."""
    t = start + np.arange(200) * step
    assert [u for u, _ in time_unit_candidates(t, inertial=True)][0] == "ms"
