"""clinical.md's stair and step-time asymmetry lines of one track (decision C190, docs/decisions/cohort.md; trial T1
F6): what the track's console printed - its stair flights (stairs.csv, L432) and its step-time asymmetry (summary.json,
L121 / L416 with L490's standard error) - read from what ``track`` wrote, for every session block, not only for a
``gait`` pair of two foot units (L561, W438). No new measure."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.report.daily_living import _csv
from pdrlearn.track.labelled_asymmetry import asymmetry_flags, short_step_withheld


def _number(v) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) and np.isfinite(v) else None


def _direction(rows: pd.DataFrame, way: str) -> str:
    """One direction's flights of stairs.csv: count, stairs (``n_stairs`` summed when every flight has it, else the
    stair strides), height, time and stairs (or strides) per minute over that time."""
    def col(c: str) -> np.ndarray:
        return pd.to_numeric(rows[c], errors="coerce").to_numpy(float) if c in rows else np.full(len(rows), np.nan)

    stairs, strides, height, time = col("n_stairs"), col("n_strides"), col("height_m"), col("time_s")
    counted = bool(np.isfinite(stairs).all())
    n, word = (stairs, "stairs") if counted else (strides, "stair strides")
    parts = [f"{np.nansum(n):.0f} {word}"] if np.isfinite(n).any() else []
    if np.isfinite(height).any():
        parts.append(f"{abs(float(np.nansum(height))):.2f} m")
    if np.isfinite(time).all() and np.nansum(time) > 0:
        parts.append(f"{float(np.nansum(time)):.1f} s")
        if np.isfinite(n).all():
            parts.append(f"{60.0 * float(np.nansum(n)) / float(np.nansum(time)):.0f} {word}/min")
    k = len(rows)
    return f"{k} flight{'s' if k != 1 else ''} {way}" + (f" ({', '.join(parts)})" if parts else "")


def stairs_line(summary: dict, folder: Path, unit: str) -> str | None:
    """Decision C190: ``- Stairs: 1 flight up (12 stairs, 2.04 m, 16.0 s, 45 stairs/min); 1 flight down (...) (foot
    unit)`` from the track ``folder``'s stairs.csv, else summary.json's flight counts; None without a flight (a
    lower-back track has none, L440)."""
    up, down = (int(summary.get(k) or 0) for k in ("n_flights_up", "n_flights_down"))
    if not (up or down):
        return None
    table = _csv(folder / "stairs.csv")
    parts = []
    for way, n in (("up", up), ("down", down)):
        rows = table[table["direction"].astype(str) == way] if table is not None and "direction" in table else None
        if rows is not None and len(rows):
            parts.append(_direction(rows, way))
        elif n:
            strides = summary.get(f"n_stair_strides_{way}")
            parts.append(f"{n} flight{'s' if n != 1 else ''} {way}"
                         + (f" ({int(strides)} stair strides)" if _number(strides) is not None else ""))
    hint = "" if table is not None and "n_stairs" in table and table["n_stairs"].notna().any() else \
        "; stairs counted with track --stair-rise METRES"
    return f"- Stairs: {'; '.join(parts)} ({unit}{hint})"


def asymmetry_line(summary: dict, unit: str) -> str | None:
    """Decision C190: ``- Step-time asymmetry 31.4 % (standard error 5.6 points, uncertain: over 3 points; right
    longer, 0.556 / 0.764 s L/R) (foot + lower-back units)`` from summary.json's index (L121, L416), its standard error
    (L490) and the console's words for it (L671, L677); a lower-back index alone says its size is misread (L121).
    Decision W532: an index withheld at a child's short steps gives ``- Step-time asymmetry: not given (...)``
    with the reason's words. None without an index otherwise."""
    pct = _number(summary.get("step_time_asymmetry_pct"))
    short = short_step_withheld(summary)
    if pct is None and short:
        return f"- Step-time asymmetry: not given ({short}) (foot + lower-back units)"
    if pct is None:
        return None
    se = _number(summary.get("step_time_asymmetry_se_points"))
    if se is None and summary.get("step_count_withheld"):  # decision C247: the lower back's contacts are no steps
        return f"- Step-time asymmetry: not given (the lower back's contacts are no step count, W476, C247) ({unit})"
    notes = ([", ".join([f"standard error {se:.1f} points", *asymmetry_flags(pct, se)])] if se is not None
             else ["its size is misread by the lower back alone (L121)"])
    left, right = _number(summary.get("step_time_s_left")), _number(summary.get("step_time_s_right"))
    if left is not None and right is not None:
        side = "equal" if left == right else f"{'left' if left > right else 'right'} longer"
        notes.append(f"{side}, {left:.3f} / {right:.3f} s L/R")
    source = "foot + lower-back units" if se is not None and unit == "foot unit" else unit
    return f"- Step-time asymmetry {pct:.1f} % ({'; '.join(notes)}) ({source})"


def flight_times(folder: Path) -> dict[str, float]:
    """Decisions C273, C275: ``{"up": s, "down": s}``: the track ``folder``'s stairs.csv flights' ``time_s`` summed
    per direction (C190's line's times), a direction without a timed flight left out; {} without stairs.csv."""
    table = _csv(Path(folder) / "stairs.csv")
    if table is None or "direction" not in table or "time_s" not in table:
        return {}
    out = {}
    for way in ("up", "down"):
        time = pd.to_numeric(table.loc[table["direction"].astype(str) == way, "time_s"], errors="coerce")
        if len(time) and time.notna().all():
            out[way] = float(time.sum())
    return out
