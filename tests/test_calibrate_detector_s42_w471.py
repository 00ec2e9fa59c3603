"""Decision W471 (session 42): ``pdrlearn calibrate --detector NAME`` fits the lower-back step length (and a gain
model's gain) on a waist step detector's contacts - a built-in or a registered / plug-in one, the names ``track
--detector`` takes; PARAMS.json records the detector, and ``track`` says in one line when it tracks with another."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.steps import DETECTORS, PLLStepDetector, get_detector, register_detector
from pdrlearn.track.waist import calibrated_detector_line, track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.params import WaistParams, load_params

USER = 11792  # this helper's simulated users: 11790-11799
METRES = 20.0


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """One short simulated straight walk, as `pdrlearn simulate --route` writes it."""
    d = tmp_path_factory.mktemp("w471") / "walk"
    assert main(["simulate", "--route", f"stand:3, straight:{METRES:g}, stand:3", "--user-seed", str(USER),
                 "--seed", "0", "--out", str(d)]) == 0
    return d


@pytest.fixture(scope="module")
def files(walk, tmp_path_factory):
    """PARAMS.json calibrated on the pipeline's own contacts (Python) and on pll's (the CLI, with the gain model)."""
    from pdrlearn.io import read_session

    root = tmp_path_factory.mktemp("w471p")
    own = calibrate([read_session(walk)], "waist-pendulum", distances=[METRES]).save(root / "own.json")
    assert main(["calibrate", str(walk), "-d", f"{METRES:g}", "--detector", "pll", "--length-model", "weinberg",
                 "--out", str(root / "pll.json")]) == 0
    return {"own": own, "pll": root / "pll.json"}


@pytest.fixture(scope="module")
def session(walk):
    from pdrlearn.io import read_session

    return read_session(walk)


def _w471(result) -> list[str]:
    return [w for w in result.info["warnings"] if "W471" in w]


def test_the_file_records_the_detector_and_tracking_with_it_gives_the_known_distance(session, files):
    own, pll = load_params(files["own"]), load_params(files["pll"])
    assert own.detector is None and pll.detector == "pll"
    assert pll.k != own.k and "weinberg" in pll.length_models  # fitted on other contacts
    assert any("--detector pll" in n and "W471" in n for n in pll.notes)
    for length_model in (None, "weinberg"):  # W21 / W460: the tracker's sum over the calibration walk
        r = track_waist(session, pipeline="waist-pendulum", params=str(files["pll"]), detector="pll",
                        length_model=length_model)
        assert r.distance_m == pytest.approx(METRES, rel=1e-3) and not _w471(r)


def test_track_says_when_it_tracks_with_another_detector(session, files):
    r = track_waist(session, pipeline="waist-pendulum", params=str(files["pll"]))
    (line,) = _w471(r)
    assert line.startswith("the parameters were calibrated on the contacts of --detector pll; this track takes the "
                           "pipeline's own") and "track with --detector pll" in line
    r = track_waist(session, pipeline="waist-pendulum", params=str(files["own"]), detector="pll")
    (line,) = _w471(r)
    assert "calibrated on the pipeline's own contacts; this track takes --detector pll's" in line
    assert "calibrate DIR -d METRES --detector pll --out PARAMS.json" in line
    assert not _w471(track_waist(session, pipeline="waist-pendulum", params=str(files["own"])))


def test_the_same_detector_with_the_same_settings_is_no_line():
    assert calibrated_detector_line(None, None) is None
    assert calibrated_detector_line("pll", get_detector("pll")) is None
    assert calibrated_detector_line("pll:loop_hz=1", get_detector("pll:loop_hz=1.0")) is None  # 1 == 1.0
    assert calibrated_detector_line("pll:loop_hz=1", get_detector("pll")) is not None
    assert calibrated_detector_line("pll", None) is not None and calibrated_detector_line(None, get_detector("pll"))


def test_cli_prints_the_detector_and_refuses_foot_unknown_and_bad_ones_in_one_line(walk, files, tmp_path, capsys):
    d = json.loads(files["pll"].read_text())
    assert d["detector"] == "pll" and d["pipeline"] == "waist-pendulum"
    for spec, said in (("accel", "calibrate: --detector accel detects the foot's strides"),
                       ("nosuch", "unknown step detector 'nosuch'"),
                       ("pll:loop_hz=abc", "pll: loop_hz='abc' is not a number")):
        assert main(["calibrate", str(tmp_path / "none"), "-d", "20", "--detector", spec,
                     "--out", str(tmp_path / "p.json")]) == 2
        err = capsys.readouterr().err
        assert err.startswith("error: ") and said in err and len(err.splitlines()) == 1, err
        assert not (tmp_path / "p.json").exists()
    p = tmp_path / "bad.json"
    p.write_text(json.dumps({**WaistParams().to_dict(), "detector": 5}))
    with pytest.raises(DataError, match=r"detector 5 is not a step detector's name.*W471"):
        load_params(p)


def test_a_registered_detector_calibrates_and_the_help_names_the_detectors(walk, tmp_path, capsys):
    class PllW471(PLLStepDetector):
        name = "pll-w471"

    register_detector("pll-w471", PllW471)
    try:
        assert main(["calibrate", str(walk), "-d", f"{METRES:g}", "--detector", "pll-w471:loop_hz=1.0",
                     "--out", str(tmp_path / "p.json")]) == 0
        out = capsys.readouterr().out
        assert "on the contacts of --detector pll-w471:loop_hz=1.0" in out
        assert load_params(tmp_path / "p.json").detector == "pll-w471:loop_hz=1.0"
        assert main(["calibrate", "--help"]) == 0
        text = " ".join(capsys.readouterr().out.replace("│", " ").split())
        assert "pelvic-gyro, pll, waist-ic, pll-w471 (waist steps)" in text and "W471" in text
    finally:
        DETECTORS._items.pop("pll-w471", None)
