"""Decision E86: classifier methods are a registry (``pdrlearn.classify.training.METHODS``, entry point group
``pdrlearn.methods``): a registered method trains, is cross-validated and evaluated as the built-ins, and export
refuses it in one line (the runtime bundle has no recipe for it)."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import Pipeline

from pdrlearn.classify import load_model, train_user
from pdrlearn.classify.training import METHODS, check_settings, register_method
from pdrlearn.errors import DataError, ModelError
from pdrlearn.export.from_model import export_model
from pdrlearn.features import make_features
from tests.runtime_helpers import synthetic_session


def logreg(task, unit, *, seed=0):
    """A user's method: the SVM's features and a logistic regression."""
    return Pipeline([("features", make_features(task, unit, "svm")),
                     ("clf", LogisticRegression(max_iter=500, random_state=seed))])


@pytest.fixture()
def registered():
    register_method("logreg", logreg)
    yield "logreg"
    del METHODS["logreg"]


def test_builtins_are_refused_and_plugins_reach_the_settings(registered):
    with pytest.raises(DataError, match=r"'svm' is a built-in classifier method; register_method\('svm', ..., "
                                        r"replace=True\)"):
        register_method("svm", logreg)
    with pytest.raises(DataError, match="not a function factory"):
        register_method("x", 3)
    assert check_settings(methods=["logreg", "nn"])[1] == ["logreg", "nn"]
    with pytest.raises(DataError, match="unknown method nosuch; choose from .*logreg"):
        check_settings(methods=["nosuch"])


def test_a_registered_method_trains_evaluates_and_export_refuses_it(registered, tmp_path):
    train = synthetic_session(60, seed=0)
    model = train_user([train], tasks=["terrain"], methods=["logreg", "nn"], units=["foot", "waist", "fused"],
                       cv=2, seed=0, distance_calibration=False)
    tm = model.tasks["terrain"]
    assert {"foot", "waist", "fused"} <= set(tm.models["logreg"]) and "logreg" in tm.cv
    assert tm.cv["logreg"]["foot"]["balanced_accuracy"] > 0.5
    tm.chosen = ("logreg", "fused")
    model.save(tmp_path / "m")
    test = synthetic_session(30, seed=3)
    pred = load_model(tmp_path / "m").predict_steps(test)
    assert len(pred) and set(np.unique(pred["terrain"])) <= {"flat", "up", "down"}
    with pytest.raises(ModelError, match="chosen model logreg/fused is a plug-in classifier method, which the runtime "
                                         "bundle cannot carry; export built-in methods with --methods"):
        export_model(tmp_path / "m", tmp_path / "b")
    with pytest.raises(ModelError, match="--methods logreg: a plug-in classifier method"):
        export_model(tmp_path / "m", tmp_path / "b", methods=["logreg"])
    export_model(tmp_path / "m", tmp_path / "b", methods=["nn"])  # the built-in beside it still exports
    assert (tmp_path / "b" / "manifest.json").is_file()


def test_a_factory_that_returns_no_classifier_is_one_line(registered):
    register_method("broken", lambda task, unit, *, seed=0: "not an estimator")
    try:
        with pytest.raises(DataError, match="factory returned str, which has no fit / predict_proba"):
            train_user([synthetic_session(30, seed=0)], tasks=["terrain"], methods=["broken"], units=["foot"], cv=2,
                       distance_calibration=False)
    finally:
        del METHODS["broken"]


def test_export_fallback_skips_a_plugin_foot_model_and_run_advice_says_reexport(registered, tmp_path, caplog):
    """Decision E201 (trial T4 finding 2): a plug-in ranked the best foot model left the bundle without a foot-only
    model; the next exportable foot model takes its place, and a bundle without one advises re-exporting."""
    import json
    import logging

    from pdrlearn.runtime import Tracker

    model = train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=["logreg", "svm"],
                       units=["foot", "waist", "combined"], cv=2, seed=0, distance_calibration=False)
    tm = model.tasks["terrain"]
    tm.chosen = ("svm", "combined")
    tm.cv["logreg"]["foot"].update(balanced_accuracy=1.0, accuracy=1.0)  # the plug-in ranks first on the foot
    tm.cv["svm"]["foot"].update(balanced_accuracy=0.9, accuracy=0.9)
    assert [p for p in tm.ranking() if p[1] == "foot"] == [("logreg", "foot"), ("svm", "foot")]
    model.save(tmp_path / "m")
    with caplog.at_level(logging.WARNING):
        export_model(tmp_path / "m", tmp_path / "b")
    m = json.loads((tmp_path / "b" / "manifest.json").read_text())
    assert m["tasks"]["terrain"]["foot_only"] == {"method": "svm", "unit": "foot"}
    assert any(s.startswith("terrain logreg/foot:") for s in m["export"]["skipped"])
    assert "foot-only fallback is svm/foot (logreg/foot skipped" in caplog.text
    assert Tracker(tmp_path / "b", units=("foot",)).classifiers["terrain"].method == "svm"
    del m["tasks"]["terrain"]["foot_only"]  # a bundle without it (as exported before E201): the advice
    (tmp_path / "b" / "manifest.json").write_text(json.dumps(m))
    from pdrlearn.runtime.bundle import sha256_file

    (tmp_path / "b" / "manifest.sha256").write_text(sha256_file(tmp_path / "b" / "manifest.json"))
    with pytest.raises(ModelError, match=r"re-export with a built-in method that has a foot model \(pdrlearn export "
                                         r"MODEL --methods svm"):
        Tracker(tmp_path / "b", units=("foot",))


def test_a_pipeline_ending_without_predict_proba_names_its_last_step_and_the_fix():
    """Trial T4 finding 8: a Pipeline has fit; what is missing is predict_proba on its last step."""
    from sklearn.svm import LinearSVC

    register_method("linsvc", lambda task, unit, *, seed=0: Pipeline(
        [("features", make_features(task, unit, "svm")), ("clf", LinearSVC())]))
    try:
        with pytest.raises(DataError, match=r"classifier method 'linsvc': its factory returned a Pipeline whose last "
                                            r"step 'clf' \(LinearSVC\) has no predict_proba; end it with a "
                                            r"probabilistic classifier .*CalibratedClassifierCV\(LinearSVC"):
            train_user([synthetic_session(30, seed=0)], tasks=["terrain"], methods=["linsvc"], units=["foot"], cv=2,
                       distance_calibration=False)
    finally:
        del METHODS["linsvc"]


def test_export_converts_each_model_once_past_a_failed_foot_model_e207(tmp_path, monkeypatch):
    """Decision E207: with --methods, the foot models E201's fallback goes through were converted already (they are
    among the requested ones); each model is converted once and a failed one is skipped (and said) once."""
    import json

    from pdrlearn.export import from_model

    model = train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=["svm", "nn", "heuristic"],
                       units=["foot", "combined"], cv=2, seed=0, distance_calibration=False)
    tm = model.tasks["terrain"]
    tm.chosen = ("svm", "combined")
    for m, score in (("svm", 1.0), ("nn", 0.95), ("heuristic", 0.9)):
        tm.cv[m]["foot"].update(balanced_accuracy=score, accuracy=score)
    assert [p for p in tm.ranking() if p[1] == "foot"] == [("svm", "foot"), ("nn", "foot"), ("heuristic", "foot")]
    model.save(tmp_path / "m")
    real, calls = from_model._Collector.entry, []

    def counted(self, est, stem):
        calls.append(stem)
        if stem in ("terrain_svm_foot", "terrain_nn_foot"):  # as a model the bundle cannot carry (E79, E86)
            raise ModelError(f"{stem}: cannot be exported yet")
        return real(self, est, stem)

    monkeypatch.setattr(from_model._Collector, "entry", counted)
    export_model(tmp_path / "m", tmp_path / "b", methods=["svm", "nn", "heuristic"])
    top = [c for c in calls if c.count("_") == 2]  # not a fusion's members
    assert sorted(top) == sorted(set(top)), top  # each model converted once
    m = json.loads((tmp_path / "b" / "manifest.json").read_text())
    assert m["tasks"]["terrain"]["foot_only"] == {"method": "heuristic", "unit": "foot"}
    assert [s.split(":")[0] for s in m["export"]["skipped"]] == ["terrain svm/foot", "terrain nn/foot"]
