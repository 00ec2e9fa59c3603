"""Decision L582: the backward and side strides, their distances and the turns in `pdrlearn report` and its
``--clinical`` summary, when a track has any (trial T1 F5: a physiotherapist's backward / side-step / turning
exercises came out of clinical.md as gait speed and cadence only).

The numbers are the track's own: summary.json ``n_backward_strides`` / ``backward_distance_m`` (L203, L484),
``n_side_strides`` / ``side_distance_m`` (L270, L484), ``forward_distance_m``, ``turn_count`` / ``turn_time_s``
(L104, L200) and bouts.csv's per-bout counts (L581). Counts are strides of the tracked foot (one stride = a step of
each foot), as the summary's.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

#: decision L582: the summary keys of report.md's "distance by travel direction" table (shown when a run has a
#: backward or side stride)
TRAVEL_COLUMNS = ("run", "distance_m", "forward_distance_m", "n_backward_strides", "backward_distance_m",
                  "n_side_strides", "side_distance_m", "turn_count", "turn_time_s")
#: decision L582: bouts.csv's columns of report.md's per-bout travel table
BOUT_TRAVEL_COLUMNS = ("bout", "start_s", "end_s", "duration_s", "n_strides", "distance_m", "direction",
                       "n_backward_strides", "n_side_strides")


def _count(v) -> int:
    try:
        return int(v) if v is not None and not pd.isna(v) else 0
    except (TypeError, ValueError):
        return 0


def _metres(v) -> str:
    try:
        return f"{float(v):.2f} m"
    except (TypeError, ValueError):
        return "? m"


def has_travel(row) -> bool:
    """Decision L582: a summary (or report row) with a backward or side stride."""
    return _count(row.get("n_backward_strides")) > 0 or _count(row.get("n_side_strides")) > 0


def travel_table(df: pd.DataFrame) -> pd.DataFrame | None:
    """Decision L582: report.md's per-run table of :data:`TRAVEL_COLUMNS`, the runs with a backward or side stride
    only; None without one (a forward walk's report is unchanged)."""
    if "n_backward_strides" not in df and "n_side_strides" not in df:
        return None
    keep = df.apply(has_travel, axis=1)
    if not keep.any():
        return None
    return df.loc[keep, [c for c in TRAVEL_COLUMNS if c in df.columns]]


def travel_bouts(bouts: pd.DataFrame | None) -> pd.DataFrame | None:
    """Decision L582: bouts.csv's :data:`BOUT_TRAVEL_COLUMNS` when any bout has a backward or side stride (L581's
    counts; a bouts.csv from before L581 has none); None otherwise."""
    if bouts is None or not len(bouts) or not {"n_backward_strides", "n_side_strides"} <= set(bouts.columns):
        return None
    if not bouts.apply(has_travel, axis=1).any():
        return None
    return bouts[[c for c in BOUT_TRAVEL_COLUMNS if c in bouts.columns]]


def _bout_text(row) -> str:
    parts = [f"{n} {what} stride(s)" for n, what in ((_count(row.get("n_backward_strides")), "backward"),
                                                     (_count(row.get("n_side_strides")), "side")) if n]
    n = _count(row.get("n_strides"))
    return f"bout {_count(row.get('bout'))} {row.get('direction')} ({', '.join(parts)} of {n}, " \
        f"{_metres(row.get('distance_m'))})"


def travel_lines(summary: dict, folder: Path, unit: str) -> list[str]:
    """Decision L582: clinical.md's lines for a track with backward or side strides or turns: the distance by
    travel direction with the stride counts, the bouts holding backward / side strides (bouts.csv, several bouts
    only), and the turns (count, median and total duration); [] when the track has none of them."""
    lines = []
    if has_travel(summary):
        parts = [f"forward {_metres(summary.get('forward_distance_m'))}"]
        for key, what in (("backward", "backward"), ("side", "sideways")):
            n = _count(summary.get(f"n_{key}_strides"))
            if n:
                parts.append(f"{what} {n} stride(s), {_metres(summary.get(f'{key}_distance_m'))}")
        lines.append(f"- Walking directions: {_metres(summary.get('distance_m'))} in all: " + "; ".join(parts)
                     + f" (strides of the {unit}: a step of each foot)")
        path = folder / "bouts.csv"
        bouts = travel_bouts(pd.read_csv(path)) if path.is_file() else None
        if bouts is not None and len(bouts) > 1:
            lines.append("  bouts with backward / side strides: "
                         + "; ".join(_bout_text(r) for _, r in bouts.iterrows() if has_travel(r)))
    turns = _count(summary.get("turn_count"))
    if turns:
        med, total = summary.get("median_turn_duration_s"), summary.get("turn_time_s")
        times = ", ".join(t for t in (f"median {med:.1f} s" if isinstance(med, int | float) else "",
                                      f"{total:.1f} s in all" if isinstance(total, int | float) else "") if t)
        deg = summary.get("turn_count_min_deg")
        lines.append(f"- Turns{f' of >= {deg:g} deg' if isinstance(deg, int | float) else ''}: {turns}"
                     f"{f' ({times})' if times else ''} ({unit})")
    return lines
