"""Decision L677's measurement (session 45): L416's foot + lower-back step-time asymmetry with L490's standard error
(the other foot's phases only) and L677's (the lower back's lag too), on slow walkers (users 12900-12909, 0.3 m /
0.9 s steps, 40 m straight or with ``slow100`` 100 m, A 0 / 0.15) and on L416's own walks (users 8044-8055, 60 m,
normal, A 0 / 0.05 / 0.15).

Run: PYTHONPATH=. .venv/bin/python experiments/slow_asymmetry_s45.py [slow|slow100|l416]
"""

from __future__ import annotations

import dataclasses
import logging
import sys
import warnings

import numpy as np

from labelled_asymmetry_s34 import walk_contacts
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.labelled_asymmetry import (
    UNCERTAIN_SE_POINTS,
    index_standard_error_pct,
    labelled_step_asymmetry,
    other_foot_phases,
)

SLOW_USERS = range(12900, 12910)
L416_USERS = range(8044, 8056)


def walk(uid: int, a: float, slow: bool, length_m: float = 40.0) -> dict:
    """One walk's truth, index, the old (phases only, L490) and new (L677) standard errors."""
    user = UserProfile.from_seed(uid)
    if slow:
        user = dataclasses.replace(user, step_length_m=0.3, step_time_s=0.9)
        s = simulate_path([Stand(3), Straight(length_m), Stand(3)], user, speed="normal", rate_hz=100, seed=uid,
                          bounce="pendulum", rocker="smooth", step_time_asymmetry=a)
    else:  # L416's own walks (experiments/labelled_asymmetry_s34.py)
        s = simulate_path([Stand(3), Straight(60), Stand(3)], user, speed="normal", rate_hz=100, seed=uid,
                          bounce="pendulum", step_time_asymmetry=a)
    truth, foot, waist = walk_contacts(s)
    est = labelled_step_asymmetry(foot, waist)
    return {"truth": truth, "est": est["step_time_asymmetry_pct"], "n": est["n_strides"],
            "se_old": index_standard_error_pct(other_foot_phases(foot, waist)), "se_new": est["standard_error_points"]}


def main(which: str) -> None:
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")
    slow = which.startswith("slow")
    length = 100.0 if which == "slow100" else 40.0  # L677's second rule: 100 m walks
    runs = [(u, a) for u in (SLOW_USERS if slow else L416_USERS) for a in ((0.0, 0.15) if slow else (0.0, 0.05, 0.15))]
    errs, bare_old, bare_new, note_old, note_new = [], 0, 0, 0, 0
    for uid, a in runs:
        r = walk(uid, a, slow, length)
        err = np.nan if r["est"] is None else r["est"] - r["truth"]
        errs.append(err)
        if r["est"] is not None:
            note_old += r["se_old"] > UNCERTAIN_SE_POINTS
            note_new += r["se_new"] > UNCERTAIN_SE_POINTS
            bare_old += abs(err) > 6.0 and r["se_old"] <= UNCERTAIN_SE_POINTS
            bare_new += abs(err) > 6.0 and r["se_new"] <= UNCERTAIN_SE_POINTS
        print(f"user {uid} A {a:.2f}: truth {r['truth']:5.2f} % estimate "
              f"{'-' if r['est'] is None else format(r['est'], '5.2f')} % ({r['n']} strides) error {err:+.2f} "
              f"SE old {r['se_old']:.2f} new {r['se_new']:.2f}", flush=True)
    e = np.asarray(errs)
    ok = np.isfinite(e)
    print(f"{which}: median |error| {np.median(np.abs(e[ok])):.2f} points, within 3.0 points "
          f"{int((np.abs(e[ok]) <= 3.0).sum())} of {len(e)}, mean signed error {np.mean(e[ok]):+.2f}, no estimate "
          f"{int((~ok).sum())}; noted uncertain (SE > {UNCERTAIN_SE_POINTS:g}) old {note_old} new {note_new}; "
          f"over 6 points off without the note: old {bare_old} new {bare_new}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "slow")
