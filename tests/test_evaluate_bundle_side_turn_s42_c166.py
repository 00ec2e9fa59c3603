"""Decision C166 (session 42): `evaluate BUNDLE` leaves the side-step and turn strides (the simulator's ``kind``) out
of the direction score and reports them on C160's line, through C160's code (``pdrlearn.classify.uncovered``): the
same record and line as the model directory the bundle was exported from."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

USER = 11790  # this helper's simulated users: 11790-11799


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """A direction model (svm, foot) of one simulated user, its bundle, and a route walk with side steps and a turn
    on the spot (C160's test route)."""
    from pdrlearn.classify.training import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.sim.simulate import simulate

    root = tmp_path_factory.mktemp("c166")
    train_user([simulate("direction", user_seed=USER, seed=0)], tasks=["direction"], methods=["svm"],
               units=["foot"], cv=3, distance_calibration=False).save(root / "model")
    export_model(root / "model", root / "bundle", methods=["svm"])
    for name, route, seed in (("walk", "stand:2, straight:3, side:2, side:-2, turn:180, straight:3, backward:3, "
                                       "stand:2", 1),
                              ("side", "stand:2, side:3, stand:2", 3)):
        write_session(simulate_path(parse_route(route), UserProfile.from_seed(USER), rate_hz=100.0, seed=seed,
                                    scenario="route"), root / name)
    return root


def _evaluate(capsys, *args) -> dict:
    assert main(["evaluate", *map(str, args), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_a_bundle_scores_side_and_turn_strides_apart_as_its_model_directory(made, capsys):
    bundle = _evaluate(capsys, made / "bundle", made / "walk")["tasks"]["direction"]
    model = _evaluate(capsys, made / "model", made / "walk")["tasks"]["direction"]
    unc = bundle["uncovered"]
    assert unc is not None and set(unc["by_kind"]) == {"side", "turn"}
    assert unc["n_steps"] == model["uncovered"]["n_steps"]  # the labelled side / turn steps, counted alike
    n_apart = sum(e["n_matched"] for e in unc["by_kind"].values())
    assert n_apart > 0 and all(sum(e["predicted"].values()) == e["n_matched"] for e in unc["by_kind"].values())
    assert sum(map(sum, bundle["confusion"])) == bundle["n_steps"]
    # no side / turn stride in the score: the scored strides are the walk's forward and backward ones
    assert bundle["n_steps"] <= model["n_steps"]
    assert main(["evaluate", str(made / "bundle"), str(made / "walk")]) == 0
    out = capsys.readouterr().out
    assert f"{unc['n_steps']} side / turn stride(s) left out of the direction score" in out and "C160" in out


def test_a_bundle_on_side_steps_only_says_so(made, capsys):
    assert main(["evaluate", str(made / "bundle"), str(made / "side")]) == 2
    errors = [line for line in capsys.readouterr().err.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and "direction: every labelled step is a side / turn stride" in errors[0]
