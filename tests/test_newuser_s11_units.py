"""A new-user trial (session 11): gravity-removed acceleration got "looks like units of g" or ran silently
(decision B30), sample-index timestamps were read as a 1000 Hz ms clock (B31), meta.json's ``rate_hz`` and
``units`` of a sensor file were ignored (B32), and +-4 ms sampling jitter read as 104.65 Hz with 392 "gaps"
and tripled the stride-length error (B33)."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Stream

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
LEVEL = REAL / "gaitmap_level_left"  # foot, 204.8 Hz, labelled strides
WAIST = REAL / "mobgap_HA001_Test5_Trial1"  # lower back, 100 Hz
G = 9.80665


def _at_100hz(dst: Path, *, times=None, meta: dict | None = None, src: Path = LEVEL) -> Path:
    """A 100 Hz copy of the foot recording (values interpolated at ``times`` ms, default a 10 ms grid),
    written with ``timestamp`` = ``times`` (or what ``times`` returns for the grid)."""
    dst.mkdir(parents=True)
    acc, gyr = (pd.read_csv(src / f"{n}.csv") for n in ("fAccelerometer", "fGyroscope"))
    grid = np.arange(20.0, min(acc.timestamp.iloc[-1], gyr.timestamp.iloc[-1]) - 20.0, 10.0)
    t = grid if times is None else times(grid)
    for name, df in (("fAccelerometer", acc), ("fGyroscope", gyr)):
        out = pd.DataFrame({"timestamp": t})
        for c in "xyz":
            out[c] = np.interp(t, df.timestamp, df[c])
        out.to_csv(dst / f"{name}.csv", index=False, float_format="%.10g")
    m = {k: v for k, v in json.loads((src / "meta.json").read_text()).items() if k not in ("rate_hz", "units")}
    (dst / "meta.json").write_text(json.dumps({**m, **(meta or {})}))
    return dst


def _one_line_error(capsys, args) -> str:
    assert main(args) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


# -- B30: gravity removed ------------------------------------------------------------------------------
def _linear(src: Path, dst: Path, name: str, unit: float = 1.0) -> Path:
    """Copy of ``src`` whose ``name`` file has gravity removed (a 2 s moving average subtracted, what a
    phone's "linear acceleration" does), in m/s^2 (``unit`` 1) or g (``unit`` 1/G)."""
    shutil.copytree(src, dst)
    df = pd.read_csv(dst / f"{name}.csv")
    for c in "xyz":
        df[c] = (df[c] - df[c].rolling(200, center=True, min_periods=1).mean()) * unit
    df.to_csv(dst / f"{name}.csv", index=False)
    return dst


def test_gravity_removed_foot_acceleration_is_refused(tmp_path, capsys):
    d = _linear(LEVEL, tmp_path / "foot_lin", "fAccelerometer")
    line = _one_line_error(capsys, ["track", str(d), "--out", str(tmp_path / "out")])
    assert str(d / "fAccelerometer.csv") in line and "gravity has been removed" in line
    assert "gravity included" in line and "multiply" not in line


def test_gravity_removed_waist_acceleration_in_g_is_not_called_units_of_g(tmp_path, capsys):
    d = _linear(WAIST, tmp_path / "waist_lin", "wAccelerometer", unit=1 / G)
    line = _one_line_error(capsys, ["info", str(d)])
    assert str(d / "wAccelerometer.csv") in line and "gravity has been removed" in line
    assert "units of g" not in line and "9.80665" not in line


def test_gravity_included_recordings_in_g_keep_the_g_message(tmp_path):
    shutil.copytree(WAIST, tmp_path / "g")
    df = pd.read_csv(tmp_path / "g" / "wAccelerometer.csv")
    df[["x", "y", "z"]] /= G
    df.to_csv(tmp_path / "g" / "wAccelerometer.csv", index=False)
    with pytest.raises(DataError, match=r"units of g; multiply by 9.80665.*\"wAccelerometer\": \"g\""):
        read_session(tmp_path / "g")


# -- B31: sample-index timestamps --------------------------------------------------------------------------
def test_sample_index_timestamps_are_refused_naming_the_fix(tmp_path, capsys):
    d = _at_100hz(tmp_path / "index", times=lambda g: np.arange(g.size))
    line = _one_line_error(capsys, ["track", str(d), "--out", str(tmp_path / "out")])
    assert str(d / "fAccelerometer.csv") in line and "consecutive integers" in line
    assert "rate_hz" in line and "ms" in line


def test_sample_index_timestamps_with_rate_hz_are_read_at_that_rate(tmp_path, caplog):
    clean = read_session(_at_100hz(tmp_path / "clean", times=lambda g: g - g[0]))
    d = _at_100hz(tmp_path / "index", times=lambda g: np.arange(g.size), meta={"rate_hz": 100})
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        s = read_session(d)
    assert [r for r in caplog.records if "sample indices at 100 Hz" in r.getMessage()]
    np.testing.assert_allclose(s["fAccelerometer"].t, clean["fAccelerometer"].t, atol=1e-9)
    decl = _at_100hz(tmp_path / "decl", times=lambda g: np.arange(g.size),
                     meta={"rate_hz": 100, "units": {"timestamp": "samples"}})
    np.testing.assert_allclose(read_session(decl)["fGyroscope"].t, clean["fGyroscope"].t, atol=1e-9)


def test_a_genuine_1000_hz_ms_clock_is_read_as_ms_with_rate_hz(tmp_path):
    # decision B98: without rate_hz consecutive integers are refused (sample counters write the same numbers)
    with pytest.raises(DataError, match="sample counters"):
        read_session(_at_100hz(tmp_path / "bare", times=lambda g: np.arange(g[0], g[-1], 1.0)))
    d = _at_100hz(tmp_path / "k1000", times=lambda g: np.arange(g[0], g[-1], 1.0), meta={"rate_hz": 1000})
    s = read_session(d)
    assert s["fAccelerometer"].rate_hz == pytest.approx(1000.0)


# -- B32: meta.json rate_hz and units ------------------------------------------------------------------------
def test_declared_value_units_are_converted(tmp_path):
    si = read_session(_at_100hz(tmp_path / "si"))
    d = _at_100hz(tmp_path / "gdeg", meta={"units": {"fAccelerometer": "g", "fGyroscope": "deg/s (as exported)"}})
    for name, k in (("fAccelerometer", 1 / G), ("fGyroscope", 180 / np.pi)):
        df = pd.read_csv(d / f"{name}.csv")
        df[["x", "y", "z"]] *= k
        df.to_csv(d / f"{name}.csv", index=False, float_format="%.17g")
    s = read_session(d)
    for name in ("fAccelerometer", "fGyroscope"):
        np.testing.assert_allclose(s[name].values, si[name].values, rtol=1e-9, atol=1e-12)
    from pdrlearn.io import write_session

    back = read_session(write_session(s, tmp_path / "written"))  # written in SI: not converted twice
    np.testing.assert_allclose(back["fAccelerometer"].values, si["fAccelerometer"].values, rtol=1e-9)


def test_unknown_or_wrong_declared_value_unit_is_refused(tmp_path):
    d = _at_100hz(tmp_path / "bad", meta={"units": {"fAccelerometer": "furlongs/fortnight^2"}})
    with pytest.raises(DataError, match=r"meta.json: units.fAccelerometer 'furlongs.*m/s\^2"):
        read_session(d)
    d = _at_100hz(tmp_path / "wrong", meta={"units": {"fAccelerometer": "g"}})  # values are m/s^2 already
    with pytest.raises(DataError, match=r"converted from 'g', the unit meta.json declares"):
        read_session(d)


def test_rate_hz_contradicting_the_timestamps_warns(tmp_path, caplog):
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        read_session(_at_100hz(tmp_path / "ok", meta={"rate_hz": 100}))
        assert not [r for r in caplog.records if "rate_hz" in r.getMessage()]
        read_session(_at_100hz(tmp_path / "r200", meta={"rate_hz": 200}))
    msg = [r.getMessage() for r in caplog.records if "rate_hz 200 contradicts" in r.getMessage()]
    assert len(msg) == 1 and "fAccelerometer 100 Hz" in msg[0] and "meta.json" in msg[0]


# -- B33: sampling jitter ----------------------------------------------------------------------------------
def _jittered(tmp_path, name="jit", amp=4.0, seed=0):
    rng = np.random.default_rng(seed)
    return _at_100hz(tmp_path / name, times=lambda g: g + rng.uniform(-amp, amp, g.size))


def test_jittered_period_is_not_biased():
    rng = np.random.default_rng(1)
    t = (np.arange(4000) * 10.0 + rng.uniform(-4, 4, 4000)) * 1e-3
    s = Stream("fAccelerometer", t, np.zeros((t.size, 3)))
    assert s.rate_hz == pytest.approx(100.0, rel=0.005)  # was 104.65 Hz: the long intervals were dropped


def test_jittered_streams_have_their_rate_and_no_made_up_gaps(tmp_path):
    a = read_session(_jittered(tmp_path))["fAccelerometer"]  # was 104.65 Hz and ~270 "gaps" (B11 steps lost)
    assert a.gaps() == [] and a.rate_hz == pytest.approx(100.0, rel=1e-3) and a.jittered


def test_jittered_streams_are_put_on_a_uniform_clock_on_request(tmp_path, caplog):
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        s = read_session(_jittered(tmp_path), uniform_clock=True)
    a = s["fAccelerometer"]
    assert a.gaps() == [] and np.ptp(np.diff(a.t)) < 1e-9 and a.rate_hz == pytest.approx(100.0, rel=1e-3)
    assert [r for r in caplog.records if "interpolated onto a uniform 100 Hz clock" in r.getMessage()]


def test_uniform_and_quantised_clocks_are_untouched(tmp_path):
    for src in (LEVEL, _at_100hz(tmp_path / "clean")):
        s = read_session(src, uniform_clock=True)
        raw = pd.read_csv(src / "fAccelerometer.csv")
        assert np.array_equal(s["fAccelerometer"].t, raw.timestamp.to_numpy() * 1e-3)
    q = tmp_path / "quantised"  # 204.8 Hz in integer ms (D7)
    shutil.copytree(LEVEL, q)
    for n in ("fAccelerometer", "fGyroscope"):
        df = pd.read_csv(q / f"{n}.csv")
        df["timestamp"] = np.round(df.timestamp).astype(int)
        df.to_csv(q / f"{n}.csv", index=False)
    s = read_session(q, uniform_clock=True)["fAccelerometer"]
    assert np.array_equal(s.t, pd.read_csv(q / "fAccelerometer.csv").timestamp * 1e-3) and not s.jittered


def test_a_real_gap_in_a_jittered_stream_stays_a_gap(tmp_path):
    d = _jittered(tmp_path)
    for n in ("fAccelerometer", "fGyroscope"):
        df = pd.read_csv(d / f"{n}.csv")
        df[(df.timestamp < 15000) | (df.timestamp > 17000)].to_csv(d / f"{n}.csv", index=False)
    for uniform in (False, True):
        gaps = read_session(d, uniform_clock=uniform)["fAccelerometer"].gaps()
        assert len(gaps) == 1 and gaps[0].duration_s == pytest.approx(2.0, abs=0.03)
