"""Decision B241: the "no per-user calibration", height and leg-length lines depend on whether the parameters hold
calibration values, not on whether a parameters file was given (an options-only ``--params`` kept them silent)."""

from __future__ import annotations

from pdrlearn.io import Session
from pdrlearn.waist.params import NO_SENSOR_HEIGHT, default_params, resolve_params


def _lines(params) -> list[str]:
    return resolve_params(Session(name="s", meta={}), params)[1]


def _kinds(lines: list[str]) -> set[str]:
    return {k for k, p in (("calibration", "no per-user calibration"), ("height", "meta.json gives no subject height"),
                           ("leg", NO_SENSOR_HEIGHT)) if any(w.startswith(p) for w in lines)}


def test_an_options_only_params_file_keeps_the_default_lines(tmp_path):
    f = tmp_path / "sv.json"
    f.write_text('{"options": {"stand_veto": true}}')
    assert _kinds(_lines(None)) == {"calibration", "height", "leg"}
    assert _kinds(_lines(str(f))) == {"calibration", "height", "leg"}
    assert _kinds(_lines({"options": {"integrate_end": True}})) == {"calibration", "height", "leg"}


def test_calibration_values_silence_what_they_replace():
    cal = default_params(Session(name="c", meta={"height_m": 1.8, "sensor_height_m": 1.0}))[0].to_dict()
    cal["source"] = "calibrated"
    assert _kinds(_lines(cal)) == set()
    pendulum = {"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated", "pipeline": "waist-pendulum"}
    assert _kinds(_lines(pendulum)) == set()  # its unused frequency line filled in: no line, as before
    leg_only = {"leg_m": 0.95}  # a leg length given, the step-length line still the height's default
    assert _kinds(_lines(leg_only)) == {"calibration", "height"}


def test_calibrate_does_not_warn_that_its_own_walks_are_uncalibrated(tmp_path):
    """B241 (session 28 fresh-clone demo): `calibrate` tracks its walks with the defaults to make the calibration;
    the "no per-user calibration" line is not said of them."""
    import subprocess
    import sys
    from pathlib import Path

    walk = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"
    r = subprocess.run([sys.executable, "-m", "pdrlearn", "calibrate", str(walk), "--pipeline", "waist-pendulum",
                        "--out", str(tmp_path / "p.json")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-1000:]
    assert "no per-user calibration" not in r.stderr
    assert "decision W169" in r.stderr  # the short walk's own line stays
