"""Decision E211 (session 38, trial T5 finding 3): the foot runtime's ``Tracker`` (and so ``pdrlearn run``) names
each lift or escalator ride it does not count in z, as the stride after it is reported. Simulated user 9760 on the
trial's route with a +6 m lift ride; a level walk with a long stand names none."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def _live(route: str, user: int):
    s = simulate_path(parse_route(route), UserProfile.from_seed(user), seed=user, scenario="route")
    tr = Tracker(load_bundle(SHIPPED))
    data = {n: (st.t, st.values) for n, st in s.streams.items() if n in tr.used_sensors}
    t_end = max(t[-1] for t, _ in data.values())
    steps = []
    for lo in np.arange(0.0, t_end + 1.0, 1.0):  # 1 s chunks, as an app pushes them
        chunk = {n: (t[(t >= lo) & (t < lo + 1.0)], v[(t >= lo) & (t < lo + 1.0)]) for n, (t, v) in data.items()}
        steps += tr.push({n: c for n, c in chunk.items() if len(c[0])})
    return tr, steps + tr.flush()


def test_a_lift_ride_is_named_live_e211():
    tr, steps = _live("stand:3, straight:10, lift:+6, straight:5, stand:3", 9760)
    lines = [w for w in tr.warnings if "decision E211" in w]
    assert len(lines) == 1, tr.warnings
    # the line carries the ride (RideWatch keeps no list of them since session 39: it was read by no code)
    m = re.search(r"changed ([+-][0-9.]+) m while the wearer stood from ([0-9.]+) to ([0-9.]+) s", lines[0])
    dz, a, b = (float(g) for g in m.groups())
    assert 4.5 < dz < 7.5, lines[0]
    assert any(st.end_s <= a for st in steps) and any(st.start_s >= b for st in steps)


def test_a_level_walk_with_a_stand_names_no_ride_e211():
    tr, _ = _live("stand:3, straight:10, stand:40, straight:10, stand:3", 9761)
    assert not [w for w in tr.warnings if "E211" in w], tr.warnings
