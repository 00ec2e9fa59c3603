"""Decision S63 (session 31 prosthesis trial, finding 2): `pdrlearn gait` on simulated feet WITHOUT force sensors.

Run: ``PYTHONPATH=$PWD python experiments/nof_gait_rocker.py``

Fresh users 6060-6069, two foot sessions of one hemiparetic walk (S54 ``--foot left``, S55 ``--paretic-side``),
route ``stand:3, straight:30, stand:3`` at 100 Hz, step-time asymmetry (0, 0.1, 0.2, 0.3)[u % 4] (and step-length
asymmetry half of it), paretic side alternating; ``fForceA/fForceB`` deleted (an IMU-only lab), so both feet's
contacts come from the accelerometer detector (steps decision 3). Each pair simulated with the default Hermite
heel rocker and with S31's ``--rocker smooth``; printed: the tracked step-time SI and ratio against the same
sessions' labelled contacts, and each foot's contact timing error (steps decision 30's second peak shows there).
"""

from __future__ import annotations

import logging
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import score_steps
from pdrlearn.track.bilateral import pair_sessions
from pdrlearn.track.plasys import track_plasys

logging.disable(logging.WARNING)
USERS = range(6060, 6070)
ASYM = (0.0, 0.1, 0.2, 0.3)


def main() -> None:
    py = sys.executable
    rows = {"hermite": [], "smooth": []}
    with tempfile.TemporaryDirectory() as tmp:
        for u in USERS:
            a, side = ASYM[u % 4], ("left", "right")[(u // 2) % 2]
            for rocker in ("hermite", "smooth"):
                dirs = {}
                for foot in ("left", "right"):
                    d = dirs[foot] = Path(tmp) / f"u{u}_{rocker}_{foot}"
                    subprocess.run([py, "-m", "pdrlearn", "simulate", "--route", "stand:3, straight:30, stand:3",
                                    "--step-time-asymmetry", str(a), "--step-length-asymmetry", str(a / 2),
                                    "--paretic-side", side, "--foot", foot, "--rocker", rocker, "--user-seed", str(u),
                                    "--rate", "100", "--out", str(d)], check=True, capture_output=True)
                    for f in ("fForceA.csv", "fForceB.csv"):
                        (d / f).unlink()
                res = pair_sessions(dirs["left"], dirs["right"])
                w, r = res["walk"], res["reference"]["walk"]
                lag = {}
                for foot, d in dirs.items():
                    s = read_session(d)
                    sc = score_steps(track_plasys(s).steps, s, unit="foot")
                    lag[foot] = (1000 * sc["timing_error_mean_s"], 1000 * sc["timing_error_sd_s"])
                rows[rocker].append(abs(w["step_time_s_si_pct"] - r["step_time_s_si_pct"]))
                print(f"user {u} a={a} paretic {side} {rocker:7s}: step SI {w['step_time_s_si_pct']:.1f} % (labels "
                      f"{r['step_time_s_si_pct']:.1f}) ratio L/R {w['step_time_s_ratio']:.3f} "
                      f"({r['step_time_s_ratio']:.3f}); contact error left {lag['left'][0]:+.0f} +- "
                      f"{lag['left'][1]:.0f} ms, right {lag['right'][0]:+.0f} +- {lag['right'][1]:.0f} ms", flush=True)
    for rocker, e in rows.items():
        print(f"{rocker}: |tracked - labels| step SI median {np.median(e):.1f}, max {np.max(e):.1f} points "
              f"({len(e)} pairs)")


if __name__ == "__main__":
    main()
