"""Discoverability from Python (session-13 API trial): lazy packages list their names, the pipeline registry
is never seen empty, get_pipeline documents every pipeline's keywords, 2-D-only classifiers name the route
for step windows."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from pdrlearn.errors import DataError
from tests.conftest import ROOT


def _fresh(code: str) -> str:
    """Run ``code`` in a new interpreter (nothing imported before) and return its stdout."""
    env_path = str(ROOT)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"PYTHONPATH": env_path, "PATH": "/usr/bin:/bin"})
    return out.stdout.strip()


def test_lazy_classify_lists_its_names_before_any_import():
    names = _fresh("import pdrlearn.classify as c; print(' '.join(dir(c)))").split()
    import pdrlearn.classify as c

    assert set(c.__all__) <= set(names)
    assert {"SVMClassifier", "make_estimator", "train_user", "training_data",
            "HeuristicTerrainClassifier"} <= set(names)


def test_every_lazy_name_resolves():
    import pdrlearn.classify as c

    for name in c.__all__:
        assert getattr(c, name) is not None
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        c.nope  # noqa: B018


def test_pipelines_are_listed_before_get_pipeline():
    assert _fresh("import pdrlearn.track as t; print(sorted(t.PIPELINES))") == \
        "['plasys', 'waist-pendulum', 'waist-pll']"


def test_get_pipeline_docstring_names_every_keyword():
    from pdrlearn.track import PIPELINES, get_pipeline
    from pdrlearn.track.base import keyword_names
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.waist import track_waist

    doc = get_pipeline.__doc__
    for name in PIPELINES:
        assert f'"{name}"' in doc
    for kw in [*keyword_names(track_plasys), *keyword_names(track_waist, exclude=("pipeline",))]:
        assert f"``{kw}``" in doc, kw
    assert 'logging.getLogger("pdrlearn")' in doc


@pytest.mark.parametrize("name, method", [("SVMClassifier", "svm"), ("NNClassifier", "nn")])
def test_2d_classifiers_name_the_window_route(name, method):
    import pdrlearn.classify as c

    X = np.zeros((6, 17, 40))
    with pytest.raises(DataError, match=rf"takes a 2-D feature matrix .*make_estimator\('terrain', '{method}'"):
        getattr(c, name)(task="terrain").fit(X, ["flat", "up"] * 3)


def test_detector_repr_prints_changed_settings_only():
    from pdrlearn.steps import AccelStepDetector, PLLStepDetector, WaistICStepDetector

    assert repr(AccelStepDetector()) == "AccelStepDetector()"
    assert repr(AccelStepDetector(threshold=2.0)) == "AccelStepDetector(threshold=2.0)"
    assert repr(PLLStepDetector(placement="pocket", loop_hz=0.3)) == "PLLStepDetector(loop_hz=0.3, placement='pocket')"
    assert repr(WaistICStepDetector(delay_s=1.75)) == "WaistICStepDetector(delay_s=1.75)"


@pytest.mark.parametrize("kw", [{"threshold": -1}, {"still_window_s": -0.08}, {"cutoff_hz": float("nan")},
                                {"max_swing_s": float("inf")}])
def test_detector_refuses_negative_or_non_finite_settings(kw):
    from pdrlearn.steps import AccelStepDetector

    name, value = next(iter(kw.items()))
    with pytest.raises(ValueError, match=rf"AccelStepDetector: {name}={value!r} is not allowed; .*>= 0"):
        AccelStepDetector(**kw)
    det = AccelStepDetector()
    with pytest.raises(ValueError, match=rf"{name}="):
        det.set_params(**kw)
    assert repr(det) == "AccelStepDetector()"  # a refused set_params changes nothing


def test_detector_tuple_settings_are_checked_per_element():
    from pdrlearn.steps import PelvicGyroStepDetector

    with pytest.raises(ValueError, match="weights="):
        PelvicGyroStepDetector(weights=(0.25, -0.1, 0.4, 0.25))
    assert PelvicGyroStepDetector(turn_cutoff_hz=0.0).turn_cutoff_hz == 0.0  # 0 = off stays allowed


def test_write_track_is_a_top_level_entry_point():
    """Decision E166: ``pdrlearn.write_track`` (track --out's folder from a TrackResult) is listed before any import
    and documented with its signature."""
    assert "write_track" in _fresh("import pdrlearn; print(' '.join(dir(pdrlearn)))").split()
    import inspect

    import pdrlearn

    assert "write_track" in pdrlearn.__all__
    params = list(inspect.signature(pdrlearn.write_track).parameters)
    assert params == ["result", "session", "out", "force", "plot"]  # L533: plot=False writes no figure
