"""Decisions L692 and L693 (session 46, trial T2 findings F3, F4): backward steps taken while turning, and the false
freeze after box steps, measured against the rules written in docs/decisions/localization.md.

(a) L692: T2's waltz figure on users 14440-14459 (20 Hz, seed = user): the truth-backward strides the track counts
    ``backward_travel``, the strides counted backward whose truth is not backward, and L578's on-the-spot strides;
    (b) L692: a straight backward / box session on the same users: ``n_backward_strides``, ``n_side_strides`` and
    the distance per user; (c) L693: T2's box route on users 14460-14479 (100 Hz): the sessions keeping an episode;
    (d) L693: simulated freezes (users 14470-14479): the sessions whose freezes.csv overlaps the truth freeze.
Run it with main's code on the path and with the branch's to compare.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/dance_travel_s46.py [a b c d]
"""

from __future__ import annotations

import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

WALTZ = ("stand:3, straight:2, curve:135:0.6, backward:3:direct, curve:-135:0.6, straight:2, curve:-135:0.6, "
         "backward:3:direct, curve:135:0.6, straight:2, stand:3")
STRAIGHT = "stand:3, straight:3, backward:4, side:1, backward:2, side:-1, straight:2, stand:3"
BOX = ("stand:3, straight:1.2, side:0.8, backward:2, side:-0.8, straight:1.2, side:0.8, backward:2, side:-0.8, "
       "stand:3")
FREEZES = {range(14470, 14475): "straight:4, freeze:6:5:8, straight:4",
           range(14475, 14480): "side:3, freeze:6:5:8, straight:4"}


def _sim(route: str, user: int, rate: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=rate, seed=user, scenario="route")


def _track(session):
    from pdrlearn.track.plasys import track_plasys

    return track_plasys(session)


def _truth_kind(steps, truth) -> np.ndarray:
    """Each tracked stride's truth ``direction`` (the truth stride it overlaps most)."""
    a, b = truth["start_s"].to_numpy(float), truth["end_s"].to_numpy(float)
    out = []
    for s0, s1 in zip(steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float), strict=True):
        ov = np.minimum(b, s1) - np.maximum(a, s0)
        out.append(str(truth["direction"].iloc[int(np.argmax(ov))]) if ov.max() > 0 else "")
    return np.asarray(out, dtype=object)


def waltz() -> None:
    from pdrlearn.track.evaluate import backward_travel
    from pdrlearn.track.travel import travel_labels

    hit = truth_back = false_back = spot = 0
    for u in range(14440, 14460):
        s = _sim(WALTZ, u, 20)
        st = _track(s).steps
        kind = _truth_kind(st, s.steps)
        back = np.asarray(backward_travel(st), bool)
        truly = kind == "backward"
        h, t, f = int((back & truly).sum()), int(truly.sum()), int((back & ~truly).sum())
        n_spot = int((travel_labels(st) == "turn").sum())
        hit, truth_back, false_back, spot = hit + h, truth_back + t, false_back + f, spot + n_spot
        print(f"(a) user {u}: truth-backward {h}/{t} counted backward, {f} counted backward not truth-backward, "
              f"{n_spot} travel turn")
    print(f"(a) all: {hit}/{truth_back} truth-backward strides counted backward, {false_back} false, "
          f"{spot} travel turn")


def straight() -> None:
    from pdrlearn.track.evaluate import backward_travel
    from pdrlearn.track.gait import sideways_rows

    for u in range(14440, 14460):
        st = _track(_sim(STRAIGHT, u, 20)).steps
        print(f"(b) user {u}: backward strides {int(np.sum(backward_travel(st)))} side strides "
              f"{int(np.sum(sideways_rows(st)))} distance_m {float(np.abs(st['length_m']).sum()):.3f}")


def _episodes(session) -> list[dict]:
    """The foot track's freeze episodes as ``pdrlearn track`` writes them (W213, L413, L617, L693)."""
    from pdrlearn.track.freezes import foot_freezes

    r = _track(session)
    return foot_freezes(session, r.info.get("pipeline"), r.steps)[0] or []


def box() -> None:
    kept = 0
    for u in range(14460, 14480):
        eps = _episodes(_sim(BOX, u, 100))
        kept += bool(eps)
        print(f"(c) user {u}: {len(eps)} episode(s) {[(e['start_s'], e['end_s']) for e in eps]}")
    print(f"(c) all: {kept} of 20 box sessions keep an episode")


def freezes() -> None:
    for users, route in FREEZES.items():
        n = 0
        for u in users:
            s = _sim(route, u, 100)
            eps = _episodes(s)
            truth = s.extras.get("freezes")
            if truth is None or not len(truth):
                print(f"(d) user {u}: no truth freeze")
                continue
            t0, t1 = float(truth["start_s"].min()), float(truth["end_s"].max())
            over = any(min(t1, e["end_s"]) > max(t0, e["start_s"]) for e in eps)
            n += over
            print(f"(d) user {u} [{route}]: {len(eps)} episode(s), overlaps the truth freeze {t0:.2f}-{t1:.2f}: {over}")
        print(f"(d) {route}: {n} of {len(users)} sessions find the freeze")


def main() -> None:
    logging.disable(logging.WARNING)
    parts = sys.argv[1:] or ["a", "b", "c", "d"]
    for p, f in (("a", waltz), ("b", straight), ("c", box), ("d", freezes)):
        if p in parts:
            f()


if __name__ == "__main__":
    main()
