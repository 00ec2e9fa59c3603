"""Decision L731: ``FootDisplacement(rest_drift=True, rest_drift_by="stand")`` reads the foot gyroscope's bias at
every stand of 30 s or more by the stand's own length (the foot's still run), where L712's stride gap of a 30 s
stand is under 30 s (docs/decisions/localization.md L723 / L731)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.displace.foot import FOOT_REST_DRIFT_MIN_S, FootDisplacement
from pdrlearn.errors import DataError
from pdrlearn.orient import unit_data
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys

SLOPE = 2e-4  # rad/s per s: the foot bias's steady climb about the vertical (L712's test's warming unit)


def _walk(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20, seed=0)


def _fit(session, **kw) -> FootDisplacement:
    return FootDisplacement(**kw).estimate(unit_data(session, "foot"), session.steps)


def _heading(fd: FootDisplacement) -> np.ndarray:
    return np.degrees(np.cumsum(fd.yaw_change_ + fd.gap_yaw_))


@pytest.fixture(scope="module")
def stands():
    """User 16280: 25 m, a 30 s stand, 25 m, a 30 s stand, 10 m (each stand's stride gap under 30 s, its still run
    over 30 s); and the same session whose foot bias climbs by SLOPE per s about the vertical from the set-up on."""
    s = _walk("stand:5, straight:25, stand:30, straight:25, stand:30, straight:10, stand:5", 16280)
    drifted = s.copy()
    g, a = drifted.streams["fGyroscope"], s.streams["fAccelerometer"]
    up = a.values[a.t < 3.0].mean(axis=0)
    up /= np.linalg.norm(up)  # the vertical in the resting foot's frame
    g.values = g.values + SLOPE * (g.t - g.t[0])[:, None] * up[None, :]
    return {"plain": _fit(s, rest_drift=True, rest_drift_by="stand"),
            "gap": _fit(drifted, rest_drift=True), "stand": _fit(drifted, rest_drift=True, rest_drift_by="stand")}


def test_a_30_s_stand_is_read_by_its_still_run_not_skipped_by_its_stride_gap_l731(stands):
    assert FOOT_REST_DRIFT_MIN_S == 30.0
    # L712's gap rule reads neither 30 s stand (their gaps are under 30 s); L731's reads both, by their still runs
    assert stands["gap"].rest_bias_rests_ == []
    runs = stands["stand"].rest_bias_rests_
    assert len(runs) == 2 and all(t1 - t0 >= 30.0 for t0, t1 in runs)
    ref = _heading(stands["plain"])
    legs = 0.5 * (stands["stand"].start_s_ + stands["stand"].end_s_) < runs[-1][1]  # the two legs between the reads
    # the set-up's bias only: the climb turns the two legs' strides (printed 16.68 deg); interpolated between the
    # set-up and the two stands' reads they follow it (printed 0.0032 deg)
    assert np.abs(_heading(stands["gap"]) - ref)[legs].max() > 5.0
    assert np.abs(_heading(stands["stand"]) - ref)[legs].max() < 0.5


def test_stands_under_30_s_leave_the_walk_unchanged_bit_for_bit_l731():
    s = _walk("stand:5, straight:10, stand:20, straight:10, stand:5", 16281)
    a, b = _fit(s), _fit(s, rest_drift=True, rest_drift_by="stand")
    assert b.rest_bias_rests_ == []
    assert np.array_equal(a.yaw_change_, b.yaw_change_) and np.array_equal(a.disp_, b.disp_)


def test_the_summary_names_the_rule_and_a_wrong_one_is_one_line_l731():
    s = _walk("stand:3, straight:5, stand:3", 16282)
    r = track_plasys(s, method="M3", model="oracle", params={"rest_drift": True, "rest_drift_by": "stand"})
    assert r.info["settings"]["rest_drift_by"] == "stand"
    with pytest.raises(DataError, match="rest_drift_by 'still' is not one of gap, stand"):
        FootDisplacement(rest_drift_by="still")
