"""Decision W394 (session 37, trial T1 finding 10): a waist unit whose gravity or forward is beyond 35 deg of every
axis (a phone in a pocket) is refused by the frame inference as before, and the refusal suggests the nearest axis
assignment its walking gives instead of the thesis mounting; that suggestion, declared, tracks the walk."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.io.session import Session, Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist


def _tilted(u: int = 9217) -> Session:
    s = simulate_path(parse_route("stand:2, straight:25"), UserProfile.from_seed(u), seed=2, scenario="route")
    r = Rotation.from_euler("xyz", [170, 30, 25], degrees=True).as_matrix()  # trial T1's phone.py rotation
    m = s.require_frame("waist").matrix()  # sensor -> FLU: the walk in FLU axes, then turned into the phone's
    streams = {n: Stream(n, s[n].t, s[n].values @ m.T @ r) for n in ("wAccelerometer", "wGyroscope")}
    return Session(name="tilted", streams=streams, meta={"session": "tilted"})


def test_the_tilt_refusal_suggests_the_frame_the_walk_gives():
    s = _tilted()
    with pytest.raises(DataError) as e:
        track_waist(s, pipeline="waist-pendulum")
    msg = str(e.value)
    assert "deg from both horizontal sensor axes (more than 35)" in msg  # the forward axis of a 40 deg tilt
    assert "the nearest axis assignment its walking gives" in msg and "the thesis mounting" not in msg
    frames = json.loads(re.search(r'"frames": (\{.*\}\})', msg).group(1))
    t = Session(name="tilted", streams=s.streams, meta={"session": "tilted", "frames": frames})
    res = track_waist(t, pipeline="waist-pendulum")
    assert len(res.steps) > 20 and 15.0 < res.distance_m < 40.0
    assert np.isfinite(res.trajectory["x"].iloc[-1])
