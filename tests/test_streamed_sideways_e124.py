"""Decision E124: the streamed foot tracker (``track --streaming``, ``pdrlearn run``, ``Tracker``) places a
side-stepping stretch's strides headed by the waist gyroscope along their travel angle, from the run's third
sideways stride on (L219's rule one stride at a time, :class:`pdrlearn.kernels.sideways.SideRun`). Adopted (E125);
decision E234: no module switch, the tracks "before E124" stand in ``SideRun``'s angle with 0 (the experiment's
:func:`~experiments.side_steps_streamed.before_e124`)."""

from __future__ import annotations

import contextlib
import logging
import math

import numpy as np
import pytest

from pdrlearn.kernels import sideways as KS
from pdrlearn.kernels.sideways import SideRun
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track
from tests.runtime_helpers import replay, trained_dirs


def _stride(angle_deg: float, length: float = 0.4) -> tuple[float, float]:
    a = math.radians(angle_deg)
    return length * math.cos(a), length * math.sin(a)


def test_side_run_adds_the_travel_angle_from_the_third_sideways_stride_on(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    run = SideRun()
    extras = [run.stride(*_stride(d, 1.4 if abs(d) < 45 else 0.4), 0.4) for d in (4, 6, 5, 90, 92, 91, 89, 5, 88)]
    # forward strides and the run's first two: 0; then the angle less the usual offset (median of 6, 5 deg: the
    # stream's first stride, 4 deg, is not judged nor usual, decision L505)
    assert extras[:5] == [0.0] * 5 and extras[7] == 0.0 and extras[8] == 0.0
    assert math.degrees(extras[5]) == pytest.approx(91 - 5.5, abs=1e-9)
    assert math.degrees(extras[6]) == pytest.approx(89 - 5.5, abs=1e-9)
    # a broken run's strides (two sideways, then a forward one) count as usual offsets, as offline's "other strides"
    run = SideRun()
    for d in (0, 90, 90, 0):  # the first stride not judged (L505)
        run.stride(*_stride(d), 0.4)
    assert sorted(math.degrees(a) for a in run.others) == pytest.approx([0, 90, 90], abs=1e-9)
    # a step frame turned 90 deg from the foot: a stride along the step frame's x travels sideways
    run = SideRun()
    assert [run.stride(0.4, 0.0, 0.4, frame=math.pi / 2) for _ in range(4)][3] == pytest.approx(math.pi / 2)
    # the rules' length against the stride's x (L37): the stride goes along its displacement (pi more)
    run = SideRun()
    ex = [run.stride(-0.01, 0.4, 0.4) for _ in range(4)][3]  # the first one not judged (L505)
    assert ex == pytest.approx(math.pi - math.atan2(0.4, 0.01), abs=1e-12)
    assert 0.4 * math.cos(ex) == pytest.approx(-0.01, abs=1e-3) and 0.4 * math.sin(ex) == pytest.approx(0.4, abs=1e-3)


def _sim(route: str, user: int = 4):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=1, scenario="route")


def _streamed(s, on: bool, **kw):
    from experiments.side_steps_streamed import before_e124

    logging.disable(logging.WARNING)
    try:
        with contextlib.nullcontext() if on else before_e124():
            return get_pipeline("plasys")(s, streaming=True, **kw)
    finally:
        logging.disable(logging.NOTSET)


def test_track_streaming_puts_a_side_stretch_sideways():
    s = _sim("side:-4")
    off, on = (_streamed(s, flag) for flag in (False, True))
    e_off, e_on = (evaluate_track(r, s)["final_position_error_m"] for r in (off, on))
    assert e_off > 4.0 and e_on < 2.0, (e_off, e_on)
    assert on.trajectory["y"].iloc[-1] < -2.5  # to the right, as walked
    assert on.steps["length_m"].sum() == pytest.approx(off.steps["length_m"].sum(), abs=1e-12)


@pytest.mark.parametrize("route", ["A", "straight:5, backward:6, straight:5"])
def test_tracks_without_side_steps_are_the_same(route):
    s = simulate(route, 4, rate_hz=20.0, seed=1) if len(route) == 1 else _sim(route)
    off, on = (_streamed(s, flag) for flag in (False, True))
    assert np.array_equal(off.trajectory[["x", "y"]].to_numpy(), on.trajectory[["x", "y"]].to_numpy())
    assert np.array_equal(off.steps["heading_rad"].to_numpy(), on.steps["heading_rad"].to_numpy())


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def test_run_equals_track_streaming_on_a_side_stretch(root):
    from experiments.side_steps_streamed import before_e124

    s = _sim("straight:4, side:2, straight:4")
    logging.disable(logging.WARNING)
    try:
        runs = [replay(Tracker(root / "bundle"), s, chunk) for chunk in (0.5, 1.0)]
        res = get_pipeline("plasys")(s, model=str(root / "model"), streaming=True)
    finally:
        logging.disable(logging.NOTSET)
    t = res.trajectory
    for steps in runs:
        assert len(steps) == len(t) - 1
        assert np.allclose([(st.x, st.y) for st in steps], t[["x", "y"]].to_numpy()[1:], atol=1e-9)
        assert np.allclose(np.cos([st.heading_rad for st in steps]), np.cos(res.steps["heading_rad"]), atol=1e-9)
    logging.disable(logging.WARNING)
    try:
        with before_e124():
            before = replay(Tracker(root / "bundle"), s, 1.0)
    finally:
        logging.disable(logging.NOTSET)
    assert abs(before[-1].y - runs[0][-1].y) > 0.5  # the rule moved the run's track


def test_the_usual_travel_angle_reads_a_bounded_window(monkeypatch):
    """E124 (session 28 review): the streamed tracker's usual travel angle is the median of the latest
    SIDE_USUAL_STRIDES strides outside any run, so its state stays bounded over a long stream (main: one float per
    stride for the whole stream)."""
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    import math

    from pdrlearn.kernels.sideways import SIDE_USUAL_STRIDES, SideRun

    run = SideRun()
    for _ in range(3 * SIDE_USUAL_STRIDES):
        assert run.stride(1.0, 0.02, 1.0) == 0.0  # forward strides
    assert len(run.others) == SIDE_USUAL_STRIDES
    turns = [run.stride(0.02, 0.6, 0.6) for _ in range(4)]  # a side-stepping stretch to the left
    assert turns[:2] == [0.0, 0.0] and all(abs(a - (math.atan2(0.6, 0.02) - math.atan2(0.02, 1.0))) < 1e-9
                                            for a in turns[2:])
