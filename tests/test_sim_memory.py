"""Decision S44: the simulator builds its 500 Hz poses in parts (`simulate._unit_motion`, `FINE_CHUNK`): the same
session to 1e-9 (relative) with any part size, and a traced peak well below the whole-grid version's."""

from __future__ import annotations

import importlib
import tracemalloc

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.kernels import euler_zyx
from pdrlearn.sim.route import parse_route

sim_module = importlib.import_module("pdrlearn.sim.simulate")


def _arrays(s) -> dict[str, np.ndarray]:
    out = {f"{k}.t": v.t for k, v in s.streams.items()} | {k: v.values for k, v in s.streams.items()}
    for name, df in (("trajectory", s.trajectory), ("steps", s.steps), ("foot", s.extras["foot_trajectory"])):
        out |= {f"{name}.{c}": df[c].to_numpy(float) for c in df.columns if df[c].dtype.kind in "fi"}
    return out


@pytest.mark.parametrize("options", [{}, {"pelvis": "realistic", "bounce": "pendulum", "rocker": "smooth",
                                          "sit_start_s": 3.0, "sit_end_s": 2.0, "step_length_asymmetry": 0.2}])
def test_parts_give_the_whole_grid_session(monkeypatch, options):
    """User 2841, a 70 s route with a sit and stairs: parts of 1003 samples (a 500 Hz block boundary every 2 s, not a
    multiple of the 5-sample blocks: rounded down to 1000) against one part holding the whole grid."""
    route = parse_route("stand:2, straight:12, sit:4, up:6, turn:90, down:6, curve:90:2, stand:2")
    u = UserProfile.from_seed(2841)
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 10**9)
    whole = _arrays(simulate_path(route, u, rate_hz=100.0, seed=5, scenario="route", **options))
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 1003)
    parts = _arrays(simulate_path(route, u, rate_hz=100.0, seed=5, scenario="route", **options))
    assert whole.keys() == parts.keys()
    worst = max(float(np.max(np.abs(parts[k] - whole[k]) / np.maximum(np.abs(whole[k]), 1e-6))) for k in whole)
    print(f"largest relative difference over {len(whole)} arrays: {worst:.3g}")
    assert worst <= 1e-9


def test_traced_peak_of_a_long_walk():
    """A 306 s walk (user 2840): tracemalloc's peak was 103.8 MB with the whole 500 Hz grid (main before S44) and
    60.3 MB in parts (both measured in a fresh interpreter); bound 80 MB."""
    tracemalloc.start()
    try:
        s = simulate("walk", 2840, length_m=450.0)
        peak = tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()
    print(f"{s.duration_s:.0f} s walk: traced peak {peak:.1f} MB")
    assert s.duration_s > 300 and peak < 80.0


def test_s62_grid_parts_and_output_rate_poses_are_the_whole_arrays():
    """Decision S62: the 500 Hz grid made per part is the whole array's values (bit for bit), its block means too,
    and `_unit_motion(pose_every=k)` keeps exactly the whole run's poses at the middle of each output block, for part
    sizes that do and do not line up with the output blocks."""
    n, k_fine = 25 * 4003, 25
    whole = (np.arange(n) - 0.5 * (k_fine - 1)) / 500.0
    grid = sim_module._FineGrid(n, 0.5 * (k_fine - 1), 500.0)
    assert np.array_equal(grid[0:n], whole) and np.array_equal(grid[137:9001], whole[137:9001])
    assert grid[0] == whole[0] and grid[-1] == whole[-1] and grid.size == n
    assert np.array_equal(grid.block_means(5, chunk=997), sim_module.block_mean(whole, 5))

    def pose(tt):
        rot = euler_zyx(0.1 * tt, 0.2 * np.cos(0.7 * tt), 0.3 * np.sin(tt))  # pointwise in time, as the poses
        return np.column_stack([np.sin(tt), tt, np.cos(tt)]), rot

    every = sim_module._unit_motion(grid, pose, 1 / 500.0, chunk=10**9)
    for chunk in (1003, 2500, 60_000):
        for k in (1, 2, 5):
            f, w, p, r = sim_module._unit_motion(grid, pose, 1 / 500.0, chunk=chunk, pose_every=k)
            assert np.array_equal(p, every[2][k // 2 :: k]) and np.array_equal(r, every[3][k // 2 :: k])
            assert f.shape == every[0].shape and w.shape == every[1].shape


def test_s62_outputs_stay_the_pinned_numbers():
    """Decision S62 keeps every output: a 20 Hz session of user 5970 with a sit, stairs and a freeze, summed per
    stream (the sums printed by main before S62, commit 4bea4b83)."""
    route = parse_route("stand:2, straight:6, sit:30, up:4, freeze:2, turn:90, straight:4, stand:2")
    s = simulate_path(route, UserProfile.from_seed(5970), rate_hz=20.0, seed=2, scenario="route")
    sums = {k: float(np.sum(v.values)) for k, v in s.streams.items()}
    sums["foot_trajectory"] = float(s.extras["foot_trajectory"][["x", "y", "z", "qw"]].to_numpy().sum())
    print({k: repr(v) for k, v in sums.items()})
    assert sums == PINNED_S62


#: main's sums (commit 4bea4b83, before S62) for the session of `test_s62_outputs_stay_the_pinned_numbers`
PINNED_S62 = {"fAccelerometer": 13254.107062500001, "fGyroscope": 82.9036979750913, "fForceA": 164407.86177412706,
              "fForceB": 185063.1438538178, "wAccelerometer": 13716.436809761344, "wGyroscope": 37.22564709730392,
              "wMagneticField": -12267.629999999997, "wBarometer": 1364848.6752, "foot_trajectory": 9708.026736948328}
