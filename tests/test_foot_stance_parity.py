"""Decision L29 (docs/decisions/localization.md): the streaming stance segmenter also applies the offline
stance test (the 0.1 s mean of |w| below the threshold), so that streaming finds the strides offline finds."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.stride import StanceSegmenter, stance_strides
from tests.conftest import external_session
from tests.test_stance_floor import _walk

L27_ONLY = {"stance_mean_min_s": 0.0}


def _sharp(t, gyr, stances, stance_s):
    """Swing samples at >= 2.5 rad/s (no slow swing edge lengthening the foot-flat)."""
    dt = t[1] - t[0]
    in_stance = np.abs(t[:, None] - stances[None, :]).min(axis=1) <= 0.5 * stance_s + 0.5 * dt
    swing = (t > 2.0) & (t < stances[-1] + 0.9) & ~in_stance
    gyr[swing, 1] = np.where(gyr[swing, 1] < 0, -1.0, 1.0) * np.maximum(np.abs(gyr[swing, 1]), 2.5)
    return gyr


def test_a_foot_flat_one_sample_short_is_still_a_stance():
    # 10-sample foot-flats at 102.4 Hz last 0.088 s from first to last sample: under E7/L27's 0.1 s
    t, gyr, _, stances = _walk(0.3, fs=102.4, stance_s=0.098, swing_s=0.8)
    gyr = _sharp(t, gyr, stances, 0.098)
    old, new = stance_strides(t, gyr, L27_ONLY), stance_strides(t, gyr)
    assert len(old) == 0  # every stance too short: no stride at all
    assert len(new) >= len(stances) - 1
    # boundaries in the stances (the last stride ends in the final standstill)
    assert np.abs(new[:-1, 1, None] - stances[None, :]).min(axis=1).max() < 0.06


def test_a_stance_split_by_a_short_bump_is_one_stance():
    # 0.16 s foot-flats split by a 0.05 s bump (the MS patient's right foot: 1.1-1.3 rad/s against a 0.84
    # threshold); 2 rad/s here, above the L27 threshold the bump itself raises (2 x its 0.1 s floor)
    t, gyr, _, stances = _walk(0.3, stance_s=0.16, swing_s=0.8)
    gyr = _sharp(t, gyr, stances, 0.16)
    dt = t[1] - t[0]
    for c in stances:
        gyr[np.abs(t - c) < 0.025 + dt / 2, 1] = 2.0
    old, new = stance_strides(t, gyr, L27_ONLY), stance_strides(t, gyr)
    assert len(old) == 0  # two 0.05 s halves, each shorter than 0.1 s
    assert len(new) >= len(stances) - 1 and np.diff(new[1:-1], axis=1).max() < 1.0  # one stride per 0.96 s


def test_mean_rule_is_chunk_invariant():
    t, gyr, _, _ = _walk(0.3, fs=102.4, stance_s=0.098, swing_s=0.8, seed=4)
    whole = stance_strides(t, gyr)
    seg, parts, i = StanceSegmenter(), [], 0
    rng = np.random.default_rng(2)
    while i < len(t):
        j = i + int(rng.integers(1, 40))
        parts += seg.update(t[i:j], gyr[i:j])
        i = j
    np.testing.assert_array_equal(np.array(parts).reshape(-1, 2), whole)


@pytest.mark.parametrize("name,min_matched", [("gaitmap_ms_right", 71), ("gaitmap_ms_left", 72),
                                              ("gaitmap_walk4x10_right", 30), ("gaitmap_walk4x10_left", 29)])
def test_streaming_finds_the_offline_strides(name, min_matched):
    """Streaming (``track --streaming``) against offline (M3 oracle, detector steps): strides overlapping with
    IoU >= 0.5. Before L29 the MS patient's right foot matched 68 of 72 (4 strides merged in streaming)."""
    from pdrlearn.io import read_session
    from pdrlearn.track.evaluate import match_by_overlap
    from pdrlearn.track.plasys import track_plasys

    s = read_session(external_session(name))
    logging.disable(logging.WARNING)
    try:
        off = track_plasys(s, method="M3", model="oracle", steps="detector", heading="foot").steps
        st = track_plasys(s, method="M3", model="oracle", streaming=True, heading="foot").steps
    finally:
        logging.disable(logging.NOTSET)
    pairs = match_by_overlap(pd.DataFrame(off[["start_s", "end_s"]]).reset_index(drop=True),
                             pd.DataFrame(st[["start_s", "end_s"]]).reset_index(drop=True), min_iou=0.5)
    assert len(pairs) >= min_matched, (name, len(pairs), len(off), len(st))
    assert len(st) <= len(off) + 1  # no extra splits (turn pivots) beyond a session-start stride
