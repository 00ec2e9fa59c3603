"""Decision C121 (trial T4 finding 6): ``pdrlearn --plugin MODULE`` (also after the command name) imports a user's
module that registers plug-ins, so the CLI trains, evaluates and tracks with a method from a plain ``.py`` file;
an unknown method names where plug-ins come from."""

from __future__ import annotations

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
    METHODS.pop(name, None)
    sys.modules.pop(name, None)


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
