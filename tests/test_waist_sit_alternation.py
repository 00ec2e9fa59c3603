"""Decision W180: `sit_veto="alternation"` - W109's rhythm veto that also spares an undecided contact between two
same-side contacts of its walking sequence (`undecided_between`); W181: measured, rule not met, an option value
(W185 made W184's "opposite" the offline default, so "off" is `sit_veto=False` here).
W179's re-measurement of `"rhythm"` on today's defaults is pinned by its rows here too."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import waist_metrics
from pdrlearn.waist.events import steps_from_events
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.posture import transfer_veto, undecided_between
from tests.conftest import external_session
from tests.test_waist_posture import FS, _imu


def test_undecided_between_is_an_undecided_contact_between_two_same_side_contacts_of_its_sequence():
    hn = np.ones(3, dtype=bool)
    assert undecided_between([1, 0, 1], hn).tolist() == [False, True, False]  # L ? L: the R of the sequence
    assert undecided_between([-1, 0, -1], hn).tolist() == [False, True, False]
    assert not undecided_between([1, 0, -1], hn).any()  # neighbours on opposite sides: no foot left for it
    assert not undecided_between([0, 0, 1], hn).any()  # a neighbour undecided
    assert not undecided_between([1, 1, 1], hn).any()  # decided itself: W109's pairs judge it
    assert not undecided_between([1, 0, 1], [False, True, True]).any()  # the one before ends its sequence
    assert not undecided_between([1, 0, 1], [True, False, True]).any()  # it ends its sequence
    assert not undecided_between([0, 1], [True, True]).any() and undecided_between([], []).size == 0
    side = np.array([1, -1, 0, -1, 1, 0, 1, 0])
    has_next = np.array([True, True, True, True, True, True, True, False])
    # 2: -1 ? -1 kept; 5: 1 ? 1 kept; 7: last contact, no neighbour after it
    assert undecided_between(side, has_next).tolist() == [False, False, True, False, False, True, False, False]


def test_the_alternation_veto_keeps_an_unswaying_contact_between_two_same_side_contacts():
    """W109's hand-made bend (test_waist_posture): a 1 Hz lateral sway stopped at 10.5-11.5 s; the rhythm veto drops
    the unswaying 11.0 s, whose neighbours 10.5 / 11.5 s sway to the same side: "alternation" keeps it."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    steps = steps_from_events(t, np.arange(50, 1950, 50))
    sway = np.sin(2.0 * np.pi * t) * ((t < 10.5) | (t > 11.5))
    imu = dataclasses.replace(_imu(Rotation.identity()), acc_ml=sway)
    assert transfer_veto(steps, imu, keep_rhythm=True).attrs["n_vetoed"] == 1
    out = transfer_veto(steps, imu, keep_rhythm=True, keep_between=True)
    assert out.attrs["n_vetoed"] == 0 and len(out) == len(steps)
    # without any sway every contact of the window is undecided: W104's five contacts go, with or without W180
    still = dataclasses.replace(imu, acc_ml=np.zeros(t.size))
    assert transfer_veto(steps, still, keep_rhythm=True, keep_between=True).attrs["n_vetoed"] == 5


def test_the_alternation_veto_removes_a_simulated_sit_to_stand():
    s = simulate_path(parse_route("straight:10, sit:20, straight:10"), UserProfile.from_seed(621), rate_hz=100,
                      seed=621)
    tr = s.extras["transfers"].iloc[0]
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto="alternation")
    e0, e1 = off.steps["event_s"].to_numpy(float), on.steps["event_s"].to_numpy(float)
    n_in = int(((e0 >= tr.start_s) & (e0 <= tr.end_s)).sum())
    assert n_in > 0 and not ((e1 >= tr.start_s) & (e1 <= tr.end_s)).any()
    assert on.info["n_vetoed_contacts"] == n_in and len(e1) == len(e0) - n_in


def test_an_upright_walk_is_unchanged():  # the default: W185 (tests/test_waist_sit_opposite.py)
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto="alternation")
    pd.testing.assert_frame_equal(on.steps, off.steps)
    assert off.info["n_vetoed_contacts"] == 0 and on.info["n_vetoed_contacts"] == 0


def test_a_bad_sit_veto_value_names_alternation():
    s = simulate_path([Stand(3.0), Straight(6.0), Stand(3.0)], UserProfile.from_seed(541), rate_hz=100, seed=541)
    values = r'"rhythm", "alternation", "opposite" \(decisions W104, W109, W180, W184\)'  # W184 added "opposite"
    with pytest.raises(DataError, match=values) as e:
        track_waist(s, pipeline="waist-pendulum", sit_veto="Alternation")
    assert "\n" not in str(e.value)


def _row(name: str, sit_veto) -> tuple[float, int]:
    s = read_session(external_session(f"mobgap_{name}_Test11_Trial1"))
    # turn_bridge false: the rows were measured before W385 made "side" the default (as W131 / W243's MS001 rows)
    m = waist_metrics(track_waist(s, pipeline="waist-pendulum", sit_veto=sit_veto, turn_bridge=False).steps, s)
    return round(float(m["step_f1"]), 4), int(m["n_detected"])


@pytest.mark.parametrize(("name", "off", "rhythm", "alternation"), [
    ("HA001", (0.9531, 65), (0.9683, 63), (0.9606, 64)),
    ("HA002", (0.8182, 42), (0.8046, 41), (0.8046, 41)),
    ("MS001", (0.8865, 94), (0.8962, 92), (0.8962, 92))])
def test_the_measured_real_test11_rows(name, off, rhythm, alternation):
    """W179 / W181 as printed (uncalibrated waist-pendulum, today's defaults, in-bout step F1 and detections):
    HA002's in-bout step (31.74 s) is lost by both vetoes, so W180's rule fails on the same row as W109's."""
    assert _row(name, False) == off
    assert _row(name, "rhythm") == rhythm
    assert _row(name, "alternation") == alternation


def test_where_the_alternation_veto_differs_from_the_rhythm_veto_on_ha001():
    """W181, looked at after the measurement: on HA001 Test11 "alternation" keeps 4.72 s and 123.76 s (each undecided
    between two left-side contacts), neither within 0.25 s of a reference contact; HA002's lost 31.74 s lies between
    contacts on opposite sides (31.46 s +1, 32.25 s -1), which W180's reading does not spare."""
    d = external_session("mobgap_HA001_Test11_Trial1")
    s = read_session(d)
    ic = pd.read_csv(d / "ics.csv")["ic_ms"].to_numpy(float) / 1000.0
    r = track_waist(s, pipeline="waist-pendulum", sit_veto="rhythm").steps["event_s"].to_numpy(float)
    a = track_waist(s, pipeline="waist-pendulum", sit_veto="alternation").steps["event_s"].to_numpy(float)
    extra = np.array([e for e in a if np.abs(r - e).min() > 1e-9])
    assert np.round(extra, 2).tolist() == [4.72, 123.76]
    assert all(np.abs(ic - e).min() > 0.25 for e in extra)


def test_the_lost_ha002_step_lies_between_contacts_on_opposite_sides():
    """W181 (after the measurement): HA002 Test11's in-bout contact at 31.74 s is undecided and its sequence
    neighbours 31.46 s / 32.25 s are on opposite decided sides - W109's literal wording ("neighbours that alternate
    with each other"), not W180's same-side reading; the next candidate, not measured here."""
    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    st = track_waist(s, pipeline="waist-pendulum", sit_veto=False).steps
    e, hn = st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool)
    imu = waist_imu(s)
    side = K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, e), hn)
    i = int(np.argmin(np.abs(e - 31.74)))
    assert abs(e[i] - 31.74) < 0.005 and hn[i - 1] and hn[i]
    assert (side[i - 1], side[i], side[i + 1]) == (1, 0, -1)
    assert not undecided_between(side, hn)[i]
