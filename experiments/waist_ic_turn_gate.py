"""Decision 28 of docs/decisions/steps.md: the waist motion gate also open while the pelvis turns
(`InitialContactDetector(turn_gate_rps=0.45)`), measured against its adoption rule (written before this ran).

Scored as decision 25 (`experiments/waist_ic_period.py`, whose scoring helpers this imports): Test11 and Test5 of
the mobgap subjects with `score_steps` (as `pdrlearn steps --detector waist-ic`), the simulator (A-D x
slow/normal/fast x users 1-3, 100 Hz, model and realistic pelvis) with `score_events`; for information the fresh
TUG walks of W72 (users 61-70, 20 and 100 Hz).

Run: PYTHONPATH=$PWD python experiments/waist_ic_turn_gate.py [--external datasets/external] [--sim-users 3]
"""

from __future__ import annotations

import argparse
import itertools
import logging
import warnings
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.steps.detectors import get_detector
from pdrlearn.steps.evaluate import score_events
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import InitialContactDetector
from waist_ic_period import SUBJECTS, TEST5, f1, real_counts
from waist_turn_gaps import ROUTES

ROOT = Path(__file__).resolve().parents[1]
TURN_GATE_RPS = 0.45  # decision 28: DEFAULT_TURN_GMM's turning mean (W7)


def contacts(imu, candidate: dict | None) -> np.ndarray:
    """Sorted contact times (s) of the default detector, or with the options ``candidate`` when given."""
    det = InitialContactDetector(**(candidate or {})).detect(imu)
    return np.sort(imu.t[det.ic_])


def _sim_counts(s, candidate: dict) -> tuple[tuple, tuple]:
    imu = waist_imu(s)
    ref = s.extras["ics"]["ic_s"].to_numpy(float)
    out = []
    for cand in (None, candidate):
        sc = score_events(contacts(imu, cand), ref)
        out.append((sc["true_positives"], sc["count"], sc["reference_count"]))
    return tuple(out)


def measure(doc: str, candidate: dict, tug_users: range, tug_rule: bool) -> None:
    """One script's run, its rows printed: the default waist detector vs ``InitialContactDetector(**candidate)``
    (decisions 28 and 29 of docs/decisions/steps.md) on the mobgap recordings, the TUG walks of ``tug_users``
    (``tug_rule``: part of the rule, F1 printed; else for information) and, unless ``--skip-sim``, the simulator.
    ``doc``: the script's docstring (``--help``)."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    ap.add_argument("--skip-sim", action="store_true")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.basicConfig(level=logging.ERROR)
    cli = get_detector("waist-ic")
    rows = {}
    print("| recording | default F1 (TP/det/ref) | candidate F1 (TP/det/ref) |\n|---|---|---|", flush=True)
    for name in [f"{s}_Test11_Trial1" for s in SUBJECTS] + list(TEST5):
        s = read_session(args.external / f"mobgap_{name}")
        imu = waist_imu(s)
        base = contacts(imu, None)
        assert np.allclose(base, np.sort(cli.detect(s)["event_s"].to_numpy(float))), name
        rows[name] = (real_counts(s, base), real_counts(s, contacts(imu, candidate)))
        b, c = rows[name]
        print(f"| {name} | {f1([b]):.3f} ({b[0]}/{b[1]}/{b[2]}) | {f1([c]):.3f} ({c[0]}/{c[1]}/{c[2]}) |", flush=True)
    t11 = [rows[f"{s}_Test11_Trial1"] for s in SUBJECTS]
    print(f"| Test11 pooled | {f1([r[0] for r in t11]):.3f} | {f1([r[1] for r in t11]):.3f} |", flush=True)
    for rate in (20.0, 100.0):  # fresh TUG walks (W72's route)
        acc = [_sim_counts(simulate_path(parse_route(ROUTES["tug"]), UserProfile.from_seed(u), speed="normal",
                                         rate_hz=rate, seed=7, name=f"tug_u{u}", scenario="route"), candidate)
               for u in tug_users]
        tot = [[sum(x) for x in zip(*(a[j] for a in acc), strict=True)] for j in (0, 1)]
        head = f"TUG users {tug_users[0]}-{tug_users[-1]} {rate:.0f} Hz"
        score = (f": F1 {f1([a[0] for a in acc]):.4f} -> {f1([a[1] for a in acc]):.4f}, " if tug_rule
                 else " (info): ")
        print(f"{head}{score}TP/det/ref default {tot[0]} -> candidate {tot[1]}", flush=True)
    if args.skip_sim:
        return
    for pelvis in ("model", "realistic"):
        acc = []
        for scenario, speed in itertools.product("ABCD", ("slow", "normal", "fast")):
            for user in range(1, args.sim_users + 1):
                acc.append(_sim_counts(simulate(scenario, user, speed=speed, rate_hz=100.0, pelvis=pelvis),
                                       candidate))
                if acc[-1][0] != acc[-1][1]:
                    print(f"  changed: u{user} {scenario} {speed} {pelvis}: {acc[-1][0]} -> {acc[-1][1]}", flush=True)
        tot = [[sum(x) for x in zip(*(a[j] for a in acc), strict=True)] for j in (0, 1)]
        print(f"simulator ({pelvis} pelvis) F1 default {f1([a[0] for a in acc]):.4f} (TP/det/ref {tot[0]}) -> "
              f"candidate {f1([a[1] for a in acc]):.4f} (TP/det/ref {tot[1]})", flush=True)


def main() -> None:
    measure(__doc__, {"turn_gate_rps": TURN_GATE_RPS}, range(61, 71), tug_rule=False)  # TUG: W72's set, for information


if __name__ == "__main__":
    main()
