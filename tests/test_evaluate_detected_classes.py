"""Decision C76: evaluate's figure on the detected strides (C49, what the user gets) has per-class recall, the
confusion matrix and per-session numbers, in --json and under the table (trial 31 finding 6: slowback's 0 of 6
backward strides disappeared into a pooled accuracy)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.classify.detected import detected_lines
from pdrlearn.classify.evaluation import evaluate_model, markdown_tables
from pdrlearn.classify.training import train_user
from pdrlearn.sim.simulate import simulate


@pytest.fixture(scope="module")
def evaluated():
    model = train_user([simulate("direction", user_seed=6143, seed=0)], tasks=["direction"], methods=["svm"],
                       units=["foot"], cv=3, distance_calibration=False)
    walks = [dataclasses.replace(simulate("direction", user_seed=6143, seed=s), name=f"walk{s}") for s in (1, 2)]
    return evaluate_model(model, walks, latency=False)


def test_detected_figure_has_per_class_confusion_and_sessions(evaluated):
    det = evaluated["tasks"]["direction"]["detected"]
    assert det["classes"] == ["forward", "backward"]
    conf = np.array(det["confusion"])
    assert conf.sum() == det["n_steps"] and list(conf.sum(axis=1)) == [det["per_class_n"][c] for c in det["classes"]]
    assert det["per_class"]["backward"] == pytest.approx(conf[1, 1] / conf[1].sum())
    assert set(det["sessions"]) == {"walk1", "walk2"}
    assert sum(v["n_steps"] for v in det["sessions"].values()) == det["n_steps"]
    pooled = np.sum([v["confusion"] for v in det["sessions"].values()], axis=0)
    assert pooled.tolist() == det["confusion"]


def test_detected_lines_in_the_table_and_report(evaluated):
    lines = detected_lines(evaluated["tasks"]["direction"]["detected"])
    assert lines[0].startswith("chosen model on the detected strides, recall % per class: forward ")
    assert lines[1].startswith("confusion on the detected strides (rows: true forward, backward; columns: predicted)")
    assert lines[0] in markdown_tables(evaluated)
    det = {"n_steps": 13, "classes": ["forward", "backward"], "per_class": {"forward": 1.0, "backward": 0.5},
           "per_class_n": {"forward": 7, "backward": 6}, "confusion": [[7, 0], [3, 3]],
           "sessions": {"a": {"per_class": {"forward": 1.0, "backward": 0.0}, "per_class_n": {"forward": 3,
                                                                                              "backward": 3}},
                        "b": {"per_class": {"forward": 1.0, "backward": 1.0}, "per_class_n": {"forward": 4,
                                                                                              "backward": 3}}}}
    lines = detected_lines(det)
    assert "forward 100.0 (7/7), backward 50.0 (3/6)" in lines[0]
    assert lines[2] == "lowest session recall on the detected strides: backward 0.0 % (a, 3 steps)"
    assert detected_lines(None) == [] and detected_lines({"n_steps": 0}) == []
