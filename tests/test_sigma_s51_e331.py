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


def test_the_streamed_waist_regime_carries_it_and_no_other():
    """E331 adopted on fresh users 17890-17909: `run` / `track --streaming` with the waist unit; the foot-only
    streamed regime and L267's offline fallback keep their constants."""
    from pdrlearn.track.position_sigma import sigma_params, sigma_per_row

    assert sigma_params("plasys-streaming")["heading_offset_rad"] == 0.0073  # E337 (E336 removed the offset's cause)
    assert all("heading_offset_rad" not in sigma_params(r) for r in ("plasys-foot-streaming", "plasys-gyro-fallback",
                                                                    "plasys-fused", "plasys-foot", "waist"))
    import pandas as pd

    steps = pd.DataFrame({"length_m": np.ones(40), "heading_rad": np.zeros(40), "end_s": np.arange(1.0, 41.0),
                          "start_s": np.arange(0.0, 40.0)})
    t = np.r_[0.0, steps["end_s"]]
    old = {k: v for k, v in sigma_params("plasys-streaming").items() if k != "heading_offset_rad"}
    new, before = sigma_per_row(steps, t, sigma_params("plasys-streaming")), sigma_per_row(steps, t, old)
    assert new[-1] ** 2 - before[-1] ** 2 == pytest.approx((0.0073 * 40) ** 2, rel=1e-6)  # 0.29 m across 40 m
