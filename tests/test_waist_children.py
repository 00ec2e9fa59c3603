"""Session 23 trial `peds`: children's gait on the waist pipelines (docs/decisions/waist.md W113-W116). A three-year
old steps at ~3.3-3.9 Hz: W16's fixed 0.3 s shortest step dropped every other step (W113: relative to the session's
rhythm); the W98 / W99 lines blamed wheelchairs and phantom contacts for missed steps (W114); a missing height_m
became 1.70 m although the sensor height says ~1 m (W115: named in the warning); W100's walk-ratio band warned on
every child (W116: scaled with stature)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.kernels import waist as K
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.steps.waist_ic import WaistICStepDetector
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import calibration as C
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.params import DEFAULT_HEIGHT_M, LEG_PER_HEIGHT, SLOPE_PER_HEIGHT, default_params, subject_height
from pdrlearn.waist.plausibility import (
    WALK_RATIO_BAND,
    not_alternating_message,
    walk_ratio_message,
    walk_ratio_scale,
)


def _toddler(step_time_s: float = 0.28, seed: int = 951):
    """A simulated ~3-year-old (0.95 m, leg 0.45 m, 0.36 m steps) stepping every ``step_time_s`` (0.28 s: 214
    steps/min), body lengths scaled from user ``seed`` as the trial's mk.py, 100 Hz."""
    b = UserProfile.from_seed(seed)
    r = 0.95 / b.height_m
    u = dataclasses.replace(b, height_m=0.95, leg_length_m=0.45, sensor_height_m=0.53, foot_length_m=0.144,
                            step_length_m=0.36, step_time_s=step_time_s, step_width_m=b.step_width_m * r,
                            swing_height_m=b.swing_height_m * r, pelvis_bounce_m=b.pelvis_bounce_m * r,
                            pelvis_sway_m=b.pelvis_sway_m * r, impact_speed_mps=b.impact_speed_mps * np.sqrt(r))
    return simulate_path([Stand(3), Straight(15), Stand(3)], u, speed="normal", rate_hz=100, seed=seed)


@pytest.fixture(scope="module")
def toddler():
    return _toddler()


def test_step_period_is_the_first_dominant_autocorrelation_peak():
    fs = 100.0
    t = np.arange(0, 20, 1 / fs)
    for f in (1.8, 3.3):  # an adult's and a toddler's step frequency
        assert K.step_period_s(np.sin(2 * np.pi * f * t), fs) == pytest.approx(1 / f, abs=1.5 / fs)
    # a stride peak (asymmetric steps) higher than the step peak still gives the step
    x = np.sin(2 * np.pi * 2.0 * t) + 0.4 * np.sin(2 * np.pi * 1.0 * t)
    assert K.step_period_s(x, fs) == pytest.approx(0.5, abs=2 / fs)
    assert np.isnan(K.step_period_s(np.zeros(t.size), fs))


def test_shortest_step_is_w16s_at_150_steps_per_min_and_slower():
    assert K.shortest_step_s(0.55) == K.SHORTEST_STEP_S == 0.3
    assert K.shortest_step_s(0.4) == pytest.approx(0.3)
    assert K.shortest_step_s(0.28) == pytest.approx(0.21)
    assert K.shortest_step_s(float("nan")) == 0.3
    assert K.relative_min_gap(np.array([0, 28, 56, 84, 112]), 100.0) == 21
    assert K.relative_min_gap(np.array([0, 50]), 100.0) == 30  # too few steps: W16's


def test_waist_ic_finds_a_toddlers_steps(toddler):
    """On main (fixed 0.3 s) the detector found about half of them (the trial: 22 of 51 at this cadence)."""
    m = step_metrics(WaistICStepDetector().detect(toddler), toddler)
    assert m["step_recall"] >= 0.95 and m["step_precision"] >= 0.95
    w16 = step_metrics(WaistICStepDetector(min_step_s=0.3).detect(toddler), toddler)
    assert w16["step_recall"] < 0.75  # the option keeps W16's detector


def test_realtime_waist_ic_finds_more_of_a_toddlers_steps(toddler):
    """W31's decisions with the relative repeat check: more than W16's (not all: the decided ICs jitter, W113)."""
    live = step_metrics(WaistICStepDetector(delay_s=1.75).detect(toddler), toddler)
    w16 = step_metrics(WaistICStepDetector(delay_s=1.75, min_step_s=0.3).detect(toddler), toddler)
    assert live["step_recall"] > w16["step_recall"] + 0.2


def test_missed_steps_are_not_blamed_on_wheelchairs():
    missed = not_alternating_message(0.2, 20, (22, 51))
    assert "misses steps" in missed and "W114" in missed and "wheelchair" not in missed
    assert "wheelchair" in not_alternating_message(0.2, 20, (51, 22))
    assert "wheelchair" in not_alternating_message(0.2, 20, None)


def test_calibrate_count_line_names_missed_steps(monkeypatch, toddler):
    monkeypatch.setattr(C, "step_counts", lambda s, ev: (22, 51))
    line = C.step_count_check(toddler, np.arange(22.0))
    assert "fewer contacts than pelvic-gyro steps" in line and "phantom" not in line and "W554" in line
    monkeypatch.setattr(C, "step_counts", lambda s, ev: (51, 22))
    assert "phantom contacts" in C.step_count_check(toddler, np.arange(51.0))


def test_a_missing_height_names_the_one_the_sensor_height_implies():
    meta = {"subject": {"sensor_height_m": 0.57}}
    h, line = subject_height(meta)
    assert h == DEFAULT_HEIGHT_M and "implies about 1.08 m" in line and "W115" in line
    h, line = subject_height(meta, infer=True)  # the option (W115 failed its rule)
    assert h == pytest.approx(0.57 / LEG_PER_HEIGHT) and "inferred" in line
    assert subject_height({"subject": {"height_m": 1.2, "sensor_height_m": 0.57}}) == (1.2, None)
    assert subject_height({}) == (DEFAULT_HEIGHT_M, "meta.json gives no subject height: assumed 1.7 m")


def test_infer_height_option_sets_the_step_length_line(toddler):
    s = dataclasses.replace(toddler, meta={k: v for k, v in toddler.meta.items() if k != "height_m"})
    p, _ = default_params(s, infer_height=True)
    assert p.a_walk == pytest.approx(SLOPE_PER_HEIGHT * toddler.meta["leg_length_m"] / LEG_PER_HEIGHT)
    p, warnings = default_params(s)
    assert p.a_walk == pytest.approx(SLOPE_PER_HEIGHT * DEFAULT_HEIGHT_M)
    assert any("implies about" in w for w in warnings)


def test_walk_ratio_band_scales_with_stature():
    assert walk_ratio_scale(1.70) == pytest.approx(1.0)
    assert walk_ratio_scale(0.95) == pytest.approx((0.95 / 1.70) ** 1.5)
    # a three-year-old's 0.36 m steps at 198 steps/min (WR 0.0018): an adult's band warns, a child's does not
    assert walk_ratio_message(0.0018, 40, 0.36, 198.0, 1.70) is not None
    assert walk_ratio_message(0.0018, 40, 0.36, 198.0, 0.95) is None
    assert walk_ratio_message(WALK_RATIO_BAND[0] * walk_ratio_scale(0.95) * 0.99, 40, 0.2, 198.0, 0.95) is not None


def test_a_toddlers_uncalibrated_track_has_no_walk_ratio_warning(toddler):
    r = track_waist(toddler, pipeline="waist-pendulum")
    assert r.info["walk_ratio"] is not None
    assert not any("decision W100" in w or "W116" in w for w in r.info["warnings"])


def test_pll_range_follows_a_fast_rhythm_only():
    """W117: 2.4 Hz and slower (and no rhythm) keep steps decision 6's 1.8 / 3.2 Hz; faster free-runs at the rhythm,
    clamped at 1 / 0.75 of it."""
    assert K.pll_range(0.5) == K.pll_range(1 / 2.4) == K.pll_range(float("nan")) == (1.8, 3.2)
    f0, f_max = K.pll_range(0.28)
    assert f0 == pytest.approx(1 / 0.28) and f_max == pytest.approx(1 / 0.21)


def test_pll_range_locks_on_a_toddler_by_default(toddler):
    """W117: a 3.6 Hz toddler is past the 3.2 Hz clamp; the rhythm-relative range (the default, also in the
    waist-pll pipeline) finds its steps."""
    from pdrlearn.steps import PLLStepDetector

    rec = {fm: step_metrics(PLLStepDetector(f_max_hz=fm).detect(toddler), toddler)["step_recall"]
           for fm in (3.2, None)}
    assert rec[None] >= 0.95 and rec[3.2] < 0.9, rec
    assert PLLStepDetector().f_max_hz is None
    assert track_waist(toddler, pipeline="waist-pll").summary(toddler)["step_recall"] >= 0.95


def test_dimensionless_line_is_todays_at_the_reference_leg_and_scales_the_frequency():
    """W118: the line read at f sqrt(L / L0); L0 = 0.53 x 1.70 m (a 1.70 m adult without a leg length: today's)."""
    from pdrlearn.waist.params import SL_LEG_REF_M, WaistParams, line_leg_m
    from pdrlearn.waist.steplength import frequency_lengths

    assert line_leg_m({}, DEFAULT_HEIGHT_M) == pytest.approx(SL_LEG_REF_M)
    assert line_leg_m({"leg_length_m": 0.45}, DEFAULT_HEIGHT_M) == 0.45
    line = dict(a_walk=0.25 * 0.95, b_walk=0.25 * 0.95 * 1.8 - 0.415 * 0.95, a_run=0.19, b_run=0.0)
    today, child = WaistParams(**line), WaistParams(**line, sl_leg_m=0.45)
    f = np.array([1.6, 2.0, 2.6, 3.3])
    assert np.array_equal(frequency_lengths(f, WaistParams(**line, sl_leg_m=SL_LEG_REF_M)), frequency_lengths(f, today))
    s = np.sqrt(0.45 / SL_LEG_REF_M)
    running = np.zeros(f.size, dtype=bool)
    assert np.allclose(frequency_lengths(f, child, running=running), frequency_lengths(f * s, today, running=running))
    # the 2.2 Hz cap is a dimensionless one: a 3.0 Hz child step is below it (3.0 x 0.707 = 2.12 Hz)
    assert frequency_lengths(np.array([3.0]), child, running=running[:1])[0] < frequency_lengths(
        np.array([3.1]), child, running=running[:1])[0]


def test_offset_only_calibration_fits_the_dimensionless_line():
    """W118: the calibration fit sums the walk as the tracker will, at the scaled (and capped) frequency."""
    from pdrlearn.waist.params import WaistParams
    from pdrlearn.waist.steplength import CalibrationWalk, fit_frequency, frequency_lengths

    p = WaistParams(a_walk=0.24, b_walk=0.0, sl_leg_m=0.45)
    w = CalibrationWalk(distance_m=20.0, f_hz=np.full(50, 3.0), g=np.zeros(50))
    a, b, _ = fit_frequency([w], p)
    q = WaistParams(a_walk=a, b_walk=b, sl_leg_m=0.45)
    assert frequency_lengths(w.f_hz, q, running=np.zeros(50, dtype=bool)).sum() == pytest.approx(20.0)
