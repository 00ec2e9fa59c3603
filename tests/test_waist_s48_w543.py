"""Decision W543: the gyro heading keeps gentle curves (runs of same-sign strides under seed 003's turning class,
integrated at the stride's mean rate) with ``gentle_curves``; sways, single strides, a bias under 1.5 deg/s and the
strides after an integrated one are left alone, and the live tracker equals its realtime replay."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels import waist as K
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.heading import TurnClassifier
from tests.runtime_helpers import push_waist


def test_gentle_curve_strides_are_runs_of_same_sign_strides():
    r = K.GENTLE_RPS + 0.01
    none = np.zeros(7, dtype=bool)
    run = np.array([0.0, r, r, r, r, 0.0, 0.0])
    got = K.gentle_curve_strides(run, none)
    # the run's first stride waits for the two after it (one of look-ahead only): strides 2-4 are kept
    assert got.tolist() == [False, False, True, True, True, False, False]
    assert not K.gentle_curve_strides(np.array([0.0, r, r, 0.0, r, r, 0.0]), none).any()  # runs of two
    assert not K.gentle_curve_strides(np.array([r, -r, r, -r, r, -r, r]), none).any()  # a sway
    assert not K.gentle_curve_strides(np.full(7, K.GENTLE_RPS - 0.001), none).any()  # under 1.5 deg/s
    assert K.gentle_curve_strides(-run, none).tolist() == got.tolist()  # either direction
    done = none.copy()
    done[2] = True  # seed 003 integrated step 2: it stays its own, and step 3's stride holds it
    assert K.gentle_curve_strides(run, done).tolist() == [False] * 4 + [True, False, False]


def _rate_walk(rate_rps, n_steps=24, step_s=0.55, fs=50.0):
    t = np.arange(0.0, n_steps * step_s + 0.5, 1.0 / fs)
    w = np.full(t.size, 0.0) + (rate_rps(t) if callable(rate_rps) else rate_rps)
    return t, w, np.arange(n_steps + 1) * step_s


def _heading_change(t, w, ev, gentle):
    h, turning = K.gyro_headings(t, w, ev, predict=TurnClassifier().predict,
                                 gentle_curves=gentle)
    assert not turning.any()
    return float(h[-1] - h[0])


def test_a_gentle_curve_turns_the_heading_and_a_sway_or_a_small_bias_does_not():
    t, w, ev = _rate_walk(0.06)  # 3.4 deg/s: under the W7 prior's 0.136 rad/s boundary
    assert _heading_change(t, w, ev, False) == 0.0
    turned = _heading_change(t, w, ev, True)
    true = 0.06 * (ev[-2] - ev[0])
    assert true - 0.06 * 2 * 0.55 - 1e-9 <= turned <= true + 1e-9  # at most the first stride lost
    t, w, ev = _rate_walk(lambda t: 0.3 * np.sin(np.pi * t / 0.55))  # the pelvis's swing, one per stride
    assert abs(_heading_change(t, w, ev, True)) < 1e-9
    t, w, ev = _rate_walk(np.radians(0.5))  # Cb's bias: under GENTLE_RPS
    assert _heading_change(t, w, ev, True) == 0.0


@pytest.fixture(scope="module")
def curve():
    return simulate_path(parse_route("straight:6, curve:90:15, straight:6"), UserProfile.from_seed(4),
                         speed="normal", rate_hz=50.0, seed=4, name="w543", scenario="route", bounce="pendulum")


def test_a_simulated_gentle_curve_is_kept(curve):
    off = track_waist(curve, pipeline="waist-pendulum", gentle_curves=False)
    on = track_waist(curve, pipeline="waist-pendulum", gentle_curves=True)
    e_off, e_on = (evaluate_track(r, curve)["final_position_error_m"] for r in (off, on))
    assert e_on < 0.5 * e_off
    np.testing.assert_array_equal(on.steps["length_m"], off.steps["length_m"])  # headings only
    np.testing.assert_array_equal(on.steps["turning"], off.steps["turning"])


def test_live_gentle_curves_equal_the_realtime_replay(curve):
    a = curve["wAccelerometer"]
    tr = WaistTracker(a.rate_hz, meta=curve.meta, frame=curve.require_frame("waist"), gentle_curves=True)
    out = push_waist(tr, curve, list(np.random.default_rng(11).integers(1, 200, 400)))
    ref = track_waist(curve, pipeline="waist-pendulum", realtime=True, gentle_curves=True)
    off = track_waist(curve, pipeline="waist-pendulum", realtime=True, gentle_curves=False)
    assert len(out) == len(ref.steps) > 20
    h = np.array([o.heading_rad for o in out])
    assert np.abs(np.angle(np.exp(1j * (h - ref.steps["heading_rad"].to_numpy())))).max() < 1e-9
    assert np.abs(ref.steps["heading_rad"].to_numpy() - off.steps["heading_rad"].to_numpy()).max() > 0.5
