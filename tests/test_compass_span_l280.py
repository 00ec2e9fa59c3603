"""Decision L280 (session 30): L182's one fit also judges a walk up to 15 min (L264's windows alone no longer moved
two 3 uT R1 x2 tracks whose foot heading drifts at ~0.2 deg/s to the waist gyroscope, L265 (d)), and L266's drifting
line needs a fallback stretch of two of L264's windows (over a ~100 s loop it fitted the compass's place-dependent
error, L265 (b))."""

from __future__ import annotations

import logging

import numpy as np
import pytest

import pdrlearn.track.plasys as P
from pdrlearn.track.plasys import (
    COMPASS_CHECK_WINDOW_S,
    COMPASS_DISAGREE_DEG,
    COMPASS_ONE_FIT_MAX_S,
    FALLBACK_DRIFT_MIN_S,
    check_angle,
    fuse_heading,
    fuse_with_drift,
    track_plasys,
)


def _drifting_foot(span_s: float, drift_dps: float):
    """Straight strides 1 s apart on legs of 20 turning 90 deg; a clean compass (22 uT Earth field + a hard iron) at
    the true heading; the foot's relative heading drifts ``drift_dps`` away from it."""
    t = np.arange(0.0, span_s)
    true = np.radians(90.0) * (t // 20)
    psi = true + np.radians(drift_dps) * t
    return 22.0 * np.sin(true + 0.4) + 3.0, 22.0 * np.cos(true + 0.4) - 2.0, psi, t


def test_a_short_walk_whose_foot_drifts_away_from_the_compass_is_judged_by_the_one_fit_too():
    """(i): 390 s of a foot heading drifting 0.3 deg/s (u5171: ~0.2): L264's windows see < 20 deg, L182's one fit more;
    with the gates the larger judges. A 40 min shift drifting 0.1 deg/s stays judged by the windows alone."""
    mf, ml, psi, t = _drifting_foot(390.0, 0.3)
    windows, info0 = check_angle(mf, ml, psi, t, windowed=True, span_gates=False)
    gated, info = check_angle(mf, ml, psi, t, windowed=True, span_gates=True)
    assert windows < COMPASS_DISAGREE_DEG < gated and info0["by"] == "windows" and info["by"] == "one fit"
    assert info["median_windows_deg"] == pytest.approx(windows) and info["median_one_fit_deg"] == pytest.approx(gated)
    assert gated == pytest.approx(check_angle(mf, ml, psi, t, windowed=False)[0])  # L182's one fit, as before L264
    mf, ml, psi, t = _drifting_foot(2400.0, 0.1)
    assert np.ptp(t) > COMPASS_ONE_FIT_MAX_S
    long, info = check_angle(mf, ml, psi, t, windowed=True, span_gates=True)
    assert long < 5.0 and info["by"] == "windows" and info["median_one_fit_deg"] is None
    assert check_angle(mf, ml, psi, t, windowed=False)[0] > COMPASS_DISAGREE_DEG  # what L182 alone said


def test_the_fallback_line_needs_a_stretch_of_two_windows():
    """(ii): a stretch under two of L264's windows gets L226's one constant, a longer one L266's line."""
    assert FALLBACK_DRIFT_MIN_S == 2 * COMPASS_CHECK_WINDOW_S
    rng = np.random.default_rng(1)
    for span, line in ((100.0, False), (1620.0, True)):
        t = np.arange(0.0, span, 1.2)
        true = np.cumsum(rng.normal(0, 0.2, len(t)))
        gyro = true + np.radians(0.05) * t + 1.0
        compass = true + np.radians(rng.normal(0, 10.0, len(t)))
        got = fuse_with_drift(gyro, compass, t, min_span_s=FALLBACK_DRIFT_MIN_S)
        want = fuse_with_drift(gyro, compass, t) if line else fuse_heading(gyro, compass, t, tau_s=np.inf)
        np.testing.assert_allclose(got, want)
        assert not np.allclose(fuse_with_drift(gyro, compass, t), fuse_heading(gyro, compass, t, tau_s=np.inf))


@pytest.fixture
def gates():
    old = P.COMPASS_SPAN_GATES
    logging.disable(logging.WARNING)
    yield lambda on: setattr(P, "COMPASS_SPAN_GATES", on)
    P.COMPASS_SPAN_GATES = old
    logging.disable(logging.NOTSET)


def test_a_short_disturbed_loop_falls_back_by_one_constant(gates):
    """(ii) on the track: L182's ~100 s loop at 30 uT falls back; with the gates its heading is L226's one-constant
    fallback, without them L266's line."""
    from tests.test_compass_shift_l264 import _biased_loop

    s = _biased_loop()
    const = track_plasys(s, fallback_drift=False).steps["heading_rad"].to_numpy(float)
    gates(True)
    r = track_plasys(s)
    assert r.info["compass_check"]["gyro_fallback"] is True
    np.testing.assert_allclose(r.steps["heading_rad"].to_numpy(float), const)
    gates(False)
    assert not np.allclose(track_plasys(s, fallback_drift=True).steps["heading_rad"].to_numpy(float), const)


def test_the_3ut_r1x2_walk_l182_moved_to_the_gyroscope_falls_back_again(gates):
    """(i) on the track: L265 (d)'s u5171 (3 uT, R1 x2, its foot heading drifting ~80 deg over 6.5 min): with the gates
    L182's one fit judges it (23.3 deg at diagnosis) and the track follows the waist gyroscope, the line naming L280;
    without them L264's windows (~6 deg) keep L17's fused heading."""
    import sys
    from pathlib import Path

    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
    from compass_check_long import R1

    s = simulate_path(parse_route(", ".join([R1] * 2)), UserProfile.from_seed(5171), seed=5171, mag_disturbance_ut=3.0,
                      scenario="route")  # as `simulate --route ... --user-seed 5171 --seed 5171`
    gates(False)
    off = track_plasys(s).info["compass_check"]
    gates(True)
    r = track_plasys(s)
    on = r.info["compass_check"]
    assert off["gyro_fallback"] is False and off["median_deg"] < COMPASS_DISAGREE_DEG and off["by"] == "windows"
    assert on["gyro_fallback"] is True and on["by"] == "one fit" and on["median_deg"] > COMPASS_DISAGREE_DEG
    line = [w for w in r.info["warnings"] if "decision L182" in w]
    assert len(line) == 1 and "L280" in line[0]
