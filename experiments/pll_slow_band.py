"""Decision W475 (steps decision 83): the PLL's band from a slow walker's pelvic-gyro rhythm, against its adoption
rule written in docs/decisions/waist.md before this ran. ``PLLStepDetector()`` scored by ``score_steps`` (as
``pdrlearn steps --detector pll``) with W117's range ("base"), candidate A (0.3 Hz .. f_g / 0.75) and candidate B
(0.3 .. 2.5 Hz), on fresh simulated slow walkers (30-60 steps/min) and every real lower-back recording.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/pll_slow_band.py [--users 11830-11839] [--sim DIR]
Writes experiments/results/pll_slow_band.md.
"""

from __future__ import annotations

import argparse
import functools
import logging
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import pdrlearn.kernels.waist as kw
from pdrlearn.io import read_session
from pdrlearn.steps import PLLStepDetector
from pdrlearn.steps.evaluate import score_steps
from waist_kid_steps import span

ROOT = Path(__file__).resolve().parents[1]
#: the variants: W117 alone (the slow band off), candidate A, candidate B
VARIANTS = {"base": lambda period, f_max_hz=None: None, "A": kw.pll_slow_band,
            "B": functools.partial(kw.pll_slow_band, f_max_hz=2.5)}
#: (step time s, step length m) of the fresh users in turn: 60 / 50 / 40 / 34 / 30 steps/min
GAITS = [(1.0, 0.3), (1.2, 0.2), (1.5, 0.45), (1.75, 0.3), (2.0, 0.2),
         (1.0, 0.45), (1.2, 0.3), (1.5, 0.2), (1.75, 0.45), (2.0, 0.3)]


def simulate(user: int, k: int, out: Path) -> Path:
    """A slow walk of fresh user ``user`` (the k-th gait of :data:`GAITS`), simulated once into ``out``."""
    step_s, step_m = GAITS[k % len(GAITS)]
    d = out / f"u{user}"
    if not (d / "meta.json").exists():
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", "stand:2, straight:8, stand:2",
                        "--step-length", str(step_m), "--step-time", str(step_s), "--bounce", "pendulum",
                        "--rocker", "smooth", "--user-seed", str(user), "--rate", "100", "--out", str(d), "--force"],
                       check=True, capture_output=True)
    return d


def score(path: Path) -> dict:
    """``{variant: (F1, count error %, true positives, scored detections, reference steps)}`` of the PLL detector's
    defaults on the session at ``path``."""
    s = read_session(path)
    out = {}
    for name, band in VARIANTS.items():
        orig, kw.pll_slow_band = kw.pll_slow_band, band
        try:
            sc = score_steps(PLLStepDetector().detect(s), s) or {}
        finally:
            kw.pll_slow_band = orig
        out[name] = (float(sc.get("f1", np.nan)), float(sc.get("count_error_pct", np.nan)),
                     *(int(sc.get(k) or 0) for k in ("true_positives", "scored_count", "reference_count")))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="11830-11839")
    ap.add_argument("--sim", type=Path, default=None, help="folder of the simulated walks (default: a temporary one)")
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--shared", type=Path, default=Path("/work/shared/data"))
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    sim = args.sim or Path(tempfile.mkdtemp(prefix="pll_slow_band_"))
    lines = ["# W475 the PLL's slow band (experiments/pll_slow_band.py)", "",
             "| session | base F1 | base count err % | A F1 | A count err % | B F1 | B count err % |",
             "|---|---|---|---|---|---|---|"]
    rows = {}
    for k, u in enumerate(span(args.users)):
        step_s, step_m = GAITS[k % len(GAITS)]
        rows[f"u{u} {step_m} m x {step_s} s"] = score(simulate(u, k, sim))
    n_sim = len(rows)
    real = sorted({p.name: p for root in (args.shared, args.external) for p in root.glob("mobgap_*")}.items())
    for name, p in real:
        rows[name] = score(p)
    for name, r in rows.items():
        lines.append(f"| {name} | " + " | ".join(f"{r[v][0]:.4f} | {r[v][1]:.1f}" for v in VARIANTS) + " |")
    sims = list(rows.values())[:n_sim]
    lines += ["", "| simulated | pooled F1 | median abs count error % |", "|---|---|---|"]
    for v in VARIANTS:
        tp, det, ref = (sum(r[v][i] for r in sims) for i in (2, 3, 4))
        f1 = 2 * tp / (det + ref) if det + ref else float("nan")
        ce = np.nanmedian([abs(r[v][1]) for r in sims])
        lines.append(f"| {v} | {f1:.4f} | {ce:.1f} |")
    text = "\n".join(lines) + "\n"
    out = ROOT / "experiments" / "results" / "pll_slow_band.md"
    out.write_text(text)
    print(text)


if __name__ == "__main__":
    main()
