"""Decision L573 (session 41, trial T3 finding F3): ``curbs.csv``, the single level changes of a foot track - a curb
stepped up or down, one stride that changes height by at least L179's 0.10 m outside stairs.csv's flights (L432,
which need two such strides, L438), outside ramps.csv's ramps (L301) and L302's ramp climbs of two strides or
more (L303).

Only where the height source sees a single stride's rise: a foot track (its own strides' heights, or ``--altitude
fused``, L154, which keeps the foot's height of a stride of 0.10 m or more). A lower-back track's barometer does not
(its noise is 0.13 m per sample, W89): no curbs.csv there, as no stairs.csv (L440). A curb ramp (a ramp under L301's
2 m ``RAMP_MIN_RUN_M``) is in neither table: it rises a curb's height over several strides of under 0.10 m each.
Pure functions of a steps table and its trajectory."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.distance import LEVEL_DZ_M

#: decision L573: the least |dz| (m) of a curb stride: L179's stair-stride rule (L39's level bound, half a stair
#: rise, decision S3); a 0.15 m curb (ADA 2010 sec. 303.2 allows 6 mm unbevelled, so any curb needs a ramp) exceeds it
CURB_MIN_DZ_M = LEVEL_DZ_M
#: decision L573: a stride of a ramps.csv ramp that carries at least this share of the ramp's rise is a curb: L301
#: joins a curb stride with a neighbour into a 2 m "ramp" (a 0.15 m curb down read as a 2.19 m ramp at -8.13 %, its
#: curb stride -0.139 of -0.178 m); a ramp's strides share its rise (a 1:12 ramp rises 0.10 m per 1.2 m stride)
CURB_SHARE = 0.5
#: decision L587: the |dz| (m) under which a curb stride's neighbour is level: half L573's curb bound. A stride of
#: 0.10 m or more between two such strides is a curb even inside a ramp or a barometric climb (the lagging climb
#: swallowed a 0.15 m curb 4 m after a ramp, T4 #2); a ramp's steady rise has risen neighbours (1:12: 0.10 m each)
CURB_LEVEL_DZ_M = 0.05
#: decision L573: the columns of ``curbs.csv``; ``x_m`` / ``y_m`` the trajectory's position halfway through the
#: stride (the curb is within half a stride of it); the clock columns are added with a recording start (L298)
CURB_COLUMNS = ("curb", "start_s", "end_s", "direction", "dz_m", "length_m", "x_m", "y_m")


def curb_rows(dz, candidate, excluded, min_dz_m: float = CURB_MIN_DZ_M) -> np.ndarray:
    """Decision L573: (rows,) bool, the ``candidate`` rows (valid strides) not ``excluded`` (in a flight, a ramp or a
    ramp climb) whose |``dz``| is at least ``min_dz_m``. A pure kernel."""
    dz = np.nan_to_num(np.abs(np.asarray(dz, dtype=float)))
    return np.asarray(candidate, bool) & ~np.asarray(excluded, bool) & (dz >= min_dz_m)


def isolated_rows(dz, min_dz_m: float = CURB_MIN_DZ_M, level_dz_m: float = CURB_LEVEL_DZ_M) -> np.ndarray:
    """Decision L587: (rows,) bool, the strides whose |``dz``| is at least ``min_dz_m`` while the stride before and
    the one after (where there is one; a missing height counts as level) are under ``level_dz_m``: a single level
    change, not a part of a ramp's steady rise. A pure kernel."""
    a = np.nan_to_num(np.abs(np.asarray(dz, dtype=float)))
    level = np.concatenate([[True], a < level_dz_m, [True]])
    return (a >= min_dz_m) & level[:-2] & level[2:]


def curb_table(steps: pd.DataFrame, trajectory: pd.DataFrame | None, info: dict | None, *,
               found=None) -> pd.DataFrame:
    """``curbs.csv`` (decision L573): one row per :func:`curb_rows` stride of a foot track's ``steps`` (sorted by
    ``start_s``): its times, direction, ``dz_m``, horizontal ``length_m`` and the ``trajectory``'s ``x`` / ``y`` at
    the stride's middle time. The header alone on a lower-back track, without ``dz_m`` and on a declared inclined
    belt (L442). ``found``: :func:`pdrlearn.track.grade.track_ramps` of ``steps`` (session 42), used when ``steps``
    are in ``start_s`` order already (its rows are then the sorted table's)."""
    from pdrlearn.signal import runs
    from pdrlearn.track.clinical import _is_lower_back
    from pdrlearn.track.evaluate import ramp_climb_rows
    from pdrlearn.track.gait import stride_rows
    from pdrlearn.track.grade import table_ramps
    from pdrlearn.track.stair_flights import flight_spans

    if (not len(steps) or "dz_m" not in steps or _is_lower_back(steps)
            or (info or {}).get("belt_incline_pct") is not None):
        return pd.DataFrame(columns=list(CURB_COLUMNS))
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    dz = pd.to_numeric(st["dz_m"], errors="coerce").to_numpy(float)
    excluded = np.zeros(len(st), bool)
    if found is not None and not steps["start_s"].is_monotonic_increasing:
        found = None  # the sorted rows are not the rows the ramps were found on
    for r in table_ramps(st, info, found):  # ramps.csv's rows, but a stride that carries half a ramp's rise or more: a
        rows = np.arange(r["first"], r["last"] + 1)  # curb L301 joined with its neighbour into a 2 m run
        excluded[rows] = ~(np.abs(np.nan_to_num(dz[rows])) >= CURB_SHARE * abs(r["rise_m"]))
    for a, b in runs(ramp_climb_rows(st, info)):  # L303's climbs under 20 %: of two rows or more, a ramp walked
        excluded[a:b] |= b - a >= 2                # by a foot track (its single stride is the curb itself)
    excluded &= ~isolated_rows(dz)  # decision L587: but a single level change between level strides is a curb
    for a, b, _ in flight_spans(st):
        excluded[a:b] = True
    if "ride" in st:  # decision L377: a ride's height is no curb
        excluded |= st["ride"].notna().to_numpy(bool) & st["ride"].astype(str).ne("").to_numpy(bool)
    rows = np.flatnonzero(curb_rows(dz, stride_rows(st), excluded))
    start, end = st["start_s"].to_numpy(float)[rows], st["end_s"].to_numpy(float)[rows]
    x = y = np.full(len(rows), np.nan)
    if trajectory is not None and len(trajectory) and {"t", "x", "y"} <= set(trajectory):
        tr = trajectory.sort_values("t", kind="stable")
        mid = (start + end) / 2
        x = np.interp(mid, tr["t"].to_numpy(float), tr["x"].to_numpy(float))
        y = np.interp(mid, tr["t"].to_numpy(float), tr["y"].to_numpy(float))
    length = (pd.to_numeric(st["length_m"], errors="coerce").to_numpy(float)[rows] if "length_m" in st
              else np.full(len(rows), np.nan))
    return pd.DataFrame({"curb": np.arange(1, len(rows) + 1), "start_s": start, "end_s": end,
                         "direction": np.where(dz[rows] > 0, "up", "down"), "dz_m": dz[rows],
                         "length_m": length, "x_m": x, "y_m": y}, columns=list(CURB_COLUMNS))
