"""trajectory.csv's ride-inclusive altitude and floor (decisions L630, L631; session 44 trial T3 finding F1).

A foot track's ``z`` integrates the strides' height only (L39); a lift or escalator ride, read from the waist
barometer while the feet stand (L378), is in rides.csv / steps.csv ``pause_dz_m`` and in the floor counts (L375), not
in ``z``. ``z_rides`` adds it; ``floor`` is the storey each row is on, from the same climbs the summary counts, so its
last value is the summary's ``storeys_changed`` (the "end floor") whenever no ride follows the last stride (L394).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: the columns :func:`with_floor_columns` appends to trajectory.csv (decisions L630, L631)
FLOOR_COLUMNS = ("z_rides", "floor")


def counted_rides(records: list[dict] | None) -> list[tuple[float, float]]:
    """Decision L630: ``(end_s, dz_m)`` of the rides (rides.csv's records) whose altitude change counts as a ride's:
    finite and of W231's ``RIDE_MIN_M`` or more, the rides steps.csv's ``pause_dz_m`` and the floors carry (L375)."""
    from pdrlearn.kernels.pause_ride import RIDE_MIN_M

    out = []
    for r in records or []:
        dz = r.get("dz_m")
        if dz is not None and np.isfinite(float(dz)) and abs(float(dz)) >= RIDE_MIN_M:
            out.append((float(r["end_s"]), float(dz)))
    return out


def ride_altitude(t, z, rides: list[tuple[float, float]]) -> np.ndarray:
    """Decision L630: ``z`` (m, per row at times ``t``) plus each ride's ``dz_m`` from the first row at or after its
    end (``rides``: :func:`counted_rides`); a ride before the first row (L393) lifts every row, one after the last
    (L394) none."""
    t, z = np.asarray(t, dtype=float), np.asarray(z, dtype=float)
    out = z.copy()
    for end, dz in rides:
        out[t >= end - 1e-9] += dz
    return out


def climb_floor(t, z, changes: list[tuple[float, float, int]], storey_height_m: float) -> np.ndarray:
    """Decision L631: per row at times ``t`` the storey reached: the sum of the ``changes`` ``(start, end, storeys)``
    (:func:`floor_changes`) ended at or before the row; a row inside a walking climb (``start`` <= t < ``end``) adds
    the storeys its height ``z`` (m) has climbed since the climb's start, rounded, within 0 and the climb's."""
    t, z = np.asarray(t, dtype=float), np.asarray(z, dtype=float)
    out = np.zeros(len(t), dtype=int)
    for start, end, n in changes:
        out[t >= end - 1e-9] += int(n)
        inside = (t >= start - 1e-9) & (t < end - 1e-9)
        if inside.any():
            z0 = float(np.interp(start, t, z))
            part = np.rint((z[inside] - z0) / storey_height_m)
            out[inside] += np.clip(np.nan_to_num(part), min(0, n), max(0, n)).astype(int)
    return out


def floor_changes(result, storey_height_m: float) -> list[tuple[float, float, int]] | None:
    """Decision L631: the summary's climbs (L127's per-climb count, :func:`pdrlearn.track.evaluate.climb_inputs`; L375
    rides, L394 a ride after the last step) as ``(start, end, storeys)`` (s): a walking climb from the start of its
    first stair step to the end of its last; a ride at the start of the step after it (start = end; a ride after the
    last step: its own end). None where the floors are counted on the altitude (no per-climb count)."""
    from pdrlearn.track.evaluate import STOREY_BAND, _climbs, climb_inputs

    steps = result.steps
    dz, bridge, parts, slope_rows = climb_inputs(result)
    if dz is None or not len(steps) or "end_s" not in steps:
        return None
    ends = steps["end_s"].to_numpy(float)
    starts = steps["start_s"].to_numpy(float) if "start_s" in steps else ends
    after = {int(r["row"]): float(r["end_s"]) for r in (result.info.get("rides") or []) if "row" in r}
    out = []
    for rows, n, ride in _climbs(dz, storey_height_m, STOREY_BAND, bridge, None, False, slope_rows, parts):
        last = int(rows[-1])
        if ride:  # decision L375: a ride's storeys, reached when it ends, before step `last`
            when = float(starts[last]) if last < len(steps) else after.get(last, np.inf)
            out.append((when, when, n))
        else:
            out.append((float(starts[int(rows[0])]), float(ends[min(last, len(steps) - 1)]), n))
    return out


def _z_rides(result) -> list[tuple[float, float]]:
    """The rides ``z`` leaves out: a foot track's (:func:`counted_rides`); none on a lower-back track (its barometric
    ``z`` holds them)."""
    units = set(result.steps["unit"].astype(str)) if "unit" in result.steps else {"foot"}
    return counted_rides(result.info.get("rides")) if units == {"foot"} else []


def ride_change(result, t0: float, t1: float) -> float:
    """Decision L630: the height the rides ``z`` leaves out (:func:`_z_rides`) add from ``t0`` to ``t1`` (s)."""
    return float(np.diff(ride_altitude([t0, t1], [0.0, 0.0], _z_rides(result)))[0])


def with_floor_columns(traj: pd.DataFrame, result, storey_height_m: float | None = None) -> pd.DataFrame:
    """trajectory.csv with ``z_rides`` and ``floor`` appended (decisions L630, L631). ``z_rides``: a foot track's ``z``
    plus its rides (:func:`ride_altitude`; a lower-back track's ``z`` is barometric and holds them already: ``z``).
    ``floor``: storeys of ``storey_height_m`` (``--storey-height``; L64's assumed 3.0 m without it) from the start's,
    reached by the summary's climbs (:func:`floor_changes`), else L64's band rule on ``z_rides``. A window's rows keep
    the counts of its own steps."""
    if not len(traj) or "z" not in traj or "t" not in traj:
        return traj
    out = traj.copy()
    out["z_rides"], out["floor"] = floor_values(out["t"], out["z"], result, storey_height_m)
    return out


def floor_values(t, z, result, storey_height_m: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``z_rides`` and ``floor`` (decisions L630, L631) at times ``t`` (s, ascending) of heights ``z`` (m): the rides
    counted from their ends and the climbs from :func:`floor_changes` at those times (:func:`with_floor_columns`)."""
    from pdrlearn.track.evaluate import STOREY_HEIGHT_M, floor_levels

    storey_height_m = STOREY_HEIGHT_M if storey_height_m is None else float(storey_height_m)
    t = np.asarray(t, dtype=float)
    z_rides = ride_altitude(t, z, _z_rides(result))  # decision L630
    changes = floor_changes(result, storey_height_m)
    floor = (climb_floor(t, z_rides, changes, storey_height_m) if changes is not None  # decision L631
             else floor_levels(z_rides, storey_height_m))
    return z_rides, floor


def floor_at_times(traj: pd.DataFrame, t, z, result, storey_height_m: float | None = None,
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Review R1 F2 (decision L638): ``z_rides`` and ``floor`` at the given times ``t`` (s, any order) with heights
    ``z`` there, not the trajectory row's held: a ride that ends after a time before the first row does not lift it,
    one that ends before a time after the last row does. Judged among the trajectory's rows (``traj``'s ``t``, ``z``:
    a walking climb's start height and L64's band read them), the given times' values returned."""
    t, z = np.asarray(t, dtype=float), np.asarray(z, dtype=float)
    rows = len(traj) if "t" in traj and "z" in traj else 0
    at = np.r_[traj["t"].to_numpy(float) if rows else [], t]
    order = np.argsort(at, kind="stable")  # a row before a given time at the same instant
    zr, fl = floor_values(at[order], np.r_[traj["z"].to_numpy(float) if rows else [], z][order], result,
                          storey_height_m)
    back = np.empty(len(at), dtype=int)
    back[order] = np.arange(len(at))
    return zr[back][rows:], fl[back][rows:]


def rides_altitude_phrase(summary: dict) -> str:
    """Decision L630: the one-line summary's ", +0.00 m with its rides (...)" where the rides changed a
    foot track's altitude (``altitude_change_rides_m`` not ``altitude_change_m``); "" otherwise."""
    a, b = summary.get("altitude_change_m"), summary.get("altitude_change_rides_m")
    if a is None or b is None or abs(float(b) - float(a)) < 0.005:
        return ""
    return f", {float(b):+.2f} m with its rides (rides.csv; trajectory.csv z_rides, L630)"
