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


def test_headline_leads_with_the_matched_strides_and_names_both_spans_l419():
    """Decision L419 (session 34, trial T5 finding 6): the printed distance error compares like with like first (the
    matched tracked strides against their labelled strides), then the whole track with the spans it compares; the
    summary keys stay (distance_error_pct is still the whole track) and two are added."""
    from pdrlearn.cli.track import distance_error_phrase

    start = np.arange(6.0)
    est = pd.DataFrame({"start_s": start, "end_s": start + 1.0, "length_m": [0.5, 1.1, 1.1, 1.1, 1.1, 0.5],
                        "heading_rad": 0.0})
    ref = pd.DataFrame({"start_s": start[1:5], "end_s": start[1:5] + 1.0, "ic_s": start[1:5] + 1.0,
                        "length_m": 1.0})
    out = {"distance_m": float(est["length_m"].sum()), "n_steps": 6}
    session = Session("part-labelled", {}, steps=ref)
    result = SimpleNamespace(steps=est, trajectory=pd.DataFrame())
    _ground_truth(result, session, out)
    _stride_lengths(result, session, out)
    assert out["distance_matched_m"] == pytest.approx(4.4) and out["distance_matched_ref_m"] == pytest.approx(4.0)
    assert out["distance_error_scope"] == "whole track" and out["distance_error_pct"] == pytest.approx(35.0)
    text = distance_error_phrase(out)
    assert text.startswith(", distance error +10.00 % over the 4 strides matched to labels (4.40 m tracked vs "
                           "4.00 m labelled); whole track +35.00 % (all 6 tracked strides 5.40 m vs")
    full = {"distance_m": 4.0, "n_steps": 4, "distance_error_pct": 1.5, "stride_length_matched": 4,
            "distance_matched_error_pct": 1.5}
    assert distance_error_phrase(full) == ", distance error +1.50 %"  # every stride labelled: one number, as before
