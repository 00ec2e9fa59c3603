"""GNSS/PDR step-triggered Kalman filter, receiver state machine, compensation, step-length model."""

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid._kernels import kf_predict, kf_update
from pdrlearn.aid.fixgen import gnss_fixes
from pdrlearn.aid.gnss import ACQUIRING, OFF, ON, GnssPdrFusion, StepLengthModel, fsm_next
from pdrlearn.aid.synth import pdr_with_drift, position_errors, synthetic_walk
from pdrlearn.errors import DataError


def test_kf_two_step_hand_computed():
    x, P = np.zeros(2), np.eye(2)
    x, P = kf_predict(x, P, 1.0, 0.0, sigma_length_m=0.1, sigma_heading_rad=0.2)
    assert x == pytest.approx([1.0, 0.0]) and np.diag(P) == pytest.approx([1.01, 1.04])
    x, P = kf_predict(x, P, 2.0, np.pi / 2, sigma_length_m=0.1, sigma_heading_rad=0.2)
    # G = [[0, -2], [1, 0]]: Q = diag(4 * 0.04, 0.01)
    assert x == pytest.approx([1.0, 2.0]) and P == pytest.approx(np.diag([1.17, 1.05]), abs=1e-12)
    xu, Pu, nu, nis = kf_update(x, P, np.array([2.0, 2.0]), np.array([1.0]))
    assert xu == pytest.approx([1.0 + 1.17 / 2.17, 2.0])
    assert Pu == pytest.approx(np.diag([1.17 / 2.17, 1.05 / 2.05]), abs=1e-12)
    assert nu == pytest.approx([1.0, 0.0]) and nis == pytest.approx(1.0 / 2.17)
    # size-varying: two fixes at once = their mean with half the variance
    x2, P2, _, _ = kf_update(x, P, np.array([[2.0, 2.0], [0.0, 2.0]]), np.array([1.0, 1.0]))
    assert x2 == pytest.approx([1.0, 2.0]) and P2[0, 0] == pytest.approx(1.17 * 0.5 / 1.67)
    # no fix: open loop
    x0, P0, _, _ = kf_update(x, P, np.zeros((0, 2)), np.zeros(0))
    assert x0 is x and P0 is P


def test_fsm_transitions():
    kw = dict(period_s=60.0, ttff_s=2.0, max_on_s=30.0)
    assert fsm_next(OFF, mode="saving", t=59.0, switched_on_s=0, last_fix_s=0.0, fix_used=False, **kw) == OFF
    assert fsm_next(OFF, mode="saving", t=60.0, switched_on_s=0, last_fix_s=0.0, fix_used=False, **kw) == ACQUIRING
    assert fsm_next(ACQUIRING, mode="saving", t=61.0, switched_on_s=60, last_fix_s=0, fix_used=False, **kw) == ACQUIRING
    assert fsm_next(ACQUIRING, mode="saving", t=62.0, switched_on_s=60, last_fix_s=0, fix_used=False, **kw) == ON
    assert fsm_next(ON, mode="saving", t=63.0, switched_on_s=60, last_fix_s=0, fix_used=True, **kw) == OFF
    assert fsm_next(ON, mode="saving", t=90.0, switched_on_s=60, last_fix_s=0, fix_used=False, **kw) == OFF
    assert fsm_next(OFF, mode="best", t=0.0, switched_on_s=0, last_fix_s=0, fix_used=True, **kw) == ON
    assert fsm_next(ON, mode="off", t=0.0, switched_on_s=0, last_fix_s=0, fix_used=False, **kw) == OFF


def _straight(n=600, length=0.7, heading=0.3, dt=0.5):
    t = np.arange(1, n + 1) * dt
    steps = pd.DataFrame({"start_s": t - dt, "end_s": t, "length_m": length, "heading_rad": heading})
    x = np.r_[0.0, np.cumsum(np.full(n, length * np.cos(heading)))]
    y = np.r_[0.0, np.cumsum(np.full(n, length * np.sin(heading)))]
    truth = pd.DataFrame({"t": np.r_[0.0, t], "x": x, "y": y})
    return steps, truth


def test_energy_saving_uses_one_fix_per_period_and_compensates():
    steps, truth = _straight()
    fx = gnss_fixes(truth, accuracy_m=3.0, correlation_s=0.0, seed=0)
    biased = steps.assign(length_m=steps["length_m"] * 1.1, heading_rad=steps["heading_rad"] + np.radians(10))
    f = GnssPdrFusion(mode="saving", period_s=60.0, ttff_s=1.0).run(biased, fx)
    st = f.stats_
    assert 4 <= st["fixes_used"] <= 5 and st["activations"] == st["fixes_used"]  # 300 s / 60 s
    assert st["gnss_on_fraction"] < 0.1 and st["fixes_while_off"] > 250
    assert f.scale_ == pytest.approx(1 / 1.1, abs=0.03)
    assert np.degrees(f.heading_bias_rad_) == pytest.approx(-10.0, abs=2.0)
    # the compensation shrinks the error between fixes
    g = GnssPdrFusion(mode="saving", period_s=60.0, compensate=False).run(biased, fx)
    e_c, e_n = position_errors(f.trajectory_, truth), position_errors(g.trajectory_, truth)
    assert np.sqrt(np.mean(e_c**2)) < 0.6 * np.sqrt(np.mean(e_n**2))
    # the state column follows the machine
    assert set(f.trajectory_["gnss"]) <= {OFF, ACQUIRING, ON} and (f.trajectory_["gnss"] == OFF).mean() > 0.8


def test_fused_error_below_pdr_on_synthetic_walk():
    steps_true, truth = synthetic_walk(4, length_m=1000)
    pdr = pdr_with_drift(steps_true, 4)
    fx = gnss_fixes(truth, accuracy_m=5.0, seed=4)
    e_pdr = position_errors(pdr.trajectory, truth)
    rmse = {}
    for mode, per in (("best", 60.0), ("saving", 60.0), ("off", 60.0)):
        f = GnssPdrFusion(mode=mode, period_s=per).run(pdr.steps, fx)
        rmse[mode] = float(np.sqrt(np.mean(position_errors(f.trajectory_, truth) ** 2)))
        assert f.trajectory_[["x_pdr", "y_pdr"]].to_numpy() == pytest.approx(pdr.trajectory[["x", "y"]].to_numpy())
    pdr_rmse = float(np.sqrt(np.mean(e_pdr**2)))
    assert rmse["off"] == pytest.approx(pdr_rmse, rel=1e-9)
    assert rmse["best"] < 0.5 * pdr_rmse and rmse["saving"] < pdr_rmse
    assert rmse["best"] < 8.0


def test_step_length_model_rls_converges():
    m = StepLengthModel(a=0.3, b=-0.16, forgetting=1.0)
    rng = np.random.default_rng(0)
    for _ in range(200):
        f = rng.uniform(1.4, 2.2)
        m.update(f, 0.42 * f - 0.05 + 0.005 * rng.standard_normal(), var_m2=0.005**2)
    assert m.a == pytest.approx(0.42, abs=0.02) and m.b == pytest.approx(0.05, abs=0.03)
    assert m.predict(2.0) == pytest.approx(0.79, abs=0.01)


def test_model_step_length_refined_from_gnss():
    steps, truth = _straight(n=900, length=0.75, dt=0.5)  # 2 Hz steps of 0.75 m
    fx = gnss_fixes(truth, accuracy_m=2.0, correlation_s=0.0, seed=1)
    f = GnssPdrFusion(mode="saving", period_s=60.0, step_length="model").run(steps, fx)
    assert f.stats_["model_updates"] >= 3
    assert f.model_.predict(2.0) == pytest.approx(0.75, abs=0.03)


def test_bad_settings_and_tables():
    steps, _ = _straight(n=5)
    with pytest.raises(DataError, match="mode"):
        GnssPdrFusion(mode="eco").run(steps, None)
    with pytest.raises(DataError, match="heading_rad"):
        GnssPdrFusion().run(steps.drop(columns="heading_rad"), None)
    with pytest.raises(DataError, match="NaN"):
        GnssPdrFusion().run(steps.assign(length_m=np.nan), None)


def test_compensation_between_continuous_fixes():
    steps, truth = _straight(n=600)
    fx = gnss_fixes(truth, accuracy_m=5.0, correlation_s=0.0, seed=2)
    biased = steps.assign(length_m=steps["length_m"] * 0.7, heading_rad=steps["heading_rad"] - np.radians(8))
    always = GnssPdrFusion(mode="best").run(biased, fx)
    paper = GnssPdrFusion(mode="best", compensate_when="off").run(biased, fx)
    assert always.stats_["compensations"] > 100
    e_a = np.sqrt(np.mean(position_errors(always.trajectory_, truth) ** 2))
    e_p = np.sqrt(np.mean(position_errors(paper.trajectory_, truth) ** 2))
    assert e_a < e_p
    # averaging the noisy single-baseline estimates (constant true errors) gets closer to them
    smooth = GnssPdrFusion(mode="best", heading_drift_deg_per_min=0.1, scale_drift_per_min=0.001).run(biased, fx)
    assert abs(smooth.scale_ - 1 / 0.7) < abs(always.scale_ - 1 / 0.7)
    assert smooth.scale_ == pytest.approx(1 / 0.7, rel=0.05)
    assert np.degrees(smooth.heading_bias_rad_) == pytest.approx(8.0, abs=1.5)
    with pytest.raises(DataError, match="compensate_when"):
        GnssPdrFusion(compensate_when="sometimes").run(steps, fx)
