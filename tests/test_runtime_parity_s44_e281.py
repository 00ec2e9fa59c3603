"""Decision E281 (session 44, I1): a restart state (L134) carries E272's waist gyroscope bias read at the last stop.

Before E281 a tracker resumed from ``restart_state()`` started E272's bias at 0 (docs/decisions/export.md E272: "Not
carried"), so after a restart past a stop its waist-headed strides turned by the bias again (0.01 rad/s x the rest of
the walk). The walk is E272's test's: a clean simulated walk with a 25 s stand, and a bias step of 0.01 rad/s on the
waist's up axis from the stand on."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from tests.test_stop_bias_s43_e272 import BIAS_RPS, walks  # noqa: F401 (the shared walk fixture)

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def biased(walks):  # noqa: F811 (pytest passes the imported fixture)
    """E272's walk (user 12076, a 25 s stand), its waist gyro biased after the stand: test_stop_bias_s43_e272's
    fixture, shared."""
    _, session, stop_at = walks
    return session, stop_at

def _replay(session, restart_at: float | None = None, strip=None):
    """The steps of ``pdrlearn run``'s replay (1 s chunks); with ``restart_at`` a new Tracker resumed from the old
    one's JSON state (``strip``: that state made older) at the first chunk from then on."""
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.runtime.replay import read_streams, replay_chunks, session_frames

    bundle = load_bundle(SHIPPED)
    streams, meta = read_streams(session, bundle)
    kw = {"frames": session_frames(meta, bundle, bundle.body_units, "test"), "sensors": list(streams)}
    tr, out, restarted = Tracker(bundle, **kw), [], None
    for chunk in replay_chunks(streams, 1.0):
        t = min(float(c[0][0]) for c in chunk.values() if len(c[0])) if any(len(c[0]) for c in chunk.values()) \
            else None
        if restart_at is not None and restarted is None and t is not None and t >= restart_at:
            state = json.loads(json.dumps(tr.restart_state()))
            tr, restarted = Tracker(bundle, resume=strip(state) if strip else state, **kw), tr
        out += tr.push(chunk)
    return out + tr.flush(), tr, restarted


def test_a_restarted_tracker_keeps_the_stop_bias_e281(biased):
    session, stop_at = biased
    ref, tr_ref, _ = _replay(session)
    assert tr_ref._stop_bias.n_stops >= 1 and abs(tr_ref._stop_bias.rps - BIAS_RPS) < 0.002
    at = stop_at + 25.0 + 6.0  # after the stand, a few strides into the walk after it: the bias is read
    got, tr, old = _replay(session, at)
    assert old._stop_bias.n_stops >= 1  # read before the restart
    assert len(got) == len(ref) > 20
    for a, r in zip(got, ref, strict=True):
        assert (a.start_s, a.end_s) == (r.start_s, r.end_s)
        assert abs(a.heading_rad - r.heading_rad) < 1e-9, (a.start_s, a.heading_rad, r.heading_rad)
    assert np.hypot(got[-1].x - ref[-1].x, got[-1].y - ref[-1].y) < 1e-6
    assert tr._stop_bias.rps == tr_ref._stop_bias.rps


def test_an_old_state_without_the_bias_still_loads_and_starts_it_at_0_e281(biased):
    """A version-2 state (before E281) is read as before: the bias is 0 until the next stop, so the strides after the
    restart turn by the bias again (what E281 fixes, measured here)."""
    session, stop_at = biased
    ref, _, _ = _replay(session)
    at = stop_at + 25.0 + 6.0
    got, tr, _ = _replay(session, at, strip=lambda s: {k: v for k, v in s.items() if k != "stop_bias"} | {"version": 2})
    assert tr._stop_bias.rps == 0.0 and len(got) == len(ref)
    drift = np.degrees(abs(got[-1].heading_rad - ref[-1].heading_rad))
    assert drift > 5.0, drift  # 0.01 rad/s over the ~20 s walked after the restart


def test_a_bad_stop_bias_is_one_line_e281(biased):
    from pdrlearn.runtime import Tracker, load_bundle

    bundle = load_bundle(SHIPPED)
    state = Tracker(bundle).restart_state()
    assert state["version"] == 3 and state["stop_bias"] == {"rps": 0.0, "n_stops": 0}
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): .*stop_bias .*not finite"):
        Tracker(bundle, resume={**state, "stop_bias": {"rps": float("nan"), "n_stops": 1}})
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): .*stop_bias or pedal_history are malformed"):
        Tracker(bundle, resume={**state, "stop_bias": {"rps": 0.1}})
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): not a restart state of version 3 \(got 2\)"):
        Tracker(bundle, resume={k: v for k, v in state.items() if k != "waist_clock_offset_s"} | {"version": 2})
