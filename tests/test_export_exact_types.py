"""Decisions E79 (export refuses subclasses and pipelines of another shape, which a bundle would run as
pdrlearn's own class) and E80 (a bundle is written only when it reproduces the model's predict_proba)."""

from __future__ import annotations

import copy

import numpy as np
import pytest
from sklearn.pipeline import Pipeline
from sklearn.preprocessing import StandardScaler

from pdrlearn.classify import SVMClassifier, load_model
from pdrlearn.errors import ModelError
from pdrlearn.export.from_model import export_model
from pdrlearn.features import make_features, step_windows
from tests.runtime_helpers import synthetic_session, trained_dirs


class BiasedSVM(SVMClassifier):
    """A user's subclass that changes the probabilities (the trial's: the bundle ran the base SVM)."""

    def predict_proba(self, X):
        p = super().predict_proba(X) + np.array([0.5, 0.0, 0.0])
        return p / p.sum(axis=1, keepdims=True)


@pytest.fixture(scope="module")
def foot(tmp_path_factory):
    model = load_model(trained_dirs(tmp_path_factory)["root"] / "model_foot")
    w = step_windows(synthetic_session(90, seed=0))
    y, keep = w.labels("terrain")
    return model, w.X[keep], y


def _inject(foot, est):
    """The model with ``est`` (fitted) as the terrain task's only and chosen model (the trial's injection)."""
    model, X, y = foot
    m = copy.deepcopy(model)
    est.fit(X, y)
    tm = m.tasks["terrain"]
    tm.models, tm.chosen = {"svm": {"foot": est}}, ("svm", "foot")
    return m


@pytest.mark.parametrize("case", ["three_steps", "subclass"])
def test_export_refuses_what_the_bundle_would_run_as_something_else(foot, tmp_path, case):
    if case == "three_steps":
        est = Pipeline([("features", make_features("terrain", "foot", "svm")), ("sc", StandardScaler()),
                        ("clf", SVMClassifier(task="terrain"))])
        said = "a Pipeline of 3 steps (features, sc, clf) cannot be exported"
    else:
        est = Pipeline([("features", make_features("terrain", "foot", "svm")), ("clf", BiasedSVM(task="terrain"))])
        said = "BiasedSVM is a subclass of SVMClassifier"
    m = _inject(foot, est)
    with pytest.raises(ModelError, match="no task could be exported") as err:
        export_model(None, tmp_path / "b", model=_only_terrain(m))
    assert said in str(err.value) and "pdrlearn track --model" in str(err.value)
    assert not (tmp_path / "b").exists()


def _only_terrain(m):
    m.tasks = {"terrain": m.tasks["terrain"]}
    return m


def test_export_writes_no_bundle_whose_probabilities_differ_from_predict_proba(foot, tmp_path):
    """E80: an estimator of an exportable type whose predict_proba is not its exported formula (here: replaced on
    the instance) passes the type check; the parity check stops the export and leaves no folder."""
    est = Pipeline([("features", make_features("terrain", "foot", "svm")), ("clf", SVMClassifier(task="terrain"))])
    m = _inject(foot, est)
    clf = est.steps[-1][1]
    plain = clf.predict_proba
    clf.predict_proba = lambda X: plain(X)[:, ::-1]
    with pytest.raises(ModelError, match=r"terrain svm/foot model \(Pipeline\) gives probabilities up to"):
        export_model(None, tmp_path / "b", model=m)
    assert not (tmp_path / "b").exists() and not list(tmp_path.iterdir())
    clf.predict_proba = plain  # the same model as trained exports
    assert export_model(None, tmp_path / "b", model=m).exists()


def test_export_checks_the_step_graph_too(foot, tmp_path, monkeypatch):
    """E80: the step graph (what the Tracker runs for the chosen models, E10) is compared as well: here it is built
    from another SVM's graph (fitted on shuffled labels) while the per-model file stays right."""
    from pdrlearn.export import from_model
    from pdrlearn.export.onnx_convert import svm_decision_to_onnx

    est = Pipeline([("features", make_features("terrain", "foot", "svm")), ("clf", SVMClassifier(task="terrain"))])
    m = _inject(foot, est)
    _, X, y = foot
    other = Pipeline([("features", make_features("terrain", "foot", "svm")), ("clf", SVMClassifier(task="terrain"))])
    other.fit(X, np.random.default_rng(3).permutation(y))
    clf = other.steps[-1][1]
    wrong = svm_decision_to_onnx(clf.mean_, clf.scale_, clf.decision_params_, [str(c) for c in clf.classes_],
                                 name="terrain_svm_foot")[0]
    real = from_model.build_step_graph

    def tampered(tasks, onnx_models, features):
        return real(tasks, {**onnx_models, "models/terrain_svm_foot.onnx": wrong}, features)

    monkeypatch.setattr(from_model, "build_step_graph", tampered)
    with pytest.raises(ModelError, match=r"terrain step graph \(svm/foot\) \(Pipeline\) gives probabilities up to"):
        export_model(None, tmp_path / "b", model=m)
    assert not (tmp_path / "b").exists()
