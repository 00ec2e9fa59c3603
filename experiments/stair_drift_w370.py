"""Decision W370's measurement (adoption rule in docs/decisions/waist.md): the barometric ascent / descent of L172
(:func:`ascent_descent` with its 60 s window) against W370's (:func:`climbs_within_weather`) on the same tracks' z.

Fresh simulated users 8482-8489 (stairs, two flights with landing pauses, step-to-step stairs, a lift, level, 2 km)
tracked with the default lower-back pipeline (waist-pendulum) and the foot with ``altitude="fused"`` (no model),
and the nine mobgap lower-back recordings (waist-pendulum). W370 is an option (not adopted), switched on here.
One line per track (truth, before, after) and the rule's checks.

    PYTHONPATH=. OMP_NUM_THREADS=1 python experiments/stair_drift_w370.py
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import altitude_check
from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M, CLIMB_WINDOW_S, ascent_descent, climbs_within_weather
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.waist import track_waist
from ramp_ascent_w229 import level_check

ROUTES = {
    "STAIRS": "stand:3, straight:3, up:12, turn:180, down:12, straight:3, stand:3",
    "FLIGHTS2": "stand:3, straight:3, up:12, stand:4, up:12, turn:180, down:12, stand:4, down:12, straight:3, stand:3",
    "S2S": "stand:3, straight:3, up:12:step-to-step, turn:180, down:12:step-to-step, straight:3, stand:3",
    "LIFT": "stand:3, straight:5, lift:+3, straight:5, stand:3",
    "LEVEL": "stand:3, straight:40, turn:180, straight:40, stand:3",
}
PLAN = ([(u, "STAIRS") for u in (8482, 8483, 8484)] + [(u, "FLIGHTS2") for u in (8485, 8486)]
        + [(u, "S2S") for u in (8487, 8488)] + [(u, "LIFT") for u in (8482, 8483, 8484)]
        + [(8489, "LEVEL"), (8489, "WALK2K")])
STAIRS = ("STAIRS", "FLIGHTS2", "S2S")
REAL = sorted(Path("datasets/external").glob("mobgap_*"))


def _truth(s) -> tuple[float, float]:
    st = s.steps
    h = list(st.loc[st["foot"] == st["foot"].iloc[0], "height_m"].to_numpy(float)) if st is not None else []
    rides = (s.extras or {}).get("rides")
    if rides is not None and len(rides):
        h += list(rides["dz_m"].to_numpy(float))
    h = np.asarray(h)
    return float(h[h > 0].sum()), float(-h[h < 0].sum())


def _both(res) -> tuple[tuple[float, float], tuple[float, float]]:
    z, t = res.trajectory["z"].to_numpy(float), res.trajectory["t"].to_numpy(float)
    return (ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S),
            climbs_within_weather(z, t, ASCENT_BAND_BARO_M, CLIMB_WINDOW_S))


def main() -> int:
    logging.disable(logging.WARNING)
    altitude_check.CLIMBS_WITHIN_WEATHER = True  # W370 measured as an option (not adopted: off by default)
    rows = []
    for u, r in PLAN:
        s = (simulate("walk", UserProfile.from_seed(u), "normal", seed=u, length_m=2000.0) if r == "WALK2K" else
             simulate_path(parse_route(ROUTES[r]), UserProfile.from_seed(u), seed=u))
        tu, td = _truth(s)
        for pipe, res in (("waist", track_waist(s, pipeline="waist-pendulum")),
                          ("fused", track_plasys(s, altitude="fused"))):
            b, a = _both(res)
            span = float(res.trajectory["t"].iloc[-1] - res.trajectory["t"].iloc[0])
            rows.append((u, r, pipe, tu, td, b, a))
            print(f"{u} {r:8s} {pipe:6s} {span:6.1f} s truth {tu:6.3f}/{td:6.3f} before {b[0]:6.3f}/{b[1]:6.3f} "
                  f"after {a[0]:6.3f}/{a[1]:6.3f}", flush=True)
    real = []
    for folder in REAL:
        res = track_waist(read_session(folder), pipeline="waist-pendulum")
        b, a = _both(res)
        span = float(res.trajectory["t"].iloc[-1] - res.trajectory["t"].iloc[0])
        real.append((b, a))
        print(f"{folder.name:28s} waist {span:6.1f} s before {b[0]:.3f}/{b[1]:.3f} after {a[0]:.3f}/{a[1]:.3f}",
              flush=True)

    ok = True
    sel = [x for x in rows if x[1] in STAIRS]
    for k, name in ((0, "ascent"), (1, "descent")):
        eb = np.median([abs(x[5][k] - x[3 + k]) / x[3 + k] for x in sel]) * 100
        ea = np.median([abs(x[6][k] - x[3 + k]) / x[3 + k] for x in sel]) * 100
        good = ea <= 5.0 and (ea <= eb if k == 1 else ea <= eb + 1.0)
        ok &= good
        print(f"(1) stairs median |{name} - truth| / truth {eb:5.2f} % -> {ea:5.2f} % {'ok' if good else 'FAILS'}")
    worse = [(x[0], x[1], x[2]) for x in sel if any(abs(x[6][k] - x[3 + k]) > abs(x[5][k] - x[3 + k]) + 0.10
                                                    for k in (0, 1))]
    print(f"(1) stair tracks with an |error| > before + 0.10 m: {worse}")
    ok &= not worse
    lift = [(x[0], x[2]) for x in rows if x[1] == "LIFT" and abs(x[6][0] - x[3]) > abs(x[5][0] - x[3]) + 0.10]
    print(f"(2) lift tracks with |ascent error| > before + 0.10 m: {lift}")
    ok &= not lift
    ok &= level_check(rows)  # W229's rule (3), shared
    sb, sa = sum(sum(x[0]) for x in real), sum(sum(x[1]) for x in real)
    each = [i for i, x in enumerate(real) if sum(x[1]) > sum(x[0]) + 0.5]
    print(f"(4) mobgap summed ascent + descent {sb:.3f} -> {sa:.3f} m (limit before + 1.0 m); recordings over "
          f"their own + 0.5 m: {[REAL[i].name for i in each]}")
    ok &= sa <= sb + 1.0 and not each
    print("W370:", "ADOPTED" if ok else "NOT ADOPTED")
    return 0


if __name__ == "__main__":
    sys.exit(main())
