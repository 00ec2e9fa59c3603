"""Decisions B425 / B426 / B427 (docs/decisions/bad-input.md; trial T1 F3, F6, session 42): a sensor file with a
finite value beyond any sensor's range (1e308) is one line naming the file, the line and the value, without numpy
warnings; a sensor file (B426) or label table (B427) whose header names more columns than it may have is refused
before its body is read, and the extra columns of a sensor file that is read are named in one warning."""

from __future__ import annotations

import json
import logging
import warnings

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.plasys import MAX_SENSOR_COLUMNS
from pdrlearn.io.sensors import SENSORS
from pdrlearn.kernels.units import VALUE_LIMITS, out_of_range

G = 9.80665


def _walk(seconds: float = 20.0, fs: float = 100.0, seed: int = 0):
    """A foot's accelerometer (m/s^2; gravity on +y, at rest half of each 1 s cycle) and gyroscope (rad/s)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, seconds, 1.0 / fs)
    swing = (t % 1.0) > 0.5
    acc = np.column_stack([np.zeros_like(t), np.full_like(t, G), np.zeros_like(t)])
    acc[swing] += 8.0 * np.sin(2 * np.pi * 2 * t[swing])[:, None] * [1.0, 0.5, 0.2]
    gyr = np.zeros((t.size, 3))
    gyr[swing, 2] = 6.0 * np.sin(2 * np.pi * 2 * t[swing])
    return t, acc + rng.normal(0, 0.05, acc.shape), gyr + rng.normal(0, 0.01, gyr.shape)


def _write(folder, name, t, v, header: str | None = None, extra: str = ""):
    folder.mkdir(exist_ok=True)
    cols = SENSORS[name].columns
    lines = [header or ",".join(("timestamp", *cols))]
    for a, row in zip(t, np.atleast_2d(v.T).T, strict=True):
        lines.append(",".join([str(round(a * 1000)), *(f"{x:.9g}" for x in np.atleast_1d(row))]) + extra)
    (folder / f"{name}.csv").write_text("\n".join(lines) + "\n")


def _session(tmp_path, acc=None, gyr=None, name="s"):
    t, a, g = _walk()
    d = tmp_path / name
    _write(d, "fAccelerometer", t, a if acc is None else acc(a))
    _write(d, "fGyroscope", t, g if gyr is None else gyr(g))
    return d


def _set(row: int, value):
    def f(v):
        v = v.copy()
        v[row] = value
        return v
    return f


def test_one_absurd_accelerometer_sample_is_one_line_naming_file_line_and_value_without_warnings_b425(tmp_path):
    d = _session(tmp_path, acc=_set(100, [1e308, 1e308, -1e308]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's overflow RuntimeWarnings fail the test
        with pytest.raises(DataError) as exc:
            read_session(d)
    msg = str(exc.value)
    assert msg.startswith(f"{d / 'fAccelerometer.csv'}: 1 row(s) with a value beyond any accelerometer's range")
    assert "first at line 102: x = 1e+308" in msg and "2000 m/s^2" in msg and "B425" in msg


def test_the_cli_refuses_it_in_one_line_exit_2(tmp_path, capsys):
    d = _session(tmp_path, gyr=_set(500, [0.0, 0.0, 250.0]))  # 250 rad/s: beyond any gyroscope
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert main(["steps", str(d)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and "fGyroscope.csv" in err[0]
    assert "line 502: z = 250" in err[0] and "100 rad/s" in err[0]


def test_a_declared_unit_is_converted_before_the_limit_and_named_b425(tmp_path):
    d = _session(tmp_path, acc=lambda a: _set(40, [0.0, 300.0, 0.0])(a / G))  # a file in g: 300 g on one row
    (d / "meta.json").write_text(json.dumps({"units": {"fAccelerometer": "g"}}))
    with pytest.raises(DataError, match=r"line 42: y = 300 \(300 x 9\.80665 in m/s\^2\)"):
        read_session(d)
    d2 = _session(tmp_path, acc=lambda a: _set(40, [0.0, 150.0, 0.0])(a / G), name="s2")  # 150 g: a high-g impact
    (d2 / "meta.json").write_text(json.dumps({"units": {"fAccelerometer": "g"}}))
    assert read_session(d2).streams["fAccelerometer"].values[40, 1] == pytest.approx(150 * G)


def test_a_whole_file_in_another_unit_keeps_its_unit_message_b425(tmp_path):
    # mm/s^2 (every sample beyond 2000) and deg/s (the swings beyond 100): B30's lines, not B425's
    d = _session(tmp_path, acc=lambda a: a * 1000.0)
    with pytest.raises(DataError, match="raw counts or mm/s"):
        read_session(d)
    d2 = _session(tmp_path, gyr=lambda g: np.degrees(g) * 3, name="s2")
    with pytest.raises(DataError, match="looks like deg/s"):
        read_session(d2)
    # decision B433: without the unit checks (the documented opt-out) such a file is read as written
    got = read_session(d, check_units=False).streams["fAccelerometer"].values
    assert np.abs(got).max() > VALUE_LIMITS["accelerometer"]


def test_limits_are_per_kind_and_never_overflow_b425():
    assert VALUE_LIMITS == {"accelerometer": 2000.0, "gyroscope": 100.0, "magnetometer": 1e4, "barometer": 2000.0,
                            "force": 1e7}
    big = np.array([[1.0, 2.0, 3.0], [1e308, 0.0, 0.0], [0.0, -1e308, 0.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert out_of_range("magnetometer", big, factor=100.0).tolist() == [1, 2]  # gauss: x100 not computed
        assert out_of_range("barometer", np.array([[1013.0], [2500.0]])).tolist() == [1]
        assert out_of_range("accelerometer", np.array([[1999.0, 0.0, 0.0]])).size == 0


def test_a_header_with_too_many_columns_is_refused_before_the_body_b426(tmp_path, monkeypatch):
    import pdrlearn.io.plasys as plasys

    t, a, g = _walk()
    d = tmp_path / "s"
    names = ",".join(f"c{i}" for i in range(200_000))
    _write(d, "fAccelerometer", t, a, header=f"timestamp,x,y,z,{names}")
    _write(d, "fGyroscope", t, g)

    def unread(path, *args, **kwargs):  # the refused file's body is never parsed
        assert "fAccelerometer" not in str(path), "the body of a refused file was read"
        return read_table(path, *args, **kwargs)

    read_table = plasys.read_table
    monkeypatch.setattr(plasys, "read_table", unread)
    with pytest.raises(DataError) as exc:
        read_session(d)
    assert str(exc.value) == (f"{d / 'fAccelerometer.csv'}: the header names 200004 columns, more than the "
                              f"{MAX_SENSOR_COLUMNS} a sensor file may have (it needs timestamp,x,y,z; decision "
                              "B426): keep those columns and drop the others")


def test_a_semicolon_header_is_counted_by_its_separator_b426(tmp_path):
    t, a, g = _walk(seconds=12.0)
    d = tmp_path / "s"
    names = ";".join(f"c{i}" for i in range(MAX_SENSOR_COLUMNS))  # 4 + 64 fields
    (d).mkdir()
    rows = "\n".join(f"{round(x * 1000)};{v[0]:.6f};{v[1]:.6f};{v[2]:.6f}" for x, v in zip(t, a, strict=True))
    (d / "fAccelerometer.csv").write_text(f"sep=;\ntimestamp;x;y;z;{names}\n{rows}\n")
    _write(d, "fGyroscope", t, g)
    with pytest.raises(DataError, match=f"the header names {MAX_SENSOR_COLUMNS + 4} columns"):
        read_session(d)


def test_extra_columns_are_read_around_with_one_warning_naming_them_b426(tmp_path, caplog):
    t, a, g = _walk()
    d = tmp_path / "s"
    _write(d, "fAccelerometer", t, a)
    _write(d, "fGyroscope", t, g, header="timestamp,x,y,z,Temp,acc_x", extra=",21.5,0.1")
    with caplog.at_level(logging.WARNING):
        s = read_session(d)
    lines = [r.getMessage() for r in caplog.records if "B426" in r.getMessage()]
    assert lines == [f"{d / 'fGyroscope.csv'}: 2 column(s) besides timestamp,x,y,z not read: 'Temp', 'acc_x' "
                     "(decision B426)"]
    assert s.streams["fGyroscope"].values.shape == (t.size, 3)


def test_a_label_table_with_too_many_columns_is_refused_before_the_body_b427(tmp_path):
    from pdrlearn.io.plasys import MAX_TABLE_COLUMNS

    d = _session(tmp_path)
    names = ",".join(f"c{i}" for i in range(MAX_TABLE_COLUMNS))
    (d / "steps.csv").write_text(f"start_ms,end_ms,{names}\n0,1000{',' * MAX_TABLE_COLUMNS}\n")
    with pytest.raises(DataError) as exc:
        read_session(d)
    assert str(exc.value).startswith(f"{d / 'steps.csv'}: the header names {MAX_TABLE_COLUMNS + 2} columns, more "
                                     f"than the {MAX_TABLE_COLUMNS} a session's table may have (decision B427)")


def test_a_separator_ending_every_line_is_not_named_b426(tmp_path, caplog):
    t, a, g = _walk()
    d = tmp_path / "s"
    _write(d, "fAccelerometer", t, a, header="timestamp,x,y,z,", extra=",")
    _write(d, "fGyroscope", t, g)
    with caplog.at_level(logging.WARNING):
        s = read_session(d)
    assert not [r for r in caplog.records if "B426" in r.getMessage()]
    assert s.streams["fAccelerometer"].values.shape == (t.size, 3)
