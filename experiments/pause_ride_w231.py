"""Decision W231's adoption rule (docs/decisions/waist.md): floors of a level night, a lift and an escalator with
waits, waist-pendulum offline with ``pause_ride`` false (= main) and true, fresh simulated users 5652-5656; and the
mobgap lower-back recordings with a barometer. Prints one line per session."""

from __future__ import annotations

import sys
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.waist import track_waist

ROUTES = {"night": "straight:10, sit:1800, straight:10, sit:1800, straight:10",
          "lift": "straight:10, stand:40, lift:+3, stand:40, straight:10",
          "escalator": "straight:10, stand:40, escalator:3, stand:40, straight:10"}


def floors(session, ride: bool) -> str:
    r = track_waist(session, pipeline="waist-pendulum", pause_ride=ride)
    s = track_summary(r, session)
    return f"{s.get('floors_up', 0)}/{s.get('floors_down', 0)} alt {r.trajectory['z'].iloc[-1]:+.2f}"


def main() -> None:
    for user in range(5652, 5657):
        for kind, route in ROUTES.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=0)
            print(f"u{user} {kind}: off {floors(s, False)} | on {floors(s, True)}", flush=True)
    root = Path(__file__).resolve().parents[1] / "datasets"
    for d in sorted([*root.glob("real/mobgap_*"), *root.glob("external/mobgap_*")]):
        if (d / "wBarometer.csv").exists():
            s = read_session(d)
            print(f"{d.parent.name}/{d.name}: off {floors(s, False)} | on {floors(s, True)}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
