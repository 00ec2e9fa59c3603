"""Decision L731's adoption rule (docs/decisions/localization.md): L712's ``rest_drift`` reading every stand of 30 s
or more by the stand's own length (``rest_drift_by="stand"``: the foot's still run, first still sample to last)
against false (= main), on L712's long route simulated at RATE Hz, fresh users 16240-16279.

``python experiments/foot_rest_drift_l731.py RATE [--no-checks]``: L723's report (a) / (b) / (c) / (f1) / (f2), (d) /
(e) unless ``--no-checks``; then, for information, L712's gap rule's final heading error on the same sessions.
"""

from __future__ import annotations

import sys

import numpy as np

from foot_rest_drift_l712 import heading_errors, long_route, track
from foot_rest_drift_l723 import report
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

USERS = range(16240, 16280)
STAND = {"rest_drift_by": "stand"}  # L731's candidate, with rest_drift true


def main() -> None:
    rate = float(sys.argv[1])
    r = report(rate, USERS, STAND, checks="--no-checks" not in sys.argv)
    gap = []
    for user, h0, h1 in r[:, :3]:
        s = simulate_path(parse_route(long_route(int(user))), UserProfile.from_seed(int(user)), seed=0, rate_hz=rate)
        gap.append(heading_errors(track(s, True, heading="foot"), s)[-1])
        print(f"u{int(user)} {rate:g} Hz (information) foot heading final error false {h0:+.2f}, gap rule (L712) "
              f"{gap[-1]:+.2f}, stand rule (L731) {h1:+.2f} deg", flush=True)
    g = np.abs(np.array(gap)) - np.abs(r[:, 1])
    print(f"{rate:g} Hz (information) gap rule (L712): mean |final heading error| {np.mean(np.abs(gap)):.2f} deg; "
          f"largest growth {g.max():+.2f} deg (u{int(r[int(np.argmax(g)), 0])}); sessions grown > 20 deg: "
          f"{int(np.sum(g > 20))}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
