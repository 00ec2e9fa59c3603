"""Decision C125 (trial T4 finding 4): ``evaluate --all-methods --predictions-out`` writes every method x unit's class
of each labelled step matched to a detected stride, the same steps for every model (paired tests), agreeing with
C97's per-method detected scores."""

from __future__ import annotations

import json
import math

import pandas as pd

from pdrlearn.classify import train_user
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def test_all_methods_predictions_are_every_model_on_the_same_detected_strides(tmp_path, capsys):
    model = train_user([simulate("terrain", user_seed=9203)], tasks=["terrain"], methods=["heuristic", "svm"],
                       units=["foot", "waist", "combined"], cv=3, distance_calibration=False)
    model.save(tmp_path / "m")
    test = write_session(simulate("terrain", user_seed=9203, seed=7), tmp_path / "test")
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "m"), str(test), "--all-methods", "--predictions-out",
                 str(tmp_path / "p.csv"), "--json"]) == 0
    res = json.loads(capsys.readouterr().out)["tasks"]["terrain"]
    rows = pd.read_csv(tmp_path / "p.csv")
    pairs = {(m, u) for m, per in model.tasks["terrain"].models.items() for u in per}
    assert set(zip(rows["method"], rows["unit"], strict=True)) == pairs and len(pairs) >= 4
    steps = {mu: set(g["step"]) for mu, g in rows.groupby(["method", "unit"])}
    assert len({frozenset(v) for v in steps.values()}) == 1  # the same matched steps for every model
    for (m, u), g in rows.groupby(["method", "unit"]):
        det = res["methods"][m]["units"][u]["detected"]
        assert math.isclose(g["correct"].mean(), det["accuracy"]) and len(g) == det["n_steps"]
    chosen = rows[(rows["method"] == res["chosen"]["method"]) & (rows["unit"] == res["chosen"]["unit"])]
    assert math.isclose(chosen["correct"].mean(), res["detected"]["accuracy"])
    assert rows.filter(like="p_").isna().all().all()
    assert (rows.groupby(["method", "unit"])["predicted"].apply(tuple).nunique()) > 1  # not one model copied


def test_all_methods_rows_are_the_steps_every_model_classified_and_no_strides_is_one_line(tmp_path, capsys):
    """Review R4: with a foot-only session the foot models wrote twice the steps of the waist and fused ones, and a
    waist-only session (no detected strides) wrote 0 rows without a reason."""
    model = train_user([simulate("terrain", user_seed=9360)], tasks=["terrain"], methods=["svm"],
                       units=["foot", "waist", "fused"], cv=2, distance_calibration=False)
    model.save(tmp_path / "m")
    both = write_session(simulate("terrain", user_seed=9360, seed=5), tmp_path / "both")
    foot = write_session(simulate("terrain", user_seed=9360, seed=6), tmp_path / "foot")
    waist = write_session(simulate("terrain", user_seed=9360, seed=6), tmp_path / "waist")
    for f in foot.glob("w*.csv"):
        f.unlink()
    for f in waist.glob("f*.csv"):
        f.unlink()
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "m"), str(foot), str(both), "--all-methods", "--predictions-out",
                 str(tmp_path / "p.csv")]) == 0
    rows = pd.read_csv(tmp_path / "p.csv")
    per = rows.groupby(["method", "unit"])
    assert per.ngroups == 3 and per.size().nunique() == 1  # before: 2x the rows for svm/foot
    assert len({frozenset(zip(g["session"], g["step"], strict=True)) for _, g in per}) == 1
    assert rows["session"].nunique() == 1  # the foot-only session's steps: not classified by svm/waist
    assert main(["evaluate", str(tmp_path / "m"), str(waist), "--all-methods", "--predictions-out",
                 str(tmp_path / "p2.csv")]) == 0
    err = capsys.readouterr().err
    assert sum("no detected strides" in line for line in err.splitlines()) == 1, err


def test_no_strides_line_is_said_once_for_a_two_task_model(tmp_path, capsys):
    """Closing re-read (session 37): the C125 no-strides line names the session, not the task; a model of two tasks
    said it twice."""
    model = train_user([simulate("terrain", user_seed=9361), simulate("direction", user_seed=9361)],
                       tasks=["terrain", "direction"], methods=["svm"], units=["foot", "waist"], cv=2,
                       distance_calibration=False)
    model.save(tmp_path / "m")
    waist = write_session(simulate("direction", user_seed=9361, seed=6), tmp_path / "waist")
    for f in waist.glob("f*.csv"):
        f.unlink()
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "m"), str(waist), "--all-methods", "--predictions-out",
                 str(tmp_path / "p.csv")]) == 0
    err = capsys.readouterr().err
    assert sum("no detected strides" in line for line in err.splitlines()) == 1, err
