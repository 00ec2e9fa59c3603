"""Decision C181 (session 45): a corridor's laps end at the walker's cone turns only - a turn made seated or riding
(L622's ``carried``: a swivel chair's) ends no lap - and L645's final lap allows for the half cone turn it did not
walk, so a corridor whose cone turns are stepped round (their arcs in every lap between two turns) counts its last
lap as one on a short corridor too."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from experiments.turn_gaps_c180 import swivel
from pdrlearn.cli import main
from pdrlearn.track.corridor import corridor_laps

STEP_M, STEP_S, ARC_STEPS = 0.5, 1.0, 3  # a 12 m leg is 24 steps; each cone turn an arc of 3 steps (1.5 m)


def _corridor(laps: int, last_m: float = 12.0):
    """A lower-back step table up and down a 12 m corridor whose cone turns are arcs of ARC_STEPS steps, the final
    leg ``last_m`` long, and its turns table (each turn the arc's steps, 180 deg)."""
    n_leg = int(round(12.0 / STEP_M))
    legs = [n_leg] * (laps - 1) + [int(round(last_m / STEP_M))]
    lengths, turns, k = [], [], 0
    for i, n in enumerate(legs):
        lengths += [STEP_M] * n
        k += n
        if i < len(legs) - 1:
            turns.append({"start_s": k * STEP_S, "end_s": (k + ARC_STEPS) * STEP_S, "angle_deg": 180.0,
                          "carried": False})
            lengths += [STEP_M] * ARC_STEPS
            k += ARC_STEPS
    t = np.arange(len(lengths)) * STEP_S
    steps = pd.DataFrame({"start_s": t, "end_s": t + STEP_S, "event_s": t + STEP_S, "length_m": lengths,
                          "unit": "waist"})
    return steps, pd.DataFrame(turns)


def test_a_final_lap_to_the_cone_counts_on_a_round_the_cone_corridor():
    """Laps between two arcs' middles track 13.5 m, the final lap 12.75 m (half an arc): 94.4 % of a lap, under
    L645's 95 % before C181; with the half arc it did not walk, 100 %: 4 laps, 48 m."""
    steps, turns = _corridor(4)
    laps, out, _ = corridor_laps(steps, turns, 12.0)
    assert out["n_laps"] == 4 and out["walk_test_distance_m"] == pytest.approx(48.0)
    assert laps["tracked_m"].iloc[-1] == pytest.approx(12.75) and laps["tracked_m"].iloc[1] == pytest.approx(13.5)


def test_a_final_lap_two_metres_short_stays_partial():
    steps, turns = _corridor(4, last_m=10.0)
    laps, out, _ = corridor_laps(steps, turns, 12.0)
    assert out["n_laps"] == 3 and laps["corridor_laps"].iloc[-1] == 0
    assert laps["distance_m"].iloc[-1] == pytest.approx(10.75 * 12.0 / 13.5)  # L383's tracked x scale, unchanged


def test_a_carried_turn_ends_no_lap():
    """A 180 deg row marked carried in the middle of lap 3 (a swivel while seated): 4 laps; taken as the walker's
    (before C181) it split lap 3 into two half laps that L384's rounding counts as a lap each."""
    steps, turns = _corridor(4)
    lap3 = float(turns["end_s"].iloc[1]) + 12.0 * STEP_S  # 6 m into lap 3
    swivel = pd.DataFrame([{"start_s": lap3 - 0.2, "end_s": lap3 + 0.2, "angle_deg": 175.0, "carried": True}])
    table = pd.concat([turns, swivel], ignore_index=True).sort_values("start_s", ignore_index=True)
    assert corridor_laps(steps, table, 12.0)[1]["n_laps"] == 4
    assert corridor_laps(steps, table.assign(carried=False), 12.0)[1]["n_laps"] == 5


def test_a_simulated_swivel_on_a_corridor_is_carried_and_ends_no_lap(tmp_path):
    """User 12731, 4 laps of a 12 m corridor, a 20 s sit mid-lap 3 with a 180 deg swivel spliced into the seated yaw
    rate: turns.csv marks it carried, `track --corridor 12` counts 4 laps (5 before C181)."""
    from pdrlearn.io import read_session, write_session

    route = "straight:12, turn:180, straight:12, turn:180, straight:6, sit:20, straight:6, turn:180, straight:12"
    assert main(["simulate", "--route", route, "--user-seed", "12731", "--bounce", "pendulum", "--rate", "100",
                 "--stand", "3", "--out", str(tmp_path / "s")]) == 0
    tr = pd.read_csv(tmp_path / "s" / "transfers.csv")
    mid = 0.5 * (float(tr["seated_ms"].iloc[0]) + float(tr["rise_ms"].iloc[0])) / 1000.0
    write_session(swivel(read_session(tmp_path / "s"), mid - 5.0, mid + 5.0, 180.0), tmp_path / "w")
    assert main(["track", str(tmp_path / "w"), "--units", "waist", "--corridor", "12", "--no-plot", "--out",
                 str(tmp_path / "t")]) == 0
    turns = pd.read_csv(tmp_path / "t" / "turns.csv")
    seat = turns[(turns["start_s"] < mid) & (turns["end_s"] > mid)]
    assert len(seat) == 1 and bool(seat["carried"].iloc[0]) and abs(seat["angle_deg"].iloc[0]) >= 135
    assert json.loads((tmp_path / "t" / "summary.json").read_text())["n_laps"] == 4
