"""Decision E136: `evaluate`'s JSON (and report.json) and `calibrate`'s PARAMS.json (and --json) carry
``pdrlearn_version``, as track's summary.json (C18); a PARAMS.json with it loads as before."""

from __future__ import annotations

import dataclasses
import json

from pdrlearn import __version__
from pdrlearn.classify import evaluate_model, train_user
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.waist.params import load_params
from tests.test_classify_training import labelled_session


def test_evaluate_result_and_report_carry_the_version(tmp_path):
    model = train_user([labelled_session(1, 12), labelled_session(2, 12)], tasks=["terrain"], methods=["heuristic"],
                       units=["foot"], cv=3, seed=0)
    out = evaluate_model(model, [labelled_session(9, 12)], report_dir=tmp_path / "rep", latency=False)
    assert out["pdrlearn_version"] == __version__
    assert json.loads((tmp_path / "rep" / "report.json").read_text())["pdrlearn_version"] == __version__


def test_calibrate_writes_and_prints_the_version(tmp_path, capsys):
    user = dataclasses.replace(UserProfile.from_seed(4969), step_length_m=0.54, step_time_s=0.54)
    s = simulate_path([Stand(2), Straight(12), Stand(2)], user, speed="normal", rate_hz=100, seed=0, bounce="pendulum")
    write_session(s, tmp_path / "walk")
    assert main(["calibrate", str(tmp_path / "walk"), "-d", "12", "--out", str(tmp_path / "p.json"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["pdrlearn_version"] == __version__
    assert json.loads((tmp_path / "p.json").read_text())["pdrlearn_version"] == __version__
    assert load_params(tmp_path / "p.json").source == "calibrated"
