"""Decision E371 (``uniform_clock="nearest"``): the live waist ``Bridge`` puts each pushed sample on its nearest
clock instant ``t0 + k / fs``, values as they are (no interpolation of the stamps' error into them); an instant with
no sample is filled as W59 fills a gap; a uniform stream passes as W59 passes it; the same whatever the chunking."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.waist_stream import Bridge, clock_option

FS = 50.0


def _phone(jitter_s: float, seed: int = 11, n: int = 600):
    """True samples every 1 / FS s stamped with Gaussian jitter (ms resolution), sorted, 1 % dropped (as phoneify)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / FS
    v = np.column_stack([np.sin(2 * np.pi * 1.8 * t + c) for c in range(6)])
    tj = np.round(t + rng.normal(0.0, jitter_s, n), 3)
    keep = rng.random(n) > 0.01
    keep[0] = keep[-1] = True
    order = np.argsort(tj, kind="stable")
    tj, v = tj[order][keep[order]], v[order][keep[order]]
    return tj - tj[0], v


def _push(t, v, clock, sizes=None):
    b = Bridge(FS, {}, uniform_clock=clock)
    sizes = sizes or [t.size]
    out, i = [], 0
    while i < t.size:
        for n in sizes:
            out.append(b(t[i:i + n], v[i:i + n]))
            i += n
    return np.concatenate([o[0] for o in out]), np.vstack([o[1] for o in out]), b


def test_each_sample_lands_on_its_nearest_instant_unchanged():
    t, v = _phone(0.004)
    bt, bv, b = _push(t, v, "nearest")
    k = np.rint(bt * FS)
    assert np.array_equal(k, np.arange(k.size)) and np.allclose(bt, k / FS, atol=1e-9)  # one per clock instant
    # the pushed values pass as they are on (nearly) every instant: E366's interpolation changes almost every one
    passed = np.isin(bv[:, 0], v[:, 0]).mean()
    assert passed > 0.95
    it, iv, _ = _push(t, v, True)
    assert np.isin(iv[:, 0], v[:, 0]).mean() < 0.5
    assert len(b.filled) >= 1  # the dropped samples' instants were filled (W59's fill, listed as W136's)


def test_a_uniform_stream_passes_as_the_default_and_chunking_does_not_matter():
    t, v = _phone(0.0)
    ft, fv, _ = _push(t, v, False)
    nt, nv, _ = _push(t, v, "nearest")
    assert ft.shape == nt.shape and np.max(np.abs(ft - nt)) <= 1e-9 and np.max(np.abs(fv - nv)) <= 1e-9
    jt, jv = _phone(0.006)
    whole = _push(jt, jv, "nearest")
    parts = _push(jt, jv, "nearest", sizes=[1, 7, 10, 3])
    assert np.array_equal(whole[0], parts[0]) and np.array_equal(whole[1], parts[1])


def test_the_keyword_values():
    assert clock_option("nearest") == "nearest" and clock_option(True) is True and clock_option(False) is False
    with pytest.raises(ValueError, match="nearest"):
        clock_option("closest")


def test_e372_the_clock_follows_the_stamps_phase_not_the_first_stamp():
    """E372: the first stamp 4 ms late (0.4 of a 100 Hz period), the others within 1 ms: E371's clock, anchored at
    it, puts many samples on a neighbour's instant; E372's follows the stamps' phase and puts each on its own."""
    fs = 100.0
    rng = np.random.default_rng(3)
    t = np.arange(400) / fs + np.round(rng.normal(0.0, 0.001, 400), 3)
    t[0] += 0.004
    v = np.column_stack([np.arange(400.0)] * 6)  # each sample's true index
    wrong = {}
    for clock in ("nearest", "nearest-phase"):
        b = Bridge(fs, {}, uniform_clock=clock)
        bt, bv = b(t, v)
        k = np.rint((bt - bt[0]) * fs)
        wrong[clock] = int(np.sum(bv[50:, 0] != k[50:]))  # after E372's phase has settled (~1 s at 50 Hz)
    assert wrong["nearest-phase"] == 0 and wrong["nearest"] > 20
