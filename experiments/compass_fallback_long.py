"""Decision L226's adoption measurement (run once; the rule is in docs/decisions/localization.md): the default
fused heading against the candidate (``compass_fallback=True``: the waist gyroscope's heading, one constant offset
to the compass, when L182 warns) on fresh simulated users - R1 x2 (users 4400-4419), short level routes (users
4400-4409) and scenarios A-D at 100 Hz (users 4400-4404) - and the real gaitmap level walks. Offline, no model,
``storey_height_m`` 2.89 on R1. Prints; changes nothing.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_fallback_long.py``
"""

from __future__ import annotations

import logging
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.io.plasys import read_session
from pdrlearn.track.evaluate import STOREY_HEIGHT_M, track_summary
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
from compass_check_long import R1  # noqa: E402  the trial's R1

SHORT = ("straight:30, turn:90, straight:30", ", ".join(["straight:15, curve:-90:1"] * 8))  # L182's level routes


def simulate(out: Path, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", *args, "--out", str(out)], check=True,
                   capture_output=True, env=env)


def pair(folder: Path, storey_height_m: float = STOREY_HEIGHT_M) -> tuple[dict, dict, bool]:
    s = read_session(folder)
    a = track_plasys(s)
    b = track_plasys(s, compass_fallback=True)
    used = bool((b.info.get("compass_check") or {}).get("gyro_fallback"))
    return (track_summary(a, s, storey_height_m=storey_height_m), track_summary(b, s, storey_height_m=storey_height_m),
            used)


def main() -> None:
    logging.disable(logging.WARNING)
    tmp = Path(tempfile.mkdtemp(prefix="l226_"))
    base, cand, worse = [], [], []
    for u in range(4400, 4420):
        d = tmp / f"r1_{u}"
        simulate(d, "--route", ", ".join([R1] * 2), "--user-seed", str(u))
        a, b, used = pair(d, storey_height_m=2.89)
        fa, fb, sig2 = a["final_position_error_m"], b["final_position_error_m"], 2 * a["final_position_sigma_m"]
        base.append(fa)
        cand.append(fb)
        worse += [u] if fb - fa > sig2 else []
        print(f"R1x2 u{u}: default {fa:.2f} m, candidate {fb:.2f} m (fallback {used}), default 2 sigma {sig2:.2f} m",
              flush=True)
    print(f"R1x2 median final error: default {np.median(base):.2f} m, candidate {np.median(cand):.2f} m; "
          f"worse by more than 2 sigma: {worse}")
    groups = {f"level {i}": [(("--route", r, "--user-seed", str(u)), u) for u in range(4400, 4410)]
              for i, r in enumerate(SHORT)}
    groups |= {f"scenario {c}": [(("--scenario", c, "--rate", "100", "--user-seed", str(u)), u)
                                 for u in range(4400, 4405)] for c in "ABCD"}
    for name, runs in groups.items():
        fa, fb, n_used = [], [], 0
        for args, u in runs:
            d = tmp / f"{name.replace(' ', '_')}_{u}"
            simulate(d, *args)
            a, b, used = pair(d)
            fa.append(a["final_position_error_m"])
            fb.append(b["final_position_error_m"])
            n_used += used
        print(f"{name}: median final error default {np.median(fa):.3f} m, candidate {np.median(fb):.3f} m, "
              f"fallback on {n_used} of {len(runs)}", flush=True)
    for d in sorted((ROOT / "datasets" / "real").glob("gaitmap_level_*")):
        a, b, used = pair(d)
        print(f"real {d.name}: distance error default {a.get('distance_error_pct')} %, candidate "
              f"{b.get('distance_error_pct')} %, final error {a.get('final_position_error_m')} / "
              f"{b.get('final_position_error_m')} m, compass_check {a['info'].get('compass_check')}, fallback {used}")


if __name__ == "__main__":
    main()
