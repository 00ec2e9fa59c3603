"""Simulator: a ramp walked with level steps, route item `slope:M:PCT` (decision S37)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Slope, UserProfile, simulate_path
from pdrlearn.sim.path import plan_footsteps
from pdrlearn.sim.route import parse_route


def test_slope_parses_with_a_signed_grade_and_a_gait():
    assert parse_route("slope:30:5, slope:20:-7.5:long") == [Slope(30.0, 0.05), Slope(20.0, -0.075, gait="long")]


@pytest.mark.parametrize(("spec", "message"), [("slope:30", "takes 2 or 3 or 4 value"), ("slope:-3:5", "positive"),
                                               # decision S121: a slope takes a gait or a pace, as straight (S88)
                                               ("slope:30:5:brisk", "'brisk' must be a gait"),
                                               ("slope:30:5:short:brisk", "pace 'brisk' must be one of")])
def test_a_bad_slope_item_is_one_line(spec, message):
    with pytest.raises(DataError, match=message):
        parse_route(spec)


def test_a_too_steep_slope_is_refused():
    with pytest.raises(DataError, match="grade must be finite and within"):
        plan_footsteps([Slope(10.0, 0.5)], UserProfile.from_seed(1), rng=np.random.default_rng(0))


def test_a_ramp_rises_its_grade_with_level_walking_steps():
    s = simulate_path(parse_route("straight:3, slope:30:5, straight:3, slope:30:-10"), UserProfile.from_seed(1060),
                      seed=3, noise=False)
    z = s.extras["foot_trajectory"]["z"].to_numpy(float)
    steps = plan_footsteps(parse_route("slope:30:5"), UserProfile.from_seed(1060), rng=np.random.default_rng(3))[0]
    assert {st.kind for st in steps} <= {"walk", "close"}  # level-walking steps, no stair kinematics
    heel = np.array([st.heel for st in steps])
    assert heel[:, 2].max() == pytest.approx(1.5)  # 5 % of 30 m
    assert np.allclose(heel[:, 2], 0.05 * heel[:, 0])  # every footprint on the ramp
    assert z[-1] - z[0] == pytest.approx(1.5 - 3.0, abs=0.02)  # then 10 % down over 30 m
    heights = s.steps["height_m"].to_numpy(float)
    assert heights.sum() == pytest.approx(-1.5, abs=0.02)
    assert set(s.steps["terrain"]) >= {"flat", "down"}  # S3: a 5 % stride is flat, a 10 % one down
