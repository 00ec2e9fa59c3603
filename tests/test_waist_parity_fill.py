"""Decision W152: a contact without a vertical maximum for two kept contacts of one decided side about two local
periods apart, at the opposite side's lateral-sway extreme (option ``parity_fill`` of the offline
``InitialContactDetector``, measured and not adopted: off by default). The kernel on a hand-made walk (it fires;
it must not for an opposite-side pair, an undecided sway, a pair too close for W148's window, a pair in two
sequences or no side scale), the option's reach (offline only, off by default), and the measured real HA001 Test11
row."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.events import InitialContactDetector
from tests.conftest import external_session

FS = 100.0
PER = 0.6  # the hand-made walk's step period (s)
# kept maxima 0.6 s apart, alternating, but the +1 step at 2.4 s has no maximum: -1 at 1.8 s and 3.0 s, a same-side
# pair two periods apart
KEPT_T = np.array([0.0, 0.6, 1.2, 1.8, 3.0, 3.6, 4.2, 4.8])
KEPT_SIDE = np.array([1, -1, 1, -1, -1, 1, -1, 1], dtype=np.int8)
T = np.arange(0.0, 5.2, 1.0 / FS)


def walk(kept_t=KEPT_T, side=KEPT_SIDE, gain: float = 1.0):
    """``(cand, keep, side, v_lat, scale)``: every candidate kept; the lateral velocity sways once per stride (+1 at
    the +1 steps, W20's sign convention), scaled by ``gain`` between the pair."""
    cand = np.round(np.asarray(kept_t) * FS).astype(int)
    v = np.cos(np.pi * T / PER)
    between = (T > 1.85) & (T < 2.95)
    v[between] *= gain
    return cand, np.ones(cand.size, dtype=bool), np.asarray(side, dtype=np.int8), v, K.side_scale(v[cand], cand >= 0)


def test_a_same_side_pair_two_periods_apart_gets_a_contact_at_the_opposite_sway_extreme():
    cand, keep, side, v, scale = walk()
    assert scale == pytest.approx(1.0)
    np.testing.assert_array_equal(K.parity_fill(cand, keep, side, v, scale, FS), [240])  # no maximum there
    v[250] = 1.5  # the placement follows the sway, not the pair's midpoint (2.4 s)
    np.testing.assert_array_equal(K.parity_fill(cand, keep, side, v, scale, FS), [250])


def test_no_contact_for_an_opposite_side_pair_an_undecided_sway_a_close_pair_two_sequences_or_no_scale():
    cand, keep, side, v, scale = walk()
    alt = side.copy()
    alt[4:] = -alt[4:]  # the pair alternates (-1, +1): nothing is missing
    assert K.parity_fill(cand, keep, alt, v, scale, FS).size == 0
    cand, keep, side, v, scale = walk(gain=0.3)  # the sway between the pair stays under W20's third of the median
    assert K.parity_fill(cand, keep, side, v, scale, FS).size == 0
    close = KEPT_T.copy()
    close[4:] -= 0.48  # the pair 0.72 s apart (1.2 periods): W148's window (1.3-2.7 periods) is empty
    cand, keep, side, v, scale = walk(kept_t=close)
    assert K.parity_fill(cand, keep, side, v, scale, FS).size == 0
    cand, keep, side, v, scale = walk()
    assert K.parity_fill(cand, keep, side, v, scale, FS, max_step_s=1.0).size == 0  # 1.2 s: two sequences
    assert K.parity_fill(cand, keep, side, v, 0.0, FS).size == 0


def test_the_option_is_off_by_default_and_offline_only():
    assert InitialContactDetector().parity_fill == "within" == OPTION_DEFAULTS["parity_fill"]  # W159 / W160 since
    assert InitialContactDetector(parity_fill=True).rule_settings()["parity_fill"] is True
    assert InitialContactDetector(parity_fill=True, realtime=True).rule_settings()["parity_fill"] is False
    assert InitialContactDetector(parity_fill=True, learned=True).rule_settings()["parity_fill"] is False


def test_the_measured_real_row_ha001_test11():
    """W152's (b) row: HA001 Test11 in-bout F1 0.9449 -> 0.9531 (60/64 -> 61/65 of 63): one contact added, at
    123.26 s, 0.09 s before INDIP's 123.35 s (W153: a miss between a same-side pair), none removed."""
    s = read_session(external_session("mobgap_HA001_Test11_Trial1"))
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False, parity_fill=False)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=False, parity_fill=True)
    added = np.setdiff1d(on.steps["event_s"].round(6), off.steps["event_s"].round(6))
    assert np.setdiff1d(off.steps["event_s"].round(6), on.steps["event_s"].round(6)).size == 0
    assert added.size == 1 and abs(added[0] - 123.26) < 0.005
    m0, m1 = step_metrics(off.steps, s), step_metrics(on.steps, s)
    assert (m0["n_detected"], m1["n_detected"], m1["n_reference"]) == (64, 65, 63)
    assert round(m0["step_f1"], 4) == 0.9449 and round(m1["step_f1"], 4) == 0.9531
