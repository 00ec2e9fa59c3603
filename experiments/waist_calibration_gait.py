"""Decision W140: the calibration-gait warning (a calibrated waist track whose median cadence is outside x0.75-x1.33
of its calibration walks' warns) against its adoption rule, written in docs/decisions/waist.md before this ran.

(a) users 2340-2359 calibrated on one walk, tracked on a second walk (another seed) at the same speed (slow, normal,
    fast; waist-pendulum and waist-pll): at most 2 % warned;
(b) the trial's OFF/ON case (/tmp/trial_clinic/sim off_2511 calibrated with 10 m, tracked on on_2511), both
    pipelines: warned;
(c) each user calibrated on a 0.25 m / 0.4 s shuffle, tracked on the normal walk, both pipelines: >= 80 % warned.
For information: calibrated on normal, tracked on slow and fast.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_calibration_gait.py [--users 2340-2359]
     [--trial /tmp/trial_clinic/sim] [--out experiments/results/waist_calibration_gait.md]
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate

ROOT = Path(__file__).resolve().parents[1]
ROUTE = [Stand(3), Straight(14), Stand(3)]
TRUE_M = 14.0
PIPELINES = ("waist-pendulum", "waist-pll")
SHUFFLE = (0.25, 0.4)  # the trial's OFF walk (m, s)


def judge(params, session, pipeline: str, true_m: float) -> dict:
    r = track_waist(session, pipeline=pipeline, params=params)
    d = float(r.steps["length_m"].abs().sum())
    return {"err_pct": round(100.0 * (d / true_m - 1.0), 1), "cal_spm": (params.gait or {}).get("median_cadence_spm"),
            "warned": any("decision W140" in w for w in r.info["warnings"])}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="2340-2359")
    ap.add_argument("--trial", type=Path, default=Path("/tmp/trial_clinic/sim"))
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "waist_calibration_gait.md")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    rows = []

    def add(group, name, params, session, pipeline, true_m):
        rows.append({"group": group, "session": f"{name} {pipeline}", **judge(params, session, pipeline, true_m)})
        print(rows[-1], flush=True)

    if (args.trial / "off_2511").is_dir():
        off, on = read_session(args.trial / "off_2511"), read_session(args.trial / "on_2511")
        for pipe in PIPELINES:
            add("b trial OFF/ON", "U2511 off->on", calibrate([off], pipe, distances=[10.0]), on, pipe, 20.0)
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        walks = {sp: [simulate_path(ROUTE, user, speed=sp, rate_hz=100, seed=u + k, bounce="pendulum")
                      for k in (0, 1000)] for sp in ("slow", "normal", "fast")}
        shuffle = simulate_path(ROUTE, dataclasses.replace(user, step_length_m=SHUFFLE[0], step_time_s=SHUFFLE[1]),
                                speed="normal", rate_hz=100, seed=u, bounce="pendulum")
        for pipe in PIPELINES:
            cal = {sp: calibrate([w[0]], pipe, distances=[TRUE_M]) for sp, w in walks.items()}
            for sp, w in walks.items():
                add("a same speed", f"user {u} {sp}->{sp}", cal[sp], w[1], pipe, TRUE_M)
            for sp in ("slow", "fast"):
                add("info normal->other", f"user {u} normal->{sp}", cal["normal"], walks[sp][1], pipe, TRUE_M)
            add("c shuffle->normal", f"user {u} shuffle->normal", calibrate([shuffle], pipe, distances=[TRUE_M]),
                walks["normal"][1], pipe, TRUE_M)
    out = ["# W140 calibration gait (experiments/waist_calibration_gait.py)", "",
           "| group | session | error % | calibration spm | warned |", "|---|---|---|---|---|"]
    out += [f"| {r['group']} | {r['session']} | {r['err_pct']} | {r['cal_spm']} | {r['warned']} |" for r in rows]
    verdict = []
    for g, rule in (("a same speed", "rule <= 2 %"), ("b trial OFF/ON", "rule: all"),
                    ("c shuffle->normal", "rule >= 80 %"), ("info normal->other", "information")):
        rs = [r for r in rows if r["group"] == g]
        verdict.append(f"({g}) warned {sum(r['warned'] for r in rs)} of {len(rs)} ({rule})")
        for pipe in PIPELINES:
            rp = [r for r in rs if r["session"].endswith(pipe)]
            if rp:
                verdict.append(f"  {pipe}: warned {sum(r['warned'] for r in rp)} of {len(rp)}, error "
                               f"{min(r['err_pct'] for r in rp)} to {max(r['err_pct'] for r in rp)} %")
    out += ["", *verdict]
    print("\n".join(verdict))
    args.out.write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
