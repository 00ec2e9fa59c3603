"""Decision L297's rule (docs/decisions/localization.md): final position error against the final 2-sigma radius,
waist-pendulum offline (``rest_bias`` on, L297's clock), fresh users 5657-5661 on L296's routes."""

from __future__ import annotations

import sys

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.position_sigma import add_position_sigma
from pdrlearn.track.waist import track_waist

ROUTES = {"sits": "straight:10, sit:1800, straight:10, sit:1800, straight:10",
          "trips": "straight:6, stand:60, turn:180, straight:6, sit:1800, straight:6, stand:60, turn:180, straight:6"}


def main() -> None:
    for user in range(5657, 5662):
        for kind, route in ROUTES.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=0)
            r = track_waist(s, pipeline="waist-pendulum")
            add_position_sigma(r, s)
            summ = track_summary(r, s)
            e, sig = summ["final_position_error_m"], summ["final_position_sigma_m"]
            print(f"u{user} {kind}: final error {e:.2f} m, 2-sigma {2 * sig:.2f} m, inside {e <= 2 * sig}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
