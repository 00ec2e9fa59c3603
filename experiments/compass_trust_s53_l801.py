"""Decision L801 (docs/decisions/localization.md): L796's measured mount yaw is not applied when W435 does not trust
the measured forward (step-frequency power ratio under x10) or the waist frame is forced (W434).

Usage: ``PYTHONPATH=. python experiments/compass_trust_s53_l801.py asym`` (rule (a): review s53r1's asymmetric and
forced walkers), ``... fresh U0 U1 [RATES]`` (rule (b): L796's design on users U0..U1-1, rates default ``100,50``;
each run also without L801's gate, L796 as adopted, when the gate skipped the turn). L801's gate is
``track_plasys(forward_yaw_gate=True)`` (measured while it was this branch's default: the same code, the same
numbers)."""
from __future__ import annotations

import logging
import sys

import numpy as np

from offline_mount_yaw_s52_l796 import final_error, route_runs
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

ASYM_ROUTE = "stand:3, straight:15, turn:90, straight:10, turn:-90, straight:10, stand:3"


def asym() -> None:
    for uid, a, forced in ((10810, 0.2, False), (10811, 0.2, False), (10815, 0.45, False), (10814, 0.45, True),
                           (10808, 0.0, False)):
        s = simulate_path(parse_route(ASYM_ROUTE), UserProfile.from_seed(uid), rate_hz=100.0, seed=0,
                          name=f"u{uid}", scenario="route", speed="slow", step_time_asymmetry=a,
                          paretic_side="right", rocker="smooth")
        if forced:
            s.meta["force_frame"] = ["waist"]
        off, on, old = track_plasys(s, forward_yaw=False), track_plasys(s, forward_yaw_gate=True), track_plasys(s)
        cm = on.info["compass_mount"] or {}
        ev = [evaluate_track(r, s)["final_position_error_m"] for r in (off, old, on)]  # the review's measure
        print(f"user {uid} asym {a} forced {forced}: ratio {cm.get('forward_power_ratio')} yaw "
              f"{cm.get('forward_yaw_deg')} skipped {cm.get('forward_yaw_skipped')}; final error forward_yaw False "
              f"{final_error(off, s):.3f} m, L796 {final_error(old, s):.3f} m, L801 {final_error(on, s):.3f} m "
              f"(evaluate_track: {ev[0]:.3f}, {ev[1]:.3f}, {ev[2]:.3f} m)", flush=True)


def fresh(u0: int, u1: int, rates: list[float]) -> None:
    rows = []
    for u, rate, _, s in route_runs(u0, u1, rates, "l801"):
        before, after = track_plasys(s, forward_yaw=False), track_plasys(s, forward_yaw_gate=True)
        cm = after.info.get("compass_mount") or {}
        skipped = cm.get("forward_yaw_skipped")
        e0, e1 = final_error(before, s), final_error(after, s)
        e796 = final_error(track_plasys(s), s) if skipped else e1  # L796, the default
        rows.append((e0, e1, e796, skipped))
        print(f"user {u} route {u % 3} {rate:g} Hz: ratio {cm.get('forward_power_ratio')} yaw "
              f"{cm.get('forward_yaw_deg')} skipped {skipped}; final {e0:.3f} -> L801 {e1:.3f} m (L796 "
              f"{e796:.3f} m)", flush=True)
    e0, e1, e796 = (float(np.median([r[i] for r in rows])) for i in range(3))
    print(f"L801 {len(rows)} runs: median final {e0:.3f} -> {e1:.3f} m (ratio {e1 / e0:.3f}); L796 without the gate "
          f"{e796:.3f} m (ratio {e796 / e0:.3f}); gate skipped {sum(bool(r[3]) for r in rows)} runs")


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    if sys.argv[1] == "asym":
        asym()
    else:
        fresh(int(sys.argv[2]), int(sys.argv[3]),
              [float(r) for r in (sys.argv[4] if len(sys.argv) > 4 else "100,50").split(",")])
