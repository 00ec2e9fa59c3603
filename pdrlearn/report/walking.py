"""clinical.md's walking line of any recording (decision W515, docs/decisions/waist.md; trial T1 F7): the steps,
walking time, walking bouts with their lengths, the distance and the ramps, read from what ``track`` already wrote
(summary.json, bouts.csv, ramps.csv) - no new measure. A recording of an hour or more also gets W448's daily-living
block (rates per hour, posture times)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.report.daily_living import _both_feet, _csv, _estimated
from pdrlearn.waist.plausibility import CONTACTS_FLAG, withheld_steps_text

#: decision W515: up to this many bouts their lengths are listed one by one (a ward session's few walks); more get
#: the median and the longest (a day's hundreds would drown the line)
MAX_BOUTS_LISTED = 8


def _bout_lengths(bouts: pd.DataFrame | None) -> str:
    if bouts is None or not len(bouts) or "distance_m" not in bouts:
        return ""
    d = pd.to_numeric(bouts["distance_m"], errors="coerce").to_numpy(float)
    if not np.isfinite(d).any():
        return ""
    if len(d) <= MAX_BOUTS_LISTED:
        return " (" + " / ".join("-" if not np.isfinite(x) else f"{x:.1f}" for x in d) + " m)"
    return f" (median {np.nanmedian(d):.1f} m, longest {np.nanmax(d):.1f} m)"


def _ramps(ramps: pd.DataFrame | None, strides: bool) -> str:
    """Ramps up / down with their strides (a foot track's ramps.csv ``n_steps`` counts the tracked foot's strides,
    ``pdrlearn columns ramps``) or steps (lower back)."""
    if ramps is None or not len(ramps) or "direction" not in ramps:
        return ""
    word = "strides" if strides else "steps"
    parts = []
    for way in ("up", "down"):
        r = ramps[ramps["direction"] == way]
        if not len(r):
            continue
        n = pd.to_numeric(r["n_steps"], errors="coerce") if "n_steps" in r else pd.Series(dtype=float)
        counts = ", ".join(f"{v:.0f}" for v in n if np.isfinite(v))
        parts.append(f"{len(r)} {way}" + (f" ({counts} {word})" if counts else ""))
    return "; ramps: " + ", ".join(parts) if parts else ""


def walking_line(summary: dict, folder: Path, unit: str, *, distance_given: bool = True,
                 uncalibrated: bool = False) -> str | None:
    """Decision W515: ``- Walking: 206 steps, 187.5 s walking in 4 bouts (12.0 / 12.6 / 16.1 / 16.3 m), 57.0 m;
    ramps: 1 up (18 strides), 1 down (17 strides) (foot unit)`` for a track ``folder`` with steps; None without.
    ``distance_given`` False (an uncalibrated lower back under the validated speed, W446) leaves the metres out and
    says why; ``uncalibrated`` (a lower back without ``calibrate``'s PARAMS) tags the metres given as the gait speed
    line tags its speed (decision C222: trial T1 F5 read the line's 351.4 m beside a corridor's 341 m untagged)."""
    withheld = withheld_steps_text(summary)  # decision C246: W476's contacts are no steps
    counts = {k: [summary.get(k)] for k in ("n_steps", "n_steps_both_feet")}
    steps = _both_feet(pd.DataFrame(counts), summary).iloc[0] if summary.get("n_steps") is not None else np.nan
    if not withheld and (pd.isna(steps) or steps <= 0):
        return None
    approx = _estimated(summary)
    text = (f"- Walking: steps not given, {withheld}" if withheld
            else f"- Walking: {'~' if approx else ''}{int(steps)} steps")
    walking = summary.get("walking_time_s")
    if walking is not None:
        text += f", {float(walking):.1f} s walking"
    bouts = _csv(folder / "bouts.csv")
    n_bouts = len(bouts) if bouts is not None else summary.get("n_walking_bouts")
    if n_bouts:
        text += f" in {n_bouts} bout{'s' if n_bouts != 1 else ''}"
        if distance_given:
            text += _bout_lengths(bouts)
    if distance_given and summary.get("distance_m") is not None:
        text += f", {float(summary['distance_m']):.1f} m"
    text += _ramps(_csv(folder / "ramps.csv"), strides=summary.get("n_steps_counts") == "strides of the tracked foot")
    notes = [unit] + (["steps 2 per stride of the tracked foot"] if approx else [])
    if not distance_given:
        notes.append("distance not given: uncalibrated lower back under the validated speed (W446)")
    elif uncalibrated:  # decision C222
        notes.append("uncalibrated: metres from step lengths by body height (W169)")
    if withheld and distance_given:
        notes.append(CONTACTS_FLAG)  # decision C247
    return f"{text} ({'; '.join(notes)})"
