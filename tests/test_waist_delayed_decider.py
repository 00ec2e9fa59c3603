"""Decision W31's decision state (`pdrlearn.waist._kernels.DelayedDecider`): fed in pieces, as the streaming
`waist-ic` detector feeds it (steps decision 17), it decides what `delayed_decisions` decides on the whole."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.waist import _kernels as K


def _detect(seen):
    def detect(lo, hi):
        seen.append((lo, hi))
        # contacts every 0.47 s; the window's end moves each by a sample (seen again, not repeated: 0.3 s)
        ic = np.arange(40, hi, 47) + (hi // 25) % 3
        ic = ic[(ic >= lo) & (ic < hi)]
        return ic - lo, ic - lo + 7, ic - lo + 3
    return detect


@settings(max_examples=40, deadline=None)
@given(n=st.integers(0, 1500), pieces=st.lists(st.integers(1, 400), max_size=12),
       delay_s=st.sampled_from([0.0, 0.1, 0.5, 1.75]), final=st.booleans())
def test_decider_fed_in_pieces_equals_delayed_decisions(n, pieces, delay_s, final):
    fs = 100.0
    kw = {"delay_s": delay_s, "hop_s": 0.25, "history_s": 1.0}
    seen_all: list = []
    whole = K.delayed_decisions(n, fs, _detect(seen_all), final=final, **kw)
    dec = K.DelayedDecider(fs, **kw)
    seen: list = []
    rows, m = [], 0
    for p in pieces:
        if m + p >= n:
            break
        m += p
        rows += dec.decide_until(m, _detect(seen))
        assert dec.next_t > m and dec.done <= m
    if final:
        rows += dec.decide_until(n, _detect(seen), end=True)
    else:
        rows += dec.decide_until(n, _detect(seen))
    got = np.array(rows, dtype=int).reshape(-1, 4)
    for a, b in zip(whole, got.T, strict=True):
        np.testing.assert_array_equal(a, b)
    # W113: the repeat check is relative to the window's contacts; at 0.47 s steps it is W16's 0.3 s cap
    assert np.all(np.diff(got[:, 0]) >= round(K.SHORTEST_STEP_S * fs))
    # the same windows, each at most span samples long
    assert seen == seen_all and all(hi - lo <= dec.span for lo, hi in seen)
