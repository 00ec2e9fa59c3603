"""Decision L504's measurement: L489's turn line (now counting turn episodes) on L489's turn route for users 9579
and 9821-9823, a corridor walk with one and with four turnarounds (the same users) and the real gaitmap walks,
offline plasys.

    PYTHONPATH=. python experiments/turn_episodes_l504.py
"""

from __future__ import annotations

import logging
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline

TURNS = ("stand:2, straight:3, turn:90, straight:2, turn:-90, straight:3, turn:180, straight:3, stand:2, pivot:90, "
         "straight:2, turn:360, straight:2, stand:2")  # L489's test route
CORRIDOR = "stand:2, straight:10, turn:180, straight:10, stand:2"
CORRIDOR4 = "stand:2, " + "straight:10, turn:180, " * 4 + "stand:2"  # the 4 x 10 m protocol
REAL = ["datasets/external/gaitmap_walk4x10_left", "datasets/external/gaitmap_walk4x10_right",
        "datasets/external/gaitmap_lwalk", "/work/shared/data/gaitmap_level_left",
        "/work/shared/data/gaitmap_level_right"]


def line(session) -> str:
    w = [x for x in get_pipeline("plasys")(session).info["warnings"] if "L489" in x]
    return w[0][:150] if w else "-"


def main() -> None:
    logging.disable(logging.WARNING)
    for name, route in (("turns", TURNS), ("corridor", CORRIDOR), ("4x10", CORRIDOR4)):
        for user in (9579, 9821, 9822, 9823):
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100.0, seed=user,
                              scenario="route")
            print(f"{name} u{user}: {line(s)}", flush=True)
    for path in REAL:
        if Path(path).is_dir():
            print(f"{Path(path).name}: {line(read_session(path))}", flush=True)


if __name__ == "__main__":
    main()
