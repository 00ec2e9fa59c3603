"""Steps decision 84: waist-pll's walking-sequence bound from a slow pelvic rhythm, against its adoption rule written
in docs/decisions/steps.md before this ran. Per walk: ``pdrlearn steps --detector pll``'s F1 (``PLLStepDetector()``
scored by ``score_steps``; it never reads the bound) and ``track --pipeline waist-pll``'s contacts and distance error
with the bound before (``MAX_STEP_S`` 1.5 s) and after (:func:`pdrlearn.track.waist.sequence_bound_s`), on fresh
simulated slow walkers (1.2-2.2 s steps), normal walkers and every real lower-back recording.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/pll_sequence_bound_s84.py [--sim DIR]
Writes experiments/results/pll_sequence_bound_s84.md.
"""

from __future__ import annotations

import argparse
import logging
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import pdrlearn.track.waist as tw
from pdrlearn.io import read_session
from pdrlearn.steps import PLLStepDetector
from pdrlearn.steps.evaluate import score_steps
from pdrlearn.track import get_pipeline

ROOT = Path(__file__).resolve().parents[1]
#: the rule's slow walks: (user, step time s), two users a step time, 0.3 m steps over 8 m
SLOW = [(12140 + i, t) for i, t in enumerate(np.repeat([1.2, 1.4, 1.6, 1.8, 2.0, 2.2], 2))]
NORMAL = list(range(12160, 12166))  # the rule's normal walkers, drawn gait over 20 m
SLOW_M, NORMAL_M = 8.0, 20.0
OPTIONS = ["--bounce", "pendulum", "--rocker", "smooth", "--rate", "100"]


def simulate(user: int, step_s: float | None, out: Path) -> Path:
    """The rule's walk of ``user`` (slow at ``step_s`` s, 0.3 m steps; None: the drawn gait), simulated once."""
    d = out / f"u{user}"
    if not (d / "meta.json").exists():
        metres = SLOW_M if step_s else NORMAL_M
        gait = ["--step-length", "0.3", "--step-time", str(step_s)] if step_s else []
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", f"stand:3, straight:{metres:g}, "
                        "stand:3", *gait, *OPTIONS, "--user-seed", str(user), "--out", str(d), "--force"],
                       check=True, capture_output=True)
    return d


def measure(path: Path, metres: float | None) -> dict:
    """PLL F1, and waist-pll's (contacts, distance m, error %) before and after."""
    s = read_session(path)
    sc = score_steps(PLLStepDetector().detect(s), s) or {}
    out = {"f1": float(sc.get("f1", np.nan))}
    track = get_pipeline("waist-pll")
    for name, bound in (("before", lambda session, det=None: tw.MAX_STEP_S), ("after", tw.sequence_bound_s)):
        orig, tw.sequence_bound_s = tw.sequence_bound_s, bound
        try:
            res = track(s)
        finally:
            tw.sequence_bound_s = orig
        d = float(res.steps["length_m"].sum())
        out[name] = (len(res.steps), d, 100 * (d - metres) / metres if metres else np.nan)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sim", type=Path, default=None, help="folder of the simulated walks (default: a temporary one)")
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    sim = args.sim or Path(tempfile.mkdtemp(prefix="pll_bound_s84_"))
    lines = ["# steps 84 waist-pll's sequence bound (experiments/pll_sequence_bound_s84.py)", "",
             "| walk | pll F1 | contacts before | after | distance m before | after | error % before | after |",
             "|---|---|---|---|---|---|---|---|"]
    rows = {}
    for u, t in SLOW:
        rows[f"u{u} slow 0.3 m x {t:g} s"] = (t, measure(simulate(u, float(t), sim), SLOW_M))
    for u in NORMAL:
        rows[f"u{u} normal"] = (None, measure(simulate(u, None, sim), NORMAL_M))
    for p in sorted(args.external.glob("mobgap_*")):
        rows[p.name] = (None, measure(p, None))
    for name, (_, r) in rows.items():
        b, a = r["before"], r["after"]
        lines.append(f"| {name} | {r['f1']:.4f} | {b[0]} | {a[0]} | {b[1]:.4f} | {a[1]:.4f} | {b[2]:+.2f} | "
                     f"{a[2]:+.2f} |")
    long_ = [r for t, r in rows.values() if t and t > 1.5]
    better = sum(abs(r["after"][2]) < abs(r["before"][2]) for r in long_)
    med = float(np.median([abs(r["after"][2]) for r in long_]))
    short = [r for t, r in rows.values() if t and t <= 1.5]
    worse = sum(abs(r["after"][2]) > abs(r["before"][2]) + 1e-9 for r in short)
    same = all(r["before"][:2] == r["after"][:2] for t, r in rows.values() if not t)
    lines += ["", f"(a) 1.6-2.2 s walks better {better} of {len(long_)}, median |error| after {med:.2f} % "
                  f"(before {float(np.median([abs(r['before'][2]) for r in long_])):.2f} %)",
              f"(b) 1.2-1.4 s walks worse: {worse} of {len(short)}",
              f"(c) normal and real identical: {same}"]
    text = "\n".join(lines) + "\n"
    out = ROOT / "experiments" / "results" / "pll_sequence_bound_s84.md"
    out.write_text(text)
    print(text)


if __name__ == "__main__":
    main()
