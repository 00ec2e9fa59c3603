"""A windowed track's freeze episodes and chair transfers: one filter, freezes clipped at the window's edges
(decision L272)."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.sim import Freeze, Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.window import window_episodes


@pytest.fixture(scope="module")
def frozen_dir(tmp_path_factory):
    from pdrlearn.io import write_session

    route = [Stand(2.0), Straight(8.0), Freeze(10.0, 5.0, 10.0), Straight(8.0), Stand(2.0)]  # review S29 item 2
    s = simulate_path(route, UserProfile.from_seed(4812), rate_hz=100, seed=4812, bounce="pendulum")
    d = tmp_path_factory.mktemp("frz") / "s"
    write_session(s, d)
    return d


def _track(d, out, *args):
    from pdrlearn.cli import main

    assert main(["track", "--no-plot", str(d), "--out", str(out), *args]) == 0
    return pd.read_csv(out / "freezes.csv"), json.loads((out / "summary.json").read_text())


def test_foot_window_before_the_freeze_has_none(frozen_dir, tmp_path):
    whole, _ = _track(frozen_dir, tmp_path / "all")
    assert len(whole) == 1 and whole["start_s"].iloc[0] > 8.0  # the episode lies after the window below
    table, summary = _track(frozen_dir, tmp_path / "w", "--window", "0,8")
    assert len(table) == 0 and summary["n_freezes"] == 0 and summary["freeze_time_s"] == 0


def test_foot_window_clips_an_episode_crossing_its_edge(frozen_dir, tmp_path):
    whole, _ = _track(frozen_dir, tmp_path / "all")
    a, b = float(whole["start_s"].iloc[0]), float(whole["end_s"].iloc[0])
    cut = round(0.5 * (a + b), 1)
    table, summary = _track(frozen_dir, tmp_path / "w", "--window", f"0,{cut}")
    assert len(table) == 1
    assert table["start_s"].iloc[0] == pytest.approx(a) and table["end_s"].iloc[0] == pytest.approx(cut)
    assert summary["freeze_time_s"] == pytest.approx(cut - a)


def test_window_episodes_clips_or_keeps_whole():
    rows = [{"start_s": 1.0, "end_s": 3.0, "duration_s": 2.0}, {"start_s": 4.0, "end_s": 8.0, "duration_s": 4.0},
            {"start_s": 11.0, "end_s": 12.0, "duration_s": 1.0}]
    assert window_episodes(rows, 2.0, 10.0, clip=False) == [rows[1]]
    assert window_episodes(rows, 2.0, 10.0, clip=True) == [{"start_s": 2.0, "end_s": 3.0, "duration_s": 1.0},
                                                           rows[1]]
    assert window_episodes(None, 0.0, 1.0, clip=True) is None
