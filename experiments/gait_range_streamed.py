"""Decision L222 (docs/decisions/localization.md): a streamed foot track's L95 range check on its strides' gait
cycle, measured once. (a) fresh users 4100-4105, scenarios A-D, speed by user (u % 3), ``pdrlearn run
models/plasys-sim-default``; (b) the real / external recordings, ``pdrlearn track DIR --streaming``; (c) the
navigation trial's slow route at 0.35 m / 0.85 s and 0.3 m / 1.0 s, users 4106-4108, ``run`` and offline ``track``.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/gait_range_streamed.py``
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MODEL = ROOT / "models" / "plasys-sim-default"
SPEEDS = ("slow", "normal", "fast")
SLOW_ROUTE = ("stand:5, straight:15, up:17, turn:180, up:17, turn:90, straight:10, turn:180, straight:10, turn:-90, "
              "down:17, turn:180, down:17, straight:15, stand:5")  # the trial's g_slow70 / g_slow60 route
MARK = "(decision L95)"


def cli(*args: str) -> tuple[dict | None, str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.run([sys.executable, "-m", "pdrlearn", *args], capture_output=True, text=True, env=env)
    try:
        return json.loads(p.stdout), p.stderr
    except json.JSONDecodeError:
        return None, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else f"exit {p.returncode}"


def line(name: str, s: dict | None, err: str) -> str:
    if s is None:
        return f"{name}: n/a ({err[:90]})"
    return (f"{name}: L95 line {MARK in err}, gait_out_of_range {s.get('gait_out_of_range')}, straight speed "
            f"{s.get('median_speed_straight_mps') and round(s['median_speed_straight_mps'], 3)} "
            f"({s.get('n_straight_strides')} strides), gait speed "
            f"{s.get('gait_speed_mps') and round(s['gait_speed_mps'], 3)}")


def main() -> None:
    tmp = Path(tempfile.mkdtemp(prefix="l222_"))
    print("(a) fresh users 4100-4105, scenarios A-D, pdrlearn run")
    n_line = n_flag = 0
    for u in range(4100, 4106):
        for sc in "ABCD":
            d = tmp / f"{sc}_{u}"
            cli("simulate", "--scenario", sc, "--user-seed", str(u), "--speed", SPEEDS[u % 3], "--out", str(d))
            s, err = cli("run", str(MODEL), str(d), "--out", str(d) + ".run", "--json")
            n_line += MARK in err
            n_flag += bool(s and s.get("gait_out_of_range"))
            print(" ", line(f"{sc} u{u} {SPEEDS[u % 3]}", s, err))
    print(f"(a) L95 lines {n_line} / 24, gait_out_of_range true {n_flag} / 24")
    print("(b) real / external recordings, track DIR --streaming")
    n_line = n = 0
    for base in (ROOT / "datasets" / "real", ROOT / "datasets" / "external"):
        for d in sorted(p for p in base.iterdir() if p.is_dir()):
            s, err = cli("track", str(d), "--streaming", "--out", str(tmp / ("r_" + d.name)), "--json")
            n += s is not None
            n_line += MARK in err
            print(" ", line(d.name, s, err))
    print(f"(b) L95 lines {n_line} of {n} tracked")
    print("(c) the trial's slow route, users 4106-4108")
    n_line = n_flag = 0
    for u in range(4106, 4109):
        for sl, st in (("0.35", "0.85"), ("0.3", "1.0")):
            d = tmp / f"slow_{u}_{sl}"
            cli("simulate", "--route", SLOW_ROUTE, "--user-seed", str(u), "--step-length", sl, "--step-time", st,
                "--out", str(d))
            s, err = cli("run", str(MODEL), str(d), "--out", str(d) + ".run", "--json")
            o, oerr = cli("track", str(d), "--out", str(d) + ".off", "--json")
            n_line += MARK in err
            n_flag += bool(s and s.get("gait_out_of_range"))
            print(" ", line(f"u{u} {sl} m / {st} s run", s, err))
            print(" ", line(f"u{u} {sl} m / {st} s offline", o, oerr))
    print(f"(c) run L95 lines {n_line} / 6, gait_out_of_range true {n_flag} / 6")


if __name__ == "__main__":
    main()
