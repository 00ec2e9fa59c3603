"""Decision W623 (session 53, trial s53t2 finding F4): a lower-back unit re-clipped on the belt mid-walk is found by
its walking frames either side; offline its turn is no heading turn and the data after it are turned back into the
first frame; live one line and a grown radius."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.kernels.reclip import LiveReclipWatch
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist.ahrs import body_data, bridged_samples
from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.reclip import (
    find_reclips,
    frame_rotation,
    reframe,
    rotation_angle_deg,
    two_vector_rotation,
)

ROUTE = parse_route("stand:2, straight:30, straight:30, stand:2")
USER = UserProfile.from_seed(20790)  # a fresh user of this test (W623's measured users are 20700-20729)
KW = {"seed": 1, "rate_hz": 50, "stand_s": 2.0, "bounce": "population"}
REAL = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


@pytest.fixture(scope="module")
def sessions():
    logging.disable(logging.WARNING)
    try:
        return {"plain": simulate_path(ROUTE, USER, **KW),
                "z40": simulate_path(ROUTE, USER, waist_reclip=(25.0, (0.0, 0.0, 40.0)), **KW),
                "x180gap": simulate_path(ROUTE, USER, waist_reclip=(25.0, (180.0, 0.0, 0.0)),
                                         gaps=(("waist", 23.0, 4.0),), **KW)}
    finally:
        logging.disable(logging.NOTSET)


def _track(session, reclip: bool):
    return track_waist(session, pipeline="waist-pendulum", params=WaistParams(options={"reclip": reclip}))


def _lines(result):
    return [w for w in result.info["warnings"] if "W623" in w]


def test_a_yaw_reclip_is_said_once_and_not_counted_as_a_turn(sessions):
    """A 40 deg re-clip about the vertical mid-walk: without W623 the straight walk ends ~20 m to the side (the re-clip
    read as a turn); with it one line names the time and the walk stays straight."""
    off, on = _track(sessions["z40"], False), _track(sessions["z40"], True)
    assert abs(off.trajectory["y"].iloc[-1]) > 10.0 and not _lines(off)
    assert abs(on.trajectory["y"].iloc[-1]) < 2.0
    (line,) = _lines(on)
    assert "re-clipped at 24.5-25.5 s" in line and "turned 40 deg on the belt" in line


def test_the_line_alone_leaves_the_track_as_without_w624(sessions):
    """W624: W623's rule not met, the default says the re-clip and leaves the track as it is."""
    assert OPTION_DEFAULTS["reclip"] == "line"
    off, line = _track(sessions["z40"], False), _track(sessions["z40"], "line")
    assert line.trajectory.equals(off.trajectory)
    (text,) = _lines(line)
    assert "the correction is off" in text and '"reclip": true' in text


def test_a_walk_without_reclip_is_tracked_as_before(sessions):
    off, on = _track(sessions["plain"], False), _track(sessions["plain"], True)
    assert not _lines(on)
    assert on.steps.equals(off.steps) and on.trajectory.equals(off.trajectory)


def test_an_upside_down_reclip_in_a_gap_is_found_in_the_gap_and_undone(sessions):
    t, acc, gyr = body_data(sessions["x180gap"])
    skip = bridged_samples(sessions["x180gap"], t)
    (r,) = find_reclips(t, acc, gyr, 50.0, skip=skip)
    assert r.gap and 22.5 <= r.t0_s <= 23.5 and 26.5 <= r.t1_s <= 27.5
    assert r.angle_deg == pytest.approx(180.0, abs=6.0)
    a2, _ = reframe(t, acc, gyr, [r])
    before, after = a2[(t > 10) & (t < 22)].mean(0), a2[(t > 28) & (t < 40)].mean(0)
    assert np.degrees(np.arccos(before @ after / np.linalg.norm(before) / np.linalg.norm(after))) < 5.0
    assert (acc[(t > 28) & (t < 40)].mean(0) @ before) < 0  # the raw data after it are upside down


def test_frame_rotation_kernels():
    up, fwd = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    R = two_vector_rotation(up, fwd, up, np.array([np.cos(0.5), np.sin(0.5), 0.0]))
    assert rotation_angle_deg(R) == pytest.approx(np.degrees(0.5))
    assert R @ fwd == pytest.approx([np.cos(0.5), np.sin(0.5), 0.0])
    tilted = np.array([0.0, np.sin(0.3), np.cos(0.3)])
    # a forward measured with a low power ratio (W435) is not trusted: the tilt alone
    R2 = frame_rotation((up, fwd, 3.0), (tilted, np.array([0.0, 1.0, 0.0]), 50.0), 10.0)
    assert R2 @ up == pytest.approx(tilted) and rotation_angle_deg(R2) == pytest.approx(np.degrees(0.3))


def test_live_watch_says_the_reclip_and_grows_the_radius(sessions):
    def run(s):
        t, acc = s["wAccelerometer"].t, s["wAccelerometer"].values
        w, lines = LiveReclipWatch(50.0, span_s=10.0, min_walk_s=8.0), []
        for i in range(0, len(t), 50):
            line = w.push(t[i:i + 50], acc[i:i + 50])
            lines += [line] if line else []
        return w, lines

    w, lines = run(sessions["x180gap"])  # live, the gravity alone: a tilt (a yaw re-clip is seen offline only)
    assert len(lines) == 1 and "re-clipped before" in lines[0] and w.found[0][0] > 25.0
    k = np.sin(np.radians(w.found[0][1]))  # the radius grows by sin(angle) per metre walked since
    assert w.found[0][1] >= 25.0  # the first window after it still holds walking from before
    assert w.extra_sigma_m(1.0) == pytest.approx(k) and w.extra_sigma_m(1.0) == pytest.approx(2 * k)
    w0, lines0 = run(sessions["plain"])
    assert not lines0 and w0.extra_sigma_m(1.0) == 0.0


def test_no_reclip_on_the_real_lower_back_daily_activities():
    """W623 (b): the mobgap Test11 walk (six bouts, turns, sitting) is no re-clip."""
    s = read_session(REAL)
    t, acc, gyr = body_data(s)
    assert find_reclips(t, acc, gyr, 100.0) == []
