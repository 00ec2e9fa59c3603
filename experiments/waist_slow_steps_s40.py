"""Decisions W440, W441, W444 (session 40, trial T2): a very slow walk's lower-back step count, against the adoption
rule written in docs/decisions/waist.md before this ran.

W440 (pelvic_rhythm_veto, --veto slow: the second candidate, below 70 steps/min; --veto true: the first, every
cadence, written to waist_slow_steps_s40_true.md): (a) fresh slow walkers, users 10880-10899 (40-70 steps/min,
0.15-0.40 m steps), with the pendulum bounce and the default one: median |count error| lower, median step F1
higher, F1 lower on at most 4 of 40;
(b) fresh normal-speed walkers, users 10880-10889: no step F1 lower by more than 0.01; (c) the real recordings:
`experiments/waist.py --external datasets/external` before and after (not run here).
W441: how often the two-sided pelvic-gyro count line fires (on (a), (b) and the mobgap recordings).
W444: how often the freeze-index hint (W395) fires on the same sessions, none of which freezes.

Run: PYTHONPATH=$PWD python experiments/waist_slow_steps_s40.py [--external datasets/external] [--users 10880-10899]
     [--veto slow|true]
Writes experiments/results/waist_slow_steps_s40.md.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import math
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.steps.evaluate import score_events
from pdrlearn.track.waist import track_waist

ROOT = Path(__file__).resolve().parents[1]
SLOW_ROUTE = [Stand(5), Straight(10), Stand(5)]
NORMAL_ROUTE = [Stand(3), Straight(20), Turn(math.pi), Straight(20), Stand(3)]


def slow_user(u: int, lo: int, hi: int) -> tuple[UserProfile, float, float]:
    """User ``u``'s slow gait: the cadence spread evenly over 40-70 steps/min, the step length over 0.15-0.40 m in
    another order (so the two are not tied)."""
    k = (u - lo) / max(hi - lo, 1)
    cadence = 40.0 + 30.0 * k
    length = 0.15 + 0.25 * (((u - lo) * 7) % (hi - lo + 1)) / max(hi - lo, 1)
    user = UserProfile.from_seed(u)
    f_len, f_time = SPEED_FACTORS["normal"]
    user = dataclasses.replace(user, step_length_m=length / f_len, step_time_s=60.0 / cadence / f_time)
    return user, cadence, length


def truth(session) -> np.ndarray:
    ics = session.extras["ics"]
    ics = ics[ics["kind"] == "walk"] if "kind" in ics else ics
    return ics["ic_s"].to_numpy(float)


def judge(session, ref: np.ndarray | None, veto: bool | str) -> dict:
    r = track_waist(session, pipeline="waist-pendulum", pelvic_rhythm_veto=veto)
    ev = r.steps["event_s"].to_numpy(float)
    w = r.info["warnings"]
    return {"n": len(ev), "f1": None if ref is None else round(score_events(ev, ref)["f1"], 3),
            "gyro": r.info.get("n_pelvic_gyro_steps"),
            "w441": any("decision W441" in x for x in w), "w442": any("decision W442" in x for x in w),
            "freeze_hint": any("decision W395" in x for x in w)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--users", default="10880-10899")
    ap.add_argument("--veto", default="slow", help="the option value measured against false: slow (W440's second "
                    "candidate) or true (its first)")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    veto = True if args.veto == "true" else args.veto
    rows = []

    def add(group, name, session, ref, extra=""):
        off, on = judge(session, ref, False), judge(session, ref, veto)
        rows.append({"group": group, "session": name, "extra": extra, "true": None if ref is None else len(ref),
                     "off": off, "on": on})
        print(rows[-1], flush=True)

    for u in range(lo, hi + 1):
        user, cad, length = slow_user(u, lo, hi)
        for bounce in ("pendulum", "constant"):
            s = simulate_path(SLOW_ROUTE, user, speed="normal", rate_hz=20, seed=u, bounce=bounce)
            add("a slow", f"user {u} {bounce}", s, truth(s), f"{cad:.0f} steps/min, {length:.2f} m")
    for u in range(lo, min(lo + 9, hi) + 1):
        s = simulate_path(NORMAL_ROUTE, UserProfile.from_seed(u), speed="normal", rate_hz=20, seed=u)
        add("b normal", f"user {u}", s, truth(s))
    for d in sorted(args.external.glob("mobgap_*")):
        add("info real", d.name, read_session(d), None)

    def err(r, k):
        return abs(r[k]["n"] - r["true"]) / r["true"] if r["true"] else None

    out = ["# W440 / W441 / W444: a very slow walk's lower-back steps (experiments/waist_slow_steps_s40.py)", "",
           "| group | session | gait | true | n off | F1 off | n on | F1 on | pelvic-gyro | W441 off/on | "
           "W442 off/on | freeze hint off/on |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        f, n = r["off"], r["on"]
        out.append(f"| {r['group']} | {r['session']} | {r['extra']} | {r['true']} | {f['n']} | {f['f1']} | {n['n']} | "
                   f"{n['f1']} | {f['gyro']} | {f['w441']}/{n['w441']} | {f['w442']}/{n['w442']} | "
                   f"{f['freeze_hint']}/{n['freeze_hint']} |")
    a = [r for r in rows if r["group"] == "a slow"]
    b = [r for r in rows if r["group"] == "b normal"]
    med = {k: float(np.median([err(r, k) for r in a])) for k in ("off", "on")}
    f1 = {k: float(np.median([r[k]["f1"] for r in a])) for k in ("off", "on")}
    worse_a = sum(r["on"]["f1"] < r["off"]["f1"] for r in a)
    worse_b = sum(r["on"]["f1"] < r["off"]["f1"] - 0.01 for r in b)
    verdict = [f"(a) median |count error| {100 * med['off']:.1f} % -> {100 * med['on']:.1f} % (rule: lower); median F1 "
               f"{f1['off']:.3f} -> {f1['on']:.3f} (rule: higher); F1 lower on {worse_a} of {len(a)} (rule <= 4)",
               f"(b) F1 lower by more than 0.01 on {worse_b} of {len(b)} (rule 0)"]
    for key, what in (("w441", "W441 line"), ("w442", "W442 line"), ("freeze_hint", "freeze hint (W395)")):
        for g in ("a slow", "b normal", "info real"):
            grp = [r for r in rows if r["group"] == g]
            n_off, n_on = sum(r["off"][key] for r in grp), sum(r["on"][key] for r in grp)
            verdict.append(f"{what} on {g}: veto off {n_off}, on {n_on} of {len(grp)}")
    out += ["", *verdict]
    print("\n".join(verdict))
    out.insert(1, f"pelvic_rhythm_veto: false (off) against {args.veto} (on)")
    name = "waist_slow_steps_s40.md" if args.veto == "slow" else f"waist_slow_steps_s40_{args.veto}.md"
    (ROOT / "experiments" / "results" / name).write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
