"""Decision W390 (session 37, trial T1 finding 2): waist-pll's harmonic heading is 0 at the unit's initial facing,
waist-pendulum's gyro heading at the first walk's direction. Putting pll's 0 at the first walk was measured and not
adopted (an option, ``track.waist.WALK_REFERENCE``); W83's note names each pipeline's reference."""

from __future__ import annotations

import numpy as np
import pytest

import pdrlearn.track.waist as TW
from experiments.waist_pll_reference import yawed
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


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


def test_the_walk_reference_option_puts_pll_zero_along_the_first_walk(walk, monkeypatch):
    """A unit yawed 30 deg on a straight walk: pll's headings sit near -30 deg by default, the pendulum's at 0; the
    option turns every pll heading by one constant, the mean of the first walk's first 4 step directions."""
    def deg(res):
        return np.degrees(res.steps["heading_rad"].to_numpy(float))

    off = deg(TW.track_waist(walk, pipeline="waist-pll"))
    assert abs(np.median(off) + 30.0) < 10.0
    assert np.allclose(deg(TW.track_waist(walk, pipeline="waist-pendulum")), 0.0, atol=1.0)
    monkeypatch.setattr(TW, "WALK_REFERENCE", True)
    on = TW.track_waist(walk, pipeline="waist-pll")
    shift = (off - deg(on) + 180.0) % 360.0 - 180.0
    assert np.ptp(shift) < 1e-6 and abs(shift[0]) > 5.0
    assert "0 = the direction of the first walk" in _note(on)[0]


def test_walk_reference_is_the_circular_mean_of_the_first_walks_first_steps():
    raw = np.array([np.nan, 3.1, -3.1, 3.1, -3.1, 0.0, 0.0, 1.0, 1.0])
    assert abs(abs(TW.walk_reference(raw, [np.arange(2), np.arange(2, 9)])) - np.pi) < 0.05
    assert TW.walk_reference(np.full(3, np.nan), [np.arange(3)]) == 0.0
