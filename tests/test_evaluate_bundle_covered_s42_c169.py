"""Decision C169 (session 42, fixer FR, review R1 finding 5; amends C166): `evaluate BUNDLE` says "every labelled
step is a side / turn stride" only when no labelled step of the task's covered classes is in the sessions (the model
directory's rule, ``split_rows``); forward strides no runtime stride matched (a coarse labeller: each labelled stride
0.3 x as long) beside one turn stride give "no runtime stride matched", as before C166."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

USER = 11898  # fixer FR's simulated user


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """A direction bundle (svm, foot) of one simulated user; a walk with a turn on the spot whose labelled strides
    are cut to 0.3 x (IoU < 0.5 with every runtime stride); a side-steps-only walk (C166's)."""
    from pdrlearn.classify.training import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.sim.simulate import simulate

    root = tmp_path_factory.mktemp("c169")
    train_user([simulate("direction", user_seed=USER, seed=0)], tasks=["direction"], methods=["svm"],
               units=["foot"], cv=3, distance_calibration=False).save(root / "model")
    export_model(root / "model", root / "bundle", methods=["svm"])
    for name, route in (("coarse", "stand:2, straight:6, turn:180, straight:6, stand:2"),
                        ("side", "stand:2, side:3, stand:2")):
        write_session(simulate_path(parse_route(route), UserProfile.from_seed(USER), rate_hz=100.0, seed=1,
                                    scenario="route"), root / name)
    p = root / "coarse" / "steps.csv"
    st = pd.read_csv(p)
    st["end_ms"] = st["start_ms"] + 0.3 * (st["end_ms"] - st["start_ms"])  # a coarse labeller
    for c in ("ic_ms", "tc_ms"):
        st[c] = st[["start_ms", "end_ms"]].mean(axis=1)
    st.to_csv(p, index=False)
    assert (st["kind"] == "turn").any() and (st["direction"] == "forward").sum() > 1
    return root


def _error(capsys, *args) -> str:
    assert main(["evaluate", *map(str, args)]) == 2
    errors = [line for line in capsys.readouterr().err.splitlines() if line.startswith("error:")]
    assert len(errors) == 1, errors
    return errors[0]


def test_unmatched_forward_strides_beside_a_turn_say_no_stride_matched(made, capsys):
    line = _error(capsys, made / "bundle", made / "coarse")
    assert "direction: no runtime stride matched a labelled direction" in line and "every labelled" not in line


def test_side_steps_only_still_say_every_labelled_step(made, capsys):
    assert "direction: every labelled step is a side / turn stride" in _error(capsys, made / "bundle", made / "side")
