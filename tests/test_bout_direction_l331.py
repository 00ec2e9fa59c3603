"""Decision L331 (trial 31 finding 9): bouts.csv says each walking bout's direction - forward, backward or mixed -
and the fraction of its strides that travel backward, by the strides' own travelled direction (L203)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import BOUTS
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bouts import bout_direction, detected_bouts
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys


def _walk(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=3, scenario="route")


def test_track_writes_a_backward_bout_between_two_forward_ones(tmp_path):
    s = _walk("stand:2, straight:6, stand:2, backward:8, stand:2, straight:6, stand:2", 6500)
    write_session(s, tmp_path / "fsbf")
    assert main(["track", "--no-plot", str(tmp_path / "fsbf"), "--out", str(tmp_path / "t")]) == 0
    b = pd.read_csv(tmp_path / "t" / "bouts.csv")
    assert b["direction"].tolist() == ["forward", "backward", "forward"]
    assert b["backward_fraction"].tolist() == [0.0, 1.0, 0.0]
    # the backward bout holds the simulated backward strides, and the rows n_backward_strides counts
    assert b["n_strides"].iloc[1] == int((s.steps["direction"] == "backward").sum())
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    assert b["n_strides"].iloc[1] == int(steps["backward_travel"].sum())
    assert {"direction", "backward_fraction"} <= {c[0] for c in BOUTS}  # the column dictionary (docs/columns.md)


def test_a_reversal_without_a_pause_is_one_mixed_bout():
    s = _walk("stand:2, straight:6, backward:8, straight:6, stand:2", 6501)
    res = track_plasys(s)
    n_back = track_summary(res, s)["n_backward_strides"]
    b = detected_bouts(res.steps)
    assert len(b) == 1 and b["direction"].iloc[0] == "mixed"
    assert 0 < n_back < b["n_strides"].iloc[0]
    assert b["backward_fraction"].iloc[0] == pytest.approx(n_back / b["n_strides"].iloc[0])


def test_no_signed_stride_gives_no_direction():
    none = {"direction": None, "backward_fraction": None, "n_backward_strides": None, "n_side_strides": None}
    assert bout_direction(None, 5) == none  # decision L581: the two counts too
    assert bout_direction(0, 0) == none
    assert bout_direction(1, 4) == {"direction": "mixed", "backward_fraction": 0.25, "n_backward_strides": 1,
                                    "n_side_strides": 0}
    # a lower-back table: steps of either foot, no signed stride length (L203)
    t = np.arange(6, dtype=float)
    waist = pd.DataFrame({"start_s": t, "end_s": t + 1, "event_s": t, "length_m": 0.7, "unit": "waist"})
    b = detected_bouts(waist)
    assert len(b) == 1 and b["direction"].isna().all() and b["backward_fraction"].isna().all()
