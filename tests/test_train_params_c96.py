"""Decision C96: ``train --param METHOD.NAME=VALUE`` sets the built-in classifiers' hyperparameters, the model
records them, and a bad name or value is one line naming --param and the valid names (trial T6 finding 5)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.classify.hyper import parse_params, valid_names
from pdrlearn.classify.training import make_estimator, train_user
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import simulate


def test_parse_params_reads_dotted_names_and_refuses_bad_ones():
    assert parse_params(["svm.C=10", "nn.hidden=32", "svm.C_grid=0.1,1", "dtw.window=none"]) == {
        "svm": {"C": 10.0, "C_grid": (0.1, 1.0)}, "nn": {"hidden": 32}, "dtw": {"window": None}}
    assert parse_params(None) == {}
    for bad, said in (("svm.gamma=1", "unknown name 'svm.gamma'"), ("nn.hidden=0", "is not an integer >= 1"),
                      ("svm.C=-1", "is not a number > 0"), ("svmC10", "write METHOD.NAME=VALUE"),
                      ("dtw.window=2", "is not a fraction")):
        with pytest.raises(DataError, match="--param") as exc:
            parse_params([bad])
        assert said in str(exc.value) and "\n" not in str(exc.value)
    with pytest.raises(DataError, match="valid names: svm.C, "):
        parse_params(["svm.gamma=1"])
    with pytest.raises(DataError, match="given twice"):
        parse_params(["svm.C=1", "svm.C=2"])


def test_estimators_take_the_params_in_every_unit_and_the_defaults_stay_the_thesis():
    p = {"svm": {"C": 10.0}, "nn": {"hidden": 7}, "dtw": {"n_references": 5}}
    assert make_estimator("length", "svm", "foot", params=p)[-1].C == 10.0
    assert make_estimator("length", "svm", "foot")[-1].C == "cv"  # thesis ch. 2.4.2.2 grid search
    assert make_estimator("length", "nn", "combined", params=p)[-1]._hidden() == 7
    assert make_estimator("length", "nn", "combined")[-1]._hidden() == 60  # thesis ch. 6.3.1.2
    fused = make_estimator("terrain", "dtw", "fused", params=p)
    assert [e[-1].n_references for _, e, _ in fused.units] == [5, 5]
    assert make_estimator("terrain", "dtw", "foot")[-1].n_references == 36  # thesis ch. 6.1.2.2


def test_train_records_the_params_and_fits_with_them(tmp_path):
    walk = simulate("length", 8843, seed=0)
    m = train_user([walk], tasks=["length"], methods=["svm", "nn"], units=["foot"], cv=3,
                   distance_calibration=False, params={"svm": {"C": 10}, "nn": {"hidden": 7}})
    assert m.settings["params"] == {"svm": {"C": 10.0}, "nn": {"hidden": 7}}
    assert m.tasks["length"].models["svm"]["foot"][-1].C_ == 10.0
    assert m.tasks["length"].models["nn"]["foot"][-1].coefs_[0].shape[1] == 7
    m.save(tmp_path / "model")
    assert json.loads((tmp_path / "model" / "manifest.json").read_text())["settings"]["params"] == {
        "svm": {"C": 10.0}, "nn": {"hidden": 7}}
    with pytest.raises(DataError, match="nn is not trained"):
        train_user([walk], tasks=["length"], methods=["svm"], units=["foot"], params={"nn": {"hidden": 7}})


def test_cli_refuses_a_bad_param_before_reading_data(tmp_path, capsys):
    code = main(["train", str(tmp_path), "--out", str(tmp_path / "m"), "--param", "nn.layers=2"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and "Traceback" not in err and len(err.splitlines()) == 1
    assert "--param" in err and valid_names().split(", ")[0] in err
    assert not (tmp_path / "m").exists()


def test_train_all_passes_cv_groups_and_params_to_every_user(tmp_path, capsys):
    """Decision C98: train-all takes train's --cv-groups and --param (checked once, before anything is written)."""
    from pdrlearn.io import write_session

    for u in (8846, 8847):
        write_session(simulate("length", u, seed=0), tmp_path / "cohort" / f"u{u}" / "train" / "length")
    base = ["train-all", str(tmp_path / "cohort"), "--serial", "--tasks", "length", "--methods", "svm",
            "--units", "foot", "--cv", "4", "--cv-groups", "block"]
    assert main([*base, "--out", str(tmp_path / "bad"), "--param", "svm.kernel=rbf"]) == 2
    assert "unknown name 'svm.kernel'" in capsys.readouterr().err and not (tmp_path / "bad").exists()
    assert main([*base, "--out", str(tmp_path / "m"), "--param", "svm.C=3"]) == 0
    for u in (8846, 8847):
        settings = json.loads((tmp_path / "m" / f"u{u}" / "manifest.json").read_text())["settings"]
        assert (settings["cv_groups"], settings["cv_blocks"], settings["params"]) == ("block", 4, {"svm": {"C": 3.0}})


def test_a_non_finite_param_is_one_line_before_training(tmp_path, capsys):
    """Decision B373 (review R2 finding 3): inf, 1e400, nan and a grid with inf passed the check and crashed after
    training (the manifest's JSON cannot store inf)."""
    for bad in ("svm.C=inf", "svm.C=1e400", "svm.C_grid=1,inf", "nn.learning_rate=inf", "nn.weight_decay=nan",
                "dtw.window=nan"):
        with pytest.raises(DataError, match="is not ") as exc:
            parse_params([bad])
        assert "\n" not in str(exc.value)
    code = main(["train", str(tmp_path), "--out", str(tmp_path / "m"), "--param", "svm.C=inf"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and "'inf' is not a number > 0" in err
    assert not (tmp_path / "m").exists()


def test_train_all_errors_name_train_all(tmp_path, capsys):
    """Review R2 finding 7: train-all's --param and --cv-groups lines began with 'train:'."""
    for opt in (["--param", "svm.X=1"], ["--cv-groups", "blocks"]):
        code = main(["train-all", str(tmp_path), "--out", str(tmp_path / "m"), *opt])
        err = capsys.readouterr().err.strip()
        assert code == 2 and err.startswith("error: train-all: ") and len(err.splitlines()) == 1, err
    assert main(["train", str(tmp_path), "--out", str(tmp_path / "m"), "--cv-groups", "blocks"]) == 2
    assert capsys.readouterr().err.startswith("error: train: ")
