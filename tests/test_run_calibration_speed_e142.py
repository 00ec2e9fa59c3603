"""Decision E142: ``pdrlearn run`` of a waist bundle gives W211's calibration-speed line (on by default, as
``track``; PARAMS.json ``"options": {"speed_check": false}`` turns it off), read from the calibration the bundle
holds; a bundle from a calibration before W211 (no ``cadence_range_spm``) uses its median cadence for both ends, one
from before W140 (no ``gait``) is not judged. It had given W140's option line only (W141)."""

from __future__ import annotations

import json

import pytest

from tests.test_waist_calibration_speed_w211 import _walk


def _w211(summary: dict) -> list[str]:
    return [w for w in summary["info"].get("warnings", []) if "decision W211" in w]


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.waist.calibration import calibrate

    tmp = tmp_path_factory.mktemp("e142")
    cal = json.loads(calibrate([_walk(1.0, 1)], "waist-pendulum", distances=[12.0]).save(tmp / "p.json").read_text())
    return tmp, cal, {v: write_session(_walk(v, 2), tmp / f"walk{v}") for v in (1.0, 2.0)}


def _run(tmp, params: dict, name: str, walk, capsys) -> dict:
    from pdrlearn.cli import main
    from pdrlearn.export.waist import export_waist

    (tmp / f"{name}.json").write_text(json.dumps(params))
    export_waist(tmp / f"{name}.json", tmp / f"wb_{name}")
    assert main(["run", "--no-plot", str(tmp / f"wb_{name}"), str(walk), "--out", str(tmp / f"r_{name}"),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert json.loads((tmp / f"r_{name}" / "summary.json").read_text())["info"]["warnings"] == out["info"]["warnings"]
    return out


def test_run_warns_at_another_speed_and_not_at_the_calibrations(setup, capsys):
    tmp, cal, walks = setup
    (line,) = _w211(_run(tmp, cal, "new", walks[2.0], capsys))
    assert "waist-pendulum calibration's" in line and "calibrate SLOW NORMAL FAST" in line
    assert not _w211(_run(tmp, cal, "same", walks[1.0], capsys))
    assert not _w211(_run(tmp, {**cal, "options": {"speed_check": False}}, "off", walks[2.0], capsys))


def test_an_old_bundle_is_read_as_track_reads_an_old_calibration(setup, capsys):
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist

    tmp, cal, walks = setup
    pre_w211 = {**cal, "gait": {k: v for k, v in cal["gait"].items() if k != "cadence_range_spm"}}
    (line,) = _w211(_run(tmp, pre_w211, "pre_w211", walks[2.0], capsys))
    assert f"{cal['gait']['median_cadence_spm']:.0f} steps/min" in line  # the median, both ends
    offline = track_waist(read_session(walks[2.0]), pipeline="waist-pendulum", params=str(tmp / "pre_w211.json"),
                          realtime=True)
    assert [w for w in offline.info["warnings"] if "decision W211" in w] == [line]  # the same line as track's
    assert not _w211(_run(tmp, {k: v for k, v in cal.items() if k != "gait"}, "pre_w140", walks[2.0], capsys))


def test_gait_check_gives_w140s_line_instead_when_both_fire():
    from pdrlearn.waist.plausibility import calibration_line

    gait = {"median_cadence_spm": 100.0, "cadence_range_spm": [100.0, 100.0]}
    w140 = calibration_line(gait, 150.0, 30, "waist-pendulum", gait_check=True)
    assert "decision W140" in w140 and "decision W211" not in w140
    assert "decision W211" in calibration_line(gait, 150.0, 30, "waist-pendulum")
    assert "decision W211" in calibration_line(gait, 120.0, 30, "waist-pendulum", gait_check=True)  # inside W140's
    assert calibration_line(gait, 150.0, 30, "waist-pendulum", speed_check=False) is None
