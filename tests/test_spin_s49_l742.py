"""Decision L742 (trial s49t2): a turn on the spot without a step (S106's spin on the planted foot) is no stride, on
offline ``track``, ``track --streaming`` and the runtime ``Tracker`` (one kernel rule); L743: a distance error against
a reference under 2 m is printed in metres."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.spin import SPIN_TILT_MAX_RAD_S, turn_in_place
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:3, stand:2, spin:360:4, stand:2, straight:3, stand:2"


@pytest.fixture(scope="module")
def spun():
    """A walk with a spin (5 true strides) and the spin's window (s)."""
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(16420), rate_hz=50, seed=1, name="spin")
    sp = s.extras["spins"]
    return s, (float(sp["start_s"].iloc[0]), float(sp["end_s"].iloc[0]))


def _inside(steps, a: float, b: float) -> int:
    mid = 0.5 * (np.asarray(steps["start_s"], float) + np.asarray(steps["end_s"], float))
    return int(((mid > a) & (mid < b)).sum())


def test_the_kernel_tells_a_yaw_in_place_from_a_swing():
    t = np.arange(0, 3, 0.01)
    up = np.array([0.05, -0.03, 1.0]) / np.linalg.norm([0.05, -0.03, 1.0])  # a tilted mount: gravity off z
    acc = np.tile(9.80665 * up, (t.size, 1)) + np.random.default_rng(0).normal(0, 0.05, (t.size, 3))
    yaw = np.outer(3.0 * np.sin(np.pi * t / 3), up)  # 3 rad/s about gravity: over L27's 2 rad/s cap
    assert turn_in_place(t, acc, t, yaw, 0.0, 3.0)
    pitch = yaw + np.outer(np.where(np.abs(t - 1.5) < 0.2, 2 * SPIN_TILT_MAX_RAD_S, 0.0), [0, 1, 0])
    assert not turn_in_place(t, acc, t, pitch, 0.0, 3.0)  # the foot tilts: a swing
    pushed = acc + np.outer(np.where(np.abs(t - 1.5) < 0.1, 5.0, 0.0), up)  # a 5 m/s^2 lift
    assert not turn_in_place(t, pushed, t, yaw, 0.0, 3.0)  # the foot accelerates: carried
    assert not turn_in_place(t, acc, t, yaw, 5.0, 6.0)  # no samples: not judged


def test_streamed_track_makes_no_stride_of_the_spin(spun):
    from pdrlearn.track.base import get_pipeline

    s, (a, b) = spun
    res = get_pipeline("plasys")(s, streaming=True)
    assert _inside(res.steps, a, b) == 0 and len(res.steps) == len(s.steps)  # main: 6 strides, one in the spin
    assert any("L742" in w for w in res.info["warnings"])


def test_a_spin_alone_is_no_stride_offline_nor_streamed():
    from pdrlearn.errors import DataError, NoStridesError
    from pdrlearn.track.base import get_pipeline

    s = simulate_path(parse_route("stand:3, spin:360:4, stand:3"), UserProfile.from_seed(16421), rate_hz=50, seed=1,
                      name="spin")
    with pytest.raises(NoStridesError, match="L742"):  # main: one stride of 0.2-0.5 m
        get_pipeline("plasys")(s)
    with pytest.raises(DataError, match="L742"):
        get_pipeline("plasys")(s, streaming=True)


def test_the_runtime_makes_no_stride_of_the_spin(spun, synthetic_bundle):
    from pdrlearn.runtime import Tracker
    from tests.runtime_helpers import replay

    s, (a, b) = spun
    tr = Tracker(synthetic_bundle)
    steps = replay(tr, s, chunk_s=1.0)
    mids = [0.5 * (x.start_s + x.end_s) for x in steps]
    assert not [m for m in mids if a < m < b]  # main: one stride inside the spin
    assert tr.n_turns_in_place == 1 and any("L742" in w for w in tr.warnings)


def test_a_distance_error_of_a_short_reference_is_in_metres():
    from pdrlearn.cli.track import distance_error_phrase

    assert distance_error_phrase({"distance_error_pct": -53.31, "distance_ref_m": 0.79}) == (
        ", distance error -0.42 m (reference 0.79 m: under 2 m, no percent, L743)")  # main: -53.31 %
    assert distance_error_phrase({"distance_error_pct": 1.5, "distance_ref_m": 20.0}) == ", distance error +1.50 %"
    assert distance_error_phrase({"distance_error_pct": 1.5}) == ", distance error +1.50 %"


def test_a_foot_headed_stream_keeps_the_turn_in_place():
    """Without the lower back, the spin's turn is the foot's: left out as a stride, it goes to the next stride (L742;
    dropped with it, users 16650-16652's final position error was 5.6-6.3 m instead of main's 0.8-1.2 m)."""
    from pdrlearn.track.base import get_pipeline
    from pdrlearn.track.evaluate import track_summary

    s = simulate_path(parse_route("stand:2, straight:4, stand:2, spin:270:3, stand:2, straight:4, stand:2"),
                      UserProfile.from_seed(16650), rate_hz=50, seed=1, name="foot")
    for n in ("wAccelerometer", "wGyroscope", "wBarometer", "wMagneticField"):
        s.streams.pop(n, None)
    res = get_pipeline("plasys")(s, streaming=True)
    assert len(res.steps) == len(s.steps)  # main: one stride more, inside the spin
    assert track_summary(res, s, pipeline="plasys")["final_position_error_m"] < 2.0
