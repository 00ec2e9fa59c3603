"""Decision L237: the compass's place-dependent error as a random walk of the position per metre walked
(`path_diffusion_m2`, a kernel term), its candidate value derived from the simulator's documented field disturbance
(S33) and Earth field, not fitted."""

import numpy as np
import pytest

from pdrlearn.kernels.position_sigma import position_covariance
from pdrlearn.track.position_sigma import PLACE_DIFFUSION_M2, SIGMA_PARAMS

ZERO = {"displacement_rel": 0.0, "heading_walk_rad": 0.0, "bias_rps": 0.0, "point_m": 0.0}


def test_the_diffusion_term_is_the_distance_walked_times_q_on_both_axes():
    L = np.array([1.0, -0.5, 2.0, 1.5])  # a backward stride counts its length walked
    psi = np.array([0.0, 1.0, np.pi, -2.0])
    cov = position_covariance(L, psi, np.arange(1.0, 5.0), 0.0, **ZERO, path_diffusion_m2=0.01)
    s = np.cumsum(np.abs(L))
    assert cov[:, 0, 0] == pytest.approx(0.01 * s) and cov[:, 1, 1] == pytest.approx(0.01 * s)
    assert np.allclose(cov[:, 0, 1], 0.0)
    # a closed square loop: the displacement terms return to their start, this one does not
    sq = np.repeat([0.0, np.pi / 2, np.pi, -np.pi / 2], 10)
    t = np.arange(1.0, 41.0)
    base = dict(SIGMA_PARAMS["plasys-fused"])
    with_q = position_covariance(np.ones(40), sq, t, 0.0, **base, path_diffusion_m2=PLACE_DIFFUSION_M2)
    without = position_covariance(np.ones(40), sq, t, 0.0, **base)
    assert np.trace(with_q[-1]) - np.trace(without[-1]) == pytest.approx(2 * PLACE_DIFFUSION_M2 * 40.0)


def test_the_candidate_value_is_the_documented_disturbance_over_the_horizontal_field():
    """(1/4 m) A^2 2 pi w^2 / sqrt(3) / H^2 / 2 with S33's A = 3 uT, 4 m spacing, w = 1 m and H = 45 cos 55 deg uT."""
    from pdrlearn.sim.sensors import field_disturbance
    from pdrlearn.sim.simulate import KNOBS

    h = KNOBS["mag_field_ut"] * np.cos(np.radians(KNOBS["mag_inclination_deg"]))
    a = KNOBS["mag_disturbance_ut"]
    assert PLACE_DIFFUSION_M2 == pytest.approx(0.25 * a ** 2 * 2 * np.pi / np.sqrt(3.0) / h ** 2 / 2)
    assert PLACE_DIFFUSION_M2 == pytest.approx(0.00613, abs=5e-6)
    # the lateral error it stands for, measured on the simulator's own field: the heading error d_perp / H integrated
    # along a straight 400 m path, its variance per metre over many draws (the derivation's, within sampling)
    x = np.arange(0.0, 400.0, 0.1)
    pos = np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])
    # the Earth field points north (y): the heading error is the east component across it over H
    lat = [np.trapezoid(field_disturbance(pos, np.random.default_rng(k), a)[:, 0], x) / h for k in range(200)]
    assert np.var(lat) / 400.0 == pytest.approx(2 * PLACE_DIFFUSION_M2, rel=0.3)


def test_no_regime_ships_the_diffusion_term():
    """L238: measured on users 4700-4739 and not adopted (18/28 finals within 2 sigma, rule 90-99 %)."""
    assert all(not p.get("path_diffusion_m2") for p in SIGMA_PARAMS.values())
