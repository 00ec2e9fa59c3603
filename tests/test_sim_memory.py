"""Decision S44: the simulator builds its 500 Hz poses in parts (`simulate._unit_motion`, `FINE_CHUNK`): the same
session to 1e-9 (relative) with any part size, and a traced peak well below the whole-grid version's."""

from __future__ import annotations

import importlib
import tracemalloc

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate, simulate_path
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
