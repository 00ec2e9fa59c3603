"""Decision W510 (docs/decisions/waist.md, session 45): below seed 000's linear walking range the library's walking
line stays extrapolated (W37: no lower cap); the measured candidate (`experiments/waist_pll_slow_end_s45.py`, a
constant walk ratio below 1.5 Hz) failed W510's rule and lives in the experiment only."""

from __future__ import annotations

import numpy as np
import pytest

from experiments.waist_pll_slow_end_s45 import candidate, walk_ratio_slow_end
from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.steplength import WALK_MIN_HZ, frequency_lengths

P = WaistParams(leg_m=0.88, k=1.0, f_m=0.0, a_walk=0.425, b_walk=0.0595, a_run=0.34, b_run=-0.085)  # W6's 1.70 m line


def test_the_library_line_is_extrapolated_below_the_range_w510():
    f = np.array([0.5, 1.0, WALK_MIN_HZ, 2.0])
    np.testing.assert_allclose(frequency_lengths(f, P, running=np.zeros(4, dtype=bool)),
                               P.a_walk * f * P.frequency_scale() - P.b_walk)


def test_the_candidate_holds_the_walk_ratio_below_1_5_hz_and_is_restored():
    f = np.array([0.5, 1.0, WALK_MIN_HZ, 2.0])
    at_min = P.a_walk * WALK_MIN_HZ - P.b_walk
    walking = np.zeros(4, dtype=bool)
    got = walk_ratio_slow_end(f / P.frequency_scale(), P, running=walking)
    np.testing.assert_allclose(got, [at_min * 0.5 / WALK_MIN_HZ, at_min * 1.0 / WALK_MIN_HZ, at_min,
                                     P.a_walk * 2.0 - P.b_walk])
    import pdrlearn.waist.steplength as sl

    with candidate(True):
        assert sl.frequency_lengths is walk_ratio_slow_end
    assert sl.frequency_lengths is frequency_lengths


@pytest.mark.parametrize("f_hz", [0.45, 0.6])
def test_the_candidate_reads_slow_steps_longer_than_the_line(f_hz):
    one = np.array([f_hz / P.frequency_scale()])
    assert walk_ratio_slow_end(one, P, running=np.zeros(1, dtype=bool))[0] > frequency_lengths(
        one, P, running=np.zeros(1, dtype=bool))[0]
