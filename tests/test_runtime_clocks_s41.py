"""Session 41 (implementer I3): leftovers of session 40's reviews of the live pod-clock code (decisions E242-E246).

Short simulated walks of users 11100-11119 cut into 0.2 s pod packets with tests/test_runtime_clock_s40.py's helpers.
"""

from __future__ import annotations

import pytest

from pdrlearn.runtime import Tracker, links, load_bundle
from tests.test_runtime_clock_s40 import BUNDLE, _packets, _run, pods_walk


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


@pytest.fixture(scope="module")
def walk():
    return pods_walk(11101)


# -- E242 ---------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("join_s", [3.0, 3.1])
def test_a_pod_that_connected_late_on_a_packet_boundary_is_named_exactly_e242(bundle, walk, join_s):
    """The waist 8 s behind and connected later: 3.0 s is a packet boundary (its first packet, 3.00-3.15 s, pushed
    after the foot's of the same slice), 3.1 s inside a packet (its first packet the next slice's). Before E242 the
    waist's first sample was read against the foot's newest: -8.15 / -8.20, a packet off."""
    packets = [p for p in _packets(walk, waist=lambda t: t - 8.0) if not (p[0] == "waist" and p[1] < join_s)]
    tr = Tracker(bundle)
    _, errors = _run(tr, packets)
    said = [m for m in [*map(str, errors), *tr.warnings] if "decisions E223, E238" in m]
    assert said and all("waist_clock_offset_s=-8.00)" in m and "about 8.0 s behind" in m for m in said)
    assert tr._starts.offset == pytest.approx(-8.0, abs=1e-9)


def test_a_late_pod_whose_first_push_is_a_held_back_burst_is_named_by_its_newest_sample_e242():
    """A waist pod that buffered 2 s before its first push: its newest sample is the one read at the foot's newest
    (before: its first, 2 s off)."""
    c = links.StartClocks(1.0)
    for k in range(20):
        c.seen({"fGyroscope": (0.2 * k, 0.2 * k + 0.15)})
    c.seen({"wGyroscope": (-8.0 + 1.8, -8.0 + 3.95)})  # the waist's samples of 1.80-3.95 s, 8 s behind
    assert c.contact == pytest.approx(-8.0) and c.offset == c.contact
    assert "the waist's newest sample at -4.05 s when the foot's newest was 3.95 s" in c.note("wGyroscope", 0.0)
    c = links.StartClocks(1.0)  # the foot joins the waist: the same rule, signs mirrored
    c.seen({"wGyroscope": (5.0, 5.15)})
    c.seen({"fGyroscope": (-0.6, 0.15)})
    assert c.contact == pytest.approx(5.0) and "the foot's newest sample at 0.15 s" in c.note("fGyroscope", 0.0)
