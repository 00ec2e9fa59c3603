"""Decision L333: 2 ``pos_sigma_m`` never exceeds s_k + |D_k| (distance walked + the track's distance from its start),
the radius that holds the true position by construction; decision L336: L182's compass line does not claim a
magnetic disturbance."""

from __future__ import annotations

from functools import partial
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.position_sigma import position_covariance, sigma_radius
from pdrlearn.track import position_sigma as ps
from pdrlearn.track.position_sigma import SIGMA_PARAMS, reach_bound, sigma_per_row


def _steps(length, heading, gap=None) -> pd.DataFrame:
    end = np.arange(1, len(length) + 1, dtype=float)
    st = pd.DataFrame({"start_s": end - 1.0, "end_s": end, "length_m": np.asarray(length, float),
                       "heading_rad": np.asarray(heading, float)})
    if gap is not None:
        st["gap_s"] = gap
    return st


def test_the_bound_holds_any_true_path_of_the_same_strides():
    """|estimate - truth| <= s_k + |D_k| for a truth that walks the same stride lengths in any directions (the bound
    is the triangle inequality, not a model); it never decreases; out and back it is the distance walked."""
    rng = np.random.default_rng(333)
    L = rng.uniform(0.5, 1.6, 300)
    est = rng.normal(0.0, 0.3, 300).cumsum()
    R = reach_bound(L, est)
    assert np.all(np.diff(R) >= -1e-9)
    for _ in range(20):
        true = rng.uniform(-np.pi, np.pi, 300) if _ % 2 else est + np.pi  # anywhere / straight back the other way
        e = np.hypot(np.cumsum(L * (np.cos(est) - np.cos(true))), np.cumsum(L * (np.sin(est) - np.sin(true))))
        assert np.all(e <= R + 1e-9)
    R = reach_bound(np.ones(40), np.repeat([0.0, np.pi], 20))  # 20 m out, 20 m back, 1 m strides
    assert R[19] == pytest.approx(41.0) and R[-1] == pytest.approx(41.0)


def test_a_held_gap_adds_its_missed_walk_to_the_bound():
    """E127's held row (no length, ``gap_s`` > 0) may have missed speed x gap of walk: the bound grows by it."""
    st = _steps([1.0] * 10 + [np.nan] + [1.0] * 10, [0.0] * 21, gap=[0.0] * 10 + [5.0] + [0.0] * 10)
    st.loc[10, "length_m"] = 0.0
    held = ps.held_gap_variance(st)
    L = st["length_m"].to_numpy(float)
    R = reach_bound(L, st["heading_rad"].to_numpy(float), ps.missed_walk(L, np.zeros(len(L), bool), held))
    v = 1.0  # 1 m strides of 1 s
    assert R[-1] == pytest.approx(2 * 20.0 + v * 5.0 + 1.0)


def test_a_stride_of_unknown_length_widens_the_bound_by_two_longest_strides():
    """L143's stride of unknown length is modelled as 0: the bound adds twice the longest known stride for it (the
    walk it may have been, and the track's step the model left out), so the cut stays on the safe side."""
    L = np.r_[np.ones(5), np.nan, np.full(4, 1.5)]
    bad = ~np.isfinite(L)
    assert ps.missed_walk(L, bad, None).tolist() == [0.0] * 5 + [3.0] + [0.0] * 4
    st = _steps(L, np.zeros(10))
    flag: dict = {}
    s = sigma_per_row(st, np.r_[0.0, st["end_s"]], {**SIGMA_PARAMS["plasys-streaming"], "bias_rps": 1.0},
                      bounded=flag)
    assert np.isnan(s[6]) and flag["bounded"]
    assert 2 * s[-1] == pytest.approx(11.0 + 3.0 + 11.0 + 1.5)  # walked + unknown + |D| (model) + longest stride


def test_the_radius_is_cut_to_half_the_bound_only_where_the_model_exceeds_it():
    """A model far past its small-angle range (a residual heading rate of 1 rad/s) is cut to R_k / 2 and says so;
    the shipped fused model past its first strides is untouched (equal to the kernel's radius) and not flagged (its
    1.5 m point term is cut on the first metres only: 2 sigma 4.2 m against R 3 m after a 1 m stride)."""
    n = 60
    st = _steps(np.ones(n), np.repeat([0.0, np.pi / 2, np.pi], 20))
    t = np.r_[0.0, st["end_s"].to_numpy(float)]
    R = reach_bound(st["length_m"].to_numpy(float), st["heading_rad"].to_numpy(float))
    flag: dict = {}
    wild = sigma_per_row(st, t, {**SIGMA_PARAMS["plasys-streaming"], "bias_rps": 1.0}, bounded=flag)
    assert flag == {"bounded": True}
    assert np.all(2 * wild[1:] <= R + 1e-9) and 2 * wild[-1] == pytest.approx(R[-1])
    flag = {}
    shipped = sigma_per_row(st, t, SIGMA_PARAMS["plasys-fused"], bounded=flag)
    assert flag == {"bounded": False}
    cov = position_covariance(st["length_m"].to_numpy(float), st["heading_rad"].to_numpy(float),
                              st["end_s"].to_numpy(float), 0.0, **SIGMA_PARAMS["plasys-fused"])
    model = np.maximum.accumulate(sigma_radius(cov))
    np.testing.assert_allclose(shipped[1:], np.minimum(model, R / 2))
    assert np.all(shipped[4:] == model[3:]) and shipped[1] < model[0]


def test_add_position_sigma_records_whether_the_end_was_bounded(monkeypatch):
    """``info.position_sigma.bounded``: True when the end's radius is the bound, False otherwise; the summary's
    ``final_position_sigma_m`` is the cut column's last value."""
    from pdrlearn.track.evaluate import evaluate_track

    st = _steps(np.ones(40), np.repeat([0.0, np.pi], 20))
    for bias, want in ((0.0, False), (10.0, True)):
        monkeypatch.setitem(SIGMA_PARAMS, "plasys-streaming", {**SIGMA_PARAMS["plasys-streaming"], "bias_rps": bias})
        res = SimpleNamespace(trajectory=pd.DataFrame({"t": np.r_[0.0, st["end_s"]], "x": 0.0, "y": 0.0}),
                              steps=st, info={})
        ps.add_position_sigma(res, None, "plasys-streaming")
        assert res.info["position_sigma"]["bounded"] is want
        if want:
            assert 2 * res.trajectory["pos_sigma_m"].iloc[-1] == pytest.approx(41.0)  # out and back: 40 m + a stride
    assert evaluate_track  # imported: the summary reads the column (L128), tested in test_position_sigma.py


def test_compass_line_does_not_claim_a_disturbance_l336():
    """Decision L336: L182's line says the two headings disagree and either may be wrong; without the fallback it
    still names `--streaming` / `--units foot`, with it (L226) it says the track follows the waist gyroscope."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.plasys import track_plasys

    route = parse_route(", ".join(["straight:15, curve:-90:1"] * 4))
    s = simulate_path(route, UserProfile.from_seed(2972), seed=2972, mag_disturbance_ut=30.0)
    for fallback in (False, True):
        line = [w for w in track_plasys(s, compass_fallback=fallback).info["warnings"] if "decision L182" in w]
        assert len(line) == 1
        assert "cannot tell which" in line[0] and "decision L336" in line[0]
        assert "a magnetic disturbance (steel" not in line[0] and "turns this offline track" not in line[0]
        assert ("--streaming" in line[0]) is (not fallback)
        assert ("follows the waist gyroscope's heading" in line[0]) is fallback


def test_the_fused_radius_takes_the_compass_check_l335():
    """Decisions L334/L335: a ``plasys-fused`` track with L182's check gets ``extent_heading_rad`` = the check's median
    (rad) on its extent; without a check it keeps L128's model; no other regime takes it; the switch turns it off.
    Decision L341: the option is off by default (the lead did not keep L335); L595: the keyword ``compass_extent``."""
    assert ps.sigma_params("plasys-fused", {"compass_check": {"median_deg": 8.19}}) == SIGMA_PARAMS["plasys-fused"]
    info = {"compass_check": {"median_deg": 8.19}}
    on = partial(ps.sigma_params, compass_extent=True)
    assert on("plasys-fused", info)["extent_heading_rad"] == pytest.approx(np.radians(8.19))
    assert on("plasys-fused", {}) == SIGMA_PARAMS["plasys-fused"]
    assert on("plasys-fused", {"compass_check": {"median_deg": float("nan")}}) == SIGMA_PARAMS["plasys-fused"]
    for regime in set(SIGMA_PARAMS) - {"plasys-fused"}:
        assert on(regime, info) == SIGMA_PARAMS[regime]
    st = _steps(np.ones(200), np.zeros(200))  # 200 m straight: extent 200 m
    t = np.r_[0.0, st["end_s"]]

    def final(inf, compass_extent=True):
        res = SimpleNamespace(trajectory=pd.DataFrame({"t": t}), steps=st, info=dict(inf))
        ps.add_position_sigma(res, None, "plasys-fused",
                              params=ps.sigma_params("plasys-fused", inf, compass_extent=compass_extent))
        return res.trajectory["pos_sigma_m"].iloc[-1]

    today = final({})
    assert final(info) ** 2 == pytest.approx(today ** 2 + 2 * (np.radians(8.19) * 200) ** 2)
    assert final(info, compass_extent=False) == today


def test_l175_line_on_a_fused_track_names_the_compass_check_not_plasys_fused():
    """Decision L335: a ``plasys-fused`` radius wide from its compass-check term gets L175's line with the check's
    angle as the reason and fixes as the remedy, not the advice to track with `plasys-fused` it already is."""
    from pdrlearn.track.position_sigma import position_sigma_warning

    info = {"position_sigma": {"model": "plasys-fused", "extent_heading_rad": float(np.radians(13.75))}}
    line = position_sigma_warning({"final_position_sigma_m": 340.8, "distance_m": 1963.0, "info": info})
    assert line is not None and "decision L335" in line and "13.8 deg" in line and "--fixes" in line
    assert "`plasys-fused`) or" not in line and "gyroscope-only" not in line
    info = {"position_sigma": {"model": "plasys-streaming"}}
    line = position_sigma_warning({"final_position_sigma_m": 340.8, "distance_m": 1963.0, "info": info})
    assert "gyroscope-only" in line and "`plasys-fused`" in line
