"""Decision L490's measurement (session 38): L416's foot + lower-back step-time asymmetry on fresh children (users
9580-9591: 1.15-1.45 m, leg 0.5 x height, step length 0.34 x height, 0.36-0.45 s steps; the trial's 2 x 10 m walkway
route, and printed, not judged, 40 m straight) and on L416's adult validation walks (users 8044-8055, 60 m), each
at step_time_asymmetry 0 / 0.05 / 0.15, 100 Hz, pendulum bounce. Truth: the same function on the simulator's true
contacts (ics.csv).

Decision L493's fresh walks: the same children and adults (60 m) of users 9592-9599.

Run: PYTHONPATH=. .venv/bin/python experiments/labelled_asymmetry_s38.py
[children|children40|adults|children_fresh|adults_fresh]; the centred labelling (``CENTRED_OPTIONS``, L490 / L493's
option, measured when it was the default); with L416_DEFAULT=1 in the environment the default labelling instead.
"""

from __future__ import annotations

import dataclasses
import logging
import os
import sys
import warnings

import numpy as np

from experiments.labelled_asymmetry_s34 import walk_contacts
from pdrlearn.sim import Stand, Straight, Turn, UserProfile, simulate_path
from pdrlearn.track.labelled_asymmetry import CENTRED_OPTIONS, labelled_step_asymmetry

CHILDREN = range(9580, 9592)
ADULTS = range(8044, 8056)
#: decision L493's fresh walks: children and adults of users 9592-9599
FRESH = range(9592, 9600)
USERS = {"children": CHILDREN, "children40": CHILDREN, "adults": ADULTS, "children_fresh": FRESH,
         "adults_fresh": FRESH}
SETTINGS = (0.0, 0.05, 0.15)


def child(uid: int) -> UserProfile:
    """A child of 1.15-1.45 m (leg 0.5 x height) stepping 0.34 x height every 0.36-0.45 s, fixed by ``uid``."""
    h = 1.15 + 0.03 * (uid % 11)
    u = UserProfile.from_seed(uid).scaled(h, 0.5 * h)
    return dataclasses.replace(u, step_length_m=0.34 * h, step_time_s=0.36 + 0.015 * (uid % 7))


def one(group: str, uid: int, a: float) -> tuple[float, float | None, int, float | None, float | None]:
    if group.startswith("adults"):
        user, segs = UserProfile.from_seed(uid), [Stand(3), Straight(60), Stand(3)]
    else:
        user = child(uid)
        segs = ([Stand(3), Straight(10), Turn(180), Straight(10), Stand(3)] if group != "children40"
                else [Stand(3), Straight(40), Stand(3)])
    s = simulate_path(segs, user, speed="normal", rate_hz=100, seed=uid, bounce="pendulum", step_time_asymmetry=a)
    truth, foot, waist = walk_contacts(s)  # L416's measurement's truth and contacts
    if os.environ.get("L416_DEFAULT"):  # the default labelling (L416), as main's code before session 38
        est = labelled_step_asymmetry(foot, waist)
        return truth, est["step_time_asymmetry_pct"], est["n_strides"], None, est["step_time_asymmetry_pct"]
    est = labelled_step_asymmetry(foot, waist, **CENTRED_OPTIONS)  # L490 / L493's option
    # without the standard-error gate (printed, not judged)
    raw = labelled_step_asymmetry(foot, waist, **{**CENTRED_OPTIONS, "max_standard_error": np.inf}
                                  )["step_time_asymmetry_pct"]
    return truth, est["step_time_asymmetry_pct"], est["n_strides"], est.get("standard_error_points"), raw


def main(group: str) -> None:
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")
    errors = []
    for uid in USERS[group]:
        for a in SETTINGS:
            truth, est, n, se, raw = one(group, uid, a)
            err = np.nan if est is None else est - truth
            errors.append(err)
            print(f"{group} user {uid} A {a:.2f}: truth {truth:5.2f} % estimate {'-' if est is None else f'{est:5.2f}'}"
                  f" % ({n} strides, standard error {'-' if se is None else f'{se:.2f}'}) error {err:+.2f} "
                  f"(ungated {'-' if raw is None else f'{raw:.2f}'})",
                  flush=True)
    e = np.asarray(errors)
    ok = np.isfinite(e)
    print(f"{group}: given {int(ok.sum())} of {len(e)}, within 3.0 points {int((np.abs(e[ok]) <= 3.0).sum())}, "
          f"over 6 points {int((np.abs(e[ok]) > 6.0).sum())}, median |error| "
          f"{np.median(np.abs(e[ok])) if ok.any() else np.nan:.2f}, mean signed error "
          f"{np.mean(e[ok]) if ok.any() else np.nan:+.2f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "children")
