"""Decisions C41-C43 and E52: the CV folds' spread and t-interval, per-step predictions of `evaluate`
(written atomically), the leave-one-user-out title and per-user line, `run --method`."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify.evaluation import PREDICTION_COLUMNS, evaluate_model, write_predictions
from pdrlearn.classify.spread import clopper_pearson, fold_spread, t_interval
from pdrlearn.classify.training import _cv_entry, _folds, train_user
from pdrlearn.cli.common import file_kind, out_file
from pdrlearn.cli.train import cv_title, louo_line
from pdrlearn.errors import DataError
from pdrlearn.runtime.bundle import Bundle
from pdrlearn.sim.simulate import simulate


def test_t_interval_over_folds_by_hand():
    # mean 0.9, sd 0.1, k 3: half width t_{0.975,2} 4.3027 * 0.1 / sqrt(3) = 0.2484; clipped to [0, 1]
    lo, hi = t_interval([0.9, 1.0, 0.8])
    assert lo == pytest.approx(0.9 - 4.302653 * 0.1 / np.sqrt(3), abs=1e-6) and hi == 1.0
    assert t_interval([0.7]) is None  # one fold: no interval


def test_clopper_pearson_by_hand_and_all_folds_perfect():
    # k = n: the lower end solves p^n = 0.025 (Clopper & Pearson 1934), 224/224 -> 0.025^(1/224) = 98.37 %
    lo, hi = clopper_pearson(224, 224)
    assert lo == pytest.approx(0.025 ** (1 / 224), abs=1e-9) and hi == 1.0
    assert clopper_pearson(0, 10) == pytest.approx((0.0, 1 - 0.025 ** (1 / 10)))
    assert clopper_pearson(0, 0) is None
    y = np.array(["a", "b"] * 112)
    folds = [(np.setdiff1d(np.arange(224), te), te) for te in np.array_split(np.arange(224), 10)]
    s = fold_spread(y, y, folds)
    # was "100-100", the t-interval of ten perfect folds (the table's text since C150: cv_report.display_table)
    assert (s["mean"], s["sd"]) == (1.0, 0.0) and s["ci95"] == pytest.approx([0.025 ** (1 / 224), 1.0])


def test_fold_spread_scores_each_fold_and_names_the_held_out_users():
    y = np.array(["a", "a", "b", "b", "a", "b"])
    p = np.array(["a", "b", "b", "b", "a", "a"])
    folds = [(np.array([3, 4, 5]), np.array([0, 1, 2])), (np.array([0, 1, 2]), np.array([3, 4, 5]))]
    s = fold_spread(y, p, folds, groups=np.array(["u1"] * 3 + ["u2"] * 3))
    assert s["accuracy"] == pytest.approx([2 / 3, 2 / 3]) and s["n_steps"] == [3, 3]
    assert s["balanced_accuracy"] == pytest.approx([0.75, 0.75])  # per fold: mean recall of its classes
    assert s["sd"] == 0.0 and s["users"] == ["u1", "u2"] and s["t_ci95"] == pytest.approx([2 / 3, 2 / 3])
    # decision C58: the table's interval is the exact binomial one of 4 of 6 pooled steps, not the folds' point
    assert s["interval"] == "Clopper-Pearson over the pooled steps"
    assert s["ci95"] == pytest.approx(list(clopper_pearson(4, 6))) and s["ci95"] == pytest.approx([0.223, 0.957],
                                                                                                   abs=5e-4)
    e = _cv_entry(y, p, ["a", "b"], folds, 2, np.array(["u1"] * 3 + ["u2"] * 3))
    assert e["n_folds"] == 2 and e["folds"]["users"] == ["u1", "u2"] and e["accuracy"] == pytest.approx(4 / 6)
    assert cv_title(e) == "leave-one-user-out CV accuracy (2 users)"
    assert louo_line(e) == "chosen model per held-out user: u1 66.7 % (3 steps), u2 66.7 % (3 steps)"
    assert cv_title({**e, "cv_users": 12}) == "2-fold CV accuracy (folds of whole users, 12 users)"
    assert louo_line({**e, "folds": {**e["folds"], "users": None}}) is None


@pytest.fixture(scope="module")
def terrain():
    return simulate("terrain", user_seed=3, seed=0)


@pytest.fixture(scope="module")
def model(terrain):
    return train_user([terrain], tasks=["terrain"], methods=["svm", "heuristic"], units=["foot"], cv=3,
                      distance_calibration=False)


def test_train_keeps_every_folds_accuracy(model):
    r = model.tasks["terrain"].cv["svm"]["foot"]
    f = r["folds"]
    assert len(f["accuracy"]) == r["n_folds"] == 3 and sum(f["n_steps"]) == r["n_steps"]
    # the pooled accuracy is the folds' accuracies weighted by their steps
    assert np.dot(f["accuracy"], f["n_steps"]) / sum(f["n_steps"]) == pytest.approx(r["accuracy"])
    assert f["mean"] == pytest.approx(np.mean(f["accuracy"]))


def test_evaluate_writes_one_row_per_scored_step(model, terrain, tmp_path):
    tables: list = []
    res = evaluate_model(model, [terrain], latency=False, step_predictions=tables)
    n = write_predictions(tables, tmp_path / "p.csv")
    df = pd.read_csv(tmp_path / "p.csv")
    r = res["tasks"]["terrain"]
    assert n == len(df) == r["n_steps"] and tuple(df.columns[:len(PREDICTION_COLUMNS)]) == PREDICTION_COLUMNS
    assert df["correct"].mean() == pytest.approx(r["accuracy"])
    assert (df["method"] + "/" + df["unit"]).unique().tolist() == ["svm/foot"]
    assert np.allclose(df[["p_flat", "p_up", "p_down"]].sum(axis=1), 1.0)
    assert np.allclose(df["start_s"], terrain.steps["start_s"].to_numpy()[df["step"]])
    assert file_kind(tmp_path / "p.csv") == "predictions"
    out_file(tmp_path / "p.csv", (".csv",), "predictions", force=True)  # its own kind: --force replaces it


def test_predictions_are_written_atomically(tmp_path, monkeypatch):
    target = tmp_path / "p.csv"
    target.write_text("old\n")

    def broken(self, path, **kw):
        open(path, "w").write("session,st")
        raise OSError("disk full")

    monkeypatch.setattr(pd.DataFrame, "to_csv", broken)
    with pytest.raises(OSError):
        write_predictions([pd.DataFrame({"session": ["s"]})], target)
    assert target.read_text() == "old\n" and [p.name for p in tmp_path.iterdir()] == ["p.csv"]


def _bundle(methods, chosen):
    tasks = {t: {"classes": ["a", "b"], "chosen": c, "methods": m} for (t, m), c in zip(methods.items(), chosen,
                                                                                    strict=True)}
    return Bundle(__import__("pathlib").Path("/b"), {"tasks": tasks})


def test_run_method_resolves_against_what_the_bundle_exported():
    b = _bundle({"terrain": {"nn": {"combined": {}}, "svm": {"combined": {}, "foot": {}}},
                 "length": {"nn": {"combined": {}}, "dtw": {"fused": {}}}},
                [{"method": "nn", "unit": "combined"}] * 2)
    assert b.choose_methods("nn") == {"terrain": "nn/combined", "length": "nn/combined"}
    assert b.choose_methods("nn,terrain=svm/foot,length=dtw") == {"terrain": "svm/foot", "length": "dtw/fused"}
    assert b.choose_methods("terrain=svm") == {"terrain": "svm/combined"}  # the chosen unit
    with pytest.raises(DataError, match="no svm model for length .it has nn/combined, dtw/fused"):
        b.choose_methods("svm")
    with pytest.raises(DataError, match="no task 'direction'"):
        b.choose_methods("direction=svm")
    one = _bundle({"terrain": {"nn": {"combined": {}}}}, [{"method": "nn", "unit": "combined"}])
    with pytest.raises(DataError, match="chosen method only: export others"):
        one.choose_methods("svm")
    two = _bundle({"terrain": {"svm": {"foot": {}, "waist": {}}}}, [{"method": "svm", "unit": "foot"}])
    assert two.choose_methods("svm") == {"terrain": "svm/foot"}
    # the chosen model reads both units: the method's two-unit model, combined before fused
    assert b.choose_methods("length=dtw") == {"length": "dtw/fused"}
    three = _bundle({"terrain": {"nn": {"fused": {}}, "svm": {"foot": {}, "waist": {}}}},
                    [{"method": "nn", "unit": "fused"}])
    with pytest.raises(DataError, match="give one, e.g. --method terrain=svm/foot"):
        three.choose_methods("svm")
    # decision E56: two every-task items are refused (the last one won without a word); an empty TASK= named
    with pytest.raises(DataError, match="nn and svm are both for every task; give one, or one per task as "
                       "TASK=METHOD .the bundle's tasks: terrain, length"):
        b.choose_methods("nn,svm")
    with pytest.raises(DataError, match="run --method terrain=: give a method after terrain=, e.g. --method "
                       "terrain=svm"):
        b.choose_methods("terrain=")


def test_user_folds_impossible_name_the_user_and_the_class(caplog):
    y = np.array(["a", "b", "c"] * 4 + ["a", "b"] * 4)
    g = np.array(["u0"] * 12 + ["u1"] * 8)  # only u0 walked class c
    folds, n_users = _folds(y, 5, 0, "toy", groups=g)
    assert n_users == 0
    assert "holding out u0 leaves no c step to train on (only u0 walked it)" in caplog.text
