"""Decision C270's measurement (session 53, FE, trial s53t1 finding F1): L416's foot + lower-back step-time
asymmetry of slow asymmetric walkers, as shipped ("before") and with the candidate: each lower-back contact re-timed
to the largest AP-acceleration maximum within 0.1 s of its vertical maximum ("candidate"), in place of waist-ic's
last AP maximum before that vertical maximum (W3), which jumps ~0.16 s early to the previous AP maximum whenever the
filtered vertical maximum lands before the contact's own AP maximum.

Fresh users 20500-20539 (never used before): route stand 3, straight 14, stand 3 (the trial's 10 m walk), 100 Hz,
pendulum bounce, realistic pelvis, variability 1.5, paretic side right, foot unit right; the step time drawn per user
0.6-0.85 s and the step length for a speed 0.5-1.0 m/s (seeded by the user id); step_time_asymmetry 0 for every
fourth user (20500, 20504, ...), else drawn 0.03-0.22. Truth: L416's function on the simulator's true contacts.

Run: PYTHONPATH=. .venv/bin/python experiments/slow_limp_retime_s53_c270.py FIRST_USER LAST_USER (in parts, each
printing its walks), then ``pool OUT1 OUT2 ...``: the summaries over the walks the parts printed.
"""

from __future__ import annotations

import dataclasses
import logging
import sys
import warnings

import numpy as np
from scipy.signal import argrelmax, find_peaks

from pdrlearn import signal as dsp
from pdrlearn.kernels.waist import fir_taps, fir_zero_lag
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.steps.detectors import AccelForceStepDetector
from pdrlearn.steps.waist_ic import WaistICStepDetector
from pdrlearn.track.labelled_asymmetry import labelled_step_asymmetry
from pdrlearn.waist.ahrs import waist_imu


def retimed(session, events: np.ndarray, *, window_s: float = 0.1) -> np.ndarray:
    """The candidate: each waist-ic contact at the largest AP maximum within ``window_s`` of the first vertical
    maximum (2.5 Hz zero-lag FIR, seed 003 sec. 3.1) at or after it (within 0.3 s); unchanged without one."""
    imu = waist_imu(session)
    fs = imu.fs
    vf = fir_zero_lag(imu.acc_v - np.mean(imu.acc_v), fir_taps(2.5, fs, int(round(0.3 * fs))))  # seed 003 sec. 3.1
    ap = dsp.lowpass(imu.acc_ap, min(20.0, 0.4 * fs), fs)  # as contacts_offline's AP
    vp, am = find_peaks(vf)[0], argrelmax(ap)[0]
    out = []
    for e in events:
        i = int(round((e - imu.t[0]) * fs))
        nxt = vp[(vp >= i) & (vp <= i + int(0.3 * fs))]
        c = am[np.abs(am - nxt[0]) <= int(window_s * fs)] if len(nxt) else am[:0]
        out.append(imu.t[c[np.argmax(ap[c])]] if len(c) else e)
    return np.asarray(out)


def walk(uid: int) -> dict:
    rng = np.random.default_rng(uid)
    step_s = float(rng.uniform(0.6, 0.85))
    speed = float(rng.uniform(0.5, 1.0))
    a = 0.0 if uid % 4 == 0 else float(rng.uniform(0.03, 0.22))
    user = UserProfile.from_seed(uid)
    user = dataclasses.replace(user, step_length_m=speed * step_s, step_time_s=step_s,
                               class_step_length_m=user.step_length_m)
    s = simulate_path([Stand(3), Straight(14), Stand(3)], user, speed="normal", rate_hz=100, seed=uid,
                      bounce="pendulum", pelvis="realistic", variability=1.5, step_time_asymmetry=a,
                      paretic_side="right")
    ics = s.extras["ics"]
    t = ics["ic_s"].to_numpy(float)
    feet = ics["foot"].to_numpy()
    truth = labelled_step_asymmetry(t[feet == "right"], t, min_strides=2)["step_time_asymmetry_pct"]
    foot = AccelForceStepDetector().detect(s)["event_s"].to_numpy(float)  # = the plasys track's event_s
    waist = WaistICStepDetector().detect(s)["event_s"].to_numpy(float)
    before = labelled_step_asymmetry(foot, waist)
    cand = labelled_step_asymmetry(foot, retimed(s, waist))
    return {"uid": uid, "a": a, "step": step_s, "speed": speed, "truth": truth,
            "before": before["step_time_asymmetry_pct"], "cand": cand["step_time_asymmetry_pct"],
            "se_before": before["standard_error_points"], "n": before["n_strides"]}


def _fmt(v) -> str:
    return "-" if v is None else f"{v:5.2f}"


def _num(text: str) -> float | None:
    return None if text == "-" else float(text)


def summary(rows: list[dict], key: str) -> str:
    err = np.array([np.nan if r[key] is None else r[key] - r["truth"] for r in rows])
    ok = np.isfinite(err)
    sym = np.array([r["a"] == 0 for r in rows])
    est_sym = np.array([r[key] for r in rows if r["a"] == 0 and r[key] is not None], dtype=float)
    return (f"{key}: {int(ok.sum())} of {len(rows)} given, median |error| {np.median(np.abs(err[ok])):.2f} points, "
            f"median signed error {np.median(err[ok]):+.2f}, symmetric walkers' median index "
            f"{np.median(est_sym) if len(est_sym) else float('nan'):.2f} % ({len(est_sym)} of {int(sym.sum())} given)")


def main(users) -> None:
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")
    rows = []
    for uid in users:
        r = walk(uid)
        rows.append(r)
        print(f"user {uid} step {r['step']:.2f} s speed {r['speed']:.2f} m/s A {r['a']:.3f}: truth {r['truth']:5.2f} "
              f"% before {_fmt(r['before'])} candidate {_fmt(r['cand'])} (n {r['n']}, SE {r['se_before']:.1f})",
              flush=True)
    print(summary(rows, "before"), flush=True)
    print(summary(rows, "cand"), flush=True)


def pool(paths) -> None:
    """The summaries over the walks printed by parts of ``main`` (their output files ``paths``)."""
    import re

    pat = re.compile(r"user (\d+) .* A ([\d.]+): truth +([\d.]+) % before +(\S+) candidate +(\S+) ")
    rows = []
    for p in paths:
        for line in open(p):
            if m := pat.match(line):
                rows.append({"uid": int(m[1]), "a": float(m[2]), "truth": float(m[3]), "before": _num(m[4]),
                             "cand": _num(m[5])})
    print(f"pooled {len(rows)} walks (users {min(r['uid'] for r in rows)}-{max(r['uid'] for r in rows)})")
    print(summary(rows, "before"))
    print(summary(rows, "cand"))


if __name__ == "__main__":
    if sys.argv[1] == "pool":
        pool(sys.argv[2:])
    else:
        main(range(int(sys.argv[1]), int(sys.argv[2]) + 1))
