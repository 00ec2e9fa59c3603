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
