"""Decision C124 (trial T4 finding 7): a fused soft vote with a unit weight 0 reads one unit: train's table notes the
weights, and C8's choice of the model reading both units passes it over."""

from __future__ import annotations

import numpy as np

from pdrlearn.classify import train_user, training
from pdrlearn.cli.train import chosen_reason, fused_weights_line
from tests.runtime_helpers import synthetic_session


def test_a_zero_weight_vote_is_not_chosen_as_a_two_unit_model_and_its_weights_are_shown(monkeypatch):
    monkeypatch.setattr(training, "best_weights", lambda probas, y: np.array([1.0, 0.0]))
    model = train_user([synthetic_session(60, seed=0)], tasks=["terrain"], methods=["svm"],
                       units=["foot", "waist", "fused"], cv=2, seed=0, distance_calibration=False)
    tm = model.tasks["terrain"]
    assert tm.cv["svm"]["fused"]["weights"] == {"foot": 1.0, "waist": 0.0}
    assert tm.one_unit_votes() == {("svm", "fused")}
    assert tm.chosen == ("svm", "foot")  # before: svm/fused, the foot model under a two-unit name
    assert training.best_pair([("svm", "fused"), ("nn", "combined")], tm.one_unit_votes()) == ("nn", "combined")
    # decision D49 (session 43): the code points to its file
    assert fused_weights_line(tm) == ("fused weights (foot/waist; docs/decisions/classifiers.md C124): svm 1.00/0.00 "
                                      "(reads the foot only: "
                                      "not a two-unit model for the choice)")
    assert chosen_reason(tm).startswith("chosen: svm/foot, the best balanced CV accuracy")
