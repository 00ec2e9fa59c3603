"""Decisions B273-B276 (session 32 new-user trial): sessions.csv's `common_span_cut_s` counts the seconds of the WALK
the track does not cover - a foot unit whose battery died read 0.0 although the waist went on 135.6 s (B273), and
`track`, `track-all`, `run` and `info` give the same number; `run` refuses a drifting pair as `track` does (B274);
`run` takes `--drop-partial-row` (B276)."""

from __future__ import annotations

import json
import logging
import re
import shutil

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.units import walk_ends


def test_the_walk_is_both_units_recordings_when_they_are_apart():
    assert walk_ends({"foot": (0.0, 200.0), "waist": (0.0, 335.6)}) == (0.0, 335.6)  # the foot's battery died
    assert walk_ends({"foot": (0.0, 335.6), "waist": (0.0, 200.0)}) == (0.0, 335.6)  # the waist's
    assert walk_ends({"foot": (0.0, 100.0), "waist": (0.0, 100.4)}) == (0.0, 100.0)  # within B126's 1 s: the foot's
    assert walk_ends({"waist": (1.0, 50.0)}) == (1.0, 50.0)
    drift = {"foot": (0.0, 300.0), "waist": (0.0, 301.5)}  # a waist clock 5000 ppm fast
    assert walk_ends(drift) == (0.0, 301.5)
    moved = walk_ends(drift, {"offset_s": 0.0, "drift": 5e-3, "source": "given"})  # the drift given: one walk
    assert moved == pytest.approx((0.0, 300.0))


def _sim(user: int, length_m: float, **kw):
    from pdrlearn import sim

    logging.disable(logging.WARNING)
    try:
        return sim.simulate("walk", user, length_m=length_m, rate_hz=50.0, **kw)
    finally:
        logging.disable(logging.NOTSET)


def _cut(folder, prefix: str, keep: float) -> None:
    """Every file of one unit kept to its first ``keep`` of rows (a dead battery)."""
    for f in folder.glob(f"{prefix}*.csv"):
        lines = f.read_text().splitlines(keepends=True)
        f.write_text("".join(lines[:int(len(lines) * keep)]))


def _span(f) -> float:
    t = pd.read_csv(f)["timestamp"]
    return (t.iloc[-1] - t.iloc[0]) / 1000.0


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """User 6750's walk intact, with the foot unit dead at 60 % of it and with the waist unit dead there."""
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("b273")
    write_session(_sim(6750, 60), root / "intact")
    for name, prefix in (("footdead", "f"), ("waistdead", "w")):
        shutil.copytree(root / "intact", root / name)
        _cut(root / name, prefix, 0.6)
    return root


def _lost(folder) -> float:
    return abs(_span(folder / "fAccelerometer.csv") - _span(folder / "wAccelerometer.csv"))


def test_track_all_counts_the_walk_lost_by_either_dead_unit(batch, tmp_path):
    assert main(["track-all", "--no-plot", str(batch), "--common-span", "--out", str(tmp_path / "o")]) == 0
    rows = pd.read_csv(tmp_path / "o" / "sessions.csv").set_index("path")
    assert rows.loc["intact", "common_span_cut_s"] == 0.0
    assert _lost(batch / "footdead") > 10
    for name in ("footdead", "waistdead"):  # main: footdead 0.0 (the tracked foot itself lost nothing)
        assert rows.loc[name, "common_span_cut_s"] == pytest.approx(_lost(batch / name), abs=0.05), name


def test_track_run_and_info_give_the_same_number(batch, tmp_path, capsys):
    from tests.test_clock_offset_e111 import RUN_BUNDLE

    d = batch / "footdead"
    assert main(["track", "--no-plot", str(d), "--common-span", "--out", str(tmp_path / "t")]) == 0
    tracked = json.loads((tmp_path / "t" / "summary.json").read_text())["common_span_cut_s"]
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(d), "--common-span", "--out", str(tmp_path / "r")]) == 0
    ran = json.loads((tmp_path / "r" / "summary.json").read_text())["common_span_cut_s"]
    capsys.readouterr()
    assert main(["info", str(d)]) == 0
    said = re.search(r"common_span_cut_s then reads the ([\d.]+) s of the walk not tracked", capsys.readouterr().err)
    assert said, "info names the number"
    assert tracked == pytest.approx(_lost(d), abs=0.05) and ran == pytest.approx(tracked, abs=0.02)
    assert float(said.group(1)) == pytest.approx(tracked, abs=0.01)
    # the waist tracked alone covers the whole walk: nothing lost
    assert main(["track", "--no-plot", str(d), "--units", "waist", "--out", str(tmp_path / "w")]) == 0
    assert json.loads((tmp_path / "w" / "summary.json").read_text())["common_span_cut_s"] == 0.0


@pytest.fixture(scope="module")
def drift(tmp_path_factory):
    """User 6751, 350 m with a waist clock 4000 ppm fast: the ends 1.16 s apart (B264)."""
    from pdrlearn.io import write_session

    return write_session(_sim(6751, 350, clock_drift_ppm=4000.0), tmp_path_factory.mktemp("b274") / "drift")


def test_run_refuses_a_drifting_pair_as_track_does(drift, tmp_path, capsys):
    from tests.test_clock_offset_e111 import RUN_BUNDLE

    capsys.readouterr()
    assert main(["run", str(RUN_BUNDLE), str(drift), "--out", str(tmp_path / "refused")]) == 2  # main: 0, no word
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "clock drift" in err and "--clock-drift-ppm 4000" in err, err
    assert "pdrlearn run " in err and "pdrlearn track" not in err and "--units foot" in err, err
    assert not (tmp_path / "refused").exists()
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(drift), "--clock-drift-ppm", "4000", "--out",
                 str(tmp_path / "g")]) == 0
    assert json.loads((tmp_path / "g" / "summary.json").read_text())["common_span_cut_s"] == 0.0  # one walk


def test_a_drift_cut_counts_the_overhang_and_a_given_drift_none(drift, tmp_path):
    assert main(["track", "--no-plot", str(drift), "--common-span", "--out", str(tmp_path / "c")]) == 0
    cut = json.loads((tmp_path / "c" / "summary.json").read_text())["common_span_cut_s"]
    assert cut == pytest.approx(_lost(drift), abs=0.05) and cut > 1.0  # main: 0.0
    assert main(["track", "--no-plot", str(drift), "--clock-drift-ppm", "4000", "--out", str(tmp_path / "g")]) == 0
    assert json.loads((tmp_path / "g" / "summary.json").read_text())["common_span_cut_s"] == 0.0


def test_run_drops_a_partial_row_with_the_option(tmp_path, capsys):
    from pdrlearn.io import write_session
    from tests.test_clock_offset_e111 import RUN_BUNDLE

    d = write_session(_sim(6752, 40), tmp_path / "dead")
    for f in d.glob("[fw]*.csv"):  # every file ends at the same row; fAccelerometer's cut inside it
        f.write_text(f.read_text()[:-1])  # no line break after the last row
    acc = d / "fAccelerometer.csv"
    text = acc.read_text()
    acc.write_text(text[:text.rindex(",") - 3])  # the last row cut inside its y value: two cells
    capsys.readouterr()
    assert main(["run", str(RUN_BUNDLE), str(d), "--out", str(tmp_path / "refused")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--drop-partial-row" in err, err
    assert main(["run", "--no-plot", str(RUN_BUNDLE), str(d), "--drop-partial-row", "--out", str(tmp_path / "o")]) == 0
    assert "(--drop-partial-row, decision B266)" in capsys.readouterr().err


def test_columns_heading_names_the_table(capsys):
    """Decision W306: `pdrlearn columns periods` heads its table, not track-all's."""
    capsys.readouterr()
    assert main(["columns", "periods"]) == 0
    assert capsys.readouterr().out.splitlines()[0] == "# Columns of periods.csv"  # main: "track-all's tables"
    assert main(["columns"]) == 0
    assert "track-all's tables" not in capsys.readouterr().out.splitlines()[0]
