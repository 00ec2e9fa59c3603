"""Decisions S125 / S126: a long simulation's time is linear in its length - the pelvis's per-bout envelope, per-step
kicks and knots (S125), the feet's loads per stride and the magnetic disturbances per blob (S126) are worked out on
their own samples and once per session, not over the whole session for every bout, step, stride and blob (the 4 h
nurses' shift took 961 s). The values are unchanged: byte-identical sessions (decision texts)."""

from __future__ import annotations

import importlib

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

sim_module = importlib.import_module("pdrlearn.sim.simulate")
body = importlib.import_module("pdrlearn.sim.body")


sensors = importlib.import_module("pdrlearn.sim.sensors")


class _Counted(np.ndarray):
    """An array that counts the elements every ufunc over it reads (its results count on)."""

    seen: dict = {}

    def __array_ufunc__(self, ufunc, method, *inputs, **kw):
        _Counted.seen["ufunc"] = _Counted.seen.get("ufunc", 0) + max(np.size(x) for x in inputs)
        inputs = tuple(x.view(np.ndarray) if isinstance(x, _Counted) else x for x in inputs)
        if "out" in kw:
            kw["out"] = tuple(x.view(np.ndarray) if isinstance(x, _Counted) else x for x in kw["out"])
        res = getattr(ufunc, method)(*inputs, **kw)
        return res.view(_Counted) if isinstance(res, np.ndarray) and res.dtype != bool else res


def _work(monkeypatch, blocks: int) -> tuple[int, int, int]:
    """(samples passed to the pelvis's and feet's smoothstep, foot-centre evaluations, elements the feet's loads and
    the field disturbances read) simulating ``blocks`` walks with a stop each, in parts of 1000 samples of the
    500 Hz grid (2 s)."""
    seen = {"samples": 0, "centres": 0}
    _Counted.seen = {}
    smooth, centre = body.smoothstep, body._foot_centre
    loads, field = sim_module.foot_loads, sensors.field_disturbance

    def counted_smoothstep(u):
        seen["samples"] += np.size(u)
        return smooth(u)

    def counted_centre(*a):
        seen["centres"] += 1
        return centre(*a)

    monkeypatch.setattr(body, "smoothstep", counted_smoothstep)
    monkeypatch.setattr(sim_module, "foot_loads", lambda t, *a: loads(np.asarray(t).view(_Counted), *a))
    monkeypatch.setattr(sensors, "field_disturbance", lambda pos, *a: field(np.asarray(pos).view(_Counted), *a))
    monkeypatch.setattr(body, "_foot_centre", counted_centre)
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 1000)
    route = parse_route(", ".join(["straight:3, stand:2"] * blocks))
    simulate_path(route, UserProfile.from_seed(18880), rate_hz=20.0, seed=1, scenario="route")
    return seen["samples"], seen["centres"], _Counted.seen["ufunc"]


def test_pelvis_work_grows_linearly_with_the_session(monkeypatch):
    """Twice the walks, about twice the work (before S125: ~4 times the envelope's samples, ~4 times the knots')."""
    s1, c1, u1 = _work(monkeypatch, 3)
    s2, c2, u2 = _work(monkeypatch, 6)
    print(f"smoothstep samples {s1} -> {s2} ({s2 / s1:.2f} x), foot centres {c1} -> {c2} ({c2 / c1:.2f} x), loads' "
          f"and disturbances' elements {u1} -> {u2} ({u2 / u1:.2f} x)")
    assert s2 / s1 < 2.5 and c2 / c1 < 2.5 and u2 / u1 < 1.9  # S125 alone (quadratic loads): 1.97 x
