"""Decision W102: the trunk-tilt gate (option `max_tilt_deg`; measured, not adopted as the default); decision W104:
the sit-to-stand veto (option `sit_veto`); decision W109: the veto sparing left/right step pairs (`sit_veto="rhythm"`,
measured, not adopted); decision W110: an unknown `sit_veto` value is refused."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.io import Stream, read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.ahrs import WaistIMU, waist_imu
from pdrlearn.waist.events import steps_from_events
from pdrlearn.waist.posture import (
    MAX_TILT_DEG,
    TRANSFER_HALF_S,
    alternating_pairs,
    contact_tilt_deg,
    flexion_events,
    tilt_gate,
    transfer_veto,
)
from tests.conftest import external_session

FS = 100.0


def _bend(t: np.ndarray, t0: float, t1: float, peak_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """A forward bend of the trunk from ``t0`` to ``t1``: pitch angle (rad) and its rate (rad/s), a raised cosine."""
    inside = (t >= t0) & (t <= t1)
    ph = 2.0 * np.pi * (t - t0) / (t1 - t0)
    a = np.where(inside, 0.5 * np.radians(peak_deg) * (1.0 - np.cos(ph)), 0.0)
    rate = np.where(inside, 0.5 * np.radians(peak_deg) * np.sin(ph) * 2.0 * np.pi / (t1 - t0), 0.0)
    return a, rate


def _imu(mount: Rotation) -> WaistIMU:
    """20 s of a unit mounted with ``mount`` (body -> sensor), bent forward 70 deg at 10-12 s; only the attitude."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    pitch, _ = _bend(t, 10.0, 12.0, 70.0)
    up = (Rotation.from_rotvec(np.outer(pitch, [0.0, 1.0, 0.0])).inv()).apply([0.0, 0.0, 1.0])
    z = np.zeros(t.size)
    return WaistIMU(t=t, fs=FS, acc_nav=np.zeros((t.size, 3)), gyr_nav=np.zeros((t.size, 3)), yaw=z, acc_v=z,
                    acc_h=np.zeros((t.size, 2)), acc_ap=z, acc_ml=z, up_body=mount.apply(up))


def test_contact_tilt_is_from_the_sessions_walking_upright_for_any_mounting():
    ic = np.arange(50, 1950, 50)  # a contact every 0.5 s
    steps = steps_from_events(np.arange(0.0, 20.0, 1.0 / FS), ic)
    for mount in (Rotation.identity(), Rotation.from_euler("xyz", [90.0, 25.0, -40.0], degrees=True)):
        tilt = contact_tilt_deg(_imu(mount), steps["event_s"].to_numpy(), steps["has_next"].to_numpy())
        walking = (steps["event_s"] < 9.0) | (steps["event_s"] > 13.0)
        assert np.all(tilt[walking] < 1e-6)  # a sideways-mounted unit reads 0 while walking upright
        # the 2 s bend's peak (70 deg) averaged over +-0.5 s: 35 (1 + 2 / pi) = 57.3 deg
        assert abs(tilt.max() - 35.0 * (1.0 + 2.0 / np.pi)) < 1.0


def test_the_gate_drops_the_bent_contacts_and_ends_the_sequence_before_them():
    t = np.arange(0.0, 20.0, 1.0 / FS)
    steps = steps_from_events(t, np.arange(50, 1950, 50))
    out = tilt_gate(steps, _imu(Rotation.identity()), MAX_TILT_DEG)
    gone = sorted(set(steps["event_s"].round(2)) - set(out["event_s"].round(2)))
    assert out.attrs["n_tilted"] == len(gone) > 0
    assert all(10.0 < e < 12.0 for e in gone)  # only the bend
    before = out[out["event_s"] < min(gone)].iloc[-1]
    assert not before["has_next"] and before["end_s"] == before["start_s"]  # no step bridges the bend
    assert tilt_gate(steps.iloc[:0], _imu(Rotation.identity())).empty


def _bent_walk():
    """A simulated walk (user 541) with a 70 deg forward bend of the trunk spliced in at 8-10.5 s while stepping."""
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    m = s.frames["waist"].matrix()  # v_body = m @ v_sensor
    acc, gyr = s["wAccelerometer"], s["wGyroscope"]
    pitch, rate = _bend(acc.t, 8.0, 10.5, 70.0)
    r = Rotation.from_rotvec(np.outer(pitch, [0.0, 1.0, 0.0]))
    acc_b = r.inv().apply(acc.values @ m.T)
    gyr_b = r.inv().apply(gyr.values @ m.T) + np.outer(rate, [0.0, 1.0, 0.0])
    s.streams["wAccelerometer"] = Stream("wAccelerometer", acc.t, acc_b @ m)
    s.streams["wGyroscope"] = Stream("wGyroscope", gyr.t, gyr_b @ m)
    return s


def test_a_bend_spliced_into_a_simulated_walk_is_no_step_with_the_gate():
    s = _bent_walk()
    off = track_waist(s, pipeline="waist-pendulum")
    on = track_waist(s, pipeline="waist-pendulum", max_tilt_deg=MAX_TILT_DEG)
    bent = (off.steps["event_s"] > 8.8) & (off.steps["event_s"] < 9.7)
    assert bent.any() and off.info["n_tilted_contacts"] == 0  # without the gate the bend's contacts are steps
    assert on.info["n_tilted_contacts"] > 0
    assert len(on.steps) == len(off.steps) - on.info["n_tilted_contacts"]
    assert not ((on.steps["event_s"] > 8.8) & (on.steps["event_s"] < 9.7)).any()


def test_the_gate_changes_no_step_of_an_upright_walk():
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    off = track_waist(s, pipeline="waist-pendulum")
    on = track_waist(s, pipeline="waist-pendulum", max_tilt_deg=MAX_TILT_DEG)
    pd.testing.assert_frame_equal(on.steps, off.steps)


def test_the_veto_finds_the_flexion_event_and_drops_the_contacts_around_its_peak():
    t = np.arange(0.0, 20.0, 1.0 / FS)
    steps = steps_from_events(t, np.arange(50, 1950, 50))
    imu = _imu(Rotation.from_euler("xyz", [90.0, 25.0, -40.0], degrees=True))
    (a, peak, b), = flexion_events(imu, steps["event_s"].to_numpy(), steps["has_next"].to_numpy())
    # 70 deg raised cosine over 10-12 s: above 25 deg where cos(pi (t - 10)) < 1 - 50 / 70
    half = np.arccos(1.0 - 50.0 / 70.0) / np.pi
    assert abs(peak - 11.0) < 0.02 and abs(a - (10.0 + half)) < 0.02 and abs(b - (12.0 - half)) < 0.02
    out = transfer_veto(steps, imu)
    gone = sorted(set(steps["event_s"].round(2)) - set(out["event_s"].round(2)))
    assert gone == [e for e in steps["event_s"].round(2) if abs(e - 11.0) <= TRANSFER_HALF_S]
    assert out.attrs["n_vetoed"] == len(gone)
    before = out[out["event_s"] < min(gone)].iloc[-1]
    assert not before["has_next"] and before["end_s"] == before["start_s"]
    assert transfer_veto(steps.iloc[:0], imu).empty


def test_the_veto_removes_the_contacts_of_a_simulated_sit_to_stand():
    s = simulate_path(parse_route("straight:10, sit:20, straight:10"), UserProfile.from_seed(621), rate_hz=100,
                      seed=621)
    tr = s.extras["transfers"].iloc[0]

    def inside(res):
        e = res.steps["event_s"].to_numpy(float)
        return int(((e >= tr.start_s) & (e <= tr.end_s)).sum())

    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)  # W185: off is no longer the offline default
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=True)
    assert inside(off) > 0 and off.info["n_vetoed_contacts"] == 0
    assert inside(on) == 0 and on.info["n_vetoed_contacts"] == inside(off)
    assert len(on.steps) == len(off.steps) - inside(off)
    # W146: with the veto off, one line names those contacts and the option; none with it on
    hint = [w for w in off.info["warnings"] if "W146" in w]
    assert len(hint) == 1 and hint[0].startswith(f"{inside(off)} contact(s) lie at a trunk flexion over 25 deg")
    assert "a TUG" in hint[0] and not [w for w in on.info["warnings"] if "W146" in w]  # W145's advice kept
    # decision E126: the option named is W185's offline default, turned back on; no more W109's "rhythm"
    assert 'remove "sit_veto": false' in hint[0] and '"sit_veto": "opposite"' in hint[0]
    assert '"rhythm"' not in hint[0]
    # a realtime track without the option has no veto (W185): its line says to set "opposite", not to remove false
    rt = [w for w in track_waist(s, pipeline="waist-pendulum", realtime=True).info["warnings"] if "W146" in w]
    assert len(rt) == 1 and '{"sit_veto": "opposite"}' in rt[0] and "remove" not in rt[0] and "a TUG" in rt[0]


def test_the_veto_changes_no_step_of_an_upright_walk():
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=True)
    off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)
    pd.testing.assert_frame_equal(on.steps, off.steps)
    assert on.info["n_vetoed_contacts"] == 0
    assert not [w for w in off.info["warnings"] if "W146" in w]  # no flexion, no W146 line


def test_alternating_pairs_are_consecutive_contacts_of_a_sequence_on_decided_opposite_sides():
    side = np.array([1, -1, 0, 1, 1, -1, 1])
    has_next = np.array([True, True, True, True, False, True, False])
    # 0-1 a pair; 1-2 and 2-3 undecided; 3-4 same side; 4-5 not one sequence; 5-6 a pair
    assert alternating_pairs(side, has_next).tolist() == [True, True, False, False, False, True, True]


def test_the_rhythm_veto_keeps_the_contacts_that_sway_left_and_right_around_a_bend():
    t = np.arange(0.0, 20.0, 1.0 / FS)
    steps = steps_from_events(t, np.arange(50, 1950, 50))  # a contact every 0.5 s
    # a 1 Hz lateral sway (one stride per two contacts) everywhere except 10.5-11.5 s, the bend's middle
    sway = np.sin(2.0 * np.pi * t) * ((t < 10.5) | (t > 11.5))
    imu = dataclasses.replace(_imu(Rotation.identity()), acc_ml=sway)
    gone = sorted(set(steps["event_s"].round(2)) - set(transfer_veto(steps, imu)["event_s"].round(2)))
    assert gone == [10.0, 10.5, 11.0, 11.5, 12.0]  # W104: every contact within 1 s of the peak
    out = transfer_veto(steps, imu, keep_rhythm=True)
    assert sorted(set(steps["event_s"].round(2)) - set(out["event_s"].round(2))) == [11.0]  # no sway, no pair
    assert out.attrs["n_vetoed"] == 1


def test_the_rhythm_veto_removes_a_simulated_sit_to_stand_whose_pelvis_does_not_sway():
    s = simulate_path(parse_route("straight:10, sit:20, straight:10"), UserProfile.from_seed(621), rate_hz=100,
                      seed=621)
    tr = s.extras["transfers"].iloc[0]
    steps = track_waist(s, pipeline="waist-pendulum", sit_veto=False).steps
    e = steps["event_s"].to_numpy(float)
    n_in = int(((e >= tr.start_s) & (e <= tr.end_s)).sum())
    out = transfer_veto(steps, waist_imu(s), keep_rhythm=True)
    e1 = out["event_s"].to_numpy(float)
    assert n_in > 0 and not ((e1 >= tr.start_s) & (e1 <= tr.end_s)).any()
    assert out.attrs["n_vetoed"] == n_in


def test_the_rhythm_veto_keeps_the_real_steps_w104_dropped_after_standing_up():
    """mobgap HA001 Test11 (W109's measurement): W104 drops 3 contacts within 0.25 s of a reference contact
    (50.81, 76.42, 122.83 s), the rhythm veto none; it drops 8 of the 16 (W487: 18 and 10 with the seated span's)."""
    d = external_session("mobgap_HA001_Test11_Trial1")
    s = read_session(d)
    ic = pd.read_csv(d / "ics.csv")["ic_ms"].to_numpy(float) / 1000.0
    kw = {"pipeline": "waist-pendulum", "contact_shift": False, "parity_fill": False,  # W109: before W131 / W159
          "stand_veto": False}  # and before W199
    e0 = track_waist(s, sit_veto=False, **kw).steps["event_s"].to_numpy(float)

    def dropped(value):
        e1 = track_waist(s, sit_veto=value, **kw).steps["event_s"].to_numpy(float)
        gone = np.array([e for e in e0 if np.abs(e1 - e).min() > 1e-9])
        return gone, int(sum(np.abs(ic - g).min() <= 0.25 for g in gone))

    (w104, near104), (w109, near109) = dropped(True), dropped("rhythm")
    # decision W487: + 53.01 and 56.25 s, inside the seated span 52.28-76.23 s (stand-to-sit .. sit-to-stand), near
    # no reference contact; W109's counts were 16 and 8 before
    assert (len(e0), len(w104), near104) == (107, 18, 3)
    assert (len(w109), near109) == (10, 0)
    assert set(np.round(w109, 6)) <= set(np.round(w104, 6))  # the same window, fewer contacts


def test_an_unknown_sit_veto_value_is_refused_in_one_line():
    s = simulate_path([Stand(3.0), Straight(6.0), Stand(3.0)], UserProfile.from_seed(541), rate_hz=100, seed=541)
    with pytest.raises(DataError, match=r"sit_veto 'yes' is not one of false, true, \"rhythm\"") as e:
        track_waist(s, pipeline="waist-pendulum", sit_veto="yes")
    assert "\n" not in str(e.value)
