"""Step windows and feature transformers: hand-computed values, rotation invariance, errors."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation
from sklearn.base import clone
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.features import (
    CHANNEL_INDEX,
    CHANNELS,
    TASK_CLASSES,
    DirectionFeatures,
    LengthFeatures,
    SegmentFeatures,
    TerrainSVMFeatures,
    make_features,
    step_windows,
    task_labels,
)
from pdrlearn.features import _kernels as K
from pdrlearn.io import AxisFrame, Session, Stream, read_session


def blank(n_steps: int = 1, m: int = 12, duration: float = 1.1) -> np.ndarray:
    X = np.zeros((n_steps, len(CHANNELS), m))
    X[:, 0, :] = np.linspace(0, duration, m)
    return X


# -- hand-made windows ------------------------------------------------------------------------------


def test_segment_stats_hand_computed():
    X = blank(m=12, duration=1.1)  # dt = 0.1 s
    sig = np.array([0, 1, 2, 3, 5, 4, 1, 1, -2, 0, 7, 9], dtype=float)
    X[0, CHANNEL_INDEX["foot_acc_x"]] = sig
    F = SegmentFeatures(channels=("foot_acc_x",), n_segments=6).fit_transform(X)
    assert F.shape == (1, 24)
    # parts of 2 samples: (0,1) (2,3) (5,4) (1,1) (-2,0) (7,9); slope = (last-first)/0.1 s
    expect = [1, 0, 0.5, 10, 3, 2, 2.5, 10, 5, 4, 4.5, -10, 1, 1, 1, 0, 0, -2, -1, 20, 9, 7, 8, 20]
    np.testing.assert_allclose(F[0], expect, atol=1e-9)


def test_terrain_svm_features_hand_computed():
    X = blank(m=11, duration=1.0)  # dt = 0.1 s
    v = np.array([0, -2, -6, -1, 0, 3, 8, 2, 0, 0, 0], dtype=float)
    X[0, CHANNEL_INDEX["foot_acc_z"]] = v
    g = np.array([0, 1, 2, 0, -3, -4, 0, 0, 0, 0, 0], dtype=float)
    X[0, CHANNEL_INDEX["foot_gyr_y"]] = -g  # foot_pitch = -foot_gyr_y (+ = toes up)
    w = np.array([0, 0.5, 1.0, 0, -1, -2, 0, 0, 0, 0, 0], dtype=float)
    X[0, CHANNEL_INDEX["waist_acc_z"]] = w
    tf = TerrainSVMFeatures(unit="both").fit(X)
    F = tf.transform(X)[0]
    names = list(tf.get_feature_names_out())
    assert len(names) == 17 and F.shape == (17,)
    d = dict(zip(names, F, strict=True))
    # interior samples weigh 0.1 s (np.gradient of a uniform grid)
    assert d["foot_acc_v_min"] == -6 and d["foot_acc_v_max"] == 8
    assert d["foot_acc_v_dt_peaks"] == pytest.approx(0.6 - 0.2)
    assert d["foot_acc_v_range"] == 14
    assert d["foot_acc_v_sum_neg"] == pytest.approx(0.9)
    assert d["foot_acc_v_sum_pos"] == pytest.approx(1.3)
    assert d["foot_pitch_min"] == -4 and d["foot_pitch_max"] == 2
    assert d["foot_pitch_dt_peaks"] == pytest.approx(0.2 - 0.5)
    assert d["foot_pitch_sum_pos"] == pytest.approx(0.3) and d["foot_pitch_sum_neg"] == pytest.approx(0.7)
    assert d["waist_acc_v_t_min"] == pytest.approx(0.5) and d["waist_acc_v_t_max"] == pytest.approx(0.2)
    assert d["waist_acc_v_max"] == 1.0
    assert TerrainSVMFeatures(unit="foot").fit_transform(X).shape == (1, 11)
    assert TerrainSVMFeatures(unit="waist").fit_transform(X).shape == (1, 6)


def test_force_stats_hand_computed():
    t = np.linspace(0, 1.0, 21)[None, :]  # 50 ms samples, like PLASYS
    f = np.array([[50, 40, 20, 0, 0, 0, 0, 0, 0, 0, 0, 0, 30, 60, 100, 80, 70, 60, 50, 50, 50]], dtype=float)
    s = K.force_stats(f, t)
    assert s["air_time"][0] == pytest.approx(9 * 0.05)  # 9 zero samples
    assert s["time_to_peak"][0] == pytest.approx(0.7 - 0.55)  # last zero at 0.55 s, peak at 0.7 s
    assert s["contact_force_2"][0] == pytest.approx(60)  # 2 samples after the last zero
    assert s["takeoff_force"][0] == pytest.approx(40)  # 2 samples before the first zero
    assert s["peak_mean_4"][0] == pytest.approx(0.5 * (0 + 50))


def test_direction_and_length_shapes_and_names():
    X = blank(n_steps=3, m=40)
    rng = np.random.default_rng(0)
    X[:, 1:] = rng.normal(size=X[:, 1:].shape)
    assert DirectionFeatures(unit="both").fit_transform(X).shape == (3, 25)
    assert DirectionFeatures(unit="foot").fit_transform(X).shape == (3, 24)
    assert LengthFeatures(unit="both").fit_transform(X).shape == (3, 29)
    assert LengthFeatures(unit="foot").fit_transform(X).shape == (3, 27)
    assert LengthFeatures(unit="waist").fit_transform(X).shape == (3, 2)
    assert make_features("terrain", "both", "nn").fit_transform(X).shape == (3, 72)
    for task in TASK_CLASSES:
        for kind in ("svm", "nn"):
            tf = make_features(task, "both", kind)
            assert len(tf.get_feature_names_out()) == tf.fit_transform(X).shape[1]
            assert clone(tf).get_params() == tf.get_params()
    pipe = make_pipeline(TerrainSVMFeatures(), StandardScaler())
    assert pipe.fit_transform(X).shape == (3, 17)


def test_missing_sensor_errors_name_sensor_and_task():
    X = blank(n_steps=2, m=20)
    X[:, CHANNEL_INDEX["waist_acc_x"]:] = np.nan
    with pytest.raises(MissingSensorError, match="terrain.*waist"):
        TerrainSVMFeatures(unit="both").fit_transform(X)
    TerrainSVMFeatures(unit="foot").fit_transform(X)  # foot-only works
    X[:, CHANNEL_INDEX["force_a"]] = np.nan
    with pytest.raises(MissingSensorError, match="length.*force"):
        LengthFeatures(unit="foot").fit_transform(X)
    with pytest.raises(DataError, match="expected an array"):
        TerrainSVMFeatures().fit_transform(np.zeros((2, 3)))
    with pytest.raises(DataError, match="unit must be"):
        TerrainSVMFeatures(unit="hand").fit_transform(X)


def test_task_labels_skip_and_count():
    steps = pd.DataFrame({"start_s": [0, 1, 2, 3], "end_s": [1, 2, 3, 4],
                          "terrain": ["up", "unclear", "flat", None]})
    y, keep, skipped = task_labels(steps, "terrain")
    assert list(y) == ["up", "flat"] and keep.tolist() == [True, False, True, False] and skipped == 1
    with pytest.raises(DataError, match="no 'length_class' column"):
        task_labels(steps, "length")


# -- step windows on sessions -----------------------------------------------------------------------


def _rotate_foot(session: Session, rot: np.ndarray) -> Session:
    """The same motion seen by a sensor mounted with an extra fixed rotation (v_new = rot.T @ v_old)."""
    out = session.copy()
    for name in ("fAccelerometer", "fGyroscope"):
        s = out.streams[name]
        out.streams[name] = Stream(name, s.t, s.values @ rot)
    return out


@pytest.fixture(scope="module")
def level(real_dir):
    s = read_session(real_dir / "gaitmap_level_left")
    s.steps = s.steps.iloc[:8].reset_index(drop=True)
    return s


@pytest.mark.parametrize("euler_deg", [(15, 50, 0), (-10, 35, 25)])
def test_features_invariant_to_mounting_rotation(level, euler_deg):
    """A 50 deg pitch + 15 deg roll (and a roll/pitch/yaw) mounting change leaves the features unchanged."""
    rot = Rotation.from_euler("xyz", euler_deg, degrees=True).as_matrix()
    w0 = step_windows(level)
    w1 = step_windows(_rotate_foot(level, rot))
    for tf in (TerrainSVMFeatures(unit="foot"), DirectionFeatures(unit="foot"),
               SegmentFeatures(channels=("foot_acc_v", "foot_pitch", "foot_acc_fwd"))):
        f0, f1 = tf.fit_transform(w0), tf.fit_transform(w1)
        scale = np.abs(f0).max(axis=0) + 1e-9
        assert np.max(np.abs(f0 - f1) / scale) < 0.02, type(tf).__name__
    # the raw sensor axes, by contrast, change a lot
    raw0 = level.streams["fAccelerometer"].values
    raw1 = _rotate_foot(level, rot).streams["fAccelerometer"].values
    assert np.abs(raw0 - raw1).max() > 3


def test_step_windows_layout_and_gravity_removed(level):
    w = step_windows(level, n_samples=30)
    assert w.X.shape == (8, len(CHANNELS), 30) and w.channels == CHANNELS
    assert w.available == ("foot_acc", "foot_gyr")
    assert np.isnan(w.channel("waist_acc_z")).all() and np.isnan(w.channel("force_a")).all()
    np.testing.assert_allclose(w.durations_s, level.steps["end_s"] - level.steps["start_s"])
    sub = w.subset(np.array([2, 0]))
    assert len(sub) == 2 and sub.steps["start_s"].tolist() == level.steps["start_s"].iloc[[2, 0]].tolist()
    np.testing.assert_array_equal(sub.X[1], w.X[0])
    assert len(w.subset(w.durations_s > 0)) == 8
    # at the window's ends the foot rests: levelled acceleration ~0 after removing gravity
    acc = [CHANNEL_INDEX[c] for c in ("foot_acc_x", "foot_acc_y", "foot_acc_z")]
    ends = w.X[:, acc][:, :, [0, -1]]
    assert np.median(np.abs(ends)) < 1.0
    # forward walking: the integrated forward acceleration peaks positive (foot moves along +x)
    fwd = w.channel("foot_acc_x")
    vel = np.cumsum(fwd, axis=1) * (w.durations_s[:, None] / 29)
    assert (vel.max(axis=1) > 1.0).all()


def test_step_windows_bad_input(level):
    with pytest.raises(DataError, match="empty"):
        step_windows(level, level.steps.iloc[:0])
    bad = level.steps.copy()
    bad.loc[0, "end_s"] = bad.loc[0, "start_s"] - 1
    with pytest.raises(DataError, match="end_s > start_s"):
        step_windows(level, bad)
    far = level.steps.copy()
    far["start_s"] += 1000
    far["end_s"] += 1000
    with pytest.raises(DataError, match="covers"):
        step_windows(level, far)
    noframe = level.copy()
    noframe.frames, noframe.infer_frames = {}, False  # decision D8: otherwise inferred from the data
    with pytest.raises(DataError, match="declares no axis frame"):
        step_windows(noframe)
    in_g = level.copy()
    in_g.streams["fAccelerometer"].values /= 9.80665
    with pytest.raises(DataError, match="looks like units of g"):  # decision B52: read_session's check
        step_windows(in_g)
    in_deg = level.copy()
    in_deg.streams["fGyroscope"].values *= 180 / np.pi
    with pytest.raises(DataError, match="deg/s"):
        step_windows(in_deg)
    nan = level.copy()
    nan.streams["fAccelerometer"].values[5, 0] = np.nan
    with pytest.raises(DataError, match="NaN"):
        step_windows(nan)


def test_step_windows_waist_and_force_synthetic():
    """A hand-built session: waist tilted 20 deg, force pulses; levelled vertical = the known bounce."""
    fs = 100.0
    t = np.arange(0, 3, 1 / fs)
    bounce = 2.0 * np.sin(2 * np.pi * 2 * t)  # vertical acceleration, m/s^2
    tilt = Rotation.from_euler("x", 20, degrees=True).as_matrix()
    # waist frame as declared: x=up, y=right, z=forward (mobgap); body FLU vector -> sensor
    frame = AxisFrame(x="up", y="right", z="forward")
    f_body = np.column_stack([np.zeros_like(t), np.zeros_like(t), 9.81 + bounce])
    sensor = (tilt @ (frame.matrix().T @ f_body.T)).T
    force = np.clip(np.sin(2 * np.pi * t), 0, None)[:, None] * 100
    s = Session("synthetic", streams={
        "wAccelerometer": Stream("wAccelerometer", t, sensor),
        "fForceA": Stream("fForceA", t, force), "fForceB": Stream("fForceB", t, force * 0.5),
    }, frames={"waist": frame})
    steps = pd.DataFrame({"start_s": [0.5, 1.5], "end_s": [1.5, 2.5]})
    w = step_windows(s, steps, n_samples=50)
    assert set(w.available) == {"waist_acc", "force"}
    tg = steps["start_s"].to_numpy()[:, None] + w.channel("t_s")
    expect = 2.0 * np.sin(2 * np.pi * 2 * tg)
    np.testing.assert_allclose(w.channel("waist_acc_z"), expect, atol=0.1)  # box filter at the edges
    np.testing.assert_allclose(w.channel("force_b"), 0.5 * w.channel("force_a"), atol=1e-9)
    with pytest.raises(MissingSensorError, match="foot acc"):
        TerrainSVMFeatures(unit="both").fit_transform(w)
    assert TerrainSVMFeatures(unit="waist").fit_transform(w).shape == (2, 6)


def test_property_any_mounting_rotation_keeps_features(level):
    """Hypothesis: a fixed mounting error (roll/pitch/yaw up to +-60 deg) keeps the terrain features.

    Beyond ~70 deg of yaw the declared forward axis no longer tells the toes' side of the step's line
    (this lateral mount already sits ~20 deg off the walking line): decisions doc, section 1."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    three = level.copy()
    three.steps = level.steps.iloc[1:4].reset_index(drop=True)
    tf = TerrainSVMFeatures(unit="foot")
    f0 = tf.fit_transform(step_windows(three))
    scale = np.abs(f0).max(axis=0) + 1e-9

    @settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(st.floats(-60, 60), st.floats(-60, 60), st.floats(-60, 60))
    def check(roll, pitch, yaw):
        rot = Rotation.from_euler("xyz", (roll, pitch, yaw), degrees=True).as_matrix()
        f1 = tf.fit_transform(step_windows(_rotate_foot(three, rot)))
        assert np.max(np.abs(f0 - f1) / scale) < 0.03

    check()


def test_propagate_attitude_matches_step_by_step_integration():
    rng = np.random.default_rng(0)
    n = 57
    gyr = rng.normal(0, 3, (n, 3))
    dt = np.full(n - 1, 0.01)
    r0 = Rotation.from_euler("xyz", (10, -40, 70), degrees=True).as_matrix()
    steps = Rotation.from_rotvec(0.5 * (gyr[:-1] + gyr[1:]) * dt[:, None]).as_matrix()
    for k0 in (0, 20, n - 1):
        want = np.empty((n, 3, 3))
        want[k0] = r0
        for k in range(k0, n - 1):
            want[k + 1] = want[k] @ steps[k]
        for k in range(k0, 0, -1):
            want[k - 1] = want[k] @ steps[k - 1].T
        np.testing.assert_allclose(K.propagate_attitude(gyr, dt, k0, r0), want, atol=1e-12)


# -- rest-to-rest step boundaries (decision 13) ------------------------------------------------------


@pytest.mark.parametrize("fs", [20.0, 204.8])
def test_rest_boundaries_move_to_the_quietest_sample(fs):
    """Boundaries given during motion move to the foot's rest within the search span (any rate); a
    boundary already at rest stays; the inward search is capped at a quarter of the step."""
    from pdrlearn.features.windows import rest_boundaries

    t = np.arange(0.0, 6.0, 1.0 / fs)
    rate = 3.0 + np.sin(2 * np.pi * t)  # always moving ...
    for c in (1.0, 2.0, 3.0, 4.0):  # ... except short rests centred at 1, 2, 3, 4 s
        rate[np.abs(t - c) < 0.08] = 0.0
    gyr = np.column_stack([rate, 0.5 * rate, np.zeros_like(t)])
    start = np.array([0.8, 2.0, 3.0])  # 0.2 s before a rest / at rest / at rest
    end = np.array([2.25, 3.0, 4.1])  # 0.25 s after / at rest / 0.1 s after
    s, e = rest_boundaries(t, gyr, start, end, search_s=0.3)
    step = 1.0 / fs
    np.testing.assert_allclose(s, [1.0, 2.0, 3.0], atol=0.08 + step)
    np.testing.assert_allclose(e, [2.0, 3.0, 4.0], atol=0.08 + step)
    assert np.all(e > s)
    # a rest 0.5 s inside a 1 s step is beyond the quarter-step cap: the start stays before it
    s2, _ = rest_boundaries(t, gyr, np.array([1.5]), np.array([2.5]), search_s=0.6)
    assert s2[0] <= 1.5 + 0.25 + step


def test_rest_boundaries_take_the_middle_of_a_noisy_rest():
    """Inside a long rest the gyro noise decides the minimum; the middle of the quiet run does not move
    with it (20 Hz, like the simulator and the PLASYS firmware)."""
    from pdrlearn.features.windows import rest_boundaries

    fs = 20.0
    t = np.arange(0.0, 4.0, 1.0 / fs)
    rate = np.full_like(t, 3.0)
    rest = (t >= 1.0) & (t <= 1.5)  # 0.5 s rest centred at 1.25 s
    mids = []
    for seed in range(5):
        r = rate.copy()
        r[rest] = np.random.default_rng(seed).uniform(0.0, 0.03, rest.sum())
        gyr = np.column_stack([r, np.zeros_like(t), np.zeros_like(t)])
        s, _ = rest_boundaries(t, gyr, np.array([1.2]), np.array([3.0]))
        mids.append(s[0])
    np.testing.assert_allclose(mids, 1.25, atol=1.0 / fs)


def test_step_windows_rest_boundaries(level):
    """boundaries="rest": windows start and end where the foot rests; labels' times kept; bad value named."""
    late = level.steps.copy()
    late["start_s"] += 0.15  # cut like a swing detector: after the stance
    late["end_s"] += 0.15
    given = step_windows(level, late)
    rest = step_windows(level, late, boundaries="rest")
    gyr = [CHANNEL_INDEX[c] for c in ("foot_gyr_x", "foot_gyr_y", "foot_gyr_z")]

    def end_rate(w):
        return np.median(np.linalg.norm(w.X[:, gyr][:, :, [0, -1]], axis=1))

    assert end_rate(rest) < 0.15 < end_rate(given)
    assert rest.steps["start_s"].tolist() == late["start_s"].tolist()  # the labels' own times
    np.testing.assert_allclose(rest.durations_s, rest.steps["window_end_s"] - rest.steps["window_start_s"])
    assert np.abs(rest.steps["window_start_s"] - late["start_s"]).max() <= 0.3 + 1e-9
    # the same strides cut at their rests agree whichever phase the labels started at
    np.testing.assert_allclose(step_windows(level, boundaries="rest").steps["window_start_s"],
                               rest.steps["window_start_s"], atol=0.03)
    with pytest.raises(DataError, match="boundaries must be one of given, rest"):
        step_windows(level, boundaries="stance")
