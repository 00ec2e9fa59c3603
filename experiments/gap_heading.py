"""Decision L91 (docs/decisions/localization.md): the turn over a foot-gyroscope gap bridged by the waist gyroscope,
against L90 alone (the turn over the gap taken as 0), on fresh simulated walks with one injected 1 s gap.

Users 180-199 (fresh), 20 Hz, normal speed, seed 3. Sets: "straight" ("straight:40", the gap at the middle of the
walk), "curve" (TURNING route, the gap at the middle of its first 90 deg curve) and "turn" (the same route, the gap
at the middle of its 180 deg turn). The gap: the fGyroscope samples in (tg, tg + 1] s removed. `pdrlearn track`'s
defaults without a model, offline (heading fused) and streamed (heading auto = the waist gyroscope); final position
error (m, `evaluate_track`). Also checks that each walk's clean copy (no gap) gives identical steps and trajectory
with and without the candidate (rule (c)).

Run: PYTHONPATH=. .venv/bin/python experiments/gap_heading.py [--users 180-199]
(`--arm main` under PYTHONPATH=<main checkout> gives main's numbers, without the keyword: information only)
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

STRAIGHT = "straight:40"
TURNING = "straight:8, curve:90:4, straight:6, turn:180, straight:6, curve:-90:4, straight:8"
GAP_S = 1.0


def _crossing(session, deg: float) -> float:
    """First time (s) the truth heading has turned by ``deg`` from its start."""
    g = session.trajectory
    h = np.degrees(np.unwrap(g["heading_rad"].to_numpy(float)))
    i = int(np.flatnonzero(np.abs(h - h[0]) >= deg)[0])
    return float(g["t"].iloc[i])


def with_gap(session, tg: float, length_s: float = GAP_S):
    """A copy of ``session`` without the fGyroscope samples in (tg, tg + length_s]."""
    s = session.copy()
    g = s.streams["fGyroscope"]
    keep = ~((g.t > tg) & (g.t <= tg + length_s))
    s.streams["fGyroscope"] = Stream("fGyroscope", g.t[keep], g.values[keep])
    return s


def run(session, arm: str, streaming: bool):
    kw = {} if arm == "main" else {"waist_bridge": arm == "L91"}
    return track_plasys(session, streaming=streaming, **kw)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", default="180-199")
    p.add_argument("--arm", default="both", choices=("both", "main"))
    a = p.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    lo, _, hi = a.users.partition("-")
    users = range(int(lo), int(hi or lo) + 1)
    arms = ("L90", "L91") if a.arm == "both" else ("main",)
    res = {}  # (set, mode) -> list of per-arm errors
    clean_identical = [0, 0]
    for u in users:
        user = UserProfile.from_seed(u)
        for route, sets in ((STRAIGHT, ("straight",)), (TURNING, ("curve", "turn"))):
            ses = simulate_path(parse_route(route), user, speed="normal", rate_hz=20.0, seed=3,
                                name=f"gaphead_u{u}", scenario="route")
            st = ses.steps
            for name in sets:
                mid = (0.5 * (float(st["start_s"].iloc[0]) + float(st["end_s"].iloc[-1])) if name == "straight"
                       else _crossing(ses, 45.0 if name == "curve" else 180.0))
                tg = mid - 0.5 * GAP_S
                gs = with_gap(ses, tg)
                for streaming in (False, True):
                    errs = [evaluate_track(run(gs, arm, streaming), gs)["final_position_error_m"] for arm in arms]
                    res.setdefault((name, "streamed" if streaming else "offline"), []).append(errs)
                    print(f"u{u} {name:8s} {'streamed' if streaming else 'offline ':8s} gap at {tg:6.2f} s: "
                          + " / ".join(f"{arm} {e:6.2f}" for arm, e in zip(arms, errs, strict=True)), flush=True)
            if a.arm == "both":
                for streaming in (False, True):
                    r0, r1 = (run(ses, arm, streaming) for arm in arms)
                    same = r0.steps.equals(r1.steps) and r0.trajectory.equals(r1.trajectory)
                    clean_identical[0] += int(same)
                    clean_identical[1] += 1
    print()
    print("| set | mode | walks | mean final position error m (" + " / ".join(arms) + ") | worst increase m |")
    print("|---|---|---|---|---|")
    for (name, mode), rows in res.items():
        e = np.array(rows)
        inc = float((e[:, -1] - e[:, 0]).max()) if e.shape[1] > 1 else float("nan")
        print(f"| {name} | {mode} | {len(e)} | " + " / ".join(f"{v:.2f}" for v in e.mean(axis=0))
              + f" | {inc:.2f} |")
    if a.arm == "both":
        print(f"\nclean copies identical with and without the candidate: {clean_identical[0]} of {clean_identical[1]}")


if __name__ == "__main__":
    main()
