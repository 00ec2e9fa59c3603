"""Decision W211: the calibration-speed warning (a calibrated waist track whose median cadence is more than 10 %
outside its calibration walks' cadence range warns) against its adoption rule, written in docs/decisions/waist.md
before this ran.

Fresh users 4940-4969, 20 m walkways (stand 2 s, straight 20 m, stand 2 s), 100 Hz, pendulum bounce, the trial's
step length 0.42 + 0.3 (v - 0.6) m and step time = length / v; waist-pendulum calibrated (--distance 20) on the
user's 1.0 m/s walk (seed = user):
(a) the 1.0 m/s walk with seed user + 1000: >= 95 % NOT warned;
(b) the 0.6 and 2.0 m/s walks (seed user + 1000): >= 95 % warned.
For information: calibrated on 0.6 + 1.0 + 2.0 m/s, tracked on 1.4 m/s.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_calibration_speed.py [--users 4940-4969]
     [--out experiments/results/waist_calibration_speed.md]
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate

ROOT = Path(__file__).resolve().parents[1]
ROUTE = [Stand(2), Straight(20), Stand(2)]
TRUE_M = 20.0
PIPELINE = "waist-pendulum"
SPEEDS = (0.6, 1.0, 1.4, 2.0)


def walk(user: UserProfile, v: float, seed: int):
    length = 0.42 + 0.3 * (v - 0.6)  # the trial's sweep (trial_lab.md)
    u = dataclasses.replace(user, step_length_m=length, step_time_s=length / v)
    return simulate_path(ROUTE, u, speed="normal", rate_hz=100, seed=seed, bounce="pendulum")


def judge(params, session) -> dict:
    r = track_waist(session, pipeline=PIPELINE, params=params, speed_check=True)
    d = float(r.steps["length_m"].abs().sum())
    return {"err_pct": round(100.0 * (d / TRUE_M - 1.0), 2), "ratio": r.info["calibration_cadence_ratio"],
            "warned": any("decision W211" in w for w in r.info["warnings"])}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="4940-4969")
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "waist_calibration_speed.md")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    rows = []
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        test = {v: walk(user, v, u + 1000) for v in SPEEDS}
        cal1 = calibrate([walk(user, 1.0, u)], PIPELINE, distances=[TRUE_M])
        for v, group in ((1.0, "a same speed"), (0.6, "b other speed"), (2.0, "b other speed")):
            rows.append({"group": group, "session": f"user {u} 1.0->{v}", **judge(cal1, test[v])})
            print(rows[-1], flush=True)
        multi = calibrate([walk(user, v, u) for v in (0.6, 1.0, 2.0)], PIPELINE, distances=[TRUE_M] * 3)
        rows.append({"group": "info multi-speed", "session": f"user {u} 0.6+1.0+2.0->1.4", **judge(multi, test[1.4])})
        print(rows[-1], flush=True)
    out = ["# W211 calibration speed (experiments/waist_calibration_speed.py)", "",
           "| group | session | error % | cadence ratio | warned |", "|---|---|---|---|---|"]
    out += [f"| {r['group']} | {r['session']} | {r['err_pct']} | {r['ratio'] and round(r['ratio'], 3)} | "
            f"{r['warned']} |" for r in rows]
    verdict = []
    for g, rule in (("a same speed", "rule: >= 95 % not warned"), ("b other speed", "rule: >= 95 % warned"),
                    ("info multi-speed", "information")):
        rs = [r for r in rows if r["group"] == g]
        verdict.append(f"({g}) warned {sum(r['warned'] for r in rs)} of {len(rs)} ({rule}); error "
                       f"{min(r['err_pct'] for r in rs)} to {max(r['err_pct'] for r in rs)} %")
    out += ["", *verdict]
    print("\n".join(verdict))
    args.out.write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
