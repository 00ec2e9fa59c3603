"""Trajectory parity (issue 7): ``Tracker`` streaming a session reproduces ``track_plasys(streaming=True)``
within 1 mm at every step, because both run the stride kernel :mod:`pdrlearn.kernels.stride`."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels import stride as SK
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import replay, rest_dirs, synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def _stream(tr: Tracker, session, chunk_s: float = 0.37) -> list:
    return replay(tr, session, chunk_s)


@pytest.mark.parametrize("heading", ["foot", "auto"])
def test_streamed_trajectory_equals_streaming_track_within_1mm(trained, heading):
    s = synthetic_session(24, seed=11, name="parity", turn_rad_per_step=0.3)
    res = get_pipeline("plasys")(s, method="M3", model=str(trained / "model"), streaming=True, heading=heading)
    steps = _stream(Tracker(trained / "bundle", heading_source=heading), s)
    assert len(steps) == len(res.steps) >= 20
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)
    np.testing.assert_allclose([st.end_s for st in steps], res.steps["end_s"], atol=1e-12)
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    want = res.trajectory[["x", "y", "z"]].to_numpy()[1:]
    assert np.abs(got - want).max() < 1e-3  # issue 7: within 1 mm at every step
    np.testing.assert_allclose([st.length_m for st in steps], res.steps["length_m"], atol=1e-6)
    np.testing.assert_allclose([st.heading_rad for st in steps], np.unwrap(res.steps["heading_rad"]), atol=1e-9)
    # the walk turns (0.3 rad per stride of yaw rate in the synthetic sensor frame), so the heading matters
    assert np.median(np.diff([st.heading_rad for st in steps])) > 0.1


def test_rest_boundary_model_tracks_like_streaming_track(tmp_path_factory):
    """A model on rest-to-rest windows (decision 13): the runtime classifies rest-cut windows like
    predict_steps, the displacement stays stance to stance, so the trajectory still matches within 1 mm."""
    root = rest_dirs(tmp_path_factory)["rest_root"]
    s = synthetic_session(24, seed=11, name="parity", turn_rad_per_step=0.3)
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del s.streams[name]
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, heading="foot")
    tr = Tracker(root / "bundle", heading_source="foot")
    assert tr.boundaries == "rest"
    steps = _stream(tr, s)
    assert len(steps) == len(res.steps) >= 20
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_streaming_track_rejects_session_wide_options(trained):
    s = synthetic_session(6, seed=2)
    fn = get_pipeline("plasys")
    with pytest.raises(DataError, match="not streamable"):
        fn(s, method="M1", streaming=True)
    with pytest.raises(DataError, match="waist/fused headings"):
        fn(s, method="M2", streaming=True, heading="fused")
    with pytest.raises(DataError, match="not streamable"):
        fn(s, method="M3", model="oracle", streaming=True, rules="bayes")


def test_stride_rules_kernel():
    disp = np.array([[0.6, 0.8, 0.3], [-0.3, 0.4, -0.2], [1.2, 0.0, 0.0], [0.5, 0.0, 0.1]])
    bounds = {"short": (0.0, 0.6), "normal": (0.6, 0.9), "long": (0.92, 20.0)}
    length, dz = SK.apply_stride_rules(disp, ["up", "down", "flat", None], ["forward", None, "backward", None],
                                       ["long", "normal", "normal", None], bounds=bounds)
    # up: horizontal 1.0 inside long; down: 3-axis norm 0.539 (eq. 61) with the estimate's sign, clamped up
    # to normal's 0.6; backward prevails over the estimate and 1.2 is clamped to normal's 0.9; no class: raw
    np.testing.assert_allclose(length, [1.0, -0.6, -0.9, 0.5])
    np.testing.assert_allclose(dz, [0.3, -0.2, 0.0, 0.1])  # stairs |dz|, flat 0, unknown terrain: estimate


def test_one_stride_rules_equal_the_array_path():
    """The runtime's one-stride call (Python scalars) gives the array path's bits for every combination of
    classes (incl. missing and unknown ones), bounds and down mode."""
    import itertools

    rng = np.random.default_rng(3)
    bounds = {"short": (0.0, 0.6), "normal": (0.6, 0.9), "long": (0.92, 20.0)}
    for te, di, lc, b, dm in itertools.product(["flat", "up", "down", None, "", float("nan")],
                                               ["forward", "backward", "left", None],
                                               ["short", "normal", "long", "huge", None], [bounds, None],
                                               ["norm3", "horizontal"]):
        d = rng.normal(size=3) * [1.0, 0.3, 0.2]
        one = SK.apply_stride_rules(d, [te], [di], [lc], bounds=b, down_mode=dm)
        two = SK.apply_stride_rules(np.vstack([d, d]), [te, te], [di, di], [lc, lc], bounds=b, down_mode=dm)
        assert one[0].shape == one[1].shape == (1,)
        assert (one[0][0], one[1][0]) == (two[0][0], two[1][0]), (te, di, lc, b, dm)

def test_zupt_displacement_of_a_known_stride():
    """A stride with acceleration a(t) = A sin(2 pi t / T) forward, starting and ending at rest, moves
    A T^2 / (2 pi) (exact); a constant accelerometer bias is removed by the ZUPT."""
    T, A = 1.0, 3.0
    t = np.linspace(0.0, T, 205)
    acc = np.zeros((len(t), 3))
    acc[:, 0] = A * np.sin(2 * np.pi * t / T) + 0.2  # + bias 0.2 m/s^2
    d = SK.zupt_displacement(t, acc)
    assert d[0] == pytest.approx(A * T**2 / (2 * np.pi), rel=1e-3)
    assert abs(d[1]) < 1e-12 and abs(d[2]) < 1e-12


def test_segmenter_is_chunk_invariant():
    rng = np.random.default_rng(0)
    t = np.arange(0, 20, 0.01)
    moving = (np.sin(2 * np.pi * t) > -0.3)
    gyr = rng.normal(scale=0.05, size=(len(t), 3)) + moving[:, None] * 3.0
    whole = SK.stance_strides(t, gyr)
    seg = SK.StanceSegmenter()
    parts = []
    for i in range(0, len(t), 37):
        parts += seg.update(t[i:i + 37], gyr[i:i + 37])
    assert len(whole) >= 15
    np.testing.assert_array_equal(np.array(parts), whole)


def test_yaw_change_of_consecutive_strides_adds_up():
    """Strides share their boundary: the heading changes of [t0, tb] and [tb, t1] (each cut from samples
    that reach one sample beyond its ends) sum to the change over [t0, t1]."""
    t = np.arange(0.0, 3.0, 0.05)
    rate = np.sin(t) + 0.5
    whole = SK.yaw_change(t, rate, 0.52, 2.47)
    parts = SK.yaw_change(t[8:31], rate[8:31], 0.52, 1.43) + SK.yaw_change(t[28:51], rate[28:51], 1.43, 2.47)
    assert parts == pytest.approx(whole, abs=1e-12)
    assert whole == pytest.approx((np.cos(0.52) - np.cos(2.47)) + 0.5 * 1.95, abs=2e-3)
