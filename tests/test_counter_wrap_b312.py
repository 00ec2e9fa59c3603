"""Decision B312 (docs/decisions/bad-input.md): a timestamp counter that wraps around (16-bit ms, 32-bit us) with
sampling continuing across it is unwrapped with one warning, in ``read_session`` (track) and ``import``, instead of
being refused as a clock reset (B73)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.importer import import_csv
from pdrlearn.kernels.counter_wrap import counter_wraps, unwrap

G = 9.80665


def _imu(n: int, seed: int = 7985):
    """A still foot unit: gravity on +z and noise (accelerometer m/s^2, gyroscope rad/s)."""
    rng = np.random.default_rng(seed)
    acc = np.column_stack([np.zeros(n), np.zeros(n), np.full(n, G)]) + rng.normal(0, 0.05, (n, 3))
    return acc, rng.normal(0, 0.01, (n, 3))


def test_counter_wraps_finds_only_a_wrap_with_continuous_sampling():
    true = 40000.0 + 10.0 * np.arange(15000)  # 150 s at 100 Hz in ms from 40 s: wraps at 65.536 s and 131.072 s
    bits, idx = counter_wraps(true % 65536)
    assert bits == 16 and idx.size == 2
    np.testing.assert_array_equal(unwrap(true % 65536, bits, idx), true)
    us = (true * 1000.0 + 2.0 ** 32 - 60e6) % 2.0 ** 32  # a 32-bit us counter
    assert counter_wraps(us)[0] == 32
    reset = true.copy()
    reset[5000:] -= reset[5000]  # the recorder restarted at 0: a clock reset (B73), not a wrap
    assert counter_wraps(reset)[0] == 0
    gap = np.delete(true, np.arange(2400, 2700))  # 3 s missing across the first wrap: the wraps are not known
    assert counter_wraps(gap % 65536)[0] == 0
    assert counter_wraps(true)[0] == 0  # increasing: nothing to unwrap


def _write(folder, name, t_ms, v):
    folder.mkdir(exist_ok=True)
    rows = "\n".join(f"{a:.0f},{x:.6f},{y:.6f},{z:.6f}" for a, (x, y, z) in zip(t_ms, v, strict=True))
    (folder / f"{name}.csv").write_text("timestamp,x,y,z\n" + rows + "\n")


def test_read_session_unwraps_a_16_bit_millisecond_counter(tmp_path, caplog):
    true = 40000.0 + 10.0 * np.arange(15000)
    acc, gyr = _imu(true.size)
    _write(tmp_path / "s", "fAccelerometer", true % 65536, acc)
    _write(tmp_path / "s", "fGyroscope", true % 65536, gyr)
    with caplog.at_level(logging.WARNING):
        s = read_session(tmp_path / "s")
    np.testing.assert_allclose(s.streams["fAccelerometer"].t, true * 1e-3)
    lines = [r.getMessage() for r in caplog.records if "wrap around" in r.getMessage()]
    assert len(lines) == 1, lines  # one line for the files that wrap alike
    assert "fAccelerometer.csv, fGyroscope.csv: the timestamps wrap around from 65530 to 4 ticks at line 2556 " \
           "(2 times): a 16-bit counter" in lines[0] and "not a clock reset" in lines[0] and "B312" in lines[0]
    reset = true.copy()
    reset[5000:] -= reset[5000]
    _write(tmp_path / "r", "fAccelerometer", reset, acc)
    _write(tmp_path / "r", "fGyroscope", reset, gyr)
    with pytest.raises(DataError, match="a clock reset"):  # B73 keeps a restart a restart
        read_session(tmp_path / "r")


def test_import_unwraps_a_32_bit_microsecond_counter(tmp_path, caplog):
    true = 4264.967296e6 + 1e4 * np.arange(6000)  # us; 2^32 us = 4294.97 s is passed after 3000 rows
    acc, gyr = _imu(true.size)
    rows = "\n".join(f"{a:.0f}," + ",".join(f"{x:.5f}" for x in (*ac, *gy))
                     for a, ac, gy in zip(true % 2.0 ** 32, acc, gyr, strict=True))
    path = tmp_path / "fw.csv"
    path.write_text("t_us,ax,ay,az,gx,gy,gz\n" + rows + "\n")
    with caplog.at_level(logging.WARNING):
        s, _ = import_csv(path, columns={"acc": ["ax", "ay", "az"], "gyro": ["gx", "gy", "gz"]}, time_unit="us")
    np.testing.assert_allclose(s.streams["fAccelerometer"].t, (true - true[0]) * 1e-6, atol=1e-9)
    line = next(r.getMessage() for r in caplog.records if "wrap around" in r.getMessage())
    assert "fw.csv (t_us): the timestamps wrap around from 4294957296 to 0 us at line 3002" in line
    assert "32-bit counter" in line and "decision B312" in line
