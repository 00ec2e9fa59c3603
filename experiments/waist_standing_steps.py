"""Decision W134's measurement: ``pause_steps="standing"`` (W122's trunk travel, only for a step whose longest
still run lasts at least half its local step period and that is neither the first nor the last step of its walk)
against the default (off), judged by the rule written before the run (docs/decisions/waist.md W134), W122's rule
on fresh simulated users 2100-2199:
(a) simulated daily activities (W111's route and protocol): the median |bout error| falls by at least 0.5 point;
(b) real Test11 HA001 / HA002 / MS001 (calibrated, per bout as W112): each subject's median |bout error| vs
    ``Length`` and vs the bouts' strides rises by at most 1.0 point; Test5 pooled, calibrated and uncalibrated,
    rises by at most 1.0 point;
(c) Test11 pooled (15 bouts): the median vs the bouts' strides falls and the median vs ``Length`` does not rise.
For information, after the verdict: simulator A-D users 1-3 (experiments/waist.py), W122 (``"progression"``) on the
same users.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/waist_standing_steps.py [--external DIR]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import waist_pause_steps as P  # noqa: E402
import waist_progression_steps as G  # noqa: E402

USERS = range(2100, 2200)
CANDIDATE = "standing"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=P.ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    ap.add_argument("--no-information", action="store_true", help="skip W122's information rows")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    off, on = (G.measure(args.external, v, args.sim_users, users=USERS) for v in (False, CANDIDATE))
    G.judge(off, on, "W134")
    if not args.no_information:
        print("information only (not the rule): W122's \"progression\" on the same users")
        w122 = G.measure(args.external, "progression", args.sim_users, users=USERS)
        P.print_users_better(off["daily"], w122["daily"])


if __name__ == "__main__":
    main()
