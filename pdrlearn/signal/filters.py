"""Pure numerical kernels for signal conditioning: filters, magnitude, resampling, frames.

Every function works along axis 0 (time) and takes rates in Hz, windows in seconds.
"""

from __future__ import annotations

import numpy as np
from scipy import signal as _sig

from pdrlearn.errors import DataError
from pdrlearn.kernels.dsp import magnitude  # noqa: F401 (numpy-only, shared with the detectors' kernels, L177)
from pdrlearn.kernels.rotation import gravity_rotation  # noqa: F401 (numpy-only, shared with the runtime)


def butter_sos(cutoff_hz: float, fs: float, *, order: int = 3, btype: str = "low") -> np.ndarray:
    """Second-order sections of a Butterworth filter (thesis ch.5: 3rd order low-pass)."""
    if not (np.isfinite(fs) and fs > 0):
        raise DataError(f"low-pass filter: sampling rate {fs!r} Hz is not a positive number")
    nyq = 0.5 * fs
    if not (0 < cutoff_hz < nyq):
        raise DataError(
            f"low-pass filter: cutoff {cutoff_hz} Hz must be between 0 and the Nyquist rate {nyq:g} Hz; "
            "lower the cutoff or resample the stream"
        )
    return _sig.butter(order, cutoff_hz / nyq, btype=btype, output="sos")


def lowpass(x: np.ndarray, cutoff_hz: float, fs: float, *, order: int = 3,
            causal: bool = False) -> np.ndarray:
    """Butterworth low-pass along axis 0.

    Parameters
    ----------
    x : (n,) or (n, k) samples
    cutoff_hz : -3 dB cutoff (Hz)
    fs : sampling rate (Hz)
    order : filter order (thesis ch.5.1: third order)
    causal : ``False`` -> zero-phase ``sosfiltfilt`` (offline); ``True`` -> ``sosfilt`` (streaming),
        initialised at the first sample's steady state so a constant input passes unchanged.

    Returns
    -------
    ndarray with the shape of ``x``. Inputs too short for the zero-phase padding are padded as much as
    they allow; a 0- or 1-sample input is returned unchanged.
    """
    a = np.asarray(x, dtype=np.float64)
    if a.shape[0] < 2:
        return a.copy()
    sos = butter_sos(cutoff_hz, fs, order=order)
    if causal:
        zi = _sig.sosfilt_zi(sos)  # (n_sections, 2)
        shape = (sos.shape[0], 2) + (1,) * (a.ndim - 1)
        zi = zi.reshape(shape) * a[0]
        y, _ = _sig.sosfilt(sos, a, axis=0, zi=zi)
        return y
    default_pad = 3 * (2 * sos.shape[0] + 1)
    padlen = min(default_pad, a.shape[0] - 1)
    return _sig.sosfiltfilt(sos, a, axis=0, padlen=padlen)


def lowpass_delay_s(cutoff_hz: float, fs: float, *, order: int = 3, at_hz: float = 1.0) -> float:
    """Group delay (s) of the causal Butterworth low-pass at ``at_hz`` (default 1 Hz, gait frequencies);
    detectors subtract it from event times found on causally filtered signals."""
    b, a = _sig.butter(order, cutoff_hz / (0.5 * fs))
    _, gd = _sig.group_delay((b, a), w=[at_hz], fs=fs)
    return float(gd[0]) / fs


class CausalLowpass:
    """Streaming Butterworth low-pass with state; ``push(chunk)`` gives the same output as
    ``lowpass(whole, causal=True)`` whatever the chunking."""

    def __init__(self, cutoff_hz: float, fs: float, *, order: int = 3):
        self.sos = butter_sos(cutoff_hz, fs, order=order)
        self._zi: np.ndarray | None = None

    def push(self, x: np.ndarray) -> np.ndarray:
        a = np.asarray(x, dtype=np.float64)
        if a.shape[0] == 0:
            return a.copy()
        if self._zi is None:
            zi = _sig.sosfilt_zi(self.sos)
            self._zi = zi.reshape((self.sos.shape[0], 2) + (1,) * (a.ndim - 1)) * a[0]
        y, self._zi = _sig.sosfilt(self.sos, a, axis=0, zi=self._zi)
        return y


def uniform_grid(t0: float, t1: float, rate_hz: float) -> np.ndarray:
    """Timestamps ``t0, t0 + 1/rate, ...`` up to and including ``t1`` (within 1e-9 s)."""
    if not (np.isfinite(rate_hz) and rate_hz > 0):
        raise DataError(f"resample: rate {rate_hz!r} Hz is not a positive number")
    n = int(np.floor((t1 - t0) * rate_hz + 1e-9)) + 1
    return t0 + np.arange(max(n, 0)) / rate_hz


def interp_rows(t_new: np.ndarray, t: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Linear interpolation of each column of ``values`` (n, k) at ``t_new``."""
    v = np.asarray(values, dtype=np.float64)
    v2 = v.reshape(v.shape[0], -1)
    out = np.empty((t_new.shape[0], v2.shape[1]))
    for j in range(v2.shape[1]):
        out[:, j] = np.interp(t_new, t, v2[:, j])
    return out.reshape((t_new.shape[0],) + v.shape[1:])
