"""Decision C123 (trial T4 finding 3): a plug-in method registered with ``combined=True`` trains the ``combined``
unit (its factory gets ``unit="combined"``), cross-validated and chosen among the two-unit models as svm and nn; one
registered without it is skipped on that unit with a line naming the option."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import Pipeline

from pdrlearn.classify import train_user
from pdrlearn.classify.training import METHODS, can_combine, register_method
from pdrlearn.features import make_features
from tests.runtime_helpers import synthetic_session

SEEN: list[str] = []


def lr_any(task, unit, *, seed=0):
    SEEN.append(unit)
    return Pipeline([("features", make_features(task, unit, "svm")),
                     ("clf", LogisticRegression(max_iter=500, random_state=seed))])


@pytest.fixture()
def two():
    register_method("lrcomb", lr_any, combined=True)
    register_method("lrunit", lr_any)
    SEEN.clear()
    yield
    del METHODS["lrcomb"], METHODS["lrunit"]


def test_a_plugin_registered_with_combined_trains_the_combined_unit(two):
    assert can_combine("lrcomb") and not can_combine("lrunit") and can_combine("svm")
    session = synthetic_session(60, seed=0)
    model = train_user([session], tasks=["terrain"], methods=["lrcomb", "lrunit"], units=["foot", "combined"], cv=2,
                       seed=0, distance_calibration=False)
    tm = model.tasks["terrain"]
    assert set(tm.models["lrcomb"]) == {"foot", "combined"} and set(tm.models["lrunit"]) == {"foot"}
    assert "combined" in SEEN and tm.cv["lrcomb"]["combined"]["n_steps"] == tm.n_steps
    assert tm.models["lrcomb"]["combined"][0].get_params()["unit"] == "both"  # the thesis' combined vector
    only = train_user([session], tasks=["terrain"], methods=["lrunit", "lrcomb"], units=["combined"], cv=2,
                      distance_calibration=False).tasks["terrain"]
    assert set(only.models) == {"lrcomb"}
    assert any(s.startswith("lrunit/combined: only svm and nn") and "combined=True" in s for s in only.skipped)
    tm.chosen = ("lrcomb", "combined")
    pred = model.predict_steps(session)
    assert (pred["method_terrain"] == "lrcomb/combined").all() and set(np.unique(pred["terrain"])) <= {
        "flat", "up", "down"}
    register_method("lrcomb", lr_any, replace=True)  # registered again without the option: not combined any more
    assert not can_combine("lrcomb")
