"""The scalar Madgwick IMU kernel (pdrlearn.orient._kernels.madgwick_imu, decision W43) against the ``ahrs``
package's Madgwick it replaced: same attitudes to rounding, same contacts and tracks on real sessions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.io import read_session
from pdrlearn.orient import _kernels as K
from pdrlearn.waist.ahrs import MADGWICK_GAIN, body_data, imu_from_body


def _ahrs_madgwick(q0, gyr, acc, dt, *, gain):
    """The reference: ``ahrs``' ``Madgwick.updateIMU`` sample by sample (the code W43 replaced)."""
    filters = pytest.importorskip("ahrs.filters")
    filt = filters.Madgwick(Dt=dt, gain=gain)
    out, q = np.empty((len(gyr), 4)), np.asarray(q0, dtype=float)
    for i in range(len(gyr)):
        q = out[i] = filt.updateIMU(q, gyr[i], acc[i])
    return out


@pytest.fixture(scope="module")
def slice30(real_dir):
    t, acc, gyr = body_data(read_session(real_dir / "mobgap_HA001_Test11_Trial1"))
    k = slice(4000, 7000)  # 30 s of daily activity at 100 Hz (walking, turning, sitting down)
    return t[k], acc[k].copy(), gyr[k].copy()


def test_equals_ahrs_on_a_real_slice(slice30):
    _, acc, gyr = slice30
    q0 = np.array([0.9, 0.1, -0.2, 0.05]) / np.linalg.norm([0.9, 0.1, -0.2, 0.05])
    ref = _ahrs_madgwick(q0, gyr, acc, 0.01, gain=MADGWICK_GAIN)
    q = K.madgwick_imu(q0, gyr, acc, 0.01, gain=MADGWICK_GAIN)
    assert q.shape == (len(gyr), 4)
    assert np.abs(q - ref).max() < 1e-12


def test_zero_rate_and_zero_force_samples_as_ahrs(slice30):
    # decision B11 fills long gaps with zero rate: ahrs keeps the attitude there; zero force is not corrected
    _, acc, gyr = slice30
    acc, gyr = acc[:400].copy(), gyr[:400].copy()
    gyr[100:150] = 0.0
    acc[200:220] = 0.0
    ref = _ahrs_madgwick([1.0, 0.0, 0.0, 0.0], gyr, acc, 0.01, gain=0.1)
    q = K.madgwick_imu([1.0, 0.0, 0.0, 0.0], gyr, acc, 0.01, gain=0.1)
    assert np.abs(q - ref).max() < 1e-12
    np.testing.assert_allclose(q[100:150], np.tile(q[99], (50, 1)), atol=1e-15)


def test_turn_about_gravity_by_hand():
    # level unit turning at 1 rad/s about z with gravity along z: the objective is zero (no correction) and
    # each update turns by 2 atan(w dt / 2) (normalised first-order step of Madgwick eq. 12/13)
    n, w, dt = 250, 1.0, 0.01
    q = K.madgwick_imu([1, 0, 0, 0], np.tile([0.0, 0.0, w], (n, 1)), np.tile([0.0, 0.0, 9.81], (n, 1)), dt,
                       gain=0.5)
    yaw = 2 * np.arctan2(q[:, 3], q[:, 0])
    np.testing.assert_allclose(yaw, np.arange(1, n + 1) * 2 * math.atan(w * dt / 2), atol=1e-12)
    np.testing.assert_allclose(q[:, 1:3], 0.0, atol=1e-15)


def test_tilt_converges_to_gravity():
    # a unit started 30 deg off level at rest: the normalised gradient step (gain * dt per sample in the
    # quaternion, ~2 gain dt rad of tilt) levels it, down to a residue of that order
    a, gain, dt = math.radians(30), 0.1, 0.01
    q = K.madgwick_imu([math.cos(a / 2), math.sin(a / 2), 0, 0], np.full((3000, 3), 1e-9),
                       np.tile([0.0, 0.0, 9.81], (3000, 1)), dt, gain=gain)
    tilt = 2 * np.arcsin(np.hypot(q[:, 1], q[:, 2]))
    assert tilt[0] < a and tilt[-1] < 2 * gain * dt
    assert np.all(np.diff(tilt[tilt > 2 * gain * dt]) < 0)
    assert np.argmax(tilt < 2 * gain * dt) * dt < a / gain  # at most 2 gain rad/s: >= a / (2 gain) s


@settings(max_examples=10, deadline=None)
@given(cuts=st.lists(st.integers(0, 3000), min_size=1, max_size=6))
def test_chunked_equals_one_pass(slice30, cuts):
    _, acc, gyr = slice30
    whole = K.madgwick_imu([1, 0, 0, 0], gyr, acc, 0.01, gain=MADGWICK_GAIN)
    q, parts = np.array([1.0, 0, 0, 0]), []
    for a, b in zip([0, *sorted(cuts)], [*sorted(cuts), len(gyr)], strict=True):
        part = K.madgwick_imu(q, gyr[a:b], acc[a:b], 0.01, gain=MADGWICK_GAIN)
        if len(part):
            parts.append(part)
            q = part[-1]
    np.testing.assert_array_equal(np.vstack(parts), whole)


def test_imu_from_body_equals_the_ahrs_batch_form(slice30):
    filters = pytest.importorskip("ahrs.filters")
    from scipy.spatial.transform import Rotation

    from pdrlearn.signal import gravity_rotation

    t, acc, gyr = slice30
    imu = imu_from_body(t, acc, gyr, fs=100.0)
    x, y, z, w = Rotation.from_matrix(gravity_rotation(acc[:50].mean(axis=0))).as_quat()
    ref = filters.Madgwick(gyr=gyr, acc=acc, frequency=100.0, gain=MADGWICK_GAIN, q0=np.array([w, x, y, z])).Q
    rot = Rotation.from_quat(np.column_stack([ref[:, 1:], ref[:, :1]]))
    assert np.abs(imu.acc_nav - rot.apply(acc)).max() < 1e-10
    assert np.abs(imu.gyr_nav - rot.apply(gyr)).max() < 1e-12


def _memoised(filt):
    """``filt`` computed once per distinct input (the reference is a pure function; a copy is returned each time)."""
    done: dict = {}

    def run(q0, gyr, acc, dt, *, gain):
        key = (np.asarray(q0, float).tobytes(), np.ascontiguousarray(gyr, float).tobytes(),
               np.ascontiguousarray(acc, float).tobytes(), np.shape(gyr), float(dt), float(gain))
        if key not in done:
            done[key] = filt(q0, gyr, acc, dt, gain=gain)
        return done[key].copy()

    return run


@pytest.mark.parametrize("name", ["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test11_Trial1"])
def test_contacts_identical_to_the_ahrs_filter(real_dir, name, monkeypatch):
    from pdrlearn.steps.waist_ic import WaistICStepDetector
    from pdrlearn.track import get_pipeline

    s = read_session(real_dir / name)
    runs = {}
    for ref in (False, True):
        if ref:  # both the batch AHRS (pdrlearn.waist.ahrs) and the streaming one (waist-ic delay_s)
            reference = _memoised(_ahrs_madgwick)  # the detector and the pipeline filter the same whole session
            monkeypatch.setattr("pdrlearn.waist.ahrs.madgwick_imu", reference)
            monkeypatch.setattr(K, "madgwick_imu", reference)
            monkeypatch.setattr("pdrlearn.kernels.waist_stream.madgwick_imu", reference)  # the streamed filter's own
        runs[ref] = (WaistICStepDetector().detect(s), WaistICStepDetector(delay_s=1.75).detect(s),
                     get_pipeline("waist-pendulum")(s))
    (off, rt, tr), (off_r, rt_r, tr_r) = runs[False], runs[True]
    assert len(off) > 5 and len(rt) > 5
    for a, b in ((off, off_r), (rt, rt_r)):
        for c in ("event_s", "start_s", "end_s", "confidence", "fc_s"):
            np.testing.assert_array_equal(a[c].to_numpy(), b[c].to_numpy())
    np.testing.assert_array_equal(tr.steps["event_s"].to_numpy(), tr_r.steps["event_s"].to_numpy())
    assert abs(tr.distance_m - tr_r.distance_m) < 1e-9
    np.testing.assert_allclose(tr.trajectory[["x", "y"]].to_numpy(), tr_r.trajectory[["x", "y"]].to_numpy(),
                               atol=1e-9)
