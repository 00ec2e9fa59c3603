"""Decisions W325 / W326 (session 33): several TUG trials in one lower-back recording (tug_trials.csv) against the
simulator's truth (:func:`pdrlearn.sim.tug_truth.true_trials`). Measured once, no tuning, no default changed.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/tug_trials.py   # fresh users 7100-7111
Output: experiments/results/tug_trials_sim.txt (the printed lines).

Per user: 2 trials (even users) or 3 (odd) of W294's two-turn TUG route joined by ``sit:10``
(:func:`~pdrlearn.sim.tug_truth.trials_route`), seated 5 s at both ends, 20 Hz, normal / slow by (user // 2) % 2;
the track is the default waist-pendulum one, its trials :func:`pdrlearn.waist.tug_phases.tug_trial_table` of its
transfers, turns.csv and contacts, as ``track`` writes tug_trials.csv.
"""
import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.tug_truth import trials_route, true_trials
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.transfers import transfer_summary
from pdrlearn.waist.tug_phases import TUG_PHASE_KEYS, TUG_PHASES, tug_trial_table

logging.disable(logging.WARNING)

USERS = range(7100, 7112)
TRIAL = "straight:3, turn:180, straight:3, turn:180"  # W294's two-turn TUG


def trials_session(u: int, n: int, speed: str):
    """A simulated recording of ``n`` TUG trials (:func:`trials_route`) of user ``u``, seated 5 s at both ends."""
    return simulate_path(parse_route(trials_route(TRIAL, n)), UserProfile.from_seed(u), speed=speed, seed=u,
                         sit_start_s=5.0, sit_end_s=5.0)


def tracked_trials(s):
    """The track's tug_trials.csv rows and summary of session ``s`` (waist-pendulum, as ``track``)."""
    res = track_waist(s, pipeline="waist-pendulum")
    turns = turn_table(res.steps, yaw_turns=res.info.get("yaw_turns"))
    table = tug_trial_table(res.info.get("transfers"), turns, res.steps, yaw_turns=res.info.get("yaw_turns"))
    return table, transfer_summary(res.info.get("transfers"), res.steps)


def main() -> None:
    errors, phase_err, found, true_n = [], {p: [] for p in TUG_PHASES}, 0, 0
    for u in USERS:
        n, speed = 2 + u % 2, "slow" if (u // 2) % 2 else "normal"
        s = trials_session(u, n, speed)
        truth = true_trials(s, TRIAL, n)
        table, summary = tracked_trials(s)
        true_n, found = true_n + n, found + len(table)
        cells = []
        for k, t in enumerate(truth):
            row = table[(table["start_s"] < t["end_s"]) & (table["end_s"] > t["start_s"])]
            if len(row) != 1:
                cells.append(f"trial {k + 1} not found")
                continue
            e = float(row["tug_time_s"].iloc[0]) - t["tug_time_s"]
            errors.append(e)
            pe = []
            for p, key in zip(TUG_PHASES, TUG_PHASE_KEYS, strict=True):
                got, true = row[key].iloc[0], t["phases"][p]
                if true is not None and np.isfinite(got):
                    phase_err[p].append(float(got) - true["duration_s"])
                    pe.append(f"{p} {float(got) - true['duration_s']:+.2f}")
            cells.append(f"trial {k + 1} true {t['tug_time_s']:.2f} s track {row['tug_time_s'].iloc[0]:.2f} s "
                         f"error {e:+.2f} s ({', '.join(pe)})")
        print(f"user {u} {speed}, {n} true trials, {len(table)} found (n_tug_trials {summary['n_tug_trials']}, "
              f"tug_time_s {summary['tug_time_s']}): " + "; ".join(cells))
    e = np.abs(errors)
    print(f"trials found {found} of {true_n}; TUG time error (track - truth) median {np.median(errors):+.2f} s, "
          f"median |.| {np.median(e):.2f} s, max |.| {e.max():.2f} s, within 0.5 s {int((e <= 0.5).sum())}/{e.size}, "
          f"within 1 s {int((e <= 1.0).sum())}/{e.size}")
    for p in TUG_PHASES:
        v = np.asarray(phase_err[p])
        if v.size:
            print(f"phase {p}: n {v.size}, median {np.median(v):+.2f} s, max |.| {np.abs(v).max():.2f} s")


if __name__ == "__main__":
    main()
