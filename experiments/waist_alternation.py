"""Decision W98: the waist left/right alternation index against its adoption rule, written in
docs/decisions/waist.md before this ran. One run, one candidate (A < 0.5 over >= 10 pairs warns).

(a) fresh normal-speed walkers, users 460-479 at 20 and 100 Hz, plus the 9 mobgap lower-back recordings:
    at most 1 warned session of 49;
(b) the trial's wheelchair sessions with >= 10 step pairs: all warned;
(c) the trial's doubled-step walker (v_0.15_1.5) and its calibration walk (cal411): both warned.
For information: the trial's cane and slow sessions, slow-speed walks of users 460-479 at 100 Hz.

Run: PYTHONPATH=$PWD python experiments/waist_alternation.py [--external datasets/external]
     [--trial /tmp/trial_aids/simw] [--users 460-479]
Writes experiments/results/waist_alternation.md.
"""

from __future__ import annotations

import argparse
import logging
import math
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.plausibility import ALTERNATION_MIN, PLAUSIBILITY_MIN_PAIRS

ROOT = Path(__file__).resolve().parents[1]
ROUTE = [Stand(3), Straight(20), Turn(math.pi), Straight(20), Stand(3)]


def judge(session) -> dict:
    r = track_waist(session, pipeline="waist-pendulum")
    a, pairs = r.info["alternation_index"], r.info["alternation_pairs"]
    warned = a is not None and pairs >= PLAUSIBILITY_MIN_PAIRS and a < ALTERNATION_MIN
    return {"steps": int(len(r.steps)), "dist_m": round(float(r.steps["length_m"].sum()), 2),
            "A": None if a is None else round(a, 3), "pairs": pairs, "warned": warned}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--trial", type=Path, default=Path("/tmp/trial_aids/simw"))
    ap.add_argument("--users", default="460-479")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    rows = []

    def add(group, name, s):
        rows.append({"group": group, "session": name, **judge(s)})
        print(rows[-1], flush=True)

    for d in sorted(args.trial.glob("*")):
        group = ("b wheelchair" if d.name.startswith(("wc_", "wheel")) else
                 "c doubled" if d.name in ("v_0.15_1.5", "cal411") else "info trial")
        add(group, d.name, read_session(d))
    for d in sorted(args.external.glob("mobgap_*")):
        add("a real", d.name, read_session(d))
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        for rate in (20, 100):
            add("a sim normal", f"user {u} {rate} Hz", simulate_path(ROUTE, user, speed="normal", rate_hz=rate, seed=u))
        add("info sim slow", f"user {u} 100 Hz", simulate_path(ROUTE, user, speed="slow", rate_hz=100, seed=u))
    out = ["# W98 alternation index (experiments/waist_alternation.py)", "",
           "| group | session | steps | distance m | A | pairs | warned |", "|---|---|---|---|---|---|---|"]
    out += [f"| {r['group']} | {r['session']} | {r['steps']} | {r['dist_m']} | {r['A']} | {r['pairs']} | "
            f"{r['warned']} |" for r in rows]
    a = [r for r in rows if r["group"].startswith("a ")]
    b = [r for r in rows if r["group"].startswith("b ") and r["pairs"] >= PLAUSIBILITY_MIN_PAIRS]
    c = [r for r in rows if r["group"].startswith("c ")]
    verdict = [f"(a) warned {sum(r['warned'] for r in a)} of {len(a)} (rule <= 1)",
               f"(b) warned {sum(r['warned'] for r in b)} of {len(b)} wheelchair sessions with >= "
               f"{PLAUSIBILITY_MIN_PAIRS} pairs (rule: all)",
               f"(c) warned {sum(r['warned'] for r in c)} of {len(c)} (rule: all)"]
    out += ["", *verdict]
    print("\n".join(verdict))
    res = ROOT / "experiments" / "results" / "waist_alternation.md"
    res.write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
