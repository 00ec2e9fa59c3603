"""Per-user distance calibration (docs/decisions/localization.md L26) and the per-device accelerometer
scale errors of the simulator (docs/decisions/simulator.md S22)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace import calibrate_distance, distance_gain, model_distance_calibration, straight_level_forward
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.sim import sensors as sn
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import _distance_gain, track_plasys
from tests.runtime_helpers import scaled_foot_acc


# -- kernel ---------------------------------------------------------------------------------------------
def test_distance_gain_recovers_a_known_ratio_and_rejects_an_outlier():
    rng = np.random.default_rng(0)
    ref = rng.uniform(1.0, 1.6, 200)
    raw = ref / 1.02 * (1 + rng.normal(0.0, 0.005, 200))
    raw[7] = ref[7] * 0.5  # a mislabelled stride: ratio 2
    out = distance_gain(raw, ref)
    assert out["n_outliers"] >= 1 and out["reason"] is None
    assert out["ratio"] == pytest.approx(1.02, abs=0.001)
    assert out["se"] == pytest.approx(0.005 / np.sqrt(199), rel=0.3)
    assert out["stride_sd"] == pytest.approx(0.005, rel=0.25)  # robust sd of one stride's ratio
    # ratio of sums of the kept strides, shrunk by prior^2 / (prior^2 + se^2)
    w = 0.01**2 / (0.01**2 + out["se"] ** 2)
    assert out["gain"] == pytest.approx(1 + w * (out["ratio"] - 1), abs=1e-12)


def test_distance_gain_shrinks_an_uncertain_ratio_towards_one():
    rng = np.random.default_rng(1)
    ref = rng.uniform(1.0, 1.6, 12)
    noisy = ref / 1.03 * (1 + rng.normal(0.0, 0.05, 12))
    out = distance_gain(noisy, ref)
    assert out["reason"] is None and 0 < out["weight"] < 0.8
    assert abs(out["gain"] - 1) < abs(out["ratio"] - 1)


def test_distance_gain_refuses_too_few_strides_and_implausible_labels():
    few = distance_gain([1.0] * 5, [1.01] * 5)
    assert few["gain"] == 1.0 and "usable strides" in few["reason"]
    off = distance_gain(np.full(30, 1.0), np.full(30, 1.3) * np.linspace(0.999, 1.001, 30))
    assert off["gain"] == 1.0 and "check the labelled" in off["reason"]
    with pytest.raises(DataError):
        distance_gain([1.0, 1.0], [1.0])


def test_straight_level_forward_selects_the_straight_level_forward_strides():
    steps = pd.DataFrame({
        "raw_length_m": [1.3, 1.3, 1.3, -0.8, 1.3, 1.3, 1.2, 1.3, 1.3],
        "dz_m": [0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 0.36, 0.0, 0.0],
        "heading_rad": np.radians([0, 2, 4, 4, 4, 90, 90, 92, 92]),
    })
    mask = straight_level_forward(steps)
    # ends: no neighbour; 3: backward; 4, 5: next to the 86 deg turn; 6: a stair stride
    assert mask.tolist() == [False, True, True, False, False, False, False, True, False]


# -- simulator S22 ---------------------------------------------------------------------------------------
def test_accelerometer_scale_errors_belong_to_the_device_not_the_session():
    def scale(**kw):
        s = simulate("A", **kw)
        return np.array(s.meta["sensor_errors"]["fAccelerometer"]["scale"]), s.meta["sensor_errors"]

    a, ea = scale(user_seed=3, seed=0)
    b, _ = scale(user_seed=3, seed=5)
    c, _ = scale(user_seed=4, seed=0)
    # same unit, two sessions: only the turn-on/temperature term (0.05 % sd, ADXL345 0.01 %/degC)
    assert np.max(np.abs(a / b - 1)) < 5 * sn.FOOT_ACC.scale_session_sd
    assert np.max(np.abs(a - c)) > 5 * sn.FOOT_ACC.scale_session_sd  # another user's unit
    old, eo = scale(user_seed=3, seed=0, device_errors=False)
    assert np.max(np.abs(old - a)) > 5 * sn.FOOT_ACC.scale_session_sd  # the per-session model before S22
    assert eo["fAccelerometer"]["bias"] == ea["fAccelerometer"]["bias"]  # other errors unchanged
    assert eo["fGyroscope"] == ea["fGyroscope"]
    with pytest.raises(DataError, match="device_errors"):
        simulate("A", user_seed=1, device_errors=1)


# -- calibration on simulated exercises ------------------------------------------------------------------
@pytest.fixture(scope="module")
def length_exercise():
    return simulate("length", user_seed=2, speed="normal", noise=False)


def test_calibration_recovers_an_injected_accelerometer_scale_error(length_exercise):
    base = calibrate_distance([length_exercise])
    scaled = calibrate_distance([scaled_foot_acc(length_exercise, 1.01)])
    assert base["reason"] is None and base["n_strides"] >= 40
    assert base["rate_hz"] == pytest.approx(20.0)
    # a 1 % larger accelerometer output gives 1 % longer strides: the gain undoes it
    assert scaled["gain"] * 1.01 == pytest.approx(base["gain"], abs=0.001)
    # without sensor errors only the engine's own bias is left (20 Hz averaging, L25): a few 0.1 % at most
    assert abs(base["gain"] - 1.0) < 0.005


def test_calibration_skips_sessions_without_lengths_or_foot(length_exercise):
    no_len = Session(name="nolen", streams=length_exercise.streams,
                     steps=length_exercise.steps.drop(columns=["length_m"]), meta=length_exercise.meta,
                     frames=length_exercise.frames)
    out = calibrate_distance([no_len])
    assert out["gain"] == 1.0 and out["reason"] and "nolen" in out["sessions_skipped"][0]


# -- tracker ---------------------------------------------------------------------------------------------
def test_track_applies_the_gain_to_level_strides_only():
    s = simulate("D", user_seed=1, speed="normal")
    r1 = track_plasys(s, method="M2", distance_gain=1.0)
    r2 = track_plasys(s, method="M2", distance_gain=1.01)
    assert r2.info["distance_gain"] == 1.01 and r2.info["distance_gain_source"] == "argument"
    assert r1.info["distance_gain"] == 1.0
    a, b = r1.steps, r2.steps
    stairs = (a["dz_m"].abs() >= 0.1).to_numpy()  # L26: half a stair rise or more is not level
    assert stairs.sum() >= 10
    np.testing.assert_allclose(b["length_m"][stairs], a["length_m"][stairs])
    np.testing.assert_allclose(b["dz_m"], a["dz_m"])
    level = ~stairs & (a["length_m"].abs() > 0.1).to_numpy()
    np.testing.assert_allclose(b["length_m"][level] / a["length_m"][level], 1.01, rtol=1e-9)
    np.testing.assert_allclose(b["raw_length_m"], a["raw_length_m"])  # raw = the engine's own estimate
    with pytest.raises(DataError, match="distance_gain"):
        track_plasys(s, method="M2", distance_gain=float("nan"))


class _Model:
    def __init__(self, rec):
        self.data_summary = {"distance_calibration": rec} if rec is not None else {}


def test_model_gain_is_used_only_at_the_rate_it_was_estimated_at():
    warnings: list[str] = []
    rec = {"gain": 1.004, "rate_hz": 20.0, "stride_sd": 0.006, "reason": None}
    assert _distance_gain(None, _Model(rec), 20.0, warnings) == (1.004, "model", 0.006)
    assert _distance_gain(1.01, _Model(rec), 20.0, warnings) == (1.01, "argument", 0.006)
    assert _distance_gain(None, _Model(rec), 20.0, warnings, calibration=False)[::2] == (1.0, None)
    g, src, sd = _distance_gain(None, _Model(rec), 100.0, warnings)
    assert (g, sd) == (1.0, None) and "calibration" in src and "recalibrate" in warnings[-1]
    assert _distance_gain(None, _Model(None), 20.0, warnings)[0] == 1.0
    assert _distance_gain(None, "oracle", 20.0, warnings)[0] == 1.0
    assert model_distance_calibration(_Model(None)) is None


def test_calibrated_m2_is_closer_on_the_same_users_unit():
    """With the user's own unit (S22), the gain from the user's calibration exercise transfers to a
    scenario walked with that unit (L26); the signed error moves towards 0."""
    cal = [simulate("length", user_seed=5, speed="normal")]
    rec = calibrate_distance(cal)
    s = simulate("A", user_seed=5, speed="normal")
    before = evaluate_track(track_plasys(s, method="M2"), s)["distance_error_pct"]
    after = evaluate_track(track_plasys(s, method="M2", distance_gain=rec["gain"]), s)["distance_error_pct"]
    assert rec["gain"] > 1.0 and before < 0
    assert abs(after) < abs(before)


def test_train_user_stores_the_calibration_and_m3_uses_it(tmp_path, length_exercise):
    from pdrlearn.classify import load_model, train_user

    cal = simulate("length", user_seed=2, speed="normal")
    model = train_user([cal], tasks=["length"], methods=["svm"], units=["foot"], cv=2)
    rec = model.data_summary["distance_calibration"]
    assert rec["reason"] is None and rec["n_strides"] >= 40 and 0.99 < rec["gain"] < 1.01
    assert 0 < rec["stride_sd"] < 0.03
    model.length_bounds_m = cal.meta["length_class_bounds_m"]
    model.save(tmp_path / "m")
    loaded = load_model(tmp_path / "m")  # the record travels in the manifest (training_data)
    assert loaded.data_summary["distance_calibration"]["gain"] == pytest.approx(rec["gain"])
    s = simulate("A", user_seed=2, speed="normal")
    res = track_plasys(s, method="M3", model=tmp_path / "m")
    assert res.info["distance_gain_source"] == "model"
    assert res.info["distance_gain"] == pytest.approx(rec["gain"])
    assert res.info["stride_sigma_rel"] == pytest.approx(rec["stride_sd"])
    off = track_plasys(s, method="M3", model=loaded, calibration=False)
    assert off.info["distance_gain"] == 1.0 and off.info["stride_sigma_rel"] == 0.03
    # skipped when asked
    assert "distance_calibration" not in train_user([cal], tasks=["length"], methods=["svm"], units=["foot"], cv=2,
                                                    distance_calibration=False).data_summary
