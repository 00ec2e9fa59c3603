"""Decisions L374-L377's measurement: the summary's floors (``floors_up`` / ``floors_down`` and their split by kind)
of a lower-back track at barometer rates of 1-100 Hz on a simulated station route (an escalator up, a stair flight up,
a lift down), against the simulated truth (3 up / 3 down: 2 by escalator, 1 by stairs, 3 by lift).

The barometer is thinned to the rate by keeping every k-th sample of the simulator's 100 Hz stream: each kept sample
keeps its own noise (a phone barometer's ~1 Pa a sample, not an average).

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/floors_rate.py --users 7210-7214
    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/floors_rate.py --pipeline plasys --rates 100  # L378
"""

from __future__ import annotations

import argparse
import dataclasses

from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

#: the trial's station route (session 33, trial T1): +6 m by escalator, +2.89 m by 17 stairs, -9 m by lift
STATION = ("straight:20, escalator:+6, straight:10, up:17, straight:5, lift:-9, straight:10, stand:30, "
           "straight:10")
RATES_HZ = (1, 2, 5, 25, 100)
KEYS = ("floors_up", "floors_down", "floors_up_stairs", "floors_up_rides", "floors_down_rides")


def thinned(session, rate_hz: float):
    """The session with its waist barometer kept every ``100 / rate_hz``-th sample (the simulator's 100 Hz)."""
    b = session["wBarometer"]
    k = max(1, round(100.0 / rate_hz))
    streams = {**session.streams, "wBarometer": Stream("wBarometer", b.t[::k], b.values[::k])}
    return dataclasses.replace(session, streams=streams)


def station_counts(user: int, rates=RATES_HZ, pipeline: str = "waist-pendulum", route: str = STATION) -> dict:
    """``{rate: summary floor keys}`` of one simulated user's station route (seed = user)."""
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.waist import track_waist

    s = simulate_path(parse_route(route), UserProfile.from_seed(user), seed=user, scenario="route")
    out = {}
    for r in rates:
        t = thinned(s, r)
        res = track_plasys(t) if pipeline == "plasys" else track_waist(t, pipeline=pipeline)  # plasys: no model
        m = track_summary(res, t, pipeline=pipeline)
        out[r] = {k: m.get(k) for k in KEYS}
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="7210-7214")
    ap.add_argument("--pipeline", default="waist-pendulum")
    ap.add_argument("--rates", default=",".join(map(str, RATES_HZ)), help="barometer rates (Hz), comma-separated")
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    right = total = 0
    for u in range(lo, hi + 1):
        rates = [float(v) if "." in v else int(v) for v in a.rates.split(",")]
        for r, m in station_counts(u, rates, pipeline=a.pipeline).items():
            ok = (m["floors_up"], m["floors_down"], m["floors_up_stairs"], m["floors_up_rides"]) == (3, 3, 1, 2)
            right += ok
            total += 1
            print(f"user {u} {r:>3} Hz: " + ", ".join(f"{k} {v}" for k, v in m.items()) + ("" if ok else "  WRONG"),
                  flush=True)
    print(f"right (3 up / 3 down, 1 up by stairs, 2 up by ride): {right} of {total}")


if __name__ == "__main__":
    main()
