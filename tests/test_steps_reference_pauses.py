"""Decision 15 splits a foot reference into chains of touching strides only where ``pre_ic_s`` marks the
contact that opens each labelled chain (a mocap volume). A reference without it labels every stride, so a
pause between strides is labelled standing: a detection there is a false positive, not "outside labels"."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.io import Session
from pdrlearn.steps.evaluate import reference_events, score_steps


def _steps(pre_ic: bool) -> pd.DataFrame:
    # two walking bouts of 3 strides (1 s each) with a 3 s standing pause between them
    start = np.r_[0.0, 1.0, 2.0, 6.0, 7.0, 8.0]
    df = pd.DataFrame({"start_s": start, "end_s": start + 1.0, "ic_s": start + 1.0})
    if pre_ic:
        df["pre_ic_s"] = start
    return df


def _detections(times) -> pd.DataFrame:
    d = pd.DataFrame({"event_s": np.asarray(times, dtype=float)})
    d.attrs["unit"] = "foot"
    return d


def test_pause_of_a_complete_reference_is_scored():
    s = Session("complete", {}, steps=_steps(pre_ic=False))
    ref = reference_events(s, "foot")
    assert len(ref.intervals) == 1
    det = _detections([1.0, 2.0, 3.0, 4.5, 7.0, 8.0, 9.0])  # 4.5 s: a false step while standing
    sc = score_steps(det, s, unit="foot")
    assert sc["outside_labels"] == 0 and sc["false_positives"] == 1 and sc["precision"] < 1.0


def test_chains_opened_by_pre_ic_leave_the_gap_unscored():
    s = Session("mocap volume", {}, steps=_steps(pre_ic=True))
    ref = reference_events(s, "foot")
    assert len(ref.intervals) == 2  # the strides between the chains are unlabelled walking
    det = _detections([0.0, 1.0, 2.0, 3.0, 4.5, 6.0, 7.0, 8.0, 9.0])
    sc = score_steps(det, s, unit="foot")
    assert sc["outside_labels"] == 1 and sc["precision"] == 1.0


def test_reference_without_ic_says_it_scores_stride_starts():
    steps = _steps(pre_ic=False).drop(columns="ic_s")
    ref = reference_events(Session("no ic", {}, steps=steps), "foot")
    np.testing.assert_allclose(ref.times, steps["start_s"].to_numpy())
    assert "no ic_ms column" in ref.description
