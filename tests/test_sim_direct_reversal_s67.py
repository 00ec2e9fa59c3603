"""Decision S67 (trial 31 finding 11, amends S64): `backward:N:direct` reverses straight out of forward walking - no
closing step, no pause; the foot that landed last steps back past the other one."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.path import Backward, plan_footsteps
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys

DIRECT = "stand:2, straight:6, backward:8:direct, stand:2"
STOPPING = "stand:2, straight:6, backward:8, stand:2"  # S64: close, 0.6 s pause


def _sim(route: str, user: int, foot: str = "right"):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=4, scenario="route",
                         instrumented_foot=foot)


def _reversal(s):
    """(last forward IC, first backward IC) rows of ics.csv's table."""
    ics = s.extras["ics"]
    kinds = ics["kind"].astype(str).to_numpy()
    first_back = int(np.flatnonzero(kinds == "backward")[0])
    return ics.iloc[first_back - 1], ics.iloc[first_back], ics


def test_the_route_item():
    assert parse_route("backward:8:direct") == [Backward(8, direct=True)]
    assert parse_route("backward:8") == [Backward(8)]
    with pytest.raises(DataError, match="'direct'"):
        parse_route("backward:8:fast")


@pytest.mark.parametrize("foot", ["right", "left"])
def test_a_direct_reversal_has_no_closing_step_and_no_stop(foot):
    direct, stopping = _sim(DIRECT, 6520, foot), _sim(STOPPING, 6520, foot)
    last_fwd, first_back, ics = _reversal(direct)
    assert "close" not in set(ics["kind"].astype(str).iloc[:first_back.name])  # no closing step before it
    assert last_fwd["kind"] == "walk" and last_fwd["foot"] == first_back["foot"]  # the front foot steps back
    gap = first_back["ic_s"] - last_fwd["ic_s"]
    s_last, s_first, _ = _reversal(stopping)
    assert s_last["kind"] == "close"  # S64: the trail foot closes first, then the pause
    assert gap < 1.0 < s_first["ic_s"] - s_last["ic_s"]
    # the reversing step lands one backward step (0.55 x the step length, S67) behind the other foot's last contact
    # point: the stride table's backward strides are as many as S64's walk's
    assert (direct.steps["direction"] == "backward").sum() == (stopping.steps["direction"] == "backward").sum()


def test_the_reversing_foot_lands_a_backward_step_behind_the_other():
    user = UserProfile.from_seed(6523)
    steps, _, _, _ = plan_footsteps(parse_route("stand:2, straight:6, backward:4:direct"), user,
                                    rng=np.random.default_rng(0), variability=0.0)
    k = next(i for i, st in enumerate(steps) if st.kind == "backward")
    last, first = steps[k - 1], steps[k]
    assert last.kind == "walk" and first.foot == last.foot and first.pause_before_s == 0
    other = next(st for st in reversed(steps[:k]) if st.foot != last.foot)
    # along the heading (east, psi 0): the front foot swings back past the other one, a backward step behind it
    assert first.heel[0] == pytest.approx(other.heel[0] - 0.55 * user.step_length("normal"), abs=0.01)
    assert first.heel[0] < other.heel[0] < last.heel[0]


@pytest.mark.parametrize("user,foot", [(6521, "right"), (6521, "left"), (6522, "left")])
def test_the_foot_track_follows_the_reversal(user, foot):
    s = _sim(DIRECT, user, foot)
    res = track_plasys(s)
    out = track_summary(res, s)
    assert out["n_backward_strides"] == int((s.steps["direction"] == "backward").sum()) > 0
    assert out["distance_m"] == pytest.approx(float(s.steps["length_m"].sum()), rel=0.03)
    assert out["final_position_error_m"] < 0.6


def test_direct_needs_forward_walking_to_reverse():
    # from standing there is no forward push-off: the same walk as backward:3 (S64)
    a, b = _sim("stand:2, backward:3:direct, stand:2", 6523), _sim("stand:2, backward:3, stand:2", 6523)
    assert a.steps.equals(b.steps)
