"""Decision E307 (docs/decisions/export.md, session 47): ``pdrlearn.kernels.dsp.sosfilt`` runs scipy's compiled
loop when the process has imported ``scipy.signal`` already and the numpy loop otherwise; both give the same floats,
to the bit, and the lean runtime still never imports scipy."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from scipy import signal as sg

from pdrlearn.kernels import dsp


def _designs():
    yield dsp.butter_sos(3, 5.0, 100.0, "low")
    yield dsp.butter_sos(2, 0.3, 100.0, "high")
    yield dsp.butter_sos(2, (0.3, 3.0), 20.0, "bandpass")
    yield dsp.butter_sos(5, 8.0, 50.0, "low")  # three sections: the loop's two-at-a-time pass and its lone one
    yield sg.butter(4, 2.5, fs=20.0, output="sos")


@pytest.mark.parametrize("n", [1, 2, 7, 1300])
def test_fast_sosfilt_equals_the_numpy_loop_to_the_bit(n):
    rng = np.random.default_rng(n)
    for sos in _designs():
        x = rng.normal(size=n) * 100.0
        for zi in (None, rng.normal(size=(sos.shape[0], 2))):
            y, zf = dsp.sosfilt(sos, x, zi)
            y0, zf0 = dsp.sosfilt_loop(sos, x, zi)
            ref, zref = sg.sosfilt(sos, x, zi=np.zeros((sos.shape[0], 2)) if zi is None else zi)
            assert np.array_equal(y, y0) and np.array_equal(zf, zf0)
            assert np.array_equal(y, ref) and np.array_equal(zf, zref)
            assert y.shape == (n,) and zf.shape == (sos.shape[0], 2)


def test_fast_path_runs_when_scipy_is_loaded_and_leaves_its_inputs_alone(monkeypatch):
    sos, x = dsp.butter_sos(3, 5.0, 100.0, "low"), np.arange(50.0)
    zi = np.ones((2, 2))
    calls = []
    kernel = dsp._loaded_sosfilt_kernel()
    assert kernel is not None  # scipy.signal is imported by this test module
    monkeypatch.setattr(dsp, "_loaded_sosfilt_kernel", lambda: lambda *a: (calls.append(1), kernel(*a)))
    y, _ = dsp.sosfilt(sos, x, zi)
    assert calls == [1]
    assert np.array_equal(x, np.arange(50.0)) and np.array_equal(zi, np.ones((2, 2)))  # works on copies
    assert np.array_equal(y, dsp.sosfilt_loop(sos, x, zi)[0])


def test_without_scipy_the_numpy_loop_runs_and_zero_phase_filters_are_unchanged(monkeypatch):
    x = np.cumsum(np.random.default_rng(5).normal(size=1500))
    fast = dsp.lowpass(x, 2.0, 100.0), dsp.sosfiltfilt(dsp.butter_sos(2, (0.3, 3.0), 100.0, "bandpass"), x)
    monkeypatch.setattr(dsp, "_loaded_sosfilt_kernel", lambda: None)
    slow = dsp.lowpass(x, 2.0, 100.0), dsp.sosfiltfilt(dsp.butter_sos(2, (0.3, 3.0), 100.0, "bandpass"), x)
    for a, b in zip(fast, slow, strict=True):
        assert np.array_equal(a, b)


def test_sections_not_normalised_take_the_loop():
    sos = dsp.butter_sos(3, 5.0, 100.0, "low") * 2.0  # a0 = 2: scipy refuses these, the loop divides
    x = np.random.default_rng(6).normal(size=40)
    assert np.array_equal(dsp.sosfilt(sos, x)[0], dsp.sosfilt_loop(sos, x)[0])


def test_the_kernels_do_not_import_scipy_to_filter():
    code = ("import sys, numpy as np; from pdrlearn.kernels import dsp; "
            "y = dsp.lowpass(np.arange(300.0), 2.0, 100.0); "
            "print(sorted(m for m in ('scipy', 'scipy.signal') if m in sys.modules), y.shape)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip() == "[] (300,)"
