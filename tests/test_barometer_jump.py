"""Decision B188: a waist barometer whose pressure changes faster than any person travels vertically (a resampling
filter's zero padding: 826 -> 1061 hPa in 15 ms) is not read - by the lower-back altitude (W89) nor by the foot
track's comparison with it (L145) - and one warning names the file, the jump's time and the fix."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.io import Stream
from pdrlearn.kernels.barometer import MAX_VERTICAL_SPEED_MPS, implausible_pressure, pressure_hpa
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track, track_summary
from pdrlearn.track.plasys import track_plasys


def _padded(session):
    """The session with the trial's artefact: the first two barometer samples at 826 hPa (zero padding)."""
    b = session["wBarometer"]
    p = b.values.copy()
    p[:2, 0] = 826.75
    return dataclasses.replace(session, streams={**session.streams, "wBarometer": Stream("wBarometer", b.t, p)})


def _waist_only(session):
    return dataclasses.replace(session, streams={k: v for k, v in session.streams.items() if k.startswith("w")},
                               steps=None, frames={k: v for k, v in session.frames.items() if k == "waist"})


@pytest.fixture(scope="module")
def stairs():
    return simulate_path(parse_route("straight:4, up:18, straight:4"), UserProfile.from_seed(1901), rate_hz=20.0,
                         seed=1901, scenario="route", bounce="pendulum")


def test_the_check_passes_a_fast_elevator_and_catches_a_jump():
    t = np.arange(0.0, 30.0, 0.01)
    noise = np.random.default_rng(1902).normal(0.0, 0.0157, t.size)  # W89: the BMP280's noise
    elevator = pressure_hpa(np.clip(t - 10.0, 0.0, 10.0) * 15.0, 1013.25) + noise  # 150 m at 15 m/s
    assert implausible_pressure(t, elevator) is None
    jump = elevator.copy()
    jump[:2] = 826.75
    found = implausible_pressure(t, jump)
    assert found is not None and found[0] > MAX_VERTICAL_SPEED_MPS
    assert found[1:] == pytest.approx((0.01, 826.75, 0.02, jump[2]))


def test_a_waist_track_does_not_read_an_impossible_barometer(stairs):
    s = _waist_only(stairs)
    good = get_pipeline("waist-pendulum")(s)
    assert evaluate_track(good, s)["floors_up"] == 1  # the storey, read from the barometer
    res = get_pipeline("waist-pendulum")(_padded(s))
    lines = [w for w in res.info["warnings"] if "B188" in w]
    assert len(lines) == 1 and "wBarometer.csv is not used" in lines[0] and "826.75" in lines[0]
    assert "padtype" in lines[0] and "delete wBarometer.csv" in lines[0] and "z stays 0" in lines[0]
    assert "2.4 hPa/s" in lines[0]
    assert not any(w.startswith("no barometer") for w in res.info["warnings"])  # one line, not two
    assert np.all(res.trajectory["z"].to_numpy() == 0.0) and not res.steps["stairs"].any()
    ev = evaluate_track(res, _padded(s))
    assert (ev["floors_up"], ev["floors_down"]) == (0, 0)
    assert len(res.steps) == len(good.steps)  # the steps and distance do not need the barometer


def test_a_foot_track_does_not_compare_with_an_impossible_barometer(stairs):
    s = _padded(stairs)
    summary = track_summary(track_plasys(s), s)
    assert "barometer_altitude_change_m" not in summary
    lines = [w for w in summary["info"]["warnings"] if "B188" in w]
    assert len(lines) == 1 and "wBarometer.csv is not used" in lines[0] and "not compared with it (L145)" in lines[0]


def test_a_fused_foot_altitude_keeps_the_foots_own_with_an_impossible_barometer(stairs):
    s = _padded(stairs)
    res = track_plasys(s, altitude="fused")
    assert res.info["altitude_source"] == "foot"  # L154 not applied to the artefact
    assert np.allclose(res.steps["dz_m"], track_plasys(s).steps["dz_m"])
    summary = track_summary(res, s)
    lines = [w for w in summary["info"]["warnings"] if "B188" in w]
    assert len(lines) == 1 and "not fused with it (L154)" in lines[0]
