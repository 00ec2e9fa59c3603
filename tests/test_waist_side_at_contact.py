"""Decision W235: ``side_at_contact`` -- the offline detector's sequence rules (W20's pruning and parity, W18's
side-filtered fills, W23, W28, W152) read each candidate maximum's W20 side at its initial contact (W3's AP maximum
before it, W129's cue) instead of at the maximum. The kernel by hand (the side read where asked; the maximum's
reading unchanged), the option's reach (offline only; the live trackers and W193 name it) and a simulated walk whose
contacts it does not change."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim import simulate
from pdrlearn.track.waist import OPTION_DEFAULTS, ignored_options_line, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.events import InitialContactDetector
from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS


def test_candidate_sides_read_at_the_contact_or_at_the_maximum():
    # three candidate maxima at 50, 150, 250; the AP acceleration peaks 10 samples before each (the contacts);
    # the lateral velocity has one sign at the contact and the other at the maximum (a side read 0.1 s late)
    n = 300
    cand = np.array([50, 150, 250])
    ap = np.zeros(n)
    ap[cand - 10] = 1.0
    v = np.zeros(n)
    v[cand - 10] = [1.0, -1.0, 1.0]
    v[cand] = [-1.0, 1.0, -1.0]
    every = np.ones(3, dtype=bool)
    np.testing.assert_array_equal(K.candidate_sides(v, cand, every, ap, 25), [1, -1, 1])
    np.testing.assert_array_equal(K.candidate_sides(v, cand, every), [-1, 1, -1])  # W20: at the maximum
    np.testing.assert_array_equal(K.candidate_sides(v, cand, every), K.step_sides(v[cand], every))
    # the AP maximum lies outside the search window: the window's largest AP sample (W3's fallback), here its start
    np.testing.assert_array_equal(K.candidate_sides(v, cand, every, ap, 5), K.step_sides(v[cand - 5], every))
    # a weak velocity at the contact is undecided (W20's 1/3 of the median at the accepted candidates)
    v[140] = -0.2
    assert K.candidate_sides(v, cand, every, ap, 25)[1] == 0


def test_the_option_is_offline_only_and_named_where_it_does_nothing():
    assert OPTION_DEFAULTS["side_at_contact"] is False and InitialContactDetector().side_at_contact is False
    assert InitialContactDetector(side_at_contact=True).rule_settings()["side_at_contact"] is True
    assert InitialContactDetector(side_at_contact=True, realtime=True).rule_settings()["side_at_contact"] is False
    assert InitialContactDetector(side_at_contact=True, learned=True).rule_settings()["side_at_contact"] is False
    assert InitialContactDetector().rule_settings()["side_at_contact"] is False
    assert "side_at_contact" in LIVE_UNAPPLIED_OPTIONS  # E107: the live trackers say they do not apply it
    o = dict(OPTION_DEFAULTS, side_at_contact=True)
    line = ignored_options_line(o, "waist-pendulum", True, "gyro", False, True)
    assert line is not None and "side_at_contact=true" in line and "W235" in line
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True) is None


@pytest.fixture(scope="module")
def walk():
    return simulate("A", 1906, rate_hz=100.0)


def test_a_clean_simulated_walk_keeps_its_contacts(walk):
    """On a regular walk the side at the maximum and at the contact agree: the same contacts either way."""
    off = track_waist(walk, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
    on = track_waist(walk, pipeline="waist-pendulum", side_at_contact=True).steps["event_s"].to_numpy(float)
    assert off.size > 10
    np.testing.assert_array_equal(on, off)


def test_the_measured_real_row_ha002_test11_w236():
    """W236 (W235's rule, not met): on HA002 Test11 the sides at the contact lose a hit and add a false contact
    (in-bout step_f1 0.8182 36/42 -> 0.7865 35/43 of 46); the default is unchanged."""
    from pdrlearn.io import read_session
    from pdrlearn.waist.evaluate import step_metrics
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    m = {v: step_metrics(track_waist(s, pipeline="waist-pendulum", **({"side_at_contact": True} if v else {})).steps,
                         s) for v in (False, True)}
    assert (m[False]["n_detected"], m[False]["n_reference"], round(m[False]["step_f1"], 4)) == (42, 46, 0.8182)
    assert (m[True]["n_detected"], round(m[True]["step_f1"], 4)) == (43, 0.7865)
