"""Decision W99: calibrate's pelvic-gyro step-count cross-check against its adoption rule, written in
docs/decisions/waist.md before this ran. One run, one candidate (|n_waist - n_gyro| > 0.3 n_gyro warns).

(a) at most 1 warned of: 10 m calibration walks of users 480-489, normal and slow speed, 20 and 100 Hz (40),
    plus the 6 mobgap Test5 walks (46);
(b) the trial's cal411 walk (0.15 m / 1.5 s walker, 100 Hz) warned.
For information: the trial's cal407.

Run: PYTHONPATH=$PWD python experiments/waist_calibrate_count.py [--external datasets/external]
     [--trial /tmp/trial_aids/simw]
Writes experiments/results/waist_calibrate_count.md.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import step_count_check, step_counts

ROOT = Path(__file__).resolve().parents[1]
ROUTE = [Stand(3), Straight(10), Stand(3)]


def judge(session) -> dict:
    """The contacts `calibrate --distance` counts (every step with a next contact, W21) and the check on them."""
    st = track_waist(session, pipeline="waist-pendulum").steps
    st = st[st["has_next"]]
    ev = np.unique(np.concatenate([st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)]))
    counts = step_counts(session, ev)
    return {"n_waist": None if counts is None else counts[0], "n_gyro": None if counts is None else counts[1],
            "warned": step_count_check(session, ev) is not None}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--trial", type=Path, default=Path("/tmp/trial_aids/simw"))
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    rows = []

    def add(group, name, s):
        rows.append({"group": group, "session": name, **judge(s)})
        print(rows[-1], flush=True)

    add("b doubled", "cal411", read_session(args.trial / "cal411"))
    add("info trial", "cal407", read_session(args.trial / "cal407"))
    for d in sorted(args.external.glob("mobgap_*_Test5_*")):
        add("a real", d.name, read_session(d))
    for u in range(480, 490):
        user = UserProfile.from_seed(u)
        for speed in ("normal", "slow"):
            for rate in (20, 100):
                add("a sim", f"user {u} {speed} {rate} Hz", simulate_path(ROUTE, user, speed=speed, rate_hz=rate,
                                                                         seed=u))
    out = ["# W99 calibrate step-count cross-check (experiments/waist_calibrate_count.py)", "",
           "| group | session | waist contacts | pelvic-gyro steps | warned |", "|---|---|---|---|---|"]
    out += [f"| {r['group']} | {r['session']} | {r['n_waist']} | {r['n_gyro']} | {r['warned']} |" for r in rows]
    a = [r for r in rows if r["group"].startswith("a ")]
    b = [r for r in rows if r["group"].startswith("b ")]
    verdict = [f"(a) warned {sum(r['warned'] for r in a)} of {len(a)} (rule <= 1)",
               f"(b) warned {sum(r['warned'] for r in b)} of {len(b)} (rule: all)"]
    out += ["", *verdict]
    print("\n".join(verdict))
    (ROOT / "experiments" / "results" / "waist_calibrate_count.md").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
