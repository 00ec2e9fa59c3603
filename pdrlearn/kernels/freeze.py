"""The freeze index of freezing of gait (decision W213): pure kernels.

Moore, MacDougall & Ondo 2008 (J Neurosci Methods 167:340-348) defined the freeze index (FI) as the power of the
vertical leg acceleration in a "freeze" band of 3-8 Hz over its power in a "locomotor" band of 0.5-3 Hz: trembling
in place puts the power above 3 Hz, walking below. Baechlin et al. 2010 (IEEE Trans Inf Technol Biomed 14:436-446)
computed it online on 4 s windows every 0.5 s (mean removed, no taper), flagged a window as freezing when the FI
exceeded a threshold and the summed power of both bands exceeded a second one (quiet standing has no locomotor
power, and its FI is noise), with a global FI threshold of 1.5. All these values are as published and recalled
(cross-read with a public re-implementation of both definitions); they were not verified against the papers' text
here. The power threshold's value is this module's (Baechlin's was in its device's raw units): decision W213.
"""

from __future__ import annotations

import numpy as np

#: Moore et al. 2008: the "locomotor" and "freeze" bands (Hz) of the vertical acceleration (as published; not
#: verified against the paper text here)
LOCOMOTOR_BAND_HZ = (0.5, 3.0)
FREEZE_BAND_HZ = (3.0, 8.0)
#: Baechlin et al. 2010: 4 s windows every 0.5 s (as published; not verified against the paper text here)
FI_WINDOW_S = 4.0
FI_STEP_S = 0.5
#: Baechlin et al. 2010: the global freeze-index threshold (as published; not verified against the paper text here)
FI_THRESHOLD = 1.5
#: decision W213: the least mean-square acceleration (m^2/s^4) in 0.5-8 Hz of a freezing window (RMS 0.1 m/s^2):
#: quiet standing is far below (a few hundredths RMS), trembling of the trial's smallest waist amplitude (0.6 m/s^2
#: peak) far above; Baechlin's power threshold, in physical units
FI_POWER_MIN = 0.01
#: windows per chunk of :func:`freeze_index` (review S29: all windows of 8 h at 100 Hz at once took ~0.5 GB); the
#: output does not depend on it
FI_CHUNK_WINDOWS = 2000
#: decision W213: the shortest freeze episode kept (s; one window step less gives no episode)
FREEZE_MIN_S = 1.0


def freeze_index(x: np.ndarray, fs: float, *, window_s: float = FI_WINDOW_S,
                 step_s: float = FI_STEP_S) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The freeze index of the uniformly sampled signal ``x`` (a vertical acceleration, m/s^2) at ``fs`` Hz.

    Returns ``(centre, fi, power)``: each window's centre sample index, its freeze index (freeze-band power /
    locomotor-band power; inf when the locomotor band is empty and the freeze band is not, 0 when both are) and
    its mean-square acceleration in both bands together (m^2/s^4). Windows of ``window_s`` every ``step_s``
    (Baechlin et al. 2010), the window's mean removed; none when ``x`` is shorter than one window."""
    x = np.asarray(x, dtype=float)
    n = int(round(window_s * fs))
    hop = max(1, int(round(step_s * fs)))
    if n < 2 or x.size < n:
        return np.zeros(0, dtype=int), np.zeros(0), np.zeros(0)
    starts = np.arange(0, x.size - n + 1, hop)
    f = np.fft.rfftfreq(n, 1.0 / fs)
    in_loco = (f >= LOCOMOTOR_BAND_HZ[0]) & (f < LOCOMOTOR_BAND_HZ[1])
    in_frz = (f >= FREEZE_BAND_HZ[0]) & (f <= FREEZE_BAND_HZ[1])
    loco, frz = np.empty(starts.size), np.empty(starts.size)
    for k in range(0, starts.size, FI_CHUNK_WINDOWS):  # a chunk of windows at a time: memory bounded, same output
        seg = x[starts[k:k + FI_CHUNK_WINDOWS, None] + np.arange(n)[None, :]]
        seg = seg - seg.mean(axis=1, keepdims=True)
        spec = np.abs(np.fft.rfft(seg, axis=1)) ** 2 * (2.0 / n**2)  # one-sided: mean square per bin (Parseval)
        loco[k:k + seg.shape[0]] = spec[:, in_loco].sum(axis=1)
        frz[k:k + seg.shape[0]] = spec[:, in_frz].sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        fi = np.where(loco > 0, frz / np.where(loco > 0, loco, 1.0), np.where(frz > 0, np.inf, 0.0))
    return starts + n // 2, fi, loco + frz


def freeze_episodes(t: np.ndarray, x: np.ndarray, fs: float, *, threshold: float = FI_THRESHOLD,
                    power_min: float = FI_POWER_MIN, min_s: float = FREEZE_MIN_S,
                    window_s: float = FI_WINDOW_S, step_s: float = FI_STEP_S) -> list[tuple[float, float, float]]:
    """Freeze episodes ``(start_s, end_s, peak_fi)`` of the signal ``x`` sampled uniformly at ``fs`` at times ``t``:
    the runs of windows whose freeze index exceeds ``threshold`` and whose band power is at least ``power_min``
    (Baechlin et al. 2010's two thresholds); each window stands for ``step_s`` around its centre; runs shorter than
    ``min_s`` are dropped (decision W213)."""
    t = np.asarray(t, dtype=float)
    centre, fi, power = freeze_index(x, fs, window_s=window_s, step_s=step_s)
    on = (fi > threshold) & (power >= power_min)
    out: list[tuple[float, float, float]] = []
    if not on.any():
        return out
    edges = np.flatnonzero(np.diff(np.r_[0, on.astype(np.int8), 0]))
    for a, b in zip(edges[::2], edges[1::2], strict=True):
        start = max(float(t[0]), float(t[centre[a]]) - 0.5 * step_s)
        end = min(float(t[-1]), float(t[centre[b - 1]]) + 0.5 * step_s)
        if end - start >= min_s:
            out.append((start, end, float(np.max(fi[a:b]))))
    return out


def inside_episodes(times: np.ndarray, episodes: list[tuple[float, float, float]]) -> np.ndarray:
    """Boolean mask of the ``times`` (s) that fall inside one of the ``episodes`` (start, end inclusive)."""
    times = np.asarray(times, dtype=float)
    mask = np.zeros(times.shape, dtype=bool)
    for a, b, *_ in episodes:
        mask |= (times >= a) & (times <= b)
    return mask
