"""Decision C160 (session 41, trial T1 finding F6): `evaluate` leaves the side-step and turn strides (the
simulator's ``kind``) out of the direction score, which has only forward and backward, and reports them on a line
of their own: which class the chosen model gave them on the detected strides."""

from __future__ import annotations

import pytest

from pdrlearn.classify.evaluation import evaluate_model, markdown_tables
from pdrlearn.classify.training import train_user
from pdrlearn.classify.uncovered import uncovered_line
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate


@pytest.fixture(scope="module")
def model():
    return train_user([simulate("direction", user_seed=11522, seed=0)], tasks=["direction"], methods=["svm"],
                      units=["foot"], cv=3, distance_calibration=False)


def test_side_and_turn_strides_leave_the_direction_score(model):
    walk = simulate_path(parse_route("stand:2, straight:3, side:2, side:-2, turn:180, straight:3, backward:3, "
                                     "stand:2"), UserProfile.from_seed(11522), rate_hz=100.0, seed=1,
                         scenario="route")
    kinds = walk.steps["kind"].astype(str)
    n_out = int(kinds.isin(["side", "turn"]).sum())
    assert n_out >= 6 and (walk.steps["direction"][kinds.isin(["side", "turn"])] == "forward").all()
    out = evaluate_model(model, [walk], latency=False)
    t = out["tasks"]["direction"]
    assert t["n_steps"] == len(walk.steps) - n_out  # the scored steps are the walking ones only
    assert sum(t["confusion"][0]) + sum(t["confusion"][1]) == t["n_steps"]
    unc = t["uncovered"]
    assert unc["n_steps"] == n_out
    assert {k: e["n_steps"] for k, e in unc["by_kind"].items()} == kinds[kinds.isin(["side", "turn"])] \
        .value_counts().to_dict()
    assert all(sum(e["predicted"].values()) == e["n_matched"] <= e["n_steps"] for e in unc["by_kind"].values())
    line = uncovered_line("direction", unc, t["classes"])
    assert line.startswith(f"{n_out} side / turn stride(s) left out of the direction score") and "C160" in line
    assert line in markdown_tables(out)


def test_a_table_without_kind_keeps_every_step_and_all_side_is_skipped(model):
    walk = simulate("direction", user_seed=11523, seed=2)
    unlabelled = walk.steps.drop(columns=["kind"])
    walk.steps = unlabelled
    out = evaluate_model(model, [walk], latency=False)
    assert out["tasks"]["direction"]["n_steps"] == len(unlabelled)
    assert out["tasks"]["direction"]["uncovered"] is None
    side = simulate_path(parse_route("stand:2, side:3, stand:2"), UserProfile.from_seed(11522), rate_hz=100.0,
                         seed=3, scenario="route")
    assert (side.steps["kind"] == "side").all()
    out = evaluate_model(model, [side], latency=False)
    assert "direction" not in out["tasks"]
    assert any("every labelled step is a side / turn stride" in s for s in out["skipped"])


def test_the_line_names_each_kind_and_the_classes():
    unc = {"kinds": ["side", "turn"], "n_steps": 3,
           "by_kind": {"side": {"n_steps": 2, "n_matched": 2, "predicted": {"forward": 0, "backward": 2}},
                       "turn": {"n_steps": 1, "n_matched": 0, "predicted": {"forward": 0, "backward": 0}}}}
    assert uncovered_line("direction", unc, ["forward", "backward"]) == (
        "3 side / turn stride(s) left out of the direction score, which its classes (forward, backward) do not "
        "cover: side 2 (chosen model on the 2 detected: forward 0, backward 2); turn 1 (decision C160)")
    assert uncovered_line("direction", None, ["forward", "backward"]) is None
