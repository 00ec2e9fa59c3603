"""Decisions L374-L377 and B289 (session 33, trial T1 findings 2-5 and 8): a lower-back track's floors at phone
barometer rates, stairs and rides told apart, lift / escalator / other rides, rides.csv and the escalator's travel
line, and the kPa import message. Simulated users 7221-7224 (seed = user) on the trial's station route: +6 m by
escalator, a 17-stair flight (+2.89 m), -9 m by lift; truth 3 storeys up (1 by stairs, 2 ridden), 3 down (ridden)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.kernels.barometer import pressure_hpa
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.waist import track_waist

STATION = ("straight:20, escalator:+6, straight:10, up:17, straight:5, lift:-9, straight:10, stand:30, "
           "straight:10")


def _station(user: int):
    return simulate_path(parse_route(STATION), UserProfile.from_seed(user), seed=user, scenario="route")


def _with_baro(session, t, values):
    return dataclasses.replace(session, streams={**session.streams, "wBarometer": Stream("wBarometer", t, values)})


def _thinned(session, rate_hz: float):
    """The waist barometer kept every k-th sample of the simulator's 100 Hz (each keeps its own ~1 Pa noise)."""
    b = session["wBarometer"]
    k = max(1, round(100.0 / rate_hz))
    return _with_baro(session, b.t[::k], b.values[::k])


def _summary(session):
    return track_summary(track_waist(session, pipeline="waist-pendulum"), session, pipeline="waist-pendulum")


@pytest.mark.parametrize("user", [7221, 7222])
def test_floors_are_right_at_every_barometer_rate_l374(user):
    """L374: 3 up / 3 down at 1, 2, 5, 25 and 100 Hz (before: e.g. 0 up / 3 down at 1-2 Hz, 3 / 5 at 5 Hz)."""
    s = _station(user)
    got = {}
    for rate in (1, 2, 5, 25, 100):
        m = _summary(_thinned(s, rate))
        got[rate] = (m["floors_up"], m["floors_down"])
    print(user, got)
    assert set(got.values()) == {(3, 3)}, got


def test_a_ride_and_a_stair_flight_in_one_climb_are_split_l375():
    """L375: the escalator's 2 storeys are ridden, the flight's 1 is stairs (before: 0 stairs / 3 rides)."""
    m = _summary(_station(7223))
    assert (m["floors_up_stairs"], m["floors_up_rides"], m["floors_down_rides"]) == (1, 2, 3), m
    assert m["floors_up"] == 3 and m["floors_down"] == 3


def _bus(rise_m: float, over_s: float, user: int = 7224):
    """A walk with a 90 s standstill inside which the pressure altitude rises ``rise_m`` linearly over ``over_s``
    (a bus up a hill, the walker standing in it)."""
    s = simulate_path(parse_route("straight:10, stand:90, straight:10"), UserProfile.from_seed(user), seed=user,
                      scenario="route")
    b = s["wBarometer"]
    walk = s.steps["end_s"].to_numpy(float)
    t_a = float(walk[walk < walk.max() - 20].max()) + 10.0  # 10 s into the standstill
    rise = np.clip((b.t - t_a) / over_s, 0.0, 1.0) * rise_m
    p = b.values[:, 0] + pressure_hpa(rise, 1013.25) - pressure_hpa(0.0, 1013.25)
    return _with_baro(s, b.t, p[:, None])


@pytest.mark.parametrize("rise, over", [(15.0, 60.0), (4.0, 60.0)])
def test_a_vehicle_climb_is_no_storey_ridden_l376(rise, over):
    """L376: a 15 m (or 4 m) climb over 60 s while standing is neither a lift nor an escalator: no floors, one line
    (before: 5 storeys ridden for 15 m, 1 for 4 m)."""
    s = _bus(rise, over)
    r = track_waist(s, pipeline="waist-pendulum")
    m = track_summary(r, s, pipeline="waist-pendulum")
    assert m["floors_up"] == 0 and m["floors_up_rides"] == 0, m
    assert m["altitude_change_m"] == pytest.approx(rise, abs=0.5)  # the height stays in the altitude
    assert list(r.steps["ride"][r.steps["ride"] != ""]) == ["other"]
    assert any("decision L376" in w and "count no floors" in w for w in r.info["warnings"])


def test_ride_kinds_from_rate_and_duration_l376():
    from pdrlearn.kernels.pause_ride import ride_kind

    assert ride_kind(-9.0, 8.0) == "lift"  # 1.1 m/s
    assert ride_kind(6.0, 24.0) == "escalator"  # 0.25 m/s
    assert ride_kind(15.0, 60.0) == "other"  # escalator rate, too long
    assert ride_kind(4.0, 60.0) == "other"  # too slow


def test_track_writes_rides_csv_and_warns_of_the_escalator_travel_l377(tmp_path, capsys):
    """L377: rides.csv has the escalator (+6 m, estimated 10.4 m of horizontal travel) and the lift (-9 m); the
    summary counts 2 rides; the escalator's travel left out of the track is said in one line."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(_station(7223), tmp_path / "s")
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--units", "waist", "--out", str(tmp_path / "t")]) == 0
    err = capsys.readouterr().err
    rides = pd.read_csv(tmp_path / "t" / "rides.csv")
    assert list(rides["kind"]) == ["escalator", "lift"]
    assert rides["dz_m"].to_numpy() == pytest.approx([6.0, -9.0], abs=0.3)
    assert rides["horizontal_est_m"].iloc[0] == pytest.approx(6.0 / np.tan(np.radians(30.0)), abs=0.6)
    assert np.isnan(rides["horizontal_est_m"].iloc[1])
    assert json.loads((tmp_path / "t" / "summary.json").read_text())["n_rides"] == 2
    assert "escalator ride(s) (rides.csv) carried the walker an estimated" in err and "decision L377" in err


def test_kpa_pressure_error_names_the_header_hint(tmp_path, capsys):
    """B289: a pressure column in kPa is refused with the header hint that converts it."""
    from pdrlearn.cli import main

    n = 1000
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"time_s": np.arange(n) * 0.01, "acc_x": rng.normal(0, 0.1, n),
                       "acc_y": 9.81 + rng.normal(0, 0.1, n), "acc_z": rng.normal(0, 0.1, n),
                       **{f"gyr_{c}": rng.normal(0, 0.01, n) for c in "xyz"}, "pressure": 99.3 + np.zeros(n)})
    df.to_csv(tmp_path / "p.csv", index=False)
    assert main(["import", str(tmp_path / "p.csv"), "--unit", "waist", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err
    assert "looks like kPa" in err and "'pressure (kPa)'" in err and "B289" in err
    assert not (tmp_path / "o").exists()
    df.rename(columns={"pressure": "pressure (kPa)"}).to_csv(tmp_path / "q.csv", index=False)
    assert main(["import", str(tmp_path / "q.csv"), "--unit", "waist", "--out", str(tmp_path / "o")]) == 0


def test_a_foot_track_counts_the_rides_of_the_waist_barometer_l378():
    """L378: the default foot track (plasys, no model) of the station route counts 3 up / 3 down, the rides from the
    waist barometer (before: 1 up / 0 down, its stairs only); its altitude stays the foot's own."""
    from pdrlearn.track.plasys import track_plasys

    s = _station(7223)
    r = track_plasys(s)
    m = track_summary(r, s)
    assert (m["floors_up"], m["floors_down"], m["floors_up_stairs"], m["floors_up_rides"]) == (3, 3, 1, 2), m
    assert m["n_rides"] == 2 and [x["kind"] for x in r.info["rides"]] == ["escalator", "lift"]
    assert r.steps["pause_dz_m"].abs().max() == pytest.approx(9.0, abs=0.3)
    assert abs(m["altitude_change_m"] - 2.9) < 0.5  # the strides' own height: the flight, not the rides
    assert any("decision L377" in w for w in r.info["warnings"])
