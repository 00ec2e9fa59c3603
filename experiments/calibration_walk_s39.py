"""Trial T1 finding 9 (session 39, fixer FC): which walk to calibrate the lower back on for a clinic. Simulated users
10050-10053 (the trial's walker: 0.5 m steps in 0.6 s, 0.83 m/s, `--bounce pendulum`, 100 Hz) calibrate
waist-pendulum on one 10 m walk (stand, walk, stand; `-d 10`), on three such walks (`-d 10 -d 10 -d 10`) and on one
30 m walk (`-d 30`); each calibration then tracks the user's 3 x 30 m corridor walk (`--units waist`, tracked
distance, no --corridor). Printed: K with calibrate's standard error and the corridor walk's distance error.
No default changes: the numbers are for docs/waist.md's calibration advice.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/calibration_walk_s39.py [WORKDIR]
Output: experiments/results/calibration_walk_s39.txt (the printed lines).
"""
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

USERS = range(10050, 10054)
PDR = [sys.executable, "-m", "pdrlearn"]
SIM = ["--step-length", "0.5", "--step-time", "0.6", "--bounce", "pendulum", "--rate", "100"]
TEST = "stand:3, straight:30, turn:180, straight:30, turn:180, straight:30, stand:3"


def _run(args: list[str]) -> str:
    done = subprocess.run([*PDR, *args], capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{' '.join(args[:3])}: exit {done.returncode}: {done.stderr[-1500:]}")
    return done.stdout + done.stderr


def main(work: Path) -> None:
    lines = []
    for u in USERS:
        walks = {}
        ten, thirty = "stand:3, straight:10, stand:3", "stand:3, straight:30, stand:3"
        for name, route, seed in (("w10a", ten, 1), ("w10b", ten, 2), ("w10c", ten, 3), ("w30", thirty, 4),
                                  ("test", TEST, 5)):
            walks[name] = work / f"u{u}_{name}"
            if not (walks[name] / "meta.json").exists():
                _run(["simulate", "--route", route, *SIM, "--user-seed", str(u), "--seed", str(seed), "--out",
                      str(walks[name]), "--force"])
        cals = {"uncalibrated": None, "one 10 m walk": (["w10a"], [10]),
                "three 10 m walks": (["w10a", "w10b", "w10c"], [10, 10, 10]), "one 30 m walk": (["w30"], [30])}
        for label, cal in cals.items():
            extra, k_text = [], "K0 1.1467"
            if cal is not None:
                params = work / f"u{u}_{label.replace(' ', '_')}.json"
                out = _run(["calibrate", *[str(walks[w]) for w in cal[0]], *sum((["-d", str(d)] for d in cal[1]), []),
                            "--out", str(params)])
                m = re.search(r"K (\d\.\d+) \+- (\d\.\d+)", out)
                k_text = f"K {m.group(1)} +- {m.group(2)}" if m else "K ?"
                extra = ["--params", str(params)]
            tr = work / f"u{u}_tr_{label.replace(' ', '_')}"
            _run(["track", str(walks["test"]), "--units", "waist", *extra, "--out", str(tr), "--force"])
            s = json.loads((tr / "summary.json").read_text())
            line = (f"user {u}, {label}: {k_text}; 3 x 30 m corridor walk tracked {s['distance_m']:.2f} m, distance "
                    f"error {s['distance_error_pct']:+.2f} %")
            print(line, flush=True)
            lines.append(line)
    (Path(__file__).resolve().parent / "results" / "calibration_walk_s39.txt").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp()))
