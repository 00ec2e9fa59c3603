"""Decision L534 (session 40, implementer I3): `track-all --ten-m-walk ACCEL,TIMED,DECEL` times every session's
10 m walk on the one walkway given, as `track --ten-m-walk` does one session's (L522): each session's summary.json
keys and ten_m_walk_trials.csv are `track`'s, sessions.csv has the ten_m_walk_* columns, run.json records the option.
Simulated users 10452-10453 on L522's 10 m walkway with 0.5 m of run-out."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main

ROUTE = "stand:3, straight:10.5, stand:3"
KEYS = ("ten_m_walk_time_s", "ten_m_walk_speed_mps", "ten_m_walk_note", "n_ten_m_walk_trials",
        "ten_m_walk_max_speed_mps", "ten_m_walk_zones_m")


@pytest.fixture(scope="module")
def walkway(tmp_path_factory):
    root = tmp_path_factory.mktemp("l534") / "root"
    for u in (10452, 10453):
        assert main(["simulate", "--route", ROUTE, "--user-seed", str(u), "--rate", "100",
                     "--out", str(root / f"u{u}")]) == 0
    return root


def test_track_all_times_every_session_on_the_walkway_given_l534(walkway, tmp_path):
    out = tmp_path / "all"
    assert main(["track-all", "--no-plot", str(walkway), "--ten-m-walk", "2,6,2", "--out", str(out)]) == 0
    assert main(["track", "--no-plot", str(walkway / "u10452"), "--ten-m-walk", "2,6,2", "--out",
                 str(tmp_path / "one")]) == 0
    batch = json.loads((out / "u10452" / "summary.json").read_text())
    one = json.loads((tmp_path / "one" / "summary.json").read_text())
    assert {k: batch[k] for k in KEYS} == {k: one[k] for k in KEYS}
    assert batch["ten_m_walk_zones_m"] == [2.0, 6.0, 2.0] and batch["ten_m_walk_time_s"] is not None
    assert (out / "u10452" / "ten_m_walk_trials.csv").read_text() == (tmp_path / "one" / "ten_m_walk_trials.csv"
                                                                        ).read_text()
    rows = pd.read_csv(out / "sessions.csv")
    assert rows["ten_m_walk_speed_mps"].notna().all() and len(rows) == 2  # both timed over the middle 6 m
    assert json.loads((out / "run.json").read_text())["options"]["ten_m_walk"] == "2,6,2"  # C18
    # without the option the 10.5 m walk is no 14 m walkway: not timed, the note names the option (L313, L522)
    assert main(["track-all", "--no-plot", str(walkway), "--out", str(tmp_path / "plain")]) == 0
    plain = pd.read_csv(tmp_path / "plain" / "sessions.csv")
    assert plain["ten_m_walk_speed_mps"].isna().all() and plain["ten_m_walk_note"].str.contains("--ten-m-walk").all()


def test_track_all_refuses_a_bad_walkway_in_one_line_before_any_session_l534(walkway, tmp_path, capsys):
    assert main(["track-all", str(walkway), "--ten-m-walk", "2,0,2", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--ten-m-walk 2,0,2: give the walkway" in err, err
    assert not (tmp_path / "o").exists()
