"""Decision E370: a restart state carries E361's re-anchoring compass (its heading, axis and the last 60 s of offsets);
a state without it (saved before E370) starts the compass afresh. The whole-tracker
parity (a fused, bridged dropout split anywhere) is tests/test_export_s53_e356.py, which fails without E370."""

from __future__ import annotations

from pdrlearn.kernels.gap_compass import GapCompass


def test_the_compass_state_round_trips_as_a_copy_e370():
    g = GapCompass()
    g.heading, g.axis = 0.7, 2
    g.offsets.extend([(1.0, 0.1), (2.0, -0.2)])
    s = g.state()
    g.offsets.append((3.0, 0.3))  # a later stride must not reach the state taken before it
    assert s == {"heading": 0.7, "axis": 2, "offsets": [[1.0, 0.1], [2.0, -0.2]]}
    h = GapCompass()
    h.restore(s)
    assert (h.heading, h.axis, list(h.offsets)) == (0.7, 2, [(1.0, 0.1), (2.0, -0.2)])

