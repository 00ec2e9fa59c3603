"""Decision E94: ``--detector NAME:key=value,...`` sets a step detector's settings, as ``--length-model`` does (one
parser, :func:`pdrlearn.plugins.from_spec`); an unknown setting is one line naming the valid ones, exit 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.steps import PLLStepDetector, get_detector
from pdrlearn.waist.lengths import get_step_length

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
WAIST = REAL / "mobgap_HA001_Test5_Trial1"


def test_get_detector_takes_the_length_models_spec():
    det = get_detector("pll:loop_hz=1.0,damping=0.5")
    assert isinstance(det, PLLStepDetector)
    assert det.get_params()["loop_hz"] == 1.0 and det.get_params()["damping"] == 0.5
    assert get_detector("pll", loop_hz=1.0).get_params()["loop_hz"] == 1.0  # Python keywords as before


@pytest.mark.parametrize("get, spec, valid", [(get_detector, "pll:lop_hz=1", "loop_hz"),
                                              (get_step_length, "weinberg:kk=0.4", "k")])
def test_an_unknown_setting_is_one_line_naming_the_valid_ones(get, spec, valid):
    with pytest.raises(DataError) as e:
        get(spec)
    msg = str(e.value)
    assert "\n" not in msg and f"(did you mean '{valid}'?)" in msg
    assert valid in msg.split("its settings are ")[1].split(" (")[0].split(", ")


@pytest.mark.parametrize("spec, said", [("pll:loop_hz=1.0zz", "loop_hz='1.0zz' is not a number"),
                                         ("accel:rests_only=no", "rests_only='no' is not true or false"),
                                         ("accel:order=2.5", "order=2.5 is not a whole number")])
def test_a_text_value_for_a_number_or_flag_is_one_line(spec, said):
    """It had been stored as text: ``rests_only='no'`` is truthy, ``loop_hz='1.0zz'`` a TypeError in the detection."""
    with pytest.raises(DataError, match=said):
        get_detector(spec)
    assert get_detector("pll:f_max_hz=none,placement=waist").get_params()["f_max_hz"] is None  # None, text: taken


def test_steps_cli_detector_settings_reach_the_detector(capsys):
    assert main(["steps", str(WAIST), "--detector", "pll:loop_hz=1.0", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    want = PLLStepDetector(loop_hz=1.0).detect(read_session(WAIST))
    assert got["count"] == len(want)
    assert main(["steps", str(WAIST), "--detector", "pll", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] != got["count"]  # the setting changed the detections


def test_track_cli_detector_settings_change_the_track(tmp_path, capsys):
    n = {}
    for spec in ("pll", "pll:loop_hz=1.0"):
        assert main(["track", "--no-plot", str(WAIST), "--detector", spec,
                     "--out", str(tmp_path / spec.replace(":", "_")),
                     "--json"]) == 0
        n[spec] = json.loads(capsys.readouterr().out)["n_steps"]
    assert n["pll"] != n["pll:loop_hz=1.0"]


@pytest.mark.parametrize("command", ["steps", "track", "track-all"])
def test_cli_bad_detector_setting_is_one_line_exit_2(command, tmp_path, capsys):
    args = [command, str(WAIST if command != "track-all" else REAL), "--detector", "pll:lop_hz=1"]
    if command != "steps":
        args += ["--out", str(tmp_path / "o")]
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "did you mean 'loop_hz'?" in err and "its settings are" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("spec, said", [("pll:loop_hz=1,loop_hz=2", "setting 'loop_hz' is given twice"),
                                        (":loop_hz=1", "no name before ':'")])
def test_a_repeated_setting_or_no_name_is_one_line(spec, said):
    """Decision B200: the second of two values had silently won; ':x=1' had read as an unknown detector ''."""
    with pytest.raises(DataError, match=said):
        get_detector(spec)
    with pytest.raises(DataError, match=said.replace("loop_hz", "k")):
        get_step_length(spec.replace("pll", "weinberg").replace("loop_hz", "k"))
