"""Decision W344: the lower-back tracks' side-step (L219) and backward (W173) lines have a minimum stretch, and the
README says it (a vestibular clinic's trial: `side:-0.6, backward:2` gave no line and +75.73 % distance)."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.sideways import WARN_MIN_SIDE_STRIDES  # decision L487: the lines' own minimum
from pdrlearn.waist.backward import MIN_BACKWARD_STEPS

#: the README's simulator paragraph with the two minimum stretches moved to docs/simulator.md (session 36)
SIMULATOR_DOC = Path(__file__).resolve().parents[1] / "docs" / "simulator.md"


def test_readme_states_both_minimum_stretches_with_their_values():
    text = " ".join(SIMULATOR_DOC.read_text(encoding="utf-8").split())
    assert f"`WARN_MIN_SIDE_STRIDES` = {WARN_MIN_SIDE_STRIDES} consecutive sideways strides" in text
    assert f"`MIN_BACKWARD_STEPS` = {MIN_BACKWARD_STEPS} consecutive lower-back steps" in text
    assert "(W344)" in text


def _lines(route: str) -> list[str]:
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(route), UserProfile.from_seed(7389), rate_hz=20.0, seed=7389)
        return [w for w in get_pipeline("waist-pendulum")(s).info["warnings"] if "L219" in w or "W173" in w]
    finally:
        logging.disable(logging.NOTSET)


@pytest.mark.parametrize(("item", "n_lines"), [("side:-0.6", 0), ("side:-1.2", 1), ("backward:2", 0),
                                                ("backward:6", 1)])
def test_the_readme_examples_below_and_above_the_minimum(item, n_lines):
    # the README's figures for user 7389: 0.6 m sideways is 2 foot strides, 1.2 m 3; 2 backward steps 1 stride
    assert len(_lines(f"stand:3, straight:2, {item}, straight:2, stand:2")) == n_lines
