"""Decision W390 (session 37, trial T1 finding 2): waist-pll's harmonic heading is 0 at the unit's initial facing,
waist-pendulum's gyro heading at the first walk's direction. Putting pll's 0 at the first walk was measured and not
adopted (its option removed since, W401); W83's note names each pipeline's reference."""

from __future__ import annotations

import numpy as np
import pytest

import pdrlearn.track.waist as TW
from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def yawed(session, deg: float):
    """``session`` with the waist unit turned by ``deg`` about its body's vertical (FLU z; the sim's waist frame)."""
    from scipy.spatial.transform import Rotation

    frame = session.require_frame("waist").matrix()  # sensor -> FLU
    r = frame.T @ Rotation.from_euler("z", deg, degrees=True).as_matrix() @ frame  # the turn in sensor axes
    s = session.copy()
    for n in ("wAccelerometer", "wGyroscope"):
        st = s.streams[n]
        s.streams[n] = Stream(n, st.t, st.values @ r)  # each row v -> r^T v: the unit turned by +deg
    return s


@pytest.fixture(scope="module")
def walk():
    s = simulate_path(parse_route("straight:20"), UserProfile.from_seed(9215), seed=1, scenario="route")
    return yawed(s, 30.0)


def _note(res):
    return [w for w in res.info["warnings"] if "relative to the start" in w]


def test_the_note_names_each_pipelines_heading_reference(walk):
    pll = _note(TW.track_waist(walk, pipeline="waist-pll"))
    pend = _note(TW.track_waist(walk, pipeline="waist-pendulum"))
    assert len(pll) == 1 and "0 = the unit's initial facing, not the walking direction" in pll[0]
    assert "decision W390" in pll[0]
    assert len(pend) == 1 and "0 = the direction of the first walk" in pend[0] and "initial facing" not in pend[0]


def test_pll_keeps_the_units_facing_and_no_module_switch_w401(walk):
    """Decision W401: W390's candidate (0 at the first walk's direction) and its module switch are gone: a unit
    yawed 30 deg on a straight walk gives pll headings near -30 deg, the pendulum's at 0."""
    def deg(res):
        return np.degrees(res.steps["heading_rad"].to_numpy(float))

    assert not hasattr(TW, "WALK_REFERENCE") and not hasattr(TW, "walk_reference")
    assert abs(np.median(deg(TW.track_waist(walk, pipeline="waist-pll"))) + 30.0) < 10.0
    assert np.allclose(deg(TW.track_waist(walk, pipeline="waist-pendulum")), 0.0, atol=1.0)
