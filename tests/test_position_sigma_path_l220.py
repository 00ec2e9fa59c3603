"""Decision L220: a position-uncertainty term growing with the distance walked (`path_rel`, kernel option): a compass
heading error depends on the place and the direction, so an out-and-back route repeats it instead of cancelling it.
Measured as the `plasys-fused` default and not adopted (too large on routes of 3-4 loops); 0 in every shipped regime."""

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.position_sigma import position_covariance, sigma_radius
from pdrlearn.track.position_sigma import SIGMA_PARAMS, sigma_per_row

ZERO = {"displacement_rel": 0.0, "heading_walk_rad": 0.0, "bias_rps": 0.0, "point_m": 0.0}


def test_the_path_term_is_the_distance_walked_on_both_axes():
    L = np.array([1.0, -0.5, 2.0, 1.5])  # a backward stride counts its length walked
    psi = np.array([0.0, 1.0, np.pi, -2.0])
    cov = position_covariance(L, psi, np.arange(1.0, 5.0), 0.0, **ZERO, path_rel=0.1)
    s = np.cumsum(np.abs(L))
    assert cov[:, 0, 0] == pytest.approx((0.1 * s) ** 2) and cov[:, 1, 1] == pytest.approx((0.1 * s) ** 2)
    assert np.allclose(cov[:, 0, 1], 0.0)
    assert np.allclose(position_covariance(L, psi, np.arange(1.0, 5.0), 0.0, **ZERO), 0.0)  # default 0


def _out_and_back(passes: int) -> tuple[pd.DataFrame, np.ndarray]:
    n = 18  # 25 m corridor in 1.4 m strides, a 180 deg turn at each end
    head = np.concatenate([np.full(n, 0.0 if k % 2 == 0 else np.pi) for k in range(passes)])
    end = np.arange(1, len(head) + 1) * 1.05
    steps = pd.DataFrame({"start_s": end - 1.05, "end_s": end, "length_m": 1.4, "heading_rad": head})
    return steps, np.r_[0.0, end]


def test_the_measured_candidate_grows_over_repeated_passes_and_no_regime_ships_it():
    """L220's candidate (path_rel 0.0149 on `plasys-fused`) grows with each pass of an out-and-back corridor, where
    today's radius stays at its first loop's size; it was not adopted (20/20 finals within 2 sigma on the long
    routes, rule 16-19), so no shipped regime has the term."""
    one, t1 = _out_and_back(2)
    four, t4 = _out_and_back(8)
    today = SIGMA_PARAMS["plasys-fused"]
    cand = {**today, "path_rel": 0.0149}
    s1, s4 = sigma_per_row(one, t1, cand)[-1], sigma_per_row(four, t4, cand)[-1]
    # back at the start each time: the displacement term is 0 there; the distance walked is 4 x as long
    assert s4 > 1.5 * s1 > 0
    assert s4 >= np.sqrt(2) * cand["path_rel"] * four["length_m"].sum()
    assert sigma_per_row(four, t4, today)[-1] < 0.5 * s4
    for regime, par in SIGMA_PARAMS.items():
        assert par.get("path_rel", 0.0) == 0.0, regime


def test_sigma_radius_of_the_path_term_alone():
    L = np.ones(10)
    cov = position_covariance(L, np.zeros(10), np.arange(1.0, 11.0), 0.0, **ZERO, path_rel=0.02)
    assert sigma_radius(cov)[-1] == pytest.approx(np.sqrt(2) * 0.02 * 10)
