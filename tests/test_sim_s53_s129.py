"""Decision S129 (session 53, FD, trial s53t2 finding F1): the simulator's escalator climbs a 30 deg incline between
level landings, so a 5 m rise travels 10.8 m ahead (24.9 deg overall); its help and docs say so."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.sim import route
from pdrlearn.sim.ride import ESCALATOR_INCLINE_DEG, draw_ride, escalator_travel_m, ride_offset


def test_the_escalator_travel_is_the_incline_plus_its_landings():
    ride = draw_ride(3, "escalator", 5.0, 0.0, np.random.default_rng(0))
    dx, dy, dz = ride.displacement
    assert dz == pytest.approx(5.0)
    assert math.hypot(dx, dy) == pytest.approx(escalator_travel_m(5.0)) == pytest.approx(10.796, abs=1e-3)
    assert math.degrees(math.atan2(5.0, escalator_travel_m(5.0))) == pytest.approx(24.85, abs=0.01)
    # the incline itself is 30 deg: the middle of the ride
    a, b = ride_offset(np.array([0.45, 0.55]) * ride.duration_s, [ride], np.array([0.0]))
    assert math.degrees(math.atan2(b[2] - a[2], math.hypot(*(b[:2] - a[:2])))) == pytest.approx(ESCALATOR_INCLINE_DEG)
    assert escalator_travel_m(-5.0) == escalator_travel_m(5.0)


def test_the_route_help_names_the_landings():
    line = next(x for x in route.__doc__.splitlines() if x.startswith("| ``escalator:H``"))
    assert "30 deg incline" in line and "landings" in line and "S129" in line
