"""Session 31 treadmill trial: B260 (quiet standing near the force load level is no stepping), B261 (`steps` short
of the foot's own swing count), B262 (unknown meta.json keys), L319-L323 and steps 47-48."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.frozen_foot import FORCE_LOAD_LEVEL, frozen_foot_evidence, load_onsets


def test_standing_force_noise_at_the_load_level_is_no_stepping_b260():
    # the simulated 10 % incline's final stand: both sensors 74-119 N against block references of ~430 N, i.e. around
    # FORCE_LOAD_LEVEL x ref = 86 N; the foot IMU is still. Before B260 the noise read as 3+ loads (B213's warning).
    rng = np.random.default_rng(3)
    n = 700
    ref = 430.0
    still_acc, still_gyr = np.tile([0.0, 9.81, 0.0], (n, 1)), np.zeros((n, 3))
    stand = [FORCE_LOAD_LEVEL * ref + 10.0 + rng.normal(0, 10.0, n) for _ in range(2)]
    assert load_onsets(stand, [ref, ref]) == 0
    assert frozen_foot_evidence(still_acc, still_gyr, stand, refs=[ref, ref]) is None
    # real steps (the foot unloads in swing) still count, and a frozen IMU beside them is still found (B203 / B213)
    steps = (np.arange(n) // 50) % 2 == 1
    force = [np.where(steps, 600.0, 5.0) + rng.normal(0, 1, n)]
    assert load_onsets(force, [600.0]) == 7
    got = frozen_foot_evidence(still_acc, still_gyr, force)
    assert got is not None and got[0] == 7
