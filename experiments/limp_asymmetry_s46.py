"""Decision L686's measurement (session 46): L416's foot + lower-back step-time asymmetry of slow limping walkers,
with L677's standard error (old) and L686's (the bias allowance added in quadrature, new). Fresh users 14220-14239:
stand 3, straight 40, turn 180, straight 40, stand 3; steps of 0.5 x the step time (m) at 0.6 / 0.7 / 0.8 s, A 0.15 /
0.25 (``slow``: 120 walks) or the user's own gait, A 0.25 (``own``: 20 walks); paretic side right for even users,
left for odd; foot unit right; 100 Hz, pendulum bounce. Truth: the function on the simulator's contacts (L416).

Run: .venv/bin/python experiments/limp_asymmetry_s46.py [slow|own] [FIRST_USER LAST_USER]
"""

from __future__ import annotations

import dataclasses
import logging
import sys
import warnings

import numpy as np

from labelled_asymmetry_s34 import walk_contacts
from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path
from pdrlearn.track.labelled_asymmetry import (
    UNCERTAIN_SE_POINTS,
    _phases_and_lags,
    index_standard_error_pct,
    labelled_step_asymmetry,
)

USERS = range(14220, 14240)
STEP_TIMES_S = (0.6, 0.7, 0.8)
OFF_POINTS = 6.0  # L677's "more than 6 points off"


def walk(uid: int, step_s: float | None, a: float) -> dict:
    """One walk: truth, index, the old (L677) and new (L686) standard errors, the foot's median step."""
    user = UserProfile.from_seed(uid)
    if step_s is not None:  # as `simulate --step-length --step-time` (S30, S81)
        user = dataclasses.replace(user, step_length_m=0.5 * step_s, step_time_s=step_s,
                                   class_step_length_m=user.step_length_m)
    s = simulate_path([Stand(3), Straight(40), Turn(np.pi), Straight(40), Stand(3)], user, speed="normal",
                      rate_hz=100, seed=uid, bounce="pendulum", step_time_asymmetry=a,
                      paretic_side="right" if uid % 2 == 0 else "left")
    truth, foot, waist = walk_contacts(s)
    est = labelled_step_asymmetry(foot, waist)
    phases, lags = _phases_and_lags(foot, waist, tolerance_steps=0.25)
    stride = float(np.median(np.diff(np.sort(foot))))
    return {"truth": truth, "est": est["step_time_asymmetry_pct"], "se_old": index_standard_error_pct(phases, lags,
            stride), "se_new": est["standard_error_points"], "step": stride / 2.0, "n": est["n_strides"]}


def main(which: str, users) -> None:
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")
    runs = [(u, st, a) for u in users for st in STEP_TIMES_S for a in (0.15, 0.25)] if which == "slow" \
        else [(u, None, 0.25) for u in users]
    errs, bare_old, bare_new, note_old, note_new, within2 = [], 0, 0, 0, 0, 0
    for uid, st, a in runs:
        r = walk(uid, st, a)
        err = np.nan if r["est"] is None else r["est"] - r["truth"]
        errs.append(err)
        if r["est"] is not None:
            note_old += r["se_old"] > UNCERTAIN_SE_POINTS
            note_new += r["se_new"] > UNCERTAIN_SE_POINTS
            bare_old += abs(err) > OFF_POINTS and r["se_old"] <= UNCERTAIN_SE_POINTS
            bare_new += abs(err) > OFF_POINTS and r["se_new"] <= UNCERTAIN_SE_POINTS
            within2 += abs(err) <= 2.0 * r["se_new"]
        print(f"user {uid} step {r['step']:.3f} s A {a:.2f}: truth {r['truth']:5.2f} % estimate "
              f"{'-' if r['est'] is None else format(r['est'], '5.2f')} % ({r['n']} strides) error {err:+.2f} "
              f"SE old {r['se_old']:.2f} new {r['se_new']:.2f}", flush=True)
    e = np.asarray(errs)
    ok = np.isfinite(e)
    print(f"{which}: {len(e)} walks, median |error| {np.median(np.abs(e[ok])):.2f} points, within 3.0 points "
          f"{int((np.abs(e[ok]) <= 3.0).sum())}, mean signed error {np.mean(e[ok]):+.2f}, no estimate "
          f"{int((~ok).sum())}; noted uncertain (SE > {UNCERTAIN_SE_POINTS:g}) old {note_old} new {note_new}; over "
          f"{OFF_POINTS:g} points off without the note: old {bare_old} new {bare_new}; within 2 new standard errors "
          f"{within2} of {int(ok.sum())}", flush=True)


if __name__ == "__main__":
    arg = sys.argv[1:] or ["slow"]
    main(arg[0], range(int(arg[1]), int(arg[2]) + 1) if len(arg) == 3 else USERS)
