"""Classifiers decision C97 (amends cohort C92): ``evaluate-all --per-method`` gives every method x unit its own
accuracy on the strides the runtime detects, not only the chosen model."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify import evaluate_model, load_model
from pdrlearn.classify.detected import MIN_IOU, detected_strides
from pdrlearn.io import read_session
from pdrlearn.track.evaluate import match_by_overlap
from tests.sim_helpers import TERRAIN_COHORT_USERS, shared_terrain_cohort

USERS = TERRAIN_COHORT_USERS


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    """``(cohort, models, eval)``: the terrain cohort of USERS and its ``evaluate-all --per-method`` output, made
    once per run for decisions C92's and C97's tests (``tests.sim_helpers.shared_terrain_cohort``, testing D51)."""
    return shared_terrain_cohort(tmp_path_factory)


def _by_hand(model, session, method, unit):
    """Accuracy of ``method/unit`` on the detected strides matched to the labelled terrain steps."""
    strides = detected_strides(session)
    pred = model.predict_steps(session, strides, windows="given", tasks=["terrain"], method=method, unit=unit)
    pairs = match_by_overlap(strides, session.steps[["start_s", "end_s"]].reset_index(drop=True), min_iou=MIN_IOU)
    got = pred["terrain"].to_numpy(dtype=object)
    truth = session.steps["terrain"].to_numpy(dtype=object)
    ok = [got[s] == truth[t] for s, t in pairs if got[s] is not None]
    return float(np.mean(ok)), len(ok)


def test_every_method_row_has_its_own_detected_stride_accuracy(trained):
    cohort, models, out = trained
    rows = pd.read_csv(out / "cohort_methods.csv")  # evaluate-all MODELS COHORT --out eval --serial --per-method
    assert rows["accuracy_detected"].notna().all() and (rows["n_steps_detected"] > 0).all()
    differ = 0
    for u in USERS:
        model = load_model(models / f"u{u}")
        session = read_session(cohort / f"u{u}" / "test" / "terrain")
        res = evaluate_model(model, [session], latency=False, detected_methods=True)["tasks"]["terrain"]
        chosen = (res["chosen"]["method"], res["chosen"]["unit"])
        # the chosen model's own per-method score is the task's detected figure (one function, the same strides)
        assert math.isclose(res["methods"][chosen[0]]["units"][chosen[1]]["detected"]["accuracy"],
                            res["detected"]["accuracy"])
        for _, row in rows[rows["user"] == f"u{u}"].iterrows():
            acc, n = _by_hand(model, session, row["method"], row["unit"])
            assert math.isclose(row["accuracy_detected"], acc) and row["n_steps_detected"] == n
            differ += not math.isclose(acc, res["detected"]["accuracy"])
    assert differ  # some method scores otherwise than the chosen one: the rows are not the chosen figure copied
    pooled = pd.read_csv(out / "cohort_methods_summary.csv")
    for (m, unit), grp in rows.groupby(["method", "unit"]):
        p = pooled[(pooled["method"] == m) & (pooled["unit"] == unit)].iloc[0]
        assert math.isclose(p["accuracy_detected_mean"], grp["accuracy_detected"].mean())
