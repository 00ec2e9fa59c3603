"""L182's compass check on long multi-floor routes (session 28 navigation trial, finding 9: 2 of 4 fresh 12-min
default sessions warned; README: 0 of 60, measured on short level routes). Fresh users, the trial's long route (R1
four times, 12.3 min, 8 storeys up and down), the simulator's default disturbance (3 uT), offline ``pdrlearn track
DIR --storey-height 2.89`` with no model: the compass check's median angle, whether it warned, and the final
position error. A measurement; nothing is changed.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_check_long.py [--users 4120-4139]``
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
R1 = ("stand:5, straight:20, turn:90, straight:15, up:17, turn:180, up:17, straight:10, turn:-90, straight:25, "
      "backward:4, stand:20, turn:180, straight:25, turn:90, straight:10, down:17, turn:180, down:17, straight:15, "
      "turn:-90, straight:20, turn:180")  # the trial's R1


def cli(*args: str) -> tuple[dict | None, str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.run([sys.executable, "-m", "pdrlearn", *args], capture_output=True, text=True, env=env)
    try:
        return json.loads(p.stdout), p.stderr
    except json.JSONDecodeError:
        return None, p.stderr


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="4120-4139")
    a, b = (int(x) for x in ap.parse_args().users.split("-"))
    tmp = Path(tempfile.mkdtemp(prefix="compass_"))
    warned, medians = 0, []
    for u in range(a, b + 1):
        d = tmp / f"u{u}"
        cli("simulate", "--route", ", ".join([R1] * 4), "--user-seed", str(u), "--out", str(d))
        s, err = cli("track", str(d), "--storey-height", "2.89", "--out", str(d) + ".off", "--json")
        if s is None:
            print(f"u{u}: n/a ({err.strip().splitlines()[-1][:120] if err.strip() else ''})", flush=True)
            continue
        chk = (s.get("info") or {}).get("compass_check") or {}
        med = chk.get("median_deg")
        line = "waist compass disagrees" in err
        warned += line
        medians.append(med)
        fpe, sig = s.get("final_position_error_m"), s.get("final_position_sigma_m")
        print(f"u{u}: compass median {med if med is None else round(med, 2)} deg over {chk.get('n_strides')} "
              f"straight strides, warned {line}, final error {fpe and round(fpe, 2)} m, "
              f"2 sigma {sig and round(2 * sig, 2)} m", flush=True)
    shown = sorted((m for m in medians if m is not None), reverse=True)
    print(f"warned {warned} of {len(medians)}; largest medians {[round(m, 2) for m in shown[:5]]}")


if __name__ == "__main__":
    main()
