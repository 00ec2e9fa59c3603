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


def test_gait_all_pairs_each_visit_folders_feet_and_says_which_have_no_pair(tmp_path, capsys):
    study = tmp_path / "study"
    for user, visit, seed in ((8991, "visit1", 1), (8991, "visit2", 2), (8992, "visit1", 3)):
        for foot in ("left", "right"):
            _foot(study / f"P{user}" / visit / foot[0].upper(), foot, user, f"P{user}", visit, seed)
    _foot(study / "P8993" / "visit1" / "L", "left", 8993, "P8993", "visit1")  # one foot only
    capsys.readouterr()
    out = tmp_path / "res"
    assert main(["gait-all", str(study), "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "[4/4] P8993/visit1: no pair: 1 left and 0 right foot session(s)" in err, err
    pairs = pd.read_csv(out / "gait_pairs.csv", dtype=str)
    assert pairs["path"].tolist() == ["P8991/visit1", "P8991/visit2", "P8992/visit1", "P8993/visit1"]
    assert pairs["status"].tolist() == ["ok", "ok", "ok", "no_pair"]
    steps = pd.read_csv(out / "gait_steps.csv", dtype={"subject": str, "visit": str})
    assert list(steps.columns[:5]) == ["path", "session_left", "session_right", "subject", "visit"]
    assert list(dict.fromkeys(zip(steps["subject"], steps["visit"], strict=True))) == [
        ("P8991", "visit1"), ("P8991", "visit2"), ("P8992", "visit1")]
    # each pair's rows are gait's own tables of that pair, with the path in front
    visit2 = study / "P8991" / "visit2"
    assert main(["gait", str(visit2 / "L"), str(visit2 / "R"), "--out", str(tmp_path / "g")]) == 0
    one = pd.read_csv(tmp_path / "g" / "gait_bouts.csv", dtype={"subject": str, "visit": str})
    bouts = pd.read_csv(out / "gait_bouts.csv", dtype={"subject": str, "visit": str})
    mine = bouts[bouts["path"] == "P8991/visit2"].drop(columns="path").reset_index(drop=True)
    pd.testing.assert_frame_equal(mine, one, check_exact=True)  # C103: one float format (review R4)
    assert int(pairs.loc[1, "n_bouts"]) == len(one)
    # an existing output is replaced only with --force
    assert main(["gait-all", str(study), "--out", str(out)]) == 2
    assert main(["gait-all", str(study), "--out", str(out), "--force"]) == 0


def test_gait_all_without_any_pair_is_one_line_and_writes_nothing(tmp_path, capsys):
    """Decision B372."""
    _foot(tmp_path / "study" / "P8994" / "v1" / "L", "left", 8994)
    capsys.readouterr()
    out = tmp_path / "res"
    assert main(["gait-all", str(tmp_path / "study"), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: gait-all: ") and "no visit folder holds one left and one right" in err
    assert "P8994/v1: no pair: 1 left and 0 right" in err and "\n" not in err and "Traceback" not in err
    assert not out.exists()


def test_gait_all_on_a_missing_or_empty_root_is_one_line_and_writes_nothing(tmp_path, capsys):
    """B372 (closing checks): a ROOT that does not exist, and one with no session folder, are one line each, exit 2."""
    (tmp_path / "empty").mkdir()
    for root, said in ((tmp_path / "nope", "folder not found"), (tmp_path / "empty", "no session folders")):
        assert main(["gait-all", str(root), "--out", str(tmp_path / "out")]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and said in err
        assert not (tmp_path / "out").exists()
