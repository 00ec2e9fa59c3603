"""Decision W240's candidate, option ``cadence_law`` (off by default: its adoption rule was not met): a calibrated
waist-pendulum step times ``sqrt(SL(f) / SL(f_cal))``, seed 000's walking line at the step's and the calibration
walks' median step frequency held inside 1.5-2.2 Hz -- the factor by hand, the option end to end on simulated
walkways (only calibrated pendulum lengths change, by exactly the factor; calibration sums what the tracker sums,
W21), and where it does nothing."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.steplength import WALK_MAX_HZ, WALK_MIN_HZ, cadence_law_factor, calibration_cadence_hz


def _params(**kw) -> WaistParams:
    height = 1.70  # W6's line for 1.70 m: slope 0.25 x height per Hz, 0.415 x height at 1.8 Hz
    a = 0.25 * height
    return WaistParams(leg_m=0.9, k=1.0, f_m=0.0, a_walk=a, b_walk=a * 1.8 - 0.415 * height, a_run=1.0, b_run=1.0,
                       **kw)


def test_factor_by_hand_inside_and_outside_seed_000s_linear_range():
    p = _params()
    line = lambda f: p.a_walk * f - p.b_walk  # noqa: E731  (seed 000 sec. II-D)
    f = np.array([1.8, 1.6, 2.0, 1.2, 3.0, np.nan])
    out = cadence_law_factor(f, 1.8, p)
    np.testing.assert_allclose(out, [1.0,  # at the calibration cadence: the pendulum as it is
                                     math.sqrt(line(1.6) / line(1.8)),  # a slower step is shortened
                                     math.sqrt(line(2.0) / line(1.8)),  # a faster one lengthened
                                     math.sqrt(line(WALK_MIN_HZ) / line(1.8)),  # below the seed's range: held at 1.5 Hz
                                     math.sqrt(line(WALK_MAX_HZ) / line(1.8)),  # above it: at 2.2 Hz (W37)
                                     1.0])  # no frequency: unchanged
    assert out[1] == pytest.approx(0.938, abs=1e-3)  # half the line's change: the geometric mean of the two models
    # a calibration cadence below the range is held too
    assert cadence_law_factor(np.array([1.5]), 1.0, p)[0] == pytest.approx(1.0)


def test_no_calibration_cadence_no_change():
    p = _params()
    np.testing.assert_array_equal(cadence_law_factor(np.array([1.2, 2.0]), None, p), [1.0, 1.0])
    assert calibration_cadence_hz(p) is None  # defaults: no calibration walks
    assert calibration_cadence_hz(_params(source="calibrated", gait={"median_cadence_spm": 108.0})) == 1.8
    nan_line = dataclasses.replace(p, a_walk=float("nan"))
    np.testing.assert_array_equal(cadence_law_factor(np.array([1.2]), 1.8, nan_line), [1.0])


@pytest.fixture(scope="module")
def walkways():
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

    user = UserProfile.from_seed(5919)

    def walk(v: float, seed: int):  # W211's walkways: the trial's step length / time per speed
        length = 0.42 + 0.3 * (v - 0.6)
        u = dataclasses.replace(user, step_length_m=length, step_time_s=length / v)
        return simulate_path([Stand(2), Straight(20), Stand(2)], u, speed="normal", rate_hz=100, seed=seed,
                             bounce="pendulum")

    return walk(1.0, 5919), walk(0.6, 6919)


def test_calibrated_slow_walk_shortened_by_exactly_the_factor(walkways):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate

    cal, slow = walkways
    p = calibrate([cal], "waist-pendulum", distances=[20.0])
    off = track_waist(slow, pipeline="waist-pendulum", params=p)
    on = track_waist(slow, pipeline="waist-pendulum", params=p, cadence_law=True)
    assert "cadence_factor" not in off.steps and "cadence_factor" in on.steps
    fac = on.steps["cadence_factor"].to_numpy(float)
    np.testing.assert_allclose(on.steps["length_m"], off.steps["length_m"] * fac)
    walking = on.steps["has_next"].to_numpy(bool)
    assert (fac[walking] < 1.0).mean() > 0.8  # 0.6 m/s is slower than the 1.0 m/s calibration
    assert on.steps["length_m"].sum() < off.steps["length_m"].sum()
    # uncalibrated: no calibration cadence, nothing changes
    plain = track_waist(slow, pipeline="waist-pendulum")
    plain_on = track_waist(slow, pipeline="waist-pendulum", cadence_law=True)
    np.testing.assert_allclose(plain_on.steps["length_m"], plain.steps["length_m"])


def test_calibration_with_the_option_sums_the_walk_w21(walkways):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    cal, _ = walkways
    base, _ = resolve_params(cal, None)
    base.options = {"cadence_law": True}
    p = calibrate([cal], "waist-pendulum", distances=[20.0], params=base)
    res = track_waist(cal, pipeline="waist-pendulum", params=p)  # the option from the PARAMS.json's options
    assert "cadence_factor" in res.steps
    assert res.steps["length_m"].sum() == pytest.approx(20.0, rel=1e-6)


def test_waist_pll_names_the_option_as_ignored(walkways):
    from pdrlearn.track.waist import track_waist

    cal, _ = walkways
    res = track_waist(cal, pipeline="waist-pll", cadence_law=True)
    assert "cadence_factor" not in res.steps
    assert any("cadence_law=true applies to calibrated waist-pendulum tracks (W240)" in w
               for w in res.info["warnings"])


def test_realtime_applies_it_and_the_live_tracker_names_it_unapplied(walkways):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.live import unapplied_options_line

    cal, slow = walkways
    p = calibrate([cal], "waist-pendulum", distances=[20.0])
    on = track_waist(slow, pipeline="waist-pendulum", params=p, realtime=True, cadence_law=True)
    assert (on.steps["cadence_factor"] < 1.0).any()
    line = unapplied_options_line(dataclasses.replace(p, options={"cadence_law": True}))
    assert line is not None and "cadence_law=true" in line and "E107" in line


def test_a_non_flag_value_is_refused_in_one_line(walkways):
    from pdrlearn.errors import DataError
    from pdrlearn.track.waist import track_waist

    cal, _ = walkways
    with pytest.raises(DataError, match="cadence_law") as exc:
        track_waist(cal, pipeline="waist-pendulum", cadence_law="yes")
    assert "\n" not in str(exc.value)
