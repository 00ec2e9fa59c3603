"""Decision W506 (session 45, L648's leftover): a TUG turns about in front of the chair before it sits, a turn in which
the lower back sees no step (W331), so a slow (2.5-4 s) sit can start more than L648's 5 s after the last contact;
the sit side's 5 s are counted from the end of that turn."""
from __future__ import annotations

import functools
import json

import pandas as pd
import pytest

import pdrlearn.waist.transfers as T
from pdrlearn.cli import main

#: trial T1's TUG command at 2.5-4 s transfers; user 12748's sit starts beyond 5 s after its last contact
TUG = ["simulate", "--route", "straight:3, turn:180, straight:3, turn:180", "--sit-start", "5", "--sit-end", "5",
       "--stand", "0.5", "--transfer-time", "2.5:4", "--step-length", "0.4", "--step-time", "0.7", "--bounce",
       "pendulum", "--rate", "100", "--user-seed", "12748"]


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    d = tmp_path_factory.mktemp("w506")
    assert main([*TUG, "--out", str(d / "s")]) == 0
    truth = pd.read_csv(d / "s" / "transfers.csv")
    return d, (truth["seated_ms"].iloc[-1] - truth["rise_ms"].iloc[0]) / 1000.0  # 28.71 s


def _tug_time(d, out):
    assert main(["track", "--no-plot", str(d / "s"), "--units", "waist", "--out", str(d / out)]) == 0
    return json.loads((d / out / "summary.json").read_text())["tug_time_s"]


def test_the_sit_after_the_turn_in_front_of_the_chair_is_read(sim):
    d, true_s = sim
    assert _tug_time(d, "t") == pytest.approx(true_s, abs=1.0)
    rows = pd.read_csv(d / "t" / "transfers.csv")
    assert list(rows["kind"]) == ["sit-to-stand", "stand-to-sit"]


def test_without_the_turn_the_sit_is_missed(sim, monkeypatch):
    d, _ = sim
    # W555 (session 48) off too: its upright standstill also covers the turn, which is upright
    monkeypatch.setattr(T, "with_slow_edges", functools.partial(T.with_slow_edges, final_turn=False,
                                                                 standstill=False))
    assert _tug_time(d, "l648") is None  # L648 alone: the sit starts over 5 s after the last contact
