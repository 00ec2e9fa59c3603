"""Decision S101 (forty-sixth session, trial T1 finding F9): a stair flight's own pace (``up:N[...]:PACE``,
``slow`` / ``normal`` / ``fast`` or ``pace=F``) and ics.csv's per-step ``height_m`` on a step-to-step session."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Stairs, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:3, up:4:0.17:0.28:step-to-step:left{pace}, stand:2"


def test_stair_pace_parses_in_the_grammars_style():
    assert parse_route("up:12:slow") == [Stairs(12, pace="slow")]
    assert parse_route("down:3:0.17:0.28:step-to-step:right:pace=1.5") == [
        Stairs(3, up=False, step_to_step=True, lead="right", pace=1.5)]
    assert parse_route("up:2:0.17:0.28:fast") == [Stairs(2, pace="fast")]
    assert parse_route("up:5:step-to-step") == [Stairs(5, step_to_step=True)]  # no pace: the session's


@pytest.mark.parametrize("spec, message", [
    ("up:3:pace=9", r"within 0.5-4"), ("up:3:pace=x", r"not 'x'"), ("up:3:run", r"options after N"),
    ("up:3:step-to-step:slow:left", r"then a pace"), ("up:3:pace=nan", r"step-time factor"),
])
def test_bad_stair_pace_is_one_line(spec, message):
    with pytest.raises(DataError, match=message) as err:
        parse_route(spec)
    assert "\n" not in str(err.value)


def test_python_stairs_pace_is_checked_by_the_planner():
    with pytest.raises(DataError, match="decision S101"):
        simulate_path([Stairs(3, pace=0.1)], UserProfile.from_seed(3), rate_hz=20.0, seed=0)


def _stair_ics(pace: str) -> np.ndarray:
    s = simulate_path(parse_route(ROUTE.format(pace=pace)), UserProfile.from_seed(14301), rate_hz=20.0, seed=1)
    ics = s.extras["ics"]
    return ics[ics["kind"] == "stairs_up"]["ic_s"].to_numpy(float)


def test_a_numeric_pace_scales_the_stair_steps_time():
    plain, slow = np.diff(_stair_ics("")), np.diff(_stair_ics(":pace=2"))
    assert len(plain) == len(slow) == 7
    assert np.median(slow) / np.median(plain) == pytest.approx(2.0, rel=0.05)
    word = np.diff(_stair_ics(":slow"))  # S88's slow: 1.2 x the step time
    assert np.median(word) / np.median(plain) == pytest.approx(1.2, rel=0.05)


def test_ics_height_m_on_a_step_to_session():
    s = simulate_path(parse_route("straight:2, up:3:0.17:0.28:step-to-step:left, turn:180, "
                                  "down:3:0.15:0.28:step-to-step:right"), UserProfile.from_seed(7), seed=0)
    ics = s.extras["ics"]
    up, down = ics[ics["kind"] == "stairs_up"], ics[ics["kind"] == "stairs_down"]
    assert up["height_m"].tolist() == [0.17, 0.0] * 3  # the lead (left) foot rises a stair, the trail joins it
    assert up["foot"].tolist() == ["left", "right"] * 3
    assert down["height_m"].tolist() == [-0.15, 0.0] * 3
    assert (ics.loc[ics["kind"].isin(["walk", "turn", "close"]), "height_m"] == 0).all()


def test_no_height_column_without_a_step_to_flight():
    s = simulate_path(parse_route("straight:2, up:3"), UserProfile.from_seed(7), seed=0)
    assert "height_m" not in s.extras["ics"]  # sessions without a step-to flight keep their bytes
