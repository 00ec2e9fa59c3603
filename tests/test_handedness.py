"""Mirrored data (one axis negated in both the accelerometer and the gyroscope) declared with a right-handed
frame: D10 cannot see it (its inference builds left = up x forward); the gyroscope-vs-accelerometer test
does (decision D11). ``pdrlearn info`` runs the D10 and D11 checks and prints their results."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.handedness import MIN_LOG_RATIO, foot_handedness, session_handedness, waist_handedness
from pdrlearn.io.session import Stream
from pdrlearn.signal.filters import interp_rows
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
FOOT = ROOT / "datasets" / "real" / "gaitmap_level_left"
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _mirrored_copy(src: Path, dst: Path, prefix: str, axis: str) -> Path:
    """The recording with ``axis`` negated in its unit's accelerometer and gyroscope, meta.json unchanged."""
    shutil.copytree(src, dst)
    for name in ("Accelerometer", "Gyroscope"):
        f = dst / f"{prefix}{name}.csv"
        df = pd.read_csv(f)
        df[axis] = -df[axis]
        df.to_csv(f, index=False)
    return dst


def _warnings(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_mirrored_foot_recording_warns_once_naming_the_files_and_the_fix(tmp_path, caplog, axis):
    d = _mirrored_copy(FOOT, tmp_path / "m", "f", axis)
    s = read_session(d)
    with caplog.at_level(logging.WARNING):
        s.require_frame("foot")
        s.require_frame("foot")
    msgs = [m for m in _warnings(caplog) if "mirrored" in m]
    assert len(msgs) == 1, _warnings(caplog)
    m = msgs[0]
    assert str(d) in m and "fAccelerometer.csv" in m and "fGyroscope.csv" in m
    assert "left-handed" in m and "negate that axis back" in m and "D11" in m


def test_truthful_foot_and_waist_recordings_do_not_warn(caplog):
    for d, p in ((FOOT, "foot"), (WAIST, "waist")):
        s = read_session(d)
        with caplog.at_level(logging.WARNING):
            s.require_frame(p)
    assert not [m for m in _warnings(caplog) if "D11" in m]


def test_the_statistic_flips_sign_under_mirroring_and_is_clear_on_real_foot_data():
    s = read_session(FOOT)
    h = session_handedness(s, "foot")
    assert h.segments >= 20 and h.log_ratio > 1.5 and h.verdict == "right-handed"  # measured +3.15 over 33
    a, g = s["fAccelerometer"], s["fGyroscope"]
    acc, gyr = a.values.copy(), interp_rows(a.t, g.t, g.values)
    acc[:, 1] *= -1
    gyr[:, 1] *= -1
    m = foot_handedness(acc, gyr, a.rate_hz)
    assert m.log_ratio == pytest.approx(-h.log_ratio, abs=1e-6) and m.verdict == "mirrored"


@pytest.mark.parametrize("rate", [20.0, 100.0])
def test_simulated_foot_verdict_does_not_depend_on_the_rate(rate):
    s = simulate("A", 2, "normal", rate_hz=rate)
    h = session_handedness(s, "foot")
    assert h.verdict == "right-handed" and h.log_ratio > -MIN_LOG_RATIO
    for name in ("fAccelerometer", "fGyroscope"):
        st = s.streams[name]
        s.streams[name] = Stream(name, st.t, st.values * [1.0, 1.0, -1.0])
    assert session_handedness(s, "foot").verdict == "mirrored"


def test_a_standstill_gives_no_verdict():
    h = session_handedness(simulate("standstill", 0), "foot")
    assert h.segments == 0 and h.verdict == "unsure" and not h.mirrored


def test_the_waist_test_is_measured_but_never_warns(tmp_path, caplog):
    """Not adopted (docs/frames.md): truthful simulated waists score below zero."""
    d = _mirrored_copy(WAIST, tmp_path / "w", "w", "y")
    s = read_session(d)
    with caplog.at_level(logging.WARNING):
        s.require_frame("waist")
    assert not [m for m in _warnings(caplog) if "D11" in m]
    h = s.handedness("waist")
    assert h.verdict == "not tested" and not h.mirrored and h.log_ratio < 0
    acc, gyr = s["wAccelerometer"].values, s["wGyroscope"].values
    assert waist_handedness(acc, gyr, 100.0).log_ratio == pytest.approx(h.log_ratio)


def test_info_prints_the_frame_and_handedness_checks(capsys):
    assert main(["info", str(FOOT)]) == 0
    out, err = capsys.readouterr()
    line = [ln for ln in out.splitlines() if ln.startswith("foot axes:")]
    assert len(line) == 1, out
    assert "source_project frame" in line[0] and "not contradicted by the data (D10)" in line[0]
    assert "handedness (D11): right-handed" in line[0] and "strides" in line[0]
    assert "warning" not in err


def test_info_json_has_the_checks_and_prints_the_warning_once(tmp_path, capsys):
    d = _mirrored_copy(FOOT, tmp_path / "m", "f", "y")
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    chk = json.loads(out)["frame_checks"]["foot"]
    assert chk["source"] == "source_project" and chk["check"] == "ok"
    assert chk["frame"] == {"x": "forward", "y": "left", "z": "up"}
    assert chk["handedness"]["verdict"] == "mirrored" and chk["handedness"]["segments"] >= 20
    lines = [ln for ln in err.splitlines() if ln.startswith("warning:")]
    assert len(lines) == 1 and "mirrored" in lines[0] and str(d) in lines[0], err


def test_info_prints_a_d10_contradiction(tmp_path, capsys):
    d = tmp_path / "f"
    shutil.copytree(FOOT, d)
    meta = json.loads((d / "meta.json").read_text())
    meta["frames"] = {"foot": {"x": "backward", "y": "right", "z": "up"}}  # a wrong 180-degree yaw
    (d / "meta.json").write_text(json.dumps(meta))
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    chk = json.loads(out)["frame_checks"]["foot"]
    assert chk["source"] == "declared" and "contradicts its data" in chk["check"]
    assert sum("contradicts its data" in ln for ln in err.splitlines()) == 1
