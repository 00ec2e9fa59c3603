"""Decision W129: how often the lower-back steps table's ``side`` (W20's lateral velocity, v > 0 = left, fixed a
priori) agrees with the reference foot.

For each track (``waist-pendulum`` and ``waist-pll``, offline, defaults) the detected contacts are matched one to one
to the reference initial contacts within 0.25 s (:func:`pdrlearn.steps.evaluate.match_events`); of the matched ones
it counts those with a decided side, and of those the ones whose side is the reference foot's. Real: the 9 mobgap
sessions (INDIP ``ics.csv`` ``foot``); simulated: users 1900-1919 (scenario ``"ABCD"[user % 4]``, normal speed,
100 Hz; ``extras["ics"]`` ``foot``).

Run: .venv/bin/python experiments/waist_sides.py [--external datasets/external] [--users 1900-1919]
Writes experiments/results/waist_sides.md; with --users other than the default, waist_sides_partial.md (decision W497,
steps decision 67: a smoke run never overwrites the committed result).
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track.waist import track_waist

ROOT = Path(__file__).resolve().parents[1]
from partial import parsed_with_names, partial_note  # noqa: E402

TOL_S = 0.25
#: decision W497: the option that makes a run partial (waist_sides_partial.md); --external is where the same
#: recordings are (as step_count.py's)
PARTIAL_OPTIONS = ("users",)
PIPELINES = ("waist-pendulum", "waist-pll")


def side_counts(session, pipeline: str) -> tuple[int, int, int]:
    """``(agree, decided, matched)`` of one track's contacts against ``session.extras["ics"]``."""
    steps = track_waist(session, pipeline=pipeline).steps
    ics = session.extras["ics"].dropna(subset=["ic_s"])
    ref_t = ics["ic_s"].to_numpy(float)
    ref_side = ics["foot"].astype(str).str.lower().to_numpy()
    i_d, i_r = match_events(steps["event_s"].to_numpy(float), ref_t, TOL_S)
    side = steps["side"].to_numpy(object)[i_d]
    dec = side != ""
    return int(np.sum(side[dec] == ref_side[i_r][dec])), int(dec.sum()), int(i_d.size)


def row(name: str, counts: list[tuple[int, int, int]]) -> str:
    a, d, m = (sum(c[k] for c in counts) for k in range(3))
    per = [c[0] / c[1] for c in counts if c[1]]
    return (f"| {name} | {a}/{d} = {a / d:.3f} | {d}/{m} = {d / m:.1%} | "
            f"{min(per):.3f}-{max(per):.3f} |" if d else f"| {name} | - | 0/{m} | - |")


def output_names(argv: list[str] | None = None):
    """The parsed options, the options that make the run partial and the file-name function (decision W497)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--users", default="1900-1919", help="simulated users, FIRST-LAST")
    return parsed_with_names(ap, argv, PARTIAL_OPTIONS)


def main(argv: list[str] | None = None) -> None:
    args, changed, out_name = output_names(argv)
    if changed:
        print(partial_note(changed))
    logging.disable(logging.WARNING)
    first, last = (int(x) for x in args.users.split("-"))
    real = sorted(p for p in args.external.glob("mobgap_*") if (p / "ics.csv").is_file())  # with reference ICs
    if not real:
        raise SystemExit(f"{args.external}: no mobgap sessions; run `pdrlearn fetch mobgap --out {args.external}`")
    lines = ["# Lower-back step side (W129) against the reference foot", "",
             f"Matched within {TOL_S} s; agreement among the decided sides; range over sessions / users.", "",
             "| data, pipeline | agree / decided | decided / matched | per-session range |", "|---|---|---|---|"]
    sims = [simulate("ABCD"[u % 4], u, rate_hz=100.0) for u in range(first, last + 1)]
    for pipeline in PIPELINES:
        reals = [(p.name, side_counts(read_session(p), pipeline)) for p in real]
        for name, c in reals:
            lines.append(row(f"{name.removeprefix('mobgap_')}, {pipeline}", [c]))
        lines.append(row(f"**mobgap, all {len(reals)}, {pipeline}**", [c for _, c in reals]))
        lines.append(row(f"**simulated users {first}-{last}, {pipeline}**", [side_counts(s, pipeline) for s in sims]))
    text = "\n".join(lines) + "\n"
    print(text)
    (ROOT / "experiments" / "results" / out_name("waist_sides.md")).write_text(text)


if __name__ == "__main__":
    main()
