"""Decision E247 (docs/decisions/export.md): docs/deploying.md's thread recipe rebases a pod that reconnected with its
clock restarted, as E227's per-push loop does, and still drops a packet sent again long after as late.

Review R0 of session 40, finding 1: the recipe dropped every sample at or before its sensor's last pushed time as
"late", so a restarted pod's samples never reached the tracker until its new clock passed the old one, ClockWentBack
was never raised and the waist's 90 deg turn was lost (final position ~15.6 m off). The recipe is run as written in
the docs (``_example``). Simulated users 11392-11393.
"""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import ClockWentBack
from pdrlearn.runtime import Tracker, load_bundle
from tests.test_runtime_clock_s40 import _packets, _reconnected, _run, _same, _xy, pods_walk
from tests.test_runtime_threads_queue import _example

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


def in_arrival_order(packets) -> dict:
    """unit -> the chunks its thread hands over, each handed over only after every earlier packet of ``packets`` (as
    a real-time link delivers them; an unpaced replay lets one thread run seconds ahead of the other)."""
    turn, cond = [0], threading.Condition()

    def chunks(unit):
        for i, (u, _, data) in enumerate(packets):
            if u != unit:
                continue
            with cond:
                assert cond.wait_for(lambda i=i: turn[0] == i, timeout=60), "the other unit's thread stopped"
            yield data  # put on the queue before this generator runs on
            with cond:
                turn[0] = i + 1
                cond.notify_all()

    return {u: chunks(u) for u in dict.fromkeys(u for u, _, _ in packets)}


@pytest.mark.parametrize(("unit", "user"), [("waist", 11392), ("foot", 11393)])
def test_the_thread_recipe_rebases_a_pod_that_reconnected_with_its_clock_restarted_e247(bundle, unit, user):
    walk = pods_walk(user)
    clean, errors = _run(Tracker(bundle), _packets(walk))
    assert errors == []
    packets = _reconnected(walk, unit)  # the pod gone 14-15 s, its clock restarted at 0 at 15 s
    ref_tracker = Tracker(bundle)
    ref, errors = _run(ref_tracker, packets, rebase=True)  # E227's loop, packet by packet
    assert len(errors) == 1 and isinstance(errors[0], ClockWentBack)
    late, refused = {}, []
    tr = Tracker(bundle)
    got = _example()["track_from_units"](tr, in_arrival_order(packets), late=late, refused=refused)
    assert late == {} and refused == []  # before E247: 280 samples per waist sensor "late", ClockWentBack never raised
    offset = getattr(tr, f"{unit}_clock_offset_s")
    assert offset == pytest.approx(getattr(ref_tracker, f"{unit}_clock_offset_s"), abs=1e-9)  # beside the same sample
    assert _same(got, ref), (len(got), len(ref), _xy(got)[-1], _xy(ref)[-1])
    off = float(np.hypot(*(_xy(got)[-1] - _xy(clean)[-1])))
    assert off < 4.0, off  # the 1 s gap (0.33 m waist, 3.07 m foot), not the turn lost (15.6 m before)


def test_a_packet_sent_again_long_after_is_still_late_when_its_old_clock_goes_on_e247(bundle):
    walk = pods_walk(11392)
    packets = _packets(walk)
    foot = [i for i, p in enumerate(packets) if p[0] == "foot"]
    resent = [*packets[:foot[60]], packets[foot[20]], *packets[foot[60]:]]  # 8 s late: more than max_lag_s
    late, refused = {}, []
    got = _example()["track_from_units"](Tracker(bundle), in_arrival_order(resent), late=late, refused=refused)
    ref, _ = _run(Tracker(bundle), packets)
    assert _same(got, ref) and refused == []
    assert late == {n: len(t) for n, (t, _) in packets[foot[20]][2].items()}
