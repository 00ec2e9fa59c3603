"""Decision L486's adoption rule (docs/decisions/localization.md): side-stepping stretches of 1, 2 and 3 foot strides
(route S) and forward walking with turns on the spot (route F) on fresh simulated users 9560-9569 at 100 Hz, offline
and streamed ``plasys`` with no model, with L219's run test at ``MIN_SIDE_STRIDES`` 3 (before L486) and 1; and the
real gaitmap foot recordings' side strides. Prints per user: simulator's side / backward foot strides, then
``n_side_strides`` / ``n_backward_strides`` of each setting."""

from __future__ import annotations

import logging
from pathlib import Path

import pdrlearn.kernels.sideways as ks
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

ROUTE_S = ("stand:2, straight:3, stand:2, side:0.4, stand:2, straight:3, stand:2, side:-0.8, stand:2, straight:3, "
           "stand:2, side:1.2, stand:2, backward:2, stand:2, straight:3, stand:2")
ROUTE_F = "stand:2, straight:6, turn:180, straight:6, pivot:90, straight:4, turn:-90, straight:4, stand:2"
USERS = range(9560, 9570)
ROOT = Path(__file__).resolve().parents[1]
REAL = ("gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_down_left", "gaitmap_stairs_up_left")


def counts(session, min_run: int, streaming: bool = False) -> tuple[int, int]:
    ks.MIN_SIDE_STRIDES = min_run  # the run test reads the module's constant
    res = get_pipeline("plasys")(session, streaming=streaming)
    out = evaluate_track(res, session)
    return int(out["n_side_strides"] or 0), int(out["n_backward_strides"] or 0)


def truth(session) -> tuple[int, int]:
    st = session.steps
    foot = st[st["foot"] == st["foot"].iloc[0]] if "foot" in st else st
    side = foot["kind"] == "side"
    return int(side.sum()), int(((foot["direction"] == "backward") & ~side).sum())


def main() -> None:
    logging.disable(logging.WARNING)
    for name, route in (("S", ROUTE_S), ("F", ROUTE_F)):
        for user in USERS:
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=user, scenario="route")
            cells = [f"{a}/{b}" for a, b in (counts(s, 3), counts(s, 1), counts(s, 3, True), counts(s, 1, True))]
            print(f"route {name} u{user}: truth side/backward {'/'.join(map(str, truth(s)))}; offline 3: {cells[0]}, "
                  f"1: {cells[1]}; streamed 3: {cells[2]}, 1: {cells[3]}", flush=True)
    for name in REAL:
        s = read_session(ROOT / "datasets" / "real" / name)
        print(f"real {name}: side/backward min 3: {'/'.join(map(str, counts(s, 3)))}, "
              f"1: {'/'.join(map(str, counts(s, 1)))}", flush=True)


if __name__ == "__main__":
    main()
