"""Decisions C109 / C110 (session 36, trial T4 finding 7): `pdrlearn gait`'s tables carry the pair's ids
(both sessions, subject, visit) and `foot` beside `side`; `gait-all ROOT` pairs each visit folder's two feet.
Simulated users 8990-8999 only."""

from __future__ import annotations

import pandas as pd

from pdrlearn.cli import main

ROUTE = "stand:2, straight:10, stand:2"


def _foot(folder, foot, user, subject=None, visit=None, seed=1):
    args = ["simulate", "--route", ROUTE, "--user-seed", str(user), "--seed", str(seed), "--rate", "50",
            "--foot", foot, "--out", str(folder)]
    args += ["--subject", subject] if subject else []
    args += ["--visit", visit] if visit else []
    assert main(args) == 0


def test_gait_tables_carry_the_pairs_ids_and_foot(tmp_path, capsys):
    _foot(tmp_path / "L", "left", 8990, "P8990", "visit1")
    _foot(tmp_path / "R", "right", 8990, "P8990", "visit1")
    capsys.readouterr()
    assert main(["gait", str(tmp_path / "L"), str(tmp_path / "R"), "--out", str(tmp_path / "g")]) == 0
    for name in ("gait_steps.csv", "gait_cycles.csv", "gait_bouts.csv"):
        t = pd.read_csv(tmp_path / "g" / name, dtype={"subject": str, "visit": str})
        assert list(t.columns[:4]) == ["session_left", "session_right", "subject", "visit"], name
        assert len(t) and set(t["subject"]) == {"P8990"} and set(t["visit"]) == {"visit1"}, name
        assert t["session_left"].iloc[0] != t["session_right"].iloc[0]
        if "side" in t:  # kept for existing readers, with strides.csv's name beside it
            assert t["foot"].tolist() == t["side"].tolist() and set(t["foot"]) == {"left", "right"}
