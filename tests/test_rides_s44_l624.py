"""Decision L624 (session 44, helper I2): a foot track without a barometer reads L616's vehicle rows from the foot's
vibration: rides.csv with ``dz_m`` empty, steps.csv's ``ride``, the vehicle line saying "no barometer" (before: no
rides.csv, no line). ``ride_vibration=False`` (L615's option) reads none. Simulated user 12131 (seed = user), foot
streams only."""

from __future__ import annotations

import dataclasses
import math

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def foot_bus():
    s = simulate_path(parse_route("stand:3, straight:10, vehicle:40, straight:10, stand:25, straight:5, stand:3"),
                      UserProfile.from_seed(12131), seed=12131, scenario="route")
    return s, dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if k.startswith("f")})


def test_a_foot_only_track_writes_its_vehicle_ride_l624(foot_bus):
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.rides import ride_table

    full, s = foot_bus
    assert "wBarometer" not in s.streams
    r = track_plasys(s)
    rides = r.info["rides"]
    assert [x["kind"] for x in rides] == ["vehicle"]  # the quiet 25 s stand is none
    t0, t1 = (float(full.extras["rides"][c].iloc[0]) for c in ("start_s", "end_s"))
    assert min(t1, rides[0]["end_s"]) - max(t0, rides[0]["start_s"]) >= 0.8 * (t1 - t0)
    assert math.isnan(rides[0]["dz_m"]) and "pause_dz_m" not in r.steps
    assert list(r.steps["ride"][r.steps["ride"] != ""]) == ["vehicle"]
    said = [w for w in r.info["warnings"] if "vehicle ride(s)" in w]
    assert len(said) == 1 and "no barometer" in said[0]
    assert track_summary(r, s, pipeline="plasys")["n_rides"] == 1
    assert ride_table(r.info)["dz_m"].isna().all()
    off = track_plasys(s, ride_vibration=False)
    assert off.info.get("rides") is None and "ride" not in off.steps
