"""Decision S106: ``spin:DEG:SECONDS``, a stepless turn on the spot on the planted tracked foot."""

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Spin, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def _spin_walk(route: str, **knobs):
    return simulate_path(parse_route(route), UserProfile.from_seed(14740), seed=0, rate_hz=100, noise=False,
                         name="spin", **knobs)


@pytest.mark.parametrize("foot", ["right", "left"])
def test_spin_turns_the_truth_heading_on_a_planted_foot(foot):
    s = _spin_walk("stand:2, straight:4, spin:-150:8, straight:4", instrumented_foot=foot)
    row = s.extras["spins"].iloc[0]
    assert row["angle_deg"] == pytest.approx(-150.0)
    assert row["end_s"] - row["start_s"] == pytest.approx(8.0)
    tr, ft = s.trajectory, s.extras["foot_trajectory"]
    h = np.unwrap(tr["heading_rad"].to_numpy())
    i0, i1 = np.searchsorted(tr["t"], [row["start_s"] - 0.3, row["end_s"] + 0.3])
    assert math.degrees(h[i1] - h[i0]) == pytest.approx(-150.0, abs=0.5)  # the lower back yaws with the body
    on = ((ft["t_s"] >= row["start_s"] - 0.3) & (ft["t_s"] <= row["end_s"] + 0.3)).to_numpy()
    xyz = ft[["x", "y", "z"]].to_numpy()[on]
    assert np.abs(xyz - xyz[0]).max() < 0.003  # the tracked foot stays planted (within 3 mm)
    q = ft[["qw", "qx", "qy", "qz"]].to_numpy()[on]
    yaw = np.unwrap(np.arctan2(2 * (q[:, 0] * q[:, 3] + q[:, 1] * q[:, 2]), 1 - 2 * (q[:, 2] ** 2 + q[:, 3] ** 2)))
    assert math.degrees(yaw[-1] - yaw[0]) == pytest.approx(-150.0, abs=0.5)  # ... and rotates with the body
    # no stride of the tracked foot inside the spin; the walk after it heads -150 deg from the one before
    st = s.steps
    assert not ((st["start_s"] < row["end_s"]) & (st["end_s"] > row["start_s"])).any()
    end = ft[["x", "y"]].to_numpy()
    before = end[np.searchsorted(ft["t_s"], row["start_s"])] - end[0]
    after = end[-1] - end[np.searchsorted(ft["t_s"], row["end_s"])]
    turn = math.degrees(math.atan2(after[1], after[0]) - math.atan2(before[1], before[0]))
    assert (turn + 180) % 360 - 180 == pytest.approx(-150.0, abs=3.0)


def test_a_spin_is_turned_by_an_earlier_one_and_a_walk_without_spin_has_no_table():
    s = _spin_walk("stand:2, straight:3, spin:90:4, straight:3, spin:90:4, straight:3")
    assert list(s.extras["spins"]["angle_deg"]) == [90.0, 90.0]
    ft = s.extras["foot_trajectory"]
    d = ft[["x", "y"]].to_numpy()[-1] - ft[["x", "y"]].to_numpy()[np.searchsorted(ft["t_s"],
                                                                                  s.extras["spins"]["end_s"][1])]
    assert abs(math.degrees(math.atan2(d[1], d[0])) % 360 - 180) < 3  # two left quarter turns: walking west
    assert "spins" not in _spin_walk("stand:2, straight:3").extras


@pytest.mark.parametrize("item, words", [
    ("spin:0:10", "non-zero angle"),
    ("spin:400:10", "at most 360"),
    ("spin:180", "takes 2 value"),
    ("spin:180:0.5", "lasts 1-120 s"),
    ("spin:180:200", "lasts 1-120 s"),
    ("spin:360:1", "peaks at 675 deg/s"),
    ("spin:90:x", "not a number"),
])
def test_spin_route_errors_name_the_item(item, words):
    with pytest.raises(DataError) as e:
        parse_route(f"straight:3, {item}")
    assert f"'{item}'" in str(e.value) and words in str(e.value)
    assert "\n" not in str(e.value)


def test_spin_segment_is_checked_by_the_planner_too():
    with pytest.raises(DataError, match="a spin lasts"):
        simulate_path([Spin(math.radians(90), 0.2)], UserProfile.from_seed(14741), noise=False)
