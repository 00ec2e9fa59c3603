"""Decisions L388 / L389 (session 33, fixer F9): the force insoles' toe-off and clock offset on simulated users.

Usage:
    PYTHONPATH=. .venv/bin/python experiments/force_events_s33.py

L388: users 7350-7355 (scenario A, normal, 100 Hz, with force), ``track_plasys(toe_off=True)`` with the force
drop-off toe-off and with L73's gyroscope toe-off; per user the median over strides of |stance_pct - true stance %|
(truth: the simulated steps' ``ic_s`` / ``tc_s``) and ``n_stance_times``. L389: users 7356-7361, ``force_offset_s``
and the warning for the force shifted by 0, +60 and +150 ms; L390: the same on users 7362-7367 with the
drop-off against the gyroscope toe-off. Prints the tables; writes nothing.

Session 41 (decision L584): L389's arm measured the code of session 33 (``force_clock.OFFSET_FROM_TOE_OFF =
False``, the force onset against the accelerometer impact); L389 was not adopted and its code is gone, so the
script now prints L390's table only (on users 7362-7367, as before).
"""

from __future__ import annotations

import logging

import numpy as np

import pdrlearn.track.plasys as P
from pdrlearn.sim import UserProfile, simulate


def shifted(session, dt: float):
    """``session`` with its force streams delayed by ``dt`` s (the value at t is the original's at t - dt)."""
    import copy

    out = copy.copy(session)
    out.streams = dict(session.streams)
    for n in ("fForceA", "fForceB"):
        s = session.streams[n]
        v = np.column_stack([np.interp(s.t - dt, s.t, s.values[:, k]) for k in range(s.values.shape[1])])
        out.streams[n] = type(s)(s.name, s.t, v)
    return out


def true_stance_pct(truth, event_s) -> np.ndarray:
    """Per tracked IC: the true stance % of the stride ending at the nearest true IC (previous true IC to the true
    toe-off between the two ICs, over the true IC-to-IC time)."""
    ic = np.sort(truth["ic_s"].to_numpy(float))
    tc = np.sort(truth["tc_s"].to_numpy(float))
    out = np.full(len(event_s), np.nan)
    for k, e in enumerate(np.asarray(event_s, float)):
        i = int(np.argmin(np.abs(ic - e))) if len(ic) else -1
        if i < 1 or abs(ic[i] - e) > 0.3:
            continue
        inside = tc[(tc > ic[i - 1]) & (tc < ic[i])]
        if len(inside):
            out[k] = 100.0 * (inside[-1] - ic[i - 1]) / (ic[i] - ic[i - 1])
    return out


def l388() -> None:
    print("L388 user | force: med|err| pct, n | gyroscope: med|err| pct, n | true median stance %")
    for u in range(7350, 7356):
        s = simulate("A", UserProfile.from_seed(u), "normal", rate_hz=100.0)
        row = []
        for force in (True, False):
            P.FORCE_TOE_OFF = force
            r = P.track_plasys(s, toe_off=True)
            st = r.steps
            truth = true_stance_pct(s.steps, st["event_s"])
            err = np.abs(st["stance_pct"].to_numpy(float) - truth)
            row += [float(np.nanmedian(err)), int(np.isfinite(st["stance_pct"]).sum()), r.info["toe_off_source"]]
        P.FORCE_TOE_OFF = False
        print(f"{u} | {row[0]:.2f} {row[1]} {row[2]} | {row[3]:.2f} {row[4]} {row[5]} | "
              f"{np.nanmedian(truth):.1f}")


def offsets(users) -> None:
    print("L390 user | offset 0 / +60 / +150 ms (s) | warned 0 / +60 / +150 | "
          "(+60) - (0)")
    for u in users:
        s = simulate("A", UserProfile.from_seed(u), "normal", rate_hz=100.0)
        offs, warned = [], []
        for dt in (0.0, 0.06, 0.15):
            r = P.track_plasys(shifted(s, dt))
            offs.append(r.info["force_offset_s"])
            warned.append(any("decision L390" in w or "decision L389" in w for w in r.info["warnings"]))
        d = offs[1] - offs[0] if None not in offs[:2] else float("nan")
        print(f"{u} | {offs} | {warned} | {d:+.3f}")


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    l388()
    offsets(range(7362, 7368))  # decision L390
