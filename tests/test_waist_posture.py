"""Decision W102: the trunk-tilt gate (option `max_tilt_deg`; measured, not adopted as the default); decision W104:
the sit-to-stand veto (option `sit_veto`)."""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from pdrlearn.io import Stream
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.events import steps_from_events
from pdrlearn.waist.posture import (
    MAX_TILT_DEG,
    TRANSFER_HALF_S,
    contact_tilt_deg,
    flexion_events,
    tilt_gate,
    transfer_veto,
)

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

    off = track_waist(s, pipeline="waist-pendulum")
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=True)
    assert inside(off) > 0 and off.info["n_vetoed_contacts"] == 0
    assert inside(on) == 0 and on.info["n_vetoed_contacts"] == inside(off)
    assert len(on.steps) == len(off.steps) - inside(off)


def test_the_veto_changes_no_step_of_an_upright_walk():
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(541), speed="normal",
                      rate_hz=100, seed=541)
    on = track_waist(s, pipeline="waist-pendulum", sit_veto=True)
    pd.testing.assert_frame_equal(on.steps, track_waist(s, pipeline="waist-pendulum").steps)
    assert on.info["n_vetoed_contacts"] == 0
