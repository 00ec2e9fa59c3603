"""Decision W159: ``parity_fill="within"`` keeps W152's contact only inside one walking sequence of the other contacts
(the step-length stage's split: initial contacts over W16's 1.5 s apart end a sequence). The mask by hand (kept
inside a sequence; dropped across a break, past a sequence end, before a sequence start), the option's values and
reach, and the measured real rows: HA002 Test11's bridging contact (W152's 10.13 s across the 9.47 -> 11.51 s break)
is not added, HA001's in-sequence one is. Rule met, the default not yet changed (W160)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.track.waist import OPTION_DEFAULTS, PARITY_FILL_VALUES, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.events import InitialContactDetector
from tests.conftest import external_session

FS = 100.0
MAX_GAP = K._max_gap(1.5, FS)  # W16's longest step, W32's whole samples


def test_a_filled_contact_is_kept_inside_a_sequence_and_dropped_across_a_break():
    # contacts at 0, 0.6, 1.2 s, a 2.0 s break, then 3.2, 3.8 s; W152 adds 0.9 s (inside) and 2.2 s (bridging)
    ic = np.array([0, 60, 90, 120, 220, 320, 380])
    added = np.array([False, False, True, False, True, False, False])
    np.testing.assert_array_equal(K.inside_sequences(ic, added, MAX_GAP), ~np.isin(ic, [220]))
    # the break is exactly 1.5 s: one sequence (W32), the contact in it stays
    ic2 = np.array([0, 60, 120, 195, 270])
    added2 = np.array([False, False, False, True, False])
    assert K.inside_sequences(ic2, added2, MAX_GAP).all()
    ic2[-1] += 1  # 1.51 s: two sequences, the contact would join them
    assert not K.inside_sequences(ic2, added2, MAX_GAP)[3]


def test_a_filled_contact_at_a_sequence_end_or_start_is_dropped():
    ic = np.array([10, 40, 100, 160, 220])
    added = np.array([True, False, False, False, True])  # before the first and after the last unflagged contact
    np.testing.assert_array_equal(K.inside_sequences(ic, added, MAX_GAP), [False, True, True, True, False])
    assert K.inside_sequences(ic, np.zeros(5, dtype=bool), MAX_GAP).all()  # nothing flagged: nothing dropped
    same = np.array([0, 60, 60, 120])  # a flagged contact on an unflagged one's sample splits no step
    assert not K.inside_sequences(same, np.array([False, False, True, False]), MAX_GAP)[2]


def test_the_value_is_offline_only_and_others_are_refused(tmp_path):
    assert PARITY_FILL_VALUES == (False, True, "within")
    assert InitialContactDetector(parity_fill="within").rule_settings()["parity_fill"] == "within"
    assert InitialContactDetector(parity_fill="within", realtime=True).rule_settings()["parity_fill"] is False
    assert InitialContactDetector(parity_fill="within", learned=True).rule_settings()["parity_fill"] is False
    assert OPTION_DEFAULTS["parity_fill"] == "within" == InitialContactDetector().parity_fill  # W160: adopted
    s = read_session(external_session("mobgap_HA002_Test5_Trial1"))
    with pytest.raises(DataError, match="parity_fill 'inside'.*within"):
        track_waist(s, pipeline="waist-pendulum", parity_fill="inside")


def test_the_measured_real_rows_ha002_bridge_dropped_ha001_kept():
    """W159's (b) rows: W152's contact at HA002 10.13 s joins the 9.47 s and 11.51 s contacts (2.04 s apart, two
    sequences): "within" does not add it (HA002 as off, 36/42 of 46); HA001's at 123.26 s lies inside a sequence and
    stays (0.9449 -> 0.9531, 60/64 -> 61/65 of 63)."""
    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    r = {v: track_waist(s, pipeline="waist-pendulum", sit_veto=False, parity_fill=v).steps  # measured before W185
         for v in (False, True, "within")}
    ev = {v: r[v]["event_s"].round(6).to_numpy() for v in r}
    assert np.abs(np.setdiff1d(ev[True], ev[False]) - 10.13).max() < 0.005  # W152 adds it
    np.testing.assert_array_equal(ev["within"], ev[False])
    m = step_metrics(r["within"], s)
    assert (m["n_detected"], m["n_reference"], round(m["step_f1"], 4)) == (42, 46, 0.8182)
    s = read_session(external_session("mobgap_HA001_Test11_Trial1"))
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False, parity_fill=False).steps
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=False, parity_fill="within").steps
    added = np.setdiff1d(on["event_s"].round(6), off["event_s"].round(6))
    assert added.size == 1 and abs(added[0] - 123.26) < 0.005
    m0, m1 = step_metrics(off, s), step_metrics(on, s)
    assert (m0["n_detected"], m1["n_detected"], m1["n_reference"]) == (64, 65, 63)
    assert round(m0["step_f1"], 4) == 0.9449 and round(m1["step_f1"], 4) == 0.9531
