"""Decisions W572 / W573: what W518's "stand" false positives are (INDIP's gaps > 1.2 s inside a bout, read on the
lower back's own signals) and the single-cue stop veto's bookkeeping (sequence edges spared, no cue no veto)."""

from __future__ import annotations

import numpy as np
import pytest

S = pytest.importorskip("experiments.waist_stand_fp_s50_w572")
V = pytest.importorskip("experiments.waist_stop_veto_s50_w573")


def test_sequences_and_the_walkers_local_step():
    e = np.array([0.0, 0.5, 1.0, 1.6, 5.0, 5.4, 5.8, 6.2])
    has_next = np.array([True, True, True, False, True, True, True, False])
    seq = S.sequences(e, has_next)
    assert seq.tolist() == [0, 0, 0, 0, 1, 1, 1, 1]
    assert S.local_step(e, seq, 1) == pytest.approx(0.5)  # median of 0.5, 0.5, 0.6
    assert S.local_step(e, seq, 6) == pytest.approx(0.4)
    assert np.isnan(S.local_step(e[:2], np.zeros(2, int), 0))  # too few contacts for a rhythm


def test_the_stop_veto_spares_sequence_edges_and_missing_cues():
    rec = {"inner": np.array([False, True, True, True, False]), "vloc": np.array([0.1, 0.2, np.nan, 0.9, 0.1])}
    assert V.dropped(rec, "vloc", True, 0.5).tolist() == [False, True, False, False, False]
    assert V.dropped(rec, "vloc", False, 0.5).tolist() == [False, False, False, True, False]
    assert not V.dropped(rec, "vloc", True, -np.inf).any()  # "no veto"


@pytest.fixture(scope="module")
def ha002_gaps():
    from pdrlearn.io import read_session
    from tests.conftest import external_session

    return {round(g["a"], 2): g for g in S.gap_rows("HA002", read_session(
        external_session("mobgap_HA002_Test11_Trial1")))}


def test_ha002_stops_are_turns_with_a_moving_trunk_and_a_quiet_stand_gets_no_contact(ha002_gaps):
    assert len(ha002_gaps) == 11
    turn = ha002_gaps[28.80]  # a 168 deg turn on the spot: INDIP right -> right, the track two contacts, one scored
    assert turn["feet"] == "rr" and turn["n"] == 2 and turn["n_fp"] == 1
    assert abs(turn["dyaw"]) > 150 and turn["vrel"] > 0.9 and turn["still"] == 0.0
    stop = ha002_gaps[27.52]  # the one weight-shift-like stand FP (28.11 s)
    assert stop["feet"] == "lr" and stop["at"] == "28.11" and stop["n_fp"] == 1 and stop["still"] > 0.3
    quiet = ha002_gaps[72.28]  # a 2.5 s quiet stand: still, no contact
    assert quiet["n"] == 0 and quiet["still"] > 0.6 and quiet["vrel"] < 0.35
