"""Decision L712: the foot gyroscope's bias followed through every stand over 30 s, interpolated in time between
the stands (``FootDisplacement(rest_drift=...)``; docs/decisions/localization.md L711 / L712)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.displace.foot import FOOT_REST_DRIFT_MIN_S
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys

SLOPE = 2e-4  # rad/s per s: the foot bias's steady climb about the vertical (0.7 deg/s over the walk, a warming unit)


@pytest.fixture(scope="module")
def stop_walk():
    """User 15540: 25 m, a 40 s stand, 25 m, a 40 s stand at the end; and the same session whose foot gyroscope's
    bias climbs by SLOPE per s about the vertical from the set-up on."""
    s = simulate_path(parse_route("stand:5, straight:25, stand:40, straight:25, stand:40"),
                      UserProfile.from_seed(15540), rate_hz=20, seed=0)
    drifted = s.copy()
    g, a = drifted.streams["fGyroscope"], s.streams["fAccelerometer"]
    up = a.values[a.t < 3.0].mean(axis=0)
    up /= np.linalg.norm(up)  # the vertical in the resting foot's frame
    g.values = g.values + SLOPE * (g.t - g.t[0])[:, None] * up[None, :]
    return {(name, on): track_plasys(x, method="M3", model="oracle", heading="foot", params={"rest_drift": on})
            for name, x in (("plain", s), ("drifted", drifted)) for on in (False, True)}


def _headings(session, **params) -> np.ndarray:
    return track_plasys(session, method="M3", model="oracle", heading="foot",
                        params=params).steps["heading_rad"].to_numpy(float)


def _h(result) -> np.ndarray:
    return result.steps["heading_rad"].to_numpy(float)


def _off_deg(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(np.degrees(np.angle(np.exp(1j * (b - a)))))))


def test_a_bias_climbing_through_the_walk_is_followed_between_the_stands_l712(stop_walk):
    r = stop_walk
    # the set-up standstill's one bias: the climb turns the strides (printed 16.8 deg at most)
    assert _off_deg(_h(r["plain", False]), _h(r["drifted", False])) > 5.0
    # interpolated between the set-up, the 40 s stop and the final stand: every stride within 1 deg (printed 0.018;
    # forward from the stop's last block only, the second leg would lag the climb by ~2 deg)
    assert _off_deg(_h(r["plain", True]), _h(r["drifted", True])) < 1.0


def test_a_walk_whose_stands_are_not_over_30_s_is_unchanged_bit_for_bit_l712():
    assert FOOT_REST_DRIFT_MIN_S == 30.0
    s = simulate_path(parse_route("stand:5, straight:10, stand:20, straight:10, stand:5"), UserProfile.from_seed(15541),
                      rate_hz=20, seed=0)
    assert np.array_equal(_headings(s, rest_drift=False), _headings(s, rest_drift=True))


def test_the_summary_says_whether_it_ran_l712(stop_walk):
    assert stop_walk["drifted", False].info["settings"]["rest_drift"] is False
    assert stop_walk["drifted", True].info["settings"]["rest_drift"] is True
