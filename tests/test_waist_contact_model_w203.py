"""Decision W203: the learned contact re-scorer of the offline lower-back `waist-pendulum` (``contact_model``)."""

import json

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist import contact_model as cm
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import gate_threshold

DAILY = ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, "
         "straight:4, turn:-135, straight:4, stand:3")  # W111's daily route (W189's SIM_ROUTES)


def test_features_by_hand():
    ev = np.array([0.0, 0.5, 1.0, 1.6, 5.0])
    hn = np.array([True, True, True, False, False])  # a run of four, then a lone contact
    bounce = np.array([2.0, 2.0, 4.0, 2.0, 0.5])
    v = np.array([0.1, -0.2, 0.1, -0.1, 0.0])
    side = np.array([1, -1, 1, -1, 0])
    gate = np.array([1.0, 2.0, np.e, 1.0, 0.5])
    tilt = np.array([0.0, 5.0, 25.0, 0.0, 50.0])
    flexed = np.array([0, 0, 1, 0, 1])
    dyaw = np.array([0.0, np.radians(15.0), np.radians(-30.0), 0.0, 0.0])
    X = cm.feature_matrix(ev, hn, bounce, v, side, gate, tilt, flexed, dyaw)
    f = {k: X[:, i] for i, k in enumerate(cm.FEATURES)}
    assert X.shape == (5, len(cm.FEATURES))
    np.testing.assert_allclose(f["bounce_rel"], bounce / 2.0)  # median bounce 2
    np.testing.assert_allclose(f["run_bounce_rel"], [1, 1, 1, 1, 0.25])  # run medians 2 and 0.5
    np.testing.assert_allclose(f["sway_rel"], np.abs(v) / 0.1)  # median |v| 0.1
    np.testing.assert_allclose(f["side_decided"], [1, 1, 1, 1, 0])
    np.testing.assert_allclose(f["paired"], [1, 1, 1, 1, 0])
    # step times 0.5, 0.5, 0.6: median 0.5; missing neighbours read MISSING_DT_REL
    np.testing.assert_allclose(f["dt_prev_rel"], [3.0, 1.0, 1.0, 1.2, 3.0])
    np.testing.assert_allclose(f["dt_next_rel"], [1.0, 1.0, 1.2, 3.0, 3.0])
    np.testing.assert_allclose(f["rhythm_irregularity"], [1.0, 0.0, 0.1 / 1.1, 1.0, 1.0])
    np.testing.assert_allclose(f["log_run_len"], np.log([4, 4, 4, 4, 1]))
    np.testing.assert_allclose(f["log_gate_rel"], np.log(gate))
    np.testing.assert_allclose(f["tilt_rel"], tilt / 25.0)
    np.testing.assert_allclose(f["flexed"], flexed)
    np.testing.assert_allclose(f["turn_rel"], [0, 1, 2, 0, 0])
    assert cm.feature_matrix(*(np.zeros(0),) * 9).shape == (0, len(cm.FEATURES))


def _toy(seed=3):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(300, len(cm.FEATURES)))
    y = (X[:, 0] + 0.5 * rng.normal(size=300) > -1.0).astype(int)
    return X, y


def test_training_is_deterministic_and_calibrated_by_c67():
    from sklearn.linear_model import LogisticRegression
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    from pdrlearn.classify.calibration import cv_scores, fit_temperature

    X, y = _toy()
    a, b = cm.fit_contact_model(X, y), cm.fit_contact_model(X, y)
    assert a.to_json() == b.to_json()
    held = cv_scores(lambda: make_pipeline(StandardScaler(), LogisticRegression(max_iter=1000, random_state=0)), X, y,
                     lambda e, x: np.column_stack([np.zeros(len(x)), e.decision_function(x)]), random_state=0)
    assert a.temperature == pytest.approx(fit_temperature(*held))
    p = a.proba(X)
    assert ((p >= 0.5) == (a.decision(X) >= 0)).all()  # a positive temperature keeps the decision
    assert ((p >= 0.5) == y).mean() > 0.8
    with pytest.raises(DataError, match="one class only"):
        cm.fit_contact_model(X, np.ones(len(y), dtype=int))


def test_round_trip_and_refusal_lines(tmp_path):
    m = cm.fit_contact_model(*_toy())
    path = tmp_path / "m.json"
    cm.save_contact_model(m, path)
    back = cm.load_contact_model(path)
    X, _ = _toy(4)
    np.testing.assert_allclose(back.proba(X), m.proba(X), atol=1e-8)
    d = json.loads(path.read_text())
    for change, words in (({"version": cm.VERSION + 1}, "version 2, this pdrlearn reads version 1"),
                          ({"features": d["features"][:-1]}, "features differ"),
                          ({"coef": [1.0]}, "do not fit its 13 features"),
                          ({"intercept": "x"}, "not numbers")):
        path.write_text(json.dumps({**d, **change}))
        with pytest.raises(DataError) as err:
            cm.load_contact_model(path)
        line = str(err.value)
        assert "\n" not in line and str(path) in line and words in line and "waist_contact_model.py train" in line
    path.write_text("{not json")
    with pytest.raises(DataError, match="cannot read the contact model"):
        cm.load_contact_model(path)
    with pytest.raises(DataError, match="cannot read"):
        cm.load_contact_model(tmp_path / "missing.json")


def test_shipped_model_loads():
    m = cm.load_contact_model()
    assert "4600-4639" in m.trained_on and m.temperature > 0


@pytest.fixture(scope="module")
def daily():
    return simulate_path(parse_route(DAILY), UserProfile.from_seed(4600), rate_hz=100, seed=4600)


def test_option_end_to_end_on_a_simulated_session(daily):
    assert OPTION_DEFAULTS["contact_model"] is False
    # the contacts the re-scorer sees: no sit or stand veto (W199's default "adjacent" would drop them first)
    raw = track_waist(daily, pipeline="waist-pendulum", sit_veto=False, stand_veto=False)
    on = track_waist(daily, pipeline="waist-pendulum", sit_veto=False, stand_veto=False, contact_model="learned")
    imu = waist_imu(daily)
    thr, sigma, _ = gate_threshold(imu, None, relative=True)
    p = cm.load_contact_model().proba(cm.contact_features(raw.steps, imu, thr, sigma))
    assert (p < 0.5).sum() >= 1  # this session has a contact the model drops (a chair transfer's bounce)
    np.testing.assert_allclose(on.steps["event_s"], raw.steps["event_s"][p >= 0.5])
    assert on.info["n_rescored_contacts"] == int((p < 0.5).sum())
    assert raw.info["n_rescored_contacts"] == 0
    from pdrlearn.waist.params import WaistParams

    par = WaistParams(options={"contact_model": "learned", "sit_veto": False, "stand_veto": False})
    np.testing.assert_allclose(track_waist(daily, pipeline="waist-pendulum", params=par).steps["event_s"],
                               on.steps["event_s"])


def test_bad_value_refused_and_scoped(daily):
    with pytest.raises(DataError) as err:
        track_waist(daily, pipeline="waist-pendulum", contact_model="trees")
    assert "contact_model 'trees' is not one of false, \"learned\"" in str(err.value) and "W203" in str(err.value)
    pll = track_waist(daily, pipeline="waist-pll", contact_model="learned")
    assert any("contact_model" in w and "W203" in w for w in pll.info["warnings"])
    assert pll.info["n_rescored_contacts"] == 0


def test_the_live_line_names_it():
    from pdrlearn.waist.live import unapplied_options_line
    from pdrlearn.waist.params import WaistParams

    line = unapplied_options_line(WaistParams(leg_m=0.9, options={"sit_veto": False, "contact_model": "learned"}))
    assert line is not None and 'contact_model="learned"' in line and "contact_model=false" in line
    live = {"sit_veto": False, "contact_shift": False, "parity_fill": False,  # E126 / E130: what live does
            "stand_veto": False,  # W219: the offline default "walking" is not applied live either
            "pause_ride": False, "rest_bias": False,  # E145: nor W231's nor L296's
            "turn_bridge": False}  # W385: nor W384's offline default "side"
    assert unapplied_options_line(WaistParams(leg_m=0.9, options=live)) is None


def test_flexed_feature_is_posture_near_flexion(daily):  # review S29 item 7: one mechanism, features unchanged
    from pdrlearn.waist import posture

    assert cm.near_flexion is posture.near_flexion
    raw = track_waist(daily, pipeline="waist-pendulum", sit_veto=False, stand_veto=False)
    imu = waist_imu(daily)
    thr, sigma, _ = gate_threshold(imu, None, relative=True)
    feats = cm.contact_features(raw.steps, imu, thr, sigma)
    ev, hn = raw.steps["event_s"].to_numpy(float), raw.steps["has_next"].to_numpy(bool)
    old = np.zeros(ev.size, dtype=bool)  # the inline rule contact_features had before (W104's window)
    for a, peak, b in posture.flexion_events(imu, ev, hn):
        old |= ((ev >= a) & (ev <= b)) | (np.abs(ev - peak) <= posture.TRANSFER_HALF_S)
    col = feats[:, list(cm.FEATURES).index("flexed")]
    assert old.any() and np.array_equal(col, old.astype(float))
