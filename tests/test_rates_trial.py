"""Trial `rates` (session 19): a mis-scaled accelerometer (B97) and sample-counter timestamps (B98)."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.io.validate import check_session

ROOT = Path(__file__).resolve().parents[1]
LEVEL = ROOT / "datasets" / "real" / "gaitmap_level_left"  # foot, 204.8 Hz
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"  # lower back, 100 Hz


def _scaled(src: Path, dst: Path, name: str, factor: float) -> Path:
    shutil.copytree(src, dst)
    df = pd.read_csv(dst / f"{name}.csv")
    df[["x", "y", "z"]] *= factor
    df.to_csv(dst / f"{name}.csv", index=False, float_format="%.10g")
    return dst


# -- B97: ~1 g at rest -----------------------------------------------------------------------------------------
@pytest.mark.parametrize(("src", "name"), [(LEVEL, "fAccelerometer"), (WAIST, "wAccelerometer")])
def test_accelerometer_scaled_2048_is_refused_naming_the_factor(tmp_path, capsys, src, name):
    d = _scaled(src, tmp_path / "x2048", name, 2.048)
    assert main(["info", str(d)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert str(d / f"{name}.csv") in err[0] and "times gravity" in err[0]
    factor = float(err[0].split("divide them by ")[1].split(",")[0].split()[0])
    assert factor == pytest.approx(2.048, rel=0.04)


def test_a_walking_waist_scaled_half_is_told_to_divide_by_half(tmp_path):
    """B97 (review of session 19): the refusal named the measured ratio (the quiet windows of a waist walking
    without a pause sit on the bounce's peaks: x0.5 read as ~x0.59), which would leave the values 16 % off."""
    from pdrlearn.io.validate import MISSCALES, likely_misscale

    assert likely_misscale(0.593) == 0.5 and likely_misscale(2.041) == 2.048 and likely_misscale(2.6) == 2.6
    with pytest.raises(DataError) as e:
        read_session(_scaled(WAIST, tmp_path / "half_w", "wAccelerometer", 0.5))
    factor = float(str(e.value).split("divide them by ")[1].split(",")[0])
    assert any(factor == pytest.approx(m, rel=1e-3) for m in MISSCALES) and factor == pytest.approx(0.5, rel=0.03)


def test_accelerometer_scaled_half_is_refused_and_1024_passes(tmp_path):
    with pytest.raises(DataError, match=r"0\.\d+ times gravity.*too small"):
        read_session(_scaled(LEVEL, tmp_path / "half", "fAccelerometer", 0.5))
    s = read_session(_scaled(LEVEL, tmp_path / "x1024", "fAccelerometer", 1.024))  # inside the spread: B97
    assert len(s["fAccelerometer"]) > 0


def test_a_mis_scaled_stream_built_in_python_is_refused(tmp_path):
    s = read_session(LEVEL)
    acc = s["fAccelerometer"]
    s.streams["fAccelerometer"] = Stream(acc.name, acc.t, acc.values * 2.048)
    with pytest.raises(DataError, match="times gravity"):
        check_session(s)


# -- B98: sample counters without rate_hz ----------------------------------------------------------------------
def _counter(dst: Path, meta_update: dict) -> Path:
    """The foot recording with its timestamps replaced by sample numbers 0, 1, 2 ... (a 204.8 Hz counter)."""
    shutil.copytree(LEVEL, dst)
    for name in ("fAccelerometer", "fGyroscope"):
        df = pd.read_csv(dst / f"{name}.csv")
        df["timestamp"] = np.arange(len(df))
        df.to_csv(dst / f"{name}.csv", index=False, float_format="%.10g")
    for label in ("steps.csv", "trajectory.csv"):
        (dst / label).unlink(missing_ok=True)
    meta = {k: v for k, v in json.loads((dst / "meta.json").read_text()).items() if k != "rate_hz"}
    (dst / "meta.json").write_text(json.dumps({**meta, **meta_update}))
    return dst


def test_sample_counter_with_declared_ms_and_no_rate_is_refused_and_read_with_rate_hz(tmp_path, capsys):
    d = _counter(tmp_path / "idx", {"units": {"timestamp": "ms since the first sample"}})
    assert main(["steps", str(d)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "sample counters" in err[0] and '"rate_hz"' in err[0] and '"samples"' in err[0]
    t = read_session(_counter(tmp_path / "rate", {"rate_hz": 204.8, "units": {"timestamp": "samples"}}))[
        "fAccelerometer"].t
    assert 1.0 / np.median(np.diff(t)) == pytest.approx(204.8)


# -- W87: the waist calibration records its rate ----------------------------------------------------------------
def test_waist_params_applied_at_another_rate_warn_naming_calibrate(tmp_path):
    from pdrlearn.track import get_pipeline
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import load_params
    from tests.test_waist import synth_session

    p = calibrate([synth_session(fs=100.0)], "waist-pendulum", distances=[12.0])
    assert p.rate_hz == pytest.approx(100.0)
    path = p.save(tmp_path / "p.json")
    assert load_params(path).rate_hz == pytest.approx(100.0)  # round trip
    track = get_pipeline("waist-pendulum")
    same = track(synth_session(fs=100.0), params=path).info["warnings"]
    assert not [w for w in same if "calibrated at" in w]
    other = [w for w in track(synth_session(fs=25.0), params=path).info["warnings"] if "calibrated at" in w]
    assert len(other) == 1 and str(path) in other[0] and "25 Hz" in other[0] and "pdrlearn calibrate" in other[0]


# -- features 16: the step windows' gap rule has a floor in seconds ---------------------------------------------
def _dropped(rate: float, missing: int) -> Stream:
    """10 s at ``rate`` Hz with ``missing`` samples in a row dropped at 5 s."""
    t = np.arange(0.0, 10.0, 1.0 / rate)
    i = int(5.0 * rate)
    t = np.delete(t, np.arange(i, i + missing))
    return Stream("fAccelerometer", t, np.tile([0.0, 9.81, 0.0], (t.size, 1)))


def test_window_gaps_bridge_up_to_25_ms_at_any_rate():
    from pdrlearn.features.windows import window_gaps

    assert window_gaps(_dropped(1000.0, 2)) == []  # a 3 ms hole: bridged (was a gap: 3 > 2.5 periods)
    assert window_gaps(_dropped(1000.0, 20)) == []  # 21 ms
    assert len(window_gaps(_dropped(1000.0, 30))) == 1  # 31 ms: a gap
    assert window_gaps(_dropped(100.0, 1)) == []  # B46 unchanged at 100 Hz and below
    assert len(window_gaps(_dropped(100.0, 2))) == 1
    assert window_gaps(_dropped(25.0, 1)) == [] and len(window_gaps(_dropped(25.0, 2))) == 1


# -- B99, B100: raw counts named by their counts per g; a scale factor in meta.json ------------------------------
def _counts(dst: Path, per_g: float, unit: str | None) -> Path:
    """The lower-back recording's accelerometer as int16 counts at ``per_g`` LSB/g, meta.json declaring ``unit``."""
    shutil.copytree(WAIST, dst)
    df = pd.read_csv(dst / "wAccelerometer.csv")
    df[["x", "y", "z"]] = np.round(df[["x", "y", "z"]] / 9.80665 * per_g)
    df.to_csv(dst / "wAccelerometer.csv", index=False)
    meta = json.loads((dst / "meta.json").read_text())
    units = {k: v for k, v in meta.get("units", {}).items() if k != "wAccelerometer"}
    meta["units"] = {**units, **({"wAccelerometer": unit} if unit else {})}
    (dst / "meta.json").write_text(json.dumps(meta))
    return dst


def test_raw_counts_error_names_the_counts_per_g(tmp_path):
    with pytest.raises(DataError, match=r"about 20\d\d per g \(a 2048 LSB/g sensor\?\)"):
        read_session(_counts(tmp_path / "raw", 2048.0, None))


@pytest.mark.parametrize("unit", ["1/2048 g", "0.0047884 m/s^2"])
def test_a_scale_factor_in_meta_json_converts_raw_counts(tmp_path, unit):
    ref = read_session(WAIST)["wAccelerometer"].values
    got = read_session(_counts(tmp_path / "raw", 2048.0, unit))["wAccelerometer"].values
    np.testing.assert_allclose(got, ref, atol=0.01)  # 1 count = 0.0048 m/s^2
