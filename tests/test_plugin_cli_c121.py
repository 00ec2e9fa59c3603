"""Decision C121 (trial T4 finding 6): ``pdrlearn --plugin MODULE`` (also after the command name) imports a user's
module that registers plug-ins, so the CLI trains, evaluates and tracks with a method from a plain ``.py`` file;
an unknown method names where plug-ins come from."""

from __future__ import annotations

import json
import sys

import pytest

from pdrlearn.classify.training import METHODS
from pdrlearn.cli import _hoist_verbose, main
from pdrlearn.io import write_session
from tests.runtime_helpers import synthetic_session

PLUGIN = '''
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import Pipeline
from pdrlearn.classify.training import register_method
from pdrlearn.features import make_features


def {name}(task, unit, *, seed=0):
    return Pipeline([("features", make_features(task, unit, "svm")),
                     ("clf", LogisticRegression(max_iter=500, random_state=seed))])


register_method("{name}", {name})
'''


@pytest.fixture()
def plugin_file(tmp_path):
    name = "fc_c121_logreg"
    f = tmp_path / "plug" / f"{name}.py"
    f.parent.mkdir()
    f.write_text(PLUGIN.format(name=name))
    yield name, f
    _forget(name)


def test_plugin_option_trains_and_evaluates_a_method_from_a_py_file(plugin_file, tmp_path, capsys):
    name, f = plugin_file
    s = write_session(synthetic_session(60, seed=0), tmp_path / "s")
    argv = ["train", str(s), "--out", str(tmp_path / "m"), "--tasks", "terrain", "--units", "foot", "--cv", "2",
            "--methods", f"{name},nn"]
    assert main(argv) == 2  # before: the method is unknown, and the line says where plug-ins come from
    assert "unknown method fc_c121_logreg" in capsys.readouterr().err
    assert main([*argv, "--plugin", str(f)]) == 0, capsys.readouterr().err
    assert f"{name}" in capsys.readouterr().out
    assert main(["evaluate", str(tmp_path / "m"), str(s), "--plugin", str(f)]) == 0


def test_unknown_method_names_plugin_option_and_a_bad_module_is_one_line(tmp_path, capsys):
    assert main(["train", str(tmp_path), "--out", str(tmp_path / "m"), "--methods", "nosuch"]) == 2
    err = capsys.readouterr().err
    assert "unknown method nosuch" in err and "--plugin MODULE" in err and "entry point" in err
    assert main(["train", str(tmp_path), "--out", str(tmp_path / "m"), "--plugin", "no_such_module_c121"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --plugin no_such_module_c121: cannot import it (ModuleNotFoundError")
    assert len(err.strip().splitlines()) == 1 and not (tmp_path / "m").exists()
    bad = tmp_path / "broken_c121.py"
    bad.write_text("raise RuntimeError('boom')\n")
    assert main(["track", str(tmp_path), "--plugin", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "--plugin" in err and "RuntimeError: boom" in err and len(err.strip().splitlines()) == 1


def test_plugin_is_hoisted_from_after_the_command_name():
    assert _hoist_verbose(["train", "d", "--plugin", "x.py", "--out", "m"]) == ["--plugin", "x.py", "train", "d",
                                                                                 "--out", "m"]
    assert _hoist_verbose(["track", "d", "--plugin=x.py", "-v"]) == ["--plugin=x.py", "-v", "track", "d"]
    assert _hoist_verbose(["track", "d", "--", "--plugin", "x"]) == ["track", "d", "--", "--plugin", "x"]


OWN = '''
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import Pipeline
from pdrlearn.classify.training import register_method
from pdrlearn.features import make_features


class Own(ClassifierMixin, BaseEstimator):
    def __init__(self, C=1.0):
        self.C = C

    def fit(self, X, y):
        self.m_ = LogisticRegression(C=self.C, max_iter=500).fit(X, y)
        self.classes_ = self.m_.classes_
        return self

    def predict_proba(self, X):
        return self.m_.predict_proba(X)
{predict}

def {name}(task, unit, *, seed=0):
    return Pipeline([("features", make_features(task, unit, "svm")), ("clf", Own())])


register_method("{name}", {name})
'''
WITH_PREDICT = '''
    def predict(self, X):
        return self.m_.predict(X)
'''


def _own_plugin(tmp_path, name, predict=WITH_PREDICT):
    f = tmp_path / "plug dir" / f"{name}.py"
    f.parent.mkdir(exist_ok=True)
    f.write_text(OWN.format(name=name, predict=predict))
    return f


def _forget(name):
    from pdrlearn.plugin_modules import LOADED

    METHODS.pop(name, None)
    sys.modules.pop(name, None)
    LOADED[:] = [v for v in LOADED if not v.endswith(f"{name}.py")]


def test_a_model_of_a_class_defined_in_the_plugin_file_needs_it_and_records_it(tmp_path, capsys):
    """Review R4 (findings 3, 6, 7): the estimator class lives in the plug-in file, so evaluating the saved model
    fails without --plugin and works with it; the manifest records the file and its sha256; track-all --jobs 2
    gives the plug-in to its Dask workers (before: `No module named ...` in every session)."""
    import hashlib

    name = "fi_c121_own"
    f = _own_plugin(tmp_path, name)
    study = tmp_path / "study"
    s = write_session(synthetic_session(60, seed=0), study / "s1")
    try:
        assert main(["--plugin", str(f), "train", str(s), "--out", str(tmp_path / "m"), "--tasks", "terrain",
                     "--units", "foot", "--cv", "2", "--methods", name]) == 0, capsys.readouterr().err
        manifest = json.loads((tmp_path / "m" / "manifest.json").read_text())
        rec = manifest["settings"]["plugins"][name]
        assert rec["path"] == str(f.resolve()) and rec["sha256"] == hashlib.sha256(f.read_bytes()).hexdigest()
        _forget(name)
        capsys.readouterr()
        assert main(["evaluate", str(tmp_path / "m"), str(s)]) == 2
        assert name in capsys.readouterr().err
        assert main(["evaluate", str(tmp_path / "m"), str(s), "--plugin", str(f)]) == 0, capsys.readouterr().err
        capsys.readouterr()
        assert main(["track-all", "--no-plot", str(study), "--out", str(tmp_path / "ta"), "--model",
                     str(tmp_path / "m"),
                     "--jobs", "2", "--plugin", str(f)]) == 0, capsys.readouterr()
    finally:
        _forget(name)


def test_root_plugin_before_the_command_and_bad_plugin_files_are_one_line(tmp_path, capsys):
    assert _hoist_verbose(["--plugin", "a b.py", "train", "d", "--plugin", "y.py", "-v"]) == [
        "--plugin", "a b.py", "--plugin", "y.py", "-v", "train", "d"]
    (tmp_path / "j").mkdir()
    (tmp_path / "j" / "json.py").write_text("X = 1\n")
    assert main(["track", str(tmp_path), "--plugin", str(tmp_path / "j" / "json.py")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'json' is already a module" in err[0], err
    assert sys.modules["json"].__file__ != str(tmp_path / "j" / "json.py")
    (tmp_path / "fi_sysexit.py").write_text("import sys\nsys.exit(3)\n")
    assert main(["track", str(tmp_path), "--plugin", str(tmp_path / "fi_sysexit.py")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "SystemExit(3)" in err[0], err


def test_evaluate_a_plugin_with_fit_and_predict_proba_only(tmp_path):
    """Review R4 finding 5: docs/extending.md asks a plug-in for fit and predict_proba only, but evaluate called
    predict (`AttributeError: This 'Pipeline' has no attribute 'predict'`)."""
    from pdrlearn.classify import evaluate_model, train_user
    from pdrlearn.plugin_modules import load_plugin

    name = "fi_c121_noproba"
    load_plugin(str(_own_plugin(tmp_path, name, predict="")))
    try:
        model = train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=[name], units=["foot"],
                           cv=2, distance_calibration=False)
        est = model.tasks["terrain"].models[name]["foot"]
        assert not hasattr(est, "predict")
        res = evaluate_model(model, [synthetic_session(60, seed=1)], latency=True)
        got = res["tasks"]["terrain"]["methods"][name]["units"]["foot"]
        assert 0 <= got["accuracy"] <= 1 and got["latency_ms"] > 0
    finally:
        _forget(name)
