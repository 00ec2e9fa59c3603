"""Decision L111 (docs/decisions/localization.md): is the lower back's step-time asymmetry
(``pdrlearn.track.clinical.step_time_asymmetry``) good enough for every lower-back summary? Adoption rule written
in the decision before this script was run on its users.

Fresh users 260-279 (``UserProfile.from_seed``), route "stand:2, straight:30, stand:2", normal speed, 100 Hz (the
Mobilise-D lower-back rate), seed 0. The simulator draws both feet's step times from one distribution
(``pdrlearn.sim.body.schedule``): every walker is symmetric, so an index well above 0 is the measurement's error.
`pdrlearn track --pipeline waist-pendulum`'s steps, ``waist_gait_summary``'s step times (``waist_step_times``).

Run: PYTHONPATH=. .venv/bin/python experiments/step_asymmetry.py [--users 260-279]
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.clinical import step_time_asymmetry
from pdrlearn.track.gait import waist_step_times

ROUTE = "stand:2, straight:30, stand:2"
#: the rule (decision L111): under LIMIT_PCT on at least MIN_UNDER of the walks and a mean under MEAN_PCT
LIMIT_PCT, MIN_UNDER_FRAC, MEAN_PCT = 5.0, 0.95, 3.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="260-279", help="first-last user seeds")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    a, b = (int(v) for v in args.users.split("-"))
    track = get_pipeline("waist-pendulum")
    rows = []
    for u in range(a, b + 1):
        s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), speed="normal", rate_hz=100, seed=0)
        rows.append((u, *step_time_asymmetry(*waist_step_times(track(s).steps))))
        si = "None" if rows[-1][1] is None else f"{rows[-1][1]:.2f}"
        print(f"user {u}: step_time_asymmetry_pct {si} over {rows[-1][2]} step times")
    si = np.array([np.nan if r[1] is None else r[1] for r in rows])
    under = int(np.sum(si < LIMIT_PCT))
    need = int(np.ceil(MIN_UNDER_FRAC * len(rows)))
    mean = float(np.nanmean(si))
    print(f"{len(rows)} walks: mean {mean:.2f} %, median {np.nanmedian(si):.2f} %, max {np.nanmax(si):.2f} %, "
          f"under {LIMIT_PCT:g} %: {under} (need {need}), None: {int(np.isnan(si).sum())}")
    ok = under >= need and mean < MEAN_PCT
    print("rule (L111):", "holds - adopted" if ok else "fails - not adopted")


if __name__ == "__main__":
    main()
