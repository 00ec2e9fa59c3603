"""Decision C139 (trial T4 findings 2, 8): ``train --param`` reaches the estimators' documented options - the
heuristics' ``thresholds`` / ``weights`` / ``bands`` (heuristic and fusion) and DTW's ``rule`` / ``calibration`` -
checked as C96's names are; the defaults stay as they were."""

from __future__ import annotations

import json

import pytest

from pdrlearn.classify.hyper import parse_params
from pdrlearn.classify.training import make_estimator
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def test_params_name_the_heuristic_and_dtw_options_and_refuse_bad_values():
    assert parse_params(["heuristic.thresholds=thesis", "dtw.rule=spread", "fusion.weights=skill",
                         "heuristic.bands=false", "dtw.calibration=gap"]) == {
        "heuristic": {"thresholds": "thesis", "bands": False}, "dtw": {"rule": "spread", "calibration": "gap"},
        "fusion": {"weights": "skill"}}
    for bad in ("heuristic.thresholds=printed", "dtw.rule=median", "heuristic.bands=1"):
        with pytest.raises(DataError, match=r"--param .* is not '") as exc:
            parse_params([bad])
        assert "\n" not in str(exc.value)


def test_estimators_take_them_and_the_defaults_stay():
    p = {"heuristic": {"thresholds": "thesis"}, "fusion": {"thresholds": "learn"}, "dtw": {"rule": "spread"}}
    assert make_estimator("terrain", "heuristic", "foot", params=p).thresholds == "thesis"
    assert make_estimator("terrain", "heuristic", "foot").thresholds == "joint"
    assert make_estimator("length", "fusion", "fused", params=p).thresholds == "learn"
    assert make_estimator("terrain", "dtw", "waist", params=p)[-1].rule == "spread"
    dflt = make_estimator("terrain", "dtw", "waist")[-1]
    assert (dflt.rule, dflt.calibration) == ("mean", "cv")


def test_train_cli_takes_heuristic_thresholds_and_dtw_rule(tmp_path, capsys):
    data = write_session(simulate("terrain", user_seed=9605), tmp_path / "terrain")
    assert main(["train", str(data), "--out", str(tmp_path / "m"), "--tasks", "terrain", "--methods", "heuristic,dtw",
                 "--units", "foot,waist", "--cv", "3", "--param", "heuristic.thresholds=thesis",
                 "--param", "dtw.rule=spread", "--json"]) == 0
    settings = json.loads((tmp_path / "m" / "manifest.json").read_text())["settings"]
    assert settings["params"] == {"heuristic": {"thresholds": "thesis"}, "dtw": {"rule": "spread"}}
    from pdrlearn.classify import load_model

    models = load_model(tmp_path / "m").tasks["terrain"].models
    assert models["heuristic"]["foot"].thresholds == "thesis" and models["dtw"]["waist"][-1].rule == "spread"
