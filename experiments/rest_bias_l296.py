"""Decision L296's adoption rule (docs/decisions/localization.md): final position error and the heading change across
each stop over 60 s, waist-pendulum offline with ``rest_bias`` false (= main) and true, fresh simulated users
5657-5661 on a straight route with two sits and on two night8 trips; and the mobgap lower-back recordings."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.waist import track_waist

ROUTES = {"sits": "straight:10, sit:1800, straight:10, sit:1800, straight:10",
          "trips": "straight:6, stand:60, turn:180, straight:6, sit:1800, straight:6, stand:60, turn:180, straight:6"}


def run(session, on: bool) -> tuple[float | None, list[float], np.ndarray]:
    r = track_waist(session, pipeline="waist-pendulum", rest_bias=on)
    s = track_summary(r, session)
    st = r.steps
    gap = st["start_s"].to_numpy(float)[1:] - st["end_s"].to_numpy(float)[:-1]
    h = st["heading_rad"].to_numpy(float)
    across = [float(np.degrees(np.angle(np.exp(1j * (h[k + 1] - h[k]))))) for k in np.flatnonzero(gap > 60.0)]
    return s.get("final_position_error_m"), across, h


def main() -> None:
    for user in range(5657, 5662):
        for kind, route in ROUTES.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=0)
            (e0, a0, _), (e1, a1, _) = run(s, False), run(s, True)
            print(f"u{user} {kind}: final error off {e0:.2f} m on {e1:.2f} m; across stops > 60 s off "
                  f"{[round(a, 1) for a in a0]} on {[round(a, 1) for a in a1]} deg", flush=True)
    root = Path(__file__).resolve().parents[1] / "datasets"
    for d in sorted([*root.glob("real/mobgap_*"), *root.glob("external/mobgap_*")]):
        s = read_session(d)
        (e0, _, h0), (e1, _, h1) = run(s, False), run(s, True)
        print(f"{d.parent.name}/{d.name}: identical {bool(np.array_equal(h0, h1))}, final error off {e0} on {e1}",
              flush=True)


if __name__ == "__main__":
    sys.exit(main())
