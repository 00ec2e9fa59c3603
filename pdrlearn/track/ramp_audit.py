"""Decisions L568-L572 (docs/decisions/localization.md): a route audit's view of the ramps and stair flights -
``ramp_runs.csv`` (one row per run and per landing of each ramps.csv ramp, L568), the ramps' compliance flags
against the ADA 2010 ramp limits (L569), the ramps' and flights' end positions and their map features (GeoJSON
LineStrings, GPX waypoints; L570) and the console line (L571).

A landing is measured in whole strides (a foot stride of 1.2-1.7 m): its length is resolved to one stride only,
so a 1.0 m landing can read 1.7 m (trial s41 T3, F4). The flags compare the measured grades and rises with the
limits; a grade read 0.5-1 point off (L301's measurements) can decide them."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

#: decision L569: the steepest running slope of a ramp run, 1:12 (ADA 2010 sec. 405.2)
GRADE_1_12_PCT = 100.0 / 12.0
#: decision L569: a walking surface steeper than 1:20 is a ramp (ADA 2010 sec. 403.3 / 405.1)
GRADE_1_20_PCT = 100.0 / 20.0
#: decision L569: the largest rise of one ramp run, 30 in = 760 mm (ADA 2010 sec. 405.6)
RUN_MAX_RISE_M = 0.76
#: decision L588: a grade within this many points of 1:12 or 1:20 is near the limit: L301's grades read 0.5-1 point
#: off (T4: a true 1:12 ramp's runs read 9.23 / 8.97 %, one stride short, so flagged over 1:12)
NEAR_GRADE_PCT = 1.0
#: decision L588: a run's rise within this (m) of 0.76 m is near the limit: one stride more or less at a run's end
#: (T4: fused_climb read true 0.75 m runs as 0.818 / 0.789 m; the foot's heights 0.759 / 0.741 m)
NEAR_RISE_M = 0.07
#: decision L569: ramps.csv's (and ramp_runs.csv's run rows') flags; L588's ``near_limit``
FLAG_COLUMNS = ("over_1_12", "over_1_20", "run_rise_over_0_76", "near_limit")
#: decision L570: the end positions added to ramps.csv, ramp_runs.csv and stairs.csv (lat/lon empty without a
#: geodetic start, ``--start``)
POSITION_COLUMNS = ("start_x_m", "start_y_m", "start_lat", "start_lon", "end_x_m", "end_y_m", "end_lat", "end_lon")
#: decision L568: ramp_runs.csv's columns
RUN_TABLE_COLUMNS = ("ramp", "part", "kind", "start_s", "end_s", "horizontal_m", "rise_m", "grade_pct", "n_steps",
                     *FLAG_COLUMNS, *POSITION_COLUMNS)


def compliance_flags(grade_pct, rise_m) -> dict:
    """Decision L569: ``over_1_12`` / ``over_1_20`` (|``grade_pct``| over :data:`GRADE_1_12_PCT` /
    :data:`GRADE_1_20_PCT`) and ``run_rise_over_0_76`` (|``rise_m``| over :data:`RUN_MAX_RISE_M`); None for a value
    that is not finite. A pure kernel."""
    def over(v, limit):
        v = float(v) if v is not None else math.nan
        return bool(abs(v) > limit) if math.isfinite(v) else None

    return {"over_1_12": over(grade_pct, GRADE_1_12_PCT), "over_1_20": over(grade_pct, GRADE_1_20_PCT),
            "run_rise_over_0_76": over(rise_m, RUN_MAX_RISE_M)}


def near_limit(grade_pct, rise_m) -> bool | None:
    """Decision L588: True where |``grade_pct``| is within :data:`NEAR_GRADE_PCT` of 1:12 or 1:20 or |``rise_m``|
    within :data:`NEAR_RISE_M` of :data:`RUN_MAX_RISE_M` (a flag a stride more or less can flip); None when neither
    value is finite. A pure kernel."""
    vals = [(v, lim, tol) for v, lims, tol in ((grade_pct, (GRADE_1_12_PCT, GRADE_1_20_PCT), NEAR_GRADE_PCT),
                                               (rise_m, (RUN_MAX_RISE_M,), NEAR_RISE_M))
            for lim in lims if v is not None and math.isfinite(float(v))]
    if not vals:
        return None
    return any(abs(abs(float(v)) - lim) <= tol for v, lim, tol in vals)


def audit_flags(grade_pct, rise_m) -> dict:
    """Decisions L569, L588: :func:`compliance_flags` and :func:`near_limit` of a run's (or a ramp's steepest run's)
    grade and rise: the :data:`FLAG_COLUMNS`."""
    return {**compliance_flags(grade_pct, rise_m), "near_limit": near_limit(grade_pct, rise_m)}


def trajectory_values(t, v, times, *, held: bool = False) -> np.ndarray:
    """Decisions L570, L585: the values ``v`` of trajectory rows at times ``t`` (s), read at ``times`` from the rows
    with finite ``t`` and ``v``: linearly interpolated, or with ``held`` the row at or before each time (a
    trajectory row is the END of a stride, so a stride's start time lies between the row before it and its own
    row, after any standstill: the walker is at the row before until the next stride ends; decision L585). NaN
    outside the rows' time span or without two such rows. A pure kernel."""
    t, v = np.asarray(t, dtype=float), np.asarray(v, dtype=float)
    times = np.asarray(times, dtype=float)
    ok = np.isfinite(t) & np.isfinite(v)
    if ok.sum() < 2 or not len(times):
        return np.full(len(times), np.nan)
    order = np.argsort(t[ok], kind="stable")
    tt, vv = t[ok][order], v[ok][order]
    inside = (times >= tt[0]) & (times <= tt[-1])
    if held:  # decision L585: the position held until the next stride ends
        vals = vv[np.clip(np.searchsorted(tt, np.where(inside, times, tt[0]), "right") - 1, 0, len(tt) - 1)]
    else:
        vals = np.interp(times, tt, vv)
    return np.where(inside, vals, np.nan)


def positions_at(trajectory: pd.DataFrame | None, times, *, held: bool = False) -> dict[str, np.ndarray]:
    """Decisions L570, L585: ``x`` / ``y`` (m) and ``lat`` / ``lon`` of ``trajectory`` (trajectory.csv: ``t``,
    ``x``, ``y``, and ``lat`` / ``lon`` with a geodetic start) at ``times`` (s) by :func:`trajectory_values`
    (interpolated, or with ``held`` the row at or before each time); NaN without a trajectory, outside its time
    span or without two rows with finite values."""
    times = np.asarray(times, dtype=float)
    out = {k: np.full(len(times), np.nan) for k in ("x", "y", "lat", "lon")}
    if trajectory is None or "t" not in trajectory or not len(times):
        return out
    t = pd.to_numeric(trajectory["t"], errors="coerce").to_numpy(float)
    for k in out:
        if k in trajectory:
            out[k] = trajectory_values(t, pd.to_numeric(trajectory[k], errors="coerce").to_numpy(float), times,
                                       held=held)
    return out


def with_end_positions(table: pd.DataFrame, trajectory: pd.DataFrame | None) -> pd.DataFrame:
    """Decisions L570, L585: ``table`` (rows with ``start_s`` / ``end_s``) with :data:`POSITION_COLUMNS` filled
    from :func:`positions_at`: a start at the trajectory row at or before ``start_s`` (L585: where the walker
    stood until the first stride ended), an end interpolated at ``end_s`` (a stride's end is a row). The columns
    are always written; empty without a trajectory or a geodetic start."""
    out = table.copy()
    for end in ("start", "end"):
        at = positions_at(trajectory, pd.to_numeric(out[f"{end}_s"], errors="coerce").to_numpy(float)
                          if len(out) else [], held=end == "start")
        out[f"{end}_x_m"], out[f"{end}_y_m"] = at["x"], at["y"]
        out[f"{end}_lat"], out[f"{end}_lon"] = at["lat"], at["lon"]
    return out


def ramp_run_table(steps: pd.DataFrame, info: dict | None, trajectory: pd.DataFrame | None = None, *,
                   found=None) -> pd.DataFrame:
    """``ramp_runs.csv`` (decision L568): for each ramp of ramps.csv (the same :func:`pdrlearn.track.grade.ramp_runs`
    ramps, numbered alike) one row per run (``kind`` run) and per landing between two runs (``kind`` landing), in
    walking order (``part`` from 1 within the ramp): the first row's ``start_s`` and last row's ``end_s``, the
    rows' horizontal length, rise (summed ``dz_m``), grade (100 rise / horizontal), rows, L569's flags (a run's own;
    empty on a landing) and L570's end positions. A landing's length is whole strides: resolved to one stride.
    ``found``: :func:`pdrlearn.track.grade.track_ramps` of these rows, when the caller has it (session 42: a written
    track finds its ramps once)."""
    from pdrlearn.track.grade import track_ramps

    ramps, length, dz = track_ramps(steps, info) if found is None else found
    start, end = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    rows = []
    for k, r in enumerate(ramps, start=1):
        parts, prev = [], None
        for a, b in r["runs"]:
            if prev is not None and a > prev + 1:
                parts.append(("landing", prev + 1, a - 1))
            parts.append(("run", a, b))
            prev = b
        for p, (kind, a, b) in enumerate(parts, start=1):
            run_l, rise = float(length[a:b + 1].sum()), float(dz[a:b + 1].sum())
            grade = 100.0 * rise / run_l if run_l > 0 else np.nan
            flags = audit_flags(grade, rise) if kind == "run" else dict.fromkeys(FLAG_COLUMNS)
            rows.append({"ramp": k, "part": p, "kind": kind, "start_s": float(start[a]), "end_s": float(end[b]),
                         "horizontal_m": run_l, "rise_m": rise, "grade_pct": grade, "n_steps": b - a + 1, **flags})
    return with_end_positions(pd.DataFrame(rows, columns=list(RUN_TABLE_COLUMNS[:-len(POSITION_COLUMNS)])),
                              trajectory)[list(RUN_TABLE_COLUMNS)]


def _value(v):
    """A table cell as JSON: None for NaN / missing, a plain bool / int / float otherwise."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)) or v is pd.NA:
        return None
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return round(float(v), 3)
    return v


def route_features(tables: dict) -> list[dict]:
    """Decision L570: the map features of the ramps.csv and stairs.csv rows in ``tables``, in time order: ``start_s``,
    ``end_s``, a ``name`` (``ramp 1 up 8.4 %``, ``stairs 1 down -1.0 m``) and the ``properties`` (``kind`` ramp or
    stairs, ``number``, ``direction``, ``grade_pct`` (a ramp's mean grade; empty for stairs), ``max_run_grade_pct``,
    ``rise_m``, ``horizontal_run_m``, ``landings``, L569's flags; a flight's ``n_strides`` and ``n_stairs``)."""
    ramps, stairs = tables.get("ramps.csv"), tables.get("stairs.csv")
    out = []
    for r in ([] if ramps is None else ramps.to_dict("records")):
        props = {"kind": "ramp", "number": r.get("ramp"), "direction": r.get("direction"),
                 "grade_pct": r.get("mean_grade_pct"), "max_run_grade_pct": r.get("max_run_grade_pct"),
                 "rise_m": r.get("rise_m"), "horizontal_run_m": r.get("horizontal_run_m"),
                 "landings": r.get("landings"), **{c: r.get(c) for c in FLAG_COLUMNS}}
        props = {k: _value(v) for k, v in props.items()}
        name = f"ramp {props['number']} {props['direction']} {props['grade_pct']:.1f} %" \
            if props["grade_pct"] is not None else f"ramp {props['number']}"
        out.append({"start_s": float(r["start_s"]), "end_s": float(r["end_s"]), "name": name, "properties": props})
    for r in ([] if stairs is None else stairs.to_dict("records")):
        props = {k: _value(v) for k, v in {"kind": "stairs", "number": r.get("flight"), "direction": r.get("direction"),
                                           "grade_pct": None, "rise_m": r.get("height_m"),
                                           "n_strides": r.get("n_strides"), "n_stairs": r.get("n_stairs")}.items()}
        rise = f" {props['rise_m']:+.2f} m" if props["rise_m"] is not None else ""
        out.append({"start_s": float(r["start_s"]), "end_s": float(r["end_s"]),
                    "name": f"stairs {props['number']} {props['direction']}{rise}", "properties": props})
    return sorted(out, key=lambda f: f["start_s"])


def ramps_line(ramps: pd.DataFrame | None, strides: tuple[int, int] | None = None) -> str | None:
    """Decision L571: the console line of a track's ramps.csv - ``ramps N (steepest X %, rise Y m; ramps.csv)``,
    the steepest run's grade (in size) and that ramp's rise, with how many runs are over 1:12 when any and, when a
    ramp is ``near_limit`` (L588), "N near the limit: measure them"; decision L705: with ``strides`` (the summary's
    ``n_ramp_strides_up`` / ``_down``) "U / D ramp strides"; None without a ramp."""
    if ramps is None or not len(ramps):
        return None
    g = pd.to_numeric(ramps["max_run_grade_pct"], errors="coerce").abs()
    if not g.notna().any():
        return None
    i = int(g.fillna(-1.0).to_numpy(float).argmax())
    over = int(ramps["over_1_12"].eq(True).sum()) if "over_1_12" in ramps else 0
    near = int(ramps["near_limit"].eq(True).sum()) if "near_limit" in ramps else 0  # decision L588
    return (f"ramps {len(ramps)} (steepest {g.iloc[i]:.1f} %, rise {float(ramps['rise_m'].iloc[i]):+.2f} m"
            + (f"; {over} over 1:12" if over else "")
            + (f"; {near} near the limit: measure {'it' if near == 1 else 'them'}" if near else "")
            + (f"; {strides[0]} / {strides[1]} ramp strides" if strides else "") + "; ramps.csv)")  # decision L705
