"""Decision W229 (an option, ``ascent_descent(..., by_rate=True)``; L584: a keyword, no module switch): a ramp's
barometric climb is not the weather's drift (trial s30 "ramp", finding 2); decision W230: a step's barometric change
over 0.5 m is named."""

import numpy as np
import pytest

from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M, CLIMB_WINDOW_S, ascent_descent, drift_free_altitude


def _ramp_walk(rises, level_s=60.0, climb_s=5.0, dt=0.55, drift_m_per_s=0.0, noise=0.0, seed=0):
    """Steps every ``dt`` s: each rise (m) climbed in ``climb_s`` s, then ``level_s`` s level; a weather drift."""
    t, z, now, h = [0.0], [0.0], 0.0, 0.0
    for r in rises:
        for k in range(1, int(climb_s / dt) + 1):
            t.append(now + k * dt)
            z.append(h + r * k / int(climb_s / dt))
        now, h = t[-1], z[-1]
        for k in range(1, int(level_s / dt) + 1):
            t.append(now + k * dt)
            z.append(h)
        now = t[-1]
    t, z = np.array(t), np.array(z)
    z = z + drift_m_per_s * t + np.random.default_rng(seed).normal(0.0, noise, len(t))
    return t, z


def test_a_ramp_climb_of_0_4_m_in_5_s_is_not_drift():
    """L172 dropped what of a climb had not crossed the 0.5 m band within a minute (the trial's CURB: 0.45 m
    climbed, ascent 0.0, altitude_drift_m 0.455; R12UP's last 0.48 m); W229 keeps it and drops only the slow part."""
    t, z = _ramp_walk([0.45])
    assert ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S, by_rate=True) == pytest.approx((0.45, 0.0),
                                                                                       abs=1e-9)
    assert ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S) == (0.0, 0.0)  # the default, L172: drift
    t, z = _ramp_walk([0.75, 0.75, 0.75, 0.75])  # R12UP: four 1:12 runs with landings
    up, down = ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S, by_rate=True)
    assert up == pytest.approx(3.0, abs=1e-9) and down == 0.0


def test_a_closed_ramp_loop_counts_its_whole_climb_and_descent():
    """The zigzag counts from turning point to turning point: 2.25 m up and down in 0.75 m runs (R12), with the
    simulated barometer's 1-s averaged noise (0.13 m / sqrt(20), W89), within 0.15 m each (L172: ~1.8 / 1.6 m)."""
    t, z = _ramp_walk([0.75, 0.75, 0.75, -0.75, -0.75, -0.75], level_s=8.0, noise=0.13 / np.sqrt(20))
    up, down = ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S, by_rate=True)
    assert up == pytest.approx(2.25, abs=0.15) and down == pytest.approx(2.25, abs=0.15)
    assert up - down == pytest.approx(z[-1] - z[0], abs=0.01)


def test_the_weather_drift_is_still_dropped_and_a_climb_kept_on_it():
    """The weather's 0.3 hPa/h (~0.04 m per minute, S4) on an hour of level walking is drift; a 1 m climb in 10 s
    on top of it is a climb; a slow 0.2 m per minute is drift too."""
    t = np.arange(0.0, 3600.0, 0.55)
    z = 0.04 * t / 60.0 + np.random.default_rng(1).normal(0.0, 0.03, len(t))
    up, down = ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S, by_rate=True)
    assert up < 0.6 and down < 0.6
    assert (drift_free_altitude(z, t)[-1] - z[0]) == pytest.approx(0.0, abs=0.3)
    climb = z + np.clip((t - 1800.0) / 10.0, 0.0, 1.0)
    up2, _ = ascent_descent(climb, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S, by_rate=True)
    assert up2 - up == pytest.approx(1.0, abs=0.15)  # the noise at its top and foot: up to ~3 SDs
    slow = 0.2 * t[t < 600] / 60.0
    assert drift_free_altitude(slow, t[t < 600])[-1] == pytest.approx(0.0)


def test_a_step_of_1_3_m_is_a_pressure_transient():
    """Decision W230: a step's barometric change over 0.5 m (HA002 Test11: -1.28 m in one step) is held level, and
    every later altitude with it; a standstill's change (a lift ride, W158's pause) and stair steps are kept."""
    from pdrlearn.kernels.barometer import MAX_STEP_DZ_M, hold_step_jumps

    z_start = np.array([0.0, 0.17, 0.34, 3.34, 2.06])  # steps 0-2 climb risers, a 3 m ride before step 3
    z = np.array([0.0, 0.17, 0.34, 0.51, 2.06, 2.06])  # step 3 drops 1.28 m; step 4 level
    z2, zs2, jumped = hold_step_jumps(z, z_start)
    assert MAX_STEP_DZ_M == 0.5 and jumped.tolist() == [False, False, False, True, False]
    assert z2[1:] - zs2 == pytest.approx([0.17, 0.17, 0.17, 0.0, 0.0])  # each step's dz_m
    assert zs2 - z2[:-1] == pytest.approx([0.0, 0.0, 0.0, 2.83, 0.0])  # each pause's (the ride kept)
    assert z2[-1] == pytest.approx(3.34)


def test_a_stair_flight_up_and_straight_back_down_is_not_drift():
    """W229's first candidate read the rate over one centred span: up 2.89 m and at once back down cancelled there
    and half of each flight became drift (fresh users 5612-5617: ascent 1.36-1.77 of 2.89 m). Two one-sided spans."""
    t = np.arange(0.0, 40.0, 0.5)
    z = np.interp(t, [0.0, 10.0, 18.5, 19.0, 27.5, 40.0], [0.0, 0.0, 2.89, 2.89, 0.0, 0.0])
    up_down = ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S, by_rate=True)
    assert up_down == pytest.approx((2.89, 2.89), abs=1e-9)


def test_ha002_test11_names_its_pressure_transient(caplog):
    """Decision W230 (trial s30 finding 4): the real level lab recording mobgap HA002 Test11 Trial1 has two steps of
    -1.28 / -1.19 m (W108's transient); the lower-back track names them in one line, its altitude unchanged by
    default; the option ``step_bound`` holds them level."""
    from pathlib import Path

    from pdrlearn.io.plasys import read_session
    from pdrlearn.track.waist import track_waist

    folder = Path(__file__).resolve().parents[1] / "datasets" / "external" / "mobgap_HA002_Test11_Trial1"
    if not folder.is_dir():
        pytest.skip("datasets/external not linked")
    session = read_session(folder)
    res = track_waist(session, pipeline="waist-pendulum")
    lines = [w for w in res.info["warnings"] if "decision W230" in w]
    assert len(lines) == 1 and lines[0].startswith("2 step(s) changed the barometric altitude by more than 0.5 m")
    assert "step_bound" in lines[0] and res.info["barometer_jump_steps"] == 2
    dz = res.steps["dz_m"].to_numpy(float)
    assert (np.abs(dz) > 1.0).sum() == 2
    held = track_waist(session, pipeline="waist-pendulum", params={"options": {"step_bound": True}})
    assert np.abs(held.steps["dz_m"].to_numpy(float)).max() <= 0.5
