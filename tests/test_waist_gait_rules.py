"""Mobilise-D stride selection and walking-bout assembly on hand-made contact sequences (decision W47)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.waist import gait_rules as G
from pdrlearn.waist.events import steps_from_events


def walk(n: int, *, t0: float = 0.0, step_s: float = 0.6, length_m: float = 0.6):
    """``n`` contacts of one walking sequence: times, has_next, step lengths."""
    t = t0 + step_s * np.arange(n)
    hn = np.ones(n, dtype=bool)
    hn[-1] = False
    sl = np.where(hn, length_m, 0.0)
    return t, hn, sl


def join(*walks):
    return tuple(np.concatenate(parts) for parts in zip(*walks, strict=True))


def test_mobgap_constants():
    # mobgap 1.2.0 StrideSelection / WbAssembly "mobilised" defaults
    assert (G.MIN_STRIDE_S, G.MAX_STRIDE_S, G.MIN_STRIDE_LENGTH_M) == (0.2, 3.0, 0.15)
    assert (G.MIN_BOUT_STRIDES, G.MAX_BREAK_S) == (4, 3.0)


def test_strides_stay_inside_a_walking_sequence():
    _, hn, _ = join(walk(4), walk(3, t0=10.0))
    a, b = G.positional_strides(hn)
    assert a.tolist() == [0, 1, 4] and b.tolist() == [2, 3, 6]
    assert G.positional_strides(np.array([True, False]))[0].size == 0


def test_stride_selection_bounds():
    d = np.array([0.2, 0.21, 3.0, 3.01, 1.0, 1.0, 1.0])
    length = np.array([1.0, 1.0, 1.0, 1.0, 0.15, 0.151, np.nan])
    # duration exclusive below / inclusive above; length exclusive; NaN fails (mobgap's comparisons)
    assert G.select_strides(d, length).tolist() == [False, True, True, False, False, True, False]


def test_bout_assembly_break_and_size():
    s = np.array([0.0, 1.0, 2.0, 3.0, 7.0, 8.0, 9.0])
    e = s + 1.0
    # 4.0 -> 7.0 is a break of exactly 3 s: one bout (compared with <=)
    assert G.assemble_bouts(s, e).tolist() == [0] * 7
    s2 = s.copy()
    s2[4:] += 0.01  # a break just over 3 s: a bout of 4 strides and one of 3 (dropped)
    assert G.assemble_bouts(s2, s2 + 1.0).tolist() == [0, 0, 0, 0, -1, -1, -1]
    with pytest.raises(ValueError):
        G.assemble_bouts(s[::-1], e[::-1])


def test_a_walk_of_four_strides_is_kept_three_are_not():
    assert G.gait_rule_mask(*walk(6)).all()  # 6 contacts = 4 strides
    assert not G.gait_rule_mask(*walk(5)).any()  # 3 strides: no bout


def test_a_short_stride_loses_only_the_contact_of_no_other_stride():
    t, hn, sl = walk(12)
    sl[4:8] = 0.05  # strides 4->6, 5->7, 6->8 add up to 0.1 m; 3->5 and 7->9 to 0.65 m
    keep = G.gait_rule_mask(t, hn, sl)
    assert np.flatnonzero(~keep).tolist() == [6]  # 6 starts and ends only failing strides
    sl[4:8] = 0.08  # 0.16 m strides pass
    assert G.gait_rule_mask(t, hn, sl).all()


def test_a_stride_over_three_seconds_fails():
    t, hn, sl = walk(8, step_s=1.45)  # strides of 2.9 s pass
    assert G.gait_rule_mask(t, hn, sl).all()
    t, hn, sl = walk(8, step_s=1.55)  # 3.1 s strides fail: no bout
    assert not G.gait_rule_mask(t, hn, sl).any()


def test_a_break_over_three_seconds_splits_the_bout():
    # two sequences of 2 strides each: one bout of 4 if the break is <= 3 s, else two dropped bouts
    a = walk(4)  # strides end at 1.2 and 1.8 s
    for gap, kept in ((2.9, True), (3.1, False)):
        t, hn, sl = join(a, walk(4, t0=1.8 + gap))
        assert G.gait_rule_mask(t, hn, sl).all() == kept
        assert G.gait_rule_mask(t, hn, sl).any() == kept


def test_nan_step_length_fails_its_strides():
    t, hn, sl = walk(6)
    sl[2] = np.nan  # strides 1->3 and 2->4 fail: 2 of 4 left, no bout
    assert not G.gait_rule_mask(t, hn, sl).any()


def test_keep_contacts_relinks_steps():
    t = np.array([0.0, 0.6, 1.2, 1.8, 5.0, 5.6])
    steps = steps_from_events(t, np.arange(t.size), max_step_s=1.5)
    out = G.keep_contacts(steps, np.array([True, True, False, True, True, True]), max_step_s=1.5)
    assert out["event_s"].tolist() == [0.0, 0.6, 1.8, 5.0, 5.6]
    assert out["end_s"].tolist() == [0.6, 1.8, 1.8, 5.6, 5.6]
    assert out["has_next"].tolist() == [True, True, False, True, False]
    out = G.keep_contacts(steps, np.array([True, False, False, True, True, True]), max_step_s=1.5)
    assert out["has_next"].tolist() == [False, False, True, False]  # 0.0 -> 1.8 is longer than a step
    with pytest.raises(ValueError):
        G.keep_contacts(steps, np.ones(3, dtype=bool), max_step_s=1.5)
    # a sequence break (e.g. a recording gap cut by B11) is not bridged even when the contacts are close
    st = pd.DataFrame({"event_s": [0.0, 0.6, 1.2], "start_s": [0.0, 0.6, 1.2], "end_s": [0.6, 0.6, 1.2],
                       "has_next": [True, False, False], "confidence": [1.0, 0.5, 0.5]})
    out = G.keep_contacts(st, np.array([True, False, True]), max_step_s=1.5)
    assert out["has_next"].tolist() == [False, False]


def test_limits_hold_in_whole_samples():
    # mobgap compares samples / rate: 528 - 228 samples at 100 Hz are a 3 s break, which keeps one bout,
    # though 5.28 - 2.28 is 3.0000000000000004 in floats
    t = np.array([48, 108, 168, 228, 528, 588, 648, 708]) / 100.0
    hn = np.array([True, True, True, False, True, True, True, False])
    assert G.gait_rule_mask(t, hn, np.full(8, 0.6)).all()
    t[4:] += 0.01
    assert not G.gait_rule_mask(t, hn, np.full(8, 0.6)).any()
    # a 300-sample stride passes (10.3 - 7.3 = 3.000000000000001), a 20-sample one fails (1.03 - 0.83)
    d = np.array([10.3 - 7.3, 1.03 - 0.83])
    assert G.select_strides(d, np.ones(2)).tolist() == [True, False]
