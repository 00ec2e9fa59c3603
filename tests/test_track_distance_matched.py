"""``distance_matched_error_pct``: the tracked distance over the strides matched to labelled ones, for a
reference that labels only part of a walk (gaitmap's motion-capture volume)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Session
from pdrlearn.track.evaluate import _ground_truth, _stride_lengths


def test_unlabelled_strides_do_not_enter_the_matched_distance():
    start = np.arange(6.0)
    est = pd.DataFrame({"start_s": start, "end_s": start + 1.0, "length_m": [0.5, 1.1, 1.1, 1.1, 1.1, 0.5],
                        "heading_rad": 0.0})
    ref = pd.DataFrame({"start_s": start[1:5], "end_s": start[1:5] + 1.0, "ic_s": start[1:5] + 1.0,
                        "length_m": 1.0})  # the first and last strides lie outside the labelled volume
    out = {"distance_m": float(est["length_m"].sum()), "n_steps": 6}
    session = Session("part-labelled", {}, steps=ref)
    result = SimpleNamespace(steps=est, trajectory=pd.DataFrame())
    _ground_truth(result, session, out)
    _stride_lengths(result, session, out)
    assert out["distance_error_pct"] == pytest.approx(100 * (5.4 / 4.0 - 1))  # whole track vs 4 strides
    assert out["stride_length_matched"] == 4
    assert out["distance_matched_error_pct"] == pytest.approx(10.0)  # 4.4 m over the 4 labelled strides
