"""The freeze index is computed in chunks of windows, with the same output as all windows at once (review S29
item 4: memory)."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels import freeze
from pdrlearn.kernels.freeze import FREEZE_BAND_HZ, LOCOMOTOR_BAND_HZ, freeze_index


def _all_at_once(x, fs, window_s=4.0, step_s=0.5):  # the kernel before chunking (every window in one array)
    n, hop = int(round(window_s * fs)), max(1, int(round(step_s * fs)))
    starts = np.arange(0, x.size - n + 1, hop)
    seg = x[starts[:, None] + np.arange(n)[None, :]]
    seg = seg - seg.mean(axis=1, keepdims=True)
    spec = np.abs(np.fft.rfft(seg, axis=1)) ** 2 * (2.0 / n**2)
    f = np.fft.rfftfreq(n, 1.0 / fs)
    loco = spec[:, (f >= LOCOMOTOR_BAND_HZ[0]) & (f < LOCOMOTOR_BAND_HZ[1])].sum(axis=1)
    frz = spec[:, (f >= FREEZE_BAND_HZ[0]) & (f <= FREEZE_BAND_HZ[1])].sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        fi = np.where(loco > 0, frz / np.where(loco > 0, loco, 1.0), np.where(frz > 0, np.inf, 0.0))
    return starts + n // 2, fi, loco + frz


def test_chunked_freeze_index_equals_all_windows_at_once(monkeypatch):
    x = 9.81 + np.random.default_rng(29).standard_normal(100 * 300)
    x[5000:6000] = 0.0  # a flat stretch: FI 0
    monkeypatch.setattr(freeze, "FI_CHUNK_WINDOWS", 7)  # many chunks, the last one partial
    for fs in (100.0, 64.0):
        got, want = freeze_index(x, fs), _all_at_once(x, fs)
        for g, w in zip(got, want, strict=True):
            np.testing.assert_array_equal(g, w)
    got = freeze_index(x[:401], 100.0)  # exactly one window, one chunk
    assert got[0].size == 1 and np.array_equal(got[1], _all_at_once(x[:401], 100.0)[1])
