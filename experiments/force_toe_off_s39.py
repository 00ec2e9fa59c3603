"""Steps decision 76 (session 39, fixer FG): L388's force drop-off toe-off against the gyroscope's on fresh users.

Usage:
    PYTHONPATH=. .venv/bin/python experiments/force_toe_off_s39.py

Users 10131-10136 (scenario A, normal, 100 Hz, with force): per user the median over strides of
|stance_pct - true stance %| and the strides with a stance time, force toe-off vs gyroscope toe-off
(L388's measure, :func:`force_events_s33.true_stance_pct`). Prints the table; writes nothing.
"""

from __future__ import annotations

import logging

import numpy as np

import pdrlearn.track.plasys as P
from force_events_s33 import true_stance_pct  # noqa: E402
from pdrlearn.sim import UserProfile, simulate


def main() -> None:
    logging.disable(logging.WARNING)
    print("steps 76 user | force: med|err| pct, n | gyroscope: med|err| pct, n | true median stance %")
    better = 0
    for u in range(10131, 10137):
        s = simulate("A", UserProfile.from_seed(u), "normal", rate_hz=100.0)
        row = []
        for force in (True, False):
            P.FORCE_TOE_OFF = force
            st = P.track_plasys(s, toe_off=True).steps
            truth = true_stance_pct(s.steps, st["event_s"])
            row += [float(np.nanmedian(np.abs(st["stance_pct"].to_numpy(float) - truth))),
                    int(np.isfinite(st["stance_pct"]).sum())]
        P.FORCE_TOE_OFF = False
        better += row[0] < row[2]
        print(f"{u} | {row[0]:.2f} {row[1]} | {row[2]:.2f} {row[3]} | {np.nanmedian(truth):.1f}")
    print(f"force toe-off better on {better} of 6")


if __name__ == "__main__":
    main()
