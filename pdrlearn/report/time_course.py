"""Decision L386: a track's time course in `pdrlearn report` - distance, speed and cadence per period (periods.csv,
``track --per``), per lap (laps.csv, ``track --corridor``, L383) and the rests between walking bouts (bouts.csv) -
as one report section per track folder holding any of them, with a figure of distance and speed over time."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io.plasys import read_table

#: decision L386: periods.csv's columns the report shows (those the file has)
PERIOD_COLUMNS = ("period", "start_s", "end_s", "duration_s", "partial", "distance_m", "speed_mps",
                  "distance_corridor_m", "speed_corridor_mps",  # decision W563: the corridor's scale, beside
                  "median_cadence_spm", "median_speed_mps", "time_walking_s", "n_steps", "n_steps_counts")
#: decision L386: laps.csv's columns the report shows
LAP_COLUMNS = ("lap", "start_s", "end_s", "duration_s", "corridor_laps", "distance_m", "distance_source", "speed_mps",
               "rest_s", "n_steps")  # E98's speed_mps (a laps.csv written before it: speed_m_s renamed on reading)


def _read(path: Path) -> pd.DataFrame | None:
    return read_table(path) if path.is_file() else None


def rest_table(bouts: pd.DataFrame | None, turns: pd.DataFrame | None = None) -> pd.DataFrame | None:
    """Decision L386: the rests of a track between one bouts.csv row's end and the next one's start; decision L647:
    a gap's time in a turns.csv turn (widened by a step interval) is turning, and a gap is a rest only when at least
    :data:`~pdrlearn.track.rests.REST_MIN_S` is left (:func:`pdrlearn.track.rests.rests`): ``start_s`` / ``end_s``
    its rest's first and last instant, ``duration_s`` the rest's time; None without two bouts or without a rest."""
    from pdrlearn.track.rests import rests as gap_rests

    if bouts is None or len(bouts) < 2 or not {"start_s", "end_s"} <= set(bouts.columns):
        return None
    found = [gap for gap in gap_rests(bouts, turns) if gap]
    if not found:
        return None
    return pd.DataFrame({"rest": np.arange(1, len(found) + 1), "start_s": [g[0][0] for g in found],
                         "end_s": [g[-1][1] for g in found],
                         "duration_s": [sum(e - s for s, e in g) for g in found]})


def _with_speed(periods: pd.DataFrame) -> pd.DataFrame:
    """periods.csv with ``speed_mps`` (E98's name) = distance_m / duration_s (the period's mean speed, rests
    included)."""
    out = periods.copy()
    if {"distance_m", "duration_s"} <= set(out.columns):
        d = pd.to_numeric(out["duration_s"], errors="coerce")
        out["speed_mps"] = pd.to_numeric(out["distance_m"], errors="coerce") / d.where(d > 0)
    return out


def time_course_section(folder: Path, label: str):
    """Decision L386: the report section of one track ``folder`` (its periods.csv, laps.csv, bouts.csv's rests);
    None when it has none of them."""
    from pdrlearn.report.build import Section

    periods, laps = _read(folder / "periods.csv"), _read(folder / "laps.csv")
    laps = laps.rename(columns={"speed_m_s": "speed_mps"}) if laps is not None else None  # E98
    bouts = _read(folder / "bouts.csv")
    rests = rest_table(bouts, _read(folder / "turns.csv"))  # decision L647: a turn is not a rest
    from pdrlearn.report.travel import travel_bouts

    travel = travel_bouts(bouts)  # decision L582: bouts.csv's backward / side strides per bout
    if periods is None and laps is None and rests is None and travel is None:
        return None
    tables, series = [], []
    if periods is not None and len(periods):
        p = _with_speed(periods)
        tables.append(("per period (periods.csv)", p[[c for c in PERIOD_COLUMNS if c in p.columns]]))
        series.append(("period", p))
    if laps is not None and len(laps):
        tables.append(("per lap (laps.csv)", laps[[c for c in LAP_COLUMNS if c in laps.columns]]))
        series.append(("lap", laps))
    if rests is not None:
        tables.append(("rests between walking bouts (bouts.csv)", rests))
    if travel is not None:
        tables.append(("walking bouts by travel direction (bouts.csv)", travel))
    plots = []
    if series:
        name = "".join(c if c.isalnum() else "_" for c in label)[:40]
        test = walk_test_span(folder)  # decision C231: the walk test's start and end marked
        plots.append(("distance and speed over time (periods.csv, laps.csv)"
                      + ("; dashed: the walk test's start and end" if test else ""), f"time_course_{name}.png",
                      lambda path: plot_time_course(series, rests, path, test=test)))
    return Section(f"Time course — {label}", tables=tables, plots=plots)


def walk_test_span(folder: Path) -> tuple[float, float] | None:
    """Decision C231: ``(start, end)`` (s, the track's clock) of the timed walk test of the track in ``folder``
    (summary.json ``walk_test_start_s`` and + ``walk_test_duration_s``); None without one or without a readable
    summary.json."""
    import json

    try:
        summary = json.loads((Path(folder) / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    start = summary.get("walk_test_start_s") if isinstance(summary, dict) else None
    dur = summary.get("walk_test_duration_s") if isinstance(summary, dict) else None
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in (start, dur)) or dur <= 0:
        return None
    return float(start), float(start) + float(dur)


def plot_time_course(series: list[tuple[str, pd.DataFrame]], rests: pd.DataFrame | None, path: Path, *,
                     test: tuple[float, float] | None = None) -> bool:
    """Decision L386: distance (m) and speed (m/s) of each period / lap drawn as steps over the track's time, the
    rests shaded; decision C231: with ``test`` (the walk test's start and end, s) a dashed line at each; False (no
    figure) when no row has a distance."""
    from pdrlearn.mplconfig import ensure_config_dir

    ensure_config_dir()  # decision B226
    from pdrlearn.plots import new_figure, save_atomic

    drawn = [(kind, df) for kind, df in series if {"start_s", "end_s", "distance_m"} <= set(df.columns)
             and pd.to_numeric(df["distance_m"], errors="coerce").notna().any()]
    if not drawn:
        return False
    fig, axes = new_figure(2, 1, figsize=(8, 5), sharex=True, squeeze=False)
    for kind, df in drawn:
        a, b = df["start_s"].to_numpy(float), df["end_s"].to_numpy(float)
        dist = pd.to_numeric(df["distance_m"], errors="coerce").to_numpy(float)
        speed = dist / np.where(b > a, b - a, np.nan)
        for ax, v in ((axes[0][0], dist), (axes[1][0], speed)):
            ax.stairs(v, np.r_[a, b[-1]], label=f"per {kind}")  # contiguous rows: each one's start, the last end
    # decision W448: distance / the whole period, rests included - not a gait speed (T2 read 0.004 m/s beside one)
    for ax, label in ((axes[0][0], "distance (m)"), (axes[1][0], "distance / time (m/s),\nrests included")):
        for r in (rests.itertuples() if rests is not None else []):
            ax.axvspan(r.start_s, r.end_s, color="0.85", zorder=0)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    if test is not None:  # decision C231: the walk test's start and end (L644's clock of its duration)
        from pdrlearn.track.corridor import clock_text

        for ax in (axes[0][0], axes[1][0]):
            for x, color, text in ((test[0], "0.2", "walk test start"),
                                   (test[1], "C3", f"walk test end ({clock_text(test[1] - test[0])})")):
                ax.axvline(x, color=color, linestyle="--", linewidth=1.0, label=text if ax is axes[0][0] else None)
    axes[0][0].legend(fontsize=8)
    axes[1][0].set_xlabel("time (s; rests between bouts shaded)")
    save_atomic(fig, Path(path))
    return True
