"""Decision C49: `evaluate` scores the chosen model on the strides the runtime and `track` detect (what the user
gets) besides the labelled boundaries, and warns when the first falls well below the second."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.classify.detected import WARN_DROP, drop_warning
from pdrlearn.classify.evaluation import evaluate_model
from pdrlearn.classify.training import train_user
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.evaluate import match_by_overlap
from pdrlearn.track.plasys import track_plasys


@pytest.fixture(scope="module")
def model():
    return train_user([simulate("terrain", user_seed=3, seed=0)], tasks=["terrain"], methods=["svm"],
                      units=["foot"], cv=3, distance_calibration=False, boundaries="given")  # the pre-C50 default


def test_evaluate_scores_the_strides_track_classifies(model):
    walk = simulate("terrain", user_seed=3, seed=1)
    out = evaluate_model(model, [walk], latency=False)
    det = out["tasks"]["terrain"]["detected"]
    assert det["n_labelled"] == out["tasks"]["terrain"]["n_steps"]
    # the same figure from what `track --streaming` (the runtime's path) classifies, matched to the labels
    res = track_plasys(walk, method="M3", model=model, streaming=True)
    lab = walk.steps.reset_index(drop=True)
    pairs = match_by_overlap(res.steps.reset_index(drop=True), lab, min_iou=det["min_iou"])
    got = np.array([res.steps["terrain"].iloc[i] == lab["terrain"].iloc[j] for i, j in pairs])
    assert det["n_steps"] == len(pairs) > 0.9 * len(lab)
    assert det["accuracy"] == pytest.approx(got.mean())


def test_a_drop_on_the_detected_strides_is_one_warning_naming_the_fix(model, monkeypatch, caplog):
    import pdrlearn.classify.detected as D

    walk = simulate("terrain", user_seed=3, seed=1)
    real = D.detected_strides
    # strides detected 5 samples late (20 Hz): the labelled-boundary score cannot see it, the detected one does
    monkeypatch.setattr(D, "detected_strides", lambda s: real(s) + 0.25)
    with caplog.at_level(logging.WARNING):
        out = evaluate_model(model, [walk], latency=False)
    t = out["tasks"]["terrain"]
    assert t["accuracy"] - t["detected"]["accuracy"] >= WARN_DROP
    line = drop_warning("terrain", t["accuracy"], t["detected"], "given")
    assert line in caplog.text and "--boundaries rest" in line and "(decision C49)" in line
    det = {"accuracy": 0.853, "n_steps": 68, "n_labelled": 68}
    assert "85.3 % on the strides" in drop_warning("terrain", 1.0, det, "given")
    assert "--boundaries rest" not in drop_warning("terrain", 1.0, det, "rest")
    assert drop_warning("terrain", 0.9, det, "given") is None


def test_the_cli_leads_with_the_detected_figure(model, tmp_path, capsys):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    model.save(tmp_path / "m")
    walk = simulate("terrain", user_seed=3, seed=1)
    write_session(walk, tmp_path / "w")
    out = evaluate_model(model, [walk], latency=False)["tasks"]["terrain"]
    assert main(["evaluate", str(tmp_path / "m"), str(tmp_path / "w"), "--report", str(tmp_path / "r")]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("terrain:"))
    det = out["detected"]
    assert line == (f"terrain: {out['n_steps']} steps - chosen svm/foot {100 * det['accuracy']:.1f} % on the strides "
                    f"the runtime detects ({det['n_steps']} of {det['n_labelled']} labelled steps matched); "
                    f"{100 * out['accuracy']:.1f} % on the labelled boundaries (the table)")
    assert line.split(" - chosen svm/foot ")[1] in (tmp_path / "r" / "report.md").read_text()



@pytest.mark.parametrize("found", [False, True])
def test_detection_runs_once_per_session_for_every_method_and_unit(monkeypatch, found):
    """Session 37 re-read: a session without detected strides was detected again for each method x unit (C97);
    the detection is now kept per session for the object's life, strides or none."""
    import pandas as pd

    import pdrlearn.classify.detected as D

    calls = []
    strides = pd.DataFrame({"start_s": [0.0, 1.0], "end_s": [1.0, 2.0]}) if found else None
    monkeypatch.setattr(D, "detected_strides", lambda s: calls.append(s) or strides)

    class Model:  # predicts one class per stride, whichever model is asked
        def predict_steps(self, session, st, **kw):
            return pd.DataFrame({"terrain": ["level"] * len(st)})

    det = D.DetectedPredictions(Model(), ["walk a", "walk b"])
    for i in (0, 1):
        det.session(i)
        for method in ("svm", "rf"):
            for unit in ("foot", "waist", "both"):
                got = det.session(i, "terrain", method, unit)
                assert (got is None) if not found else got[0] is strides
    assert calls == ["walk a", "walk b"]
