"""Decision W531's measurement (session 47): L416's foot + lower-back step-time asymmetry with the labelling window
about the foot contact (L416, old) and centred on the lower back's lag (W531, new), on the same contacts.

``sim KIND DIR``: simulate KIND's walks and keep each walk's contacts (truth index, foot unit's and lower back's
contacts) in DIR/KIND_USER_A.npz. ``eval KIND DIR``: the index of each kept walk with the code on PYTHONPATH
(main's = old, this branch's = new), whether it is called asymmetric (index over :data:`CALLED_PCT` and over 2
standard errors) and the summary line. KIND: ``children`` (fresh users 14940-14959, symmetric, 0.34-0.45 s steps,
heights 1.15-1.45 m, 2 x 30 m corridor), ``l416`` (L416's users 8044-8055, 60 m, A 0 / 0.05 / 0.15), ``own`` (L686's
users 14220-14239, their own gait, A 0.25, L686's route).

Run: PYTHONPATH=. python experiments/child_asymmetry_s47_w531.py sim children /tmp/w531
     PYTHONPATH=/work/main python experiments/child_asymmetry_s47_w531.py eval children /tmp/w531   (old)
     PYTHONPATH=. python experiments/child_asymmetry_s47_w531.py eval children /tmp/w531             (new)
"""

from __future__ import annotations

import dataclasses
import logging
import sys
import warnings
from pathlib import Path

import numpy as np

#: decision W531's "called asymmetric": the index over this (%; trial T1: 3-5 % is clinically meaningful in a CP
#: clinic) and over 2 of its standard errors
CALLED_PCT = 3.0
CHILD_USERS = range(14940, 14960)
HEIGHTS_M = (1.15, 1.25, 1.35, 1.45)


def _child(uid: int):
    from pdrlearn.sim import UserProfile

    i = uid - CHILD_USERS.start
    h = HEIGHTS_M[i % len(HEIGHTS_M)]
    user = UserProfile.from_seed(uid).scaled(h, 0.52 * h)
    st = 0.34 + 0.11 * (i % 10) / 9.0  # 0.34-0.45 s steps (docs/simulator.md "Children": 0.36-0.45 s)
    return dataclasses.replace(user, step_length_m=0.33 * h, step_time_s=st, class_step_length_m=user.step_length_m)


def walks(kind: str):
    """(uid, A) of KIND's walks."""
    if kind == "children":
        return [(u, 0.0) for u in CHILD_USERS]
    if kind == "l416":
        return [(u, a) for u in range(8044, 8056) for a in (0.0, 0.05, 0.15)]
    return [(u, 0.25) for u in range(14220, 14240)]


def simulate(kind: str, uid: int, a: float):
    from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path

    if kind == "children":
        return simulate_path([Stand(3), Straight(30), Turn(np.pi), Straight(30), Stand(3)], _child(uid),
                             speed="normal", rate_hz=100, seed=uid, bounce="pendulum")
    if kind == "l416":  # experiments/labelled_asymmetry_s34.py
        return simulate_path([Stand(3), Straight(60), Stand(3)], UserProfile.from_seed(uid), speed="normal",
                             rate_hz=100, seed=uid, bounce="pendulum", step_time_asymmetry=a)
    # experiments/limp_asymmetry_s46.py "own"
    return simulate_path([Stand(3), Straight(40), Turn(np.pi), Straight(40), Stand(3)], UserProfile.from_seed(uid),
                         speed="normal", rate_hz=100, seed=uid, bounce="pendulum", step_time_asymmetry=a,
                         paretic_side="right" if uid % 2 == 0 else "left")


def sim(kind: str, out: Path) -> None:
    from labelled_asymmetry_s34 import walk_contacts

    out.mkdir(parents=True, exist_ok=True)
    for uid, a in walks(kind):
        path = out / f"{kind}_{uid}_{a:.2f}.npz"
        if path.exists():
            continue
        truth, foot, waist = walk_contacts(simulate(kind, uid, a))
        np.savez(path, truth=truth, foot=foot, waist=waist)
        print(f"kept {path.name}: truth {truth:.2f} %", flush=True)


def evaluate(kind: str, out: Path) -> None:
    from pdrlearn.track.labelled_asymmetry import labelled_step_asymmetry

    errs, called, called_true, given = [], 0, 0, 0
    for uid, a in walks(kind):
        z = np.load(out / f"{kind}_{uid}_{a:.2f}.npz")
        truth = float(z["truth"])
        r = labelled_step_asymmetry(z["foot"], z["waist"])
        est, se = r["step_time_asymmetry_pct"], r["standard_error_points"]
        step = float(np.median(np.diff(np.sort(z["foot"])))) / 2.0
        if est is None:
            print(f"user {uid} A {a:.2f} step {step:.3f} s: truth {truth:5.2f} % no index", flush=True)
            continue
        given += 1
        call = est > CALLED_PCT and est > 2.0 * se
        called += call
        called_true += truth > CALLED_PCT
        errs.append(est - truth)
        print(f"user {uid} A {a:.2f} step {step:.3f} s: truth {truth:5.2f} % estimate {est:5.2f} % standard error "
              f"{se:.2f} ({r['n_strides']} strides) error {est - truth:+.2f}{' CALLED' if call else ''}", flush=True)
    e = np.asarray(errs)
    print(f"{kind}: {given} of {len(walks(kind))} given, median |error| {np.median(np.abs(e)):.2f} points, within 3.0 "
          f"points {int((np.abs(e) <= 3.0).sum())}, mean signed error {np.mean(e):+.2f}; called asymmetric (over "
          f"{CALLED_PCT:g} % and 2 standard errors) {called}, truth over {CALLED_PCT:g} % {called_true}", flush=True)


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")
    sys.path.insert(0, str(Path(__file__).parent))
    what, kind, folder = sys.argv[1:4]
    (sim if what == "sim" else evaluate)(kind, Path(folder))
