"""Decision B22 (docs/decisions/bad-input.md), review: the undeclared timestamp unit is one unit for the whole
session, chosen from every sensor file at once. A slow barometer whose seconds also read as plausible
milliseconds, or whose microseconds and nanoseconds both give a plausible rate, takes the IMU files' unit;
milliseconds that contradict ``rate_hz`` are not kept when exactly one other unit matches it."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import read_session

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _copy(tmp_path: Path, factor: float, *, rate_hz=None, every: dict | None = None, unit_key: bool = False):
    """The session's sensor files only (no labels), timestamps ms x ``factor``, ``every[name]``-th rows only."""
    dst = tmp_path / "s"
    dst.mkdir(parents=True)
    meta = json.loads((SRC / "meta.json").read_text())
    if not unit_key:
        meta["units"].pop("timestamp", None)
    if rate_hz is not None:
        meta["rate_hz"] = rate_hz
    (dst / "meta.json").write_text(json.dumps(meta))
    for p in SRC.glob("w*.csv"):
        df = pd.read_csv(p)
        df = df.iloc[::(every or {}).get(p.stem, 1)].reset_index(drop=True)
        df["timestamp"] = df["timestamp"] * factor
        df.to_csv(dst / p.name, index=False)
    return dst


def _unit_lines(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if "declares no timestamp unit" in r.getMessage()]


@pytest.mark.parametrize("every", [100, 25])  # a barometer at 1 Hz and 4 Hz: its seconds x 1000 look like ms too
def test_a_slow_barometer_takes_the_sessions_unit(tmp_path, caplog, every):
    ref = read_session(_copy(tmp_path / "ref", 1.0, every={"wBarometer": every}))
    with caplog.at_level(logging.WARNING):
        s = read_session(_copy(tmp_path / "s", 1e-3, every={"wBarometer": every}))
    for name, st in ref.streams.items():
        np.testing.assert_allclose(s.streams[name].t, st.t, rtol=1e-9, atol=1e-9)
    assert s.streams["wBarometer"].rate_hz == pytest.approx(100.0 / every)
    (line,) = _unit_lines(caplog)
    assert '"timestamp": "s"' in line


@pytest.mark.parametrize("factor,unit", [(1e2, "us"), (1e5, "ns")])
def test_a_fast_recording_is_read_at_its_declared_rate(tmp_path, caplog, factor, unit):
    # 100 Hz ms timestamps x 1e2 = a 1000 Hz recording in us (read as ms it is a plausible 1 Hz); x 1e5 = 1000 Hz
    # in ns (the barometer, not held to rate_hz, is plausible in us and ns alike)
    with caplog.at_level(logging.WARNING):
        s = read_session(_copy(tmp_path, factor, rate_hz=1000.0))
    for st in s.streams.values():
        assert st.rate_hz == pytest.approx(1000.0)
    (line,) = _unit_lines(caplog)
    assert f'"timestamp": "{unit}"' in line


def test_milliseconds_off_the_declared_rate_stay_milliseconds(tmp_path, caplog):
    # a wrong rate_hz with no other unit matching it: the ms reading is kept, silently as before
    with caplog.at_level(logging.WARNING):
        s = read_session(_copy(tmp_path, 1.0, rate_hz=50.0))
    assert s.streams["wAccelerometer"].rate_hz == pytest.approx(100.0)
    assert not _unit_lines(caplog)


def test_a_magnetometer_at_its_own_rate_follows_the_session(tmp_path):
    # a 100 Hz session in seconds whose magnetometer logs at 50 Hz: read as seconds, not "disagree"
    import shutil

    src = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"
    dst = tmp_path / "s"
    shutil.copytree(src, dst)
    meta = json.loads((dst / "meta.json").read_text())
    meta["units"].pop("timestamp", None)
    (dst / "meta.json").write_text(json.dumps(meta))
    for p in dst.glob("w*.csv"):
        df = pd.read_csv(p)
        if p.name == "wMagneticField.csv":
            df = df.iloc[::2]
        df["timestamp"] = df["timestamp"] * 1e-3
        df.to_csv(p, index=False)
    s = read_session(dst)
    assert abs(s.streams["wMagneticField"].rate_hz - 50.0) < 1.0
    assert abs(s.streams["wAccelerometer"].rate_hz - 100.0) < 1.0
