"""Decisions W501-W503 (session 44, issue 8): why calibrating makes the real straight walks worse, and the gain
estimators measured against the current fit (experiments/waist_calibration_s44.py)."""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
import pytest

from experiments import waist as W
from experiments import waist_calibration_s44 as C
from pdrlearn.io import read_session
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.calibration import calibrate, calibration_walks
from pdrlearn.waist.params import DEFAULT_K, WaistParams, resolve_params
from tests.conftest import external_session

PENDULUM = [W.CONFIGS[0]]


@pytest.fixture(autouse=True)
def _quiet():
    logging.disable(logging.WARNING)  # calibrate's W169 short-walk line on every 8-step walk
    yield
    logging.disable(logging.NOTSET)


def _params(k_cal: float, se: float | None) -> WaistParams:
    p = WaistParams()
    p.k, p.f_m = k_cal, 0.0
    p.k_shrinkage = {"k_cal": k_cal, "se": se}
    return p


def test_w501_ha001_test5_calibrations_are_k_only_8_straight_steps_and_k0_lies_between_them():
    """W501: each HA001 Test5 trial is one straight 8-step bout, fitted K only with F = 0 (W8), no turning step,
    no merged fragment; the two trials' gains lie 7.7 % apart with the population K0 between them (so the defaults
    beat either calibration on the other trial), and their interior steps alone keep the gap (not the bout edges)."""
    ks, inner = [], []
    for trial in ("Trial1", "Trial2"):
        s = read_session(external_session(f"mobgap_HA001_Test5_{trial}"))
        p = calibrate([s], "waist-pendulum", params=resolve_params(s, None)[0])
        (w,) = calibration_walks(s, "waist-pendulum", params=p)
        assert p.f_m == 0.0 and len(w.g) == 8 and np.all(w.factors() > 0.95)
        ks.append(p.k)
        inner.append(w.distance_m * 6 / 8 / float(np.sum(w.g[1:-1])))
    assert min(ks) < DEFAULT_K < max(ks)
    assert abs(ks[0] / ks[1] - 1) > 0.07 and abs(inner[0] / inner[1] - 1) > 0.07


def test_w503_the_adjust_hook_tests_the_adjusted_gain():
    """experiments/waist.py real(): ``adjust`` replaces the calibrated params; K0 in place of the fit reads exactly
    as the uncalibrated defaults row on HA001 Test5 (F = 0 both)."""
    d = external_session("mobgap_HA001_Test5_Trial1").parent
    runs = [(["mobgap_HA001_Test5_Trial1"], "mobgap_HA001_Test5_Trial2")]

    def to_k0(params, sessions, distances):
        return dataclasses.replace(params, k=DEFAULT_K)

    plain = W.real(d, runs, PENDULUM)
    adj = W.real(d, runs, PENDULUM, adjust=to_k0)
    cal, dflt = plain.set_index("params").bout_err_median_pct, adj.set_index("params").bout_err_median_pct
    assert cal["calibrated"] == pytest.approx(7.668, abs=5e-3)  # W501's table
    assert dflt["calibrated"] == pytest.approx(cal["defaults"], abs=1e-9)
    assert dflt["calibrated"] != pytest.approx(cal["calibrated"], abs=0.5)


def test_w503_pretest_keeps_k0_inside_its_interval_and_the_fit_outside():
    adj = C.arm_adjust("pretest")
    assert adj(_params(DEFAULT_K + 1.9 * 0.03, 0.03), [], None).k == DEFAULT_K
    assert adj(_params(DEFAULT_K - 1.9 * 0.03, 0.03), [], None).k == DEFAULT_K
    assert adj(_params(DEFAULT_K + 2.0 * 0.03, 0.03), [], None).k == pytest.approx(DEFAULT_K + 0.06)
    assert adj(_params(1.3, None), [], None).k == 1.3  # no standard error (1 stride): the fit


def test_w503_shrunk_arm_is_w48s_weighted_mean_and_a_joint_fit_is_left_alone():
    p = _params(1.22, 0.0336)
    assert C.arm_adjust("shrunk", lambda s: 0.05)(p, [], None).k == pytest.approx(
        K.shrink_gain(1.22, 0.0336, DEFAULT_K, 0.05))
    joint = dataclasses.replace(p, f_m=-0.1)
    assert C.arm_adjust("shrunk")(joint, [], None).k == 1.22


def test_w503_simulated_calibration_walk_length_is_the_option():
    """The short (Test5-like) simulated calibration walk: fewer strides than experiments/waist.py's 60 m walk."""
    fits: list = []
    W.simulated([1], PENDULUM, fits=fits, cal_length_m=5.0)
    W.simulated([1], PENDULUM, fits=fits)
    n_short, n_long = (p.k_shrinkage["n_strides"] for _u, _l, p in fits)
    assert n_short <= 5 < 40 <= n_long
