"""Learned second stage of the offline waist IC detector (decision W33): the trees-as-data classifier,
the non-maximum suppression, the shipped model and the detector option."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.waist import learned as L
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import InitialContactDetector
from tests.test_waist import synth_session


def _stump_model(threshold=0.5) -> L.TreeEnsembleClassifier:
    """Two hand-made trees on two features: tree 1 splits feature 0 at 1.0 (NaN -> right), leaves -2 / +2;
    tree 2 splits feature 1 at 0.0 (NaN -> left), leaves +1 / -1; baseline 0.5."""
    trees = [{"feature": [0, 0, 0], "threshold": [1.0, 0.0, 0.0], "left": [1, 0, 0], "right": [2, 0, 0],
              "leaf": [False, True, True], "value": [0.0, -2.0, 2.0], "missing_left": [False, False, False]},
             {"feature": [1, 0, 0], "threshold": [0.0, 0.0, 0.0], "left": [1, 0, 0], "right": [2, 0, 0],
              "leaf": [False, True, True], "value": [0.0, 1.0, -1.0], "missing_left": [True, False, False]}]
    return L.TreeEnsembleClassifier(baseline=0.5, trees=trees, features=("a", "b"), threshold=threshold)


def test_tree_ensemble_by_hand():
    m = _stump_model()
    X = np.array([[0.0, -1.0],    # left (-2), left (+1): 0.5 - 2 + 1 = -0.5
                  [1.0, 0.0],     # x <= threshold goes left in both: -0.5
                  [3.0, 5.0],     # right (+2), right (-1): 1.5
                  [np.nan, np.nan]])  # NaN: right (+2) in tree 1, left (+1) in tree 2: 3.5
    raw = m.decision_function(X)
    np.testing.assert_allclose(raw, [-0.5, -0.5, 1.5, 3.5])
    p = m.predict_proba(X)
    np.testing.assert_allclose(p[:, 1], 1 / (1 + np.exp(-raw)))
    np.testing.assert_allclose(p.sum(axis=1), 1.0)
    assert m.predict(X).tolist() == [0, 0, 1, 1]
    with pytest.raises(DataError):
        m.decision_function(np.zeros((2, 3)))


def test_tree_ensemble_json_round_trip_and_bad_trees(tmp_path):
    m = _stump_model(threshold=0.7)
    path = tmp_path / "m.json"
    m.save(path)
    m2 = L.TreeEnsembleClassifier.from_dict(json.loads(path.read_text()))
    X = np.random.default_rng(0).normal(size=(50, 2))
    np.testing.assert_array_equal(m.decision_function(X), m2.decision_function(X))
    assert m2.threshold == 0.7
    bad = m.to_dict()
    bad["trees"][0]["left"][0] = 7  # a child that does not exist
    with pytest.raises(DataError):
        L.TreeEnsembleClassifier.from_dict(bad)
    bad = m.to_dict()
    bad["schema"] = 99
    with pytest.raises(DataError):
        L.TreeEnsembleClassifier.from_dict(bad)
    with pytest.raises(DataError):  # features differ from this version's FEATURES
        L.TreeEnsembleClassifier.load(path)


def test_from_sklearn_matches_sklearn():
    from sklearn.ensemble import HistGradientBoostingClassifier

    rng = np.random.default_rng(1)
    X = rng.normal(size=(400, 3))
    y = (X[:, 0] + X[:, 1] ** 2 - 0.5 * X[:, 2] > 0.8).astype(int)
    sk = HistGradientBoostingClassifier(max_depth=3, max_iter=30, random_state=0).fit(X, y)
    m = L.TreeEnsembleClassifier.from_sklearn(sk, features=("x0", "x1", "x2"), threshold=0.5)
    Xt = rng.normal(size=(300, 3))
    np.testing.assert_allclose(m.predict_proba(Xt), sk.predict_proba(Xt), atol=1e-12)


def test_suppress_by_hand():
    t = np.array([0.0, 0.2, 0.35, 0.9, 1.0, 2.0])
    s = np.array([0.6, 0.9, 0.7, 0.8, 0.85, 0.3])
    # by score: 0.2 kept; 1.0 kept; 0.9 (0.1 from 1.0) no; 0.35 (0.15 from 0.2) no; 0.0 (0.2) no; 2.0 < thr
    assert L.suppress(t, s, 0.5, 0.3).tolist() == [False, True, False, False, True, False]
    # exactly the radius apart is allowed (the shortest step in whole samples, W28)
    assert L.suppress(np.array([0, 30]), np.array([1.0, 0.9]), 0.5, 30).tolist() == [True, True]
    assert not L.suppress(t, s, 0.95, 0.3).any()


def test_shipped_model_loads():
    m = L.TreeEnsembleClassifier.load()
    assert m.features == L.FEATURES
    assert 0.0 < m.threshold < 1.0 and len(m.trees) > 10
    p = m.predict_proba(np.zeros((3, len(L.FEATURES))))[:, 1]
    assert np.all(np.isfinite(p)) and np.all((p >= 0) & (p <= 1))


def test_learned_detector_on_synthetic_gait(tmp_path):
    from pdrlearn.steps.evaluate import score_events

    s = synth_session(duration=20.0, fs=100.0)
    imu = waist_imu(s)
    det = InitialContactDetector(learned=True).detect(imu)
    ref = s.extras["contacts"]["ic_s"].to_numpy()
    ref = ref[(ref > 3.5) & (ref < 16.5)]
    ev = det.steps_["event_s"].to_numpy()
    assert np.all(np.diff(det.ic_) >= 30) and det.ic_.size == det.fc_.size == det.anchor_.size
    sc = score_events(ev[(ev > 3.5) & (ev < 16.5)], ref)
    assert sc["f1"] > 0.95
    path = tmp_path / "copy.json"  # a model file given by path gives the same contacts
    L.shipped_model().save(path)
    np.testing.assert_array_equal(InitialContactDetector(learned=str(path)).detect(imu).ic_, det.ic_)
    # a model that accepts nothing gives no contacts; the option is off by default
    none = _stump_model(threshold=1.1)
    ic, anchor = L.learned_contacts(imu.acc_v, imu.acc_ap, imu.acc_ml, imu.w_z, imu.fs, det.anchor_,
                                    model=L.TreeEnsembleClassifier(baseline=0.0, trees=[], features=L.FEATURES,
                                                                   threshold=none.threshold),
                                    walk_threshold=0.5)
    assert ic.size == 0 and anchor.size == 0
    assert InitialContactDetector().learned is False


@pytest.mark.parametrize("text", ["", "[]", "null", '{"schema": 99}', "BASE_NO_BASELINE", "BASE_BAD_TREE",
                                  "BASE_TEXT_BASELINE"])
def test_load_names_the_file_for_any_bad_content(tmp_path, text):
    # review: valid JSON of the wrong shape raised AttributeError/KeyError/TypeError/ValueError without the
    # file's name (missing/unparsable files already gave one DataError line naming it)
    d = _stump_model().to_dict()
    if text == "BASE_NO_BASELINE":
        text = json.dumps({k: v for k, v in d.items() if k != "baseline"})
    elif text == "BASE_BAD_TREE":
        text = json.dumps({**d, "trees": [{"feature": [0]}]})
    elif text == "BASE_TEXT_BASELINE":
        text = json.dumps({**d, "baseline": "x"})
    path = tmp_path / "ic_model.json"
    path.write_text(text)
    with pytest.raises(DataError, match="ic_model.json") as e:
        L.TreeEnsembleClassifier.load(path)
    assert "\n" not in str(e.value)
    with pytest.raises(DataError, match="ic_model.json"):
        L.TreeEnsembleClassifier.load(tmp_path / "missing" / "ic_model.json")
