"""mobgap SlZijlstra's step-length smoothing as an option of waist-pendulum (decision W56): the kernel on
hand-made step sequences, the option end to end on a simulated session (calibration sums what the tracker sums,
W21)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.waist import _kernels as K


def _steps(ics: list[float]) -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(ics, dtype=float)
    return t[:-1], t[1:]


@pytest.mark.parametrize("mode", K.LENGTH_SMOOTHING_MODES)
def test_constant_lengths_are_unchanged(mode):
    s, e = _steps([0.0, 0.55, 1.1, 1.62, 2.2, 2.71, 3.3, 3.8])
    out = K.smooth_step_lengths(s, e, np.full(7, 0.68), mode)
    np.testing.assert_allclose(out, 0.68, rtol=1e-12)


def test_hampel_replaces_the_one_outlier_by_its_window_median():
    x = np.array([0.70, 0.70, 0.71, 1.50, 0.69, 0.70, 0.70])
    # index 3: window 0.70 0.71 1.50 0.69 0.70 -> median 0.70, MAD 0.01, limit 3 x 1.4826 x 0.01 = 0.044 < 0.80
    # index 2: |0.71 - 0.70| = 0.01 < 0.044 -> kept
    np.testing.assert_allclose(K.hampel(x), [0.70, 0.70, 0.71, 0.70, 0.69, 0.70, 0.70])
    s, e = _steps([0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5])
    np.testing.assert_allclose(K.smooth_step_lengths(s, e, x, "hampel"), [0.70, 0.70, 0.71, 0.70, 0.69, 0.70, 0.70])
    # MAD 0 (mobgap's behaviour): any value off the window's median is replaced; NaN stays NaN
    np.testing.assert_allclose(K.hampel(np.array([1.0, 1.0, 1.0, 1.2, 1.0])), 1.0)
    assert np.isnan(K.hampel(np.array([1.0, np.nan, 1.0]))[1])


def test_per_second_means_and_span_means_by_hand():
    # ICs 0, 0.4, 0.9, 1.5, 2.2; per-IC values 0.6 0.8 0.7 0.9 (+ the last repeated for the last IC)
    # seconds [0,1]: (0.6 + 0.8 + 0.7) / 3 = 0.7; [1,2]: 0.9; [2,3]: 0.9
    # steps: [0,0.4] 0.7; [0.4,0.9] 0.7; [0.9,1.5] (0.1 x 0.7 + 0.5 x 0.9) / 0.6; [1.5,2.2] 0.9
    s, e = _steps([0.0, 0.4, 0.9, 1.5, 2.2])
    v = np.array([0.6, 0.8, 0.7, 0.9])
    np.testing.assert_allclose(K.per_second_means(np.append(s, e[-1]), np.append(v, v[-1]), 3), [0.7, 0.9, 0.9])
    np.testing.assert_allclose(K.smooth_step_lengths(s, e, v, "seconds"), [0.7, 0.7, 0.52 / 0.6, 0.9])


def test_a_second_without_contact_is_interpolated_and_long_gaps_are_not():
    # ICs 0, 0.9, 2.3: second [1,2] has none -> (0.75 + 0.9) / 2; step 2 = (0.1 x 0.75 + 1 x 0.825 + 0.3 x 0.9) / 1.4
    s, e = _steps([0.0, 0.9, 2.3])
    np.testing.assert_allclose(K.smooth_step_lengths(s, e, np.array([0.6, 0.9]), "seconds"),
                               [0.75, 1.17 / 1.4])
    x = np.array([1.0, np.nan, np.nan, np.nan, 2.0, np.nan, np.nan, np.nan, np.nan, 3.0, np.nan])
    out = K.interpolate_inside(x)  # 3 s filled, 4 s (> mobgap's 3 s) and the trailing edge left NaN
    np.testing.assert_allclose(out[:5], [1.0, 1.25, 1.5, 1.75, 2.0])
    assert np.isnan(out[5:9]).all() and out[9] == 3.0 and np.isnan(out[10])


def test_smoothing_is_equivariant_to_gain_and_offset():
    # the calibration solves K (and F) on the smoothed g (W56): smooth(K g + F) = K smooth(g) + F
    rng = np.random.default_rng(3)
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.4, 0.7, 30))])
    g = rng.uniform(0.5, 0.8, 30)
    g[[5, 17]] = [1.4, 0.2]
    for mode in K.LENGTH_SMOOTHING_MODES:
        a = K.smooth_step_lengths(t[:-1], t[1:], 1.13 * g + 0.04, mode)
        np.testing.assert_allclose(a, 1.13 * K.smooth_step_lengths(t[:-1], t[1:], g, mode) + 0.04, rtol=1e-12)
    sm = K.smooth_step_lengths(t[:-1], t[1:], g, "mobgap")
    assert abs(sm[5] - np.median(g)) < abs(g[5] - np.median(g))  # the outliers are pulled in
    assert abs(sm[17] - np.median(g)) < abs(g[17] - np.median(g))


def test_unknown_mode_is_refused():
    with pytest.raises(DataError, match="length_smoothing"):
        K.smooth_step_lengths(np.array([0.0]), np.array([0.5]), np.array([0.7]), "median")


@pytest.fixture(scope="module")
def sim_walks():
    from pdrlearn.sim import simulate

    return (simulate("walk", 1, "normal", rate_hz=100.0, seed=1, length_m=30.0),
            simulate("B", 1, speed="slow", rate_hz=100.0))


def test_option_end_to_end_calibration_sums_what_the_tracker_sums(sim_walks):
    from pdrlearn.track import get_pipeline
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    cal, test = sim_walks
    base, _ = resolve_params(cal, None)
    base.options = {"length_smoothing": "mobgap"}
    p = calibrate([cal], "waist-pendulum", distances=[31.5], params=base)
    st = get_pipeline("waist-pendulum")(cal, params=p).steps
    assert st["length_m"].sum() == pytest.approx(31.5, rel=1e-9)  # W21 with the smoothing on
    res = get_pipeline("waist-pendulum")(test, params=p)
    assert res.info["options"]["length_smoothing"] == "mobgap"
    off = get_pipeline("waist-pendulum")(test, params=p, length_smoothing="none").steps
    on = res.steps
    np.testing.assert_array_equal(on["event_s"], off["event_s"])  # only the lengths change
    assert not np.allclose(on["g_m"], off["g_m"])
    use = on["has_next"].to_numpy(bool) & ~on["merged"].to_numpy(bool)
    # the pendulum's K g_s + F times the turn factor (W19)
    np.testing.assert_allclose(on["length_m"].to_numpy()[use],
                               (p.k * on["g_m"] + p.f_m).to_numpy()[use]
                               * K.turning_step_factor(on["dyaw_rad"].to_numpy()[use]), rtol=1e-12)
    assert on["length_m"].sum() == pytest.approx(off["length_m"].sum(), rel=0.05)


def test_bad_option_and_realtime_are_refused(sim_walks):
    from pdrlearn.track import get_pipeline

    _, test = sim_walks
    with pytest.raises(DataError, match="not one of"):
        get_pipeline("waist-pendulum")(test, length_smoothing="median")
    with pytest.raises(DataError, match="realtime"):
        get_pipeline("waist-pendulum")(test, length_smoothing="mobgap", realtime=True)


def test_bout_error_split_into_count_and_per_step_parts_by_hand():
    # experiments/peers_bout_parts.py: 7 of 17 reference steps (17.0 m of strides, 1.0 m a step) tracked as 9.03 m
    # -> count 7/17 - 1 = -58.82 %, per-step (9.03/7)/1.0 - 1 = +29.0 %, (1 + count)(1 + step) = 9.03/17
    import sys
    from pathlib import Path

    import pandas as pd

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
    from peers_bout_parts import parts

    b = parts(pd.DataFrame({"n_steps": [7, 0], "n_reference_steps": [17, 10], "tracked_m": [9.03, 0.0],
                            "reference_strides_m": [17.0, 6.0]}))
    assert b["count_err_pct"].iloc[0] == pytest.approx(100 * (7 / 17 - 1))
    assert b["step_err_pct"].iloc[0] == pytest.approx(29.0)
    assert (1 + b["count_err_pct"].iloc[0] / 100) * (1 + b["step_err_pct"].iloc[0] / 100) == pytest.approx(9.03 / 17)
    assert b["count_err_pct"].iloc[1] == -100.0 and np.isnan(b["step_err_pct"].iloc[1])  # no step: no per-step part
