"""Decision E308 (docs/decisions/export.md, session 47): the waist rhythm rules take the median / NaN-median of a
few numbers in Python (``_median_few``, ``_nanmedian_few``) instead of ``np.median`` / ``np.nanmedian``, with the
same floats: pinned here to numpy's values, to the bit, on the sizes and kinds of numbers the rules pass."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels import waist as W


def _cases():
    rng = np.random.default_rng(47)
    for _ in range(4000):
        n = int(rng.integers(1, 7))
        kind = int(rng.integers(0, 4))
        if kind == 0:  # step intervals in whole samples (ties and equal values)
            x = rng.integers(20, 160, size=n).astype(float)
        elif kind == 1:  # sub-sample intervals and heights
            x = rng.uniform(0.01, 200.0, size=n)
        elif kind == 2:  # values of any sign and size
            x = rng.normal(size=n) * 10.0 ** rng.integers(-8, 8)
        else:  # cumulative-sum differences as local_medians makes them (not exact)
            x = np.diff(np.concatenate([[0.0], np.cumsum(rng.uniform(0.3, 1.4, size=n + 3))]))[:n]
        yield x.tolist()


def test_median_few_is_numpys_median_to_the_bit():
    for x in _cases():
        got, want = W._median_few(x), float(np.median(x))
        assert got == want and isinstance(got, float), (x, got, want)


def test_nanmedian_few_is_numpys_nanmedian_to_the_bit():
    rng = np.random.default_rng(48)
    for x in _cases():
        y = [v if rng.random() > 0.3 else float("nan") for v in x]
        got = W._nanmedian_few(y)
        want = float(np.nanmedian(y)) if any(v == v for v in y) else float("nan")
        assert (got == want) or (got != got and want != want), (y, got, want)
    assert np.isnan(W._nanmedian_few([float("nan"), float("nan")]))
    assert W._nanmedian_few([float("nan"), 3.0]) == 3.0


def test_fir_taps_are_designed_once_read_only_and_equal_the_design():
    from pdrlearn.kernels import dsp

    a, b = W.fir_taps(2.5, 100.0, 30), W.fir_taps(2.5, 100.0, 30)
    assert a is b and not a.flags.writeable
    assert np.array_equal(a, dsp.firwin_lowpass(31, 2.5, 100.0))
    assert np.array_equal(W.fir_taps(2.5, 100.0, 29), dsp.firwin_lowpass(31, 2.5, 100.0))  # order made even


def test_local_period_takes_a_list_or_an_array_alike():
    t = np.cumsum(np.random.default_rng(49).uniform(40, 70, size=30))
    t[12:] += 200.0  # a gap over max_gap: sequences end there
    for k in range(t.size):
        for side in (-1, 1):
            a, b = W._local_period(t, k, side, 150.0), W._local_period(t.tolist(), k, side, 150.0)
            assert (a == b) or (a != a and b != b)
