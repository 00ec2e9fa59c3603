"""Decision W572 (docs/decisions/waist.md), the simulator's side: does the simulator make W518's "stand" false
positives - lower-back contacts of the default offline `waist-pendulum` inside a > 1.2 s gap between the truth
contacts within the walk (a stop: `stand:S`, a stepping `turn:DEG`, a `spin:DEG:S`, the walk's end into `sit:S`)?

Fresh users 17000-17009 (session 50's range; seed = user), one route holding every kind of stop the simulator has,
`--pelvis realistic --bounce pendulum` (the most real-like trunk); each session tracked once (defaults, uncalibrated)
and scored as `step_metrics` scores it (the truth `ics.csv`); then, for each truth gap > 1.2 s (W26 / W45's gap), the
track's contacts lying inside it (0.25 s off its ends, decision 7's tolerance).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_stand_fp_sim_s50_w572.py [--users 17000-17009]
Writes experiments/results/waist_stand_fp_sim_s50_w572.md (sessions simulated into a temporary folder).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]
ROUTE = ("stand:3, straight:8, stand:2, straight:6, turn:180, straight:6, stand:1.5, straight:6, spin:90:2, "
         "straight:6, sit:5")
GAP_S, TOL = 1.2, 0.25  # W26 / W45's reference gap; decision 7's tolerance (s)


def simulate(user: int, out: Path) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", ROUTE, "--pelvis", "realistic",
                    "--bounce", "pendulum", "--user-seed", str(user), "--rate", "100", "--out", str(out)],
                   check=True, capture_output=True)


def gaps(session, ev: np.ndarray) -> list[tuple[float, float, int]]:
    """The truth gaps > GAP_S (start, end, the track's contacts inside)."""
    ref = np.sort(session.extras["ics"]["ic_s"].dropna().to_numpy(float))
    out = []
    for a, b in zip(ref[:-1], ref[1:], strict=True):
        if b - a > GAP_S:
            out.append((float(a), float(b), int(np.sum((ev > a + TOL) & (ev < b - TOL)))))
    return out


def main(users: range) -> None:
    print(f"## W572: the simulator's stops and the lower back's contacts in them (users {users.start}-"
          f"{users.stop - 1}, route `{ROUTE}`, `--pelvis realistic --bounce pendulum`)\n")
    print("| user | step F1 | detected / truth | truth gaps > 1.2 s (s) | track contacts inside them |\n"
          "|---|---|---|---|---|")
    tot_gaps = tot_in = 0
    with tempfile.TemporaryDirectory() as tmp:
        for u in users:
            d = Path(tmp) / f"u{u}"
            simulate(u, d)
            s = read_session(d)
            steps = track_waist(s, pipeline="waist-pendulum").steps
            ev = np.sort(steps["event_s"].to_numpy(float))
            m = step_metrics(steps, s)
            g = gaps(s, ev)
            tot_gaps, tot_in = tot_gaps + len(g), tot_in + sum(x[2] for x in g)
            spans = ", ".join(f"{a:.1f}-{b:.1f}" for a, b, _ in g)
            print(f"| {u} | {m['step_f1']:.4f} | {m['n_detected']} / {m['n_reference']} | {spans} | "
                  f"{' / '.join(str(x[2]) for x in g)} |")
    print(f"\n{tot_in} track contacts inside {tot_gaps} truth stops of {len(users)} users")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--users", default="17000-17009", help="first-last user (seed)")
    args = ap.parse_args()
    lo, hi = (int(x) for x in args.users.split("-"))
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main(range(lo, hi + 1))
    (ROOT / "experiments" / "results" / "waist_stand_fp_sim_s50_w572.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
