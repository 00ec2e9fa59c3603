"""Decision L571: a track's route audit in `pdrlearn report` - its climb (summary.json: ascent, descent, storeys,
ramps, flights), its ramps (ramps.csv with L569's flags), their runs and landings (ramp_runs.csv, L568) and its stair
flights (stairs.csv), as one report section per track folder that has a ramp, a flight or an altitude that measures
a slope (``grade_source``). Read from what ``track`` wrote - no new measure."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from pdrlearn.io.plasys import read_table

#: decision L571: the summary keys of the climb table (those the summary has)
CLIMB_KEYS = ("distance_m", "distance_along_slope_m", "ascent_m", "descent_m", "ramps_stairs_ascent_m",
              "ramps_stairs_descent_m", "floors_up", "floors_down",
              "n_ramps", "max_ramp_grade_pct", "n_flights_up", "n_flights_down", "grade_source")
#: decision L571: ramps.csv's columns shown (those the file has)
RAMP_KEYS = ("ramp", "start_s", "end_s", "direction", "n_runs", "landings", "horizontal_run_m", "landing_m", "rise_m",
             "mean_grade_pct", "max_run_grade_pct", "max_run_rise_m", "over_1_12", "over_1_20", "run_rise_over_0_76",
             "near_limit")  # decision L588
#: decision L571: ramp_runs.csv's columns shown
RUN_KEYS = ("ramp", "part", "kind", "start_s", "end_s", "horizontal_m", "rise_m", "grade_pct", "over_1_12",
            "over_1_20", "run_rise_over_0_76", "near_limit")  # decision L588
#: decision L571: stairs.csv's columns shown
STAIR_KEYS = ("flight", "start_s", "end_s", "direction", "n_strides", "height_m", "n_stairs")


def _rows(path: Path, keys: tuple[str, ...]) -> pd.DataFrame | None:
    t = read_table(path) if path.is_file() else None
    if t is None or not len(t):
        return None
    return t[[c for c in keys if c in t.columns]]


def route_section(folder: Path, summary: dict, label: str):
    """Decision L571: the report section of one track ``folder`` (its ``summary``): the climb, ramps, ramp runs and
    stair flights tables; None when it has no ramp, no flight and no ``grade_source``."""
    from pdrlearn.report.build import Section

    ramps, runs = _rows(folder / "ramps.csv", RAMP_KEYS), _rows(folder / "ramp_runs.csv", RUN_KEYS)
    stairs = _rows(folder / "stairs.csv", STAIR_KEYS)
    if ramps is None and stairs is None and summary.get("grade_source") is None:
        return None
    climb = pd.DataFrame([{k: summary.get(k) for k in CLIMB_KEYS if k in summary}])
    tables = [("climb (summary.json)", climb)]
    if ramps is not None:
        tables.append(("ramps (ramps.csv; flags against 1:12, 1:20 and a run's 0.76 m rise, L569)", ramps))
    if runs is not None:
        tables.append(("ramp runs and landings (ramp_runs.csv; a landing's length is resolved to one stride)", runs))
    if stairs is not None:
        tables.append(("stair flights (stairs.csv)", stairs))
    return Section(f"Ramps, stairs and climb — {label}", tables=tables)
