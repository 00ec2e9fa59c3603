"""Decision L796 (docs/decisions/localization.md): the compass-headed offline track before / after turning the waist
compass by D10's measured mount yaw (``track_plasys(forward_yaw=...)``), on fresh simulated users.

Usage: ``PYTHONPATH=. python experiments/offline_mount_yaw_s52_l796.py U0 U1 [RATES]`` (users U0..U1-1, rates
default ``100,50``); one line per run, then the pooled medians of L796's rule."""
from __future__ import annotations

import dataclasses
import logging
import sys

import numpy as np
from scipy.spatial.transform import Rotation

from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.units import keep_units

ROUTES = ("stand:5, straight:20, stand:3", "stand:5, straight:50, stand:3",
          "stand:5, straight:15, turn:90, straight:10, turn:-90, straight:15, turn:180, straight:10, stand:3")


def mount_yaw_deg(user: UserProfile) -> float:
    """The simulated waist unit's forward axis yaw (deg, + counter-clockwise) off the body's forward (S34)."""
    fwd = Rotation.from_rotvec(np.radians(user.waist_misalignment_deg)).apply([1.0, 0.0, 0.0])
    return float(np.degrees(np.arctan2(fwd[1], fwd[0])))


def final_error(res, session) -> float:
    tr, tt = res.trajectory, session.trajectory
    return float(np.hypot(tr["x"].iloc[-1] - tt["x"].iloc[-1], tr["y"].iloc[-1] - tt["y"].iloc[-1]))


def first_leg_deg(res) -> float:
    """The median heading (deg) of strides 2-5 (the first leg; the truth's heading there is 0)."""
    return float(np.degrees(np.median(res.steps["heading_rad"].to_numpy(float)[1:5])))


def route_runs(u0: int, u1: int, rates: list[float], prefix: str = "l796"):
    """L796's design: (user id, rate, profile, session) for users u0..u1-1, route ``ROUTES[u % 3]``, each rate (also
    decision L801's)."""
    for u in range(u0, u1):
        user = UserProfile.from_seed(u)
        for rate in rates:
            yield u, rate, user, simulate_path(parse_route(ROUTES[u % 3]), user, rate_hz=rate, seed=0,
                                               name=f"{prefix}_u{u}", scenario="route")


def main(u0: int, u1: int, rates: list[float]) -> None:
    logging.disable(logging.WARNING)
    rows = []
    for u, rate, user, s in route_runs(u0, u1, rates):
        before, after = track_plasys(s, forward_yaw=False), track_plasys(s, forward_yaw=True)
        yaw = (after.info.get("compass_mount") or {}).get("forward_yaw_deg")
        row = dict(user=u, rate=rate, mount=mount_yaw_deg(user), measured=yaw,
                   e0=final_error(before, s), e1=final_error(after, s),
                   h0=first_leg_deg(before), h1=first_leg_deg(after))
        extra = ""
        if rate == rates[0] and u % 3 == 0:  # rule (d): the foot-only track reads no compass
            foot = keep_units(s, ("foot",))
            f0, f1 = track_plasys(foot, forward_yaw=False), track_plasys(foot, forward_yaw=True)
            same = f0.trajectory.equals(f1.trajectory) and f0.steps.equals(f1.steps)
            extra += f"; foot-only same {same} final {final_error(f0, s):.2f} m"
        if rate == rates[0] and u < u0 + 6:  # W607's option beside it (D10 does not contradict a few degrees)
            inf = track_plasys(dataclasses.replace(s, mount_frame="inferred"))
            extra += f"; --mount-frame inferred final {final_error(inf, s):.2f} m"
        rows.append(row)
        print(f"user {u} route {u % 3} {rate:g} Hz: mount yaw {row['mount']:+.2f}, measured "
              f"{'none' if yaw is None else f'{yaw:+.2f}'} deg; first leg {row['h0']:+.2f} -> {row['h1']:+.2f} "
              f"deg; final {row['e0']:.2f} -> {row['e1']:.2f} m{extra}", flush=True)
    e0, e1 = np.median([r["e0"] for r in rows]), np.median([r["e1"] for r in rows])
    h0, h1 = np.median([abs(r["h0"]) for r in rows]), np.median([abs(r["h1"]) for r in rows])
    match = [abs(r["measured"] + r["mount"]) for r in rows if r["measured"] is not None]
    print(f"L796 {len(rows)} runs: median final {e0:.3f} -> {e1:.3f} m (ratio {e1 / e0:.3f}); median |first leg| "
          f"{h0:.2f} -> {h1:.2f} deg; median |measured + mount| {np.median(match):.2f} deg over {len(match)} runs")


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]),
         [float(r) for r in (sys.argv[3] if len(sys.argv) > 3 else "100,50").split(",")])
