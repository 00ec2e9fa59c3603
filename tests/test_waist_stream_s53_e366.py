"""Decision E366 (an option, ``uniform_clock=True``; not adopted): the live waist trackers' ``Bridge`` puts the
pushed samples on the offline uniform clock ``t0 + k / fs`` (B33 / W34): a belt phone's jittered stamps no longer add
made-up samples (trial s53t2 F3: +4 % live distance at 4 ms jitter, 50 Hz), a uniform stream passes unchanged, the
output is the same whatever the chunking."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.waist import vertical_excursion
from pdrlearn.kernels.waist_stream import Bridge

FS = 50.0
F_STEP = 1.8  # Hz, a walker's step rate: the trunk's vertical oscillation (seed 003 sec. 3.2)


def _signal(t: np.ndarray) -> np.ndarray:
    """Six channels of the true motion at the true times ``t``: a vertical acceleration at the step rate (amplitude
    3 m/s^2: a ~2.3 cm excursion), the rest small."""
    a = 3.0 * np.sin(2 * np.pi * F_STEP * t)
    return np.column_stack([a, 0.1 * np.cos(t), np.full_like(t, 9.81), 0.2 * np.sin(3 * t), 0 * t, 0.05 * t])


def _phone(jitter_s: float, seed: int = 7, n: int = 1000):
    """As the trial's phoneify: true samples every 1 / FS s, stamped with Gaussian jitter, sorted, 1 % dropped."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / FS
    v = _signal(t)
    tj = t + rng.normal(0.0, jitter_s, n)
    order = np.argsort(tj)
    keep = rng.random(n) > 0.01
    keep[0] = keep[-1] = True
    tj, v = tj[order][keep], v[order][keep]
    return tj - tj[0], v


def _push(t, v, sizes=None):
    b = Bridge(FS, {}, uniform_clock=True)
    if sizes is None:
        return b(t, v)
    out_t, out_v, i = [], [], 0
    for n in sizes:
        if i >= t.size:
            break
        ot, ov = b(t[i:i + n], v[i:i + n])
        out_t.append(ot)
        out_v.append(ov)
        i += n
    return np.concatenate(out_t), np.vstack(out_v)


@pytest.mark.parametrize("jitter_ms", [4.0, 6.0])
def test_a_jittered_stream_keeps_its_sample_count_and_the_step_excursion(jitter_ms):
    t, v = _phone(jitter_ms / 1e3)
    bt, bv = _push(t, v)
    # W59's fill had added one sample to every interval over 1.5 periods (4 ms: ~4 % of them, no sample missing)
    assert bt.size == int(np.floor(t[-1] * FS)) + 1
    assert np.allclose(np.diff(bt), 1.0 / FS, atol=1e-6)  # the uniform clock t0 + k / fs
    # the kernel that reads the step length (dt = 1 / fs): a step's excursion as without jitter (before: ~8 % high)
    ref = _signal(np.arange(bt.size) / FS)[:, 0]
    n = int(round(FS / F_STEP))  # one step's samples
    ratio = [vertical_excursion(bv[:, 0], FS, i, i + n) / vertical_excursion(ref, FS, i, i + n)
             for i in range(100, 900, 28)]
    assert vertical_excursion(ref, FS, 200, 200 + n) > 0.01 and abs(np.mean(ratio) - 1.0) < 0.02


def test_the_default_keeps_w59s_fill_and_the_trackers_take_the_option():
    """E366 not adopted (its rule failed at 100 Hz): W59's fill stays the default; the option reaches the Bridge."""
    t, v = _phone(0.004)
    assert Bridge(FS, {})(t, v)[0].size > int(np.floor(t[-1] * FS)) + 20  # W59: a made-up sample per long interval
    from pdrlearn.runtime.waist import WaistStream

    st = WaistStream.__new__(WaistStream)
    st._uniform_clock, st._proc, st._thr, st._max_step_s, st._rot, st.fs = True, None, 0.5, 1.5, None, FS
    st.options = {"rhythm": True}
    st._add = None
    st._start_proc()
    assert st._proc.bridge.uniform_clock is True


def test_a_uniform_stream_passes_unchanged_and_chunks_do_not_matter():
    t = np.arange(600) / FS
    v = _signal(t)
    bt, bv = _push(t, v)
    assert np.array_equal(bt, t) and np.array_equal(bv, v)  # bit for bit: a uniform stream is untouched
    tj, vj = _phone(0.004)
    one = _push(tj, vj)
    sizes = np.random.default_rng(3).integers(1, 40, 2000)
    chunked = _push(tj, vj, sizes)
    assert np.array_equal(one[0], chunked[0]) and np.array_equal(one[1], chunked[1])
    # a dropped sample is still bridged on the clock (W59), a long gap still filled as a rest
    g = Bridge(FS, {}, uniform_clock=True)
    gt, gv = g(np.r_[t[:100], t[102:]], np.vstack([v[:100], v[102:]]))
    assert np.array_equal(gt[:100], t[:100]) and gt.size == t.size and g.filled == [(t[99], t[102])]
    gaps: dict = {}
    g = Bridge(FS, gaps, uniform_clock=True)
    gt, gv = g(np.r_[t[:100], t[200:]], np.vstack([v[:100], v[200:]]))
    assert gt.size == t.size and np.all(gv[100:199, 3:] == 0.0) and gaps == {"online stream": [(t[99], t[200])]}
