"""Decision L31: the runtime adds the foot's turn between two strides (a slow pivot inside a long stance) as
``track --streaming`` does (trajectory parity, issue 7)."""

from __future__ import annotations

import numpy as np

from pdrlearn.io import Stream
from pdrlearn.orient import wrap_angle
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import replay, rest_dirs, synthetic_session


def _with_pivots(s, every: int = 4, pivot_s: float = 0.8, rate: float = 0.6):
    """Foot-only (with force) copy of ``s`` with every ``every``-th stance lengthened by a ``pivot_s`` slow
    turn about the vertical (thesis foot frame: y up) at ``rate`` rad/s: below the 0.8 rad/s stance threshold (one long
    stance, so the streamed strides do not touch), above the 0.4 rad/s ZARU threshold (the foot turns)."""
    fa, fg = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    t, a, g = fa.t, fa.values, fg.values
    dt = float(t[1] - t[0])
    still = np.linalg.norm(g, axis=1) < 0.2
    starts = np.flatnonzero(still[1:] & ~still[:-1]) + 1  # stance starts
    cut = starts[2::every] + 3
    n_p = int(round(pivot_s / dt))
    pa = np.tile(a[cut[0]], (n_p, 1))
    pg = np.tile([0.0, rate, 0.0], (n_p, 1))
    a2 = np.insert(a, np.repeat(cut, n_p), np.tile(pa, (len(cut), 1)), axis=0)
    g2 = np.insert(g, np.repeat(cut, n_p), np.tile(pg, (len(cut), 1)), axis=0)
    t2 = t[0] + np.arange(len(a2)) * dt
    out = s.copy()
    out.streams = {"fAccelerometer": Stream("fAccelerometer", t2, a2), "fGyroscope": Stream("fGyroscope", t2, g2)}
    for name in ("fForceA", "fForceB"):  # the loaded foot pivots: force held at its value at the cut
        v = s.streams[name].values
        out.streams[name] = Stream(name, t2, np.insert(v, np.repeat(cut, n_p), np.repeat(v[cut], n_p, axis=0), axis=0))
    out.steps = None
    return out, len(cut)


def test_runtime_keeps_the_pivot_between_strides_like_streaming_track(tmp_path_factory):
    s, n_pivots = _with_pivots(synthetic_session(24, seed=11, name="pivots"))
    root = rest_dirs(tmp_path_factory)["rest_root"]
    track = get_pipeline("plasys")
    res = track(s, method="M3", model=str(root / "model"), streaming=True, heading="foot")
    off = track(s, method="M3", model=str(root / "model"), streaming=True, heading="foot", gap_yaw=False)
    steps = replay(Tracker(root / "bundle", heading_source="foot"), s, 0.37)
    assert len(steps) == len(res.steps) >= 20
    # equal modulo 2 pi: a stride reversed by L37 jumps by pi, which np.unwrap may take either way
    dh = np.array([st.heading_rad for st in steps]) - res.steps["heading_rad"].to_numpy(float)
    np.testing.assert_allclose(wrap_angle(dh), 0.0, atol=1e-9)
    xyz = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(xyz - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    h_on, h_off = res.steps["heading_rad"].to_numpy(float), off.steps["heading_rad"].to_numpy(float)
    turned = float(np.sum(wrap_angle(np.diff(h_on) - np.diff(h_off))))  # the pivots, stride by stride
    # each pivot turns the foot by 0.6 rad/s x its last second before the next stride opens (<= 0.48 rad)
    assert 0.5 * n_pivots * 0.2 < abs(turned) <= n_pivots * 0.6 * 0.8 + 1e-9, (turned, n_pivots)
