"""Foot accelerometer detector: one long rest (a hesitation) must not raise the still time for the next
strides of a walker whose foot-flats are short (docs/decisions/steps.md 16)."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.steps import AccelStepDetector
from tests.test_steps_quiet import FAST, _session

# FAST strides (foot-flat 0.13 s) with one hesitation: a 0.30 s foot-flat, then FAST strides again
HESITATION = [(0.30, 0.0)] + FAST[1:]
D14 = {"quiet_rank": 1, "rests_only": False}  # decision 14 alone: the longest of the last 4 quiet runs


def _hesitating(fs: float):
    s, _ = _session(fs, FAST * 4 + HESITATION + FAST * 8, 1, lead_s=1.0)  # standing first
    return s, 13


@pytest.mark.parametrize("fs", [60.0, 102.4, 204.8])
def test_one_long_rest_does_not_merge_the_next_short_rests(fs):
    s, n = _hesitating(fs)
    # n - 1: the first stride after standing still needs 0.2 s (as in test_short_foot_flats_count_as_rests)
    assert n - 1 <= len(AccelStepDetector().detect(s)) <= n
    # the longest of the last 4 rests (decision 14 alone): 0.15 s still time after the 0.30 s rest,
    # the next 0.13 s foot-flats no longer end a swing and strides merge in pairs
    assert len(AccelStepDetector(**D14).detect(s)) <= n - 3  # 9 / 6 / 5 printed


def test_ms_patient_strides_after_a_long_rest():
    # gaitmap MS patient, right foot: a 0.29 s rest at 33.8 s raised the still time to 0.15 s and the
    # 0.12 s foot-flat at 35.86 s no longer ended a swing (stride 34.90-35.87 s of the rest-based
    # segmentation had no detection: 71 of 74 found, decision 16)
    from pdrlearn.io import read_session
    from pdrlearn.steps import score_steps
    from tests.conftest import external_session

    s = read_session(external_session("gaitmap_ms_right"))
    ev = AccelStepDetector().detect(s)["event_s"].to_numpy()
    assert ((ev > 34.90) & (ev < 35.87)).sum() == 1
    assert score_steps(AccelStepDetector().detect(s), s)["true_positives"] >= 72
    old = AccelStepDetector(**D14).detect(s)["event_s"].to_numpy()
    assert ((old > 34.90) & (old < 35.87)).sum() == 0


@pytest.mark.parametrize("fs", [60.0, 102.4])
@pytest.mark.parametrize("cuts", [[1] * 97 + [7, 13, 3], [0, 1, 2, 3, 5, 11, 17, 29, 31] * 10, [37] * 30])
def test_decision16_online_in_odd_chunks_equals_offline(fs, cuts):
    # the rest history (the last 4 quiet runs, the rank-2 still time, short runs left out) is kept across
    # pushes: chunked at odd sizes through the hesitation, the online detector gives the offline strides
    import pandas as pd

    from tests.steps_helpers import chunked

    s, _ = _hesitating(fs)
    det = AccelStepDetector()
    offline = det.detect(s)
    assert len(offline) >= 12
    pd.testing.assert_frame_equal(offline.reset_index(drop=True), chunked(det, det._inputs(s), cuts),
                                  check_dtype=False)


@pytest.mark.parametrize("rank", [0, -1, 1.5])
def test_quiet_rank_below_one_is_refused(rank):
    with pytest.raises(DataError, match="quiet_rank must be an integer >= 1"):
        AccelStepDetector(quiet_rank=rank)
