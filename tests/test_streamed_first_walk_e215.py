"""Decision E215 (session 39): L494's first-walk heading reference on the streamed track (``track --streaming`` and
the runtime ``Tracker``, one kernel). Measured and not adopted as the default: a streamed foot-only track says in one
line that its heading's 0 is the unit's facing and how far the first walk heads from it (no silence); the causal
re-reference is an option (decision E222: ``track_plasys(streaming=True, first_walk=True)``,
``Tracker(first_walk=True)``) that keeps a yawed unit from turning the path.
D25 is not needed streamed (the streamed heading reads no compass). Simulated user 9887 (E215's range 9880-9889)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.kernels.first_walk import FirstWalk
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.frame_inference import MIN_STRIDE_M, remount
from pdrlearn.track.plasys import WALK_REFERENCE_STRIDES, track_plasys

ROUTE = "stand:3, straight:20, turn:90, straight:10, turn:-90, straight:15, stand:3"
SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(9887), rate_hz=100.0, seed=9887, scenario="route")


def _yawed(walk, deg: float):
    s = remount(walk, "foot", Rotation.from_euler("y", deg, degrees=True).as_matrix().T)
    s.frames["foot"] = walk.frames["foot"]  # the nearest-axis declaration kept (L494's case)
    return s


def _end(result) -> np.ndarray:
    xy = result.trajectory[["x", "y"]].to_numpy(float)
    return xy[-1] - xy[0]


def test_a_streamed_foot_only_track_says_its_heading_is_the_units_facing_e215(walk):
    yawed = track_plasys(_yawed(walk, 20.0), streaming=True, method="M2", heading="foot")
    lines = [w for w in yawed.info["warnings"] if "decision E215" in w]
    assert len(lines) == 1 and "is the foot unit's facing at the start" in lines[0], yawed.info["warnings"]
    assert 10.0 < abs(yawed.info["first_walk_deg"]) < 30.0  # the walk heads ~20 deg off the yawed unit's facing
    two = track_plasys(walk, streaming=True, method="M2", heading="auto")  # the waist heads: no line
    assert not [w for w in two.info["warnings"] if "decision E215" in w]
    straight = track_plasys(walk, streaming=True, method="M2", heading="foot")  # a unit mounted straight: no line
    assert abs(straight.info["first_walk_deg"]) < 10.0
    assert not [w for w in straight.info["warnings"] if "decision E215" in w]


def test_the_opt_in_re_reference_keeps_a_yawed_unit_from_turning_the_path_e215(walk):
    truth = walk.trajectory[["x", "y"]].to_numpy(float)
    truth = truth[-1] - truth[0]
    off = track_plasys(_yawed(walk, 20.0), streaming=True, method="M2", heading="foot")
    on = track_plasys(_yawed(walk, 20.0), streaming=True, method="M2", heading="foot", first_walk=True)  # E222
    assert np.hypot(*(_end(on) - truth)) < 4.0 < np.hypot(*(_end(off) - truth))  # measured 1.72 / 11.95 m
    assert [w for w in on.info["warnings"] if "heading turned by" in w]


def test_the_runtime_says_it_as_track_streaming_e215(walk):
    from pdrlearn.runtime import Tracker

    s = _yawed(walk, -30.0)
    tr = Tracker(SHIPPED, heading_source="foot")
    data = {n: (st.t, st.values) for n, st in s.streams.items() if n in tr.used_sensors}
    for lo in np.arange(0.0, max(t[-1] for t, _ in data.values()) + 1.0, 1.0):
        tr.push({n: (t[(t >= lo) & (t < lo + 1.0)], v[(t >= lo) & (t < lo + 1.0)]) for n, (t, v) in data.items()})
    tr.flush()
    lines = [w for w in tr.warnings if "decision E215" in w]
    assert len(lines) == 1, tr.warnings
    assert 20.0 < abs(np.degrees(tr._first_walk.angle)) < 40.0  # a unit yawed 30 deg: the walk heads ~30 deg off
    streamed = track_plasys(s, streaming=True, method="M2", heading="foot")
    assert abs(tr._first_walk.angle - np.radians(streamed.info["first_walk_deg"])) < np.radians(5.0)


def test_first_walk_kernel_once_and_only_foot_headed_e215():
    assert FirstWalk(enabled=True).done is False and WALK_REFERENCE_STRIDES == 4 and MIN_STRIDE_M == 0.2
    fw = FirstWalk(0.1, enabled=True)
    got = [fw.stride(True, 0.1 + a, L) for a, L in ((1.0, 0.1), (0.5, 1.2), (0.5, 1.2), (0.5, 1.2), (0.5, 1.2),
                                                    (0.5, 1.2))]
    assert got[:4] == [None] * 4 and got[4] == pytest.approx(0.5) and got[5] is None  # the 4th walking stride, once
    said = FirstWalk(enabled=False)
    assert [said.stride(True, 0.5, 1.2) for _ in range(5)] == [None, None, None, 0.0, None]  # said, not turned
    assert "heads +28.6 deg" in said.line(9.0)
    quiet = FirstWalk(enabled=False)
    assert [quiet.stride(True, 0.1, 1.2) for _ in range(4)][-1] == 0.0 and quiet.line(9.0) is None  # 5.7 deg
    assert fw.n_before == 4  # a short pivot and three walking strides placed before it
    waist = FirstWalk(enabled=True)
    assert waist.stride(False, 0.5, 1.2) is None and waist.done  # the waist heads: its frame, not applied
    resumed = FirstWalk(enabled=True)
    resumed.stop()
    assert all(resumed.stride(True, 0.5, 1.2) is None for _ in range(5))


def test_the_streamed_heading_needs_no_compass_check_e215(walk):
    """D25's turned waist (z:180 on the belt) turned the offline fused track by ~180 deg before D25; the streamed
    track reads no compass: its end moves little."""
    turned = simulate_path(parse_route(ROUTE), UserProfile.from_seed(9887), rate_hz=100.0, seed=9887,
                           scenario="route", waist_mount_deg=(0.0, 0.0, 180.0))
    a, b = (track_plasys(s, streaming=True, method="M2", heading="auto") for s in (walk, turned))
    assert np.hypot(*(_end(a) - _end(b))) < 1.0
    assert b.info["compass_mount"]["not_judged"].startswith("not needed")
