"""Decision W100: the walk-ratio warning of an uncalibrated waist track against its adoption rule, written in
docs/decisions/waist.md before this ran. One run, one candidate (WR outside 0.0032-0.0096 m per step/min over
>= 10 steps warns).

(a) short-step walkers with the pendulum bounce, users 500-539: of those read > +50 % long, at least 80 % warned;
(b) normal walkers (slow, normal, fast; constant and pendulum bounce), users 500-539: at most 2 % warned;
(c) the real lower-back recordings (datasets/external and /work/shared/data mobgap_*): none warned.
For information: the short-step pairs with the default constant bounce; the warn rate per pair.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_walk_ratio.py [--users 500-539]
     [--external datasets/external] [--shared /work/shared/data] [--kids 1000-1039] [--out FILE]
W116 (the band relative to stature): --users 1040-1059 --kids 1000-1039
     --out experiments/results/waist_walk_ratio_w116.md
W139 (uncalibrated waist-pll judged on the pendulum's reading of the session): --pipeline waist-pll
     --users 2300-2339 --out experiments/results/waist_walk_ratio_w139.md (the errors are waist-pll's)
Writes experiments/results/waist_walk_ratio.md.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist

ROOT = Path(__file__).resolve().parents[1]
ROUTE = [Stand(3), Straight(14), Stand(3)]
TRUE_M = 14.0
#: (step length m, step time s): the trial's short-step walkers and slow elderly pairs (decision W100)
SHORT = ((0.15, 0.4), (0.1, 0.5), (0.2, 0.45), (0.2, 0.5), (0.25, 0.6), (0.3, 0.75), (0.3, 1.0), (0.4, 0.8))


def judge(session, true_m: float | None = None, pipeline: str = "waist-pendulum") -> dict:
    r = track_waist(session, pipeline=pipeline)
    wr = r.info["walk_ratio"]
    d = float(r.steps["length_m"].abs().sum())
    warned = any("decision W100" in w for w in r.info["warnings"])
    return {"steps": int(len(r.steps)), "dist_m": round(d, 2),
            "err_pct": None if true_m is None else round(100.0 * (d / true_m - 1.0), 1),
            "WR": None if wr is None else round(wr, 5), "warned": warned}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="500-539")
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--shared", type=Path, default=Path("/work/shared/data"))
    ap.add_argument("--kids", default=None, help="W116: also these simulated children (experiments/kid_profiles.py, "
                    "scenario A normal, 100 Hz), e.g. 1000-1039; none by default")
    ap.add_argument("--pipeline", default="waist-pendulum", choices=("waist-pendulum", "waist-pll"),
                    help="the pipeline tracked (W139: waist-pll, judged on the pendulum's reading)")
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "waist_walk_ratio.md")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    rows = []

    def add(group, name, s, true_m=None):
        rows.append({"group": group, "session": name, **judge(s, true_m, args.pipeline)})
        print(rows[-1], flush=True)

    for base in (args.external, args.shared):
        for d in sorted(base.glob("mobgap_*")):
            add("c real", f"{base.name}/{d.name}", read_session(d))
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        for bounce in ("constant", "pendulum"):
            for speed in ("slow", "normal", "fast"):
                add("b normal", f"user {u} {speed} {bounce}",
                    simulate_path(ROUTE, user, speed=speed, rate_hz=100, seed=u, bounce=bounce), TRUE_M)
            for sl, st in SHORT:
                short = dataclasses.replace(user, step_length_m=sl, step_time_s=st)
                group = "a short pendulum" if bounce == "pendulum" else "info short constant"
                add(group, f"user {u} {sl}/{st} {bounce}",
                    simulate_path(ROUTE, short, speed="normal", rate_hz=100, seed=u, bounce=bounce), TRUE_M)
    if args.kids:  # W116: children walking normally (their walk ratio is smaller)
        from kid_profiles import child, child_age, walk
        k0, k1 = (int(x) for x in args.kids.split("-"))
        for u in range(k0, k1 + 1):
            add("d children", f"user {u} age {child_age(u, k0)} A normal", walk(child(u, child_age(u, k0))))
    out = [f"# W100 walk ratio, {args.pipeline} (experiments/waist_walk_ratio.py)", "",
           "| group | session | steps | distance m | error % | WR | warned |", "|---|---|---|---|---|---|---|"]
    out += [f"| {r['group']} | {r['session']} | {r['steps']} | {r['dist_m']} | {r['err_pct']} | {r['WR']} | "
            f"{r['warned']} |" for r in rows]
    a = [r for r in rows if r["group"] == "a short pendulum" and r["err_pct"] > 50.0]
    b = [r for r in rows if r["group"] == "b normal"]
    c = [r for r in rows if r["group"] == "c real"]
    d = [r for r in rows if r["group"] == "d children"]
    info = [r for r in rows if r["group"] == "info short constant" and r["err_pct"] > 50.0]
    verdict = [f"(a) warned {sum(r['warned'] for r in a)} of {len(a)} pendulum-bounce short-step sessions read "
               f"> +50 % long (rule >= 80 %)",
               f"(b) warned {sum(r['warned'] for r in b)} of {len(b)} normal walks (rule <= 2 %)",
               f"(c) warned {sum(r['warned'] for r in c)} of {len(c)} real recordings (rule: none)",
               f"(info) warned {sum(r['warned'] for r in info)} of {len(info)} constant-bounce short-step sessions "
               "read > +50 % long"]
    for sl, st in SHORT:
        for bounce in ("pendulum", "constant"):
            rs = [r for r in rows if r["session"].endswith(f" {sl}/{st} {bounce}")]
            verdict.append(f"(info) {sl} m / {st} s {bounce}: warned {sum(r['warned'] for r in rs)} of {len(rs)}, "
                           f"error {min(r['err_pct'] for r in rs)} to {max(r['err_pct'] for r in rs)} %, WR "
                           f"{min(r['WR'] for r in rs)}-{max(r['WR'] for r in rs)}")
    wr_b = [r["WR"] for r in b if r["WR"] is not None]
    verdict.append(f"(info) normal walks WR {min(wr_b)}-{max(wr_b)}; real WR "
                   f"{min(r['WR'] for r in c)}-{max(r['WR'] for r in c)}")
    if d:
        n_d = sum(r['warned'] for r in d)
        verdict.append(f"(W116 a) warned {n_d} of {len(d)} children's normal walks (rule: none)")
    out += ["", *verdict]
    print("\n".join(verdict))
    args.out.write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
