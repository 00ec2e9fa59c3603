"""One line, not a traceback, for what a methods student extending pdrlearn tries first (trial `extend`, session
23): a method name as a string (decision B171), a custom estimator with encoded labels or only a decision function
(B172), a table passed as plasys's ``steps`` and a model whose custom class is not importable (B173)."""

from __future__ import annotations

import copy
import sys

import numpy as np
import pytest
from sklearn.ensemble import HistGradientBoostingClassifier
from sklearn.pipeline import Pipeline
from sklearn.preprocessing import LabelEncoder
from sklearn.svm import LinearSVC

from pdrlearn.classify import load_model, train_user
from pdrlearn.errors import DataError, ModelError
from pdrlearn.features import make_features, step_windows
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from tests.runtime_helpers import synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def session():
    return synthetic_session(90, seed=0)


@pytest.fixture(scope="module")
def foot(tmp_path_factory, session):
    model = load_model(trained_dirs(tmp_path_factory)["root"] / "model_foot")
    w = step_windows(session)
    y, keep = w.labels("terrain")
    return model, w.X[keep], y


def _inject(foot, est, y=None):
    model, X, labels = foot
    m = copy.deepcopy(model)
    est.fit(X, labels if y is None else y)
    tm = m.tasks["terrain"]
    tm.models, tm.chosen = {"mine": {"foot": est}}, ("mine", "foot")
    return m


def test_methods_as_a_string_is_one_method_and_estimators_are_refused(session):
    m = train_user([session], tasks="terrain", methods="svm", units="foot", cv=2)
    assert list(m.tasks) == ["terrain"] and list(m.tasks["terrain"].models) == ["svm"]
    with pytest.raises(DataError, match="methods: give names.*not HistGradientBoostingClassifier objects.*"
                                        "docs/characterization.md"):
        train_user([session], methods=[HistGradientBoostingClassifier()], cv=2)


def test_an_estimator_with_encoded_labels_is_one_line(foot, session):
    enc = LabelEncoder().fit(foot[2])
    m = _inject(foot, Pipeline([("f", make_features("terrain", "foot", "svm")), ("c", LinearSVC())]),
                y=enc.transform(foot[2]))
    with pytest.raises(DataError, match=r"model task terrain mine/foot: Pipeline predicts classes 0, 1, 2, not the "
                                        r"task's .*fit it on the label strings"):
        m.predict_steps(session, session.steps, tasks=["terrain"])


def test_an_estimator_with_a_decision_function_only_classifies(foot, session):
    """docs/extending.md: predict_proba or decision_function; the scores' softmax, argmax = the estimator's predict."""
    est = Pipeline([("f", make_features("terrain", "foot", "svm")), ("c", LinearSVC())])
    m = _inject(foot, est)
    out = m.predict_steps(session, session.steps, tasks=["terrain"])
    want = est.predict(step_windows(session).X)
    assert (out["terrain"].to_numpy() == want).all()
    p = out[[f"p_terrain_{c}" for c in m.tasks["terrain"].classes]].to_numpy()
    np.testing.assert_allclose(p.sum(axis=1), 1.0)


def test_plasys_steps_of_another_kind_is_one_line(real_dir):
    # B173 as amended by L149: a table or a foot detector is accepted (tests/test_plugins.py); anything else, or an
    # unknown name, is one line naming what plasys takes
    s = read_session(real_dir / "gaitmap_level_left")
    for bad, shown in ((s.steps["ic_s"].tolist(), "a list"), ("acel", "'acel'")):
        with pytest.raises(DataError, match=f"plasys: steps={shown} is not detector, stance, labels, a foot "
                                            "detector's name"):
            get_pipeline("plasys")(s, steps=bad)


def test_a_model_whose_custom_class_cannot_be_imported_names_pythonpath(foot, tmp_path, monkeypatch):
    (tmp_path / "mycls_b173.py").write_text(
        "from sklearn.svm import LinearSVC\n\nclass MySVC(LinearSVC):\n    pass\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    from mycls_b173 import MySVC

    _inject(foot, Pipeline([("f", make_features("terrain", "foot", "svm")), ("c", MySVC())])).save(tmp_path / "m")
    monkeypatch.delitem(sys.modules, "mycls_b173")
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p != str(tmp_path)])
    with pytest.raises(ModelError, match=r"No module named 'mycls_b173'\): the model holds a class this Python "
                                         r"cannot import.*PYTHONPATH"):
        load_model(tmp_path / "m")
