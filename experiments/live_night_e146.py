"""Decision E146's adoption rule (docs/decisions/export.md; L308's part a): the live waist tracker
(``pdrlearn.waist.WaistTracker``, 5 s pushes, each chunk's barometer first) with W231's ``pause_ride`` and L296's
``rest_bias`` at their defaults (true) and false, against ``track_waist(realtime=True)``'s defaults, on fresh simulated
users 5930-5939 (a 15 min sit; a lift with waits) and the mobgap lower-back recordings with a barometer. Prints one
line per session: the parity (max |heading| rad, max |z| m), the live floors up/down and final z with the options
true | false, and the heading change across the longest stop (deg)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker

ROUTES = {"night": "straight:10, sit:900, straight:10", "lift": "straight:10, stand:40, lift:+3, stand:40, straight:10"}
OFF = {"pause_ride": False, "rest_bias": False}


def live(s, options):
    a, g, b = s["wAccelerometer"], s["wGyroscope"], s["wBarometer"]
    tr = WaistTracker(a.rate_hz, meta=s.meta, frame=s.require_frame("waist"), params={"options": options})
    gyr = g.values if len(g) == len(a) and np.allclose(g.t, a.t) else None
    if gyr is None:
        from pdrlearn.signal import interp_rows
        gyr = interp_rows(a.t, g.t, g.values)
    k = np.floor((a.t - a.t[0]) / 5.0).astype(int)
    out, j = [], 0
    for c in np.unique(k):
        i = np.flatnonzero(k == c)
        j1 = int(np.searchsorted(b.t, a.t[i[-1]], side="right"))
        tr.push_barometer(b.t[j:j1], b.values[j:j1, 0])
        j = max(j, j1)
        out += tr.push(a.t[i], a.values[i], gyr[i])
    tr.push_barometer(b.t[j:], b.values[j:, 0])
    return out + tr.flush()


def floors(s, out) -> str:
    df = pd.DataFrame([{"start_s": o.t, "end_s": o.end_s, "event_s": o.t, "length_m": o.length_m,
                        "heading_rad": o.heading_rad, "dz_m": o.dz_m or 0.0, "pause_dz_m": o.pause_dz_m or 0.0,
                        "stairs": bool(o.stairs), "unit": "waist", "has_next": o.has_next, "merged": o.merged,
                        "turning": o.turning} for o in out])
    traj = pd.DataFrame({"t": [float(s["wAccelerometer"].t[0])] + [o.end_s for o in out],
                         "x": [0.0] + [o.x for o in out], "y": [0.0] + [o.y for o in out],
                         "z": [0.0] + [o.z or 0.0 for o in out]})
    m = evaluate_track(TrackResult(steps=df, trajectory=traj, info={"pipeline": "runtime-waist", "warnings": []}), s)
    return f"{m.get('floors_up', 0)}/{m.get('floors_down', 0)} z {traj['z'].iloc[-1]:+.2f}"


def across(out) -> float:
    t, end = np.array([o.t for o in out]), np.array([o.end_s for o in out])
    h = np.array([o.heading_rad for o in out])
    k = int(np.argmax(t[1:] - end[:-1]))
    return float(np.degrees(np.angle(np.exp(1j * (h[k + 1] - h[k])))))


def line(name, s) -> None:
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True)
    on, off = live(s, {}), live(s, OFF)
    n = min(len(on), len(ref.steps))
    dh = np.abs(np.angle(np.exp(1j * (np.array([o.heading_rad for o in on[:n]])
                                      - ref.steps["heading_rad"].to_numpy(float)[:n])))).max()
    dz = np.abs(np.array([o.z or 0.0 for o in on[:n]]) - ref.trajectory["z"].to_numpy(float)[1:n + 1]).max()
    print(f"{name}: steps {len(on)}/{len(ref.steps)} parity dh {dh:.1e} rad dz {dz:.1e} m | live on {floors(s, on)}"
          f" across {across(on):+.1f} deg | off {floors(s, off)} across {across(off):+.1f} deg", flush=True)


def main() -> None:
    for kind, users in (("night", range(5930, 5935)), ("lift", range(5935, 5940))):
        for user in users:
            line(f"u{user} {kind}", simulate_path(parse_route(ROUTES[kind]), UserProfile.from_seed(user), rate_hz=100,
                                                  seed=0))
    root = Path(__file__).resolve().parents[1] / "datasets"
    for d in sorted([*root.glob("real/mobgap_*"), *root.glob("external/mobgap_*")]):
        if (d / "wBarometer.csv").exists():
            line(f"{d.parent.name}/{d.name}", read_session(d))


if __name__ == "__main__":
    sys.exit(main())
