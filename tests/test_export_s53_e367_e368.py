"""Decisions E367 and E368 (trial s53t2 F10, F9): ``pdrlearn export CAL.json`` without ``--frame`` carries the frame
the calibration walks declared (a bundle the live tracker refused before); E107's line for the offline defaults is
the tracker's ``not_applied_live``, logged at DEBUG, not a warning of every ``WaistTracker(...)``."""

from __future__ import annotations

import dataclasses
import json
import logging

from pdrlearn.cli import main
from pdrlearn.export.waist import calibration_frame, declared_frame, export_waist
from pdrlearn.io.session import Session
from pdrlearn.runtime import WaistTracker, load_waist_bundle
from pdrlearn.waist.live import unapplied_options_line
from pdrlearn.waist.params import WaistParams

CAL = {"leg_m": 0.9, "k": 1.1, "f_m": 0.0, "source": "calibrated", "pipeline": "waist-pendulum", "rate_hz": 50.0}
BELT = {"x": "left", "y": "up", "z": "forward"}  # a phone upright in a belt clip at the front, screen out


def _cal(tmp_path, name="cal.json", **extra):
    p = tmp_path / name
    p.write_text(json.dumps({**CAL, **extra}))
    return p


def test_the_calibration_frame_goes_into_the_bundle(tmp_path, monkeypatch):
    # calibrate records the walks' frame when they all declare one (E367)
    walks = [Session(name=f"w{i}", meta={"frames": {"waist": BELT}}) for i in range(2)]
    assert declared_frame(walks) == BELT
    assert declared_frame([*walks, Session(name="o", meta={"frames": {"waist": {"x": "up", "y": "right",
                                                                                "z": "forward"}}})]) is None
    # the PARAMS.json's "frames"
    b = load_waist_bundle(export_waist(_cal(tmp_path, frames={"waist": BELT}), tmp_path / "b1"))
    assert b.manifest["frames"]["waist"] == BELT and b.rotation is not None
    assert WaistTracker(b, fs=50.0).position == (0.0, 0.0)  # the base refused: "has no waist axis frame"
    # a calibration written before E367: the meta.json of the walk its "fit" names, from the current folder
    (tmp_path / "walk").mkdir()
    (tmp_path / "walk" / "meta.json").write_text(json.dumps({"frames": {"waist": BELT}}))
    monkeypatch.chdir(tmp_path)
    old = _cal(tmp_path, "old.json", fit=["walk"])
    assert calibration_frame(old) == ("x=left,y=up,z=forward", "the meta.json of the calibration walk walk")
    assert load_waist_bundle(export_waist(old, tmp_path / "b2")).manifest["frames"]["waist"] == BELT
    # --frame still wins; a walk not found (or redacted) gives none
    b3 = load_waist_bundle(export_waist(old, tmp_path / "b3", frame="x=up,y=right,z=forward"))
    assert b3.manifest["frames"]["waist"]["x"] == "up"
    assert calibration_frame(_cal(tmp_path, "gone.json", fit=["nowhere"])) == (None, "")
    assert calibration_frame(_cal(tmp_path, "red.json", fit=["walk"], paths_redacted=True)) == (None, "")


def test_export_says_when_no_frame_is_known(tmp_path, capsys):
    assert main(["export", str(_cal(tmp_path)), "--out", str(tmp_path / "b")]) == 0
    err = capsys.readouterr().err
    assert "needs frame=" in err and "--frame x=left,y=up,z=forward" in err
    assert main(["export", str(_cal(tmp_path, "f.json", frames={"waist": BELT})), "--out", str(tmp_path / "c")]) == 0
    out, err = capsys.readouterr()
    assert "frame x=left,y=up,z=forward (from " in out and "needs frame=" not in err


def test_the_offline_defaults_line_is_debug_only_and_a_given_option_still_warned(tmp_path, caplog):
    b = load_waist_bundle(export_waist(_cal(tmp_path, frames={"waist": BELT}), tmp_path / "b"))
    assert "E107" in (b.manifest["not_applied_live"] or "") and not b.manifest["warnings"]
    with caplog.at_level(logging.DEBUG, logger="pdrlearn"):
        tr = WaistTracker(b, fs=50.0)
    assert 'sit_veto="opposite" (the offline default)' in tr.not_applied_live and not tr.warnings
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]
    assert [r for r in caplog.records if r.levelno == logging.DEBUG and "E107" in r.getMessage()]
    # a bundle exported before E368 holds the line among its warnings: the same
    legacy = dataclasses.replace(b, manifest={**b.manifest, "warnings": [unapplied_options_line(WaistParams())],
                                              "not_applied_live": None})
    caplog.clear()
    with caplog.at_level(logging.DEBUG, logger="pdrlearn"):
        tr = WaistTracker(legacy, fs=50.0)
    assert not tr.warnings and "E107" in tr.not_applied_live
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]
    # an option the calibration sets and the live tracker does not apply: still a warning, without the defaults
    g = load_waist_bundle(export_waist(_cal(tmp_path, "g.json", frames={"waist": BELT},
                                            options={"stairs_climb": True}), tmp_path / "g"))
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        tr = WaistTracker(g, fs=50.0)
    (line,) = [w for w in tr.warnings if "E107" in w]
    assert line.startswith("the option stairs_climb=true is not applied") and "(the offline default)" not in line
    assert [r for r in caplog.records if "stairs_climb=true" in r.getMessage()]
    assert "stairs_climb" not in tr.not_applied_live and "sit_veto" in tr.not_applied_live
