"""Decision W92: the numpy signal kernels the waist pipelines run (``pdrlearn.kernels.dsp``, ``kernels.ahrs``) equal
the scipy functions they replaced, so ``pdrlearn track`` and the lean runtime's waist tracker need no scipy."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import signal as sg
from scipy.ndimage import uniform_filter1d
from scipy.spatial.transform import Rotation

from pdrlearn.kernels import ahrs, dsp
from pdrlearn.signal import lowpass


@pytest.mark.parametrize("numtaps, cutoff, fs", [(31, 2.5, 100.0), (7, 2.5, 20.0), (13, 2.5, 40.0), (12, 8.0, 20.0)])
def test_firwin_lowpass_equals_scipy(numtaps, cutoff, fs):
    np.testing.assert_allclose(dsp.firwin_lowpass(numtaps, cutoff, fs), sg.firwin(numtaps, cutoff, fs=fs),
                               atol=1e-15, rtol=0)


def test_find_peaks_equals_scipy_with_plateaus_heights_and_distances():
    rng = np.random.default_rng(0)
    for i in range(300):
        x = np.round(rng.normal(size=400), 1 if i % 2 else 6)  # rounding to 0.1 makes flat tops and ties
        h = None if i % 3 == 0 else 0.1
        d = None if i % 5 == 0 else float(rng.integers(1, 40)) + (0.5 if i % 7 == 0 else 0.0)
        np.testing.assert_array_equal(dsp.find_peaks(x, height=h, distance=d),
                                      sg.find_peaks(x, height=h, distance=d)[0])


@pytest.mark.parametrize("size, origin", [(201, 100), (201, 0), (41, 20), (100, 0), (7, 3), (3, -1)])
def test_uniform_filter1d_equals_scipy(size, origin):
    x = np.random.default_rng(size).normal(size=900)
    np.testing.assert_allclose(dsp.uniform_filter1d(x, size, origin=origin),
                               uniform_filter1d(x, size, mode="nearest", origin=origin), atol=1e-13, rtol=0)


@pytest.mark.parametrize("order, cutoff, fs, btype", [(3, 20.0, 100.0, "low"), (3, 8.0, 20.0, "low"),
                                                      (2, 0.3, 100.0, "high"), (2, (0.3, 3.0), 100.0, "bandpass"),
                                                      (2, (0.3, 3.0), 20.0, "bandpass")])
def test_butterworth_zero_phase_equals_scipy(order, cutoff, fs, btype):
    sos = dsp.butter_sos(order, cutoff, fs, btype)
    ref = sg.butter(order, cutoff, btype=btype, fs=fs, output="sos")
    assert sos.shape == ref.shape  # the same sections, so the same default padding
    for a, b in zip(sg.sos2tf(sos), sg.sos2tf(ref), strict=True):
        np.testing.assert_allclose(a, b, atol=1e-14, rtol=1e-12)
    x = np.cumsum(np.random.default_rng(1).normal(size=1500))
    y, r = dsp.sosfiltfilt(sos, x), sg.sosfiltfilt(ref, x)
    assert np.abs(y - r).max() <= 1e-12 * np.abs(r).max()


def test_lowpass_equals_the_scipy_lowpass_also_on_short_inputs():
    x = np.random.default_rng(2).normal(size=300)
    for n in (2, 5, 10, 300):
        np.testing.assert_allclose(dsp.lowpass(x[:n], 20.0, 100.0), lowpass(x[:n], 20.0, 100.0), atol=1e-13, rtol=0)


def test_quaternion_kernels_equal_scipy_rotation():
    rng = np.random.default_rng(3)
    q, v = rng.normal(size=(60, 4)), rng.normal(size=(60, 3))
    r = Rotation.from_quat(np.column_stack([q[:, 1:], q[:, :1]]))
    np.testing.assert_allclose(ahrs.rotate(q, v), r.apply(v), atol=1e-14, rtol=0)
    for _ in range(60):
        m = Rotation.from_quat(rng.normal(size=4)).as_matrix()
        x, y, z, w = Rotation.from_matrix(m).as_quat()
        np.testing.assert_allclose(ahrs.quat_from_matrix(m), [w, x, y, z], atol=1e-14, rtol=0)
