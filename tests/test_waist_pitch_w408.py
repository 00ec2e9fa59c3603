"""Decision W408 (trial T3, session 38, finding 7): waist-pll's distance under a 20 deg pitch of the lower-back unit
(7.8 -> 12.6 % in the trial) is no pitch sensitivity: both verticals it reads (the PLL's tracked gravity direction and
the AHRS's) are the data's, not the unit's z, so without the simulated sensor errors a +-20 deg pitch tracks
identically; with them, a step at a walk's edge flips."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.mark.parametrize("pitch", [20.0, -20.0])
def test_waist_pll_is_the_same_under_a_pitch_without_sensor_errors(pitch):
    from pdrlearn.sim import simulate
    from pdrlearn.track import get_pipeline

    runs = [get_pipeline("waist-pll")(simulate("walk", user_seed=9649, length_m=30.0, rate_hz=100.0, noise=False,
                                               waist_mount_deg=m))
            for m in ((0.0, 0.0, 0.0), (0.0, pitch, 0.0))]
    a, b = (r.steps for r in runs)
    assert len(a) == len(b) > 20
    # float rounding of the rotated data (seen: 1.2e-6 m)
    np.testing.assert_allclose(b["length_m"], a["length_m"], atol=1e-4)
    np.testing.assert_allclose(b["event_s"], a["event_s"], atol=1e-9)
