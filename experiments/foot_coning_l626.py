"""Decisions L626 / L627's adoption rules (docs/decisions/localization.md): the offline foot strapdown with L35's
coning term (L626) and, with it, each stride's start tilt from the accelerometer at rest (L627), against the former
rules (the term off, the angle filter's tilt), the same sessions in one process.

Usage::

    PYTHONPATH=. python experiments/foot_coning_l626.py l626        # or l627

(1) the noise-free 200 m straight (100 Hz), right and left foot, tracked foot-only: the lateral error at the end;
(2) the thesis scenarios A-D (20 Hz default simulation, users 1-3, normal speed), M1 / M2 / M3 (oracle classes): the
mean distance error per scenario and method; (3) the real gaitmap foot walks: the final position error and the
largest stride length change (information)."""

from __future__ import annotations

import contextlib
import importlib
import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.units import keep_units

ROOT = Path(__file__).resolve().parents[1]
ROUTE = "stand:10, straight:200, stand:5"
STRAIGHT_USERS = {"l626": range(12200, 12205), "l627": range(12205, 12210), "l628": range(12211, 12216)}
SCENARIO_USERS = (1, 2, 3)
SD = importlib.import_module("pdrlearn.kernels.strapdown")
#: per decision: (old, new) = (coning coefficient, FootDisplacement settings); None = the code's default coefficient
KALMAN, ACCEL = {"attitude": "kalman"}, {"attitude": "accel"}
FINE = {**ACCEL, "upsample": "L628"}  # decision L628: x5 below 150 Hz
RULES = {"l626": ((0.0, KALMAN), (None, KALMAN)), "l627": ((0.0, KALMAN), (None, ACCEL)),
         "l628": ((0.0, {**KALMAN, "upsample": "L24"}), (None, FINE))}
#: the former default grid (L24: x5 below 50 Hz) and L628's (x5 below 150 Hz)
GRID_BELOW_HZ = {"L24": 50.0, "L628": 150.0}


@contextlib.contextmanager
def coning(coef):
    keep = SD.CONING_COEF
    SD.CONING_COEF = keep if coef is None else coef
    try:
        yield
    finally:
        SD.CONING_COEF = keep


def run(session, rule, **kw):
    coef, params = rule
    if isinstance(params.get("upsample"), str):  # the rule's default grid at this session's foot rate
        fs = session.streams["fGyroscope"].rate_hz
        params = {**params, "upsample": 5 if fs < GRID_BELOW_HZ[params["upsample"]] else 1}
    if kw.get("method") == "M1":  # M1's own attitude (the accelerometer's, L7) either way
        params = {k: v for k, v in params.items() if k != "attitude"} or None
    with coning(coef):
        return track_plasys(session, params=params, **kw)


def lateral_end(session, result) -> float:
    """The track's last point across the true straight's direction (m, + = left), both started at the track's
    first point."""
    ft = session.extras["foot_trajectory"]
    tt = ft["t_s"].to_numpy(float)
    tr = result.trajectory
    t = tr["t"].to_numpy(float)
    tx = np.interp(t, tt, ft["x"]) - np.interp(t[0], tt, ft["x"])
    ty = np.interp(t, tt, ft["y"]) - np.interp(t[0], tt, ft["y"])
    psi = np.arctan2(ty[-1], tx[-1])
    return float(-np.sin(psi) * (tr["x"].iloc[-1] - tx[-1]) + np.cos(psi) * (tr["y"].iloc[-1] - ty[-1]))


def main() -> int:
    logging.disable(logging.WARNING)
    which = sys.argv[1] if len(sys.argv) > 1 else "l626"
    old, new = RULES[which]
    worst = 0.0
    for user in STRAIGHT_USERS[which]:
        for foot in ("right", "left"):
            s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), rate_hz=100, noise=False,
                              instrumented_foot=foot)
            s = keep_units(s, ("foot",))
            a, b = lateral_end(s, run(s, old)), lateral_end(s, run(s, new))
            worst = max(worst, abs(b))
            print(f"straight u{user} {foot}: lateral error at the end old {a:+.2f} m new {b:+.2f} m", flush=True)
    print(f"straights: largest |lateral error| new {worst:.2f} m (rule: < 1 m)", flush=True)
    rows = {}
    for scen in ("A", "B", "C", "D"):
        for user in SCENARIO_USERS:
            s = simulate(scen, user)
            for m in ("M1", "M2", "M3"):
                kw = {"method": m, "model": "oracle" if m == "M3" else None}
                e = [float(track_summary(run(s, r, **kw), s)["distance_error_pct"]) for r in (old, new)]
                rows.setdefault((scen, m), []).append(e)
    worse = 0.0
    for (scen, m), e in rows.items():
        e = np.asarray(e)
        d = float(np.mean(np.abs(e[:, 1])) - np.mean(np.abs(e[:, 0])))
        worse = max(worse, float(np.mean(e[:, 1]) - np.mean(e[:, 0])), d)
        print(f"scenario {scen} {m}: mean distance error old {e[:, 0].mean():+.3f} % new {e[:, 1].mean():+.3f} % "
              f"(mean |.| {np.mean(np.abs(e[:, 0])):.3f} -> {np.mean(np.abs(e[:, 1])):.3f})", flush=True)
    print(f"scenarios: largest worsening {worse:+.3f} points (rule: <= 0.05)", flush=True)
    for p in sorted((ROOT / "datasets/real").glob("gaitmap_*")):
        s = read_session(p)
        r0, r1 = run(s, old), run(s, new)
        f0, f1 = (track_summary(r, s).get("final_position_error_m") for r in (r0, r1))
        l0, l1 = (r.steps["length_m"].to_numpy(float) for r in (r0, r1))
        rel = np.nanmax(np.abs(l1 / l0 - 1.0)) * 100 if len(l0) == len(l1) else float("nan")
        print(f"{p.name}: final position error old {f0} m new {f1} m; {len(l0)} / {len(l1)} strides, largest "
              f"stride length change {rel:.3f} %", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
