"""Decision W317: experiments/waist_bout_turn_w317.py classes the tracker's own bout error (tracked - INDIP stride/2
per step) into turning / straight x count / step, straight steps slow / normal. Hand-made bouts of W220's test."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
from tests.test_waist_bout_terms import REF_IC, _session, _steps  # noqa: E402
from waist_bout_turn_w317 import CLASSES, classify  # noqa: E402

# every reference step 0.5 s (120 steps/min) and 0.6 m (W220's hand-made bout)
NORMAL_CAL_SPM, SLOW_CAL_SPM = 120.0, 140.0  # 120 < 0.9 x 140: the steps are slow against 140 (W211's x0.9)


def _run(steps, session, cal_spm=NORMAL_CAL_SPM):
    bouts, singles = classify(steps, session, "X", "calibrated", cal_spm)
    (b,) = bouts
    assert sum(b[c] for c in CLASSES) == pytest.approx(b["own_m"])  # the classes add up to the own error
    return b, singles


def _with_yaw(steps, dyaw):
    return steps.assign(dyaw_rad=np.r_[dyaw, 0.0])


def test_a_long_step_in_an_indip_turn_is_a_turn_step_and_its_pendulum_undoes_w19():
    s = _with_yaw(_steps(REF_IC, [0.6, 0.6, 0.7, 0.6, 0.6, 0.6]), [0, 0, 0.02, 0, 0, 0])
    b, singles = _run(s, _session(turns=[(1.0, 1.5)]))
    assert b["turn step"] == pytest.approx(0.1) and b["own_m"] == pytest.approx(0.1)
    assert b["straight step normal"] == pytest.approx(0.0)
    (turn,) = [r for r in singles if r["class"] == "turn step"]
    assert turn["turns_csv"] and not turn["yaw_turn"]
    assert turn["pendulum_m"] == pytest.approx(0.7 / np.cos(0.02))  # the length before W19's cos(turn)


def test_a_step_turning_the_pelvis_by_w82s_classifier_is_a_turn_step_without_a_turns_span():
    # 0.3 rad in 0.5 s = 0.6 rad/s, past the prior GMM's 0.136 rad/s boundary (W82); 0.02 rad = 0.04 rad/s is not
    s = _with_yaw(_steps(REF_IC, [0.6, 0.6, 0.7, 0.6, 0.6, 0.6]), [0, 0, 0.3, 0, 0, 0])
    b, singles = _run(s, _session())
    assert b["turn step"] == pytest.approx(0.1)
    assert [r["yaw_turn"] for r in singles] == [False, False, True, False, False, False]
    b, _ = _run(s.assign(dyaw_rad=np.r_[0, 0, 0.02, 0, 0, 0, 0.0]), _session())
    assert b["turn step"] == pytest.approx(0.0) and b["straight step normal"] == pytest.approx(0.1)


def test_straight_steps_are_slow_below_0_9_of_the_calibration_cadence():
    s = _with_yaw(_steps(REF_IC, [0.6, 0.6, 0.7, 0.6, 0.6, 0.6]), np.zeros(6))
    b, _ = _run(s, _session(), cal_spm=SLOW_CAL_SPM)
    assert b["straight step slow"] == pytest.approx(0.1) and b["straight step normal"] == pytest.approx(0.0)
    b, _ = _run(s, _session(), cal_spm=NORMAL_CAL_SPM)
    assert b["straight step normal"] == pytest.approx(0.1) and b["straight step slow"] == pytest.approx(0.0)


def test_an_extra_contact_in_a_turn_is_turn_count_and_not_a_single_step():
    c = np.r_[REF_IC[:3], 1.25, REF_IC[3:]]
    s = _with_yaw(_steps(c, [0.6, 0.6, 0.45, 0.45, 0.6, 0.6, 0.6]), np.zeros(7))
    b, singles = _run(s, _session(turns=[(1.0, 1.5)]))
    assert b["turn count"] == pytest.approx(0.3) and b["own_m"] == pytest.approx(0.3)
    assert len(singles) == 5  # the two halves of the split step are no single step
