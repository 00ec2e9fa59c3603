"""Decision W261's gate, option ``cadence_law: "steady"``: W240's cadence-law factor only on steady walking steps --
a step closing four steps of one walking sequence whose stride times vary by at most 10 % (CV) at a median cadence
inside seed 000's linear walking range 1.5-2.2 Hz. The gate on hand-made step times, then the option end to end."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.waist.steplength import STEADY_MAX_CV, STEADY_WINDOW_STEPS, steady_steps


def _walk(n: int, step_s: float = 0.55) -> tuple[np.ndarray, np.ndarray]:
    """``n`` steps of one walking sequence plus its closing row (no next contact, no step time)."""
    return np.append(np.full(n, step_s), np.nan), np.append(np.ones(n, dtype=bool), False)


def test_a_steady_sequence_is_steady_from_its_fourth_step():
    t, h = _walk(8)
    out = steady_steps(t, h)
    assert STEADY_WINDOW_STEPS == 4
    # the first three steps (seed 004's two acceleration steps inside them) and the closing row never
    np.testing.assert_array_equal(out, [False, False, False, True, True, True, True, True, False])


def test_an_irregular_step_makes_the_windows_holding_it_unsteady():
    t, h = _walk(10)
    t[5] = 0.80  # a long step: strides 1.10, 1.35, 1.35 -> CV ~0.12 > 0.10
    out = steady_steps(t, h)
    np.testing.assert_array_equal(out[:10], [False, False, False, True, True, False, False, False, False, True])


def test_the_threshold_is_on_the_strides_cv():
    # strides (s): 1.0, 1.1, 1.2 -> CV 0.1 / 1.1 = 0.0909 (steady); 1.0, 1.12, 1.24 -> 0.12 / 1.12 = 0.107 (not)
    for steps, steady in (([0.5, 0.5, 0.6, 0.6], True), ([0.5, 0.5, 0.62, 0.62], False)):
        t, h = np.append(steps, np.nan), np.array([True] * 4 + [False])
        strides = np.array(steps[1:]) + np.array(steps[:-1])
        assert bool(strides.std(ddof=1) / strides.mean() <= STEADY_MAX_CV) is steady
        assert bool(steady_steps(t, h)[3]) is steady


def test_left_right_alternation_of_the_step_time_is_not_unsteadiness():
    t = np.array([0.50, 0.62] * 4)  # a steady asymmetric gait (W250): every stride 1.12 s
    out = steady_steps(t, np.ones(8, dtype=bool))
    assert out[3:].all()


def test_no_window_crosses_the_end_of_a_sequence():
    t = np.array([0.55, 0.55, 0.55, np.nan, 0.55, 0.55, 0.55, 0.55])
    h = np.array([True, True, True, False, True, True, True, True])
    np.testing.assert_array_equal(steady_steps(t, h), [False] * 7 + [True])


@pytest.mark.parametrize("step_s, steady", [(1 / 1.45, False), (1 / 1.55, True), (1 / 2.15, True), (1 / 2.3, False)])
def test_the_window_cadence_lies_in_seed_000s_walking_range(step_s, steady):
    t, h = _walk(4, step_s)
    assert bool(steady_steps(t, h)[3]) is steady


def test_the_cadence_is_the_dimensionless_frequency_w118():
    t, h = _walk(4, 1 / 1.45)  # 1.45 Hz, read at 1.45 x 1.1 = 1.6 Hz for a longer leg's frequency scale
    assert not steady_steps(t, h)[3] and steady_steps(t, h, frequency_scale=1.1)[3]


def test_the_gate_is_causal_a_later_step_changes_no_earlier_verdict():
    t, h = _walk(12)
    t[:12][np.arange(12) % 3 == 0] = 0.6
    t[7] = 0.9  # an irregular step: the windows closing at steps 7-10 hold it (stride CVs 0.11-0.14)
    full = steady_steps(t, h)
    np.testing.assert_array_equal(full, [False] * 3 + [True] * 4 + [False] * 4 + [True, False])
    for k in range(4, 13):
        np.testing.assert_array_equal(steady_steps(t[:k], h[:k]), full[:k])


@pytest.fixture(scope="module")
def walkways():
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

    user = UserProfile.from_seed(6379)

    def walk(v: float, seed: int):  # W211's walkways: the trial's step length / time per speed
        length = 0.42 + 0.3 * (v - 0.6)
        u = dataclasses.replace(user, step_length_m=length, step_time_s=length / v)
        return simulate_path([Stand(2), Straight(20), Stand(2)], u, speed="normal", rate_hz=100, seed=seed,
                             bounce="pendulum")

    return walk(1.0, 6379), walk(1.4, 7379)


def test_only_steady_steps_are_scaled_by_w240s_factor(walkways):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.steplength import cadence_law_factor, calibration_cadence_hz

    cal, fast = walkways
    p = calibrate([cal], "waist-pendulum", distances=[20.0])
    off = track_waist(fast, pipeline="waist-pendulum", params=p)
    law = track_waist(fast, pipeline="waist-pendulum", params=p, cadence_law=True)
    on = track_waist(fast, pipeline="waist-pendulum", params=p, cadence_law="steady")
    st = on.steps
    steady = steady_steps(1.0 / st["frequency_hz"].to_numpy(float), st["has_next"].to_numpy(bool),
                          frequency_scale=p.frequency_scale())
    fac = st["cadence_factor"].to_numpy(float)
    assert steady.sum() >= 10 and (~steady & st["has_next"].to_numpy(bool)).sum() >= 3  # both kinds of step
    law_fac = cadence_law_factor(st["frequency_hz"].to_numpy(float), calibration_cadence_hz(p), p)
    np.testing.assert_allclose(fac[steady], law_fac[steady])  # W240's factor where steady
    np.testing.assert_array_equal(fac[~steady], 1.0)  # the calibrated pendulum as it is elsewhere
    assert np.median(fac[steady]) > 1.0  # 1.4 m/s is faster than the 1.0 m/s calibration
    np.testing.assert_allclose(st["length_m"], off.steps["length_m"] * fac)
    assert off.steps["length_m"].sum() < on.steps["length_m"].sum() < law.steps["length_m"].sum()


def test_calibration_with_steady_sums_its_walk_w21(walkways):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    cal, _ = walkways
    base, _ = resolve_params(cal, None)
    base.options = {"cadence_law": "steady"}
    p = calibrate([cal], "waist-pendulum", distances=[20.0], params=base)
    res = track_waist(cal, pipeline="waist-pendulum", params=p)  # the value from the PARAMS.json's options
    assert res.info["options"]["cadence_law"] == "steady"
    fac = res.steps["cadence_factor"].to_numpy(float)
    assert (fac != 1.0).any() and (fac == 1.0).any()
    assert res.steps["length_m"].sum() == pytest.approx(20.0, rel=1e-6)


def test_realtime_gates_as_offline_and_the_live_tracker_names_it_unapplied(walkways):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.live import unapplied_options_line

    cal, fast = walkways
    p = calibrate([cal], "waist-pendulum", distances=[20.0])
    rt = track_waist(fast, pipeline="waist-pendulum", params=p, realtime=True, cadence_law="steady")
    st = rt.steps
    steady = steady_steps(1.0 / st["frequency_hz"].to_numpy(float), st["has_next"].to_numpy(bool),
                          frequency_scale=p.frequency_scale())
    assert steady.any() and (st["cadence_factor"].to_numpy(float)[~steady] == 1.0).all()
    assert np.median(st["cadence_factor"].to_numpy(float)[steady]) > 1.0
    line = unapplied_options_line(dataclasses.replace(p, options={"cadence_law": "steady"}))
    assert line is not None and 'cadence_law="steady"' in line and "E107" in line


def test_a_bad_value_is_refused_in_one_line(walkways):
    from pdrlearn.errors import DataError
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    cal, _ = walkways
    with pytest.raises(DataError, match=r"cadence_law 'steadily' is not one of false, true, \"steady\" "
                                        r"\(decisions W240, W261\)") as exc:
        track_waist(cal, pipeline="waist-pendulum", cadence_law="steadily")
    assert "\n" not in str(exc.value)
    base, _ = resolve_params(cal, None)
    base.options = {"cadence_law": "false"}  # B199: a quoted false is no flag
    with pytest.raises(DataError, match="cadence_law"):
        track_waist(cal, pipeline="waist-pendulum", params=base)
