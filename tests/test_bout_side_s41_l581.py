"""Decision L581 (session 41, trial T1 finding F8): bouts.csv counts each bout's backward and side strides
(``n_backward_strides``, ``n_side_strides``) and its ``direction`` says ``side`` for a side-stepping bout and
``mixed`` for forward walking with side steps (L331 called both ``forward``)."""

from __future__ import annotations

from pdrlearn.columns import BOUTS
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bouts import BOUT_COLUMNS, bout_direction, detected_bouts
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys


def test_a_side_stepping_bout_is_side_and_the_counts_add_up():
    s = simulate_path(parse_route("stand:2, straight:3, backward:4, stand:3, side:1.5, stand:3, backward:2, "
                                  "straight:3, stand:2"), UserProfile.from_seed(11524), rate_hz=100.0, seed=0,
                      scenario="route", speed="slow")
    res = track_plasys(s)
    out = track_summary(res, s)
    b = detected_bouts(res.steps)
    assert b["direction"].tolist() == ["mixed", "side", "mixed"]
    assert b["n_side_strides"].tolist() == [0, 4, 0] and int((s.steps["kind"] == "side").sum()) == 4
    assert int(b["n_backward_strides"].sum()) == out["n_backward_strides"] == 3
    assert int(b["n_side_strides"].sum()) == out["n_side_strides"]
    assert b["backward_fraction"].tolist() == [n / m for n, m in zip(b["n_backward_strides"], b["n_strides"],
                                                                     strict=True)]
    assert {"n_backward_strides", "n_side_strides"} <= {c[0] for c in BOUTS} & set(BOUT_COLUMNS)


def test_the_direction_rule():
    assert bout_direction(0, 4, 4)["direction"] == "side"
    assert bout_direction(0, 6, 2)["direction"] == "mixed"  # forward walking with side steps
    assert bout_direction(4, 4, 0)["direction"] == "backward"
    assert bout_direction(0, 4, 0) == {"direction": "forward", "backward_fraction": 0.0, "n_backward_strides": 0,
                                       "n_side_strides": 0}
    assert bout_direction(None, 4, None)["n_side_strides"] is None  # a lower-back track
