"""Decision E257 (session 42, implementer I3): docs/deploying.md's thread recipe, deciding a pod that reconnected with
its clock restarted while the other pod was silent, places its first new sample its held span before the other's
newest at the decision (a restarted pod streamed that span in real time) and rebases it then, so its new packets go
in time order with the other's. Before, it was put beside the other's last sample before the silence (1.049 s early
for a waist back at 15 s, the foot silent 14-15.5 s). While the other streamed, E247's placement stays (a packet
late, -0.201 s: the limit in docs/deploying.md). The recipe is run as written in the docs, packets in arrival order.
Simulated user 11786 (the 27 m pods walk)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.runtime import Tracker, load_bundle
from tests.test_runtime_clock_s40 import _packets, _run, pods_walk
from tests.test_runtime_recipe_s41_e247 import in_arrival_order
from tests.test_runtime_threads_queue import _example

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
AT = 15.0  # the waist gone AT - 1 .. AT s, back with its clock restarted at 0


@pytest.fixture(scope="module")
def setup():
    return load_bundle(BUNDLE), pods_walk(11786)


def _gaps(walk, silent):
    """The walk's packets without the waist's last second before AT and the foot's ``silent`` s from AT - 1."""
    return [(u, a, d) for u, a, d in _packets(walk)
            if not (u == "waist" and AT - 1.0 <= a < AT) and not (u == "foot" and AT - 1.0 <= a < AT - 1.0 + silent)]


@pytest.mark.parametrize("silent", [1.5, 2.0])
def test_a_pod_restarted_while_the_other_was_silent_is_placed_where_it_restarted_e257(setup, silent):
    """The foot silent 14-15.5 s or 14-16 s while the waist restarts at 15 s: the waist's new clock is rebased by the
    truth's -15.000 s (before: -13.951 s, beside the foot's 13.95 s), and the steps are those of the same packets on
    one clock (no restart), pushed packet by packet (before: 3.01 / 2.90 m off at the end on user 11784)."""
    bundle, walk = setup
    packets = [(u, a, {n: (t - AT, v) for n, (t, v) in d.items()} if (a >= AT and u == "waist") else d)
               for u, a, d in _gaps(walk, silent)]
    ref, errors = _run(Tracker(bundle), _gaps(walk, silent))
    late, refused, tr = {}, [], Tracker(bundle)
    got = _example()["track_from_units"](tr, in_arrival_order(packets), late=late, refused=refused)
    assert errors == [] and refused == [] and late == {}
    assert tr.waist_clock_offset_s == pytest.approx(-AT, abs=1e-6) and tr.foot_clock_offset_s == 0.0
    assert len(got) == len(ref) > 15
    np.testing.assert_allclose([(s.end_s, s.x, s.y) for s in got], [(s.end_s, s.x, s.y) for s in ref], atol=1e-6)


def test_a_pod_restarted_while_the_other_streamed_keeps_e247s_placement_a_packet_late_e257(setup):
    """The limit left: with the foot streaming, the waist's first new packet arrives after the foot's packet of the same
    slice and is put beside its newest (E247 / E227's loop): -15.201 s, a 0.2 s packet late."""
    bundle, walk = setup
    packets = [(u, a, {n: (t - AT, v) for n, (t, v) in d.items()} if (a >= AT and u == "waist") else d)
               for u, a, d in _gaps(walk, 0.0)]
    tr = Tracker(bundle)
    _example()["track_from_units"](tr, in_arrival_order(packets))
    assert tr.waist_clock_offset_s == pytest.approx(-AT - 0.201, abs=0.002)
