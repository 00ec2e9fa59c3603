"""Decision B243: a waist clock seconds off (both units' spans the same length, shifted) is refused with the offset
named first - `--clock-offset SECONDS`, the fix that keeps the whole walk - before the ways that cut data
(`--common-span`, `--units`), by `track` (B126's check) and `run` (B21's) alike. The trial (session 29, finding 7):
a waist clock 2 s late was refused with a hint to cut data only; `--clock-offset 2` tracked it (450.59 m, -0.17 %)."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.io.plasys import waist_clock_offset
from pdrlearn.sim import simulate
from tests.test_clock_offset_e111 import RUN_BUNDLE
from tests.test_unit_clocks import _shifted


def test_a_shift_is_told_from_a_late_start_or_stop():
    assert waist_clock_offset((0.0, 100.0), (2.0, 102.8)) == 2.0  # shifted, 0.8 s of drift
    assert waist_clock_offset((0.0, 100.0), (-3.0, 97.5)) == -3.0  # a waist clock early
    assert waist_clock_offset((0.0, 100.0), (2.0, 100.0)) is None  # started late, stopped together: no shift
    assert waist_clock_offset((0.0, 100.0), (0.0, 60.0)) is None  # stopped early
    assert waist_clock_offset((0.0, 100.0), (0.5, 100.5)) is None  # within B21's 1 s: no refusal anyway


@pytest.fixture(scope="module")
def late(tmp_path_factory):
    logging.disable(logging.WARNING)
    try:
        walk = simulate("walk", 5220, length_m=30, rate_hz=50.0)
    finally:
        logging.disable(logging.NOTSET)
    return write_session(_shifted(walk, 2.0), tmp_path_factory.mktemp("b243") / "late")


@pytest.mark.parametrize("command", ["track", "run"])
def test_the_refusal_names_the_clock_offset_first(late, command, capsys, tmp_path):
    args = ["track", "--no-plot", str(late)] if command == "track" else ["run", "--no-plot", str(RUN_BUNDLE), str(late)]
    capsys.readouterr()
    assert main([*args, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert "--clock-offset 2.00`" in err and "waist clock 2.00 s late" in err, err  # main: no --clock-offset
    assert err.index("--clock-offset 2.00") < err.index("--common-span"), err
    assert main([*args, "--clock-offset", "2.00", "--out", str(tmp_path / "given")]) == 0  # the named fix works
