"""Decisions W235 / W237: the diagnosis script's stage of a missed contact and its other cues, by hand."""

from __future__ import annotations

import numpy as np
import pytest

M = pytest.importorskip("experiments.waist_ic_misses_w235")


def _cands(**over):
    c = {"filled": np.array([True, False, False, False, True, True]),
         "strong": np.array([True, False, True, True, True, True]),
         "pruned": np.array([True, False, False, True, True, True]),
         "rules": np.array([True, False, False, False, False, True]),
         "det": np.array([True, False, False, False, False, False]),
         "ic": np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])}
    c.update(over)
    return c


def test_the_first_stage_a_candidate_does_not_pass():
    c = _cands()
    track_ic = np.array([1.0])
    got = [M.stage_of(i, c, track_ic) for i in range(1, 6)]
    # 1: never accepted; 2: accepted, pruned by W20; 3: kept by W20 but not in the filled set (shortest-step
    # tie-break); 4: filled, dropped by W23; 5: through the rules, dropped by W131
    assert got == ["height/gate", "W20 prune", "min step", "W23", "W131"]
    assert M.stage_of(0, c, track_ic) == "timing"  # a contact of the track: matched elsewhere or timed too far
    assert M.stage_of(0, c, np.array([1.5])) == "track veto"  # the detector's, not the track's


def test_other_cues_read_an_ap_maximum_and_a_5hz_maximum_apart_from_the_candidates():
    fs = 100.0
    tm = np.arange(0, 3, 1 / fs)
    ap = np.zeros(tm.size)
    ap[102] = 2.0  # an AP maximum 0.02 s after t = 1.0
    v5 = np.zeros(tm.size)
    v5[115] = 0.8  # a 5 Hz vertical maximum 0.15 s after t = 1.0
    c = {"time": tm, "ap_sig": ap, "vf5": v5, "t": np.array([0.5, 2.0])}
    apc, v5c = M.other_cues(1.0, c, med_h=1.6, med_ap=1.0)
    assert apc == "+0.02, 2.00" and v5c == "+0.15, 0.50"
    c["t"] = np.array([1.2])  # a 2.5 Hz candidate 0.05 s from the 5 Hz maximum: not another step
    assert M.other_cues(1.0, c, med_h=1.6, med_ap=1.0)[1] == "-"
    assert M.other_cues(2.5, c, med_h=1.6, med_ap=1.0) == ("-", "-")


def test_the_stage_that_made_a_false_contact_w265():
    # candidates at samples 10..50; the detector's contacts: 10 (strong), 20 (a weak W18 fill inside a sequence),
    # 30 (a weak W28 end step: kept only with W28), and one at sample 35, no candidate (W152's contact on the sway)
    c = {"cand": np.array([10, 20, 30, 40, 50]), "strong": np.array([True, False, False, True, False]),
         "no_end": np.array([True, True, False, True, False]),
         "det_ic": np.array([0.09, 0.19, 0.29, 0.33]), "det_anchor": np.array([10, 20, 30, 35])}
    assert [M.fp_stage(t, c)[0] for t in (0.09, 0.19, 0.29, 0.33)] == ["2.5 Hz max", "W18 fill", "W28 end",
                                                                        "W152 parity"]
    assert M.fp_stage(0.09, c)[1] == 0 and M.fp_stage(0.33, c)[1] is None
    assert M.fp_stage(0.5, c) == ("not the detector's", None)  # a contact the detector did not give
