"""Decision E255 (docs/decisions/export.md): E242's late-pod offset reads the other unit's newest including the push
the joining pod's first packet comes in.

Review R1 of session 41, finding 5: a phone that gathers both pods' packets of a 0.2 s slice into one push, after the
foot connected alone, had the waist's newest read against the foot's newest from before that push: -7.80 for a waist
8 s behind (-8.00 before E242). Simulated user 11610.
"""

from __future__ import annotations

import pytest

from pdrlearn.runtime import Tracker, links, load_bundle
from tests.test_runtime_clock_s40 import BUNDLE, _packets, _run, pods_walk
from tests.test_runtime_clocks_s41 import _by_slice


def test_a_push_of_both_units_after_one_joined_alone_reads_the_newest_of_that_push_e255():
    c = links.StartClocks(2.0)
    for k in range(15):
        c.seen({"fGyroscope": (0.2 * k, 0.2 * k + 0.15)})  # the foot alone, 0.00-2.95 s
    c.seen({"fGyroscope": (3.0, 3.15), "wGyroscope": (-5.0, -4.85)})  # the waist (8 s behind) joins at 3.0 s
    assert c.contact == pytest.approx(-8.0) and c.offset == pytest.approx(-8.0)  # before E255: -7.8
    line = c.note("wGyroscope", 0.0)
    assert "the waist's newest sample at -4.85 s when the foot's newest was 3.15 s" in line
    assert "waist_clock_offset_s=-8.00)" in line
    c = links.StartClocks(2.0)  # mirrored: the foot joins the waist in a push of both
    for k in range(15):
        c.seen({"wGyroscope": (0.2 * k, 0.2 * k + 0.15)})
    c.seen({"wGyroscope": (3.0, 3.15), "fGyroscope": (-5.0, -4.85)})
    assert c.contact == pytest.approx(8.0) and c.offset == pytest.approx(8.0)
    assert "the foot's newest sample at -4.85 s when the waist's newest was 3.15 s" in c.note("fGyroscope", 0.0)


@pytest.mark.parametrize("join_s", [3.0, 3.1])
def test_a_tracker_fed_both_pods_per_slice_names_a_late_pod_exactly_e255(join_s):
    walk = pods_walk(11610)
    packets = [p for p in _packets(walk, waist=lambda t: t - 8.0) if not (p[0] == "waist" and p[1] < join_s)]
    tr = Tracker(load_bundle(BUNDLE))
    _, errors = _run(tr, [(None, None, d) for d in _by_slice(packets)])
    said = [m for m in [*map(str, errors), *tr.warnings] if "decisions E223, E238" in m]
    assert said and all("waist_clock_offset_s=-8.00)" in m and "about 8.0 s behind" in m for m in said)
    assert tr._starts.offset == pytest.approx(-8.0, abs=1e-9)
