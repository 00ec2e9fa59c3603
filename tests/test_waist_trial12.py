"""Trial 12 (a waist-only user): `track --realtime` (W60), the leg length guessed from the height (W62), a
standing-only recording (W61), calibrate --start/--end (W61), dropped samples in the online detector (W59) and
one missing sample at 50 Hz (B46)."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline

ROOT = Path(__file__).resolve().parents[1]
HA001_T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _copy_without_sensor_height(tmp_path: Path) -> Path:
    d = tmp_path / "nosh"
    shutil.copytree(HA001_T5, d)
    meta = json.loads((d / "meta.json").read_text())
    meta["subject"].pop("sensor_height_m")
    meta.pop("sensor_height_m", None)
    (d / "meta.json").write_text(json.dumps(meta))
    return d


def test_leg_from_height_warns_once_naming_the_option(tmp_path, caplog):
    d = _copy_without_sensor_height(tmp_path)
    with caplog.at_level(logging.WARNING):
        res = get_pipeline("waist-pendulum")(read_session(d))
    lines = [r.getMessage() for r in caplog.records if "sensor height" in r.getMessage()]
    assert len(lines) == 1 and "--sensor-height" in lines[0] and "sensor_height_m" in lines[0]
    assert "0.843 m" in lines[0]  # 0.53 x 1.59 m
    assert res.info["params"]["leg_m"] == pytest.approx(0.53 * 1.59)
    caplog.clear()
    with caplog.at_level(logging.WARNING):  # the PLL's frequency model has no leg length: no such line
        get_pipeline("waist-pll")(read_session(d))
    assert not [r for r in caplog.records if "sensor height" in r.getMessage()]
    caplog.clear()
    with caplog.at_level(logging.WARNING):  # given: no line
        get_pipeline("waist-pendulum")(read_session(HA001_T5))
    assert not [r for r in caplog.records if "sensor height" in r.getMessage()]


def test_track_realtime_flag_equals_the_params_option(tmp_path, capsys):
    p = tmp_path / "rt.json"
    p.write_text(json.dumps({"options": {"realtime": True}}))
    assert main(["track", str(HA001_T5), "--realtime", "--out", str(tmp_path / "a"), "--json"]) == 0
    a = json.loads(capsys.readouterr().out)
    assert main(["track", str(HA001_T5), "--params", str(p), "--out", str(tmp_path / "b"), "--json"]) == 0
    b = json.loads(capsys.readouterr().out)
    assert b["distance_m"] == a["distance_m"]
    assert a["info"]["options"]["realtime"] is True and a["info"]["method"].startswith("alvarez-realtime")
    assert (tmp_path / "a" / "steps.csv").read_text() == (tmp_path / "b" / "steps.csv").read_text()
    # the foot pipeline and the PLL have no causal variant: one line, exit 2
    assert main(["track", str(HA001_T5), "--pipeline", "waist-pll", "--realtime", "--out", str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err
    assert "--realtime applies to the waist-pendulum pipeline only" in err and not (tmp_path / "c").exists()
