"""Decision B267 (trial s32 finding 8): `track-all --common-span` cut a march whose waist unit died at half of it
to half, with no table column saying so - sessions.csv's `common_span_cut_s` now gives the seconds of the tracked
unit's recording the cut took (0 for an intact session) - and `pdrlearn info` warns when the units' spans differ."""

from __future__ import annotations

import logging
import shutil

import pandas as pd
import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """A walk (user 6382) twice: intact, and with the waist files cut to their first 60 % (a dead waist battery)."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("b267")
    logging.disable(logging.WARNING)
    try:
        write_session(sim.simulate("walk", 6382, length_m=60, rate_hz=50.0), root / "intact")
    finally:
        logging.disable(logging.NOTSET)
    shutil.copytree(root / "intact", root / "wbat")
    for f in (root / "wbat").glob("w*.csv"):
        lines = f.read_text().splitlines(keepends=True)
        f.write_text("".join(lines[:int(len(lines) * 0.6)]))
    return root


def _span(f) -> float:
    t = pd.read_csv(f)["timestamp"]
    return (t.iloc[-1] - t.iloc[0]) / 1000.0


def test_sessions_csv_counts_the_seconds_cut(batch, tmp_path):
    assert main(["track-all", "--no-plot", str(batch), "--common-span", "--out", str(tmp_path / "o")]) == 0
    rows = pd.read_csv(tmp_path / "o" / "sessions.csv").set_index("path")
    foot, waist = _span(batch / "wbat" / "fAccelerometer.csv"), _span(batch / "wbat" / "wAccelerometer.csv")
    assert rows.loc["intact", "common_span_cut_s"] == 0.0
    assert rows.loc["wbat", "common_span_cut_s"] == pytest.approx(foot - waist, abs=0.05)  # main: no column
    assert rows.loc["wbat", "time_span_s"] + rows.loc["wbat", "common_span_cut_s"] == pytest.approx(foot, abs=0.05)


def test_info_warns_when_the_units_spans_differ(batch, capsys):
    capsys.readouterr()
    assert main(["info", str(batch / "wbat")]) == 0
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if "decision B267" in ln]
    assert len(lines) == 1 and "the waist unit stopped" in lines[0] and "--common-span" in lines[0], err
    assert main(["info", str(batch / "intact")]) == 0
    assert "B267" not in capsys.readouterr().err
