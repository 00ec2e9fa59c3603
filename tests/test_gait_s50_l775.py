"""Decision L775 (session 50, FI, trial s50t2 finding F6): the foot track's ``raw_dz_m`` (the stride's height before
L39's level rule) and ``gait``'s ramp kind, behind the ``ramps`` keyword (measured, not adopted: off by default)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bilateral import bilateral_gait, label_steps, stride_ramp

USER = dataclasses.replace(UserProfile.from_seed(17700), step_length_m=0.5, step_time_s=0.6)  # the trial's slow steps
ROUTE = parse_route("stand:1, straight:3, slope:8:8.33, straight:2, stand:1")  # 1:12, 0.083 m a 1 m stride


@pytest.fixture(scope="module")
def walk():
    return {f: simulate_path(ROUTE, USER, rate_hz=20, seed=1, noise=False, stand_s=1.0, instrumented_foot=f)
            for f in ("left", "right")}


def test_stride_ramp_needs_three_strides_of_one_sign_over_the_bound_l775():
    t = pd.DataFrame({"raw_dz_m": [0.0, 0.09, 0.085, 0.09, 0.0, 0.09, -0.09, 0.09, 0.03, 0.03, 0.03, 0.0]})
    np.testing.assert_array_equal(stride_ramp(t), [0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0])
    down = pd.DataFrame({"raw_dz_m": [-0.05, -0.06, -0.05, -0.05]})
    assert stride_ramp(down).all()
    stairs = np.array(["flat", "up", "up", "up"], dtype=object)  # a flight's rows (L603) are no ramp, and end a run
    assert not stride_ramp(pd.DataFrame({"raw_dz_m": [0.09, 0.34, 0.34, 0.34]}), stairs).any()
    label = pd.DataFrame({"height_m": [0.17, 0.34, 0.34, 0.09], "kind": ["walk", "stairs_up", "stairs_up", "walk"]})
    assert not stride_ramp(label).any()  # the simulator's stair entry stride stays a stair step's neighbour
    assert not stride_ramp(pd.DataFrame({"dz_m": [0.09] * 5})).any()  # an older track without raw_dz_m: none


def test_ramp_strides_leave_the_level_headline_only_with_the_keyword_l775(walk):
    labels = [label_steps(walk[f]) for f in ("left", "right")]
    off, on = bilateral_gait(*labels), bilateral_gait(*labels, ramps=True)
    # decision L789: the reference takes stairs from the simulator's kind, so S3's "up" labels of a ramp are level
    assert "ramp" not in off["by_kind"] and "stairs_up" not in off["by_kind"]
    assert off["by_kind"]["level"]["n_steps_left"] >= on["by_kind"]["level"]["n_steps_left"] + 6
    assert "stairs_up" not in on["by_kind"] and on["by_kind"]["ramp"]["n_steps_left"] >= 6
    assert not on["stairs"]  # no stair flight read from a ramp
    ramp_ics = {f: walk[f].steps.loc[walk[f].steps["height_m"] >= 0.06, "ic_s"].to_numpy() for f in walk}
    level = on["steps"][on["steps"]["kind"] == "level"]
    assert all(np.min(np.abs(ramp_ics[r.side] - r.ic_s)) > 0.1 for r in level.itertuples())


def test_the_foot_track_writes_the_ramp_height_l39_zeroes_l775(walk):
    from pdrlearn.track.plasys import track_plasys

    st = track_plasys(walk["left"], toe_off=True, transfers=False).steps
    up = st["raw_dz_m"].to_numpy() > 0.06
    assert up.sum() >= 6 and (st["dz_m"].to_numpy()[up] == 0).all()  # L39 levels them; raw_dz_m keeps them
    assert stride_ramp(st).sum() >= 6
