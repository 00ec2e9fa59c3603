"""Decision W591 (session 51, issue 8): ``slow_min_step`` - the offline lower-back contact detector's shortest step
from the pelvic gyro's median step below 70 steps/min - against the adoption rule written in docs/decisions/waist.md
before this ran (W590 has the trace).

(a) fresh slow shufflers, users 17810-17839 (step 0.2-0.4 m, step time 0.7-1.2 s, `--swing-height 0.06 --bounce
pendulum --bounce-scale 0.5`, `stand:3, straight:12, stand:3`, 50 Hz): median |count error| at least halved, median
step F1 not lower, |count error| larger on at most 3 of 30;
(b) fresh normal walkers, users 17840-17849 (speed normal and slow, `stand:3, straight:20, turn:180, straight:20,
stand:3`, 50 Hz): no F1 lower by more than 0.01, no count changed by more than 1;
(c) the real lower-back recordings (mobgap folders of --external and --shared): every contact identical.
A session whose pelvic gyro gives no W591 shortest step (faster than 70 steps/min or under 10 steps; column "acts"
false) is tracked once: the option cannot change it.

Run: PYTHONPATH=$PWD python experiments/waist_slow_min_step_s51.py [--work /tmp/w591] [--external datasets/external]
     [--shared /work/shared/data]
Writes experiments/results/waist_slow_min_step_s51.md.
"""

from __future__ import annotations

import argparse
import logging
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SHUFFLE = "stand:3, straight:12, stand:3"
NORMAL = "stand:3, straight:20, turn:180, straight:20, stand:3"
SHUFFLERS = range(17810, 17840)
WALKERS = range(17840, 17850)


def shuffler_gait(u: int) -> tuple[float, float]:
    """User ``u``'s shuffle: the step time spread evenly over 0.7-1.2 s, the step length over 0.2-0.4 m in another
    order (so the two are not tied)."""
    k = (u - SHUFFLERS.start) / (len(SHUFFLERS) - 1)
    j = ((u - SHUFFLERS.start) * 7 % len(SHUFFLERS)) / (len(SHUFFLERS) - 1)
    return round(0.2 + 0.2 * j, 3), round(0.7 + 0.5 * k, 3)


def simulated(work: Path, name: str, route: str, u: int, extra: list[str]) -> Path:
    d = work / name
    if not (d / "meta.json").exists():
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--rate", "50",
                        "--user-seed", str(u), "--seed", str(u), "--out", str(d), *extra], check=True,
                       capture_output=True)
    return d


def judge(session, value) -> dict:
    from pdrlearn.steps.evaluate import score_events
    from pdrlearn.track.waist import track_waist

    r = track_waist(session, pipeline="waist-pendulum", slow_min_step=value)
    ev = r.steps["event_s"].to_numpy(float)
    ics = session.extras.get("ics")
    ref = None if ics is None else ics["ic_s"].dropna().to_numpy(float)
    return {"ev": ev, "n": len(ev), "f1": None if ref is None or "kind" not in ics and "wb_id" in ics else
            round(score_events(ev, ref)["f1"], 3), "w442": bool(r.info.get("step_count_unusable"))}


def main() -> None:
    from pdrlearn.io import read_session
    from pdrlearn.waist.pelvic_rhythm import pelvic_steps, slow_shortest_step_s

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", type=Path, default=Path("/tmp/w591"))
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--shared", type=Path, default=Path("/work/shared/data"))
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    rows = []

    def add(group, name, d, gait=""):
        s = read_session(d)
        true = len(s.extras["ics"]) if group != "c real" else None
        off = judge(s, False)
        # the option acts only through W591's shortest step: where the pelvic gyro gives none (faster than 70
        # steps/min, or under 10 steps) the track is the default's by construction, so it is not tracked twice
        slow = slow_shortest_step_s(pelvic_steps(s))
        on = off if slow is None else judge(s, "slow")
        off["acts"] = slow is not None
        rows.append({"group": group, "session": name, "gait": gait, "true": true, "off": off, "on": on})
        print(group, name, gait, "true", true, "off", off["n"], off["f1"], "W442", off["w442"], "slow", on["n"],
              on["f1"], "W442", on["w442"], "acts", off["acts"], flush=True)

    for u in SHUFFLERS:
        sl, st = shuffler_gait(u)
        d = simulated(args.work, f"shuffle_{u}", SHUFFLE, u, ["--step-length", str(sl), "--step-time", str(st),
                                                                "--swing-height", "0.06", "--bounce", "pendulum",
                                                                "--bounce-scale", "0.5"])
        add("a shuffle", f"user {u}", d, f"{sl:.2f} m / {st:.2f} s")
    for u in WALKERS:
        for speed in ("normal", "slow"):
            add("b walk", f"user {u} {speed}", simulated(args.work, f"walk_{u}_{speed}", NORMAL, u, ["--speed", speed]))
    for root in (args.external, args.shared):
        for d in sorted(root.glob("mobgap_*")):
            add("c real", f"{root.name}/{d.name}", d)

    def err(r, k):
        return abs(r[k]["n"] - r["true"]) / r["true"]

    a = [r for r in rows if r["group"] == "a shuffle"]
    b = [r for r in rows if r["group"] == "b walk"]
    c = [r for r in rows if r["group"] == "c real"]
    med = {k: 100 * float(np.median([err(r, k) for r in a])) for k in ("off", "on")}
    f1 = {k: float(np.median([r[k]["f1"] for r in a])) for k in ("off", "on")}
    worse_a = sum(err(r, "on") > err(r, "off") for r in a)
    w442 = {k: sum(r[k]["w442"] for r in a) for k in ("off", "on")}
    worse_b = sum(r["on"]["f1"] < r["off"]["f1"] - 0.01 or abs(r["on"]["n"] - r["off"]["n"]) > 1 for r in b)
    changed_c = [r["session"] for r in c if not np.array_equal(r["off"]["ev"], r["on"]["ev"])]
    ok = (med["on"] <= 0.5 * med["off"] and f1["on"] >= f1["off"] and worse_a <= 3 and worse_b == 0
          and not changed_c)
    verdict = [f"(a) median |count error| {med['off']:.1f} % -> {med['on']:.1f} % (rule: at least halved); median F1 "
               f"{f1['off']:.3f} -> {f1['on']:.3f} (rule: not lower); |count error| larger on {worse_a} of {len(a)} "
               f"(rule <= 3); W442 withheld the count on {w442['off']} -> {w442['on']} of {len(a)}",
               f"(b) F1 lower by more than 0.01 or count changed by more than 1 on {worse_b} of {len(b)} (rule 0)",
               f"(c) real recordings with any contact changed: {len(changed_c)} of {len(c)} {changed_c} (rule 0)",
               f"adoption rule {'met' if ok else 'NOT met'}"]
    out = ["# W591: slow_min_step on slow shufflers, walkers and the real lower backs "
           "(experiments/waist_slow_min_step_s51.py)", "",
           "| group | session | gait | true | n off | F1 off | W442 off | n slow | F1 slow | W442 slow | acts |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        f, n = r["off"], r["on"]
        out.append(f"| {r['group']} | {r['session']} | {r['gait']} | {r['true']} | {f['n']} | {f['f1']} | "
                   f"{f['w442']} | {n['n']} | {n['f1']} | {n['w442']} | {f['acts']} |")
    out += ["", *verdict]
    print("\n".join(verdict))
    (ROOT / "experiments" / "results" / "waist_slow_min_step_s51.md").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
