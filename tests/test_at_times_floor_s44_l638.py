"""The lead's merge of L638 (``track --at-times``) with L630 / L631 (trajectory.csv's ``z_rides`` and ``floor``):
at_times.csv carries the floor and the ride-inclusive altitude at the given times, so an indoor-positioning user
(session 44 trial T3) reads x, y and floor at a waypoint's time after a lift ride."""

from __future__ import annotations

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def test_at_times_has_the_floor_after_a_lift_l638_l631(tmp_path):
    s = simulate_path(parse_route("stand:5, straight:10, lift:3.4, straight:10, stand:3"), UserProfile.from_seed(12700),
                      rate_hz=20, seed=12700)
    write_session(s, tmp_path / "lift")
    (tmp_path / "at.csv").write_text("t\n3\n12\n30\n")
    out = tmp_path / "tr"
    assert main(["track", "--no-plot", str(tmp_path / "lift"), "--storey-height", "3.4", "--at-times",
                 str(tmp_path / "at.csv"), "--out", str(out)]) == 0
    at = pd.read_csv(out / "at_times.csv")
    assert list(at["floor"]) == [0, 0, 1]  # before, on the ground floor, after the 3.4 m lift
    assert abs(at["z_rides"].iloc[-1] - 3.4) < 0.3 and abs(at["z"].iloc[-1]) < 0.3  # the ride is in z_rides only
    assert undocumented("at_times.csv", at.columns) == []
