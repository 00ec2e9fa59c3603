"""Decision D35 (session 39): D31's innovation gate can be switched on from the live ``Tracker``
(``Tracker(bundle, innovation_gate=True)``; off by default as ``track --fixes``' gate, D33). Simulated user 9880."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def _walk_with_a_wrong_fix(**kw) -> Tracker:
    """A 20 m walk pushed in 1 s chunks; after 6 steps one fix 10 m beside the tracked position, accuracy 3 m
    (3.3 sigma from the truth, more from the filter's estimate: the trial's wrong beacon, D31)."""
    s = simulate_path(parse_route("stand:3, straight:20, stand:3"), UserProfile.from_seed(9880), seed=9880,
                      scenario="route")
    tr = Tracker(load_bundle(SHIPPED), **kw)
    data = {n: (st.t, st.values) for n, st in s.streams.items() if n in tr.used_sensors}
    t_end = max(t[-1] for t, _ in data.values())
    n, given = 0, False
    for lo in np.arange(0.0, t_end + 1.0, 1.0):
        chunk = {k: (t[(t >= lo) & (t < lo + 1.0)], v[(t >= lo) & (t < lo + 1.0)]) for k, (t, v) in data.items()}
        n += len(tr.push({k: c for k, c in chunk.items() if len(c[0])}))
        if n >= 6 and not given:
            x, y = tr.position[:2]
            tr.add_fix(lo + 1.5, float(x), float(y) + 10.0, accuracy_m=3.0)
            given = True
    tr.flush()
    assert given
    return tr


def test_the_live_tracker_can_gate_a_wrong_fix_d35():
    plain = _walk_with_a_wrong_fix()
    assert plain.fix_stats()["fixes_used"] == 1 and plain.fix_stats()["fixes_rejected"] == 0
    gated = _walk_with_a_wrong_fix(innovation_gate=True)
    st = gated.fix_stats()
    assert st["fixes_used"] == 0 and st["fixes_rejected"] == 1, st
    assert [w for w in gated.warnings if "decision D31" in w], gated.warnings
    # the rejected fix does not pull the track: the live position stays the PDR one (the plain one moved ~10 m)
    assert gated.fix_position is None and plain.fix_position is not None
    assert gated._fixes.cfg.innovation_gate and not plain._fixes.cfg.innovation_gate
    gated._init_fixes(gated.position[:2])  # a restart (L134) re-initialises the filter with the tracker's setting
    assert gated._fixes.cfg.innovation_gate


def test_innovation_gate_is_a_flag_d35():
    with pytest.raises(DataError, match="innovation_gate='yes' must be True or False"):
        Tracker(load_bundle(SHIPPED), innovation_gate="yes")
