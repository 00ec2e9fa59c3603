"""Decisions L317, L318, L327-L329: `pdrlearn gait` findings of the session 31 treadmill and prosthesis trials."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.bilateral import bilateral_gait


def _foot(ic, length=1.4, swing=0.45) -> pd.DataFrame:
    """A foot track's steps.csv: one row per stride, its IC (event_s), the toe-off before it (tc_s), its length."""
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - swing,
                         "length_m": np.broadcast_to(np.asarray(length, float), ic.shape).copy(), "gap_s": 0.0,
                         "unit": "foot"})


def test_l317_initiation_and_termination_half_strides_count_in_no_stride_length():
    """Trial finding 1: a symmetric walker whose right foot starts (a half stride from the feet side by side) and
    closes the walk (another half stride) read 14 % stride-length asymmetry; the bout's first and last contact are
    left out, so both feet read their steady 1.4 m."""
    right = _foot(np.arange(6) * 1.2, length=[0.7, 1.4, 1.4, 1.4, 1.4, 0.7])
    left = _foot(0.6 + np.arange(5) * 1.2, length=1.4)
    w = bilateral_gait(left, right)["walk"]
    assert w["stride_length_m_left"] == pytest.approx(1.4) and w["stride_length_m_right"] == pytest.approx(1.4)
    assert w["stride_length_m_si_pct"] == pytest.approx(0.0, abs=1e-9)
