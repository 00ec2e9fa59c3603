"""Decisions W117 (the PLL's frequency range from the session's step rhythm) and W118 (the PLL step-length line in
dimensionless frequency), against their adoption rules written in docs/decisions/waist.md before this ran.
Uncalibrated ``waist-pll`` (its summary's step recall / F1 and distance error) with the PLL's 3.2 Hz clamp or W117's
``f_max_hz=None``, and W6's line or W118's (``sl_leg_m`` = :func:`pdrlearn.waist.params.line_leg_m`, passed as the
pipeline's parameters, so the rest of the defaults are the session's).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_kid_pll.py [--kids 1200-1239] [--adults 1240-1259]
Writes experiments/results/waist_kid_pll.md.
"""

from __future__ import annotations

import functools
import logging
from collections import defaultdict
from pathlib import Path

import numpy as np

import pdrlearn.track.waist as track_waist
from kid_profiles import child, child_age, walk
from pdrlearn.io import read_session
from pdrlearn.sim.user import UserProfile
from pdrlearn.steps import PLLStepDetector
from pdrlearn.track import get_pipeline
from pdrlearn.waist.params import line_leg_m, subject_height
from waist_kid_steps import cohort_args, span

ROOT = Path(__file__).resolve().parents[1]
#: (PLL upper clamp, W118 line): today's, W117 alone, W118 on today's PLL, both
VARIANTS = {"base": (3.2, False), "W117": (None, False), "W118": (3.2, True), "both": (None, True)}


def run(session) -> dict:
    """``{variant: (true positives, detected, reference, F1, distance error %)}`` (NaN where not scored)."""
    out = {}
    leg = line_leg_m(session.meta, subject_height(session.meta)[0])
    for name, (f_max, line) in VARIANTS.items():
        track_waist.PLLStepDetector = functools.partial(PLLStepDetector, f_max_hz=f_max)
        try:
            sm = get_pipeline("waist-pll")(session, params={"sl_leg_m": leg} if line else None).summary(session)
        finally:
            track_waist.PLLStepDetector = PLLStepDetector
        ref = sm.get("n_reference") or 0
        rec = sm.get("step_recall", float("nan"))
        tp = round(rec * ref) if ref and np.isfinite(rec) else 0
        out[name] = (tp, int(sm.get("n_detected") or 0), int(ref), float(sm.get("step_f1", float("nan"))),
                     float(sm.get("distance_error_pct", float("nan"))))
    return out


def pooled(rows) -> tuple[float, float]:
    tp, det, ref = (sum(r[i] for r in rows) for i in range(3))
    rec, prec = (tp / ref if ref else float("nan")), (tp / det if det else 0.0)
    return rec, 2 * prec * rec / (prec + rec) if prec + rec else 0.0


def main() -> None:
    args = cohort_args(__doc__, "1200-1239", "1240-1259")
    logging.disable(logging.WARNING)
    groups: dict[str, dict[str, list]] = defaultdict(lambda: defaultdict(list))
    lines = ["# W117 / W118 (experiments/waist_kid_pll.py)", "", "Per session: F1 and distance error % per variant "
             f"{', '.join(VARIANTS)}.", "", "| session | " + " | ".join(f"{v} F1 | {v} err %" for v in VARIANTS) + " |",
             "|---|" + "---|---|" * len(VARIANTS)]

    def add(group: str, label: str, session) -> None:
        r = run(session)
        for v, row in r.items():
            groups[group][v].append(row)
        lines.append(f"| {label} | " + " | ".join(f"{r[v][3]:.4f} | {r[v][4]:+.2f}" for v in VARIANTS) + " |")
        print(lines[-1], flush=True)

    first = span(args.kids).start
    for u in span(args.kids):
        for speed in ("normal", "fast"):
            add(f"age {child_age(u, first)}", f"kid {u} age {child_age(u, first)} {speed}",
                walk(child(u, child_age(u, first)), "A", speed))
    for u in span(args.adults):
        for speed in ("normal", "fast"):
            add("adults", f"adult {u} {speed}", walk(UserProfile.from_seed(u), "A", speed))
    for d in sorted(args.external.glob("mobgap_*")) + sorted(args.shared.glob("mobgap_*")):
        add(f"real {d.parent.name}/{d.name}", f"{d.parent.name}/{d.name}", read_session(d))
    lines += ["", "| group | " + " | ".join(f"{v} recall | {v} F1 | {v} median abs err %" for v in VARIANTS) + " |",
              "|---|" + "---|---|---|" * len(VARIANTS)]
    kids_all: dict[str, list] = defaultdict(list)
    for g, by in groups.items():
        cells = []
        for v in VARIANTS:
            rec, f1 = pooled(by[v])
            err = np.array([r[4] for r in by[v]], dtype=float)
            med = float(np.median(np.abs(err[np.isfinite(err)]))) if np.isfinite(err).any() else float("nan")
            cells.append(f"{rec:.4f} | {f1:.4f} | {med:.2f}")
            if g.startswith("age"):
                kids_all[v] += by[v]
        lines.append(f"| {g} | " + " | ".join(cells) + " |")
    cells = []
    for v in VARIANTS:
        rec, f1 = pooled(kids_all[v])
        med = float(np.median(np.abs([r[4] for r in kids_all[v]])))
        cells.append(f"{rec:.4f} | {f1:.4f} | {med:.2f}")
    lines.append("| all children | " + " | ".join(cells) + " |")
    print("\n".join(lines[-(len(groups) + 3):]), flush=True)
    out = ROOT / "experiments" / "results" / "waist_kid_pll.md"
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
