"""Decision W115: the uncalibrated waist height inferred from the sensor height when meta.json gives no height_m,
against its adoption rule written in docs/decisions/waist.md before this ran. Uncalibrated ``waist-pll`` distance
error (%) of each session with meta.json's height_m set to 1.70 m (what a missing height gives) and set to the height
its leg length / sensor height implies (W115: / 0.53; the same numbers as the candidate, which inferred it itself).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_kid_height.py [--kids 1000-1039] [--adults 1040-1059]
     [--copy /tmp/trial_peds/real/T5_fr_noh]
Writes experiments/results/waist_kid_height.md.
"""

from __future__ import annotations

import argparse
import copy
import logging
from pathlib import Path

import numpy as np

from kid_profiles import child, child_age, walk
from pdrlearn.io import read_session
from pdrlearn.sim.user import UserProfile
from pdrlearn.track import get_pipeline
from pdrlearn.waist.params import subject_height
from waist_kid_steps import span

ROOT = Path(__file__).resolve().parents[1]


def with_height(session, height: float | None):
    """``session`` with meta.json's height_m (subject and top level) set to ``height`` (None: removed)."""
    s = copy.copy(session)
    s.meta = copy.deepcopy(session.meta or {})
    for d in (s.meta, s.meta.setdefault("subject", {})):
        d.pop("height_m", None)
    if height is not None:
        s.meta["subject"]["height_m"] = height
    return s


def errors(session) -> tuple[float, float]:
    """Distance error (%) with 1.70 m assumed, and with W115's inferred height (``subject_height(infer=True)`` of the
    meta.json without height_m, written in as its height_m: the option is not the default, W115 failed its rule)."""
    pipe = get_pipeline("waist-pll")
    implied = subject_height(with_height(session, None).meta, infer=True)[0]
    return tuple(float(pipe(with_height(session, h)).summary(session)["distance_error_pct"]) for h in (1.70, implied))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kids", default="1000-1039")
    ap.add_argument("--adults", default="1040-1059")
    ap.add_argument("--copy", type=Path, default=Path("/tmp/trial_peds/real/T5_fr_noh"))
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    lines = ["# W115 height from the sensor height (experiments/waist_kid_height.py)", "",
             "| session | error % with 1.70 m | error % W115 |", "|---|---|---|"]
    groups: dict[str, list] = {"kids": [], "adults": []}
    first = span(args.kids).start
    for u in span(args.kids):
        e = errors(walk(child(u, child_age(u, first)), "A", "normal"))
        groups["kids"].append(e)
        lines.append(f"| user {u} age {child_age(u, first)} | {e[0]:+.2f} | {e[1]:+.2f} |")
        print(lines[-1], flush=True)
    for u in span(args.adults):
        e = errors(walk(UserProfile.from_seed(u), "A", "normal"))
        groups["adults"].append(e)
        lines.append(f"| user {u} adult | {e[0]:+.2f} | {e[1]:+.2f} |")
        print(lines[-1], flush=True)
    if args.copy.is_dir():
        e = errors(read_session(args.copy))
        lines.append(f"| {args.copy.name} | {e[0]:+.2f} | {e[1]:+.2f} |")
        print(lines[-1], flush=True)
    k = np.abs(np.array(groups["kids"]))
    a = np.abs(np.array(groups["adults"]))
    lines += ["", f"kids: |error| lower with W115 on {int(np.sum(k[:, 1] < k[:, 0]))} of {len(k)}; median |error| "
              f"{np.median(k[:, 0]):.2f} -> {np.median(k[:, 1]):.2f} %",
              f"adults: median |error| {np.median(a[:, 0]):.2f} -> {np.median(a[:, 1]):.2f} %"]
    print("\n".join(lines[-2:]), flush=True)
    (ROOT / "experiments" / "results" / "waist_kid_height.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
