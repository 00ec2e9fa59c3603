"""Decision L416's measurement (session 34): the step-time asymmetry of a foot unit's contacts labelling the lower
back's, against the same function on the simulator's true contacts, on fresh users 8044-8055 (60 m straight, 100 Hz,
pendulum bounce, step_time_asymmetry 0 / 0.05 / 0.15). Also printed, not judged: the same walks at 20 Hz.

Run: PYTHONPATH=. .venv/bin/python experiments/labelled_asymmetry_s34.py
"""

from __future__ import annotations

import logging
import warnings

import numpy as np

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.steps.detectors import AccelForceStepDetector
from pdrlearn.steps.waist_ic import WaistICStepDetector
from pdrlearn.track.labelled_asymmetry import labelled_step_asymmetry

USERS = range(8044, 8056)
SETTINGS = (0.0, 0.05, 0.15)


def walk_contacts(s) -> tuple[float, np.ndarray, np.ndarray]:
    """``(truth, foot, waist)`` of a simulated walk: the index on its true contacts (ics.csv), the foot unit's
    contacts (as the plasys track's event_s) and the lower back's (waist-ic)."""
    ics = s.extras["ics"]
    t = ics["ic_s"].to_numpy(float) if "ic_s" in ics else ics["ic_ms"].to_numpy(float) / 1000.0
    inst = (s.meta.get("knobs") or {}).get("instrumented_foot", "right")
    truth = labelled_step_asymmetry(t[ics["foot"].to_numpy() == inst], t)["step_time_asymmetry_pct"]
    foot = AccelForceStepDetector().detect(s)["event_s"].to_numpy(float)  # = the plasys track's event_s
    waist = WaistICStepDetector().detect(s)["event_s"].to_numpy(float)
    return truth, foot, waist


def one(uid: int, a: float, rate: int) -> tuple[float, float | None, int]:
    s = simulate_path([Stand(3), Straight(60), Stand(3)], UserProfile.from_seed(uid), speed="normal", rate_hz=rate,
                      seed=uid, bounce="pendulum", step_time_asymmetry=a)
    truth, foot, waist = walk_contacts(s)
    est = labelled_step_asymmetry(foot, waist)
    return truth, est["step_time_asymmetry_pct"], est["n_strides"]


def main() -> None:
    logging.disable(logging.WARNING)
    warnings.filterwarnings("ignore")
    for rate in (100, 20):
        errors = []
        for uid in USERS:
            for a in SETTINGS:
                truth, est, n = one(uid, a, rate)
                err = np.nan if est is None else est - truth
                errors.append(err)
                print(f"{rate} Hz user {uid} A {a:.2f}: truth {truth:5.2f} % estimate "
                      f"{'-' if est is None else f'{est:5.2f}'} % ({n} strides) error {err:+.2f}", flush=True)
        e = np.asarray(errors)
        ok = np.isfinite(e)
        print(f"{rate} Hz: median |error| {np.median(np.abs(e[ok])):.2f} points, within 3.0 points "
              f"{int((np.abs(e[ok]) <= 3.0).sum())} of {len(e)}, mean signed error {np.mean(e[ok]):+.2f}, "
              f"no estimate {int((~ok).sum())}", flush=True)


if __name__ == "__main__":
    main()
