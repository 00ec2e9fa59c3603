"""Decision 20 (docs/decisions/steps.md): two consecutive timed contacts of the same foot inside a bout bound a
contact the reference lost; one detection there is neither a hit nor a false positive."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Session
from pdrlearn.steps import score_steps
from pdrlearn.waist.evaluate import step_metrics


def _session(lost: bool = True, untimed: bool = False, two_bouts: bool = False) -> Session:
    # contacts every 0.5 s from 1.0 to 4.0 s, alternating feet; the right contact at 2.5 s is missing when
    # ``lost`` (2.0 left -> 3.0 left), with an ``ics_untimed`` entry for it when ``untimed``
    t = np.arange(1.0, 4.01, 0.5)
    foot = np.where(np.arange(t.size) % 2 == 0, "left", "right")
    wb = np.where(t < 2.75, 0, 1) if two_bouts else np.zeros(t.size, int)
    ics = pd.DataFrame({"wb_id": wb, "ic_s": t, "foot": foot})
    if lost:
        ics = ics[~np.isclose(ics["ic_s"], 2.5)]
    extras = {"ics": ics.reset_index(drop=True),
              "bouts": pd.DataFrame({"start_s": [1.0], "end_s": [4.0], "length_m": [4.0], "level": ["wb"]})}
    if untimed:
        extras["ics_untimed"] = pd.DataFrame({"after_s": [2.0], "before_s": [3.0]})
    return Session(name="lost", streams={}, steps=None, extras=extras)


def _steps(times) -> pd.DataFrame:
    t = np.asarray(times, float)
    return pd.DataFrame({"start_s": t, "end_s": t + 0.5, "event_s": t, "unit": "waist", "confidence": 1.0})


EVERY = np.arange(1.0, 4.01, 0.5)  # a detection at every contact the walker made, 2.5 s included


def test_a_detection_in_a_same_foot_gap_is_not_scored():
    sc = score_steps(_steps(EVERY), _session())
    assert sc["unscored_same_foot_gap"] == 1 and sc["unscored_untimed"] == 0
    assert sc["false_positives"] == 0 and sc["true_positives"] == 6 and sc["f1"] == 1.0
    # counted as a false positive, it gives the stricter F1 that the output also reports
    assert sc["f1_same_foot_gaps_scored"] == pytest.approx(12 / 13)
    assert step_metrics(_steps(EVERY), _session())["step_f1"] == 1.0


def test_only_one_detection_per_gap_and_none_near_its_ends():
    sc = score_steps(_steps([1.0, 1.5, 2.0, 2.4, 2.6, 3.0, 3.5, 4.0]), _session())
    assert sc["unscored_same_foot_gap"] == 1 and sc["false_positives"] == 1
    # within the tolerance of a contact: scored (a hit or a false positive), never left out
    sc = score_steps(_steps([1.0, 1.5, 2.0, 2.2, 3.0, 3.5, 4.0]), _session())
    assert sc["unscored_same_foot_gap"] == 0 and sc["false_positives"] == 1


def test_alternating_contacts_and_gaps_between_bouts_are_scored():
    sc = score_steps(_steps(EVERY), _session(lost=False))
    assert sc["unscored_same_foot_gap"] == 0 and sc["true_positives"] == 7
    # 2.0 left (bout 0) -> 3.0 left (bout 1): not one walk, so not a lost contact
    sc = score_steps(_steps(EVERY), _session(two_bouts=True))
    assert sc["unscored_same_foot_gap"] == 0 and sc["false_positives"] == 1


def test_a_gap_with_an_untimed_entry_is_left_to_the_untimed_rule():
    sc = score_steps(_steps([1.0, 1.5, 2.0, 2.4, 2.6, 3.0, 3.5, 4.0]), _session(untimed=True))
    assert sc["unscored_untimed"] == 1 and sc["unscored_same_foot_gap"] == 0 and sc["false_positives"] == 1
