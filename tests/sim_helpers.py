"""Simulator test helpers (review R2, session 33): the whole 500 Hz grid and its parts of 1000 samples."""

from __future__ import annotations

import importlib

import numpy as np

from pdrlearn.sim import simulate_path


def whole_and_parts(monkeypatch, route, user, rate_hz: float, seed: int):
    """Decision S44: the session of ``route`` simulated on the whole fine grid at once and in parts of 1000 samples
    (``FINE_CHUNK``), after checking that every stream is the same in both; ``(whole, parts)``."""
    sim_module = importlib.import_module("pdrlearn.sim.simulate")
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 10**9)
    whole = simulate_path(route, user, rate_hz=rate_hz, seed=seed)
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 1000)
    parts = simulate_path(route, user, rate_hz=rate_hz, seed=seed)
    for k in whole.streams:
        assert np.array_equal(whole.streams[k].values, parts.streams[k].values), k
    return whole, parts
