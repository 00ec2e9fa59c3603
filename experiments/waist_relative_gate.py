"""Decision W76: the session-relative motion gate (`track_waist(..., relative_gate=True)`) against its adoption
rule, written in docs/decisions/waist.md before this ran. One run, one candidate, fresh simulated users 220-239.

(a) normal and slow walks: step count and distance identical to W4's gate;
(b) the slow walks damped as the rehab trial did (dynamic part x0.4 about the 2 s mean, 20 deg forward lean):
    contact F1 >= 0.9 on at least 18 of 20;
(c) very slow walks (0.2 m/s: step 0.2 m in 1.0 s): mean contact F1 not lower than W4's by more than 0.02;
(d) standing-only 30 s sessions of users 220-229: 0 steps;
(e) the 9 mobgap lower-back recordings of datasets/external: step count unchanged.

Run: PYTHONPATH=$PWD python experiments/waist_relative_gate.py [--external datasets/external]
Writes experiments/results/waist_relative_gate.md.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import math
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]
USERS = list(range(220, 240))
ROUTE = [Stand(3), Straight(20), Turn(math.pi), Straight(20), Stand(3)]
DAMP_GAIN, DAMP_LEAN_DEG = 0.4, 20.0  # the rehab trial's rollator walk (damp.py)


def damped(session, gain: float = DAMP_GAIN, lean_deg: float = DAMP_LEAN_DEG):
    """The trial's damp.py on a session in memory: waist acc and gyro = 2 s rolling mean + gain x the rest, then
    a forward lean of the unit (rotation about its x axis: x left, y up, z forward)."""
    out = session.copy()
    a = np.radians(lean_deg)
    rot = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    for name in ("wAccelerometer", "wGyroscope"):
        st = out.streams[name]
        win = max(1, int(round(2.0 * st.rate_hz)))
        lo = pd.DataFrame(st.values).rolling(win, center=True, min_periods=1).mean().to_numpy()
        out.streams[name] = Stream(name, st.t.copy(), (lo + gain * (st.values - lo)) @ rot.T)
    return out


def run(session, relative: bool) -> dict:
    r = track_waist(session, pipeline="waist-pendulum", relative_gate=relative)
    m = step_metrics(r.steps, session) if "ics" in session.extras else {}
    return {"n": int(len(r.steps)), "dist": float(r.steps["length_m"].sum()), "f1": float(m.get("step_f1", 0.0)),
            "thr": float(r.info["walk_threshold_mps2"])}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    rows = []
    for u in USERS:
        user = UserProfile.from_seed(u)
        slow_user = dataclasses.replace(user, step_length_m=0.2 / 0.85, step_time_s=1.0 / 1.2)
        cases = {"normal": simulate_path(ROUTE, user, speed="normal", rate_hz=20, seed=u),
                 "slow": simulate_path(ROUTE, user, speed="slow", rate_hz=20, seed=u)}
        cases["slow_damped"] = damped(cases["slow"])
        cases["vslow_0.2mps"] = simulate_path(ROUTE, slow_user, speed="slow", rate_hz=20, seed=u)
        if u < 230:
            cases["standing"] = simulate_path([Stand(30)], user, speed="normal", rate_hz=20, seed=u)
        for case, s in cases.items():
            w4, cand = run(s, False), run(s, True)
            rows.append({"source": f"user {u}", "case": case,
                         **{f"{k}_w4": v for k, v in w4.items()}, **{f"{k}_cand": v for k, v in cand.items()}})
            print(rows[-1], flush=True)
    for d in sorted(args.external.glob("mobgap_*")):
        s = read_session(d)
        w4, cand = run(s, False), run(s, True)
        rows.append({"source": d.name, "case": "mobgap", **{f"{k}_w4": v for k, v in w4.items()},
                     **{f"{k}_cand": v for k, v in cand.items()}})
        print(rows[-1], flush=True)
    df = pd.DataFrame(rows)
    by = {c: df[df.case == c] for c in df.case.unique()}
    walks = pd.concat([by["normal"], by["slow"]])
    a = bool(((walks.n_w4 == walks.n_cand) & (np.abs(walks.dist_cand - walks.dist_w4) <= 1e-9)).all())
    nb = int((by["slow_damped"].f1_cand >= 0.9).sum())
    b = nb >= 18
    dc = float(by["vslow_0.2mps"].f1_cand.mean() - by["vslow_0.2mps"].f1_w4.mean())
    c = dc >= -0.02
    d = bool((by["standing"].n_cand == 0).all())
    e = bool((by["mobgap"].n_cand == by["mobgap"].n_w4).all()) if "mobgap" in by else False
    lines = ["# W76: session-relative motion gate (candidate) vs W4's 0.5 m/s^2", "",
             "`PYTHONPATH=$PWD python experiments/waist_relative_gate.py`; waist-pendulum offline, default params, "
             "20 Hz, fresh users 220-239; rule in docs/decisions/waist.md W76.", "",
             "| case | sessions | steps W4 | steps cand | mean F1 W4 | mean F1 cand | distance W4 m | distance cand m "
             "| threshold cand (min-max) |", "|---|---|---|---|---|---|---|---|---|"]
    for case, g in by.items():
        lines.append(f"| {case} | {len(g)} | {g.n_w4.sum()} | {g.n_cand.sum()} | {g.f1_w4.mean():.4f} | "
                     f"{g.f1_cand.mean():.4f} | {g.dist_w4.sum():.2f} | {g.dist_cand.sum():.2f} | "
                     f"{g.thr_cand.min():.3f}-{g.thr_cand.max():.3f} |")
    lines += ["", f"- (a) normal + slow walks identical: {a}",
              f"- (b) damped slow walks with F1 >= 0.9: {nb} of {len(by['slow_damped'])} (need 18): {b} "
              f"(W4: {int((by['slow_damped'].f1_w4 >= 0.9).sum())})",
              f"- (c) 0.2 m/s walks mean F1 change {dc:+.4f} (>= -0.02): {c}",
              f"- (d) standing sessions with 0 steps: {int((by['standing'].n_cand == 0).sum())} of "
              f"{len(by['standing'])}: {d}",
              f"- (e) mobgap step counts unchanged: {e}", "",
              f"**Rule {'met: adopt' if all((a, b, c, d, e)) else 'not met: keep as an option'}.**", "",
              "## Per session", "", df.round(4).to_markdown(index=False)]
    out = ROOT / "experiments" / "results" / "waist_relative_gate.md"
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines[:16]))


if __name__ == "__main__":
    main()
