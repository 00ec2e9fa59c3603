"""Decision B230: a waist clock 2 s late (more than B21's 1 s of cover) given by ``--clock-offset`` is moved before the
cover checks of ``run`` (B21) and ``track`` (B126), and ``run``'s refusal names ``run``'s own ``--common-span`` (the
trial, session 28, finding 6: it named ``pdrlearn track --common-span``, an option ``run`` lacked)."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate
from tests.test_clock_offset_e111 import RUN_BUNDLE, _same_track
from tests.test_unit_clocks import _shifted


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    """A fresh simulated two-unit walk (user 4041), clean and with the waist clock reading 2 s late."""
    logging.disable(logging.WARNING)
    try:
        walk = simulate("walk", 4041, length_m=30, rate_hz=50.0)
    finally:
        logging.disable(logging.NOTSET)
    root = tmp_path_factory.mktemp("cover")
    return write_session(walk, root / "clean"), write_session(_shifted(walk, 2.0), root / "late")


def test_run_refuses_a_late_waist_naming_its_own_options(folders, capsys):
    _, late = folders
    capsys.readouterr()
    assert main(["run", str(RUN_BUNDLE), str(late)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert "`pdrlearn run --common-span`" not in err  # decision B278: B126's line, the command with its arguments
    assert f"`pdrlearn run {RUN_BUNDLE} {late} --common-span`" in err and "pdrlearn track" not in err  # main: track's
    assert f"`pdrlearn run {RUN_BUNDLE} {late} --clock-offset 2.00`" in err, err  # B243's offset first, as track's


def test_run_with_the_offset_given_replays_a_2_s_late_waist(folders, tmp_path, capsys):
    clean, late = folders
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(clean), "--out", str(tmp_path / "clean")]) == 0
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(late), "--clock-offset", "2.0", "--out",
                 str(tmp_path / "given")]) == 0
    _same_track(tmp_path / "clean", tmp_path / "given")  # main: refused by B21 before the offset (exit 2)
    info = json.loads((tmp_path / "given" / "summary.json").read_text())["info"]
    assert info["unit_alignment"]["offset_s"] == 2.0


def test_run_common_span_cuts_as_track_does(folders, tmp_path, capsys):
    _, late = folders
    capsys.readouterr()
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(late), "--common-span", "--out", str(tmp_path / "cut")]) == 0
    assert "--common-span: cut to" in capsys.readouterr().err
    assert json.loads((tmp_path / "cut" / "run.json").read_text())["options"]["common_span"] is True


def test_track_with_the_offset_given_takes_a_2_s_late_waist(folders, tmp_path):
    clean, late = folders
    assert main(["track", "--no-plot", str(clean), "--out", str(tmp_path / "clean")]) == 0
    assert main(["track", "--no-plot", str(late), "--clock-offset", "2.0", "--out",
                 str(tmp_path / "given")]) == 0  # main: B126
    _same_track(tmp_path / "clean", tmp_path / "given")


def test_run_refuses_common_span_for_a_protocol_capture(tmp_path, capsys):
    capture = tmp_path / "c.txt"
    capture.write_text("")
    assert main(["run", str(RUN_BUNDLE), "--protocol", str(capture), "--common-span"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "drop --common-span" in err
