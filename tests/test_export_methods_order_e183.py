"""Decision E183: with ``export --methods``, a bundle's ``chosen`` model is the model's chosen one when it is
exported, else the best-ranked of the exported models (as training chooses, decisions C8, C23), whatever order
the methods are listed in (trial T5 finding 1: it was the first method listed)."""

from __future__ import annotations

import json

from pdrlearn.classify import train_user
from pdrlearn.classify.training import best_pair
from pdrlearn.export.from_model import export_model
from tests.runtime_helpers import synthetic_session


def _foot(session):
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del session.streams[name]
    return session


def test_chosen_is_the_best_ranked_exported_model_in_either_order(tmp_path):
    model = train_user([_foot(synthetic_session(60, seed=8620))], tasks=["terrain"], units=["foot"],
                       methods=["heuristic", "dtw", "svm"], cv=2, seed=0, distance_calibration=False)
    tm = model.tasks["terrain"]
    tm.chosen = ("svm", "foot")  # the model's own choice is not exported: export picks among the rest
    model.save(tmp_path / "m")
    best = best_pair([p for p in tm.ranking() if p[0] in ("heuristic", "dtw")])
    assert best is not None
    chosen = {}
    for order in (["heuristic", "dtw"], ["dtw", "heuristic"]):
        out = export_model(tmp_path / "m", tmp_path / "-".join(order), methods=order)
        task = json.loads((out / "manifest.json").read_text())["tasks"]["terrain"]
        chosen[order[0]] = (task["chosen"]["method"], task["chosen"]["unit"])
        assert chosen[order[0]] == best, order
        assert (task["foot_only"]["method"], task["foot_only"]["unit"]) == best  # E26: the same model
    assert chosen["heuristic"] == chosen["dtw"]
