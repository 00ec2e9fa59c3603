"""Decisions E111-E112: `--clock-offset SECONDS` gives the waist unit's clock offset by hand (`track`, `track-all`,
`run`; one option object), removes it before tracking and records it as `info.unit_alignment`; a non-finite value,
`--align-units` beside it, or a session without a waist unit is one line, exit 2."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate
from tests.test_unit_clocks import _shifted

RUN_BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # foot + waist units


@pytest.fixture(scope="module")
def folders(tmp_path_factory):
    """The same simulated two-unit walk twice: clean, and with the waist clock reading 0.3 s late."""
    logging.disable(logging.WARNING)
    try:
        walk = simulate("walk", 3210, length_m=30, rate_hz=50.0)
    finally:
        logging.disable(logging.NOTSET)
    root = tmp_path_factory.mktemp("clock")
    return write_session(walk, root / "clean"), write_session(_shifted(walk, 0.3), root / "late")


def _tables(out: Path):
    return pd.read_csv(out / "steps.csv"), pd.read_csv(out / "trajectory.csv")


def _same_track(a: Path, b: Path) -> None:
    (sa, ta), (sb, tb) = _tables(a), _tables(b)
    assert list(sa.columns) == list(sb.columns) and len(sa) == len(sb) and len(ta) == len(tb)
    for col in sa.columns:
        if pd.api.types.is_numeric_dtype(sa[col]):
            np.testing.assert_allclose(sa[col].to_numpy(float), sb[col].to_numpy(float), atol=1e-6, err_msg=col)
        else:
            assert sa[col].fillna("").tolist() == sb[col].fillna("").tolist(), col
    np.testing.assert_allclose(ta[["t", "x", "y", "z"]].to_numpy(), tb[["t", "x", "y", "z"]].to_numpy(), atol=1e-6)


def _moved(a: Path, b: Path) -> float:
    ta, tb = (pd.read_csv(p / "trajectory.csv") for p in (a, b))
    return float(np.hypot(ta["x"].iloc[-1] - tb["x"].iloc[-1], ta["y"].iloc[-1] - tb["y"].iloc[-1]))


@pytest.mark.parametrize("extra", [[], ["--streaming"]], ids=["offline", "streaming"])
def test_track_with_the_offset_given_equals_the_clean_track(folders, tmp_path, capsys, extra):
    clean, late = folders
    assert main(["track", "--no-plot", str(clean), *extra, "--out", str(tmp_path / "clean")]) == 0
    assert main(["track", "--no-plot", str(late), *extra, "--out", str(tmp_path / "late")]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(late), *extra, "--clock-offset", "0.3", "--out",
                 str(tmp_path / "given")]) == 0
    err = capsys.readouterr().err
    assert "decision L161" not in err  # the units' steps together again
    _same_track(tmp_path / "clean", tmp_path / "given")
    assert _moved(tmp_path / "late", tmp_path / "clean") > 100 * _moved(tmp_path / "given", tmp_path / "clean")
    info = json.loads((tmp_path / "given" / "summary.json").read_text())["info"]
    assert info["unit_alignment"] == {"offset_s": 0.3, "drift": 0.0, "source": "given"}
    run = json.loads((tmp_path / "given" / "run.json").read_text())
    assert "0.3" in json.dumps(run) and "clock_offset" in json.dumps(run)


def test_run_with_the_offset_given_equals_the_clean_replay(folders, tmp_path, capsys):
    clean, late = folders
    for name, folder, extra in (("clean", clean, []), ("late", late, []), ("given", late, ["--clock-offset", "0.3"])):
        assert main(["run", "--no-plot", str(RUN_BUNDLE), str(folder), *extra, "--out", str(tmp_path / name)]) == 0
        err = capsys.readouterr().err
        assert ("decision L161" in err) == (name == "late"), name
    _same_track(tmp_path / "clean", tmp_path / "given")
    info = json.loads((tmp_path / "given" / "summary.json").read_text())["info"]
    assert info["unit_alignment"] == {"offset_s": 0.3, "drift": 0.0, "source": "given"}
    assert "unit_alignment" not in json.loads((tmp_path / "late" / "summary.json").read_text())["info"]


def test_track_all_takes_the_offset_for_every_session(folders, tmp_path, capsys):
    _, late = folders
    root = tmp_path / "study"
    write_session(__import__("pdrlearn.io", fromlist=["read_session"]).read_session(late), root / "S01")
    assert main(["track-all", "--no-plot", str(root), "--clock-offset", "0.3", "--out", str(tmp_path / "batch")]) == 0
    assert main(["track", "--no-plot", str(late), "--clock-offset", "0.3", "--out", str(tmp_path / "one")]) == 0
    _same_track(tmp_path / "batch" / "S01", tmp_path / "one")
    info = json.loads((tmp_path / "batch" / "S01" / "summary.json").read_text())["info"]
    assert info["unit_alignment"]["source"] == "given"


def test_the_estimate_says_its_source():
    """--align-units' record names its source beside the given offset's (E111)."""
    from pdrlearn.track.plasys import move_waist_clock

    logging.disable(logging.WARNING)
    try:
        walk = simulate("walk", 3211, length_m=10, rate_hz=50.0)
    finally:
        logging.disable(logging.NOTSET)
    lines: list[str] = []
    moved, info = move_waist_clock(_shifted(walk, 0.3), 0.3, 0.0, lines, source="estimated")
    assert info == {"offset_s": 0.3, "drift": 0.0, "source": "estimated"} and not lines
    np.testing.assert_allclose(moved.streams["wAccelerometer"].t, walk.streams["wAccelerometer"].t, atol=1e-12)
    _, info = move_waist_clock(walk, 2.0, 0.0, lines, source="given")  # 2 s of waist data before the foot's
    assert info["common_span_s"][0] == pytest.approx(walk.streams["fAccelerometer"].t[0], abs=0.05)
    (line,) = lines
    assert line.startswith("--clock-offset moved the waist clock by -2.00 s") and "decision L162" in line


@pytest.mark.parametrize("cmd, extra, words", [
    ("track", ["--clock-offset", "nan"], "--clock-offset nan: give the waist unit's clock offset in seconds"),
    ("track", ["--clock-offset", "inf"], "a finite number"),
    ("track", ["--clock-offset", "0.3", "--align-units"], "drop one of them"),
    ("track", ["--clock-offset", "0.3", "--units", "foot"], "has no waist unit"),
    ("track", ["--clock-offset", "0.3", "--pipeline", "waist-pendulum"], "--clock-offset applies to the plasys"),
    ("track-all", ["--clock-offset", "-inf"], "a finite number"),
    ("track-all", ["--clock-offset", "0.3", "--align-units"], "drop one of them"),
    ("run", ["--clock-offset", "nan"], "a finite number"),
    ("run", ["--clock-offset", "0.3", "--align-units"], "drop one of them"),
    ("run", ["--clock-offset", "0.3", "--units", "foot"], "has no waist unit"),
])
def test_bad_clock_offsets_are_one_line(folders, tmp_path, capsys, cmd, extra, words):
    _, late = folders
    target = ([str(RUN_BUNDLE), str(late)] if cmd == "run" else
              [str(late.parent)] if cmd == "track-all" else [str(late)])
    assert main([cmd, *target, *extra, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err, err
    assert not (tmp_path / "o").exists()


def test_run_refuses_the_offset_for_a_protocol_capture(tmp_path, capsys):
    capture = tmp_path / "c.txt"
    capture.write_text("")
    assert main(["run", str(RUN_BUNDLE), "--protocol", str(capture), "--clock-offset", "0.3"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "carries the foot unit only (one clock): drop --clock-offset" in err
