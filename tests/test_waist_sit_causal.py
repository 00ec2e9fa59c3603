"""Decision W200: the causal sit veto of realtime lower-back tracks (`realtime_sit_veto`): each contact decided on the
samples before its horizon (3.25 s after it), the upright from the walking contacts so far (the start's direction
before five), W104's events on the last 10 s, W109 / W184's sparing with W20's sides filtered on that window; the
same kernels as the offline veto."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.events import steps_from_events
from pdrlearn.waist.live import unapplied_options_line
from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.posture import transfer_veto
from pdrlearn.waist.sit_causal import (
    CAUSAL_HORIZON_S,
    CAUSAL_UPRIGHT_MIN,
    causal_transfer_veto,
    causal_uprights,
    causal_veto_mask,
    start_direction,
)
from tests.test_waist_posture import FS, _bend, _imu


def _pitched(t: np.ndarray, pitch: np.ndarray, acc_ml: np.ndarray | None = None) -> WaistIMU:
    """A unit whose trunk pitches by ``pitch`` (rad) about the body's y axis; only the attitude (and ``acc_ml``)."""
    up = Rotation.from_rotvec(np.outer(pitch, [0.0, 1.0, 0.0])).inv().apply([0.0, 0.0, 1.0])
    z = np.zeros(t.size)
    return WaistIMU(t=t, fs=FS, acc_nav=np.zeros((t.size, 3)), gyr_nav=np.zeros((t.size, 3)), yaw=z, acc_v=z,
                    acc_h=np.zeros((t.size, 2)), acc_ap=z, acc_ml=z if acc_ml is None else acc_ml, up_body=up)


def _dropped(steps: pd.DataFrame, out: pd.DataFrame) -> list[float]:
    return sorted(set(steps["event_s"].round(2)) - set(out["event_s"].round(2)))


def test_the_upright_is_the_start_until_five_walking_contacts_then_their_median():
    start = np.array([0.0, 0.0, 1.0])
    rng = np.random.default_rng(0)
    d = rng.normal(size=(9, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    hn = np.array([True, False, True, True, True, False, True, True, False])
    ups = causal_uprights(d, hn, start)
    assert CAUSAL_UPRIGHT_MIN == 5
    for i in range(9):
        walk = np.flatnonzero(hn[:i + 1])
        if walk.size < 5:  # contacts 0-5: four walking contacts at most
            assert np.array_equal(ups[i], start)
        else:  # from contact 6 on: the normalised median of the walking contacts up to it (contact 8's own not one)
            m = np.median(d[walk], axis=0)
            assert np.allclose(ups[i], m / np.linalg.norm(m))
    assert np.allclose(ups[7], ups[8])  # contact 8 starts no step: the same walking contacts


def test_the_start_direction_is_the_mean_over_the_first_second():
    t = np.arange(0.0, 5.0, 1.0 / FS)
    pitch = np.where(t < 1.0, np.radians(-12.0), 0.0)  # seated, pelvis 12 deg back, for the first second
    d = start_direction(t, _pitched(t, pitch).up_body)
    assert np.isclose(np.degrees(np.arccos(d @ [0.0, 0.0, 1.0])), 12.0, atol=1e-6)


@pytest.mark.parametrize("sway", ["none", "extra", "stopped"])
def test_equal_to_the_offline_veto_where_the_upright_is_the_same(sway):
    """W104's 70 deg bend (10-12 s) in an upright walk: the start and every walking median read the walking upright
    exactly, the bend's run lies inside each window, so the causal veto drops what the offline one does, with and
    without W109 / W184's sparing (sides filtered on the window: the same decisions here)."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    ic = np.arange(50, 1950, 50)
    imu = _imu(Rotation.identity())
    if sway == "extra":  # an extra contact at 10.75 s between a left and a right one (W184's case)
        ic = np.sort(np.append(ic, 1075))
        imu = dataclasses.replace(imu, acc_ml=np.sin(2.0 * np.pi * t))
    elif sway == "stopped":  # W180's unswaying stretch
        imu = dataclasses.replace(imu, acc_ml=np.sin(2.0 * np.pi * t) * ((t < 10.5) | (t > 11.5)))
    steps = steps_from_events(t, ic)
    for kw in ({}, {"keep_rhythm": True}, {"keep_rhythm": True, "keep_between": "opposite"}):
        off, on = transfer_veto(steps, imu, **kw), causal_transfer_veto(steps, imu, **kw)
        pd.testing.assert_frame_equal(on, off)
        assert on.attrs["n_vetoed"] == off.attrs["n_vetoed"]
    # W104: the contacts within 1 s of the peak at 11 s (five, and the extra one)
    assert causal_transfer_veto(steps, imu).attrs["n_vetoed"] == (6 if sway == "extra" else 5)
    spared = causal_transfer_veto(steps, imu, keep_rhythm=True, keep_between="opposite")
    assert _dropped(steps, spared) == {"none": [10.0, 10.5, 11.0, 11.5, 12.0], "extra": [], "stopped": [11.0]}[sway]


def _slipped_walk() -> tuple[np.ndarray, pd.DataFrame, WaistIMU]:
    """40 s of contacts every 0.5 s: a 30 deg flexion at 8-10 s, then the unit slips 20 deg forward at 20 s for good
    (so the whole recording's upright is not the first half's), and a 70 deg bend at 30-32 s; the pelvis sways
    (W20) except around each flexion's peak."""
    t = np.arange(0.0, 40.0, 1.0 / FS)
    pitch = _bend(t, 8.0, 10.0, 30.0)[0] + _bend(t, 30.0, 32.0, 70.0)[0] + np.where(t >= 20.0, np.radians(20.0), 0.0)
    sway = np.sin(2.0 * np.pi * t) * ~(((t > 8.5) & (t < 9.5)) | ((t > 30.5) & (t < 31.5)))
    return t, steps_from_events(t, np.arange(50, 3950, 50)), _pitched(t, pitch, sway)


def test_nothing_after_a_contacts_horizon_is_read():
    """Each contact's veto on the data cut at any time T equals the whole recording's once its horizon (3.25 s after
    it) has passed: the contacts decided by T (1.75 s, W31) rebuilt from the cut samples."""
    t, steps, imu = _slipped_walk()
    e = steps["event_s"].to_numpy(float)
    kw = {"keep_rhythm": True, "keep_between": "opposite"}
    whole = causal_veto_mask(imu.t, imu.up_body, imu.acc_ml, FS, e, steps["has_next"].to_numpy(bool), **kw)
    assert whole[np.isclose(e, 9.0)].all() and whole[np.isclose(e, 31.0)].all()  # the unswaying flexed contacts
    for cut in (12.0, 21.0, 26.5, 33.0):
        n = int(np.searchsorted(t, cut))
        seen = steps_from_events(t[:n], np.round(e[e <= cut - 1.75] * FS).astype(int))
        part = causal_veto_mask(t[:n], imu.up_body[:n], imu.acc_ml[:n], FS, seen["event_s"].to_numpy(float),
                                seen["has_next"].to_numpy(bool), **kw)
        done = seen["event_s"].to_numpy(float) <= cut - CAUSAL_HORIZON_S
        assert done.sum() > 10 and np.array_equal(part[done], whole[:len(part)][done])
    # the offline veto reads the whole recording's upright (the later half's, 20 deg forward): the 30 deg flexion
    # reads 10 deg from it, no event, and 9.0 s is kept; the causal upright (the first half's) drops it
    off = transfer_veto(steps, imu, keep_rhythm=True, keep_between="opposite")
    on = causal_transfer_veto(steps, imu, keep_rhythm=True, keep_between="opposite")
    assert 9.0 in _dropped(steps, on) and 9.0 not in _dropped(steps, off) and 31.0 in _dropped(steps, off)


def test_a_seated_starts_rise_is_vetoed_before_any_walking_contact():
    """Seated (pelvis 12 deg back) for 5 s, a 45 deg rise at 5-7 s with contacts at 5.5-6.5 s, then an upright walk:
    no walking contact is known at the rise, the start's direction is the upright, and the rise's contacts go."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    pitch = np.where(t < 6.0, np.radians(-12.0), 0.0) * (t < 6.0) + _bend(t, 5.0, 7.0, 45.0)[0]
    imu = _pitched(t, pitch)
    steps = steps_from_events(t, np.arange(550, 1950, 50))
    out = causal_transfer_veto(steps, imu)
    assert _dropped(steps, out) == [5.5, 6.0, 6.5, 7.0]  # W104: within 1 s of the peak at 6 s
    assert np.isclose(np.degrees(np.arccos(start_direction(t, imu.up_body) @ [0.0, 0.0, 1.0])), 12.0)
    assert causal_transfer_veto(steps.iloc[:0], imu).attrs["n_vetoed"] == 0
    assert causal_transfer_veto(steps, dataclasses.replace(imu, up_body=None)).attrs["n_vetoed"] == 0


def test_a_realtime_track_with_the_option_removes_a_simulated_sit_to_stand():
    """W201: W200's rule not met, so the option is off by default (a realtime track keeps no veto, W185)."""
    assert OPTION_DEFAULTS["realtime_sit_veto"] is False
    s = simulate_path(parse_route("straight:10, sit:20, straight:10"), UserProfile.from_seed(621), rate_hz=100,
                      seed=621)
    tr = s.extras["transfers"].iloc[0]
    off = track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=False)
    on = track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=True)
    e0, e1 = off.steps["event_s"].to_numpy(float), on.steps["event_s"].to_numpy(float)
    n_in = int(((e0 >= tr.start_s) & (e0 <= tr.end_s)).sum())
    assert n_in > 0 and not ((e1 >= tr.start_s) & (e1 <= tr.end_s)).any()
    assert off.info["n_vetoed_contacts"] == 0 and on.info["n_vetoed_contacts"] == n_in == len(e0) - len(e1)
    pd.testing.assert_frame_equal(track_waist(s, pipeline="waist-pendulum", realtime=True).steps, off.steps)
    via = track_waist(s, pipeline="waist-pendulum", params={"options": {"realtime": True, "realtime_sit_veto": True}})
    pd.testing.assert_frame_equal(via.steps, on.steps)
    # sit_veto false turns it off; a value given is applied causally (True: W104's veto, no sparing)
    pd.testing.assert_frame_equal(track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=True,
                                              sit_veto=False).steps, off.steps)
    assert track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=True,
                       sit_veto=True).info["n_vetoed_contacts"] >= n_in


def test_an_upright_realtime_walk_is_unchanged():
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    off = track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=False)
    on = track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=True)
    pd.testing.assert_frame_equal(on.steps, off.steps)
    assert on.info["n_vetoed_contacts"] == 0


def test_the_option_is_named_where_it_does_nothing():
    """W193: set on an offline track it is named as ignored; E107: the live tracker (no sit veto) names the veto."""
    s = simulate_path([Stand(3.0), Straight(6.0), Stand(3.0)], UserProfile.from_seed(541), rate_hz=100, seed=541)
    flip = not OPTION_DEFAULTS["realtime_sit_veto"]
    res = track_waist(s, pipeline="waist-pendulum", realtime_sit_veto=flip)
    assert any("realtime_sit_veto" in w and "W200" in w and "W193" in w for w in res.info["warnings"])
    rt = track_waist(s, pipeline="waist-pendulum", realtime=True, realtime_sit_veto=flip)
    assert not any("realtime_sit_veto" in w for w in rt.info["warnings"])
    # the live tracker applies no sit veto in either form: E107's line names the veto itself, as before W200
    line = unapplied_options_line(WaistParams(options={"realtime_sit_veto": True}))
    assert line is not None and 'sit_veto="opposite"' in line and "realtime_sit_veto" not in line
