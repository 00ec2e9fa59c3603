"""Decision L134 (docs/decisions/localization.md): a live tracker restarted where another stood.

A new-user trial (session 22, "integrator") followed docs/deploying.md's recipe, a new ``Tracker`` with the old one's
``start=position`` and ``heading_rad=heading``, at 30 s of a 90 m walk with no sample lost: the stride in progress was
lost with its turn (-0.72 rad on every later stride, 6.45 m off at the end). ``Tracker(bundle,
resume=old.restart_state())`` goes on with the samples the old tracker buffered and gives the uninterrupted track.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import synthetic_session, time_chunks

CHUNK_S = 0.5


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(40, seed=11, name="walk", turn_rad_per_step=0.3)


def _run(bundle, walk, restart_at=None, restart=None) -> list:
    tr, out = Tracker(bundle), []
    for t0, c in time_chunks(walk, CHUNK_S):
        if restart_at is not None and abs(t0 - restart_at) < 1e-9:
            tr = restart(tr)
        out += tr.push(c)
    return out + tr.flush()


@pytest.mark.parametrize("at", [3.0, 7.0, 15.5, 22.5, 31.0])
def test_a_tracker_resumed_from_a_restart_state_gives_the_uninterrupted_track(synthetic_bundle, walk, at):
    b = synthetic_bundle
    ref = _run(b, walk)
    got = _run(b, walk, at, lambda old: Tracker(b, resume=json.loads(json.dumps(old.restart_state()))))
    assert len(ref) >= 35 and len(got) == len(ref)
    for a, r in zip(got, ref, strict=True):
        assert (a.start_s, a.end_s, a.classes) == (r.start_s, r.end_s, r.classes)
        assert np.allclose([a.length_m, a.dz_m, a.heading_rad, a.x, a.y, a.z],
                           [r.length_m, r.dz_m, r.heading_rad, r.x, r.y, r.z], rtol=0, atol=1e-9)


def test_the_old_recipe_loses_the_stride_in_progress(synthetic_bundle, walk):
    """What the trial found, on this walk: position and heading alone drop the stride in progress."""
    b = synthetic_bundle
    ref = _run(b, walk)
    held = []

    def restart(old):
        held.append(len(old._loops.held))  # decision E280: strides held for L611's verdict are lost with it too
        return Tracker(b, start=tuple(old.position), heading_rad=old.heading)

    got = _run(b, walk, 22.5, restart)
    # the stride in progress and the next (opened at the stance after the restart), and those held (E280)
    assert len(got) == len(ref) - 2 - held[0]
    assert np.hypot(got[-1].x - ref[-1].x, got[-1].y - ref[-1].y) > 0.3


def test_a_bad_restart_state_is_one_line(synthetic_bundle):
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): not a restart state of version 3 .*restart_state"):
        Tracker(synthetic_bundle, resume={"position": [0, 0, 0]})
    state = Tracker(synthetic_bundle).restart_state()
    state["heading_rad"] = float("nan")
    with pytest.raises(DataError, match="not finite"):
        Tracker(synthetic_bundle, resume=state)


def test_a_resampling_tracker_refuses_a_restart_state(synthetic_bundle):
    """Decision L140: a tracker resampling 50 Hz input to the bundle's 20 Hz cannot hand on its filter's last raw
    samples; its resampled buffer re-pushed into a new resampling tracker lost a stride (0.20-0.28 m off), so
    restart_state() refuses in one line naming the start=/heading_rad= restart."""
    walk50 = synthetic_session(12, seed=3, name="walk50", rate_hz=50.0)
    tr = Tracker(synthetic_bundle, resample=True)
    for _, c in list(time_chunks(walk50, CHUNK_S))[:12]:
        tr.push(c)
    assert tr.resampled_hz
    with pytest.raises(DataError, match=r"^restart_state\(\): this tracker resamples .*start=tuple.*L140"):
        tr.restart_state()
