"""Decision W390 (docs/decisions/waist.md): waist-pll's harmonic heading with 0 at the first walk's direction
(``walk``) against main's 0 at the unit's initial facing (``unit``), on fresh simulated walks with a yawed waist unit.

Users 9210-9214 (fresh), trial T1's route, normal speed, seed 38; the waist streams rotated about the body's vertical
by 0, 20 and 30 deg. ``track_waist`` defaults; final position error (m) per arm, waist-pll and waist-pendulum.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_pll_reference.py [--users 9210-9214]
"""

from __future__ import annotations

import numpy as np

import pdrlearn.track.waist as TW
from experiments.waist_gap_rate import ROUTE, user_range
from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist

YAWS_DEG = (0.0, 20.0, 30.0)
ARMS = {"unit": False, "walk": True}  # TW.WALK_REFERENCE


def yawed(session, deg: float):
    """``session`` with the waist unit turned by ``deg`` about its body's vertical (FLU z; the sim's waist frame)."""
    from scipy.spatial.transform import Rotation

    frame = session.require_frame("waist").matrix()  # sensor -> FLU
    r = frame.T @ Rotation.from_euler("z", deg, degrees=True).as_matrix() @ frame  # the turn in sensor axes
    s = session.copy()
    for n in ("wAccelerometer", "wGyroscope"):
        st = s.streams[n]
        s.streams[n] = Stream(n, st.t, st.values @ r)  # each row v -> r^T v: the unit turned by +deg
    return s


def run(session, pipeline: str, arm: str):
    old, TW.WALK_REFERENCE = TW.WALK_REFERENCE, ARMS[arm]
    try:
        return track_waist(session, pipeline=pipeline)
    finally:
        TW.WALK_REFERENCE = old


def main() -> None:
    err = {k: [] for k in ARMS}
    pend_same = 0
    n = 0
    for u in user_range(__doc__):
        ses = simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), speed="normal", seed=38,
                            name=f"pllref_u{u}", scenario="route")
        for deg in YAWS_DEG:
            s = yawed(ses, deg)
            e = {k: evaluate_track(run(s, "waist-pll", k), s)["final_position_error_m"] for k in ARMS}
            pend = [run(s, "waist-pendulum", k) for k in ARMS]
            ok = pend[0].trajectory.equals(pend[1].trajectory)
            pend_same += ok
            n += 1
            for k in ARMS:
                err[k].append(e[k])
            print(f"u{u} yaw {deg:.0f} deg: pll final error unit {e['unit']:.2f} m, walk {e['walk']:.2f} m; "
                  f"pendulum identical: {ok}", flush=True)
    worst = max(np.subtract(err["walk"], err["unit"]))
    for k in ARMS:
        print(f"{k}: mean pll final position error {np.mean(err[k]):.2f} m")
    print(f"worst change {worst:+.2f} m; pendulum identical {pend_same}/{n}")
    rule = (np.mean(err["walk"]) < np.mean(err["unit"]), worst <= 1.0, pend_same == n)
    print("rule (a)-(c):", rule, "(d): experiments/waist.py --external")


if __name__ == "__main__":
    main()
