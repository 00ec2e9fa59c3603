"""Decisions E163 / L422: track-all writes one pooled strides.csv with the session, the foot, turn_deg and is_turn."""

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    root = tmp_path_factory.mktemp("pooled") / "study"
    for user, route, foot in ((8107, "stand:2, straight:6, turn:180, straight:6, stand:2", "right"),
                              (8108, "stand:2, straight:8, stand:2", "left")):
        s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100.0, seed=user,
                          instrumented_foot=foot)
        write_session(s, root / f"u{user}")
    out = tmp_path_factory.mktemp("pooled_out") / "o"
    assert main(["track-all", "--no-plot", str(root), "--out", str(out)]) == 0
    return out


def test_track_all_writes_one_strides_table_with_the_session_and_foot(batch):
    pooled = pd.read_csv(batch / "strides.csv")
    per = {p: pd.read_csv(batch / p / "steps.csv") for p in ("u8107", "u8108")}
    assert len(pooled) == sum(len(s) for s in per.values())
    assert list(pooled.columns[:7]) == ["path", "visit", "session", "subject", "foot", "turn_deg", "is_turn"]  # C100
    assert undocumented("strides.csv", pooled.columns) == []
    for p, steps in per.items():
        mine = pooled[pooled["path"] == p].reset_index(drop=True)
        assert (mine["foot"] == ("right" if p == "u8107" else "left")).all()
        assert np.allclose(mine["length_m"], steps["length_m"])
        assert np.allclose(mine["turn_deg"], np.degrees(steps["turn_angle_rad"]), equal_nan=True)
    walk = pooled[pooled["path"] == "u8107"]
    turn = pd.read_csv(batch / "u8107" / "turns.csv")
    assert len(turn) == 1 and walk["is_turn"].sum() >= 1
    # the strides flagged carry the turn: their turn_deg sums to most of it, the others turn little
    assert abs(walk.loc[walk["is_turn"], "turn_deg"].sum()) > 0.8 * abs(turn["angle_deg"].iloc[0])
    assert (walk.loc[~walk["is_turn"], "turn_deg"].abs() < 30).all()
    assert not pooled.loc[pooled["path"] == "u8108", "is_turn"].any()


def test_turn_membership_takes_half_of_either_span():
    from pdrlearn.track.pooled import turn_membership

    turns = pd.DataFrame({"start_s": [10.0], "end_s": [12.0]})
    got = turn_membership([8.0, 9.2, 10.5, 11.4, 12.0, 9.0], [9.0, 10.4, 11.5, 12.6, 13.0, 13.0], turns)
    assert got.tolist() == [False, False, True, True, False, True]
