"""Decision L620 (session 43, fixer FJ; amends L615 / L616, docs/decisions/localization.md): a climbing vehicle ride
spans the vehicle's motion (L616's vibrating span), not only its barometric climb - review R1 finding 5: the 60 s
bus ride that climbs 4 m (truth 16.41-76.41 s) read 40.23-52.73 s in rides.csv and "0.7 min in all" for 1.5 min."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys

# R1's route (the L615 test's bus): a bus climbing 4 m while the walker stands, then a level 30 s ride
ROUTE = "stand:3, straight:10, vehicle:60::4, straight:10, vehicle:30, straight:10, stand:25, straight:5, stand:3"


@pytest.mark.parametrize("user", [12090, 12117])
def test_a_climbing_vehicle_ride_covers_the_ride_l620(user):
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), seed=user, scenario="route")
        rides = track_plasys(s).info["rides"]
    finally:
        logging.disable(logging.NOTSET)
    truth = s.extras["rides"]
    assert [r["kind"] for r in rides] == ["vehicle", "vehicle"], rides
    for got, (_, want) in zip(rides, truth.iterrows(), strict=True):
        a, b = float(want["start_s"]), float(want["end_s"])
        covered = max(0.0, min(got["end_s"], b) - max(got["start_s"], a))
        assert covered >= 0.8 * (b - a), (got, a, b)
        assert got["duration_s"] == pytest.approx(got["end_s"] - got["start_s"])
    climb = rides[0]
    assert climb["dz_m"] > 3.0 and climb["vertical_rate_mps"] > climb["dz_m"] / climb["duration_s"]  # the climb's
