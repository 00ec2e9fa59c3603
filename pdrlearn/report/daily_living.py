"""clinical.md's daily-living block of a long recording (decision W448, docs/decisions/waist.md): steps, walking
bouts, chair transfers and posture times, read from what ``track`` already wrote (summary.json, bouts.csv,
periods.csv) - no new measure."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.report.build import STEPS_COLUMN, step_count_columns
from pdrlearn.waist.plausibility import withheld_steps_text

#: decision W448: a recording this long (s) or longer gets the block (a supervised test lasts minutes); decision
#: C254: from 30 min (five 6-minute walks), not 1 h - a 59-min shift got none
DAILY_MIN_S = 1800.0
#: decision W448: a walking bout this long (s) or longer is counted apart (Mobilise-D style long bouts)
LONG_BOUT_S = 30.0
#: decision W448: the steps per period are listed when periods.csv has at most this many rows (a day of hours)
MAX_PERIODS_LISTED = 48
#: decision L95: the lowest cadence (steps/min) the pipelines are validated on
VALIDATED_MIN_SPM = 70.0


def _csv(path: Path) -> pd.DataFrame | None:
    try:
        return pd.read_csv(path) if path.is_file() else None
    except (OSError, ValueError, pd.errors.EmptyDataError):
        return None


def _h(seconds) -> str:
    s = float(seconds)
    return f"{s / 3600:.1f} h" if s >= 3600 else f"{s / 60:.0f} min"


def _per(per_s) -> str:
    per = float(per_s)
    return f"{per / 3600:g} h" if per % 3600 == 0 else f"{per / 60:g} min" if per % 60 == 0 else f"{per:g} s"


def _both_feet(table: pd.DataFrame, summary: dict) -> pd.Series:
    """Decision W458: the steps of both feet per row of ``table`` (the summary or periods.csv): its
    ``n_steps_both_feet``, else L103's reading of ``n_steps`` by the track's ``pipeline`` (a foot track's ``n_steps``
    counts strides of the tracked foot, 2 steps each)."""
    table = table.assign(pipeline=summary.get("pipeline"))
    out = step_count_columns(table)
    return pd.to_numeric(out[STEPS_COLUMN], errors="coerce") if STEPS_COLUMN in out else pd.Series(np.nan, table.index)


def _estimated(summary: dict) -> bool:
    """Decision W458 (L103): a foot track's step count is 2 per stride of the tracked foot, an estimate."""
    return summary.get("n_steps_counts") == "strides of the tracked foot" or (
        summary.get("n_steps_counts") is None and str(summary.get("pipeline")) in ("plasys", "runtime"))


def daily_living_lines(summary: dict, folder: Path) -> list[str]:
    """Decision W448: the daily-living lines of a track ``folder`` (its ``summary``) that spans
    :data:`DAILY_MIN_S` or more; none for a shorter one."""
    span = summary.get("time_span_s")
    if span is None or float(span) < DAILY_MIN_S:
        return []
    lines = []
    cad = summary.get("median_cadence_spm")
    # decision W458: steps of both feet, as the cadence beside it (a foot track's n_steps counts strides)
    counts = {k: [summary.get(k)] for k in ("n_steps", "n_steps_both_feet")}
    steps = _both_feet(pd.DataFrame(counts), summary).iloc[0] if summary.get("n_steps") is not None else np.nan
    approx = "~" if _estimated(summary) else ""
    withheld = withheld_steps_text(summary)  # decision C246: W476's contacts are no steps
    if withheld or not pd.isna(steps):
        caveat = ("; lower-back step count not validated below "
                  f"{VALIDATED_MIN_SPM:g} steps/min (L95)" if str(summary.get("pipeline")).startswith("waist")
                  and cad is not None and cad < VALIDATED_MIN_SPM else "")
        text = f"- Daily living over {_h(span)} recorded: "
        if withheld:
            text += f"steps not given, {withheld}"
        else:
            text += f"{approx}{int(steps)} steps ({3600 * steps / float(span):.0f} per hour"
            text += f", {86400 * steps / float(span):.0f} per day" if float(span) >= 86400 else ""
            text += "; 2 per stride of the tracked foot)" if approx else ")"
            text += with_turns_text(summary.get("n_steps_with_turns"), steps, span)  # decision W603
        walking = summary.get("walking_time_s")
        if walking is not None:
            text += f"; walking {float(walking) / 60:.1f} min"
        bouts = _csv(folder / "bouts.csv")
        if bouts is not None and len(bouts) and "duration_s" in bouts:
            d = pd.to_numeric(bouts["duration_s"], errors="coerce").to_numpy(float)
            text += (f" in {len(d)} walking bouts (median {np.nanmedian(d):.0f} s, longest {np.nanmax(d):.0f} s, "
                     f"{int((d >= LONG_BOUT_S).sum())} of {LONG_BOUT_S:g} s or more)")
        lines.append(text + caveat)
    if summary.get("n_sit_to_stand") is not None:
        text = f"- Transfers: {summary['n_sit_to_stand']} sit-to-stand"
        if summary.get("median_sit_to_stand_s") is not None:
            text += f" (median {summary['median_sit_to_stand_s']:.1f} s)"
        text += (f", {summary.get('n_stand_to_sit')} stand-to-sit, {summary.get('n_lie_down')} lie-down, "
                 f"{summary.get('n_get_up')} get-up")
        if summary.get("n_chair_walks"):
            text += f"; {summary['n_chair_walks']} chair-to-chair walk(s) (W445)"
        lines.append(text)
    post = [(k, summary.get(f"{k}_time_s")) for k in ("sitting", "standing", "lying", "unknown")]
    if any(v is not None for _, v in post[:3]):
        lines.append("- Posture: " + ", ".join(f"{k} {_h(v)}" for k, v in post if v is not None))
    periods = _csv(folder / "periods.csv")
    if periods is not None and 1 < len(periods) <= MAX_PERIODS_LISTED and (
            "n_steps" in periods or "n_steps_both_feet" in periods):
        n = _both_feet(periods, summary)  # decision W458: periods.csv's n_steps_both_feet, as the line above
        per = f" per {_per(summary['per_s'])}" if summary.get("per_s") else " per period"
        src = "periods.csv, ~2 per stride of the tracked foot" if _estimated(summary) else "periods.csv"
        counts = ("not given: the lower back's contacts are no step count (W476, C246)" if withheld  # C246
                  else ", ".join("-" if pd.isna(v) else f"{v:.0f}" for v in n))
        turned = pd.to_numeric(periods["n_steps_with_turns"], errors="coerce") if (
            "n_steps_with_turns" in periods and not withheld) else None
        if turned is not None and turned.notna().any() and not turned.fillna(n).equals(n.astype(float)):
            counts += "; with the turning steps on the spot (W603): " + ", ".join(
                "-" if pd.isna(v) else f"{v:.0f}" for v in turned)
        lines.append(f"- Steps{per} ({src}): {counts}")
    return lines


def with_turns_text(with_turns, steps, span) -> str:
    """Decision W603: the daily-living line's clause giving ``n_steps_with_turns`` (the detected ``steps`` and W331's
    turning steps on the spot) per hour of ``span`` s; "" when not given or no step was added."""
    if with_turns is None or pd.isna(with_turns) or pd.isna(steps) or int(with_turns) == int(steps):
        return ""
    return (f"; ~{int(with_turns)} steps ({3600 * float(with_turns) / float(span):.0f} per hour) with the turning "
            "steps on the spot the lower back does not detect (W331's estimate, W603)")
