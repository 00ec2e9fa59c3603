"""Steps decisions 74 / 75 (session 39, fixer FG): dead force channels and the accel-force detector on one channel.

Usage:
    PYTHONPATH=. .venv/bin/python experiments/force_channels_s39.py

Simulated users 10120-10129 (scenario B, normal, 100 Hz, with force). Steps 74: which channels
:func:`~pdrlearn.displace.force_channels.dead_channels` names on the clean session and on copies with fForceA or
fForceB at 0 or fForceB as |N(0, 2)| N, and the clean sessions' track stride count and distance with and without
the dead-channel drop. Steps 75: `AccelForceStepDetector` scored against the simulated ICs with two channels, one
total channel (heel + toe in fForceA), the heel alone and the forefoot alone. Prints the tables; writes nothing.
"""

from __future__ import annotations

import copy
import logging

import numpy as np

import pdrlearn.track.plasys as P
from pdrlearn.displace.force_channels import dead_channels
from pdrlearn.sim import UserProfile, simulate
from pdrlearn.steps import AccelForceStepDetector
from pdrlearn.steps.evaluate import score_events

USERS = range(10120, 10130)


def variant(s, kind: str):
    """A copy of session ``s`` with its force channels changed: "two" (as simulated), "total" (heel + toe in
    fForceA, no fForceB), "heel" / "fore" (that channel alone), "deadA" / "deadB" (0), "noisyB" (|N(0, 2)|)."""
    out = copy.copy(s)
    st = dict(s.streams)
    a, b = st["fForceA"], st["fForceB"]
    if kind == "total":
        st["fForceA"] = type(a)(a.name, a.t, a.values + np.interp(a.t, b.t, b.values[:, 0])[:, None])
        del st["fForceB"]
    elif kind == "heel":
        del st["fForceB"]
    elif kind == "fore":  # the lone forefoot read as steps 75's fill would (the detector now refuses it alone)
        st["fForceA"] = type(a)(a.name, a.t, np.zeros_like(a.values))
    elif kind in ("deadA", "deadB"):
        x = st["fForce" + kind[-1]]
        st[x.name] = type(x)(x.name, x.t, np.zeros_like(x.values))
    elif kind == "noisyB":
        st["fForceB"] = type(b)(b.name, b.t, np.abs(np.random.default_rng(0).normal(0, 2, b.values.shape)))
    out.streams = st
    return out


def main() -> None:
    logging.disable(logging.WARNING)
    sims = {u: simulate("B", UserProfile.from_seed(u), "normal", rate_hz=100.0) for u in USERS}
    print("steps 74 user | dead named: clean / deadA / deadB / noisyB | track clean: strides, m (drop on / off)")
    for u, s in sims.items():
        named = []
        for k in ("two", "deadA", "deadB", "noisyB"):
            v = variant(s, k)
            dead = dead_channels({n: v.streams[n].values[:, 0] for n in ("fForceA", "fForceB")})
            named.append(",".join(sorted(dead)) or "-")
        on = P.track_plasys(s)
        orig = P.live_force
        P.live_force = lambda ses: (ses, None)
        off = P.track_plasys(s)
        P.live_force = orig
        print(f"{u} | {' / '.join(named)} | {len(on.steps)}, {on.steps['length_m'].sum():.3f} / {len(off.steps)}, "
              f"{off.steps['length_m'].sum():.3f}")
    print("steps 75 kind | count error (sum |n - ref|) | mean timing error s (matched, all users) | F1 min")
    for k in ("two", "total", "heel", "fore"):
        errs, times, f1 = 0, [], []
        for s in sims.values():
            t = AccelForceStepDetector().detect(variant(s, k))
            sc = score_events(t["event_s"], s.steps["ic_s"])
            errs += abs(sc["count"] - sc["reference_count"])
            times.append(sc["timing_error_mean_s"])
            f1.append(sc["f1"])
        print(f"{k} | {errs} | {np.mean(times):+.4f} | {min(f1):.3f}")


if __name__ == "__main__":
    main()
