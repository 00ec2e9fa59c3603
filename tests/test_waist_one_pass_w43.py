"""W43: the heading kernels integrate the rate once per recording and read each walking sequence's samples
only; the results are the same numbers as the per-window passes over the whole recording they replaced."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.heading import gyro_headings, harmonic_directions


@pytest.fixture(scope="module")
def imu(real_dir):
    return waist_imu(read_session(real_dir / "mobgap_HA001_Test11_Trial1"))


def _events(imu, t0, t1, period=0.55):
    return np.arange(t0, t1, period) + 0.003  # between samples: the interpolated ends are exercised


def test_rate_integral_passed_in_is_the_same(imu):
    w = imu.w_z - 0.01
    ev = _events(imu, 20.0, 60.0)
    cum = K.rate_integral(imu.t, w)
    np.testing.assert_array_equal(K.mean_rate_per_stride(imu.t, w, ev, cum=cum), K.mean_rate_per_stride(imu.t, w, ev))
    np.testing.assert_array_equal(K.integrate_rate(imu.t, w, ev[:-1], ev[1:], cum=cum),
                                  [K.integrate_rate(imu.t, w, a, b) for a, b in zip(ev[:-1], ev[1:], strict=True)])
    h1, tr1 = gyro_headings(imu, ev, bias_rps=0.01, heading0=0.3, cum=cum)
    h2, tr2 = gyro_headings(imu, ev, bias_rps=0.01, heading0=0.3)
    np.testing.assert_array_equal(h1, h2)
    np.testing.assert_array_equal(tr1, tr2)
    assert tr1.any() and not tr1.all()  # the recording turns: some steps integrated, some held


@pytest.mark.parametrize("method", ["ahe", "ellipse", "ellipse-stride"])
def test_harmonic_directions_on_the_sequence_slice_equal_the_whole_recording(imu, method):
    ev = _events(imu, 30.5, 52.0)
    raw = harmonic_directions(imu, ev, method=method)
    ref = np.full(len(ev) - 1, np.nan)
    for k in range(len(ev) - 1):
        t0, t1, t2 = (ev[0], ev[1], ev[2]) if k == 0 else (ev[k - 1], ev[k], ev[k + 1])
        if method == "ellipse":
            ref[k] = K.ellipse_direction(imu.t, imu.acc_h, imu.acc_v, ev[k], ev[k + 1])
        elif method == "ahe":
            ref[k] = K.tip_to_tail_direction(imu.t, imu.acc_h, imu.acc_v, t0, t1, t2)
        else:
            ref[k] = K.stride_ellipse_direction(imu.t, imu.acc_h, imu.acc_v, t0, t2)
    np.testing.assert_array_equal(raw, ref)
    assert np.isfinite(raw).sum() > 0.8 * len(raw)


@pytest.mark.parametrize("method, kernel", [("ahe", "tip_to_tail_direction"), ("ellipse", "ellipse_direction"),
                                            ("ellipse-stride", "stride_ellipse_direction")])
def test_each_harmonic_kernel_reads_its_window_only(imu, method, kernel, monkeypatch):
    """E100: a long unbroken walk made `track --pipeline waist-pll` superlinear (each step's kernel masked the
    whole walking sequence: 1 / 5 / 20 km took 3.2 / 7.05 / 37.6 s in trial "longhaul"); now each call gets the
    samples of its own window (a stride: two steps of 0.55 s, at most ~1.1 s of samples plus the end samples),
    and the directions are the same numbers (the test above)."""
    seen = []
    real = getattr(K, kernel)

    def spy(t, *args, **kw):
        seen.append(len(t))
        return real(t, *args, **kw)

    monkeypatch.setattr(K, kernel, spy)
    ev = _events(imu, 30.5, 52.0)
    harmonic_directions(imu, ev, method=method)
    assert seen and max(seen) <= int(np.ceil(2 * 0.55 * imu.fs)) + 2  # the sequence is ~21.5 s of samples
