"""Session 41, review R2 finding 3 (decision L586): ``fused_climb`` with a model that classes terrain did nothing and
said nothing; it is said, offline and streamed, and a track without a terrain model is unchanged."""

from __future__ import annotations

import pytest

from pdrlearn.track.plasys import FUSED_CLIMB_DROPPED, track_plasys


@pytest.fixture(scope="module")
def ramp():
    """A 10 % ramp of 6 m between level walks (simulated user 11671, in-process)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:3, straight:4, slope:6:10, straight:4, stand:3"),
                         UserProfile.from_seed(11671), seed=11671)


@pytest.mark.parametrize("streaming", [False, True])
def test_l586_fused_climb_with_a_terrain_model_is_said(ramp, streaming, caplog):
    res = track_plasys(ramp, model="oracle", altitude="fused", fused_climb=True, streaming=streaming)
    assert FUSED_CLIMB_DROPPED in res.info["warnings"]
    assert sum(FUSED_CLIMB_DROPPED in r.getMessage() for r in caplog.records) == 1  # logged once
    assert "L586" in FUSED_CLIMB_DROPPED and "without a terrain model" in FUSED_CLIMB_DROPPED
    off = track_plasys(ramp, model="oracle", altitude="fused", streaming=streaming)
    assert FUSED_CLIMB_DROPPED not in off.info["warnings"]
    assert res.steps["dz_m"].tolist() == off.steps["dz_m"].tolist()  # it was dropped: the same heights


def test_l586_without_a_model_it_applies_and_is_not_said(ramp):
    res = track_plasys(ramp, altitude="fused", fused_climb=True)
    assert FUSED_CLIMB_DROPPED not in res.info["warnings"]
    plain = track_plasys(ramp, altitude="fused")
    assert res.steps["dz_m"].tolist() != plain.steps["dz_m"].tolist()  # L564 acts here
