"""Decisions B405 / B406 (trial T2 finding 7): a coarsely quantised sensor at rest is not called frozen, its
repeated peak level is not called clipped, a sensor frozen while the unit moves still is, and `info` prints each
stream's resolution."""

from __future__ import annotations

import json
import logging

import numpy as np

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.validate import clipped_samples
from tests.test_saturation_units import _write

G = 9.80665
FS = 52.0


def _quantise(v, step):
    return np.round(np.asarray(v) / step) * step


def _resting_unit(tmp_path, *, walk_mid: bool):
    """52 Hz foot, 12 s: a 12-bit +-2000 deg/s gyroscope (0.0171 rad/s steps) reads all zeros; the accelerometer
    rests with a filter's edge transient on its first and last sample (|acc| 7.5 m/s^2, trial T2's d_w12), or
    (``walk_mid``) swings by 6 m/s^2 from 4 s to 8 s while the gyroscope stays stuck: a frozen sensor."""
    rng = np.random.default_rng(10185)
    t = np.arange(0.0, 12.0, 1.0 / FS)
    acc = np.column_stack([np.zeros_like(t), np.zeros_like(t), np.full_like(t, G)]) + rng.normal(0, 0.03, (t.size, 3))
    acc[0, 2] = acc[-1, 2] = 7.5
    if walk_mid:
        k = (t >= 4.0) & (t < 8.0)
        acc[k, 0] += 6.0 * np.sin(2 * np.pi * 1.8 * t[k])
    gyr = _quantise(rng.normal(0, 0.0015, (t.size, 3)), np.deg2rad(4000.0 / 4096))
    _write(tmp_path, "fAccelerometer", t, acc)
    _write(tmp_path, "fGyroscope", t, gyr)
    return tmp_path


def _frozen_lines(caplog, folder):
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        read_session(folder)
    return [r.getMessage() for r in caplog.records if "looks frozen" in r.getMessage()]


def test_a_quantised_gyroscope_at_rest_is_not_frozen_b405(tmp_path, caplog):
    assert _frozen_lines(caplog, _resting_unit(tmp_path / "rest", walk_mid=False)) == []
    lines = _frozen_lines(caplog, _resting_unit(tmp_path / "stuck", walk_mid=True))
    assert len(lines) == 1 and "fGyroscope.csv" in lines[0] and "decision B120" in lines[0], lines


def test_coarse_levels_are_not_clipping_b405():
    t = np.arange(0.0, 30.0, 1.0 / FS)
    peak = np.column_stack([6.3 * np.sin(2 * np.pi * 0.9 * t), np.zeros_like(t), np.zeros_like(t)])
    eight_bit = _quantise(peak, np.deg2rad(4000.0 / 256))  # 8 bits at +-2000 deg/s: 0.273 rad/s steps
    assert clipped_samples(eight_bit, "gyroscope") == (0, 0.0)
    full = np.deg2rad(250.0)  # an 8-bit +-250 deg/s gyroscope clipped at its scale is still said
    clipped = _quantise(np.clip(peak, -full, full), np.deg2rad(500.0 / 256))
    n, top = clipped_samples(clipped, "gyroscope")
    assert n > 100 and abs(top - full) < np.deg2rad(2.0)


def test_info_prints_each_streams_resolution_b406(tmp_path, capsys):
    folder = _resting_unit(tmp_path / "rest", walk_mid=False)
    t = np.arange(0.0, 12.0, 1.0 / FS)
    _write(folder, "fGyroscope", t, _quantise(np.random.default_rng(10186).normal(0, 0.05, (t.size, 3)),
                                              np.deg2rad(4000.0 / 4096)))  # 12 bits at +-2000 deg/s
    capsys.readouterr()
    assert main(["info", str(folder), "--json"]) == 0
    sensors = json.loads(capsys.readouterr().out)["sensors"]
    assert abs(sensors["fGyroscope"]["resolution"] - np.deg2rad(4000.0 / 4096)) < 1e-5
    assert 0 < sensors["fAccelerometer"]["resolution"] < 0.01
    assert main(["info", str(folder)]) == 0
    out = capsys.readouterr().out
    assert "resolution" in out and "0.017" in out  # the cell may wrap its unit onto a second line


def test_info_prints_no_resolution_for_float_noise_b412(capsys):
    """Decision B412 (review R3 finding 4): mobgap's converted gyroscope printed 9.14e-17 rad/s, the smallest gap
    between floats; off a grid `info` prints "-" and --json null, while a quantised stream keeps its step."""
    from tests.conftest import external_session

    folder = external_session("mobgap_HA001_Test5_Trial1")
    assert main(["info", str(folder), "--json"]) == 0
    sensors = json.loads(capsys.readouterr().out)["sensors"]
    assert sensors["wGyroscope"]["resolution"] is None
    assert main(["info", str(folder)]) == 0
    row = next(ln for ln in capsys.readouterr().out.splitlines() if "wGyroscope" in ln)
    assert "e-17" not in row and row.rstrip(" │|").endswith("-"), row
    from pdrlearn.io.validate import resolution

    step = np.deg2rad(4000.0 / 4096)
    q = _quantise(np.random.default_rng(10351).normal(0, 0.3, (500, 3)), step)
    assert abs(resolution(q, grid=True) - step) < 1e-9
