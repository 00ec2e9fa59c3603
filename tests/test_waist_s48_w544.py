"""Decision W544: W543's gentle-curve test reads each stride's rate less W105's reading at rest, so a waist gyro
bias over 1.5 deg/s read while the unit stands still is no gentle curve; offline only (realtime and live keep W543)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels import waist as K
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist.heading import TurnClassifier
from pdrlearn.waist.live import unapplied_options_line
from pdrlearn.waist.params import WaistParams
from tests.test_waist_s48_w543 import _rate_walk

BIAS = np.radians(2.0)  # R2-F3's bias: over GENTLE_RPS on every straight stride


def _turn(t, w, ev, bias):
    h, turning = K.gyro_headings(t, w, ev, predict=TurnClassifier().predict, gentle_curves=True,
                                 gentle_bias_rps=bias)
    assert not turning.any()
    return float(h[-1] - h[0])


def test_the_rate_at_rest_is_taken_from_the_gentle_curve_test_only():
    t, w, ev = _rate_walk(BIAS)  # a straight walk on a biased gyroscope
    assert _turn(t, w, ev, 0.0) > 0.3  # W543 alone integrates the bias (R2-F3)
    assert _turn(t, w, ev, BIAS) == 0.0  # W544: no curve once the reading at rest is taken off
    t, w, ev = _rate_walk(0.06 + BIAS)  # a gentle curve on the same gyroscope
    true = 0.06 * (ev[-2] - ev[0])
    assert true - 0.06 * 2 * 0.55 - 1e-9 <= _turn(t, w, ev, BIAS) <= true + 1e-9  # the curve's own rate
    assert K.gentle_rest_rate(None) == 0.0 and K.gentle_rest_rate((BIAS, 0.0, 5.0), on=False) == 0.0
    assert K.gentle_rest_rate((BIAS, 0.0, 5.0)) == BIAS


@pytest.fixture(scope="module")
def biased():
    s = simulate_path(parse_route("straight:40, turn:90, straight:20"), UserProfile.from_seed(7), speed="normal",
                      rate_hz=50.0, seed=7, name="w544", scenario="route", bounce="pendulum")
    g = s.streams["wGyroscope"]
    g.values = g.values + np.array([0.0, BIAS, 0.0])  # waist frame: y up; the simulator stands still first
    return s


def test_a_bias_read_at_rest_is_no_gentle_curve_offline(biased):
    res = {g: track_waist(biased, pipeline="waist-pendulum", gentle_rest_bias=g) for g in (False, True)}
    err = {g: evaluate_track(r, biased)["final_position_error_m"] for g, r in res.items()}
    assert err[True] < 0.5 * err[False]
    np.testing.assert_array_equal(res[True].steps["length_m"], res[False].steps["length_m"])  # headings only
    assert any("decision W105" in w for w in res[True].info["warnings"])  # W105 still says so


def test_realtime_and_live_do_not_apply_it(biased):
    rt = {g: track_waist(biased, pipeline="waist-pendulum", realtime=True, gentle_rest_bias=g) for g in (False, True)}
    np.testing.assert_array_equal(rt[True].steps["heading_rad"], rt[False].steps["heading_rad"])
    p = WaistParams()
    assert unapplied_options_line(p) is None or "gentle_rest_bias" not in unapplied_options_line(p)
    p.options = {"gentle_rest_bias": True}
    assert "gentle_rest_bias=true" in unapplied_options_line(p)  # E107: named where the PARAMS.json gives it
    assert OPTION_DEFAULTS["gentle_rest_bias"] is K.GENTLE_DEFAULTS["gentle_rest_bias"] is True
