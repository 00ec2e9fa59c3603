"""Decision C226 (trial s49t2 finding F7a): evaluate scores the length class track / run report (C88 / C191: a
stride whose measured length contradicts its class takes the measured class) beside the classifier's own, with the
count of strides the rules changed (evaluate read 0.0 % where track wrote short for 11 of 11 tandem strides)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

BOUNDS = {"short": (0.0, 1.3), "normal": (1.3, 1.9), "long": (1.9, 10.0)}


def test_the_rules_give_a_contradicted_stride_its_measured_class():
    from pdrlearn.classify.detected_rules import track_length_classes

    measured = pd.DataFrame({"length_m": [1.0, 1.6, np.nan, 1.6], "turn_rad": [0.0, 0.0, 0.0, np.deg2rad(40)]})
    out = track_length_classes(["long", "normal", "long", "short"], measured, BOUNDS)
    # 1.0 m called long: short (C191); 1.6 m normal: kept; no measurement: kept; a turning stride: measured (C88)
    assert list(out) == ["short", "normal", "long", "normal"]
    assert list(track_length_classes(["long"], measured.iloc[:1], None)) == ["long"]  # no bounds: the classifier's


def test_the_line_says_what_track_reports_and_how_many_changed():
    from pdrlearn.classify.detected_rules import track_length_line

    assert track_length_line({"accuracy": 0.0, "n_steps": 11}, None) is None
    assert track_length_line({"accuracy": 1.0, "n_steps": 11}, {"accuracy": 1.0, "n_steps": 11, "n_changed": 0}) \
        is None
    line = track_length_line({"accuracy": 0.0, "n_steps": 11}, {"accuracy": 1.0, "n_steps": 11, "n_changed": 11})
    assert line.startswith("length as track / run report it: 100.0 % on the strides the runtime detects (the "
                           "classifier's own: 0.0 %): the measured-length rules changed the class of 11 of 11 strides")
    assert "docs/decisions/classifiers.md C88, C191, C226" in line


@pytest.fixture(scope="module")
def tandem():
    """A short tandem-like walk: 0.28 m steps (0.56 m strides), all short against the user's bounds."""
    import dataclasses

    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import SPEED_FACTORS, UserProfile

    user = UserProfile.from_seed(16725)
    f_len, f_time = SPEED_FACTORS["normal"]
    walker = dataclasses.replace(user, step_length_m=0.28 / f_len, class_step_length_m=user.step_length_m,
                                 step_time_s=0.8 / f_time)
    return simulate_path(parse_route("stand:2, straight:5, stand:2"), walker, seed=3)


class _AllLong:
    """A stand-in model that calls every stride long, with the session's bounds."""

    def __init__(self, bounds):
        lo, hi = bounds
        self.length_bounds_m, self.data_summary = [lo, hi], {}

    def predict_steps(self, session, strides, **_):
        return pd.DataFrame({"length_class": ["long"] * len(strides)})


def test_evaluate_scores_the_class_track_reports_on_the_detected_strides(tandem):
    from pdrlearn.classify.detected import DetectedPredictions
    from pdrlearn.classify.detected_rules import measured_strides, track_length_score

    model = _AllLong(tandem.meta["length_class_bounds_m"])
    detected = DetectedPredictions(model, [tandem])
    strides = detected.strides(0)
    measured = measured_strides(tandem, strides)
    full = measured["length_m"].to_numpy(float) > 0.4  # the walk's strides, not its half first / last
    assert full.sum() >= 3
    assert np.allclose(measured["length_m"][full], 0.56, atol=0.08)  # the ZUPT stride, as track measures it
    lab = tandem.steps.reset_index(drop=True)
    rows = np.arange(len(lab))
    data = SimpleNamespace(step=rows, y=lab["length_class"].to_numpy(dtype=object))
    score = track_length_score(model, data, [SimpleNamespace(steps=lab)], {0: rows}, detected)
    assert (lab["length_class"] == "short").all()
    # the classifier's own: 0 % (all long); as track reports them: every matched stride short
    assert score["n_steps"] >= 3 and score["n_changed"] == score["n_steps"] and score["accuracy"] == 1.0
