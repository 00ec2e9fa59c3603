"""Decision L609 (docs/decisions/localization.md): L589's straight-stride fused offset judged on the median final
position error per route over fresh users (L590's open point).

Each user (``UserProfile.from_seed(u)``, 50 Hz, ``seed=u``) walks four routes - T4's two 360-deg turns on the spot,
the same with two 180-deg turns, the plain route and a square of three 90-deg turns on the spot - tracked by
``track_plasys`` (two-unit foot pipeline, fused heading) with ``fused_straight`` False (L17's all-stride offset)
and True (L589 / L609); one JSON line per user and route (``final_position_error_m`` before / after), then the
medians per route.

Run: ``PYTHONPATH=$PWD python experiments/fused_straight_l609.py FIRST LAST OUT.jsonl`` (L609: 11995 12019).
"""

from __future__ import annotations

import json
import logging
import sys

import numpy as np

ROUTES = {"turn360": "stand:2, straight:3, turn:360, stand:5, turn:360, straight:3, stand:2",
          "turn180": "stand:2, straight:3, turn:180, stand:5, turn:180, straight:3, stand:2",
          "plain": "stand:2, straight:3, stand:5, straight:3, stand:2",
          "square90": "stand:2, straight:4, turn:90, straight:4, turn:90, straight:4, turn:90, straight:4, stand:2"}


def one(user: int, route: str) -> tuple[float | None, float | None]:
    """The final position error (m) with the all-stride and with the straight-stride offset."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=50.0, seed=user, scenario="route")
    return tuple(evaluate_track(track_plasys(s, fused_straight=fs), s).get("final_position_error_m")
                 for fs in (False, True))


def main(first: int, last: int, out: str) -> None:
    logging.disable(logging.WARNING)
    rows = []
    with open(out, "a") as f:
        for u in range(first, last + 1):
            for name, route in ROUTES.items():
                before, after = one(u, route)
                rows.append({"user": u, "route": name, "before": before, "after": after})
                print(json.dumps(rows[-1]), flush=True)
                f.write(json.dumps(rows[-1]) + "\n")
    for name in ROUTES:
        b = np.array([r["before"] for r in rows if r["route"] == name])
        a = np.array([r["after"] for r in rows if r["route"] == name])
        print(f"{name}: n={len(b)} median before {np.median(b):.3f} m, after {np.median(a):.3f} m, change "
              f"{np.median(a) - np.median(b):+.3f} m; worse users {int((a > b + 1e-9).sum())}, max rise "
              f"{np.max(a - b):+.3f} m")


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]), sys.argv[3])
