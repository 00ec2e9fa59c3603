"""Decision C199 (trial T1 finding F2): `calibrate` tracks the lower back alone, as `track --units waist` (W547): a
foot unit in the calibration folder changes no calibration step. User 15863 (session 48)."""

from __future__ import annotations

import dataclasses

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate


def test_a_foot_unit_read_as_at_rest_does_not_empty_the_calibration():
    """The foot unit's streams held still (a unit left on a table, or a foot W336 reads as at rest, T1's race walks):
    a waist track of the whole folder drops every contact (W336's default veto), so calibrate read "0 steps detected"
    before; now it fits on the lower back's steps, as on the folder without the foot unit."""
    s = simulate_path(parse_route("stand:2, straight:16, stand:2"), UserProfile.from_seed(15863), rate_hz=100.0,
                      seed=15863)
    rng = np.random.default_rng(15863)
    still = dict(s.streams)
    for name, level in (("fAccelerometer", np.array([0.0, 9.81, 0.0])), ("fGyroscope", np.zeros(3))):
        st = still[name]
        still[name] = dataclasses.replace(st, values=level + 0.01 * rng.standard_normal(st.values.shape))
    rest = dataclasses.replace(s, streams=still)
    assert len(track_waist(rest, pipeline="waist-pendulum").steps) == 0  # W336 on the whole folder
    got = calibrate([rest], "waist-pendulum", distances=[16.0])
    phone = calibrate([dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if not k.startswith("f")})],
                      "waist-pendulum", distances=[16.0])
    assert np.isfinite(got.k) and abs(got.k - phone.k) < 1e-9
