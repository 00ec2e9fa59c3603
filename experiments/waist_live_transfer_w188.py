"""Decision W188's measurement: how much altitude the live lower-back tracker (``pdrlearn.waist.WaistTracker``, W93,
fed its barometer as E106) gains per sit-to-stand, against offline ``waist-pendulum`` (W174 holds a transfer's change
in ``transfer_dz_m``). Nothing is changed; the live trackers have no W174.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/waist_live_transfer_w188.py

Fresh users 3700-3719, defaults (no calibration), 20 Hz as W174's check, walk seed 1: the trial's seated TUG and
W111's daily-activity route, each with ``sit_start_s=5, sit_end_s=5`` (``--sit-start 5 --sit-end 5``).
Prints, per route, the live and offline altitude at the first step (after the seated start's stand-up: the live
gain per stand-up) and at the last step.
"""

from __future__ import annotations

import importlib.util
import logging
from pathlib import Path

import numpy as np

from pdrlearn.sim import UserProfile
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker

ROOT = Path(__file__).resolve().parents[1]
USERS = range(3700, 3720)


def _routes() -> dict[str, tuple[str, str]]:
    spec = importlib.util.spec_from_file_location("wb", ROOT / "experiments" / "waist_backward.py")
    wb = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wb)
    return {"tug": (wb.TUG, "slow"), "daily": (wb.DAILY, "normal")}  # as W174's check


def live_steps(s, chunk: int = 20) -> list:
    """The live tracker's steps, each chunk's barometer samples pushed before its motion samples (E106)."""
    a, g, b = s["wAccelerometer"], s["wGyroscope"], s["wBarometer"]
    tr = WaistTracker(s.meta.get("rate_hz", 20.0), meta=s.meta, frame=s.require_frame("waist"))
    out, j = [], 0
    for i in range(0, len(a.t), chunk):
        k = int(np.searchsorted(b.t, a.t[min(i + chunk, len(a.t)) - 1], side="right"))
        if k > j:
            tr.push_barometer(b.t[j:k], b.values[j:k, 0])
        out += tr.push(a.t[i:i + chunk], a.values[i:i + chunk], g.values[i:i + chunk])
        j = max(j, k)
    if j < len(b.t):
        tr.push_barometer(b.t[j:], b.values[j:, 0])
    return out + tr.flush()


def main() -> None:
    logging.disable(logging.WARNING)
    for name, (route, speed) in _routes().items():
        rows = []
        for user in USERS:
            s = simulate_path(parse_route(route), UserProfile.from_seed(user), speed=speed, rate_hz=20.0, seed=1,
                              scenario="route", sit_start_s=5.0, sit_end_s=5.0)
            off = track_waist(s, pipeline="waist-pendulum", sit_veto=False)  # as measured, before W185
            ev = evaluate_track(off, s)
            live = live_steps(s)
            z = np.array([st.z for st in live], dtype=float)
            rows.append((z[-1], ev["altitude_change_m"], z[0], float(off.trajectory["z"].iloc[1]),
                         float(s.extras["transfers"]["drop_m"].iloc[0]), len(live), len(off.steps)))
        a = np.array(rows)
        gain = a[:, 2] - a[:, 3]  # the seated start's stand-up: live minus offline altitude at the first step
        print(f"{name}, users {USERS.start}-{USERS.stop - 1}: altitude at the first step (after the seated start's "
              f"stand-up, simulated rise median {np.median(a[:, 4]):.3f} m): live median {np.median(a[:, 2]):+.3f} m, "
              f"offline (W174) {np.median(a[:, 3]):+.3f} m; live gain per stand-up median {np.median(gain):.3f} m "
              f"(min {gain.min():.3f}, max {gain.max():.3f}); at the last step: live median {np.median(a[:, 0]):+.3f}"
              f" m (max |.| {np.abs(a[:, 0]).max():.3f}), offline {np.median(a[:, 1]):+.3f} m (max |.| "
              f"{np.abs(a[:, 1]).max():.3f}); steps live/offline median {np.median(a[:, 5]):.0f}/"
              f"{np.median(a[:, 6]):.0f}", flush=True)


if __name__ == "__main__":
    main()
