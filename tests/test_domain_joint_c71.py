"""Decision C71: the joint (Mahalanobis) domain score sees a stride whose features are each inside their
training range but whose combination the model never saw (a soft foot, a ramp), where C16's range cannot."""

from __future__ import annotations

import json

import joblib
import numpy as np
import pytest

from pdrlearn.classify import train_user
from pdrlearn.classify.domain import (
    JOINT_QUANTILE,
    FeatureRange,
    JointDomain,
    _leaves,
    fit_joint,
    step_joint_score,
)
from pdrlearn.errors import DataError
from tests.test_classify_training import labelled_session


class _Identity:
    """A leaf whose inputs are the windows themselves (a heuristic-style leaf: ``_features`` / ``_stages``)."""

    def _stages(self):
        return ()

    def _feature_names(self, stages):
        return ["a", "b"]

    def _features(self, X, names):
        return X


def _correlated(n=400, seed=0):
    rng = np.random.default_rng(seed)
    a = rng.normal(size=n)
    return np.column_stack([a, a + 0.1 * rng.normal(size=n)])


def test_joint_score_sees_a_combination_the_range_does_not():
    X = _correlated()
    y = np.where(np.arange(len(X)) % 2 == 0, "flat", "up")
    j = fit_joint(_Identity(), X, y)
    r = FeatureRange("x", ["a", "b"], *np.quantile(X, [0.01, 0.99], axis=0), len(X))
    odd = np.array([[1.5, -1.5]])  # each feature inside its 1-99 % range, the pair against the correlation
    assert r.excess(odd).max() == 0.0
    assert j.score(odd)[0] > 3.0
    fresh = _correlated(seed=1)  # the same distribution: about 1 - JOINT_QUANTILE of the strides out
    assert (j.score(fresh) > 1).mean() < 3 * (1 - JOINT_QUANTILE) + 0.02
    assert j.score(j.means * j.scale + j.center).max() == pytest.approx(0.0, abs=1e-9)  # a class mean is in


def test_joint_domain_round_trips_and_refuses_bad_shapes():
    X = _correlated(100)
    j = fit_joint(_Identity(), X, np.array(["a", "b"] * 50))
    back = JointDomain.from_dict(json.loads(json.dumps(j.to_dict())))
    np.testing.assert_allclose(back.score(X), j.score(X))
    bad = j.to_dict()
    bad["precision"] = bad["precision"][:1]
    with pytest.raises(DataError, match="retrain"):
        JointDomain.from_dict(bad)


@pytest.fixture(scope="module")
def model():
    train = [labelled_session(1, 12), labelled_session(2, 12)]
    return train_user(train, tasks=["terrain"], methods=["svm", "heuristic", "dtw"], units=["foot"], cv=3, seed=0)


def test_every_leaf_keeps_a_joint_model_and_predict_reports_it(model, tmp_path):
    for per in model.tasks["terrain"].models.values():
        for est in per.values():
            for leaf, _ in _leaves(est, np.zeros((1, 1))):
                assert isinstance(leaf.training_joint_, JointDomain)
    test = labelled_session(3, 12)
    assert "ood_joint_terrain" not in model.predict_steps(test)  # C71: an option, off by default
    pred = model.predict_steps(test, joint_domain=True)
    v = pred["ood_joint_terrain"].to_numpy(float)
    assert np.isfinite(v).all() and (v > 1).mean() <= 0.5
    rep = model.domain_report(pred)
    assert rep["joint_out_of_domain_fraction"] == pytest.approx((v > 1).mean())
    assert "out_of_domain_fraction" in rep  # C16's field kept
    joblib.dump(model, tmp_path / "m.joblib")
    again = joblib.load(tmp_path / "m.joblib").predict_steps(test, joint_domain=True)
    np.testing.assert_allclose(again["ood_joint_terrain"].to_numpy(float), v)


def test_track_reports_the_joint_fraction_only_with_the_option(model):
    from experiments.domain_joint import joint_domain_on
    from pdrlearn.classify import domain
    from pdrlearn.track.plasys import track_plasys

    assert not hasattr(domain, "JOINT_DEFAULT")  # decision C162: predict_steps' option, no module switch
    test = labelled_session(3, 12)
    off = track_plasys(test, method="M3", model=model).info["out_of_domain"]
    assert "joint_out_of_domain_fraction" not in off and off["out_of_domain_fraction"] is not None
    with joint_domain_on():
        on = track_plasys(test, method="M3", model=model).info["out_of_domain"]
    assert on["out_of_domain_fraction"] == off["out_of_domain_fraction"]
    assert 0 <= on["joint_out_of_domain_fraction"] <= 0.5


def test_model_without_joint_model_predicts_with_nan(model):
    est = model.tasks["terrain"].models["svm"]["foot"]
    X = np.zeros((2, 1))
    saved = est.training_joint_
    try:
        del est.training_joint_
        assert step_joint_score(est, X) is None
        pred = model.predict_steps(labelled_session(3, 12), method="svm", unit="foot", joint_domain=True)
        assert pred["ood_joint_terrain"].isna().all()
        assert pred["ood_terrain"].notna().all()  # C16's range is unchanged
        rep = model.domain_report(pred)  # the check is unavailable: None, C16's fraction as before
        assert rep["joint_out_of_domain_fraction"] is None and rep["out_of_domain_fraction"] is not None
    finally:
        est.training_joint_ = saved
