"""Fixes from the real-data sweep (docs/real-data-sweep.md): the PLL step-length model is not extrapolated
past its frequency range (W37), a waist track's reference distance from strides of both feet counts the path
once (W38), and a calibration walk with an implausible known distance warns (W39)."""

from __future__ import annotations

import logging
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import Session, read_session
from pdrlearn.track.evaluate import _ground_truth
from pdrlearn.waist.calibration import PLAUSIBLE_GAIN, calibrate, check_gain
from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.steplength import RUN_MAX_HZ, WALK_MAX_HZ, CalibrationWalk, fit_frequency, frequency_lengths

EXT = Path(__file__).resolve().parents[1] / "datasets" / "external"
P = WaistParams(leg_m=0.9, a_walk=0.42, b_walk=0.06, a_run=0.336, b_run=-0.084)


def test_spurious_fast_steps_keep_the_length_at_the_end_of_the_walking_range():
    f = np.array([1.8, 2.2, 2.9, 5.3])
    sl = frequency_lengths(f, P, running=np.zeros(4, dtype=bool))
    top = 0.42 * WALK_MAX_HZ - 0.06
    assert sl[:2] == pytest.approx(0.42 * f[:2] - 0.06)  # inside the range: the line
    assert sl[2:] == pytest.approx([top, top])  # was 1.16 and 2.17 m
    run = frequency_lengths(np.array([3.0, 6.0]), P, running=np.ones(2, dtype=bool))
    assert run == pytest.approx([0.336 * 3.0 + 0.084, 0.336 * RUN_MAX_HZ + 0.084])


def test_offset_fit_sums_the_walk_as_the_capped_tracker_does():
    f = np.array([1.9, 2.0, 2.6, 1.9])
    w = CalibrationWalk(3.0, f, np.zeros(4))
    a, b, _ = fit_frequency([w], P)
    p = WaistParams(a_walk=a, b_walk=b)
    assert frequency_lengths(f, p, running=np.zeros(4, dtype=bool)).sum() == pytest.approx(3.0)


def _both_feet_session(with_foot=True):
    ic = np.array([6.73, 7.63, 7.98, 8.74, 9.10, 9.75, 10.16])
    ref = pd.DataFrame({"start_s": ic, "end_s": ic + 1.1, "ic_s": ic,
                        "length_m": [0.97, 1.15, 1.18, 1.12, 1.21, 1.10, 0.99]})
    if with_foot:
        ref["foot"] = ["left", "right"] * 3 + ["left"]
    return Session("both-feet", {}, steps=ref)


@pytest.mark.parametrize("unit", ["waist", "foot"])
def test_waist_reference_from_strides_of_both_feet_counts_the_path_once(unit):
    est = pd.DataFrame({"start_s": [6.7], "end_s": [11.3], "length_m": [4.75], "unit": unit})
    out = {"distance_m": 4.75, "n_steps": 1}
    _ground_truth(SimpleNamespace(steps=est, trajectory=pd.DataFrame()), _both_feet_session(), out)
    if unit == "waist":  # the left foot's 4 strides span the walk: 4.35 m, not 7.72 m
        assert out["distance_ref_m"] == pytest.approx(0.97 + 1.18 + 1.21 + 0.99)
    else:  # foot tracks unchanged
        assert out["distance_ref_m"] == pytest.approx(7.72)


def test_waist_reference_of_one_foot_is_its_sum():
    est = pd.DataFrame({"start_s": [6.7], "end_s": [11.3], "length_m": [4.75], "unit": "waist"})
    out = {"distance_m": 4.75, "n_steps": 1}
    _ground_truth(SimpleNamespace(steps=est, trajectory=pd.DataFrame()), _both_feet_session(False), out)
    assert out["distance_ref_m"] == pytest.approx(7.72)


def _walk(distance, n=9):
    g = np.full(n, 0.6)  # pendulum chord of each step at K = 1: 5.4 m for the walk
    return CalibrationWalk(distance, np.full(n, 1.8), g, name="walk-A")


def test_implausible_calibration_distance_warns_once_naming_the_walk():
    base = WaistParams(leg_m=0.9, k=1.0, f_m=0.0)
    assert check_gain([_walk(5.0)], "waist-pendulum", base) == []
    lo, hi = PLAUSIBLE_GAIN
    assert lo < 1.0 < hi
    msgs = check_gain([_walk(5.0), _walk(20.0)], "waist-pendulum", base)
    assert len(msgs) == 1 and "walk-A" in msgs[0] and "--distance" in msgs[0] and "3.70 x" in msgs[0]
    pll = WaistParams(a_walk=0.42, b_walk=0.06)  # 9 steps at 1.8 Hz: 9 x 0.696 = 6.26 m
    assert check_gain([_walk(6.0)], "waist-pll", pll) == []
    assert len(check_gain([_walk(25.0)], "waist-pll", pll)) == 1
    with pytest.raises(DataError):
        check_gain([CalibrationWalk(5.0, np.full(3, 1.8), np.zeros(3), name="still")], "waist-pendulum", base)


@pytest.mark.skipif(not (EXT / "mobgap_HA002_Test5_Trial1").is_dir(), reason="needs `make external`")
def test_calibrate_with_a_wrong_distance_warns(caplog):
    # a ~5 m walk given as 20 m: K = 4.15 (3.93 before W131 dropped its first contact, 1.49 s: no weight shift, a
    # weak bounce 0.95 s before the next; the recording has no reference contacts to say whether it was a step)
    s = read_session(EXT / "mobgap_HA002_Test5_Trial1")
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        p = calibrate([s], "waist-pendulum", distances=[20.0])
    warn = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING and "W169" not in r.getMessage()]
    assert p.k == pytest.approx(4.15, abs=0.01)  # (W169's short-walk warning, a 5 m walk, is counted apart)
    assert len(warn) == 1 and "mobgap_HA002_Test5_Trial1" in warn[0] and "--distance" in warn[0]
    assert any("decision W39" in n for n in p.notes)
