"""Decision C161 (session 41, trial T1 finding F7): the model's manifest records how many side-step (and turn)
strides its direction task was trained on, and C137's side-step line says what the model saw instead of always
claiming "its calibration walks had no side steps"."""

from __future__ import annotations

import pandas as pd

from pdrlearn.classify.model_dir import load_model, save_model
from pdrlearn.classify.training import train_user
from pdrlearn.classify.uncovered import trained_side_strides
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.travel import side_class_warning


def _table():
    return pd.DataFrame({"direction": ["forward", "backward", "backward"], "sideways": [False, True, True],
                         "confidence": [0.9, 0.62, 0.65]})


def test_the_line_follows_what_the_model_was_trained_on():
    said = {}
    for trained in (None, 0, 12):
        lines: list[str] = []
        side_class_warning(_table(), lines, trained)
        assert len(lines) == 1 and lines[0].startswith("2 of 2 side-step strides") and "(decision C137)" in lines[0]
        said[trained] = lines[0]
    assert "its calibration walks had no side steps" in said[0]
    assert "its calibration walks held 12 side-step strides labelled forward" in said[12]
    assert "had no side steps" not in said[12] and "had no side steps" not in said[None]
    assert "its manifest does not say whether its calibration held side steps" in said[None]


def test_the_manifest_keeps_the_side_strides_of_the_training(tmp_path):
    user = UserProfile.from_seed(11527)
    calib = simulate("direction", user_seed=11527, seed=0)
    side = simulate_path(parse_route("stand:2, straight:3, side:2, side:-2, straight:3, stand:2"), user,
                         rate_hz=20.0, seed=5, scenario="route")
    n_side = int((side.steps["kind"] == "side").sum())
    assert n_side > 0
    for sessions, want in (([calib], 0), ([calib, side], n_side)):
        model = train_user(sessions, tasks=["direction"], methods=["svm"], units=["foot"], cv=3,
                           distance_calibration=False)
        assert trained_side_strides(model) == want
        out = tmp_path / f"m{want}"
        save_model(model, out)
        assert trained_side_strides(load_model(out)) == want
        assert load_model(out).tasks["direction"].trained_kinds == {"side": want, "turn": 0}
    # a steps table without kind (hand-labelled): not known
    calib.steps = calib.steps.drop(columns=["kind"])
    model = train_user([calib], tasks=["direction"], methods=["svm"], units=["foot"], cv=3,
                       distance_calibration=False)
    assert trained_side_strides(model) is None
    assert trained_side_strides(None) is None and trained_side_strides("oracle") is None
