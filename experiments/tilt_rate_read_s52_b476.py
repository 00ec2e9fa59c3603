"""Decision B476 (docs/decisions/bad-input.md): B40's tilt-rate test run by ``read_session`` on session folders.

Prints, per unit recording, the tilt-rate ratio (accelerometer / gyroscope, :func:`pdrlearn.kernels.units.
tilt_rate_ratio`) and the gyroscope's tilt RMS with the right unit, and the ratio with the gyroscope in deg/s read as
rad/s; whether ``read_session`` refuses each (ratio under 0.3 with the tilt RMS over 0.5 rad/s). The recordings: every
real one (datasets/real, datasets/external, /work/shared/data) and simulated sessions (slow walkers, long stands,
stairs, rides, turns on the spot, sitting and lying; fresh users 19370-19389 with varied routes, speeds and rates),
simulated into a temporary folder with ``pdrlearn simulate``.

    PYTHONPATH=$PWD nice python experiments/tilt_rate_read_s52_b476.py
"""

from __future__ import annotations

import logging
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.io.sensors import UNIT_IMU
from pdrlearn.io.validate import TILT_GYRO_RMS_MIN, TILT_RATIO_MIN, tilt_rate_ratio

ROOT = Path(__file__).resolve().parents[1]
REAL = (ROOT / "datasets" / "external", ROOT / "datasets" / "real", Path("/work/shared/data"),
        Path("/work/main/datasets/external"))

#: (user, route, options): fresh users 19370-19389, each a kind of recording the check must not refuse
SIMS = [
    (19370, "stand:3, straight:20, stand:3", ["--speed", "slow"]),
    (19371, "stand:3, straight:16, stand:3", ["--step-length", "0.3", "--step-time", "0.75", "--bounce", "pendulum"]),
    (19372, "stand:120, straight:10, stand:60", ["--rate", "20"]),
    (19373, "straight:5, up:12, turn:180, down:12", ["--rate", "100"]),
    (19374, "straight:5, lift:+9, escalator:-9, straight:5", []),
    (19375, "straight:5, vehicle:60, straight:5", ["--rate", "50"]),
    (19376, "straight:5, cycle:30, straight:5", ["--rate", "100"]),
    (19377, "turn:180, pivot:360, spin:180:3, turn:-90, straight:5", []),
    (19378, "stand:3, inplace:20, spin:360:6, stand:3", ["--rate", "100"]),
    (19379, "straight:5, sit:20, straight:5, lie:60, straight:3", []),
    (19380, "stand:3, straight:20:short:slow, turn:180, straight:20:short:slow, stand:3", ["--rate", "100"]),
    (19381, "straight:10, curve:90:2, slope:9:8.33, backward:3, side:3", []),
    (19382, "straight:14:fast, turn:180, straight:14:fast", ["--rate", "100"]),
    (19383, "straight:5, freeze:10, straight:5, trolley:10", []),
    (19384, "straight:5, up:12:step-to-step:slow, down:12:slow", ["--rate", "50"]),
    (19385, "stand:300, straight:5, stand:300", ["--rate", "20"]),
    (19386, None, ["--scenario", "A"]),
    (19387, None, ["--scenario", "D", "--speed", "slow", "--rate", "100"]),
    (19388, None, ["--scenario", "rotations"]),
    (19389, "stand:2, straight:20, stand:2", ["--height", "0.95", "--leg-length", "0.45", "--step-length", "0.36",
                                              "--step-time", "0.3", "--rate", "100"]),
]


def real_folders() -> list[Path]:
    seen, out = set(), []
    for base in REAL:
        for p in sorted(base.glob("*/")) if base.is_dir() else ():
            if p.is_dir() and p.name not in seen and any(p.glob("[fw]Accelerometer.csv*")):
                seen.add(p.name)
                out.append(p)
    return out


def simulated(tmp: Path) -> list[Path]:
    out = []
    for user, route, opts in SIMS:
        dest = tmp / f"u{user}"
        cmd = [sys.executable, "-m", "pdrlearn", "simulate", "--user-seed", str(user), "--out", str(dest), *opts]
        if route is not None:
            cmd += ["--route", route]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode:
            print(f"u{user}: simulate failed: {r.stderr.strip().splitlines()[-1]}")
            continue
        out.append(dest)
    return out


def rows(folder: Path, group: str) -> list[tuple]:
    s = read_session(folder, check_units=False)
    out = []
    for unit, (acc, gyr) in UNIT_IMU.items():
        if acc in s.streams and gyr in s.streams:
            a, g = s.streams[acc], s.streams[gyr]
            r, rms = tilt_rate_ratio(a.t, a.values, g.t, g.values)
            r2, rms2 = tilt_rate_ratio(a.t, a.values, g.t, np.degrees(g.values))
            out.append((group, folder.name, unit, r, rms, rms > TILT_GYRO_RMS_MIN and r < TILT_RATIO_MIN,
                        r2, rms2, rms2 > TILT_GYRO_RMS_MIN and r2 < TILT_RATIO_MIN))
    return out


def main() -> None:
    logging.disable(logging.WARNING)
    with tempfile.TemporaryDirectory() as td:
        table = [row for f in real_folders() for row in rows(f, "real")]
        table += [row for f in simulated(Path(td)) for row in rows(f, "sim")]
    print("| group | recording | unit | ratio | tilt RMS rad/s | refused | deg/s as rad/s: ratio | tilt RMS | "
          "refused |")
    print("|---|---|---|---|---|---|---|---|---|")
    for g, name, unit, r, rms, ref, r2, rms2, ref2 in table:
        print(f"| {g} | {name} | {unit} | {r:.3f} | {rms:.3g} | {'yes' if ref else 'no'} | {r2:.4f} | {rms2:.3g} | "
              f"{'yes' if ref2 else 'no'} |")
    for g in ("real", "sim"):
        for unit in ("foot", "waist"):
            sel = [t for t in table if t[0] == g and t[2] == unit]
            if not sel:
                continue
            print(f"{g} {unit}: {len(sel)} unit recordings; right unit refused {sum(t[5] for t in sel)}, lowest ratio "
                  f"{np.nanmin([t[3] for t in sel]):.3f}; deg/s as rad/s refused {sum(t[8] for t in sel)}, highest "
                  f"ratio {np.nanmax([t[6] for t in sel]):.4f}, lowest tilt RMS {np.nanmin([t[7] for t in sel]):.3g}")


if __name__ == "__main__":
    main()
