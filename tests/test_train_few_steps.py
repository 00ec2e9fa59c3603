"""Decision C75: ``train`` warns when a trained task has a class with fewer than 12 labelled steps (trial 31
finding 3: 6 backward strides of 189 were accepted with only a CV-fold note)."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.classify import train_user
from pdrlearn.classify.training import FEW_STEPS_PER_CLASS, few_steps_line
from tests.test_classify_training import labelled_session


def _lines(caplog):
    return [r.getMessage() for r in caplog.records if "decision C75" in r.getMessage()]


def test_few_backward_steps_are_warned_and_enough_are_not(caplog):
    with caplog.at_level(logging.WARNING):
        train_user([labelled_session(1, 8)], tasks=["direction"], methods=["svm"], cv=2)  # 8 backward of 24
    lines = _lines(caplog)
    assert len(lines) == 1, lines
    assert "task direction: few labelled steps per class ('backward' has 8 of 24; under 12" in lines[0]
    assert "--methods direction=heuristic,fusion,dtw (decision C74)" in lines[0]
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        train_user([labelled_session(1, 12)], tasks=["direction"], methods=["svm"], cv=2)  # 12 backward of 36
    assert not _lines(caplog)


def test_few_steps_line_names_every_small_class_and_no_alternative_for_a_template_method():
    y = np.array(["flat"] * 40 + ["up"] * 11 + ["down"] * 5)
    line = few_steps_line("terrain", y, ["flat", "up", "down"], ("dtw", "fused"))
    assert "'up' has 11, 'down' has 5 of 56" in line and "--methods" not in line
    assert few_steps_line("terrain", np.array(["flat", "up", "down"] * FEW_STEPS_PER_CLASS),
                          ["flat", "up", "down"], ("nn", "combined")) is None


def test_a_waist_only_model_says_track_needs_the_foot_unit(caplog):
    """Decision C77 (trial 31 finding 7): `train --units waist` wrote a model nothing could use on a waist-only
    recording, without a word."""
    from pdrlearn.classify.training import WAIST_ONLY_MODEL_LINE

    with caplog.at_level(logging.WARNING):
        m = train_user([labelled_session(1, 12)], tasks=["direction"], methods=["svm"], units=["waist"], cv=2)
    assert m.tasks["direction"].chosen == ("svm", "waist")
    assert f"train: {WAIST_ONLY_MODEL_LINE}" in caplog.text and "tracked session still needs a foot unit" in caplog.text
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        train_user([labelled_session(1, 12)], tasks=["direction"], methods=["svm"], units=["foot"], cv=2)
    assert WAIST_ONLY_MODEL_LINE not in caplog.text
