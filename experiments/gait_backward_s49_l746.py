"""Decision L746 (session 49, FG, trial s49t2): does `gait`'s level headline of a walk with a backward item equal the
same walk's without it?

Usage:
    PYTHONPATH=.:experiments .venv/bin/python experiments/gait_backward_s49_l746.py [FIRST_USER N_USERS]

Users 16680-16699 (fresh, session 49). Per user two walks of one seed, both feet simulated at 100 Hz
(:data:`WITH` and :data:`WITHOUT`, the trial's shape: a normal, a short-stride and a long-stride straight, and in
:data:`WITH` a backward item between the first two), tracked as ``gait`` tracks them (offline, L73's toe-off) and the
labels' reference. Prints per user the level stride length left / right of both walks (tracked, reference), the
level steps landing on a backward-labelled contact and the flight line's cause, then L746's rule; writes nothing.
Runs on any tree (main: the "before" numbers).
"""

from __future__ import annotations

import logging
import sys

import numpy as np

from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.bilateral import bilateral_gait, label_steps, offline_foot_track

WITH = ("stand:3, straight:8, stand:5, backward:10, stand:5, straight:6:short, stand:5, straight:10:long, "
        "stand:3")
WITHOUT = "stand:3, straight:8, stand:5, straight:6:short, stand:5, straight:10:long, stand:3"
TOL = 0.03  # L746's rule: within 3 % of the walk without the backward item
NEED = 18  # ... on both sides for at least 18 of 20 users
NEAR_S = 0.15  # a step lands on a labelled contact within this (s)


def backward_ics(labels) -> np.ndarray:
    """The labelled ICs (s) of the backward strides of both feet."""
    out = [lab.loc[lab["direction"].astype(str) == "backward", "ic_s"].to_numpy(float) for lab in labels]
    return np.sort(np.concatenate(out))


def level_on_backward(res: dict, back: np.ndarray) -> int:
    """How many of the headline's steps (the level kind's, or every step on L608's ``all`` basis) land on (or start
    from) a backward-labelled contact."""
    st = res["steps"]
    if not len(back):
        return 0
    if res["walk"].get("headline_steps") == "level":
        st = st[st["kind"] == "level"]
    n = 0
    for col in ("ic_s", "start_s"):
        t = st[col].to_numpy(float)
        n += int((np.min(np.abs(t[:, None] - back[None, :]), axis=1) <= NEAR_S).sum()) if len(t) else 0
    return n


def walk(route: str, u: int) -> tuple[dict, dict, np.ndarray, list[str]]:
    user = UserProfile.from_seed(u)
    sessions = [simulate_path(parse_route(route), user, rate_hz=100.0, seed=u, instrumented_foot=f)
                for f in ("left", "right")]
    labels = [label_steps(s) for s in sessions]
    ref = bilateral_gait(*labels)
    tracks = [offline_foot_track(s, False) for s in sessions]
    res = bilateral_gait(*(t.steps for t in tracks), contact_source="force")
    flights = [w for w in res["warnings"] if "have a flight" in w or "flight" in w.split(":")[0]]
    return res, ref, backward_ics(labels), flights


def stride(res: dict) -> tuple[float, float]:
    w = res["walk"]
    return tuple(np.nan if w[f"stride_length_m_{s}"] is None else w[f"stride_length_m_{s}"] for s in ("left", "right"))


def main() -> None:
    logging.disable(logging.WARNING)
    first, n = (int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else (16680, 20)
    print("user | tracked with L/R | without L/R | ref with L/R | ref without L/R | headline steps on backward "
          "(tracked, ref) | basis | flight line")
    ok_t = ok_r = bad = 0
    diffs_t, diffs_r = [], []
    for u in range(first, first + n):
        rw, fw, back, fl = walk(WITH, u)
        ro, fo, _, _ = walk(WITHOUT, u)
        tw, to, qw, qo = stride(rw), stride(ro), stride(fw), stride(fo)
        dt = [abs(a - b) / b for a, b in zip(tw, to, strict=True)]
        dr = [abs(a - b) / b for a, b in zip(qw, qo, strict=True)]
        diffs_t += dt
        diffs_r += dr
        ok_t += all(d <= TOL for d in dt)
        ok_r += all(d <= TOL for d in dr)
        nb = (level_on_backward(rw, back), level_on_backward(fw, back))
        bad += sum(nb)
        cause = "-" if not fl else ("names backward" if "backward" in fl[0] else "race walking / clock")
        print(f"{u} | {tw[0]:.3f} / {tw[1]:.3f} | {to[0]:.3f} / {to[1]:.3f} | {qw[0]:.3f} / {qw[1]:.3f} | "
              f"{qo[0]:.3f} / {qo[1]:.3f} | {nb[0]}, {nb[1]} | {rw['walk']['headline_steps']} | {cause}", flush=True)
    print(f"tracked: within {TOL:.0%} on both sides for {ok_t} of {n} users (median |diff| "
          f"{100 * np.nanmedian(diffs_t):.2f} %, max {100 * np.nanmax(diffs_t):.2f} %)")
    print(f"reference: within {TOL:.0%} on both sides for {ok_r} of {n} users (median |diff| "
          f"{100 * np.nanmedian(diffs_r):.2f} %, max {100 * np.nanmax(diffs_r):.2f} %)")
    print(f"headline steps on a backward-labelled contact: {bad}")
    passed = ok_t >= NEED * n / 20 and ok_r >= NEED * n / 20 and bad == 0
    print(f"L746 rule (a, b): {'passes' if passed else 'fails'} (need {NEED} of 20 each, 0 backward in the level)")


if __name__ == "__main__":
    main()
