"""Decision W184: `sit_veto="opposite"` - W109's rhythm veto that also spares an undecided contact between two
contacts of its walking sequence on opposite decided sides (`undecided_between(..., opposite=True)`: an extra contact
inside a left/right pair); W180's same-side case is not spared by this value. W185: W184's rule met, the default of
offline tracks (realtime tracks keep no veto unless they set it)."""

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
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.events import steps_from_events
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.posture import transfer_veto, undecided_between
from tests.conftest import external_session
from tests.test_waist_posture import FS, _imu


def test_undecided_between_opposite_is_an_undecided_contact_between_two_opposite_side_contacts_of_its_sequence():
    hn = np.ones(3, dtype=bool)
    assert undecided_between([1, 0, -1], hn, opposite=True).tolist() == [False, True, False]  # L ? R
    assert undecided_between([-1, 0, 1], hn, opposite=True).tolist() == [False, True, False]  # R ? L
    assert not undecided_between([1, 0, 1], hn, opposite=True).any()  # L ? L: W180's case, not this value's
    assert not undecided_between([-1, 0, -1], hn, opposite=True).any()
    assert not undecided_between([0, 0, -1], hn, opposite=True).any()  # a neighbour undecided
    assert not undecided_between([1, -1, 1], hn, opposite=True).any()  # decided itself: W109's pairs judge it
    assert not undecided_between([1, 0, -1], [False, True, True], opposite=True).any()  # the one before ends
    assert not undecided_between([1, 0, -1], [True, False, True], opposite=True).any()  # it ends its sequence
    assert not undecided_between([0, 1], [True, True], opposite=True).any()  # the ends have one neighbour
    assert undecided_between([], [], opposite=True).size == 0
    side = np.array([0, 1, 0, -1, -1, 0, -1, 1, 0, -1, 0])
    has_next = np.array([True, True, True, True, True, True, True, True, False, True, False])
    # 0 first contact; 2: +1 ? -1 kept; 5: -1 ? -1 not (same side); 8: +1 ? -1 but it ends its sequence; 10 last
    want = [False, False, True, False, False, False, False, False, False, False, False]
    assert undecided_between(side, has_next, opposite=True).tolist() == want
    # W180's reading on the same sequence is unchanged: only 5
    assert np.flatnonzero(undecided_between(side, has_next)).tolist() == [5]


def _extra_contact_bend():
    """W109's hand-made bend (70 deg at 10-12 s) under a 1 Hz lateral sway, a contact every 0.5 s and one extra at
    10.75 s, where the sway's velocity passes zero: undecided between 10.5 s and 11.0 s, on opposite sides."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    steps = steps_from_events(t, np.sort(np.append(np.arange(50, 1950, 50), 1075)))
    imu = dataclasses.replace(_imu(Rotation.identity()), acc_ml=np.sin(2.0 * np.pi * t))
    return steps, imu


def test_the_opposite_veto_keeps_an_extra_contact_inside_a_left_right_pair():
    steps, imu = _extra_contact_bend()
    e, hn = steps["event_s"].to_numpy(float), steps["has_next"].to_numpy(bool)
    side = K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, e), hn)
    i = int(np.flatnonzero(np.isclose(e, 10.75))[0])
    assert (side[i - 1], side[i], side[i + 1]) in ((1, 0, -1), (-1, 0, 1))
    gone = sorted(set(steps["event_s"].round(2)) - set(transfer_veto(steps, imu, keep_rhythm=True)["event_s"].round(2)))
    assert gone == [10.75]  # the rhythm veto: no pair for it
    assert transfer_veto(steps, imu, keep_rhythm=True, keep_between=True).attrs["n_vetoed"] == 1  # W180 neither
    out = transfer_veto(steps, imu, keep_rhythm=True, keep_between="opposite")
    assert out.attrs["n_vetoed"] == 0 and len(out) == len(steps)


def test_the_opposite_veto_drops_an_unswaying_contact_between_two_same_side_contacts():
    """W180's case (W109's sway stopped at 10.5-11.5 s: 11.0 s undecided between two same-side contacts) is not
    spared by "opposite" (W184's decision); with no sway at all W104's five contacts go."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    steps = steps_from_events(t, np.arange(50, 1950, 50))
    sway = np.sin(2.0 * np.pi * t) * ((t < 10.5) | (t > 11.5))
    imu = dataclasses.replace(_imu(Rotation.identity()), acc_ml=sway)
    out = transfer_veto(steps, imu, keep_rhythm=True, keep_between="opposite")
    assert sorted(set(steps["event_s"].round(2)) - set(out["event_s"].round(2))) == [11.0]
    still = dataclasses.replace(imu, acc_ml=np.zeros(t.size))
    assert transfer_veto(steps, still, keep_rhythm=True, keep_between="opposite").attrs["n_vetoed"] == 5


def test_the_opposite_veto_removes_a_simulated_sit_to_stand_and_reads_the_params_json_option():
    s = simulate_path(parse_route("straight:10, sit:20, straight:10"), UserProfile.from_seed(621), rate_hz=100,
                      seed=621)
    tr = s.extras["transfers"].iloc[0]
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto="opposite")
    e0, e1 = off.steps["event_s"].to_numpy(float), on.steps["event_s"].to_numpy(float)
    n_in = int(((e0 >= tr.start_s) & (e0 <= tr.end_s)).sum())
    assert n_in > 0 and not ((e1 >= tr.start_s) & (e1 <= tr.end_s)).any()
    assert on.info["n_vetoed_contacts"] == n_in and len(e1) == len(e0) - n_in
    via = track_waist(s, pipeline="waist-pendulum", params={"options": {"sit_veto": "opposite"}})
    pd.testing.assert_frame_equal(via.steps, on.steps)


def test_an_upright_walk_is_unchanged():
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto="opposite")
    pd.testing.assert_frame_equal(on.steps, off.steps)
    assert on.info["n_vetoed_contacts"] == 0


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_opposite_is_the_offline_default_and_realtime_keeps_no_veto(pipeline):
    """W185: W184's rule met, so an offline track without `sit_veto` is `"opposite"`; a realtime track without it
    stays unvetoed (W472: the rule, no module constant), and the option given (argument or PARAMS.json) is applied
    either way."""
    s = simulate_path(parse_route("straight:10, sit:20, straight:10"), UserProfile.from_seed(621), rate_hz=100,
                      seed=621)
    assert OPTION_DEFAULTS["sit_veto"] == "opposite"
    default = track_waist(s, pipeline=pipeline)
    pd.testing.assert_frame_equal(default.steps, track_waist(s, pipeline=pipeline, sit_veto="opposite").steps)
    assert default.info["n_vetoed_contacts"] > 0
    off = track_waist(s, pipeline=pipeline, params={"options": {"sit_veto": False}})
    pd.testing.assert_frame_equal(off.steps, track_waist(s, pipeline=pipeline, sit_veto=False).steps)
    assert off.info["n_vetoed_contacts"] == 0 and len(off.steps) > len(default.steps)
    if pipeline == "waist-pendulum":  # realtime is the pendulum's causal detector
        rt = track_waist(s, pipeline=pipeline, realtime=True)
        assert rt.info["n_vetoed_contacts"] == 0
        pd.testing.assert_frame_equal(rt.steps, track_waist(s, pipeline=pipeline, realtime=True,
                                                            sit_veto=False).steps)
        for given in ({"sit_veto": "opposite"}, {"params": {"options": {"sit_veto": "opposite"}}}):
            assert track_waist(s, pipeline=pipeline, realtime=True, **given).info["n_vetoed_contacts"] > 0


def test_a_bad_sit_veto_value_lists_every_value():
    s = simulate_path([Stand(3.0), Straight(6.0), Stand(3.0)], UserProfile.from_seed(541), rate_hz=100, seed=541)
    with pytest.raises(DataError, match=r'sit_veto .Opposite. is not one of false, true, "rhythm", "alternation", '
                                        r'"opposite" \(decisions W104, W109, W180, W184\)') as e:
        track_waist(s, pipeline="waist-pendulum", sit_veto="Opposite")
    assert "\n" not in str(e.value)


def test_the_opposite_veto_keeps_ha002s_step_between_opposite_side_contacts():
    """W181's HA002 Test11 in-bout contact at 31.74 s (undecided; its neighbours 31.46 s +1 and 32.25 s -1): the
    rhythm and alternation vetoes drop it, "opposite" keeps it."""
    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False).steps["event_s"].to_numpy(float)
    assert np.abs(off - 31.74).min() < 0.005

    def kept(value) -> bool:
        e = track_waist(s, pipeline="waist-pendulum", sit_veto=value).steps["event_s"].to_numpy(float)
        return bool(np.abs(e - 31.74).min() < 0.005)

    assert not kept("rhythm") and not kept("alternation") and kept("opposite")
    assert kept(None)  # the offline default since W185
