"""Decisions E253, E254 (docs/decisions/export.md): docs/deploying.md's thread recipe (E247) takes a resent burst of
old packets for late, not for a restarted clock, and decides pods that restarted together in one push.

Review R1 of session 41, findings 2 and 3: a pod that sent 12 old packets (2.4 s, more than max_lag_s) again 8 s late
was rebased as a restart (10.24 m off, 6 refused pushes); when both pods restarted, the second was placed beside the
first's new samples max_lag_s later (waist - foot -2.151 s against E227's loop's -0.201 s). The recipe is run as
written in the docs (``_example``), its packets handed over in arrival order. Simulated users 11611-11613.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.errors import ClockWentBack
from pdrlearn.runtime import Tracker, load_bundle
from tests.test_runtime_clock_s40 import _packets, _run, _same, pods_walk
from tests.test_runtime_clocks_s41 import _restarted
from tests.test_runtime_recipe_s41_e247 import in_arrival_order
from tests.test_runtime_threads_queue import _example

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


def _resent(packets, n, unit="foot"):
    """``unit``'s packets 20..20+n sent again at once, just before its packet 60 (8 s late)."""
    mine = [i for i, p in enumerate(packets) if p[0] == unit]
    return [*packets[:mine[60]], *[packets[i] for i in mine[20:20 + n]], *packets[mine[60]:]]


def _late(packets, n, unit="foot"):
    mine = [p for p in packets if p[0] == unit][20:20 + n]
    return {name: sum(len(p[2][name][0]) for p in mine) for name in mine[0][2]}


def test_a_resent_burst_longer_than_max_lag_is_late_not_a_restart_e253(bundle):
    packets = _packets(pods_walk(11611))
    ref, _ = _run(Tracker(bundle), packets)
    late, refused, tr = {}, [], Tracker(bundle)
    got = _example()["track_from_units"](tr, in_arrival_order(_resent(packets, 12)), late=late, refused=refused)
    assert tr.foot_clock_offset_s == 0.0 and refused == []  # before E253: rebased -7.95 s, 6 refused pushes
    assert _same(got, ref) and late == _late(packets, 12)


def test_a_one_unit_tracker_counts_a_resent_burst_late_e253(bundle):
    packets = [p for p in _packets(pods_walk(11612)) if p[0] == "foot"]
    ref, _ = _run(Tracker(bundle, units=("foot",)), packets)
    late, refused, tr = {}, [], Tracker(bundle, units=("foot",))
    got = _example()["track_from_units"](tr, in_arrival_order(_resent(packets, 12)), late=late, refused=refused)
    assert tr.foot_clock_offset_s == 0.0 and refused == []  # no other unit to tell a restart by: late (E253)
    assert _same(got, ref) and late == _late(packets, 12)


def test_both_pods_restarted_are_placed_together_as_the_loop_places_them_e254(bundle):
    packets = _restarted(pods_walk(11613))  # both pods gone 14-15 s, back with their clocks restarted at 0
    loop = Tracker(bundle)  # E227 / E243's loop, packet by packet
    for _, _, data in packets:
        try:
            loop.push(data)
        except ClockWentBack as e:
            for unit, offset_s in e.offsets.items():
                loop.rebase_clock(unit, offset_s)
            loop.push(data)
    late, refused, tr = {}, [], Tracker(bundle)
    _example()["track_from_units"](tr, in_arrival_order(packets), late=late, refused=refused)
    assert late == {} and refused == []
    assert tr.foot_clock_offset_s == pytest.approx(loop.foot_clock_offset_s, abs=0.25)
    want = loop.waist_clock_offset_s - loop.foot_clock_offset_s  # -0.201: the waist's packet a slice after the foot's
    got = tr.waist_clock_offset_s - tr.foot_clock_offset_s  # before E254: -2.151 (the second pod max_lag_s late)
    assert got == pytest.approx(want, abs=0.25), (got, want)
