"""Decision S125: a long simulation's time is linear in its length - the pelvis's per-bout envelope, per-step kicks
and knots are worked out on the samples and once per session, not on every 2-min part for every bout and step of
the session (the 4 h nurses' shift took 961 s). The values are unchanged: byte-identical sessions (decision text)."""

from __future__ import annotations

import importlib

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

sim_module = importlib.import_module("pdrlearn.sim.simulate")
body = importlib.import_module("pdrlearn.sim.body")


def _work(monkeypatch, blocks: int) -> tuple[int, int]:
    """(samples passed to the pelvis's and feet's smoothstep, foot-centre evaluations) simulating ``blocks`` walks
    with a stop each, in parts of 1000 samples of the 500 Hz grid (2 s)."""
    seen = {"samples": 0, "centres": 0}
    smooth, centre = body.smoothstep, body._foot_centre

    def counted_smoothstep(u):
        seen["samples"] += np.size(u)
        return smooth(u)

    def counted_centre(*a):
        seen["centres"] += 1
        return centre(*a)

    monkeypatch.setattr(body, "smoothstep", counted_smoothstep)
    monkeypatch.setattr(body, "_foot_centre", counted_centre)
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 1000)
    route = parse_route(", ".join(["straight:3, stand:2"] * blocks))
    simulate_path(route, UserProfile.from_seed(18880), rate_hz=20.0, seed=1, scenario="route")
    return seen["samples"], seen["centres"]


def test_pelvis_work_grows_linearly_with_the_session(monkeypatch):
    """Twice the walks, about twice the work (before S125: ~4 times the envelope's samples, ~4 times the knots')."""
    s1, c1 = _work(monkeypatch, 4)
    s2, c2 = _work(monkeypatch, 8)
    print(f"smoothstep samples {s1} -> {s2} ({s2 / s1:.2f} x), foot centres {c1} -> {c2} ({c2 / c1:.2f} x)")
    assert s2 / s1 < 2.5 and c2 / c1 < 2.5
