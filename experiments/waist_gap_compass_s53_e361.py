"""Decision E361 (session 53, I4): the real check of the compass re-anchoring after a waist gyroscope gap.

    python experiments/waist_gap_compass_s53_e361.py real [DIR ...]    # E361's arms: before / after
    ARMS=before,e361,e362 python experiments/waist_gap_compass_s53_e361.py real   # E362: the Earth's-field gate too
    ARMS=before,e364,e362,e364c python experiments/waist_gap_compass_s53_e361.py real   # E364 (line alone, compass)

The real lower-back recordings (datasets/external/mobgap_*, /work/shared/data/mobgap_*; the same recording once)
have no foot unit, so ``track --streaming`` cannot run on them: the streamed chain is driven here by the kernels the
live ``Tracker`` and ``track --streaming`` call (``kernels.stride.CycleGapLine``, ``kernels.gap_compass.GapCompass``)
on each foot's INDIP reference strides (steps.csv, IC to IC, consecutive ones of one walking bout). For every run of
two consecutive strides with at least two strides before it in its bout, a copy of the recording loses every waist
sample inside those two strides (an artificial gap of ~2 strides), and the heading change from the end of the stride
before the gap to the end of the stride after it is compared with the same change in the recording without the gap
(the waist gyroscope integrated): |difference| before (E354's line) and after (E361), median and max per recording
and pooled. Never tuned on: the rule's data are the fresh simulated users."""

from __future__ import annotations

import csv
import math
import os
import sys
from pathlib import Path

import numpy as np

from pdrlearn.kernels.gap_compass import GapCompass
from pdrlearn.kernels.stride import CycleGapLine, waist_bridge_yaw, waist_gap_s

ROOT = Path(__file__).resolve().parents[1]
DIRS = [ROOT / "datasets" / "external", Path("/work/main/datasets/external"), Path("/work/shared/data")]
NAMES = ("wAccelerometer", "wGyroscope", "wMagneticField")
#: the arms: E354's line ("before"), E361's compass without E362's field gate ("after" / "e361"), with it ("e362")
ARMS = {"before": None, "after": {"field_ut": None}, "e361": {"field_ut": None}, "e362": {}}
#: decision E364 (session 53, FB): these arms run E354's line with the rate after limited to the rate before's size
#: (``CycleGapLine(limit_after=True)``, E364's default); the others run E354's line as it was
LIMITED = {"e364": None, "e364c": {}}
ARMS.update(LIMITED)


def load(rec: Path) -> dict:
    out = {}
    for n in NAMES:
        a = np.loadtxt(rec / f"{n}.csv", delimiter=",", skiprows=1)
        out[n] = (a[:, 0] / 1000.0, a[:, 1:4])
    return out


def cut(streams: dict, a: float, b: float) -> dict:
    """The streams without their samples strictly inside ``(a, b)`` s (the strides' own ends kept)."""
    return {n: (t[~((t > a + 1e-6) & (t < b - 1e-6))], v[~((t > a + 1e-6) & (t < b - 1e-6))])
            for n, (t, v) in streams.items()}


def chains(rec: Path) -> list[list[tuple[float, float]]]:
    """Each foot's runs of consecutive reference strides (s) inside one walking bout."""
    rows = list(csv.DictReader(open(rec / "steps.csv")))
    out = []
    for foot in sorted({r["foot"] for r in rows}):
        mine = sorted((float(r["start_ms"]) / 1000, float(r["end_ms"]) / 1000, r.get("wb_id")) for r in rows
                      if r["foot"] == foot and r["start_ms"] and r["end_ms"])
        run: list[tuple[float, float]] = []
        for k, (a, b, wb) in enumerate(mine):
            if run and (abs(a - run[-1][1]) > 0.02 or wb != mine[k - 1][2]):
                out.append(run)
                run = []
            run.append((a, b))
        out.append(run)
    return [r for r in out if len(r) >= 5]


def heading_chain(stream, strides, compass: dict | None, limit_after: bool = False) -> list[float]:
    """The streamed heading after each stride: the waist's turn from the previous stride's end (a waist gap inside it
    counting 0), E354's line across a gap (held at the gap, taken by the stride after; ``limit_after``: E364's) and,
    with ``compass``, E361's turn (``compass``: :class:`GapCompass`'s keywords; None: no compass)."""
    line = CycleGapLine(limit_after=limit_after)
    anchor, h, out, prev = GapCompass(**(compass or {})), 0.0, [], None
    for a, b in strides:
        lo = a if prev is None else prev
        if prev is not None and waist_gap_s(stream, prev, a) > 0:
            line.hold(stream, prev, a)  # decision E365: the rate before is the last stride noted
        dyaw = waist_bridge_yaw(stream, lo, b, gap_line=False) + line.take(stream, a, b)
        line.note(stream, a, b)
        if compass is not None:
            dyaw += anchor.stride(stream, a, b, dyaw, line.spread)
        h += dyaw
        out.append(h)
        prev = b
    return out


def real(dirs: list[Path]) -> None:
    arms = os.environ.get("ARMS", "before,after").split(",")
    seen, pooled = set(), {a: [] for a in arms}
    for d in dirs:
        for rec in sorted(d.glob("mobgap_*")):
            if rec.name in seen or not (rec / "steps.csv").exists():
                continue
            seen.add(rec.name)
            full = load(rec)
            errs = {a: [] for a in arms}
            for run in chains(rec):
                for j in range(2, len(run) - 2):
                    kept = run[:j] + run[j + 2:]  # the 2 strides inside the gap leave no row
                    gap = cut(full, run[j][0], run[j + 1][1])
                    ref = heading_chain(full.__getitem__, run, None)
                    true = ref[j + 2] - ref[j - 1]
                    for name in arms:
                        h = heading_chain(gap.__getitem__, kept, ARMS[name], name in LIMITED)
                        e = math.degrees(math.remainder((h[j] - h[j - 1]) - true, 2 * math.pi))
                        errs[name].append(abs(e))
            if not errs["before"]:
                continue
            line = [f"{rec.name:28s} n={len(errs['before']):3d}"]
            for name in arms:
                v = np.array(errs[name])
                pooled[name] += list(v)
                line.append(f"{name} median |diff| {np.median(v):6.2f} deg, max {np.max(v):6.2f}")
            print("  ".join(line))
    for name in arms:
        v = np.array(pooled[name])
        print(f"pooled {name:6s} n={len(v)} median |diff| {np.median(v):.2f} deg, max {np.max(v):.2f} deg")


if __name__ == "__main__":
    if sys.argv[1] == "real":
        real([Path(p) for p in sys.argv[2:]] or DIRS)
