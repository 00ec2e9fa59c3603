"""Decisions L615, L616, L617 (session 43, trial T3 findings F2, F6, F10): the foot track's vehicle rides and the
freezes with no walking next to them, measured against the rules written in docs/decisions/localization.md.

(a) vehicle climbs while standing (S75's ``vehicle:60::RISE``): read as a lift or escalator, with and without the
    foot's vibration (``track_plasys(ride_vibration=...)``);
(b) lifts and escalators (L374's station route, L403's short-lift route): kinds that change with the vibration;
(c) / (f) the real foot recordings (gaitmap): the foot's vibration over each standstill of 3 s or more between two
    strides, and those of 20 s or more reading 0.15 m/s^2 or more (what L616 would call a vehicle);
(e) level vehicle rides (``vehicle:D``): the vehicle rows and how much of the simulated ride each covers;
(g) simulated freezes (``freeze:6``): sessions whose freezes.csv overlaps the simulated freeze, with and without
    L617; (h) trial T3's ``c41`` / ``c41c`` (given with ``--t3``): their episodes with and without L617;
(i) L616 amended: long simulated freezes (``freeze:20-45``), vehicle rows with and without the freeze guard.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/foot_vehicle_l615.py [--t3 /tmp/lead_s43/scratch_T3]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.kernels.pause_ride import VEHICLE_STILL_MIN_S, VEHICLE_VIBRATION_MPS2, ride_vibration
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

CLIMB = "stand:3, straight:10, vehicle:60::{rise}, straight:10, stand:3"
RISES = ("+4", "-4", "+8", "-6")
STATION = ("straight:20, escalator:+6, straight:10, up:17, straight:5, lift:-9, straight:10, stand:30, "
           "straight:10")
SHORT_LIFT = "stand:3, straight:5, lift:+3, stand:2, straight:5, escalator:-3, straight:5"
LEVEL = "stand:5, straight:20, stand:5, vehicle:{d}, stand:3, straight:20, stand:30, straight:10, stand:5"
FREEZE = "stand:3, straight:10, freeze:6, straight:10, stand:3"
LONG_FREEZE = "stand:3, straight:10, freeze:{d}, straight:10, stand:3"
REAL_DIRS = (Path("datasets/real"), Path("datasets/external"), Path("/work/shared/data"))
STILL_MIN_S = 3.0


def _sim(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=100, seed=user,
                         scenario="route")


def _kinds(session, on: bool) -> list[tuple[str, float, float]]:
    """``(kind, vibration, start_s)`` of each ride the foot track reads, with or without the vibration."""
    from pdrlearn.track.plasys import track_plasys

    res = track_plasys(session, ride_vibration=on)
    return [(r["kind"], round(float(r["vibration_mps2"]), 3), round(float(r["start_s"]), 2))
            for r in res.info.get("rides") or []]


def climbs(users) -> None:
    bad = {False: 0, True: 0}
    for u in users:
        s = _sim(CLIMB.format(rise=RISES[u % len(RISES)]), u)
        ks = {on: _kinds(s, on) for on in (False, True)}
        for on in ks:
            bad[on] += any(k[0] in ("lift", "escalator") for k in ks[on])
        print(f"(a) user {u} rise {RISES[u % len(RISES)]}: off {ks[False]}, on {ks[True]}")
    print(f"(a) vehicle climbs read as a lift or escalator: off {bad[False]} / {len(users)}, on {bad[True]} / "
          f"{len(users)}")


def lifts(users) -> None:
    changed = n = 0
    vmax = 0.0
    for k, u in enumerate(users):
        s = _sim(STATION if k < len(users) // 2 else SHORT_LIFT, u)
        off = [r for r in _kinds(s, False) if r[0] in ("lift", "escalator")]
        on = _kinds(s, True)
        on_at = {r[2]: r[0] for r in on}
        n += len(off)
        changed += sum(on_at.get(r[2]) != r[0] for r in off)
        vmax = max([vmax] + [r[1] for r in on])
        print(f"(b) user {u}: off {off}, on {on}")
    print(f"(b) lift / escalator rides whose kind changed: {changed} / {n} (largest foot vibration {vmax:.3f})")


def real() -> None:
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    seen, vib, long_still = set(), [], []
    for root in REAL_DIRS:
        for d in sorted(p.parent for p in root.glob("*/fAccelerometer.csv")):
            if d.name in seen:
                continue
            seen.add(d.name)
            s = read_session(d)
            st = track_plasys(s).steps
            acc = s["fAccelerometer"]
            ends = np.concatenate([[acc.t[0]], st["end_s"].to_numpy(float)])
            starts = np.concatenate([st["start_s"].to_numpy(float), [acc.t[-1]]])
            for a, b in zip(ends, starts, strict=True):
                if b - a >= STILL_MIN_S:
                    v = ride_vibration(acc.t, acc.values, a, b)
                    vib.append(v)
                    if b - a >= VEHICLE_STILL_MIN_S:
                        long_still.append((d.name, a, b, v))
                    print(f"(c) {d.name} still {a:.1f}-{b:.1f} s: foot vibration {v:.3f}")
    vib = np.array(vib, dtype=float)
    print(f"(c) {len(seen)} real foot recordings; standstills >= {STILL_MIN_S:g} s under {VEHICLE_VIBRATION_MPS2:g}: "
          f"{int(np.sum(vib < VEHICLE_VIBRATION_MPS2))} / {len(vib)}"
          + (f" (median {np.nanmedian(vib):.3f}, max {np.nanmax(vib):.3f})" if len(vib) else ""))
    hot = [x for x in long_still if x[3] >= VEHICLE_VIBRATION_MPS2]
    print(f"(f) real standstills >= {VEHICLE_STILL_MIN_S:g} s: {len(long_still)}, reading >= "
          f"{VEHICLE_VIBRATION_MPS2:g}: {len(hot)} {hot}")


def level(users) -> None:
    from pdrlearn.track.plasys import track_plasys

    good = 0
    for u in users:
        s = _sim(LEVEL.format(d=30 + 10 * (u % 10)), u)
        truth = s.extras["rides"]
        t0, t1 = float(truth["start_s"].iloc[0]), float(truth["end_s"].iloc[0])
        rows = [r for r in track_plasys(s).info.get("rides") or [] if r["kind"] == "vehicle"]
        cover = [max(0.0, min(t1, r["end_s"]) - max(t0, r["start_s"])) / (t1 - t0) for r in rows]
        ok = len(rows) == 1 and cover[0] >= 0.8
        good += ok
        print(f"(e) user {u} truth {t0:.1f}-{t1:.1f} s: vehicle rows "
              + "; ".join(f"{r['start_s']:.1f}-{r['end_s']:.1f} s vib {r['vibration_mps2']:.3f} dz {r['dz_m']:+.2f}"
                          f" covers {c:.2f}" for r, c in zip(rows, cover, strict=True)) + f" -> {'ok' if ok else 'NO'}")
    print(f"(e) sessions with exactly one vehicle row covering >= 80 % of the ride: {good} / {len(users)}")


def _episodes(session, steps, rule: bool):
    from pdrlearn.track.freezes import foot_freezes, session_freezes, side_step_freezes

    if rule:
        return foot_freezes(session, "plasys", steps)[0] or []
    return side_step_freezes(session_freezes(session, "plasys"), steps)[0] or []


def _spans(eps) -> list[tuple]:
    return [(e["start_s"], e["end_s"], e["peak_fi"]) for e in eps]


def freeze_hits(sessions, episodes, tag: str, rule_name: str) -> None:
    """For each ``(user, session)`` of ``sessions`` (simulated with one freeze), the foot track's episodes without and
    with a rule (``episodes(session, steps, rule)``) and whether one overlaps the simulated freeze; printed per user
    and in all (also decision L765's (b), experiments/foot_freeze_walked_l765.py)."""
    from pdrlearn.track.plasys import track_plasys

    hit, n = {False: 0, True: 0}, 0
    for u, s in sessions:
        truth = s.extras["freezes"]
        t0, t1 = float(truth["start_s"].iloc[0]), float(truth["end_s"].iloc[0])
        steps = track_plasys(s).steps
        got = {rule: episodes(s, steps, rule) for rule in (False, True)}
        for rule, eps in got.items():
            hit[rule] += any(min(t1, e["end_s"]) > max(t0, e["start_s"]) for e in eps)
        n += 1
        print(f"{tag} user {u} truth {t0:.1f}-{t1:.1f} s: without {_spans(got[False])}, with {_spans(got[True])}")
    print(f"{tag} sessions with an episode on the simulated freeze: without {rule_name} {hit[False]} / {n}, with "
          f"{hit[True]} / {n}")


def freezes(users, t3: Path | None) -> None:
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    freeze_hits(((u, _sim(FREEZE, u)) for u in users), _episodes, "(g)", "L617")
    if t3 is None:
        return
    for name in ("c41", "c41c"):
        s = read_session(t3 / name)
        steps = track_plasys(s).steps
        without, with_ = _spans(_episodes(s, steps, False)), _spans(_episodes(s, steps, True))
        print(f"(h) {name}: without L617 {without}, with {with_}")


def long_freezes(users, t3: Path | None) -> None:
    """(i) L616 amended: vehicle rows on long simulated freezes, with and without the freeze guard."""
    from unittest import mock

    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    bad = {False: 0, True: 0}
    for u in users:
        s = _sim(LONG_FREEZE.format(d=20 + 5 * (u % 6)), u)
        for guard in (False, True):
            with mock.patch("pdrlearn.track.rides.freeze_share", return_value=0.0) if not guard else _nothing():
                rows = [r for r in track_plasys(s).info.get("rides") or [] if r["kind"] == "vehicle"]
            bad[guard] += bool(rows)
            print(f"(i) user {u} freeze {20 + 5 * (u % 6)} s, guard {guard}: "
                  + "; ".join(f"vehicle {r['start_s']:.1f}-{r['end_s']:.1f} s {r['vibration_mps2']:.3f}" for r in rows))
    print(f"(i) sessions with a vehicle row on a freeze: without the guard {bad[False]} / {len(users)}, with "
          f"{bad[True]} / {len(users)}")
    for name in ("s11940", "c41") if t3 is not None else ():
        rows = [r for r in track_plasys(read_session(t3 / name)).info.get("rides") or [] if r["kind"] == "vehicle"]
        print(f"(i) {name}: vehicle rows " + "; ".join(f"{r['start_s']:.1f}-{r['end_s']:.1f} s" for r in rows))


def _nothing():
    import contextlib

    return contextlib.nullcontext()


def _users(text: str) -> list[int]:
    lo, hi = (int(v) for v in text.split("-"))
    return list(range(lo, hi + 1))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--climb-users", type=_users, default="12060-12065")
    ap.add_argument("--ride-users", type=_users, default="12066-12069")
    ap.add_argument("--users", type=_users, default="12060-12069")
    ap.add_argument("--t3", type=Path, default=None, help="trial T3's scratch folder (c41, c41c)")
    ap.add_argument("--freeze-users", type=_users, default="12064-12069")
    ap.add_argument("--parts", default="abcefgi")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    print(f"threshold {VEHICLE_VIBRATION_MPS2} m/s^2, vehicle standstill {VEHICLE_STILL_MIN_S:g} s")
    if "a" in a.parts:
        climbs(a.climb_users)
    if "b" in a.parts:
        lifts(a.ride_users)
    if "c" in a.parts or "f" in a.parts:
        real()
    if "e" in a.parts:
        level(a.users)
    if "g" in a.parts:
        freezes(a.users, a.t3)
    if "i" in a.parts:
        long_freezes(a.freeze_users, a.t3)


if __name__ == "__main__":
    main()
