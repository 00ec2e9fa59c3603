"""Decision L624 (session 44, helper I2): a foot track without a barometer reads L616's vehicle rows from the foot's
vibration. The adoption rule's three checks (docs/decisions/localization.md, L624), foot streams only, plasys:

(a) fresh users 12132-12137 (100 Hz, seed = user) on L616's route, D = 30 + 10 x (user mod 6) s: exactly one vehicle
    row covering >= 80 % of the simulated ride and none in the 30 s quiet stand, in at least 5 of 6;
(b) fresh users 12138-12139 on a 25 s freeze of gait: no vehicle row;
(c) every real foot recording (the L615 experiment's folders): no vehicle row.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/foot_only_rides_s44.py``.
"""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

LEVEL = "stand:5, straight:20, stand:5, vehicle:{d}, stand:3, straight:20, stand:30, straight:10, stand:5"
FREEZE = "stand:3, straight:10, freeze:25, straight:10, stand:3"
REAL_DIRS = (Path("datasets/real"), Path("datasets/external"), Path("/work/shared/data"))


def foot_only(session):
    """``session`` with its foot unit's streams only (no waist barometer)."""
    return dataclasses.replace(session, streams={k: v for k, v in session.streams.items() if k.startswith("f")})


def vehicle_rows(session) -> list[dict]:
    from pdrlearn.track.plasys import track_plasys

    return [r for r in track_plasys(session).info.get("rides") or [] if r["kind"] == "vehicle"]


def _sim(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=user, scenario="route")


def level() -> None:
    met = 0
    for user in range(12132, 12138):
        s = _sim(LEVEL.format(d=30 + 10 * (user % 6)), user)
        truth = s.extras["rides"]
        t0, t1 = float(truth["start_s"].iloc[0]), float(truth["end_s"].iloc[0])
        rows = vehicle_rows(foot_only(s))
        cover = [(min(t1, r["end_s"]) - max(t0, r["start_s"])) / (t1 - t0) for r in rows]
        ok = len(rows) == 1 and cover[0] >= 0.8
        met += ok
        print(f"(a) user {user}: ride {t0:.1f}-{t1:.1f} s; vehicle rows "
              + ", ".join(f"{r['start_s']:.1f}-{r['end_s']:.1f} s ({r['vibration_mps2']:.3f} m/s^2, cover {c:.2f})"
                          for r, c in zip(rows, cover, strict=True)) + f" -> {'ok' if ok else 'NOT ok'}")
    print(f"(a) sessions with exactly one vehicle row covering >= 80 % of the ride: {met} / 6")


def freeze() -> None:
    n = 0
    for user in (12138, 12139):
        rows = vehicle_rows(foot_only(_sim(FREEZE, user)))
        n += bool(rows)
        print(f"(b) user {user}: vehicle rows {[(round(r['start_s'], 1), round(r['end_s'], 1)) for r in rows]}")
    print(f"(b) freeze sessions with a vehicle row: {n} / 2")


def real() -> None:
    from pdrlearn.io import read_session

    seen, hot = set(), []
    for root in REAL_DIRS:
        for d in sorted(p.parent for p in root.glob("*/fAccelerometer.csv")):
            if d.name in seen:
                continue
            seen.add(d.name)
            s = read_session(d)
            rows = vehicle_rows(foot_only(s))
            hot += [(d.name, r["start_s"], r["end_s"]) for r in rows]
            print(f"(c) {d}: {len(rows)} vehicle row(s)")
    print(f"(c) {len(seen)} real foot recordings; vehicle rows: {len(hot)} {hot}")


def main() -> None:
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    level()
    freeze()
    real()


if __name__ == "__main__":
    main()
