"""Decision W131: W23's weight-shift test read at the initial contact, on every kept contact, sparing turns (option
``contact_shift`` of the offline ``InitialContactDetector``, measured and adopted as the default). The kernel on
hand-made contacts, the option end to end on a simulated pause (the one contact it drops is false), the realtime
detector and waist-pll unchanged, and the measured real MS001 Test11 row."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.steps.evaluate import score_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.events import InitialContactDetector
from tests.conftest import external_session

FS = 100.0
VMAX = np.arange(8) * 60 + 30  # kept contacts' vertical maxima, 0.6 s apart (one sequence)
HEIGHT = np.array([1.0, 1.1, 0.9, 0.3, 1.0, 1.2, 0.8, 1.0])  # the fourth under half its neighbours' (1.0)
V_IC = np.array([0.2, -0.2, 0.25, 0.01, 0.2, -0.22, 0.18, -0.2])  # lateral velocity at the ICs; the fourth undecided


def test_an_undecided_weak_contact_is_dropped_and_a_shift_a_bounce_or_a_turn_keeps_it():
    keep = K.unshifted_contacts(VMAX, HEIGHT, V_IC, FS)
    assert keep.tolist() == [True, True, True, False, True, True, True, True]
    # a weight shift at the contact (|v| >= 1/3 of the median 0.2) keeps it: the side is read at the contact
    assert K.unshifted_contacts(VMAX, HEIGHT, np.where(np.arange(8) == 3, 0.07, V_IC), FS).all()
    # half its neighbours' bounce or more keeps it (W23's 1/2: neighbours 1.1 0.9 1.0 1.2 -> median 1.05)
    assert K.unshifted_contacts(VMAX, np.where(np.arange(8) == 3, 0.53, HEIGHT), V_IC, FS).all()
    assert not K.unshifted_contacts(VMAX, np.where(np.arange(8) == 3, 0.52, HEIGHT), V_IC, FS)[3]
    # a contact where the pelvis turns is not judged
    assert K.unshifted_contacts(VMAX, HEIGHT, V_IC, FS, exempt=np.arange(8) == 3).all()
    # neighbours of another sequence (more than 1.5 s away) are no neighbours: alone, nothing to compare with
    far = np.array([30, 500, 1000])
    assert K.unshifted_contacts(far, np.array([1.0, 0.1, 1.0]), np.array([0.2, 0.0, -0.2]), FS).all()


@pytest.fixture(scope="module")
def pause():
    """Simulated user 2051 (fresh, the lead's 2000-2099 range; not in W131's measurement, users 2000-2049):
    W111's daily route, a 4 s stand between two walks."""
    route = ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, "
             "straight:4, turn:-135, straight:4, stand:3")
    return simulate_path(parse_route(route), UserProfile.from_seed(2051), rate_hz=100, seed=2051)


def test_the_default_drops_one_false_contact_of_a_simulated_pause_and_keeps_every_true_one(pause):
    truth = np.sort(pause.extras["ics"]["ic_s"].to_numpy(float))
    on = track_waist(pause, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
    off = track_waist(pause, pipeline="waist-pendulum", contact_shift=False).steps["event_s"].to_numpy(float)
    gone = np.setdiff1d(off, on)
    assert np.setdiff1d(on, off).size == 0 and gone.size == 1  # only removes, here exactly one contact
    assert np.min(np.abs(truth - gone[0])) > 0.25  # ... that is no true contact
    s_on, s_off = (score_events(x, truth, tolerance_s=0.25) for x in (on, off))
    assert s_on["true_positives"] == s_off["true_positives"]
    # the option is the detector's: InitialContactDetector(contact_shift=False) gives the contacts before W131
    imu = waist_imu(pause)
    old = InitialContactDetector(contact_shift=False, walk_threshold=0.5).detect(imu).steps_["event_s"]
    new = InitialContactDetector(walk_threshold=0.5).detect(imu).steps_["event_s"]
    assert np.setdiff1d(old, new).size == 1 and np.setdiff1d(new, old).size == 0


def test_realtime_and_the_pll_are_unchanged(pause):
    for kw in ({"pipeline": "waist-pendulum", "realtime": True}, {"pipeline": "waist-pll"}):
        on, off = track_waist(pause, **kw), track_waist(pause, contact_shift=False, **kw)
        np.testing.assert_array_equal(on.steps["event_s"], off.steps["event_s"])
    imu = waist_imu(pause)
    rt = InitialContactDetector(realtime=True, walk_threshold=0.5)
    assert rt.rule_settings()["contact_shift"] is False
    np.testing.assert_array_equal(rt.detect(imu).ic_,
                                  InitialContactDetector(realtime=True, walk_threshold=0.5,
                                                         contact_shift=False).detect(imu).ic_)


def test_the_measured_real_row_ms001_test11():
    """W131's (b) row: MS001 Test11 in-bout F1 0.8663 -> 0.8804 (81/96 -> 81/93 of 91), 4 contacts dropped."""
    s = read_session(external_session("mobgap_MS001_Test11_Trial1"))
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=False, parity_fill=False,  # measured before W159
                     stand_veto=False, turn_bridge=False)  # and before W219, W385
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False, contact_shift=False, parity_fill=False,
                      stand_veto=False, turn_bridge=False)
    assert len(off.steps) - len(on.steps) == 4 and on.info["options"]["contact_shift"] is True
    m0, m1 = step_metrics(off.steps, s), step_metrics(on.steps, s)
    assert (m0["n_detected"], m1["n_detected"], m1["n_reference"]) == (96, 93, 91)
    assert round(m0["step_f1"], 4) == 0.8663 and round(m1["step_f1"], 4) == 0.8804
