"""Decision E331 (session 51, I4): the position covariance's constant heading offset term (``heading_offset_rad``):
a heading error held the same from the start moves the position by delta C_k, P_k += delta^2 C_k C_k^T."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.position_sigma import position_covariance

BASE = {"displacement_rel": 0.029, "heading_walk_rad": 0.007, "bias_rps": 0.00051, "point_m": 0.0}


def test_a_constant_heading_offset_grows_across_the_displacement():
    n = 10
    length, heading, t_end = np.ones(n), np.zeros(n), np.arange(1.0, n + 1)
    without = position_covariance(length, heading, t_end, 0.0, **BASE)
    delta = 0.05
    got = position_covariance(length, heading, t_end, 0.0, **BASE, heading_offset_rad=delta)
    k = np.arange(1, n + 1)
    added = got - without  # walking east: C_k = (0, k), the offset's error is across the walk (north)
    assert added[:, 1, 1] == pytest.approx((delta * k) ** 2)
    assert np.allclose(added[:, 0, 0], 0.0) and np.allclose(added[:, 0, 1], 0.0)
    back = position_covariance(np.r_[length, length], np.r_[heading, np.full(n, np.pi)], np.arange(1.0, 2 * n + 1),
                               0.0, **BASE, heading_offset_rad=delta)
    there_and_back = back - position_covariance(np.r_[length, length], np.r_[heading, np.full(n, np.pi)],
                                                np.arange(1.0, 2 * n + 1), 0.0, **BASE)
    assert there_and_back[-1, 1, 1] == pytest.approx(0.0, abs=1e-12)  # back at the start: the offset cancels
