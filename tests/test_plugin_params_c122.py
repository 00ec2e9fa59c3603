"""Decision C122 (trial T4 finding 5): ``--param PLUGIN.KEY=VALUE`` (``train_user(params={PLUGIN: {KEY: VALUE}})``)
passes KEY=VALUE to a registered plug-in method's factory, recorded in the model's ``settings.params`` as C96's; a key
the factory does not take is one line."""

from __future__ import annotations

import pytest
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import Pipeline

from pdrlearn.classify import load_model, train_user
from pdrlearn.classify.hyper import parse_params
from pdrlearn.classify.training import METHODS, register_method
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.features import make_features
from pdrlearn.io import write_session
from tests.runtime_helpers import synthetic_session


def lr_c(task, unit, *, seed=0, C=1.0, max_iter=500):
    return Pipeline([("features", make_features(task, unit, "svm")),
                     ("clf", LogisticRegression(C=C, max_iter=max_iter, random_state=seed))])


@pytest.fixture()
def registered():
    register_method("lrc", lr_c)
    yield "lrc"
    del METHODS["lrc"]


def test_plugin_params_reach_the_factory_in_every_unit_and_are_recorded(registered, tmp_path):
    model = train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=["lrc"],
                       units=["foot", "waist", "fused"], cv=2, distance_calibration=False,
                       params={"lrc": {"C": 0.05, "max_iter": 300}})
    per = model.tasks["terrain"].models["lrc"]
    assert per["foot"][-1].C == 0.05 and per["waist"][-1].max_iter == 300
    assert [m[-1].C for m in per["fused"].estimators_] == [0.05, 0.05]
    assert model.settings["params"] == {"lrc": {"C": 0.05, "max_iter": 300}}


def test_cli_param_of_a_plugin_and_a_key_its_factory_does_not_take(registered, tmp_path, capsys):
    s = write_session(synthetic_session(60, seed=0), tmp_path / "s")
    argv = ["train", str(s), "--out", str(tmp_path / "m"), "--tasks", "terrain", "--units", "foot", "--cv", "2",
            "--methods", "lrc"]
    assert main([*argv, "--param", "lrc.C=0.2"]) == 0, capsys.readouterr().err
    assert load_model(tmp_path / "m").tasks["terrain"].models["lrc"]["foot"][-1].C == 0.2
    assert load_model(tmp_path / "m").settings["params"] == {"lrc": {"C": 0.2}}
    assert main([*argv[:3], str(tmp_path / "m2"), *argv[4:], "--param", "lrc.penalty=l1"]) == 2
    errors = [line for line in capsys.readouterr().err.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and not (tmp_path / "m2").exists()
    assert errors[0].startswith("error: train: --param 'lrc.penalty=l1': the factory of plug-in method lrc takes no "
                                "keyword 'penalty' (its keywords: C, max_iter)")


def test_builtin_names_stay_checked_and_plugins_only_when_registered():
    with pytest.raises(DataError, match="unknown name 'svm.gamma'"):
        parse_params(["svm.gamma=1"], plugins={"svm": lr_c})
    with pytest.raises(DataError, match="unknown name 'lrc.C'.*PLUGIN.KEY=VALUE"):
        parse_params(["lrc.C=1"])
    assert parse_params(["lrc.C=1", "lrc.max_iter=none"], plugins={"lrc": lr_c}) == {"lrc": {"C": 1, "max_iter": None}}
    with pytest.raises(DataError, match="takes no keyword 'seed'"):
        parse_params(["lrc.seed=3"], plugins={"lrc": lr_c})
