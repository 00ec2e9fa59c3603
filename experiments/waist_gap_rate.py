"""Decision W389 (docs/decisions/waist.md): the waist gyroscope across a gap of up to 1 s as the pre-gap mean rate
(``pre-mean``) against W34's straight line between the gap's edge samples (``line``), on fresh simulated walks.

Users 9210-9214 (fresh), trial T1's route, normal speed, seed 37, the waist streams resampled to 50 Hz (a phone);
gaps of 0.3, 0.5, 0.7, 0.9 s from 15 s (straight walking) and a 0.9 s gap centred on the middle of the 90 deg turn.
``track_waist(pipeline="waist-pendulum")`` defaults, offline. Prints per walk the heading change across the gap
minus the clean walk's (deg) and the final position error (m), then the means and rule (a)-(d).

Run: PYTHONPATH=. .venv/bin/python experiments/waist_gap_rate.py [--users 9210-9214]
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from pdrlearn.io.session import Stream
from pdrlearn.kernels import gaps as G
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist
from tests.runtime_helpers import without

ROUTE = "stand:3, straight:30, turn:90, straight:20, stand:3"  # trial T1's route
RATE_HZ = 50.0
ARMS = {"line": False, "pre-mean": True}  # G.PRE_GAP_RATE
STRAIGHT_GAPS = (0.3, 0.5, 0.7, 0.9)
TURN_GAP_S = 0.9


def at_rate(session, fs: float = RATE_HZ):
    """``session`` with its waist streams linearly resampled onto a uniform ``fs`` clock (a phone's rate)."""
    s = session.copy()
    for n in ("wAccelerometer", "wGyroscope"):
        st = s.streams[n]
        t = st.t[0] + np.arange(int((st.t[-1] - st.t[0]) * fs) + 1) / fs
        s.streams[n] = Stream(n, t, np.column_stack([np.interp(t, st.t, st.values[:, j]) for j in range(3)]))
    return s


def turn_middle(session) -> float:
    g = session.trajectory
    h = np.degrees(np.unwrap(g["heading_rad"].to_numpy(float)))
    i = int(np.flatnonzero(np.abs(h - h[0]) >= 45.0)[0])
    return float(g["t"].iloc[i])


def across(res, a: float, b: float) -> float:
    """Heading change (deg) from the last step ending before ``a`` to the first step starting after ``b``."""
    st = res.steps
    before = st[st["end_s"] <= a]
    after = st[st["start_s"] >= b]
    d = after["heading_rad"].iloc[0] - before["heading_rad"].iloc[-1]
    return float(np.degrees(np.angle(np.exp(1j * d))))


def run(session, arm: str):
    old, G.PRE_GAP_RATE = G.PRE_GAP_RATE, ARMS[arm]
    try:
        return track_waist(session, pipeline="waist-pendulum")
    finally:
        G.PRE_GAP_RATE = old


def user_range(doc: str, default: str = "9210-9214") -> list[int]:
    """The ``--users A-B`` of session 37's phone experiments (this one and waist_pll_reference.py), pdrlearn quiet."""
    p = argparse.ArgumentParser(description=doc.splitlines()[0])
    p.add_argument("--users", default=default)
    a = p.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    lo, _, hi = a.users.partition("-")
    return list(range(int(lo), int(hi or lo) + 1))


def main() -> None:
    users = user_range(__doc__)
    dev = {k: [] for k in ARMS}
    err = {k: [] for k in ARMS}
    same = 0
    for u in users:
        ses = at_rate(simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), speed="normal", seed=37,
                                    name=f"gaprate_u{u}", scenario="route"))
        clean = {k: run(ses, k) for k in ARMS}
        ok = clean["line"].steps.equals(clean["pre-mean"].steps) and \
            clean["line"].trajectory.equals(clean["pre-mean"].trajectory)
        same += ok
        tm = turn_middle(ses)
        for a0, d in [(15.0, g) for g in STRAIGHT_GAPS] + [(tm - TURN_GAP_S / 2, TURN_GAP_S)]:
            gs = without(ses, a0, a0 + d, ["wAccelerometer", "wGyroscope"])
            row = []
            for k in ARMS:
                r = run(gs, k)
                dv = across(r, a0, a0 + d) - across(clean[k], a0, a0 + d)
                e = evaluate_track(r, gs)["final_position_error_m"]
                dev[k].append(abs(dv))
                err[k].append(e)
                row.append(f"{k}: dev {dv:+.1f} deg, final {e:.2f} m")
            print(f"u{u} gap {d:.1f} s at {a0:.1f} s: " + "; ".join(row), flush=True)
        print(f"u{u} clean walk identical in both arms: {ok}", flush=True)
    m = {k: (np.mean(dev[k]), np.mean(err[k])) for k in ARMS}
    worst = max(np.subtract(err["pre-mean"], err["line"]))
    for k in ARMS:
        print(f"{k}: mean |heading deviation| {m[k][0]:.2f} deg, mean final position error {m[k][1]:.2f} m")
    print(f"worst change of a gapped walk's final error {worst:+.2f} m; clean walks identical {same}/{len(users)}")
    rule = (m["pre-mean"][0] < m["line"][0], m["pre-mean"][1] < m["line"][1], worst <= 1.0, same == len(users))
    print("rule (a)-(d):", rule, "-> adopted" if all(rule) else "-> not adopted")


if __name__ == "__main__":
    main()
