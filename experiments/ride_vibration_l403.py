"""Decision L402's measurement (L403): a ride's vibration tells a vehicle's climb from a lift or an escalator.

For each ride a track reads, the kind by L376's vertical rate and duration alone ("off", the old code) and with
L402's vibration ("on", ``ride_kind(dz, duration, vibration)``), on:

(a) vehicle climbs while standing (S75's ``vehicle:60::RISE``), fresh simulated users;
(b) lifts and escalators (the station route of L374 and a short lift), fresh simulated users;
(c) the real lower-back recordings with a barometer: their rides, and the vibration of each standstill of 3 s or
    more between two steps (what a ride there would read).

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/ride_vibration_l403.py
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.kernels.pause_ride import VEHICLE_VIBRATION_MPS2, ride_kind, ride_vibration
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

VEHICLE = "stand:3, straight:10, vehicle:60::{rise}, straight:10, stand:3"
RISES = ("+4", "-4", "+8", "-6")
STATION = ("straight:20, escalator:+6, straight:10, up:17, straight:5, lift:-9, straight:10, stand:30, "
           "straight:10")
SHORT_LIFT = "stand:3, straight:5, lift:+3, stand:2, straight:5, escalator:-3, straight:5"
PIPELINES = ("waist-pendulum", "plasys")
REAL_DIRS = (Path("datasets/external"), Path("/work/shared/data"))
STILL_MIN_S = 3.0


def _track(session, pipeline: str):
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.waist import track_waist

    return track_plasys(session) if pipeline == "plasys" else track_waist(session, pipeline=pipeline)


def kinds(session, pipeline: str) -> list[tuple[str, str, float]]:
    """``(off, on, vibration)`` of each ride the track reads."""
    res = _track(session, pipeline)
    return [(ride_kind(r["dz_m"], r["duration_s"]), ride_kind(r["dz_m"], r["duration_s"], r["vibration_mps2"]),
             float(r["vibration_mps2"])) for r in res.info.get("rides") or []]


def simulated(users, route_of, pipeline: str) -> list[tuple[int, str, list]]:
    out = []
    for u in users:
        route = route_of(u)
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), seed=u, scenario="route")
        out.append((u, route, kinds(s, pipeline)))
    return out


def real() -> tuple[list, list]:
    """The real sessions' rides ``(name, off, on, vib)`` and standstills ``(name, start, end, vib)``."""
    from pdrlearn.io import read_session
    from pdrlearn.track.rides import ride_accelerometer

    rides, still = [], []
    for root in REAL_DIRS:
        for d in sorted(p.parent for p in root.glob("*/wBarometer.csv")):
            s = read_session(d)
            for off, on, vib in kinds(s, "waist-pendulum"):
                rides.append((d.name, off, on, vib))
            res = _track(s, "waist-pendulum")
            acc = ride_accelerometer(s)
            st = res.steps
            ends, starts = st["end_s"].to_numpy(float)[:-1], st["start_s"].to_numpy(float)[1:]
            for a, b in zip(ends, starts, strict=True):
                if b - a >= STILL_MIN_S:
                    still.append((d.name, a, b, ride_vibration(acc[0], acc[1], a, b)))
    return rides, still


def _users(text: str) -> list[int]:
    """``"LO-HI"`` -> the users LO to HI."""
    lo, hi = (int(v) for v in text.split("-"))
    return list(range(lo, hi + 1))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--vehicle-users", type=_users, default="7660-7671")
    ap.add_argument("--ride-users", type=_users, default="7680-7689")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    vusers, rusers = a.vehicle_users, a.ride_users
    print(f"threshold {VEHICLE_VIBRATION_MPS2} m/s^2")
    for p in PIPELINES:
        rows = simulated(vusers, lambda u: VEHICLE.format(rise=RISES[u % len(RISES)]), p)
        bad_off = sum(any(k[0] in ("lift", "escalator") for k in ks) for _, _, ks in rows)
        bad_on = sum(any(k[1] in ("lift", "escalator") for k in ks) for _, _, ks in rows)
        for u, route, ks in rows:
            print(f"(a) {p} user {u} {route.split(',')[2].strip()}: " + "; ".join(
                f"off {o}, on {n}, vib {v:.3f}" for o, n, v in ks))
        print(f"(a) {p}: vehicle climbs read as a lift or escalator: off {bad_off} / {len(rows)}, on {bad_on} / "
              f"{len(rows)}")
        half = len(rusers) * 6 // 10
        rows = simulated(rusers[:half], lambda u: STATION, p) + simulated(rusers[half:], lambda u: SHORT_LIFT, p)
        n = sum(len(ks) for _, _, ks in rows)
        changed = sum(o != k for _, _, ks in rows for o, k, _ in ks)
        for u, _route, ks in rows:
            print(f"(b) {p} user {u}: " + "; ".join(f"off {o}, on {k}, vib {v:.3f}" for o, k, v in ks))
        vmax = max((v for _, _, ks in rows for _, _, v in ks), default=float("nan"))
        print(f"(b) {p}: lift / escalator rides whose kind changed: {changed} / {n} (largest vibration {vmax:.3f})")
    rides, still = real()
    print(f"(c) real rides: {len(rides)}, kind changed: {sum(o != k for _, o, k, _ in rides)}")
    vib = np.array([v for *_, v in still], dtype=float)
    for name, a_, b_, v in still:
        print(f"(c) still {name} {a_:.1f}-{b_:.1f} s: vib {v:.3f}")
    under = int(np.sum(vib < VEHICLE_VIBRATION_MPS2))
    print(f"(c) real standstills >= {STILL_MIN_S:g} s under the threshold: {under} / {len(vib)}"
          + (f" (median {np.nanmedian(vib):.3f}, max {np.nanmax(vib):.3f})" if len(vib) else ""))


if __name__ == "__main__":
    main()
