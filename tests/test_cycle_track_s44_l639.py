"""Decisions L639 / L640 / L641 (docs/decisions/localization.md): the default offline foot track of a bike ride (S99's
``cycle:S``, both units, with the insoles) counts no stride in the ride and no walked metre for it.

The insoles' stance (loaded and a calm gyroscope) has no rest while the crank turns the foot, so every pedal stroke's
detection lay between the same two rests and made ONE "stride" of the whole ride (user 12130: 18.75-76.27 s, 24.59 m;
S99's finding). L639: a stride longer than 3 of the foot's stride caps is a ride, not walking, and goes (its span is
then a standstill the vehicle test reads). L641: a removed stride goes with every detection that makes it (a stride of
several crank turns had come back from its other detections, user 12302: 6 strides, +53 %). L640: a stride chained
to a pedalling stride that travels under 0.3 m or is a steep stroke is pedalling too (the streamed track had kept the
mount's and the dismount's stroke, S99).
"""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels.pedal import RIDE_STRIDE_CAPS, closed_loop_strides, pedal_line, ride_strides
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys


def _track(user: int, ride_s: int, **kw):
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(f"stand:3, straight:10, cycle:{ride_s}, straight:10, stand:3"),
                          UserProfile.from_seed(user), seed=user, scenario="route")
        return s, s.extras["rides"].iloc[0], track_plasys(s, **kw)
    finally:
        logging.disable(logging.NOTSET)


def _in_ride(steps, r) -> np.ndarray:
    return ((steps["end_s"] > r["start_s"]) & (steps["start_s"] < r["end_s"])).to_numpy()


def test_a_stride_far_longer_than_the_cap_is_a_ride_l639():
    start, end = np.array([0.0, 2.0, 10.0, 30.0]), np.array([1.2, 10.0, 19.5, 35.0])
    assert ride_strides(start, end, 3.0).tolist() == [False, False, True, False]  # 9 s is the limit at 3 s
    assert not ride_strides(start, end, 3.5).any()  # a slow foot's cap (L605) moves it: 10.5 s
    line = pedal_line(np.zeros(4, bool), np.zeros(4, bool), start, end, ride=ride_strides(start, end, 3.0), cap_s=3.0)
    assert line.count("\n") == 0 and "10.00-19.50 s" in line and "decision L639" in line
    assert f"longer than {RIDE_STRIDE_CAPS * 3:g} s" in line


def test_the_default_offline_track_counts_no_stride_in_a_bike_ride_l639():
    s, r, res = _track(12130, 60)  # S99's user: one 24.59 m stride over the ride, 44.56 m tracked for 20 m walked
    walked = float(s.steps["length_m"].sum())
    assert not _in_ride(res.steps, r).any()
    assert res.steps["length_m"].sum() == pytest.approx(walked, rel=0.05)
    assert len(res.steps) == len(s.steps)
    line = next(w for w in res.info["warnings"] if "decision L639" in w)
    assert "not walking, removed from the track" in line
    assert not any("stride(s) longer than" in w for w in res.info["warnings"])
    # the ride is then a standstill between two strides: L616 reads it as a vehicle (as --ignore-force does)
    rides = [x for x in res.info["rides"] if x["kind"] == "vehicle"]
    assert len(rides) == 1
    cover = min(rides[0]["end_s"], r["end_s"]) - max(rides[0]["start_s"], r["start_s"])
    assert cover >= 0.8 * (r["end_s"] - r["start_s"])


def test_a_removed_stride_takes_every_detection_that_makes_it_l641():
    s, r, res = _track(12302, 40)  # L611 marked all 37 ride strides; 6 of several crank turns came back
    assert not _in_ride(res.steps, r).any()
    assert res.steps["length_m"].sum() == pytest.approx(float(s.steps["length_m"].sum()), rel=0.05)
    assert len(res.steps) == len(s.steps)


def test_a_short_stride_chained_to_pedalling_is_pedalling_l640():
    # three walking strides, the mount's stroke (rests before it), six crank strides (the first rises with the mount,
    # no reversal there), the dismount's (a foot still on the pedal: no height, no travel), three walking strides
    dz = np.array([0.01, -0.01, 0.01, 0.42, 0.9, -0.3, 0.3, -0.3, 0.3, -0.3, -0.002, 0.01, -0.01, 0.01])
    travel = np.array([1.5, 1.5, 1.5, 0.22, 0.5, 0.05, 0.05, 0.05, 0.05, 0.05, 0.01, 1.5, 1.5, 1.5])
    unrested = np.array([False] * 4 + [True] * 6 + [False] * 4)
    start = np.arange(len(dz), dtype=float)
    marked = closed_loop_strides(dz, start, start + 1.0, unrested, travel)
    assert marked.tolist() == [False] * 3 + [True] * 8 + [False] * 3
    # a walking stride chained to a crank stride stays
    marked = closed_loop_strides(np.r_[dz[:9], 0.02], start[:10], start[:10] + 1.0, np.r_[unrested[:9], False],
                                 np.r_[travel[:9], 1.4])
    assert not marked[:3].any() and marked[3:9].all() and not marked[9]


def test_the_mount_and_dismount_strokes_go_with_the_ride_l640():
    s, r, res = _track(12131, 60, streaming=True)  # before: the two strokes, 0.23 m, kept
    assert any("cycling? decision L611" in w for w in res.info["warnings"])
    assert not _in_ride(res.steps, r).any()
    assert len(res.steps) == len(s.steps)
