"""Decision L400's check: side strides (L219 / L228) on turns on the spot and on side steps, per simulated user.

Prints, for each user (20 Hz), the foot track's side-stride rows (plasys offline, steps.csv's ``sideways``) and the
number of L219 lines of waist-pendulum. Run it on the code before and after L400 to compare:

    PYTHONPATH=. python experiments/sideways_turns_l400.py
"""

from __future__ import annotations

import logging

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline

SPIN = "straight:10, turn:360, stand:2, turn:-360, stand:2"  # the new user's route (finding 5)
SIDE = "straight:6, side:-3, straight:6"  # tests/test_track_sideways_l219.py's side stretch
CASES = [(SPIN, u) for u in range(7560, 7570)] + [(SIDE, u) for u in range(7570, 7575)]


def side_counts(route: str, user: int) -> tuple[int, int]:
    s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=user, scenario="route")
    foot = get_pipeline("plasys")(s)
    waist = get_pipeline("waist-pendulum")(s)
    lines = [w for w in waist.info["warnings"] if "decision L219" in w]
    return int(foot.steps["sideways"].sum()), len(lines)


def main() -> None:
    logging.disable(logging.WARNING)
    for route, user in CASES:
        rows, lines = side_counts(route, user)
        print(f"{'spin' if route == SPIN else 'side'} user {user}: plasys side-stride rows {rows}, "
              f"waist-pendulum L219 lines {lines}")


if __name__ == "__main__":
    main()
