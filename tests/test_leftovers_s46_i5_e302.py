"""Decision E302 (session 46, I5): the Reorderer tells a restarted pod clock itself (samples set aside as late in 3
pushes or more, none in place between, spanning more than ``hold_s``), says so in one warning line per sensor, and
keeps the new clock's samples instead of dropping them as ``late``; the Tracker's ClockWentBack (E227) then gives
the rebase."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import ClockWentBack, DataError
from pdrlearn.runtime import CounterUnwrapper, Reorderer, Tracker
from tests.ble_packets import START_MS, U32, packets
from tests.test_ble_stream_s45_e296 import walk  # noqa: F401  (the module fixture: T2's walk, user 12820)


def _push_packets(ro, t0, n, dt=0.05, k=20, name="fAccelerometer", v0=0.0):
    out = []
    for i in range(n):
        t = t0 + (i * k + np.arange(k)) * dt
        got = ro.push({name: (t, np.column_stack([t, t, t]) + v0)})
        out.append(got.get(name, (np.empty(0), None))[0])
    return np.concatenate(out)


def test_a_restarted_clock_is_told_warned_once_and_kept_e302(caplog):
    ro = Reorderer(1.2)
    old = _push_packets(ro, 0.0, 10)  # 0-9.95 s, the old clock
    with caplog.at_level(logging.WARNING, logger="pdrlearn.runtime.ble"):
        # the pod restarted: its clock from 0 again, the gateway not told; it reads other values at the old times
        # (the same values would be a packet sent again, decision E306)
        new = _push_packets(ro, 0.0, 5, v0=100.0)
    lines = [r.getMessage() for r in caplog.records]
    assert len(lines) == 1 and "fAccelerometer's clock went back from 9.950 s to 0.000 s" in lines[0]
    assert "restarted pod (decision E302)" in lines[0]
    assert ro.restarts == {"fAccelerometer": 1} and ro.late == {}
    rest = ro.flush()["fAccelerometer"][0]
    # every old sample once (those held released with the third push after the restart), then all 100 new ones
    np.testing.assert_allclose(np.concatenate([old, new, rest]), np.r_[np.arange(200), np.arange(100)] * 0.05)


def test_overtaken_packets_are_still_late_not_a_restart_e302():
    """One or two overtaken packets span more than a short hold too (the trial's 20-sample packets: 0.95 s against
    hold_s 0.5): counted late, as before E302."""
    ro = Reorderer(0.5)
    _push_packets(ro, 0.0, 10)
    for _ in range(2):  # two late packets in a row, then one in place
        ro.push({"fAccelerometer": (np.arange(20) * 0.05 + 3.0, np.zeros((20, 3)))})
    ro.push({"fAccelerometer": ([10.0], np.zeros((1, 3)))})
    assert ro.restarts == {} and ro.late == {"fAccelerometer": 40}  # each copy late, as before E302
    ro2 = Reorderer(0.5)  # the same late packets pushed thrice with the in-place one between: never a restart
    _push_packets(ro2, 0.0, 10)
    for i in range(3):
        ro2.push({"fAccelerometer": (np.arange(20) * 0.05 + 2.0 + i, np.zeros((20, 3)))})
        ro2.push({"fAccelerometer": ([10.0 + i], np.zeros((1, 3)))})
    assert ro2.restarts == {} and ro2.late == {"fAccelerometer": 60}


def _restarted(pk, at_s):
    """The foot pod's uint32 ms counter from 0 again from its first packet at or after ``at_s`` (session time)."""
    for p in pk:
        if p["unit"] == "f":
            t_ms = (p["counter"].astype(np.int64) - START_MS["f"]) % U32
            if t_ms[0] >= at_s * 1000:
                p = dict(p, counter=((t_ms - int(at_s * 1000)) % U32).astype(np.uint32))
        yield p


def _gateway(bundle, pk):
    """E296's gateway, following the Tracker's ClockWentBack by its rebase (E227)."""
    tr, steps = Tracker(bundle), []
    unw = {u: CounterUnwrapper(bits=32, tick_s=1e-3) for u in "fw"}
    ro, rebases = Reorderer(hold_s=1.2), 0

    def push(chunk):
        nonlocal rebases
        if chunk:
            try:
                steps.extend(tr.push(chunk))
            except ClockWentBack as e:
                rebases += 1
                for unit, off in e.offsets.items():
                    tr.rebase_clock(unit, off)
                steps.extend(tr.push(chunk))
            except DataError:
                pass

    for p in pk:
        ts = unw[p["unit"]](p["counter"]) - START_MS[p["unit"]] * 1e-3
        push(ro.push({n: (ts, v) for n, v in p["data"].items()}))
    push(ro.flush())
    steps += tr.flush()
    return sum(abs(s.length_m) for s in steps if not s.gap_s), ro, rebases


@pytest.mark.slow
def test_the_trials_walk_with_the_foot_pod_restarted_is_tracked_e302(walk, caplog):  # noqa: F811
    d, bundle = walk
    clean, _, _ = _gateway(bundle, packets(d, 0, faults=False))
    with caplog.at_level(logging.WARNING, logger="pdrlearn.runtime.ble"):
        dist, ro, rebases = _gateway(bundle, list(_restarted(packets(d, 0, loss=0.0), 25.0)))
    told = [r.getMessage() for r in caplog.records if r.name == "pdrlearn.runtime.ble"]
    assert sorted(ro.restarts) == ["fAccelerometer", "fForceA", "fForceB", "fGyroscope"] and len(told) == 4
    assert set(ro.restarts.values()) == {1} and ro.late == {} and rebases == 1
    assert dist == pytest.approx(clean, rel=0.02)  # 45.71 / 45.71 m printed (before E302: 33.44 m, 152 late each)
