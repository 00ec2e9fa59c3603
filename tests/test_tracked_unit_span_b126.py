"""Decisions B126 / B127 (trial `stats` findings 1 and 4): a foot unit that stops early while the waist goes on
is refused, not tracked "ok" over part of the walk; ``--window`` is checked against the tracked unit's recording;
``track`` / ``track-all --units foot`` keep the foot outcome of a session whose waist stopped early."""

from __future__ import annotations

import json
import shutil

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError


def _cut(folder, prefix: str, t_s: float) -> None:
    """Cut every ``prefix`` sensor file of ``folder`` at ``t_s`` (a unit whose battery ran out)."""
    for f in folder.glob(f"{prefix}*.csv"):
        df = pd.read_csv(f)
        df[df.iloc[:, 0] <= t_s * 1e3].to_csv(f, index=False)


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn import sim
    from pdrlearn.io import write_session

    d = tmp_path_factory.mktemp("b126")
    write_session(sim.simulate("walk", 5, length_m=60), d / "whole")
    foot_short = d / "foot_short"
    shutil.copytree(d / "whole", foot_short)
    _cut(foot_short, "f", 25.0)
    waist_short = d / "waist_short"
    shutil.copytree(d / "whole", waist_short)
    _cut(waist_short, "w", 20.0)
    return d


def test_a_foot_unit_that_stopped_early_is_refused_naming_the_ways_out(walk, tmp_path, capsys):
    capsys.readouterr()
    assert main(["track", str(walk / "foot_short"), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and not (tmp_path / "t").exists()
    assert "the tracked foot unit covers 0.00-25.00 s" in err and "stopped" in err and "before the waist" in err
    assert "--common-span" in err and "--units waist" in err and "B126" in err
    # the time both cover, as the refusal says; and the waist alone covers the whole walk
    assert main(["track", "--no-plot", str(walk / "foot_short"), "--common-span", "--out", str(tmp_path / "c")]) == 0
    assert main(["track", "--no-plot", str(walk / "foot_short"), "--units", "waist", "--out", str(tmp_path / "w")]) == 0
    assert json.loads((tmp_path / "w" / "summary.json").read_text())["pipeline"] == "waist-pendulum"


def test_the_window_is_checked_against_the_tracked_unit(walk, tmp_path, capsys):
    from pdrlearn.io import read_session
    from pdrlearn.track.window import check_window

    session = read_session(walk / "foot_short")
    assert check_window((5.0, 30.0), session) == pytest.approx((5.0, 30.0))  # the session: the waist's 40 s
    # decision B242: a window ending past the tracked unit's recording is clipped to it (one warning line)
    assert check_window((5.0, 30.0), session, "foot") == pytest.approx((5.0, 25.0))
    with pytest.raises(DataError, match="outside the recording, which lasts 25.00 s \\(the tracked foot unit's"):
        check_window((26.0, 30.0), session, "foot")
    capsys.readouterr()
    assert main(["track", "--no-plot", str(walk / "foot_short"), "--units", "foot", "--window", "26,30",
                 "--out", str(tmp_path / "t")]) == 2
    assert "which lasts 25.00 s (the tracked foot unit's" in capsys.readouterr().err


def test_units_foot_keeps_the_foot_outcome_of_a_session_whose_waist_stopped(walk, tmp_path, capsys):
    capsys.readouterr()
    assert main(["track", str(walk / "waist_short"), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "--common-span" in err and "--units foot (decision B127)" in err  # the refusal names both (B83, B127)
    assert main(["track", "--no-plot", str(walk / "waist_short"), "--units", "foot", "--out", str(tmp_path / "f")]) == 0
    assert main(["track", "--no-plot", str(walk / "whole"), "--units", "foot", "--out", str(tmp_path / "w")]) == 0
    cut, whole = (json.loads((tmp_path / n / "summary.json").read_text()) for n in ("f", "w"))
    assert cut["distance_m"] == pytest.approx(whole["distance_m"], rel=1e-9) and cut["distance_m"] > 50
    root = tmp_path / "study"
    shutil.copytree(walk / "waist_short", root / "S01" / "v2")
    assert main(["track-all", "--no-plot", str(root), "--units", "foot", "--out", str(tmp_path / "all")]) == 0
    row = pd.read_csv(tmp_path / "all" / "sessions.csv").iloc[0]
    assert row["status"] == "ok" and row["distance_m"] == pytest.approx(whole["distance_m"], rel=1e-9)


@pytest.mark.parametrize(("units", "says"), [("knee", "expected foot, waist or foot,waist"),
                                              ("waist", "has no waist unit")])
def test_bad_units_is_one_line(walk, tmp_path, capsys, units, says):
    folder = tmp_path / "foot_only"
    shutil.copytree(walk / "whole", folder)
    for f in folder.glob("w*.csv"):
        f.unlink()
    capsys.readouterr()
    assert main(["track", str(folder), "--units", units, "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip()
    assert says in err and len(err.splitlines()) == 1
