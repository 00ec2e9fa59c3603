"""Signal-processing primitives in numpy alone, for the waist pipelines and the lean runtime (decision W92).

The waist-only contact detector (seed 003 sec. 3.1, decisions W3-W31) and its live form need a windowed-sinc FIR
design, a peak picker, a moving average and zero-phase Butterworth filters. They were ``scipy.signal.firwin``,
``find_peaks``, ``butter`` + ``sosfiltfilt`` and ``scipy.ndimage.uniform_filter1d``; these are the same
algorithms in numpy, so :mod:`pdrlearn.runtime` can run the waist tracker without scipy. Each is pinned to its
scipy counterpart by ``tests/test_kernels_dsp.py`` (equal to the bit where the order of operations is scipy's:
``firwin``, ``find_peaks``, ``uniform_filter1d``; to rounding, 1e-12 relative, for the IIR filters, whose
sections are grouped differently). :func:`sosfilt` hands its loop to scipy's compiled one when the process has loaded
``scipy.signal`` already (decision E307: the same floats; it never imports scipy itself).
"""

from __future__ import annotations

import functools
import math
import sys

import numpy as np


# -- FIR design ---------------------------------------------------------------------------------------
def magnitude(v: np.ndarray) -> np.ndarray:
    """Euclidean norm of each row of ``v`` ((n, k) -> (n,)); a 1-D input is returned as ``|v|``
    (:func:`pdrlearn.signal.magnitude`, re-exported there)."""
    a = np.asarray(v, dtype=np.float64)
    if a.ndim == 1:
        return np.abs(a)
    return np.sqrt(np.einsum("ij,ij->i", a, a))


def firwin_lowpass(numtaps: int, cutoff_hz: float, fs: float) -> np.ndarray:
    """Hamming-windowed sinc low-pass of ``numtaps`` taps, unit gain at 0 Hz: ``scipy.signal.firwin(numtaps,
    cutoff_hz, fs=fs)`` (window method; Oppenheim & Schafer, Discrete-Time Signal Processing, sec. 7.5)."""
    c = float(cutoff_hz) / (0.5 * float(fs))
    m = np.arange(0, numtaps) - 0.5 * (numtaps - 1)
    h = c * np.sinc(c * m)
    h *= np.hamming(numtaps)
    return h / np.sum(h)


# -- peaks --------------------------------------------------------------------------------------------
def local_maxima(x: np.ndarray) -> np.ndarray:
    """Indices of the local maxima of ``x``: a sample (or the middle of a flat top, rounded down) higher than both
    neighbours; the first and last samples are none (as ``scipy.signal.find_peaks`` without conditions)."""
    x = np.asarray(x, dtype=np.float64)
    if x.size < 3:
        return np.zeros(0, dtype=np.intp)
    start = np.flatnonzero(np.concatenate([[True], x[1:] != x[:-1]]))  # runs of equal values
    end = np.append(start[1:] - 1, x.size - 1)
    v = x[start]
    k = np.arange(1, start.size - 1)
    top = (v[k - 1] < v[k]) & (v[k + 1] < v[k])
    k = k[top]
    return ((start[k] + end[k]) // 2).astype(np.intp)


def find_peaks(x: np.ndarray, *, height: float | None = None, distance: float | None = None) -> np.ndarray:
    """``scipy.signal.find_peaks(x, height=height, distance=distance)[0]``: the local maxima at least ``height``
    high, then, from the highest down, each keeps out the maxima closer than ``ceil(distance)`` samples."""
    x = np.asarray(x, dtype=np.float64)
    peaks = local_maxima(x)
    if height is not None:
        peaks = peaks[x[peaks] >= height]
    if distance is None or peaks.size < 2:
        return peaks
    d = math.ceil(distance)
    keep = np.ones(peaks.size, dtype=bool)
    order = np.argsort(x[peaks])  # scipy's priority order (the same sort)
    pl = peaks.tolist()
    for i in range(peaks.size - 1, -1, -1):
        j = int(order[i])
        if not keep[j]:
            continue
        k = j - 1
        while k >= 0 and pl[j] - pl[k] < d:
            keep[k] = False
            k -= 1
        k = j + 1
        while k < peaks.size and pl[k] - pl[j] < d:
            keep[k] = False
            k += 1
    return peaks[keep]


# -- moving average -----------------------------------------------------------------------------------
def uniform_filter1d(x: np.ndarray, size: int, *, origin: int = 0) -> np.ndarray:
    """Mean of ``x`` over ``size`` samples, edges extended with the edge value: ``scipy.ndimage.uniform_filter1d(
    x, size, mode="nearest", origin=origin)`` (output ``i`` averages ``x[i - size // 2 - origin ..]``), computed
    as scipy does, a running sum updated one sample at a time."""
    x = np.asarray(x, dtype=np.float64)
    n = x.size
    if n == 0:
        return x.copy()
    s1 = size // 2 + origin
    s2 = size - size // 2 - 1 - origin
    xp = np.concatenate([np.full(max(s1, 0), x[0]), x, np.full(max(s2, 0), x[-1])])
    first = np.cumsum(xp[:size])[-1] / size
    upd = (xp[size:size + n - 1] - xp[:n - 1]) / size
    return np.cumsum(np.concatenate([[first], upd]))


# -- Butterworth --------------------------------------------------------------------------------------
def butter_sos(order: int, cutoff_hz, fs: float, btype: str = "low") -> np.ndarray:
    """Second-order sections of a digital Butterworth filter (analog prototype poles on the unit circle, frequency
    transform, bilinear transform with pre-warping: Oppenheim & Schafer sec. 7.1-7.2), as ``scipy.signal.butter(
    order, cutoff_hz, btype, fs=fs, output="sos")`` up to how the poles are grouped in sections: ``btype`` "low" /
    "high" (``cutoff_hz`` a number) or "bandpass" (``(low, high)``)."""
    fs = float(fs)
    wn = np.atleast_1d(np.asarray(cutoff_hz, dtype=np.float64)) / (0.5 * fs)
    warped = 4.0 * np.tan(np.pi * wn / 2.0)  # pre-warped at the internal rate 2 (as scipy)
    p = -np.exp(1j * np.pi * np.arange(-order + 1, order, 2) / (2 * order))
    z = np.zeros(0, dtype=complex)
    k = 1.0
    if btype == "low":
        p = warped[0] * p
        k = warped[0] ** order
    elif btype == "high":
        z = np.zeros(order, dtype=complex)
        p = warped[0] / p  # the prototype's gain 1 / prod(-p) is 1 (its poles lie on the unit circle)
    elif btype == "bandpass":
        bw, w0 = warped[1] - warped[0], math.sqrt(warped[0] * warped[1])
        lp = p * bw / 2.0
        p = np.concatenate([lp + np.sqrt(lp ** 2 - w0 ** 2), lp - np.sqrt(lp ** 2 - w0 ** 2)])
        z = np.zeros(order, dtype=complex)
        k = bw ** order
    else:
        raise ValueError(f"butter_sos: btype {btype!r} is not low, high or bandpass")
    # bilinear transform at the internal rate 2 (fs2 = 4): z = (4 + s) / (4 - s)
    fs2 = 4.0
    zd = (fs2 + z) / (fs2 - z)
    pd = (fs2 + p) / (fs2 - p)
    zd = np.append(zd, -np.ones(len(pd) - len(zd)))
    kd = k * np.real(np.prod(fs2 - z) / np.prod(fs2 - p))
    return _zpk_sections(zd, pd, kd)


def _zpk_sections(z: np.ndarray, p: np.ndarray, k: float) -> np.ndarray:
    """Second-order sections of real coefficients from zeros / poles that come in conjugate pairs (a real one at
    most once per kind): each section takes a conjugate pole pair (or the real pole) and two zeros, the gain goes
    to the first section."""
    def pairs(r):
        r = np.asarray(r, dtype=complex)
        cplx = r[np.imag(r) > 1e-12]
        real = np.sort(np.real(r[np.abs(np.imag(r)) <= 1e-12]))
        out = [np.array([c, np.conj(c)]) for c in cplx[np.argsort(np.abs(cplx))]]
        out += [real[i:i + 2] for i in range(0, real.size, 2)]
        return out

    pp, zz = pairs(p), pairs(z)
    sos = np.zeros((len(pp), 6))
    for i, pr in enumerate(pp):
        zr = zz[i] if i < len(zz) else np.zeros(0)
        b = np.real(np.poly(zr)) if zr.size else np.array([1.0])
        a = np.real(np.poly(pr))
        b, a = np.concatenate([b, np.zeros(3 - b.size)]), np.concatenate([a, np.zeros(3 - a.size)])
        sos[i, :3], sos[i, 3:] = b, a
    sos[0, :3] *= k
    return sos


def _loaded_sosfilt_kernel():
    """The compiled loop behind ``scipy.signal.sosfilt`` (``scipy.signal._sosfilt._sosfilt(sos, x, zi)``, in place
    on ``x`` (signals, samples) and ``zi`` (signals, sections, 2)) when this process has imported ``scipy.signal``
    already, else None: never imports scipy itself, so the lean runtime stays numpy only (E307). The kernel is
    called directly because the public function's argument checks cost ~0.2 ms a call, more than the loop on a
    short chunk."""
    return getattr(sys.modules.get("scipy.signal._sosfilt"), "_sosfilt", None)


def sosfilt(sos: np.ndarray, x: np.ndarray, zi: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The cascade ``sos`` over ``x`` (n,) in transposed direct form II, from the state ``zi`` (n_sections, 2;
    None: zeros), as ``scipy.signal.sosfilt``; returns ``(y, zf)``. When the process has loaded ``scipy.signal``
    and every section is normalised (``a0 == 1``, as scipy requires), scipy's compiled loop runs: the same
    operations in the same order, so the same floats (decision E307, pinned by
    ``tests/test_dsp_speed_s47_e307.py``); otherwise :func:`sosfilt_loop`."""
    if np.ndim(x) != 1:  # one signal (samples,): both paths refuse the same (review R1 finding 6, session 47)
        raise ValueError(f"sosfilt: x must be one signal (samples,), not an array of shape {np.shape(x)}")
    kernel = _loaded_sosfilt_kernel()
    sos = np.asarray(sos, dtype=np.float64)
    if kernel is None or sos.ndim != 2 or sos.shape[0] == 0 or not bool(np.all(sos[:, 3] == 1.0)):
        return sosfilt_loop(sos, x, zi)
    y = np.array(x, dtype=np.float64, order="C").reshape(1, -1)  # a copy: the kernel works in place
    zs = np.zeros((1, sos.shape[0], 2)) if zi is None else np.array(zi, dtype=np.float64).reshape(1, -1, 2)
    try:
        kernel(np.array(sos, order="C"), y, zs)  # a writable copy: the kernel takes writable buffers only
    except (TypeError, ValueError):  # a scipy whose private kernel changed its arguments: the loop, same floats
        return sosfilt_loop(sos, x, zi)
    return y.reshape(-1), zs.reshape(sos.shape[0], 2)


def sosfilt_loop(sos: np.ndarray, x: np.ndarray, zi: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sosfilt` in numpy and Python alone (the lean runtime's path). Two sections run in one pass over the
    samples (the same operations in the same order per section as one pass per section, so the same floats: only
    fewer Python loop turns; the live waist tracker filters a 12 s window every 0.25 s, W31)."""
    y = np.asarray(x, dtype=np.float64).tolist()
    zs = np.zeros((sos.shape[0], 2)) if zi is None else np.array(zi, dtype=np.float64).reshape(sos.shape[0], 2)
    zf = np.empty_like(zs)
    co = []
    for s in range(sos.shape[0]):
        b0, b1, b2, a0, a1, a2 = (float(v) for v in sos[s])
        co.append((b0 / a0, b1 / a0, b2 / a0, a1 / a0, a2 / a0))
    s = 0
    while s < len(co):
        if s + 1 < len(co):  # two sections per pass
            (b0, b1, b2, a1, a2), (c0, c1, c2, d1, d2) = co[s], co[s + 1]
            z0, z1, w0, w1 = float(zs[s, 0]), float(zs[s, 1]), float(zs[s + 1, 0]), float(zs[s + 1, 1])
            for i, xi in enumerate(y):
                yi = b0 * xi + z0
                z0 = b1 * xi - a1 * yi + z1
                z1 = b2 * xi - a2 * yi
                ui = c0 * yi + w0
                w0 = c1 * yi - d1 * ui + w1
                w1 = c2 * yi - d2 * ui
                y[i] = ui
            zf[s], zf[s + 1] = (z0, z1), (w0, w1)
            s += 2
            continue
        b0, b1, b2, a1, a2 = co[s]
        z0, z1 = float(zs[s, 0]), float(zs[s, 1])
        for i, xi in enumerate(y):
            yi = b0 * xi + z0
            z0 = b1 * xi - a1 * yi + z1
            z1 = b2 * xi - a2 * yi
            y[i] = yi
        zf[s] = z0, z1
        s += 1
    return np.array(y), zf


def sosfilt_zi(sos: np.ndarray) -> np.ndarray:
    """Each section's state for a unit step's steady state, scaled by the gain of the sections before it:
    ``scipy.signal.sosfilt_zi`` (``lfilter_zi`` per section: ``(I - A) zi = B``, A the companion matrix)."""
    zi = np.empty((sos.shape[0], 2))
    scale = 1.0
    for s in range(sos.shape[0]):
        b, a = sos[s, :3] / sos[s, 3], sos[s, 3:] / sos[s, 3]
        ima = np.eye(2) - np.array([[-a[1], 1.0], [-a[2], 0.0]])
        zi[s] = scale * np.linalg.solve(ima, b[1:] - a[1:] * b[0])
        scale *= b.sum() / a.sum()
    return zi


@functools.lru_cache(maxsize=64)
def _sosfilt_zi_of(shape: tuple, data: bytes) -> np.ndarray:
    """:func:`sosfilt_zi` of the sections given by their bytes, computed once per design (read-only): the realtime
    waist detector (W31) zero-phase filters a window every 0.25 s with the same few designs."""
    zi = sosfilt_zi(np.frombuffer(data, dtype=np.float64).reshape(shape))
    zi.flags.writeable = False
    return zi


def sosfiltfilt(sos: np.ndarray, x: np.ndarray, padlen: int | None = None) -> np.ndarray:
    """Zero-phase ``sos`` over ``x`` (n,): odd extension by ``padlen`` samples (None: scipy's default, 3 x (2
    n_sections + 1) less the sections' trailing zeros), forward and backward passes from the steady state of the
    first sample of each, as ``scipy.signal.sosfiltfilt``."""
    x = np.asarray(x, dtype=np.float64)
    if padlen is None:
        ntaps = 2 * sos.shape[0] + 1 - min(int((sos[:, 2] == 0).sum()), int((sos[:, 5] == 0).sum()))
        padlen = 3 * ntaps
    if padlen >= x.size:
        raise ValueError(f"sosfiltfilt: the input must be longer than padlen = {padlen} samples")
    if padlen > 0:
        ext = np.concatenate([2 * x[0] - x[padlen:0:-1], x, 2 * x[-1] - x[-2:-padlen - 2:-1]])
    else:
        ext = x
    zi = _sosfilt_zi_of(sos.shape, np.asarray(sos, dtype=np.float64).tobytes())
    y, _ = sosfilt(sos, ext, zi * ext[0])
    y, _ = sosfilt(sos, y[::-1], zi * y[-1])
    y = y[::-1]
    return y[padlen:y.size - padlen] if padlen > 0 else y


@functools.lru_cache(maxsize=32)
def _butter_low(order: int, cutoff_hz: float, fs: float) -> np.ndarray:
    """:func:`butter_sos` low-pass, designed once per setting (read-only; :func:`lowpass` runs every 0.25 s in the
    realtime waist detector, W31, and the design cost as much as a window's filtering, as W43 found for W20's)."""
    sos = butter_sos(order, cutoff_hz, fs, "low")
    sos.flags.writeable = False
    return sos


def lowpass(x: np.ndarray, cutoff_hz: float, fs: float, *, order: int = 3) -> np.ndarray:
    """Zero-phase Butterworth low-pass of ``x`` (n,): :func:`pdrlearn.signal.lowpass` (``causal=False``; padding
    3 x (2 n_sections + 1), at most n - 1; a 0- or 1-sample input unchanged), in numpy."""
    a = np.asarray(x, dtype=np.float64)
    if a.shape[0] < 2:
        return a.copy()
    sos = _butter_low(int(order), float(cutoff_hz), float(fs))
    return sosfiltfilt(sos, a, padlen=min(3 * (2 * sos.shape[0] + 1), a.shape[0] - 1))
