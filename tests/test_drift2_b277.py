"""Decisions B277-B279 (session 32's clock fixes, left over): a simulated `--clock-drift-ppm 5000` session, on B264's
limit, is refused naming the drift, not "it stopped 1.55 s before" (B277: the limit read within 10 ppm); `run`
refuses a foot unit that died before the waist as `track` does (B278: B126's whole check); a refused cut last row
under `run` names `pdrlearn run BUNDLE SESSION --drop-partial-row`, not `pdrlearn track` (B279)."""

from __future__ import annotations

import json
import logging
import shutil

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.io.plasys import CLOCK_DRIFT_TOLERANCE_PPM, MAX_CLOCK_DRIFT_PPM, waist_clock_drift
from tests.test_clock_offset_e111 import RUN_BUNDLE


def _sim(user: int, length_m: float, **kw):
    from pdrlearn import sim

    logging.disable(logging.WARNING)
    try:  # users 6800-6819: session 32's drift2 range
        return sim.simulate("walk", user, length_m=length_m, rate_hz=50.0, **kw)
    finally:
        logging.disable(logging.NOTSET)


def _one_line(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


def test_the_limit_is_read_within_its_tolerance():
    limit = MAX_CLOCK_DRIFT_PPM * 1e-6
    assert waist_clock_drift((0.0, 309.26), (0.0, 309.26 * (1 + limit) + 1e-9)) is not None  # main: None
    over = (MAX_CLOCK_DRIFT_PPM + 2 * CLOCK_DRIFT_TOLERANCE_PPM) * 1e-6
    assert waist_clock_drift((0.0, 3600.0), (0.0, 3600.0 * (1 + over))) is None
    assert waist_clock_drift((0.0, 3600.0), (0.0, 3600.0 * (1 + 1.01 * limit))) is None  # B264's 1.01 x


def test_a_5000_ppm_session_is_refused_naming_the_drift(tmp_path, capsys):
    d = write_session(_sim(6800, 450, clock_drift_ppm=5000.0), tmp_path / "d5000")
    capsys.readouterr()
    assert main(["track", str(d), "--out", str(tmp_path / "refused")]) == 2
    err = _one_line(capsys)
    assert "clock drift" in err and "--clock-drift-ppm 5000`" in err, err  # main: "it stopped 1.55 s before"
    assert "stopped" not in err.split("--")[0], err
    assert not (tmp_path / "refused").exists()
    assert main(["track", "--no-plot", str(d), "--clock-drift-ppm", "5000", "--out", str(tmp_path / "given")]) == 0
    got = json.loads((tmp_path / "given" / "summary.json").read_text())
    clean = write_session(_sim(6800, 450), tmp_path / "clean")  # the same walk, one clock
    assert main(["track", "--no-plot", str(clean), "--out", str(tmp_path / "clean_out")]) == 0
    ref = json.loads((tmp_path / "clean_out" / "summary.json").read_text())
    assert got["common_span_cut_s"] == 0.0 and got["distance_m"] == pytest.approx(ref["distance_m"], rel=1e-3)


def test_run_refuses_a_foot_unit_that_died_before_the_waist(tmp_path, capsys):
    intact = write_session(_sim(6801, 60), tmp_path / "intact")
    d = tmp_path / "footdead"
    shutil.copytree(intact, d)
    for f in d.glob("f*.csv"):  # every foot file kept to its first 60 % of rows: a dead battery
        lines = f.read_text().splitlines(keepends=True)
        f.write_text("".join(lines[:int(len(lines) * 0.6)]))
    capsys.readouterr()
    assert main(["run", str(RUN_BUNDLE), str(d), "--out", str(tmp_path / "refused")]) == 2  # main: runtime's lag line
    err = _one_line(capsys)
    assert "the tracked foot unit covers" in err and "stopped" in err and "(decision B126)" in err, err
    assert f"`pdrlearn run {RUN_BUNDLE} {d} --common-span`" in err and "pdrlearn track" not in err, err
    assert not (tmp_path / "refused").exists()
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(d), "--common-span", "--out", str(tmp_path / "cut")]) == 0
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(intact), "--out", str(tmp_path / "intact_run")]) == 0


def test_a_cut_last_row_names_the_command_that_was_run(tmp_path, capsys):
    d = write_session(_sim(6802, 40), tmp_path / "dead")
    acc = d / "fAccelerometer.csv"
    text = acc.read_text()
    acc.write_text(text[:text.rindex(",") - 3])  # the last row cut inside its y value: two cells
    capsys.readouterr()
    assert main(["run", str(RUN_BUNDLE), str(d), "--out", str(tmp_path / "r")]) == 2
    err = _one_line(capsys)
    assert f"`pdrlearn run {RUN_BUNDLE} {d} --drop-partial-row`" in err and "pdrlearn track" not in err, err  # main
    assert main(["track", str(d), "--out", str(tmp_path / "t")]) == 2
    assert f"`pdrlearn track {d} --drop-partial-row`" in _one_line(capsys)  # track's line as before (B266)
