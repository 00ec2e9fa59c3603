"""Session 20's trial `aids`: a waist track whose steps do not alternate left/right says so (decision W98): a
wheelchair user's arm pushes and a walker's doubled step count; a normal walk does not warn. `calibrate` says when
the walk's waist contact count and the pelvic-gyro detector's disagree (W99)."""

from __future__ import annotations

import dataclasses
import re

import numpy as np

from pdrlearn.io.session import Stream
from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.plausibility import alternation_index


def _wheelchair(period_s: float = 0.7, push_mps2: float = 3.0, lean_deg: float = 12.0, vib_mps2: float = 0.5,
                jolt_mps2: float = 1.5):
    """The trial's wheelchair.py (its first configuration, 100 Hz) on a simulated standstill: an arm push every
    ``period_s`` (forward pulse, trunk lean, vertical jolt) and rolling vibration on the waist; no foot motion
    and no sideways weight shift."""
    s = simulate_path([Stand(45)], UserProfile.from_seed(405), speed="normal", rate_hz=100, seed=405)
    rng = np.random.default_rng(0)
    acc, gyr = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    t = acc.t - acc.t[0]
    dt = float(np.median(np.diff(t)))
    pushes = np.arange(5.5, t[-1] - 5.5, period_s) + rng.normal(0, 0.05, size=np.arange(5.5, t[-1] - 5.5,
                                                                                         period_s).size)
    fwd, pitch, vert = np.zeros_like(t), np.zeros_like(t), np.zeros_like(t)
    for p in pushes:
        fwd += push_mps2 * (np.exp(-0.5 * ((t - p - 0.15) / 0.08) ** 2)
                            - 0.35 * np.exp(-0.5 * ((t - p - 0.55) / 0.2) ** 2))
        pitch += np.radians(lean_deg) * np.exp(-0.5 * ((t - p - 0.2) / 0.18) ** 2)
        vert += jolt_mps2 * (np.exp(-0.5 * ((t - p - 0.1) / 0.07) ** 2) - np.exp(-0.5 * ((t - p - 0.35) / 0.07) ** 2))
    moving = ((t > 5) & (t < t[-1] - 5))[:, None]
    a = acc.values.copy()  # x left, y up, z forward
    a[:, 2] += fwd + 9.80665 * np.sin(pitch)
    a[:, 1] += 9.80665 * (np.cos(pitch) - 1) + vert
    a += vib_mps2 * rng.standard_normal(a.shape) * moving
    w = gyr.values.copy()
    w[:, 0] -= np.interp(gyr.t - acc.t[0], t, np.gradient(pitch, dt))
    s.streams["wAccelerometer"] = Stream("wAccelerometer", acc.t.copy(), a)
    s.streams["wGyroscope"] = Stream("wGyroscope", gyr.t.copy(), w)
    return s


def _w98(r) -> list[str]:
    return [w for w in r.info["warnings"] if "decision W98" in w]


def test_alternation_index_of_alternating_random_and_same_side_contacts():
    hn = np.ones(20, dtype=bool)
    assert alternation_index(np.tile([1.0, -1.0], 10), hn) == (1.0, 19)
    assert alternation_index(np.ones(20), hn) == (-1.0, 19)
    a, n = alternation_index(np.tile([1.0, 0.0], 10), hn)  # a phantom contact between each pair of steps
    assert a == 0.0 and n == 19
    assert alternation_index(np.tile([1.0, -1.0], 10), np.zeros(20, dtype=bool)) == (None, 0)  # no sequence


def test_wheelchair_pushes_are_dropped_by_the_foot_rest_veto():
    """W343: the simulated foot unit rests through the pushes, so W337's default foot_rest_veto drops them all with
    W336's line (the pushes are not steps)."""
    r = track_waist(_wheelchair(), pipeline="waist-pendulum")
    assert len(r.steps) == 0 and not _w98(r)
    (line,) = [w for w in r.info["warnings"] if "decision W336" in w and "dropped (foot_rest_veto" in w]
    # session 48, W547: W76's "no steps found" line names the veto too (and the way to track the lower back alone)
    assert any("no steps found" in w and "decision W547" in w for w in r.info["warnings"])


def test_wheelchair_pushes_warn_that_the_steps_do_not_alternate():
    """Trial finding 1: the pushes are counted as steps (a known limit) but the track now says they are not
    walking, naming the W98 index and the pelvic-gyro check; W343: without a foot unit's veto (foot_rest_veto
    false), as a phone-only wheelchair user's track keeps them."""
    r = track_waist(_wheelchair(), pipeline="waist-pendulum", foot_rest_veto=False)
    assert r.info["alternation_pairs"] >= 10
    assert r.info["alternation_index"] < 0.5
    (line,) = _w98(r)
    assert "wheelchair" in line and "--detector pelvic-gyro" in line


def test_normal_walk_does_not_warn():
    s = simulate_path([Stand(3), Straight(20), Turn(np.pi), Straight(20), Stand(3)], UserProfile.from_seed(7),
                      speed="normal", rate_hz=20, seed=7)
    r = track_waist(s, pipeline="waist-pendulum")
    assert r.info["alternation_index"] > 0.8
    assert not _w98(r)


def _w99(params) -> list[str]:
    return [n for n in params.notes if "the pelvic-gyro detector" in n]


def test_calibrate_on_a_doubled_step_count_names_the_pelvic_gyro_count():
    """Trial finding 3: a 0.15 m / 1.5 s walker (user 411); the waist IC detector finds about 1.5x the pelvic-gyro
    detector's steps on the 5 m calibration walk (truth ~34) and calibrate fitted K to it without a word."""
    u = dataclasses.replace(UserProfile.from_seed(411), step_length_m=0.15, step_time_s=1.5)
    s = simulate_path([Stand(3), Straight(5), Stand(3)], u, speed="normal", rate_hz=100, seed=5)
    (line,) = _w99(calibrate([s], "waist-pendulum", distances=[5.0]))
    n_waist, n_gyro = (int(x) for x in re.findall(r"counted (\d+) contacts.*detector (\d+) ", line)[0])
    assert n_waist > 1.3 * n_gyro
    assert "--detector pelvic-gyro" in line


def test_calibrate_on_a_normal_walk_has_no_count_warning():
    s = simulate_path([Stand(3), Straight(10), Stand(3)], UserProfile.from_seed(7), speed="normal", rate_hz=20, seed=7)
    assert not _w99(calibrate([s], "waist-pendulum", distances=[10.0]))
