"""Decisions L538 / L539 / L541 (session 40, fixer FD, trial T1 findings F4 / F9): `pdrlearn gait`'s headline on the
walk's level straight steps, its per-kind rows, and its gait speed / cadence / distance, against the simulator's truth.

Run: ``PYTHONPATH=$PWD python experiments/gait_kinds_l538.py OUT_DIR [USER ...]`` (default users 10780-10785).

Each user walks (both feet simulated, S54 ``--foot``; IMU only, no force insoles: the pair T1's clinic has) a route
of level walking, a step-to-step stair flight up, a 180 deg turn and the flight down (T1's F2 / F4 route), slow, 100
Hz, ``--rocker smooth``, step-time asymmetry 0.15 (even users) or 0.25 (odd users), the right side paretic. Printed
per user: the step-time symmetry index (%) of

* ``truth_level``: the labelled contacts' level steps (the simulator's steps.csv IC times and terrain / turns; the
  reference ``by_kind["level"]``), what the headline should read;
* ``headline``: the tracked walk's headline (level straight steps, L538);
* ``pooled``: the tracked walk's steps of every kind (the headline before session 40);
* ``truth_pooled``: the labels' steps of every kind;

and the tracked gait speed / cadence / distance (L539) against the labels' and the simulator's walked distance
(meta.json ``distance_m``).
"""

from __future__ import annotations

import json
import logging
import sys
from pathlib import Path

import numpy as np

ROUTE = ("stand:3, straight:6, up:10:0.17:0.28:step-to-step, straight:3, turn:180, straight:3, "
         "down:10:0.17:0.28:step-to-step, straight:6, stand:3")


def _si(steps) -> float:
    from pdrlearn.track.clinical import symmetry_index_pct

    m = [steps.loc[steps["side"] == s, "step_time_s"].mean() for s in ("left", "right")]
    return symmetry_index_pct(m[0], m[1])


def one_user(root: Path, user: int) -> dict:
    from pdrlearn.cli import main
    from pdrlearn.track.bilateral import pair_sessions

    asym = 0.15 if user % 2 == 0 else 0.25
    feet = {}
    for foot in ("left", "right"):
        d = root / f"u{user}_{foot}"
        if not d.exists():
            assert main(["simulate", "--route", ROUTE, "--step-time-asymmetry", str(asym), "--paretic-side", "right",
                         "--speed", "slow", "--rate", "100", "--user-seed", str(user), "--rocker", "smooth", "--foot",
                         foot, "--out", str(d), "--json"]) == 0
            for f in d.glob("fForce*.csv"):  # IMU only (T1's clinic)
                f.unlink()
        feet[foot] = d
    res = pair_sessions(feet["left"], feet["right"])
    ref = res["reference"]
    meta = json.loads((feet["left"] / "meta.json").read_text())
    w, rw = res["walk"], ref["walk"]
    return {"user": user, "asym": asym, "truth_level": ref["by_kind"]["level"]["step_time_s_si_pct"],
            "headline": w["step_time_s_si_pct"], "basis": w["headline_steps"], "pooled": _si(res["steps"]),
            "truth_pooled": _si(ref["steps"]),
            "kinds": {k: (v["step_time_s_si_pct"], ref["by_kind"].get(k, {}).get("step_time_s_si_pct"))
                      for k, v in res["by_kind"].items()},
            "speed": (w["gait_speed_mps"], rw["gait_speed_mps"]), "cadence": (w["cadence_spm"], rw["cadence_spm"]),
            "distance": (w["distance_m"], rw["distance_m"], meta["distance_m"])}


def main(argv: list[str]) -> None:
    logging.disable(logging.WARNING)
    root = Path(argv[0])
    root.mkdir(parents=True, exist_ok=True)
    users = [int(u) for u in argv[1:]] or list(range(10780, 10786))
    rows = [one_user(root, u) for u in users]
    for r in rows:
        kinds = ", ".join(f"{k} {_f(a)} ({_f(b)})" for k, (a, b) in r["kinds"].items())
        print(f"user {r['user']} a={r['asym']}: step-time SI truth_level {_f(r['truth_level'])} headline "
              f"{_f(r['headline'])} ({r['basis']}) pooled {_f(r['pooled'])} truth_pooled {_f(r['truth_pooled'])} | "
              f"{kinds} | speed {r['speed'][0]:.3f} ({r['speed'][1]:.3f}) cadence {r['cadence'][0]:.1f} "
              f"({r['cadence'][1]:.1f}) distance {r['distance'][0]:.2f} ({r['distance'][1]:.2f}; walked "
              f"{r['distance'][2]:.2f})")
    given = [r for r in rows if r["headline"] is not None]  # L461: under 10 level steps a side, withheld
    head = np.array([abs(r["headline"] - r["truth_level"]) for r in given])
    pooled = np.array([abs(r["pooled"] - r["truth_level"]) for r in given])
    print(f"headline withheld (under 10 level straight steps a side, L461) on {len(rows) - len(given)} of {len(rows)}: "
          + ", ".join(f"user {r['user']} pooled {_f(r['pooled'])} truth_level {_f(r['truth_level'])}"
                      for r in rows if r["headline"] is None))
    speed = np.array([100 * (r["speed"][0] / r["speed"][1] - 1) for r in rows])
    dist = np.array([100 * (r["distance"][0] / r["distance"][2] - 1) for r in rows])
    cad = np.array([r["cadence"][0] - r["cadence"][1] for r in rows])
    print(f"|headline - truth_level| median {np.median(head):.2f} max {head.max():.2f} points; |pooled - truth_level| "
          f"median {np.median(pooled):.2f} max {pooled.max():.2f}; headline nearer on {(head < pooled).sum()} of "
          f"{len(given)}")
    print(f"gait speed vs labels {speed.min():+.2f} to {speed.max():+.2f} %; distance vs walked {dist.min():+.2f} to "
          f"{dist.max():+.2f} %; cadence vs labels {cad.min():+.2f} to {cad.max():+.2f} steps/min")


def _f(v) -> str:
    return "-" if v is None else f"{v:.1f}"


if __name__ == "__main__":
    main(sys.argv[1:])
