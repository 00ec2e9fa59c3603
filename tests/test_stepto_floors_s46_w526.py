"""Decision W526 (trial T1 F3): a run of the lower back's W108 climb rows that turns back by a climb (1.5 m) is two
climbs, cut at its turn - a short step-to return flight whose stand and turn at the top hold no step counts one floor
up and one down, not one direction (whichever the noise's sign gave)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.kernels.barometer import STAIR_CLIMB_MIN_M, climb_turn_pieces
from pdrlearn.track.evaluate import _climb_parts, count_floors_by_climb


def test_pieces_cut_at_each_turn_of_a_climb():
    up, down = [0.15] * 12, [-0.15] * 12
    assert climb_turn_pieces(up + down) == [(0, 12), (12, 24)]
    assert climb_turn_pieces(up + down + up) == [(0, 12), (12, 24), (24, 36)]
    assert climb_turn_pieces(down) == [(0, 12)]
    # a first row rising a little before a descent: the extreme is not 1.5 m from the start, no cut
    assert climb_turn_pieces([0.01] + down) == [(0, 13)]
    # turns under W108's least climb are the climb's own sway
    assert climb_turn_pieces([0.15] * 5 + [-0.15] * 5) == [(0, 10)]
    assert STAIR_CLIMB_MIN_M == 1.5
    assert climb_turn_pieces([]) == []


def _waist_flight(seed: int) -> pd.DataFrame:
    """A step-to return flight on the lower back: 24 steps up alternating ~0.03 / ~0.15 m, then 24 down, every row
    inside one run of W108's climb rows (no step at the top), barometric noise 0.02 m."""
    rng = np.random.default_rng(seed)
    rise = np.tile([0.03, 0.14], 12)
    dz = np.concatenate([rise, -rise]) + rng.normal(0.0, 0.02, 48)
    return pd.DataFrame({"unit": "waist", "climb": True, "dz_m": dz, "pause_dz_m": 0.0})


def test_an_adjacent_up_and_down_flight_count_one_floor_each():
    for seed in range(5):
        steps = _waist_flight(seed)
        parts = _climb_parts(steps)
        assert set(parts[2][:24]) == {1} and set(parts[2][24:]) == {-1}
        assert count_floors_by_climb(steps["dz_m"].to_numpy(float), 3.0, bridge=8, parts=parts) == (1, 1, 0)


def test_t1_step_to_return_flight_on_the_lower_back(tmp_path):
    # trial T1 F3's session (user 4602): main read floors up 1 / down 0, end floor +1
    s, out = tmp_path / "stairs", tmp_path / "w"
    assert main(["simulate", "--route", "stand:3, straight:4, up:12:0.17:0.28:step-to-step:left, stand:3, turn:180, "
                 "down:12:0.17:0.28:step-to-step:right, straight:4, stand:3", "--step-length", "0.42", "--step-time",
                 "0.7", "--step-time-asymmetry", "0.25", "--step-length-asymmetry", "0.2", "--stance-time-asymmetry",
                 "0.15", "--paretic-side", "right", "--bounce", "pendulum", "--user-seed", "4602", "--rate", "100",
                 "--out", str(s)]) == 0
    assert main(["track", str(s), "--units", "waist", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert (summary["floors_up"], summary["floors_down"], summary["storeys_changed"]) == (1, 1, 0)
    # decision W527: its steps on the stairs (24 each way) counted from the climbs (main: 8 / 8)
    assert summary["n_stair_strides_up"] >= 20 and summary["n_stair_strides_down"] >= 20
