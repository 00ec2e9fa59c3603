"""Decision S29: the opt-in pendulum bounce (the pelvis's vertical excursion scales with the step length)."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.body import COMFORTABLE_STEP_PER_HEIGHT, pendulum_rise


def test_pendulum_rise_hand_computed():
    """h = L - sqrt(L^2 - (s/2)^2): L 0.9 m, s 0.6 m -> 0.9 - sqrt(0.72) = 0.051472 m; s 0 -> 0."""
    h = pendulum_rise(np.array([0.6, 0.0, -0.6]), 0.9)
    assert np.allclose(h, [0.9 - math.sqrt(0.72), 0.0, 0.9 - math.sqrt(0.72)], atol=1e-12)


def _patient(step_m: float, step_s: float) -> UserProfile:
    # the rehab trial's patients: speed "slow" multiplies the step length by 0.85 and the step time by 1.2
    return dataclasses.replace(UserProfile.from_seed(1), step_length_m=step_m / 0.85, step_time_s=step_s / 1.2)


def _bounce_pp(session, t0: float, t1: float) -> float:
    """Median peak-to-peak of the waist unit's height over its steps between t0 and t1 (noise-free session)."""
    tr = session.trajectory
    ics = np.sort(session.extras["ics"]["ic_s"].to_numpy(float))
    ics = ics[(ics > t0) & (ics < t1)]
    z = np.interp(np.linspace(t0, t1, 4000), tr["t"].to_numpy(float), tr["z"].to_numpy(float))
    tt = np.linspace(t0, t1, 4000)
    return float(np.median([np.ptp(z[(tt >= a) & (tt < b)]) for a, b in zip(ics[:-1], ics[1:], strict=True)]))


def test_short_steps_bounce_as_the_pendulum():
    """A 0.3 m step of a 1.59 m user bounces h(0.3) / h(0.415 x 1.59) of the user's bounce with the pendulum
    mode (about 0.2), the full bounce with the constant default."""
    u = _patient(0.30, 0.75)
    kw = dict(speed="slow", rate_hz=20, seed=0, noise=False)
    const = simulate_path([Stand(2), Straight(10), Stand(2)], u, **kw)
    pend = simulate_path([Stand(2), Straight(10), Stand(2)], u, bounce="pendulum", **kw)
    want = float(pendulum_rise(np.array([0.30]), u.leg_length_m)[0]
                 / pendulum_rise(np.array([COMFORTABLE_STEP_PER_HEIGHT * u.height_m]), u.leg_length_m)[0])
    assert 0.15 < want < 0.3
    a, b = 5.0, 12.0  # steady walking, away from the start and stop
    # the unit's height also moves with the pelvic tilt (0.12 m lever, in phase with the bounce), the same in both:
    # the difference of the peak-to-peaks is the bounce's own, pelvis_bounce_m x (1 - want)
    drop = _bounce_pp(const, a, b) - _bounce_pp(pend, a, b)
    expect = u.pelvis_bounce_m * (1.0 - want)
    assert abs(drop - expect) < 0.15 * expect, (drop, expect)
    # the default is the S1-S28 simulator: the knob is not written to meta.json
    assert "bounce" not in const.meta["knobs"] and pend.meta["knobs"]["bounce"] == "pendulum"


def test_slow_patient_waist_distance_with_the_pendulum_bounce():
    """The trial's 0.4 m/s patient (0.3 m steps in 0.75 s, 14 m): the uncalibrated waist-pendulum distance was
    +81 % on the constant bounce (25.30 m), within 15 % with the pendulum bounce (measured 14.95 m)."""
    from pdrlearn.track.waist import track_waist

    u = _patient(0.30, 0.75)
    out = {}
    for mode in ("constant", "pendulum"):
        s = simulate_path([Stand(3), Straight(14), Stand(3)], u, speed="slow", rate_hz=20, seed=0, bounce=mode)
        out[mode] = float(track_waist(s, pipeline="waist-pendulum").steps["length_m"].sum())
    assert out["constant"] > 1.5 * 14.0
    assert abs(out["pendulum"] - 14.0) < 0.15 * 14.0, out


def test_pendulum_bounce_on_a_standstill():
    """A route without steps simulates with the pendulum bounce as with the constant one (no step to scale)."""
    u = UserProfile.from_seed(2)
    a = simulate_path([Stand(4)], u, rate_hz=20, seed=0, bounce="pendulum")
    b = simulate_path([Stand(4)], u, rate_hz=20, seed=0)
    assert np.array_equal(a.streams["wAccelerometer"].values, b.streams["wAccelerometer"].values)


@pytest.mark.parametrize("mode", ["pendulum", "population"])  # S29, S74
def test_cli_bounce_option(tmp_path, capsys, mode):
    """`pdrlearn simulate --bounce MODE` writes the knob into meta.json; a bad value is one error line naming the
    three modes (S74)."""
    out = tmp_path / "pend"
    code = main(["simulate", "--route", "straight:4", "--user-seed", "1", "--bounce", mode, "--out", str(out)])
    _, err = capsys.readouterr()
    assert code == 0, err
    assert json.loads((out / "meta.json").read_text())["knobs"]["bounce"] == mode
    code = main(["simulate", "--route", "straight:4", "--user-seed", "1", "--bounce", "foo",
                 "--out", str(tmp_path / "x")])
    _, err = capsys.readouterr()
    assert code != 0 and err.startswith("error: --bounce") and err.count("\n") == 1, err
    assert "constant, pendulum or population" in err, err
    assert not (tmp_path / "x").exists()
