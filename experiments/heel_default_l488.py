"""Decision L488's adoption rule (docs/decisions/localization.md): the foot track's distance error with
``reference_point`` "sensor" (the default before L488) and "heel" (L22) on fresh simulated users 9573-9578 (route T:
turns on the spot; route W: straight walks), scenario D (user 1, M1 / M2 / M3 with the oracle classes), and the real
gaitmap level walks' stride-length errors against their mocap reference."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys

ROUTES = {"T": "stand:2, straight:3, turn:90, straight:2, turn:-90, straight:3, turn:180, straight:3, stand:2, "
               "pivot:90, straight:2, turn:360, straight:2, stand:2",
          "W": "stand:2, straight:10, stand:2, straight:10, stand:2"}
POINTS = ("sensor", "heel")
ROOT = Path(__file__).resolve().parents[1]


def summary(session, point: str, **kw) -> dict:
    return track_summary(track_plasys(session, params={"reference_point": point}, **kw), session)


def main() -> None:
    logging.disable(logging.WARNING)
    for name, route in ROUTES.items():
        errs = {p: [] for p in POINTS}
        for user in range(9573, 9579):
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=user, scenario="route")
            for p in POINTS:
                errs[p].append(float(summary(s, p)["distance_error_pct"]))
            print(f"route {name} u{user}: distance error sensor {errs['sensor'][-1]:+.2f} %, heel "
                  f"{errs['heel'][-1]:+.2f} %", flush=True)
        print(f"route {name}: mean |error| sensor {np.mean(np.abs(errs['sensor'])):.2f} %, heel "
              f"{np.mean(np.abs(errs['heel'])):.2f} %", flush=True)
    d = simulate("D", 1)
    for method in ("M1", "M2", "M3"):
        e = [float(summary(d, p, method=method, model="oracle")["distance_error_pct"]) for p in POINTS]
        print(f"scenario D {method}: distance error sensor {e[0]:+.3f} %, heel {e[1]:+.3f} %", flush=True)
    for side in ("left", "right"):
        s = read_session(ROOT / "datasets" / "real" / f"gaitmap_level_{side}")
        o = [summary(s, p) for p in POINTS]
        print(f"gaitmap level {side}: stride MAE sensor {o[0]['stride_length_mae_pct']:.2f} % (straight "
              f"{o[0]['stride_length_mae_pct_straight']:.2f}), heel {o[1]['stride_length_mae_pct']:.2f} % (straight "
              f"{o[1]['stride_length_mae_pct_straight']:.2f})", flush=True)


if __name__ == "__main__":
    main()
