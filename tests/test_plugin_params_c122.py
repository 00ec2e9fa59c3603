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
    with pytest.raises(DataError, match="--seed sets it"):
        parse_params(["lrc.seed=3"], plugins={"lrc": lr_c})


seen_c122 = []


def mlp_c122(task, unit, *, seed=0, sizes=(10,), tag="x"):
    seen_c122.append((sizes, tag))
    return lr_c(task, unit, seed=seed)


def lr_kw(task, unit, *, seed=0, **kw):
    return Pipeline([("features", make_features(task, unit, "svm")),
                     ("clf", LogisticRegression(random_state=seed, **kw))])


def test_api_params_reach_a_plugin_factory_unchanged():
    """Review R4: a tuple stayed a tuple and "007" stayed text only through the CLI; the API's values went through a
    text round trip ((8, 4) -> '8,4', "007" -> 7)."""
    register_method("mlpc122", mlp_c122)
    try:
        seen_c122.clear()
        model = train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=["mlpc122"], units=["foot"],
                           cv=2, distance_calibration=False, params={"mlpc122": {"sizes": (8, 4), "tag": "007"}})
        assert seen_c122 and all(v == ((8, 4), "007") for v in seen_c122)
        assert model.settings["params"] == {"mlpc122": {"sizes": [8, 4], "tag": "007"}}
        with pytest.raises(DataError, match="takes no keyword 'nosuch'"):
            train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=["mlpc122"], units=["foot"],
                       cv=2, params={"mlpc122": {"nosuch": 1}})
    finally:
        del METHODS["mlpc122"]


def test_a_kwargs_factory_refusing_a_param_is_one_line_and_seed_names_the_seed_option(tmp_path, capsys):
    register_method("lrkw", lr_kw)
    try:
        s = write_session(synthetic_session(60, seed=0), tmp_path / "s")
        assert main(["train", str(s), "--out", str(tmp_path / "m"), "--tasks", "terrain", "--units", "foot",
                     "--cv", "2", "--methods", "lrkw", "--param", "lrkw.bogus=3"]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "--param lrkw.bogus" in err[0] and "bogus" in err[0], err
        assert not (tmp_path / "m").exists()
        with pytest.raises(DataError, match="--seed sets it"):
            parse_params(["lrkw.seed=1"], plugins={"lrkw": lr_kw})
    finally:
        del METHODS["lrkw"]
