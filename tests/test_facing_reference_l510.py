"""Decisions L510 / L511 (trial T3 findings 2 and 5): a foot-only (and D25-fallback) track's heading 0 is the
walker's facing at the first walk, so a drill starting with a side step or a backpedal ends where the truth does in
the truth's frame; ``--initial-heading`` is taken when D25 fell back to the foot gyroscope's heading."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def _walk(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=0, scenario="route")


def _end_error(walk, **kw) -> float:
    from pdrlearn.track.plasys import track_plasys

    r = track_plasys(walk, heading="foot", **kw)
    xy, true = (t[["x", "y"]].to_numpy(float) for t in (r.trajectory, walk.trajectory))
    return float(np.hypot(*((xy[-1] - xy[0]) - (true[-1] - true[0]))))


@pytest.mark.parametrize(("route", "user"), [("stand:2, side:3, straight:4, stand:2", 10010),
                                             ("stand:2, side:-3, straight:4, stand:2", 10011),
                                             ("stand:2, backward:4, straight:4, stand:2", 10012)])
def test_side_and_backward_first_drills_end_at_the_truth_in_its_frame_l510(route, user):
    assert _end_error(_walk(route, user)) < 0.2  # side-first before L510: turned 90 deg, 5-8 m off


def test_forward_first_walk_is_unchanged_by_the_facing_reference_l510(monkeypatch):
    from pdrlearn.track import plasys

    walk = _walk("stand:2, straight:6, turn:90, straight:4, side:2, stand:2", 10013)
    new = plasys.track_plasys(walk, heading="foot").trajectory
    l494 = plasys.foot_walk_reference  # L494's travel reference: the strides' headings without their sides (W413)
    monkeypatch.setattr(plasys, "foot_walk_reference", lambda head, disp, lateral=None, turn=None: l494(head, disp))
    old = plasys.track_plasys(walk, heading="foot").trajectory
    np.testing.assert_array_equal(new[["x", "y"]].to_numpy(), old[["x", "y"]].to_numpy())


def test_initial_heading_turns_a_side_first_drill_from_the_facing_l510():
    from pdrlearn.track.plasys import track_plasys

    walk = _walk("stand:2, side:3, straight:4, stand:2", 10010)
    xy = track_plasys(walk, heading="foot", initial_heading=np.pi / 2).trajectory[["x", "y"]].to_numpy(float)
    d = xy[-1] - xy[0]
    np.testing.assert_allclose(d, [-3.0, 4.0], atol=0.3)  # facing north: the left shuffle goes west, then north


def test_initial_heading_is_accepted_when_d25_fell_back_to_the_foot_heading_l511():
    from types import SimpleNamespace

    from pdrlearn.cli.track import _apply_start_heading
    from pdrlearn.errors import DataError
    from pdrlearn.track.plots import heading_is_absolute

    session = SimpleNamespace(streams={"wMagneticField": None})
    info = {"pipeline": "plasys", "heading_source": "fused", "compass_mount": {"fallback": True}}
    assert not heading_is_absolute(info, session)  # before L511: absolute, and --initial-heading refused
    result = SimpleNamespace(info=dict(info))
    _apply_start_heading(result, session, 0.5, None)
    assert result.info["initial_heading_rad"] == 0.5
    with pytest.raises(DataError, match="absolute"):  # the compass kept: still refused (L98; L635: unless turned)
        _apply_start_heading(SimpleNamespace(info={**info, "compass_mount": {"fallback": False}}), session, 0.5, None)


def test_d25_warning_names_the_facing_and_initial_heading_l511():
    # review R1 finding 11: the line D25 prints, not the source (a comment would have satisfied a grep)
    from types import SimpleNamespace

    from pdrlearn.track.compass_mount import MOUNT_FORWARD_OFF_DEG, mount_check

    turned = SimpleNamespace(forward_deg=MOUNT_FORWARD_OFF_DEG + 30.0, side_drill=False, unchecked=None)
    session = SimpleNamespace(declared_check=lambda placement: turned)  # a waist unit turned on the belt
    heading = np.zeros(20)
    line, info = mount_check(session, heading, heading, np.ones(20, bool))
    assert info["fallback"] and line is not None
    assert "the walker's facing at the first walk" in line and "--initial-heading DEG sets it, L511" in line
    walked = SimpleNamespace(forward_deg=0.0, side_drill=False, unchecked=None)  # worn as declared: no line
    assert mount_check(SimpleNamespace(declared_check=lambda placement: walked), heading, heading,
                       np.ones(20, bool))[0] is None
