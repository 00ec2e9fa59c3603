"""Decisions B264, B265: two units whose clocks drift apart (the ends differ in proportion to the duration, the
starts together) are refused naming the drift in ppm and `--clock-drift-ppm N` first - not "it stopped 1.74 s
before the waist unit" - and `track --clock-drift-ppm` moves the waist clock with `--clock-offset`'s mechanism
(E111's `move_waist_clock`). Trial s32 finding 5: a 200 ppm drift over 2.28 h was refused as a unit stopped early."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.io.plasys import MAX_CLOCK_DRIFT_PPM, waist_clock_drift, waist_clock_offset
from pdrlearn.sim import simulate


def test_drift_is_told_from_a_shift_and_from_a_unit_that_stopped():
    # the trial's 2.28 h march, 0.1 s + 200 ppm: the offset rule (B243) does not see it, the drift rule does
    foot, waist = (0.0, 8196.65), (0.10, 8198.39)
    assert waist_clock_offset(foot, waist) is None
    offset, drift = waist_clock_drift(foot, waist)
    assert drift * 1e6 == pytest.approx(200, abs=15) and offset == pytest.approx(0.10)
    assert waist_clock_drift((0.0, 600.0), (0.0, 598.8))[1] * 1e6 == pytest.approx(-2000)  # a waist clock slow
    assert waist_clock_drift((0.0, 100.0), (2.0, 102.8)) is None  # a shift with 0.8 s of drift: B243's case
    assert waist_clock_drift((0.0, 1919.0), (0.0, 3838.0)) is None  # a foot battery dead at half the walk
    assert waist_clock_drift((0.0, 3600.0), (0.0, 3600.0 * (1 + 1.01 * MAX_CLOCK_DRIFT_PPM * 1e-6))) is None
    assert waist_clock_drift((0.0, 3600.0), (0.0, 3600.5)) is None  # within B21's 1 s: no refusal anyway


def _walk(ppm: float):
    logging.disable(logging.WARNING)
    try:  # user 6380 (the range of session 32's clock fix); the motion is the same, only the waist clock differs
        return simulate("walk", 6380, length_m=450, rate_hz=50.0, clock_drift_ppm=ppm)
    finally:
        logging.disable(logging.NOTSET)


@pytest.fixture(scope="module")
def sessions(tmp_path_factory):
    root = tmp_path_factory.mktemp("b264")
    return write_session(_walk(0.0), root / "clean"), write_session(_walk(4000.0), root / "drift")


def _track(args, out) -> dict:
    assert main(["track", "--no-plot", *args, "--out", str(out)]) == 0
    return json.loads((out / "summary.json").read_text())


def test_a_drift_is_refused_naming_it_and_tracked_with_the_option(sessions, capsys, tmp_path):
    clean, drift = sessions
    capsys.readouterr()
    assert main(["track", str(drift), "--out", str(tmp_path / "refused")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert "clock drift" in err and "--clock-drift-ppm 4000`" in err, err  # main: "it stopped 1.2 s before"
    assert err.index("--clock-drift-ppm") < err.index("--common-span"), err
    assert not (tmp_path / "refused").exists()
    ref = _track([str(clean)], tmp_path / "clean")
    got = _track([str(drift), "--clock-drift-ppm", "4000"], tmp_path / "given")
    assert got["info"]["unit_alignment"] == {"offset_s": 0.0, "drift": pytest.approx(4e-3), "source": "given"}
    assert got["distance_m"] == pytest.approx(ref["distance_m"], rel=1e-3)
    assert abs(got["final_position_error_m"] - ref["final_position_error_m"]) < 0.5


def test_bad_drift_values_are_one_line(sessions, capsys, tmp_path):
    clean, _ = sessions
    for args, says in ((["--clock-drift-ppm", "nan"], "finite number"),
                       (["--clock-drift-ppm", "200", "--align-units"], "drop one of them"),
                       (["--clock-drift-ppm", "200", "--pipeline", "waist-pendulum"], "--clock-drift-ppm")):
        capsys.readouterr()
        assert main(["track", str(clean), *args, "--out", str(tmp_path / "x")]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and says in err, err



@pytest.fixture(scope="module")
def slow(tmp_path_factory):
    """A waist clock 4000 ppm slow: the waist ends first, refused by B21's cover check (`run`, and `track`'s waist
    heading), not by B126's."""
    return write_session(_walk(-4000.0), tmp_path_factory.mktemp("b264s") / "slow")


@pytest.mark.parametrize("command", ["track", "run"])
def test_a_slow_waist_clock_is_named_by_b21s_check_too(slow, command, capsys, tmp_path):
    from tests.test_clock_offset_e111 import RUN_BUNDLE

    args = ["track", "--no-plot", str(slow)] if command == "track" else ["run", "--no-plot", str(RUN_BUNDLE), str(slow)]
    capsys.readouterr()
    assert main([*args, "--out", str(tmp_path / "refused")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--clock-drift-ppm -4000`" in err and "slow" in err, err
    assert main([*args, "--clock-drift-ppm", "-4000", "--out", str(tmp_path / "o")]) == 0
    info = json.loads((tmp_path / "o" / "summary.json").read_text())["info"]
    assert info["unit_alignment"]["drift"] == pytest.approx(-4e-3)



def test_info_names_the_drift(sessions, capsys):
    _, drift = sessions
    capsys.readouterr()
    assert main(["info", str(drift)]) == 0
    err = capsys.readouterr().err
    assert "clock drift, decision B264" in err and "--clock-drift-ppm 4000`" in err, err  # B269: track's words
