"""Decision E345 (session 52, FE; trial s52t1): a slow stair stride's swing lull is no stance - an option
(``{"stance_lull_join": 1}``; not adopted as the default by E347's rule, see docs/decisions/export.md).

The streamed segmenter (gyroscope alone) takes the middle of a slow stair swing for a stance and cuts the stride in two
halves whose heights reverse: L611 drops them as "cycling", the descent halves read "up, backward". With the option
the strides either side of a boundary where L611's own rest test finds no rest, between two rests, are one stride, in
``track --streaming`` and the live ``Tracker`` alike (``kernels.lull``)."""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.kernels.lull import join_lulls, joins, moving_at
from pdrlearn.kernels.stride import StanceSegmenter

ROOT = Path(__file__).resolve().parents[1]
#: decision E345's option (track --streaming --params, a bundle's displacement)
OPTION = {"stance_lull_join": 1}
#: a short slow flight up and down, one step at a time (the trial's knobs: slow, 0.5 m steps of 0.65 s, 8 cm swing)
ROUTE = "stand:2, up:4:0.17:0.28:step-to-step:slow, stand:1, turn:180, down:4:0.17:0.28:step-to-step:slow, stand:2"


@pytest.fixture(scope="module")
def slow_stairs():
    from pdrlearn.cli.simulate import with_swing_and_sway
    from pdrlearn.sim import UserProfile
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS

    f_len, f_time = SPEED_FACTORS["slow"]
    user = dataclasses.replace(with_swing_and_sway(UserProfile.from_seed(19001), 0.08, None),
                               step_length_m=0.5 / f_len, step_time_s=0.65 / f_time)
    logging.disable(logging.WARNING)
    try:
        return simulate_path(parse_route(ROUTE), user, speed="slow", rate_hz=100.0, seed=0, scenario="route",
                             bounce="population")
    finally:
        logging.disable(logging.NOTSET)


@pytest.fixture(scope="module")
def streamed(slow_stairs):
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        return track_plasys(slow_stairs, streaming=True, method="M2", params=OPTION)
    finally:
        logging.disable(logging.NOTSET)


def test_the_lull_cut_is_joined_in_track_streaming_e345(slow_stairs, streamed):
    """Without the option: 14 strides (4 cut in halves), the halves of the flights dropped as L611's cycling."""
    st, labels = streamed.steps, slow_stairs.steps
    assert len(st) == len(labels) == 10
    assert not any("cycling?" in w for w in streamed.info["warnings"])
    assert np.allclose(st["start_s"], labels["start_s"], atol=0.3) and np.allclose(st["end_s"], labels["end_s"],
                                                                                  atol=0.3)
    dz = st["dz_m"].to_numpy()
    terrain = labels["terrain"].to_numpy()
    assert (terrain == "up").sum() == (terrain == "down").sum() == 4
    assert (dz[terrain == "up"] > 0.12).all() and (dz[terrain == "down"] < -0.12).all()  # not "up, backward"
    assert abs(float(dz.sum())) < 0.1


def test_the_live_tracker_joins_the_same_strides_e345(slow_stairs, streamed):
    from pdrlearn.runtime import Tracker, load_bundle
    from tests.runtime_helpers import time_chunks

    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    bundle.manifest["displacement"].update(OPTION)  # as a bundle exported with the option
    tr = Tracker(bundle, tasks=[], sensors=list(slow_stairs.streams))
    steps = []
    logging.disable(logging.WARNING)
    try:
        for _, chunk in time_chunks(slow_stairs, 0.5):
            steps += tr.push(chunk)
        steps += tr.flush()
    finally:
        logging.disable(logging.NOTSET)
    st = streamed.steps
    assert len(steps) == 10  # 14 without the option (the trial's run: halves dropped as cycling)
    assert [(s.start_s, s.end_s) for s in steps] == list(zip(st["start_s"], st["end_s"], strict=True))
    assert abs(steps[-1].z - float(st["dz_m"].sum())) < 1e-6


def test_the_default_keeps_every_cut_and_a_crank_is_never_joined_e345(slow_stairs):
    gyr, acc = slow_stairs.streams["fGyroscope"], slow_stairs.streams["fAccelerometer"]
    seg = StanceSegmenter.from_params({})
    assert not seg.lull_join and StanceSegmenter.from_params(OPTION).lull_join  # E347: an option, off by default
    cut = np.array(seg.update(gyr.t, gyr.values))
    assert len(cut) == 14  # the segmenter's own strides: four strides cut at a lull
    joined = join_lulls(cut, acc.t, acc.values, 9.81, seg.max_step_s)
    assert len(joined) == 10 and set(map(tuple, joined)) >= {(a, b) for a, b in cut if b - a > 0.9}
    # L611's crank: every boundary unrested, so no outer rest, no join (nor across a pause, nor past max_step_s)
    assert not joins((0.0, 0.6), (0.6, 1.2), True, True, True, 3.0)
    assert not joins((0.0, 0.6), (0.6, 1.2), False, True, True, 3.0)
    assert not joins((0.0, 0.6), (0.7, 1.2), False, True, False, 3.0)
    assert not joins((0.0, 2.0), (2.0, 3.5), False, True, False, 3.0)
    assert joins((0.0, 0.6), (0.6, 1.2), False, True, False, 3.0)
    t = np.arange(0.0, 1.0, 0.01)
    a = np.tile([0.0, 0.0, 9.81], (len(t), 1))
    a[40:60, 2] = 14.0  # a swing's |acc| from 0.4 to 0.6 s
    assert moving_at(t, a, [0.2, 0.5, 0.55], 9.81).tolist() == [False, True, True]
