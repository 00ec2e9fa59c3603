"""Physics, determinism, format and CLI checks of the gait simulator (pdrlearn.sim)."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hst
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import (
    Backward,
    Curve,
    Stairs,
    Stand,
    Straight,
    Turn,
    UserProfile,
    simulate,
    simulate_path,
)
from pdrlearn.sim.kernels import STANDARD_GRAVITY
from tests.sim_helpers import session_digest as _digest  # shared with the S115-S117 tests

G = STANDARD_GRAVITY


def _aligned(seed: int = 1) -> UserProfile:
    return dataclasses.replace(
        UserProfile.from_seed(seed), foot_misalignment_deg=[0.0, 0.0, 0.0], waist_misalignment_deg=[0.0, 0.0, 0.0]
    )


def _foot_axes(s) -> np.ndarray:
    """Columns: the foot sensor axes in body FLU (declared frame + recorded misalignment)."""
    mis = Rotation.from_rotvec(np.radians(s.meta["misalignment_deg"]["foot"])).as_matrix()
    return mis @ s.frames["foot"].matrix()


@pytest.fixture(scope="module")
def exact_a():
    return simulate("A", 1, rate_hz=100, noise=False)


@pytest.fixture(scope="module")
def exact_d():
    return simulate("D", 2, rate_hz=100, noise=False)


def test_standing_units_read_gravity_in_their_frames():
    s = simulate_path([], _aligned(), rate_hz=20, noise=False)
    # thesis foot frame: y up; waist phone: y up (pdrlearn.io.frames)
    np.testing.assert_allclose(
        s["fAccelerometer"].values, np.tile([0.0, G, 0.0], (len(s["fAccelerometer"]), 1)), atol=1e-9
    )
    np.testing.assert_allclose(s["wAccelerometer"].values[5], [0.0, G, 0.0], atol=1e-9)
    np.testing.assert_allclose(s["fGyroscope"].values, 0.0, atol=1e-12)
    # misaligned unit: still |g|, and the declared frame + recorded misalignment explain the reading
    m = simulate("standstill", 4, noise=False)
    f = m["fAccelerometer"].values
    np.testing.assert_allclose(np.linalg.norm(f, axis=1), G, atol=1e-9)
    np.testing.assert_allclose(f[0], _foot_axes(m).T @ [0.0, 0.0, G], atol=1e-9)
    assert m.duration_s == pytest.approx(60.0, abs=0.06)  # thesis Table 34: 60 s standstill


def _stride_windows(s, rows):
    t = s["fAccelerometer"].t
    for _, r in rows.iterrows():
        i0 = int(np.searchsorted(t, r.start_s))
        i1 = int(np.searchsorted(t, r.end_s)) - 1
        yield r, i0, i1


def test_double_integration_recovers_stride_displacement(exact_a):
    s = exact_a
    ft = s.extras["foot_trajectory"]
    R = Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy()).as_matrix()
    f_body = s["fAccelerometer"].values @ _foot_axes(s).T
    a_nav = np.einsum("nij,nj->ni", R, f_body) - [0.0, 0.0, G]
    dt = 0.01
    rows = s.steps[s.steps.steady]
    assert len(rows) >= 10
    for r, i0, i1 in _stride_windows(s, rows):
        v = np.vstack([np.zeros(3), np.cumsum(0.5 * (a_nav[i0:i1] + a_nav[i0 + 1 : i1 + 1]) * dt, axis=0)])
        disp = np.sum(0.5 * (v[:-1] + v[1:]) * dt, axis=0)
        assert np.hypot(*disp[:2]) == pytest.approx(r.length_m, rel=0.02)
        assert np.linalg.norm(v[-1]) < 0.05  # foot at rest again at mid-stance
    # the labelled length is the foot-unit displacement of the ground truth trajectory
    p = ft[["x", "y"]].to_numpy()
    r, i0, i1 = next(_stride_windows(s, rows))
    assert np.hypot(*(p[i1] - p[i0])) == pytest.approx(r.length_m, abs=1e-6)


def _integrate_gyro(w: np.ndarray, dt: float) -> Rotation:
    rot = Rotation.identity()
    for wi in w:
        rot = rot * Rotation.from_rotvec(wi * dt)
    return rot


def test_gyroscope_integrates_to_orientation_change(exact_a):
    s = exact_a
    ft = s.extras["foot_trajectory"]
    q = Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy())
    axes = _foot_axes(s)
    w_body = s["fGyroscope"].values @ axes.T
    for _, i0, i1 in list(_stride_windows(s, s.steps[s.steps.steady]))[:3]:
        mid = (i0 + i1) // 2  # compare at mid-swing, where the foot has rotated most
        est = _integrate_gyro(0.5 * (w_body[i0:mid] + w_body[i0 + 1 : mid + 1]), 0.01)  # trapezoid
        true = q[i0].inv() * q[mid]
        assert true.magnitude() > 0.3
        assert (est.inv() * true).magnitude() < math.radians(2.0)


def test_waist_gyroscope_sees_in_place_rotations():
    s = simulate("rotations", 3, rate_hz=100, noise=False)
    w = s["wGyroscope"].values[:, 1]  # waist y axis = up
    t = s["wGyroscope"].t
    yaw = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])
    heading = s.trajectory["heading_rad"].to_numpy()
    # four pi/2 rotations: anticlockwise, two clockwise, anticlockwise (thesis Table 35)
    moves = np.flatnonzero(np.abs(np.diff(heading)) > 1e-4)
    assert abs(yaw[-1]) < 0.05 and np.max(yaw) == pytest.approx(math.pi / 2, rel=0.05)
    assert np.min(yaw) == pytest.approx(-math.pi / 2, rel=0.05) and moves.size > 0


def test_force_only_in_stance(exact_a):
    s = simulate("A", 1, rate_hz=100)  # with noise: an unloaded sensor still reads exactly 0
    for sess in (exact_a, s):
        fa, fb = sess["fForceA"], sess["fForceB"]
        total = fa.values[:, 0] + fb.values[:, 0]
        for _, r in sess.steps[sess.steps.steady].iterrows():
            swing = (fa.t > r.tc_s + 0.02) & (fa.t < r.ic_s - 0.02)
            assert swing.sum() > 10 and np.all(total[swing] == 0.0)
            stance = (fa.t > r.start_s) & (fa.t < r.start_s + 0.1)
            assert np.all(fb.values[stance, 0] > 0)
            heel_strike = (fa.t > r.ic_s + 0.03) & (fa.t < r.ic_s + 0.1)
            assert np.all(fa.values[heel_strike, 0] > 0)
    assert fa.values.max() <= 440.0  # Table 7 range


def test_stairs_rise_two_stairs_per_stride(exact_d):
    st = exact_d.steps
    up = st[(st.terrain == "up") & st.steady]
    assert len(up) >= 6
    np.testing.assert_allclose(up.height_m, 2 * 3.8 / 21, atol=1e-6)  # stride = two stairs
    z = exact_d.trajectory.z.to_numpy()
    assert z[-1] - z[0] == pytest.approx(3.8, abs=1e-6)  # thesis ch.7.3.2.1: 3.8 m rise
    assert exact_d.meta["distance_m"] == pytest.approx(90.0, rel=0.05)
    # the barometer sees the climb: ~0.12 hPa per metre
    p = exact_d["wBarometer"].values[:, 0]
    assert p[0] - p[-1] == pytest.approx(3.8 * 0.1193, rel=0.05)


def test_same_seed_same_session_other_seed_other_user():
    a, b = simulate("B", 5, seed=2), simulate("B", 5, seed=2)
    for name in a.streams:
        np.testing.assert_array_equal(a[name].values, b[name].values)
        np.testing.assert_array_equal(a[name].t, b[name].t)
    assert a.steps.equals(b.steps) and a.meta == b.meta
    u5, u6 = UserProfile.from_seed(5), UserProfile.from_seed(6)
    assert u5 == UserProfile.from_seed(5) and u5.height_m != u6.height_m and u5.step_time_s != u6.step_time_s
    c = simulate("B", 6, seed=2)
    assert c.meta["user"] != a.meta["user"] and len(c["fAccelerometer"]) != len(a["fAccelerometer"])
    d = simulate("B", 5, seed=3)
    assert not np.array_equal(d["fGyroscope"].values[:50], a["fGyroscope"].values[:50])


def test_round_trip(tmp_path):
    s = simulate("direction", 2, clock_offset_s=0.2, drop_rate=0.02)
    write_session(s, tmp_path / "s")
    r = read_session(tmp_path / "s", bridge_drops=False)  # as recorded: B64 would bridge the dropped samples
    assert set(r.streams) == set(s.streams)
    for name in s.streams:
        np.testing.assert_allclose(r[name].t, s[name].t, atol=1e-9)
        np.testing.assert_array_equal(r[name].values, s[name].values)
    np.testing.assert_allclose(r.steps.start_s, s.steps.start_s, atol=1e-9)
    assert list(r.steps.direction) == list(s.steps.direction)
    np.testing.assert_allclose(r.extras["ics"].ic_s, s.extras["ics"].ic_s, atol=1e-9)
    assert r.frames == s.frames and r.meta["length_class_bounds_m"] == s.meta["length_class_bounds_m"]
    np.testing.assert_allclose(r.trajectory[["x", "y", "z"]], s.trajectory[["x", "y", "z"]])


def test_steps_table_and_ics_contract(exact_a):
    st = exact_a.steps
    for col in (
        "start_s",
        "end_s",
        "ic_s",
        "terrain",
        "direction",
        "length_m",
        "height_m",
        "length_class",
        "heading_change_deg",
    ):
        assert col in st
    assert (st.start_s < st.ic_s).all() and (st.ic_s < st.end_s).all() and (st.length_m >= 0).all()
    assert st.end_s.to_numpy()[:-1] == pytest.approx(st.start_s.to_numpy()[1:])
    ics = exact_a.extras["ics"]
    assert set(ics.foot) == {"left", "right"} and np.all(np.diff(ics.ic_s) > 0)
    assert (ics.foot.to_numpy()[1:] != ics.foot.to_numpy()[:-1]).mean() > 0.9
    # >= 5 s still at both ends (thesis: 5 s standstill for calibration)
    acc = exact_a["fAccelerometer"]
    still = acc.values[(acc.t < 5.0) | (acc.t > acc.t[-1] - 5.0)]
    assert np.ptp(still, axis=0).max() < 1e-9
    for key in ("sensor_height_m", "leg_length_m", "height_m", "scenario", "user", "clock_offset_s"):
        assert key in exact_a.meta


def test_exercises_label_balance():
    t = simulate("terrain", 3).steps
    counts = t.terrain.value_counts()
    assert 60 <= len(t) <= 110 and min(counts.get(c, 0) for c in ("flat", "up", "down")) >= 20
    d = simulate("direction", 3).steps
    assert 40 <= len(d) <= 60 and (d.direction == "backward").sum() >= 20
    assert (d.direction == "forward").sum() >= 20
    # backward strides: the foot moves backward (the heading stays)
    ft = simulate("direction", 3, rate_hz=100, noise=False)
    back = ft.steps[(ft.steps.direction == "backward") & ft.steps.steady].iloc[0]
    fx = ft.extras["foot_trajectory"]
    x = np.interp([back.start_s, back.end_s], fx.t_s, fx.x)
    assert x[1] < x[0] - 0.2
    ln = simulate("length", 3)
    c = ln.steps[ln.steps.steady].length_class.value_counts()
    assert min(c.get(k, 0) for k in ("short", "normal", "long")) >= 15
    lo, hi = ln.meta["length_class_bounds_m"]
    assert 0 < lo < hi


def test_speed_changes_cadence_and_length():
    slow, fast = simulate("A", 2, "slow").steps, simulate("A", 2, "fast").steps
    s, f = slow[slow.steady], fast[fast.steady]
    assert (s.end_s - s.start_s).median() > 1.15 * (f.end_s - f.start_s).median()
    assert s.length_m.median() < f.length_m.median()


def test_waist_shows_pelvic_rotation_and_bounce(exact_a):
    g = exact_a["wGyroscope"]
    st = exact_a.steps[exact_a.steps.steady]
    m = (g.t > st.start_s.min()) & (g.t < st.end_s.max())
    yaw_rate = g.values[m, 1]
    assert 0.08 < yaw_rate.std() < 0.6
    stride_hz = 1.0 / (st.end_s - st.start_s).median()
    spec = np.abs(np.fft.rfft(yaw_rate - yaw_rate.mean()))
    freqs = np.fft.rfftfreq(yaw_rate.size, 0.01)
    assert abs(freqs[np.argmax(spec)] - stride_hz) < 0.15  # pelvic rotation at stride frequency
    acc_up = exact_a["wAccelerometer"].values[m, 1]
    assert 1.0 < acc_up.std() < 3.5


def test_clock_knobs_drops_and_bad_values():
    s = simulate("A", 1, clock_offset_s=0.3, clock_drift_ppm=50, drop_rate=0.05)
    ref = simulate("A", 1)
    tw, tf = s["wAccelerometer"].t, ref["fAccelerometer"].t
    np.testing.assert_allclose(tw, tf * (1 + 50e-6) + 0.3)
    assert len(s["fAccelerometer"]) == len(tf) - s.meta["dropped_samples"] and s.meta["dropped_samples"] > 5
    assert s["fAccelerometer"].gaps()
    with pytest.raises(DataError, match="scenario"):
        simulate("E", 1)
    with pytest.raises(DataError, match="speed"):
        simulate("A", 1, "jogging")
    with pytest.raises(DataError, match="unknown option"):
        simulate("A", 1, wobble=3)
    with pytest.raises(DataError, match="100 Hz divided"):
        simulate("A", 1, rate_hz=30)
    with pytest.raises(DataError, match="non-negative"):
        simulate("A", -1)
    with pytest.raises(DataError, match="gait"):
        simulate_path([Straight(5.0, "huge")], UserProfile.from_seed(1))


def test_custom_path_segments():
    user = UserProfile.from_seed(8)
    s = simulate_path(
        [
            Straight(3.0),
            Curve(math.pi / 2, 1.5),
            Stand(2.0),
            Backward(4),
            Turn(-math.pi),
            Stairs(4, up=False, rise_m=0.16, run_m=0.3),
        ],
        user,
        rate_hz=50,
        noise=False,
    )
    assert s["fAccelerometer"].rate_hz == pytest.approx(50.0)
    traj = s.trajectory
    assert traj.z.iloc[-1] - traj.z.iloc[0] == pytest.approx(-0.64, abs=1e-6)
    assert math.degrees(s.trajectory.heading_rad.iloc[-1]) == pytest.approx(-90.0, abs=1.0)
    assert {"backward", "forward"} <= set(s.steps.direction)


def test_cli_end_to_end(tmp_path, capsys):
    out = tmp_path / "sim_b"
    code = main(["simulate", "--scenario", "B", "--user-seed", "3", "--speed", "fast", "--out", str(out), "--json"])
    printed, err = capsys.readouterr()
    assert code == 0, err
    summary = json.loads(printed)
    assert summary["strides"] > 10 and summary["distance_m"] == pytest.approx(25.0, rel=0.05)
    s = read_session(out)
    assert len(s.streams) == 8 and s.steps is not None and "ics" in s.extras
    for bad in (
        ["--scenario", "Z", "--user-seed", "1"],
        ["--scenario", "A", "--user-seed", "-2"],
        ["--scenario", "A", "--user-seed", "1", "--speed", "jog"],
        ["--scenario", "A", "--user-seed", "1", "--rate", "33"],
    ):
        target = tmp_path / "bad"
        code = main(["simulate", *bad, "--out", str(target)])
        _, err = capsys.readouterr()
        assert code != 0 and err.startswith("error:") and err.count("\n") == 1, err
        assert not target.exists()
    code = main(["simulate", "--scenario", "A", "--user-seed", "1", "--out", str(out)])
    _, err = capsys.readouterr()
    assert code == 2 and "not an empty folder" in err
    assert len(list(out.iterdir())) > 8  # untouched


def test_irregular_steps_are_short_and_slow():
    st = simulate("C", 2, irregular_rate=0.3).steps
    irr, reg = st[st.irregular & (st.kind == "walk")], st[~st.irregular & st.steady]
    assert len(irr) >= 5 and len(reg) >= 10
    assert irr.length_m.median() < 0.9 * reg.length_m.median()
    assert (irr.end_s - irr.start_s).median() > 1.05 * (reg.end_s - reg.start_s).median()
    assert simulate("C", 2).steps.irregular.sum() == 0  # default: none


def test_20hz_is_the_mean_of_five_100hz_samples(exact_a):
    """Firmware averaging (thesis ch.4.2.3): each 20 Hz sample is the mean of five 100 Hz samples."""
    s20 = simulate("A", 1, rate_hz=20, noise=False)
    for name in ("fAccelerometer", "fGyroscope", "wAccelerometer", "fForceB"):
        v100, v20 = exact_a[name].values, s20[name].values
        j = np.arange(1, len(v20) - 1)
        means = np.stack([v100[5 * k - 2 : 5 * k + 3].mean(axis=0) for k in j])
        np.testing.assert_allclose(v20[j], means, atol=1e-9)
        np.testing.assert_allclose(s20[name].t[j], exact_a[name].t[5 * j], atol=1e-12)


@settings(max_examples=6, deadline=None)
@given(
    user_seed=hst.integers(0, 10**6),
    length=hst.floats(2.0, 12.0),
    speed=hst.sampled_from(["slow", "normal", "fast"]),
    angle=hst.floats(-math.pi, math.pi),
)
def test_property_any_user_walks_the_path(user_seed, length, speed, angle):
    user = UserProfile.from_seed(user_seed)
    s = simulate_path(
        [Straight(length), Curve(angle, 2.0)] if abs(angle) > 0.05 else [Straight(length)],
        user,
        speed=speed,
        noise=False,
    )
    for stream in s.streams.values():
        assert np.isfinite(stream.values).all()
    assert (s["fForceA"].values >= 0).all() and (s["fForceB"].values >= 0).all()
    steps = s.steps
    assert ((steps.start_s < steps.ic_s) & (steps.ic_s < steps.end_s)).all()
    # the right foot ends beside the left one at the end of the path: its strides add up to the path
    expected = length + (abs(angle) * 2.0 if abs(angle) > 0.05 else 0.0)
    assert steps.length_m.sum() == pytest.approx(expected, rel=0.08)
    # the waist ends where the path ends (start and end standing still)
    tr = s.trajectory
    end = np.array([tr.x.iloc[-1], tr.y.iloc[-1]])
    assert np.linalg.norm(end) > 0.5 * length


def test_standstill_noise_matches_thesis_tables():
    """At 20 Hz the stationary deviation reproduces thesis Tables 4, 6, 12, 14, 16 (within 15 %)."""
    from pdrlearn.sim import sensors as sn

    s = simulate("standstill", 5)
    for name, table in (
        ("fAccelerometer", sn.FOOT_ACC.noise_sd),
        ("fGyroscope", sn.FOOT_GYR.noise_sd),
        ("wAccelerometer", sn.WAIST_ACC.noise_sd),
        ("wGyroscope", sn.WAIST_GYR.noise_sd),
        ("wMagneticField", sn.MAG_NOISE_SD),
    ):
        v = s[name].values
        sd = np.diff(v, axis=0).std(axis=0) / math.sqrt(2)  # white-noise sd, insensitive to the slow drift
        np.testing.assert_allclose(sd, table, rtol=0.15, err_msg=name)
    p = s["wBarometer"].values[:, 0]
    assert 996.0 < p.mean() < 1030.0  # Table 18 range, minus ~0.1 hPa for the phone's 1 m height


def test_instep_mount_pitch_knob():
    s = simulate("A", 1, foot_mount_pitch_deg=50.0, noise=False)
    rest = s["fAccelerometer"].values[0]
    # toes-down tilt: gravity shows on -x like the real instep recordings (rest acc_x ~ -7.6 m/s^2)
    assert rest[0] == pytest.approx(-G * math.sin(math.radians(50.0)), abs=0.6)
    np.testing.assert_allclose(rest, _foot_axes(s).T @ [0.0, 0.0, G], atol=1e-6)


def test_magnetometer_gives_the_true_heading_at_rest():
    s = simulate("rotations", 2, noise=False, heading0_deg=30.0)
    mis = Rotation.from_rotvec(np.radians(s.meta["misalignment_deg"]["waist"])).as_matrix()
    b_body = s["wMagneticField"].values @ (mis @ s.frames["waist"].matrix()).T
    rest = [0, len(b_body) - 1]  # pelvis level at the start and end standstills
    np.testing.assert_allclose(np.linalg.norm(b_body[rest], axis=1), 45.0, atol=1e-9)
    heading = np.arctan2(b_body[rest, 0], b_body[rest, 1])  # field points north: psi = atan2(b_x, b_y)
    truth = s.trajectory.heading_rad.to_numpy()[rest]
    np.testing.assert_allclose(np.angle(np.exp(1j * (heading - truth))), 0.0, atol=1e-6)
    assert math.degrees(truth[0]) == pytest.approx(30.0, abs=1e-6)


@pytest.mark.parametrize(
    "knobs, match",
    [
        ({"noise": "yes"}, "noise"),
        ({"drop_rate": 0.7}, "drop_rate"),
        ({"variability": -1}, "variability"),
        ({"clock_offset_s": float("nan")}, "clock_offset_s"),
        ({"stand_s": "5"}, "stand_s"),
        ({"mag_inclination_deg": 120}, "mag_inclination_deg"),
    ],
)
def test_bad_knobs_are_one_line_errors(knobs, match):
    with pytest.raises(DataError, match=match) as err:
        simulate("A", 1, **knobs)
    assert "\n" not in str(err.value)


def test_edge_cases_of_custom_paths():
    user = UserProfile.from_seed(1)
    with pytest.raises(DataError, match="nothing to simulate"):
        simulate_path([], user, stand_s=0.0)
    with pytest.raises(DataError, match="seed"):
        simulate_path([Straight(5.0)], user, seed=-3)
    with pytest.raises(DataError, match="radius"):
        simulate_path([Curve(1.0, 0.0)], user)
    with pytest.raises(DataError, match="stairs|n >= 1"):
        simulate_path([Stairs(0)], user)
    s = simulate_path([Turn(0.0), Stand(1.0)], user, seed=None)
    assert s.steps is None and s.duration_s == pytest.approx(11.0, abs=0.1)


def _peak_lag_ms(t, sig, ics, half_window_s=0.25):
    lags = []
    for ic in ics:
        m = (t >= ic - half_window_s) & (t <= ic + half_window_s)
        lags.append(t[m][np.argmax(sig[m])] - ic)
    return 1e3 * float(np.median(lags))


def test_waist_forward_acc_and_yaw_rate_peak_near_contact(exact_a):
    """Decisions S17: as on the real lower back (mobgap: forward-acc peak -30..-110 ms, |yaw rate| peak
    -70..+50 ms from IC), not 0.15-0.2 s before / mid-step as with sinusoidal surge and rotation."""
    acc, gyr = exact_a["wAccelerometer"], exact_a["wGyroscope"]
    st = exact_a.steps[exact_a.steps.steady]
    ics = exact_a.extras["ics"]["ic_s"].to_numpy()
    ics = ics[(ics > st.start_s.min()) & (ics < st.end_s.max())]
    fwd = acc.values[:, 2]  # waist frame: z forward
    assert abs(_peak_lag_ms(acc.t, fwd, ics)) < 60
    assert abs(_peak_lag_ms(gyr.t, np.abs(gyr.values[:, 1]), ics)) < 80  # y up: yaw rate


def test_skewed_phase_and_sawtooth_kernels():
    from pdrlearn.sim.kernels import sawtooth_surge, skewed_phase

    ph = np.linspace(-2.0, 4.0, 6001)
    w = skewed_phase(ph, shift=-0.2, skew=0.6, centre=0.1)
    assert np.all(np.diff(w) > 0)  # monotone
    np.testing.assert_allclose(skewed_phase(np.arange(-2.0, 4.0) - 0.2, shift=-0.2, skew=0.6, centre=0.1),
                               np.arange(-2.0, 4.0), atol=1e-12)  # integers of ph - shift map to integers
    rate = np.gradient(w, ph)
    assert abs(ph[np.argmax(rate[:1000])] % 1.0 - (0.1 - 0.2) % 1.0) < 0.01  # fastest `centre` after
    acc = np.gradient(np.gradient(sawtooth_surge(ph, drop=0.1), ph), ph)  # x'': rising sawtooth
    k = np.argmax(acc[(ph >= 0.5) & (ph < 1.5)])
    assert -0.2 < ph[(ph >= 0.5) & (ph < 1.5)][k] - 1.0 < 0.05  # peaks just before the drop at 1 + 0.1


def test_stairs_up_lands_without_heel_rocker_and_down_lowers_early():
    """Decisions S15: ascending steps land fore/midfoot (no heel-first pitch), descending ones are pointed
    before contact and start down right after toe-off."""
    s = simulate("terrain", 1, rate_hz=100, noise=False)
    ft = s.extras["foot_trajectory"]
    t = ft["t_s"].to_numpy()
    pitch = np.asarray([Rotation.from_quat([r.qx, r.qy, r.qz, r.qw]).as_euler("ZYX")[1] for r in ft.itertuples()])
    z = ft["z"].to_numpy()
    st = s.steps[s.steps.steady]
    for row in st[st.terrain == "up"].itertuples():
        i = np.searchsorted(t, row.ic_s)
        assert np.degrees(-pitch[i]) < 1.0  # not toes-up at contact (body pitch < 0 = toes up in FLU)
    for row in st[st.terrain == "down"].itertuples():
        i_to, i_ic = np.searchsorted(t, [row.tc_s, row.ic_s])
        i_mid = (i_to + i_ic) // 2
        assert z[i_to:i_mid].max() < z[i_to] + 0.05  # no lift by the clearance after toe-off
        assert z[i_mid] < z[i_to]  # already going down at mid-swing


def test_stance_fraction_and_heel_off_timing(exact_a):
    """Decisions S14: stance 62-68 % of the contact-to-contact cycle (real gaitmap mocap ~67 %, mobgap INDIP
    ~68 %), heel-off at 45 % of the cycle."""
    assert all(0.62 <= UserProfile.from_seed(u).stance_fraction <= 0.68 for u in range(1, 30))
    ics = exact_a.extras["ics"]
    right = np.sort(ics.loc[ics["foot"] == "right", "ic_s"].to_numpy())
    st = exact_a.steps[exact_a.steps.steady]
    fracs = []
    for row in st.itertuples():
        prev = right[right < row.tc_s].max()  # the contact that starts this stride's stance
        fracs.append((row.tc_s - prev) / (row.ic_s - prev))
    user = UserProfile.from_seed(1)
    assert np.median(fracs) == pytest.approx(user.stance_fraction, abs=0.02)


def test_foot_mount_is_drawn_per_user_and_moves_the_sensor():
    """Decisions S19: the foot unit sits between a lateral mount below the ankle and the instep; the rest of
    the user is unchanged by that draw, and a rear mount rises faster in push-off than an instep mount."""
    users = [UserProfile.from_seed(u) for u in range(1, 40)]
    x = np.array([u.foot_sensor_x_frac for u in users])
    h = np.array([u.foot_sensor_height_m for u in users])
    assert x.min() >= 0.25 and x.max() <= 0.5 and np.ptp(x) > 0.15
    assert h.min() >= 0.03 and h.max() <= 0.07 and np.corrcoef(x, h)[0, 1] > 0.5  # higher on the instep
    base = _aligned(2)
    peak_up = {}
    for name, (xf, hm) in {"rear": (0.25, 0.03), "instep": (0.5, 0.07)}.items():
        user = dataclasses.replace(base, foot_sensor_x_frac=xf, foot_sensor_height_m=hm)
        s = simulate_path([Straight(6.0)], user, rate_hz=100, seed=0, noise=False)
        ft = s.extras["foot_trajectory"]
        vz = np.gradient(ft["z"].to_numpy(), ft["t_s"].to_numpy())
        t = ft["t_s"].to_numpy()
        st = s.steps[s.steps.steady]
        # upward speed of the unit between heel-off (stance start .. toe-off) and toe-off
        peak_up[name] = np.median([vz[(t > r.start_s) & (t < r.tc_s)].max() for r in st.itertuples()])
    assert peak_up["rear"] > 1.5 * peak_up["instep"], peak_up


def test_level_push_off_lifts_the_foot_before_toe_off(exact_a):
    """Decisions S21: the foot rolls over the toe tip in push-off, so the heel is already at its highest at
    toe-off (no further lift by the swing spline on level ground) and rising fast when it leaves."""
    ft = exact_a.extras["foot_trajectory"]
    t, z = ft["t_s"].to_numpy(), ft["z"].to_numpy()
    vz = np.gradient(z, t)
    st = exact_a.steps[exact_a.steps.steady]
    for r in st.itertuples():
        i_to, i_ic = np.searchsorted(t, [r.tc_s, r.ic_s])
        z_floor = z[np.searchsorted(t, r.start_s)]
        assert z[i_to] - z_floor > 0.05  # lifted by the push-off itself
        assert vz[i_to - 5:i_to].max() > 0.3  # and rising when the toes leave
        # coasts up a little, not lifted to the swing height (+15 cm before S21)
        assert z[i_to:i_ic].max() < z[i_to] + 0.06


def _heel_and_toe(s, user: UserProfile) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Time (s), heel height, toe-tip height (m) and pitch (rad, > 0 toes up) of the simulated right foot."""
    from pdrlearn.sim.body import toe_tip_m

    ft = s.extras["foot_trajectory"]
    rot = Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy())
    r = np.array([user.foot_sensor_x_frac * user.foot_length_m, 0.0, user.foot_sensor_height_m])
    heel = ft[["x", "y", "z"]].to_numpy() - rot.apply(r)
    toe = heel + rot.apply([toe_tip_m(user), 0.0, 0.0])
    return ft["t_s"].to_numpy(), heel[:, 2], toe[:, 2], -rot.as_euler("ZYX")[:, 1]


def _swings(strides, t: np.ndarray, heel: np.ndarray):
    """Per labelled stride: (row, heel height at its start = the floor, toe-off index, contact index, swing
    length in samples)."""
    for r in strides.itertuples():
        i_to, i_ic = np.searchsorted(t, [r.tc_s, r.ic_s])
        yield r, heel[np.searchsorted(t, r.start_s)], i_to, i_ic, i_ic - i_to


def test_level_swing_heel_falls_early_and_contact_at_largest_pitch(exact_a):
    """Decisions S23: on level ground the toes stay just above the floor in swing, so the heel (lifted by
    the plantarflexed foot at toe-off) falls in mid-swing and skims the floor in terminal swing (mocap heel
    trajectories), and the foot reaches its largest pitch at contact: the heel rocker starts from rest."""
    user = UserProfile.from_seed(1)
    assert 0.004 <= user.toe_clearance_m <= 0.022
    t, heel, toe, pitch = _heel_and_toe(exact_a, user)
    rate = np.gradient(pitch, t)
    st = exact_a.steps[exact_a.steps.steady & (exact_a.steps.terrain == "flat")]
    assert len(st) > 10
    for _r, floor, i_to, i_ic, n in _swings(st, t, heel):
        sw_heel, sw_toe = heel[i_to:i_ic] - floor, toe[i_to:i_ic] - floor
        assert np.argmax(sw_heel) < 0.3 * n  # highest early in swing (before S23: ~0.55 of swing)
        assert sw_heel[int(0.75 * n):].max() < 0.04  # near the floor in terminal swing (before: 5-9 cm)
        assert sw_toe[int(0.1 * n):int(0.9 * n)].min() > -0.005  # the toes never go through the floor
        assert abs(rate[i_ic - 1]) < 1.0  # largest pitch at contact (before: -3..-4 rad/s)
        assert rate[i_ic:i_ic + int(0.1 / (t[1] - t[0]))].min() < -2.0  # then the heel rocker


def test_stair_ascent_toes_clear_the_next_nosing_right_after_toe_off():
    """Decisions S24: ascending, the toes rise above the intermediate step's nosing in early swing (the
    riser is right in front of them at toe-off), so the foot's upward speed peaks in the first half of
    swing and it decelerates before it lands."""
    user = UserProfile.from_seed(1)
    s = simulate("terrain", 1, rate_hz=100, noise=False)
    t, heel, toe, _ = _heel_and_toe(s, user)
    vz = np.gradient(heel, t)
    st = s.steps[s.steps.steady & (s.steps.terrain == "up")]
    assert len(st) > 5
    for r, floor, i_to, i_ic, n in _swings(st, t, heel):
        half_rise = 0.5 * r.height_m
        assert toe[i_to + int(0.38 * n)] - floor > half_rise  # above the intermediate nosing
        assert np.argmax(vz[i_to:i_ic]) < 0.5 * n


def test_push_off_rolls_over_the_front_of_the_shoe(exact_a):
    """Decisions S25: the toe rocker pivots at the front of the shoe's sole (toe tip + a 1-3 cm allowance
    drawn per user), so at toe-off the heel is that far from the floor times sin(push-off angle)."""
    from pdrlearn.sim.body import toe_tip_m

    allow = np.array([UserProfile.from_seed(u).shoe_toe_allowance_m for u in range(1, 40)])
    assert allow.min() >= 0.01 and allow.max() <= 0.03 and np.ptp(allow) > 0.01
    user = UserProfile.from_seed(1)
    assert toe_tip_m(user) > user.foot_length_m
    t, heel, toe, pitch = _heel_and_toe(exact_a, user)
    st = exact_a.steps[exact_a.steps.steady & (exact_a.steps.terrain == "flat")]
    for r in st.itertuples():
        floor = heel[np.searchsorted(t, r.start_s)]
        i_to = np.searchsorted(t, r.tc_s)
        assert toe[i_to] - floor == pytest.approx(0.0, abs=0.003)  # the pivot is on the floor
        assert heel[i_to] - floor == pytest.approx(toe_tip_m(user) * np.sin(-pitch[i_to]), abs=0.005)


def _strapdown_velocity(acc_body: np.ndarray, gyr_body: np.ndarray, r0: Rotation, dt: float) -> np.ndarray:
    """ENU velocity (n, 3) from rest: attitude from ``r0`` (body -> ENU) and the gyroscope (trapezoid),
    gravity removed from the rotated specific force."""
    r = r0
    a_nav = np.empty_like(acc_body)
    for i in range(len(acc_body)):
        a_nav[i] = r.apply(acc_body[i]) - [0.0, 0.0, G]
        if i + 1 < len(acc_body):
            r = r * Rotation.from_rotvec(0.5 * (gyr_body[i] + gyr_body[i + 1]) * dt)
    return np.vstack([np.zeros(3), np.cumsum(0.5 * (a_nav[1:] + a_nav[:-1]) * dt, axis=0)])


def _waist_strapdown_error(s, sign: float, dt: float = 0.01) -> float:
    """Largest waist velocity error (m/s) of a strapdown over the whole session from the initial standstill
    (pelvis level, heading from the ground truth), the gyroscope multiplied by ``sign``."""
    mis = Rotation.from_rotvec(np.radians(s.meta["misalignment_deg"]["waist"])).as_matrix()
    axes = mis @ s.frames["waist"].matrix()
    v_true = np.gradient(s.trajectory[["x", "y", "z"]].to_numpy(), dt, axis=0)
    r0 = Rotation.from_euler("z", s.trajectory.heading_rad.iloc[0])
    v = _strapdown_velocity(s["wAccelerometer"].values @ axes.T, sign * s["wGyroscope"].values @ axes.T, r0, dt)
    return float(np.abs(v - v_true).max())


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_accelerometer_and_gyroscope_of_one_rigid_body(exact_a, sign):
    """The gyroscope is the body-frame angular rate of the orientation that put gravity and the linear
    acceleration into the accelerometer (same frame, sign and order; decision S26): strapdown from the true
    start orientation reproduces the true velocity of both units; with the gyroscope reversed (sign -1, what a
    mirrored or sign-flipped simulator would produce) it must not."""
    s, dt = exact_a, 0.01
    waist_err = _waist_strapdown_error(s, sign)
    # foot: each steady stride from the true orientation at its start (the unit is at rest there)
    ft = s.extras["foot_trajectory"]
    q = Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy())
    vf_true = np.gradient(ft[["x", "y", "z"]].to_numpy(), dt, axis=0)
    axes = _foot_axes(s)
    acc_f, gyr_f = s["fAccelerometer"].values @ axes.T, sign * s["fGyroscope"].values @ axes.T
    foot_err = 0.0
    for _, i0, i1 in _stride_windows(s, s.steps[s.steps.steady]):
        sl = slice(i0, i1 + 1)
        v = _strapdown_velocity(acc_f[sl], gyr_f[sl], q[i0], dt)
        foot_err = max(foot_err, float(np.abs(v - vf_true[sl]).max()))
    print(f"gyroscope x {sign:+.0f}: largest velocity error waist {waist_err:.3f} m/s, foot {foot_err:.3f} m/s")
    if sign > 0:  # (0.021, 0.093) m/s; peak speeds 1.6 / 5 m/s
        assert waist_err < 0.05 and foot_err < 0.25, (waist_err, foot_err)
    else:
        assert waist_err > 1.0 and foot_err > 1.0, (waist_err, foot_err)


# -- decision S27: the opt-in realistic pelvis ---------------------------------------------------------
# computed with the simulator before the pelvis option existed (commit a324768)
DEFAULT_DIGESTS = {
    ("walk", 2, "normal", 100.0, 3): "1cc0769699eee84046c30eedd9fb9482d172d0c79c51172d0130b563987c4ea7",
    ("A", 1, "fast", 20.0, 0): "d169e165c3d3ece45226740b61a37e70777866e33f2e95385f886b942e213e4a",
}


@pytest.mark.parametrize("key", list(DEFAULT_DIGESTS))
def test_default_pelvis_is_unchanged(key):
    """S27: the pelvis option leaves the default sessions (streams, ground truth, meta) as they were; the
    explicit default is the default, and the realistic pelvis changes only the waist."""
    sc, u, speed, rate, seed = key
    kw = {"length_m": 15.0} if sc == "walk" else {}
    s = simulate(sc, u, speed, rate_hz=rate, seed=seed, **kw)
    assert _digest(s) == DEFAULT_DIGESTS[key]
    assert _digest(simulate(sc, u, speed, rate_hz=rate, seed=seed, pelvis="model", **kw)) == DEFAULT_DIGESTS[key]
    r = simulate(sc, u, speed, rate_hz=rate, seed=seed, pelvis="realistic", **kw)
    assert r.meta["knobs"]["pelvis"] == "realistic" and set(r.meta["pelvis"]) >= {"roll_deg", "roll_phase_deg"}
    for name in ("fAccelerometer", "fGyroscope", "fForceA", "wBarometer"):
        np.testing.assert_array_equal(r[name].values, s[name].values)
    assert np.abs(r["wGyroscope"].values - s["wGyroscope"].values).max() > 0.01


def test_pelvis_option_rejects_unknown_values():
    with pytest.raises(DataError, match="pelvis="):
        simulate("walk", 1, length_m=5.0, pelvis="real")


def test_realistic_pelvis_draws_cover_the_real_ranges():
    """S27: roll 0.4-2 deg, phase -45..+45 deg, sway acceleration 0.4-0.9 m/s^2, drawn per user (S26's real
    lower backs); deterministic per user seed."""
    from pdrlearn.sim.body import realistic_pelvis

    p = [realistic_pelvis(UserProfile.from_seed(u)) for u in range(60)]
    roll, ph, acc = (np.array([getattr(x, k) for x in p]) for k in ("roll_deg", "roll_phase_deg", "sway_acc_mps2"))
    assert roll.min() >= 0.4 and roll.max() <= 2.0 and np.ptp(roll) > 1.2
    assert ph.min() >= -45 and ph.max() <= 45 and ph.min() < -30 and ph.max() > 30
    assert acc.min() >= 0.4 and acc.max() <= 0.9 and np.ptp(acc) > 0.35
    assert realistic_pelvis(UserProfile.from_seed(7)) == p[7]


def _stride_coupling(s) -> tuple[float, float, float]:
    """Noise-free walk: |g roll|, |a_lat| (m/s^2) and the phase of g roll ahead of a_lat (deg) at the stride
    frequency over whole strides of the steady walk (lock-in, as experiments/waist_tilt_coupling.py)."""
    mis = Rotation.from_rotvec(np.radians(s.meta["misalignment_deg"]["waist"])).as_matrix()
    axes = mis @ s.frames["waist"].matrix()
    acc, gyr, t = s["wAccelerometer"].values @ axes.T, s["wGyroscope"].values @ axes.T, s["wAccelerometer"].t
    ic = np.sort(s.extras["ics"].ic_s.to_numpy())
    f = 0.5 / np.median(np.diff(ic))
    m = (t >= ic[3]) & (t < ic[3] + np.floor((ic[-4] - ic[3]) * f) / f)

    def lockin(x):
        tt = t[m] - t[m][0]
        w = np.hanning(tt.size)
        x = x[m] - np.polyval(np.polyfit(tt, x[m], 1), tt)
        return complex(2 * np.sum(w * x * np.exp(-2j * np.pi * f * tt)) / np.sum(w))

    c = G * lockin(gyr[:, 0]) / (2j * np.pi * f)  # lateral gravity term +g roll
    a = lockin(acc[:, 1]) - c
    return abs(c), abs(a), float(np.degrees(np.angle(c * np.conj(a))))


@pytest.mark.parametrize("u", [1, 2, 3])
def test_realistic_pelvis_leans_toward_the_stance_side(u):
    """S26/S27: the model's roll is opposite to the lateral acceleration (~180 deg), the realistic roll in
    phase with it (within the user's drawn phase +- 25 deg: the pelvic rotation's lever arm to the unit adds
    some lateral acceleration), with the drawn amplitude, and the sway acceleration is smaller."""
    from pdrlearn.sim.body import realistic_pelvis

    user = UserProfile.from_seed(u)
    p = realistic_pelvis(user)
    c_m, a_m, ph_m = _stride_coupling(simulate_path([Straight(25.0)], user, rate_hz=100, noise=False))
    c_r, a_r, ph_r = _stride_coupling(
        simulate_path([Straight(25.0)], user, rate_hz=100, noise=False, pelvis="realistic")
    )
    assert abs(ph_m) > 150 and abs(ph_r) < 70
    assert abs(ph_r - p.roll_phase_deg) < 25
    assert c_r == pytest.approx(G * np.radians(p.roll_deg), rel=0.15)
    assert 0.4 <= a_r <= 1.2 and a_r < 0.8 * a_m


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_realistic_pelvis_is_one_rigid_body(sign):
    """S27 with the S26 strapdown check: the realistic pelvis's gyroscope and accelerometer belong to one
    rigid body (the true velocity from the true start, within 0.05 m/s; reversed gyroscope > 1 m/s)."""
    err = _waist_strapdown_error(simulate("A", 1, rate_hz=100, noise=False, pelvis="realistic"), sign)
    print(f"realistic pelvis, gyroscope x {sign:+.0f}: largest waist velocity error {err:.3f} m/s")
    assert err < 0.05 if sign > 0 else err > 1.0


def test_cli_pelvis_option(tmp_path, capsys):
    """S27: `pdrlearn simulate --pelvis realistic` writes the user's pelvis into meta.json; a bad value is
    one error line."""
    out = tmp_path / "real_pelvis"
    code = main(["simulate", "--scenario", "walk", "--length-m", "8", "--user-seed", "1", "--pelvis", "realistic",
                 "--out", str(out)])
    _, err = capsys.readouterr()
    assert code == 0, err
    from pdrlearn.sim.body import realistic_pelvis

    meta = json.loads((out / "meta.json").read_text())
    assert meta["pelvis"] == dataclasses.asdict(realistic_pelvis(UserProfile.from_seed(1)))
    code = main(["simulate", "--scenario", "walk", "--user-seed", "1", "--pelvis", "foo", "--out", str(tmp_path / "x")])
    _, err = capsys.readouterr()
    assert code != 0 and err.startswith("error: --pelvis") and err.count("\n") == 1, err
