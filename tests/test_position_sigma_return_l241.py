"""Decision L241: L239's bounded heading error only on the part of the route's extent the track has come back from
(`extent_return_rad`, a kernel term): per axis e^2 (R_k^2 - |D_k|^2), R_k the farthest the track has been from its
start, |D_k| its displacement now."""

import inspect

import numpy as np
import pytest

from pdrlearn.kernels.position_sigma import position_covariance
from pdrlearn.track.position_sigma import EXTENT_HEADING_RAD, SIGMA_PARAMS

TODAY = {"displacement_rel": 0.026, "heading_walk_rad": 0.0034, "bias_rps": 0.0, "point_m": 1.5}  # L128's fused
ZERO = {"displacement_rel": 0.0, "heading_walk_rad": 0.0, "bias_rps": 0.0, "point_m": 0.0}


def _walk(*legs: tuple[int, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Strides of 1 m, ``n`` of them on each leg's heading (rad)."""
    psi = np.concatenate([np.full(n, h) for n, h in legs])
    return np.ones(len(psi)), psi, np.arange(1.0, len(psi) + 1.0)


@pytest.mark.parametrize("legs", [((40, 0.0),), ((30, 0.0), (30, np.pi / 2))], ids=["straight", "L-shaped"])
def test_a_walk_that_only_goes_out_from_its_start_keeps_todays_radius(legs):
    """L240's failure: L239's term added (e |D_k|)^2 per axis on such walks; this one adds nothing."""
    L, psi, t = _walk(*legs)
    today = position_covariance(L, psi, t, 0.0, **TODAY)
    cand = position_covariance(L, psi, t, 0.0, **TODAY, extent_return_rad=EXTENT_HEADING_RAD)
    assert np.allclose(cand, today, rtol=0.0, atol=1e-9)
    l239 = position_covariance(L, psi, t, 0.0, **TODAY, extent_heading_rad=EXTENT_HEADING_RAD)
    assert np.trace(l239[-1]) - np.trace(today[-1]) > 10.0  # the double count L240 measured (2 (0.097 x 40 m)^2)


def test_a_closed_loop_keeps_the_extent_term():
    """A square of 10 m sides back to its start: the farthest point is the far corner, 10 sqrt(2) m away."""
    L, psi, t = _walk((10, 0.0), (10, np.pi / 2), (10, np.pi), (10, -np.pi / 2))
    e = EXTENT_HEADING_RAD
    cand = position_covariance(L, psi, t, 0.0, **ZERO, extent_return_rad=e)
    l239 = position_covariance(L, psi, t, 0.0, **ZERO, extent_heading_rad=e)
    assert cand[-1] == pytest.approx(l239[-1]) and cand[-1, 0, 0] == pytest.approx(e ** 2 * 200.0)
    # added to today's terms: back at the start today's displacement term is 0, the candidate's extent term stays
    today = position_covariance(L, psi, t, 0.0, **TODAY)
    both = position_covariance(L, psi, t, 0.0, **TODAY, extent_return_rad=e)
    assert np.trace(both[-1]) - np.trace(today[-1]) == pytest.approx(2 * e ** 2 * 200.0)


def test_on_the_way_back_the_term_is_the_extent_less_the_displacement_by_hand():
    """20 m east, then 20 m back west: R_k = 20 m after the turn, |D_k| = 40 - k; a backward stride counts with its
    sign (20 m forward, 20 m backward on one heading is the same walk)."""
    L, psi, t = _walk((20, 0.0), (20, np.pi))
    e = 0.1
    cov = position_covariance(L, psi, t, 0.0, **ZERO, extent_return_rad=e)
    k = np.arange(1, 41)
    d = np.where(k <= 20, k, 40 - k).astype(float)
    r = np.minimum(k, 20).astype(float)
    want = e ** 2 * (r ** 2 - d ** 2)
    assert cov[:, 0, 0] == pytest.approx(want, abs=1e-12) and cov[:, 1, 1] == pytest.approx(want, abs=1e-12)
    assert np.allclose(cov[:, 0, 1], 0.0)
    bwd = position_covariance(np.r_[np.ones(20), -np.ones(20)], np.zeros(40), t, 0.0, **ZERO, extent_return_rad=e)
    assert bwd == pytest.approx(cov, abs=1e-12)
    # laps within the extent do not make it grow: 3 laps out and back end where one does
    L3, psi3, t3 = _walk(*[(20, 0.0), (20, np.pi)] * 3)
    assert position_covariance(L3, psi3, t3, 0.0, **ZERO, extent_return_rad=e)[-1] == pytest.approx(cov[-1])


def test_todays_fused_parameters_are_the_ones_the_walks_above_compare_with():
    assert {k: v for k, v in SIGMA_PARAMS["plasys-fused"].items() if k in TODAY} == TODAY


def test_the_return_term_is_an_option_off_by_default_on_the_fused_radius_only():
    """L242: measured on users 5130-5169 and not adopted (20/25 long-route finals within 2 sigma, rule 90-99 %);
    ``sigma_params(..., extent_return=True)`` (L595) adds it to ``plasys-fused`` and to no other regime."""
    from types import SimpleNamespace

    import pandas as pd

    from pdrlearn.track import position_sigma as ps

    assert inspect.signature(ps.sigma_params).parameters["extent_return"].default is False
    assert all(not p.get("extent_return_rad") for p in SIGMA_PARAMS.values())
    L, psi, t = _walk((10, 0.0), (10, np.pi / 2), (10, np.pi), (10, -np.pi / 2))  # a closed square
    steps = pd.DataFrame({"start_s": t - 1.0, "end_s": t, "length_m": L, "heading_rad": psi})

    def final(regime, **option):
        res = SimpleNamespace(trajectory=pd.DataFrame({"t": np.r_[0.0, t]}), steps=steps, info={})
        ps.add_position_sigma(res, None, regime, params=ps.sigma_params(regime, {}, **option))
        return res.trajectory["pos_sigma_m"].iloc[-1], res.info["position_sigma"]

    off = {r: final(r) for r in ("plasys-fused", "waist")}
    assert "extent_return_rad" not in off["plasys-fused"][1]
    on = {r: final(r, extent_return=True) for r in ("plasys-fused", "waist")}
    assert on["plasys-fused"][1]["extent_return_rad"] == EXTENT_HEADING_RAD
    assert "extent_heading_rad" not in on["plasys-fused"][1]
    # the track's radius is the kernel's with the term (never shrinking: the largest so far); back at the start that
    # is today's covariance plus the far corner's 10 sqrt(2) m times the heading error on both axes
    fused = {**SIGMA_PARAMS["plasys-fused"], "extent_return_rad": EXTENT_HEADING_RAD}
    cand = np.trace(position_covariance(L, psi, t, 0.0, **fused), axis1=1, axis2=2)
    today = np.trace(position_covariance(L, psi, t, 0.0, **SIGMA_PARAMS["plasys-fused"]), axis1=1, axis2=2)
    assert on["plasys-fused"][0] == pytest.approx(np.sqrt(cand.max()))
    assert cand[-1] == pytest.approx(today[-1] + 2 * EXTENT_HEADING_RAD ** 2 * 200.0)
    assert on["plasys-fused"][0] > off["plasys-fused"][0] + 0.5
    assert on["waist"] == off["waist"]
