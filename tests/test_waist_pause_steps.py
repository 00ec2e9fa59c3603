"""A step that spans a pause keeps one local period's length (decision W111, ``pause_steps``): the kernel on
hand-made step durations, the option end to end on a simulated turn on the spot (calibration sums what the
tracker sums, W21; the realtime detector ignores it). Decision W122, ``pause_steps="progression"``: a step with a
standstill in it keeps at most the trunk's horizontal travel over it (the kernels by hand, the option end to end);
W123: an unknown value is refused. Decision W134, ``pause_steps="standing"``: W122 only for a still run of half a
local step period inside a walk (not its first or last step); W135: the refusal names it."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.waist import _kernels as K


def _factor(durations, use=None, closes=None):
    d = np.asarray(durations, dtype=float)
    use = np.ones(d.size, bool) if use is None else np.asarray(use, bool)
    closes = np.zeros(d.size, bool) if closes is None else np.asarray(closes, bool)
    return K.pause_step_factor(d, use, closes)


def test_a_step_over_one_and_a_half_periods_keeps_one_period():
    # local period 0.5 s on both sides; 1.2 s > 1.5 x 0.5 -> 0.5 / 1.2; the closing contact (no length) stays 1
    out = _factor([0.5, 0.5, 0.5, 1.2, 0.5, 0.5, 0.5, 0.0], use=[True] * 7 + [False], closes=[False] * 7 + [True])
    np.testing.assert_allclose(out, [1, 1, 1, 0.5 / 1.2, 1, 1, 1, 1])


def test_the_period_is_the_median_of_both_sides_and_needs_two_steps_on_a_side():
    # before: 0.4 0.5 0.6 -> 0.5; after: 0.7 0.7 -> 0.7; period median(0.5, 0.7) = 0.6; 1.0 > 0.9 -> 0.6
    np.testing.assert_allclose(_factor([0.4, 0.5, 0.6, 1.0, 0.7, 0.7])[3], 0.6)
    # exactly 1.5 periods is no pause (W18's gap rule is "over 1.5")
    assert _factor([0.5, 0.5, 0.75, 0.5, 0.5])[2] == 1.0
    # one step on each side is no local period: nothing changes
    np.testing.assert_array_equal(_factor([0.5, 1.5, 0.5]), 1.0)


def test_other_sequences_and_fragments_do_not_set_the_period():
    # two sequences: the second's slow steps are not the first's period, and the first's steps are not the second's
    d = [0.5, 0.5, 0.5, 0.0, 1.0, 1.0, 1.0, 1.0]
    closes = [False, False, False, True, False, False, False, False]
    use = [True, True, True, False, True, True, True, True]
    np.testing.assert_array_equal(_factor(d, use, closes), 1.0)
    # a W27 fragment (0.1 s, no length of its own) neither is scaled nor shortens the period
    # (counted, the period before row 2 would be median(0.5, 0.1) = 0.3 and the factor 0.4 / 0.8)
    out = _factor([0.5, 0.1, 0.8, 0.5, 0.5], use=[True, False, True, True, True])
    np.testing.assert_allclose(out, [1, 1, 0.5 / 0.8, 1, 1])


@pytest.fixture(scope="module")
def turn_walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    route = parse_route("straight:6, turn:180, straight:6")
    return simulate_path(route, UserProfile.from_seed(993), rate_hz=100, seed=993)


def test_option_end_to_end_on_a_turn_on_the_spot(turn_walk):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    off = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps=False).steps
    on = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps=True).steps
    np.testing.assert_array_equal(on["event_s"], off["event_s"])  # only the lengths change
    f = on["pause_factor"].to_numpy(float)
    assert (f < 1).any() and (f <= 1).all()
    np.testing.assert_allclose(on["length_m"], off["length_m"] * f, rtol=1e-12)
    # the shortened steps are the long intervals at the turn, not the walking ones
    dur = (on["end_s"] - on["start_s"]).to_numpy(float)
    assert dur[f < 1].min() > 1.5 * np.median(dur[on["has_next"].to_numpy(bool)])
    # W21: calibrated with the option on, tracking the calibration walk sums to its distance
    base, _ = resolve_params(turn_walk, None)
    base.options = {"pause_steps": True}
    p = calibrate([turn_walk], "waist-pendulum", distances=[12.0], params=base)
    assert track_waist(turn_walk, pipeline="waist-pendulum", params=p).steps["length_m"].sum() == pytest.approx(
        12.0, rel=1e-9)
    # the realtime detector does not look ahead: the option changes nothing there
    rt = track_waist(turn_walk, pipeline="waist-pendulum", realtime=True, pause_steps=True).steps
    assert "pause_factor" not in rt


# decision W122: pause_steps="progression" -- a step with a standstill keeps at most the trunk's travel over it


def test_still_displacement_integrates_from_zero_velocity_in_the_standstill():
    fs = 100.0
    # 0.5 s braking from 1 m/s along x (-2 m/s^2), 0.3 s still, 0.5 s speeding up to 1 m/s along y (+2 m/s^2):
    # 0.25 m along x, then 0.25 m along y -> |d| = 0.25 sqrt(2)
    a = np.zeros((131, 2))
    a[:50, 0], a[81:, 1] = -2.0, 2.0
    still = np.zeros(131, bool)
    still[52:79] = True
    assert K.still_displacement(a, still, fs, 0, 130) == pytest.approx(0.25 * np.sqrt(2), rel=0.03)
    # only speeding up after the standstill: 0.5 a t^2 = 0.25 m
    assert K.still_displacement(a, still, fs, 52, 130) == pytest.approx(0.25, rel=0.03)
    # the zero velocity is the middle of the LONGEST still run: a one-sample "still" while moving is not it
    # (taken as zero there, the velocity before and after it would be off by 0.6 m/s: 0.58 m)
    one = still.copy()
    one[20] = True
    assert K.still_displacement(a, one, fs, 0, 130) == pytest.approx(0.25 * np.sqrt(2), rel=0.03)
    # no still sample in the step: no displacement (the walker never stopped)
    assert np.isnan(K.still_displacement(a, still, fs, 0, 40))


def test_progression_factor_caps_at_one_and_leaves_steps_without_a_standstill():
    out = K.progression_factor([0.1, 0.9, np.nan, 0.1], [0.5, 0.5, 0.5, 0.0])
    np.testing.assert_allclose(out, [0.2, 1.0, 1.0, 1.0])


def test_progression_option_end_to_end_on_a_turn_on_the_spot(turn_walk):
    from pdrlearn.signal.conditioning import standstill_mask
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.ahrs import waist_imu

    off = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps=False).steps
    on = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps="progression").steps
    np.testing.assert_array_equal(on["event_s"], off["event_s"])  # only the lengths change
    f = on["pause_factor"].to_numpy(float)
    np.testing.assert_allclose(on["length_m"], off["length_m"] * f, rtol=1e-12)
    # exactly the steps with a standstill in them are shortened
    imu = waist_imu(turn_walk)
    still = standstill_mask(imu.acc_nav, imu.gyr_nav, imu.fs)
    t = imu.t
    has_still = np.array([bool(r.has_next) and still[(t >= r.start_s) & (t <= r.end_s)].any()
                          for r in on.itertuples()])
    assert has_still.any() and (f[has_still] < 1).all() and (f[~has_still] == 1).all()
    # and they come nearer the unit's own travel (the simulated waist path from contact to contact)
    tr = turn_walk.trajectory

    def travel(a, b):
        seg = tr[(tr["t"] >= a) & (tr["t"] <= b)]
        return float(np.hypot(seg["x"].iloc[-1] - seg["x"].iloc[0], seg["y"].iloc[-1] - seg["y"].iloc[0]))

    # (the stop before the turn 0.07 m, the restart 0.40 m: W111's one period gives 0.25 / 0.27 m, off 0.63 / 0.60 m)
    true = np.array([travel(r.start_s, r.end_s) for r in on[has_still].itertuples()])
    np.testing.assert_allclose(on["length_m"].to_numpy(float)[has_still], true, atol=0.05)
    assert (np.abs(off["length_m"].to_numpy(float)[has_still] - true) > 0.1).all()
    # the realtime detector keeps it off (as W111)
    rt = track_waist(turn_walk, pipeline="waist-pendulum", realtime=True, pause_steps="progression").steps
    assert "pause_factor" not in rt


def test_an_unknown_pause_steps_value_is_refused_in_one_line(turn_walk):
    from pdrlearn.errors import DataError
    from pdrlearn.track.waist import track_waist

    with pytest.raises(DataError, match=r"pause_steps 'Progression' is not one of false, true, \"progression\"") as e:
        track_waist(turn_walk, pipeline="waist-pendulum", pause_steps="Progression")
    assert "\n" not in str(e.value) and "W122" in str(e.value)


# decision W134: pause_steps="standing" -- W122's trunk travel only for a stand of half a local period inside a walk


def _standing(run_s, durations, use=None, closes=None):
    d = np.asarray(durations, dtype=float)
    use = np.ones(d.size, bool) if use is None else np.asarray(use, bool)
    closes = np.zeros(d.size, bool) if closes is None else np.asarray(closes, bool)
    return K.standing_step_mask(np.asarray(run_s, dtype=float), d, use, closes)


def test_longest_still_run_is_in_sample_indices_of_the_whole_signal():
    still = np.zeros(50, bool)
    still[12:15] = still[20:30] = still[40:45] = True
    assert K.longest_still_run(still, 10, 49) == (20, 30)
    assert K.longest_still_run(still, 25, 49) == (25, 30)  # clipped to the step: 5 samples, the first of equals
    assert K.longest_still_run(still, 0, 11) is None


def test_a_stand_is_half_a_local_period_of_stillness_inside_the_walk():
    n = np.nan
    # period 0.5 s everywhere; still runs 0.25 s (half: a stand), 0.24 s (a slow phase), none
    run = [n, n, n, 0.25, n, 0.24, n, n, n]
    np.testing.assert_array_equal(_standing(run, [0.5] * 9), [0, 0, 0, 1, 0, 0, 0, 0, 0])
    # the walk's first and last steps are never a stand, however long their stillness (quiet standing next to them)
    run = [2.0, n, n, n, n, n, n, n, 2.0]
    assert not _standing(run, [0.6] * 9).any()
    # the last step with a length, not the closing contact, is the walk's last step
    run = [n, n, n, n, n, n, n, 2.0, n]
    closes = [False] * 8 + [True]
    use = [True] * 8 + [False]
    assert not _standing(run, [0.6] * 8 + [0.0], use, closes).any()
    # without a local period (one step on a side) nothing is a stand
    assert not _standing([n, 2.0, n], [0.6, 0.6, 0.6]).any()


def test_the_half_period_is_the_local_one():
    # a stand of 0.4 s among 1.0 s steps (elderly, slow) is under half a period; among 0.5 s steps it is one
    run = [np.nan] * 3 + [0.4] + [np.nan] * 3
    assert not _standing(run, [1.0] * 7).any()
    assert _standing(run, [0.5] * 7)[3]


def test_standing_option_end_to_end_keeps_the_walk_edges_and_shortens_the_stand(turn_walk):
    from pdrlearn.track.waist import track_waist

    off = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps=False).steps
    prog = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps="progression").steps
    on = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps="standing").steps
    np.testing.assert_array_equal(on["event_s"], off["event_s"])  # only the lengths change
    f, fp = on["pause_factor"].to_numpy(float), prog["pause_factor"].to_numpy(float)
    # each step it shortens, it shortens as W122 does; it shortens some (the stop before the turn on the spot)
    np.testing.assert_allclose(f[f < 1], fp[f < 1], rtol=1e-12)
    assert (f < 1).any()
    # and never a walk's first or last step
    has = on["has_next"].to_numpy(bool)
    use = has & ~on["merged"].to_numpy(bool)
    seq = np.concatenate([[0], np.cumsum(~has)[:-1]])
    for sid in np.unique(seq[use]):
        rows = np.flatnonzero(use & (seq == sid))
        assert f[rows[0]] == 1.0 and f[rows[-1]] == 1.0
    # W165: the realtime detector applies it too (its own contacts), never to a walk's edge either
    rt = track_waist(turn_walk, pipeline="waist-pendulum", realtime=True, pause_steps="standing").steps
    fr, has = rt["pause_factor"].to_numpy(), rt["has_next"].to_numpy(bool)
    use = has & ~rt["merged"].to_numpy(bool)
    seq = np.concatenate([[0], np.cumsum(~has)[:-1]])
    for sid in np.unique(seq[use]):
        rows = np.flatnonzero(use & (seq == sid))
        assert fr[rows[0]] == 1.0 and fr[rows[-1]] == 1.0


def test_a_real_walks_slow_second_step_is_no_stand():
    """W122 shortened MS001 Test5 Trial1's second step (6.76-7.39 s, inside the reference bout) to 0.11 of its
    length: a 0.05 s still run next to gait initiation. W134 leaves it (and every step of the walk) whole."""
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_MS001_Test5_Trial1"))
    prog = track_waist(s, pipeline="waist-pendulum", pause_steps="progression").steps
    on = track_waist(s, pipeline="waist-pendulum", pause_steps="standing").steps
    second = (prog["start_s"] > 6.7) & (prog["start_s"] < 6.8)
    assert second.sum() == 1 and float(prog.loc[second, "pause_factor"].iloc[0]) < 0.2
    assert (on["pause_factor"] == 1.0).all()


def test_an_unknown_pause_steps_value_names_standing(turn_walk):
    from pdrlearn.errors import DataError
    from pdrlearn.track.waist import track_waist

    with pytest.raises(DataError, match=r"not one of false, true, \"progression\", \"standing\" \(decisions W111, "
                       r"W122, W134\)") as e:
        track_waist(turn_walk, pipeline="waist-pendulum", pause_steps="Standing")
    assert "\n" not in str(e.value)


def test_standing_is_the_offline_pendulum_default_and_calibration_sums_with_it(turn_walk):
    """W134's rule held (experiments/results/waist_standing_steps.txt): the offline pendulum's default; calibrated
    with the defaults, tracking the calibration walk sums to its distance (W21)."""
    from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
    from pdrlearn.waist.calibration import calibrate

    assert OPTION_DEFAULTS["pause_steps"] == "standing"
    default = track_waist(turn_walk, pipeline="waist-pendulum").steps
    on = track_waist(turn_walk, pipeline="waist-pendulum", pause_steps="standing").steps
    pd_testing = pytest.importorskip("pandas").testing
    pd_testing.assert_frame_equal(default, on)
    assert (default["pause_factor"] < 1).any()
    p = calibrate([turn_walk], "waist-pendulum", distances=[12.0])
    # within 0.2 %, not exactly: a stand step keeps min(length, trunk travel), and calibration holds the factor the
    # starting K gives (W122); calibrated without the factor (pause_steps false) the walk sums 11.23 m (6 % short)
    assert track_waist(turn_walk, pipeline="waist-pendulum", params=p).steps["length_m"].sum() == pytest.approx(
        12.0, rel=2e-3)
    # realtime: the default since W165 too; pause_steps false gives the realtime track before it (no factor)
    assert "pause_factor" in track_waist(turn_walk, pipeline="waist-pendulum", realtime=True).steps
    assert "pause_factor" not in track_waist(turn_walk, pipeline="waist-pendulum", realtime=True,
                                             pause_steps=False).steps


def test_samples_made_up_inside_a_gap_are_no_stand():
    """W136: a 0.5 s gap of dropped samples in a real straight walk is bridged by a line (W34), which reads as a
    standstill of over half a step; W134 shortened the step across it (the walk 20 % short at this gap position,
    tests/test_waist_clock_gaps.py's mean -9.1 % instead of -5.2 %). The made-up samples are no stand."""
    from pdrlearn.io import read_session
    from pdrlearn.io.session import Stream
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.ahrs import bridged_samples, waist_imu
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_HA001_Test5_Trial1"))
    b = s.extras["bouts"].iloc[0]
    t0 = float(np.linspace(b.start_s + 0.5, b.end_s - 1.0, 8)[2])
    g = s.copy()
    for k, st in g.streams.items():
        keep = (st.t < t0) | (st.t >= t0 + 0.5)
        g.streams[k] = Stream(k, st.t[keep], st.values[keep])
    imu = waist_imu(g)
    made_up = bridged_samples(g, imu.t)
    assert imu.bridged is not None and np.array_equal(imu.bridged, made_up)
    assert 45 <= made_up.sum() <= 50 and (imu.t[made_up] > t0 - 0.02).all() and (imu.t[made_up] < t0 + 0.5).all()
    assert not bridged_samples(s, waist_imu(s).t).any()  # a recording without gaps: nothing made up
    on = track_waist(g, pipeline="waist-pendulum").steps
    off = track_waist(g, pipeline="waist-pendulum", pause_steps=False).steps
    assert (on["pause_factor"] == 1.0).all()
    np.testing.assert_allclose(on["length_m"], off["length_m"], rtol=1e-12)
