"""Decision W113: the waist IC detector's shortest step relative to the session's step rhythm, against its adoption
rule written in docs/decisions/waist.md before this ran. Offline ``waist-ic`` contacts (as ``track --pipeline
waist-pendulum``), W16's fixed 0.3 s (``min_step_s=0.3``) vs W113 (``min_step_s=None``), recall / F1 as
:func:`pdrlearn.waist.evaluate.step_metrics` (pooled counts).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_kid_steps.py [--kids 1000-1039] [--adults 1040-1059]
Writes experiments/results/waist_kid_steps.md.
"""

from __future__ import annotations

import argparse
import logging
from collections import defaultdict
from pathlib import Path

from kid_profiles import child, child_age, walk
from pdrlearn.io import read_session
from pdrlearn.sim.user import UserProfile
from pdrlearn.steps.waist_ic import WaistICStepDetector
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]
VARIANTS = {"W16 0.3 s": 0.3, "W113 relative": None}


def counts(session) -> dict:
    """``{variant: (true positives, detected, reference, F1)}``; empty without timed reference contacts."""
    out = {}
    for name, ms in VARIANTS.items():
        steps = WaistICStepDetector(min_step_s=ms).detect(session)
        m = step_metrics(steps, session)
        if "step_recall" not in m:
            return {}
        tp = round(m["step_recall"] * m["n_reference"])
        out[name] = (tp, int(m["n_detected"]), int(m["n_reference"]), m["step_f1"])
    return out


def pooled(rows) -> tuple[float, float]:
    tp, det, ref = (sum(r[i] for r in rows) for i in range(3))
    rec, prec = tp / ref, tp / det if det else 0.0
    return rec, 2 * prec * rec / (prec + rec) if prec + rec else 0.0


def span(s: str) -> range:
    lo, hi = (int(x) for x in s.split("-"))
    return range(lo, hi + 1)


def cohort_args(doc: str, kids: str = "1000-1039", adults: str = "1040-1059") -> argparse.Namespace:
    """The command line of the children's waist experiments: simulated children / adults and the real recordings."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--kids", default=kids)
    ap.add_argument("--adults", default=adults)
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--shared", type=Path, default=Path("/work/shared/data"))
    return ap.parse_args()


def main() -> None:
    args = cohort_args(__doc__)
    logging.disable(logging.WARNING)
    lines = ["# W113 shortest step (experiments/waist_kid_steps.py)", "",
             "| group | W16 recall | W16 F1 | W113 recall | W113 F1 |", "|---|---|---|---|---|"]
    groups: dict[str, dict[str, list]] = defaultdict(lambda: defaultdict(list))
    first = span(args.kids).start
    for u in span(args.kids):
        p = child(u, child_age(u, first))
        for speed in ("normal", "fast"):
            for name, row in counts(walk(p, "A", speed)).items():
                groups[f"age {child_age(u, first)}"][name].append(row)
        print("kid", u, flush=True)
    for u in span(args.adults):
        for speed in ("normal", "fast"):
            for name, row in counts(walk(UserProfile.from_seed(u), "A", speed)).items():
                groups["adults"][name].append(row)
        print("adult", u, flush=True)
    real = sorted(args.external.glob("mobgap_*")) + sorted(args.shared.glob("mobgap_*"))
    for d in real:
        for name, row in counts(read_session(d)).items():
            groups[f"real {d.parent.name}/{d.name}"][name].append(row)
    for g, by in groups.items():
        (r0, f0), (r1, f1) = pooled(by["W16 0.3 s"]), pooled(by["W113 relative"])
        lines.append(f"| {g} | {r0:.4f} | {f0:.4f} | {r1:.4f} | {f1:.4f} |")
        print(lines[-1], flush=True)
    out = ROOT / "experiments" / "results" / "waist_kid_steps.md"
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
