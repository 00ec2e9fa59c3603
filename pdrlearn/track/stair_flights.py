"""Stair flights of a foot track (decision L432, docs/decisions/localization.md): ``stairs.csv``, one row per flight.

A flight is a run of consecutive stair strides of one direction: rows that L179 counts as stair strides
(:func:`pdrlearn.track.gait.stair_rows`, |``dz_m``| >= 0.10 m) whose height changes have one sign, inside one
walking bout (L104's bouts, :func:`pdrlearn.track.clinical.bout_rows`: a pause of a second or more, or a data gap,
ends a flight), of at least :data:`MIN_FLIGHT_STRIDES` strides (L438: one drifting stride is no flight). A level
stride ends it: a landing, and a turn on a landing whose strides are level (a landing turn whose strides climb, as
scenario D's, stays in the flight). Unlike L127's
storey climbs (:func:`pdrlearn.track.evaluate.floor_climbs`), which bridge a landing to count a storey, a flight is
never bridged. A winding stair's turning stair strides stay one flight.

The number of stairs cannot come from the strides: a stride of the tracked foot holds two steps, and a walker going
step-over-step climbs one stair per step (2 per stride) while one going step-to-step (both feet on each stair, as
many older adults do) climbs one per stride, and a skipped stair adds one more. With a known rise (``track
--stair-rise METRES``) ``n_stairs`` = round(|height| / rise). Pure functions of a steps table.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

#: the columns of ``stairs.csv`` (decision L432); the clock columns are added with a recording start (L298)
FLIGHT_COLUMNS = ("flight", "start_s", "end_s", "direction", "n_strides", "height_m", "time_s", "cadence_spm",
                  "vertical_speed_mps", "median_stride_dz_m", "stride_dz_cv_pct", "n_stairs", "stairs_per_min")
#: the summary keys of :func:`flight_summary` (decision L432; L602: the flights' summed rise and drop, m)
KEYS = ("n_flights_up", "n_flights_down", "flights_rise_m", "flights_drop_m")
#: decision L433: an interior stride of a run of stair strides whose grade (|dz| / horizontal length) is under this
#: share of the run's median grade is a landing stride: every stair stride climbs at the stair's own grade however
#: many stairs it takes (one step-to-step, two step-over-step, three with a skipped stair), while a stride onto or
#: off a landing adds level ground, whose depth is at least the stair's width, >= 0.91 m (IBC 2018 sec. 1011.6 with
#: sec. 1011.2's 36 in), to at most a stride's stair part; None: runs are not split at landing strides. Measured
#: with 0.5 and not adopted (L433: a lone landing stride's stair went to the wrong flight on a 1.0 m landing): an
#: option of :func:`flight_runs` (``landing_ratio=0.5``), off by default
LANDING_GRADE_RATIO: float | None = None
#: decision L438: the fewest consecutive stair strides of one sign that make a flight: one stride over L179's 0.10 m
#: on a level walk is drift (L68: up to 0.47 m per stride), two in a row are a repeat (measured in L439)
MIN_FLIGHT_STRIDES = 2


def flight_runs(dz, stair, bouts: list[tuple[int, int]], length=None,
                landing_ratio: float | None = LANDING_GRADE_RATIO,
                min_strides: int = MIN_FLIGHT_STRIDES) -> list[tuple[int, int, int]]:
    """Decision L432: ``(first, last + 1, sign)`` of each run of at least ``min_strides`` (L438) consecutive rows
    that are ``stair`` rows whose ``dz`` has one ``sign`` (+1 up, -1 down), never across a bout's end (``bouts``:
    ``(first, last + 1)`` row ranges). Decision L433: with ``length`` (horizontal, m) and ``landing_ratio``, a run is
    also split at its landing strides (:func:`landing_cuts`). A pure kernel."""
    from pdrlearn.signal import runs

    dz = np.nan_to_num(np.asarray(dz, dtype=float))
    stair = np.asarray(stair, dtype=bool)
    out = []
    for a, b in bouts:
        for sign in (1, -1):
            for r0, r1 in runs(stair[a:b] & (sign * dz[a:b] > 0)):
                if r1 - r0 < min_strides:  # decision L438: a lone stair stride is no flight
                    continue
                rows = slice(a + r0, a + r1)
                cuts = ([] if length is None or landing_ratio is None
                        else landing_cuts(dz[rows], np.asarray(length, dtype=float)[rows], landing_ratio))
                edges = [a + r0, *(a + r0 + c for c in cuts), a + r1]
                out += [(e0, e1, sign) for e0, e1 in zip(edges[:-1], edges[1:], strict=True)]
    return sorted(out)


def landing_cuts(dz, length, ratio: float) -> list[int]:
    """Decision L433: where a run of stair strides (height changes ``dz`` and horizontal lengths ``length``, m, in
    walking order) is cut at a landing: its interior strides (not the first or the last, which step on or off the
    stairs) whose grade |dz| / |length| is under ``ratio`` x the run's median grade are landing strides; two
    consecutive ones (onto the landing, off it) are cut between, one alone (over a short landing) after it. Returns
    the cut positions (row offsets into the run, each the first row of a new flight). A pure kernel."""
    dz, length = np.abs(np.asarray(dz, dtype=float)), np.abs(np.asarray(length, dtype=float))
    n = len(dz)
    if n < 3:
        return []
    with np.errstate(divide="ignore", invalid="ignore"):
        grade = np.where(length > 0, dz / length, np.inf)  # no length: no landing stride
    shallow = np.zeros(n, bool)
    shallow[1:-1] = grade[1:-1] < ratio * float(np.median(grade))
    cuts, k = [], 1
    while k < n - 1:
        if shallow[k]:
            cuts.append(k + 1)
            k += 2 if shallow[k + 1] else 1  # a pair: cut between them (k + 1 is the next flight's first)
        else:
            k += 1
    return cuts


def flight_strides(st: pd.DataFrame, min_strides: int | None = None) -> int:
    """Decision L434 (L438): the stair strides (L179's rows, as ``n_stair_strides`` counts them) of the rows ``st``
    (one bout, in walking order) that belong to a flight of at least ``min_strides`` (None:
    :data:`MIN_FLIGHT_STRIDES`); 0: no flight."""
    from pdrlearn.track.gait import stair_rows, stride_rows

    dz = pd.to_numeric(st["dz_m"], errors="coerce").to_numpy(float) if "dz_m" in st else np.zeros(len(st))
    found = flight_runs(dz, stair_rows(st) & stride_rows(st), [(0, len(st))],
                        min_strides=MIN_FLIGHT_STRIDES if min_strides is None else min_strides)
    return int(sum(b - a for a, b, _ in found))


#: decision L466: a flight made only of a ramp climb's steep strides (L455's rule; none of its rows a stair row by
#: L443) needs this many strides: L455's false flight on a real level walk had 2; a trail's stair section worth
#: reporting has 6 stairs (3 strides) or more
MIN_STEEP_FLIGHT_STRIDES = 3


def flight_row_masks(st: pd.DataFrame, dz: np.ndarray, length: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """Decisions L443, L455, L466: (rows,) bool twice, from one pass (the climb search runs once): L179's stair rows
    less the climbs L302 calls "ramps" (L443), and those plus each stride of such a climb whose own grade
    |dz| / |length| reaches :func:`pdrlearn.track.grade.stair_min_grade_pct` (L469: 20 %, ``--stair-grade``; a stair
    beside a ramp, L455). L455 alone was not adopted (a real level recording gained a 2-stride drift flight); L466
    adopted it with :data:`MIN_STEEP_FLIGHT_STRIDES`, so stairs.csv's flights are made of the second (decision L595:
    the rule, no module switch ``STEEP_STRIDES_IN_RAMPS``; its unused reader ``flight_rows`` removed). Decision L788:
    with ``length``, neither holds :func:`pdrlearn.track.grade.long_slope_rows` of the stair rows (a slope)."""
    from pdrlearn.track.evaluate import ramp_climb_rows
    from pdrlearn.track.gait import stair_rows
    from pdrlearn.track.grade import long_slope_rows, stair_min_grade_pct

    stair = stair_rows(st, ramp_not_stair=False)
    kept = stair & ~ramp_climb_rows(st)  # decision L443
    if length is None:
        return kept, kept
    with np.errstate(invalid="ignore", divide="ignore"):
        steep = np.abs(np.nan_to_num(dz)) >= stair_min_grade_pct(st) / 100.0 * np.abs(length)  # L455, L463
    slope = long_slope_rows(dz, length, stair)  # decision L788: a run far longer than a building's flight, a slope
    return kept & ~slope, (kept | (stair & steep)) & ~slope


def flight_spans(st: pd.DataFrame) -> list[tuple[int, int, int]]:
    """Decisions L432, L443, L466: ``(first, last + 1, sign)`` of each stair flight of a foot track's rows ``st``
    (sorted by ``start_s``, with ``dz_m``), as stairs.csv lists them - shared by :func:`flight_table` and the curbs
    outside flights (decision L573, :mod:`pdrlearn.track.curbs`)."""
    from pdrlearn.track.clinical import bout_rows
    from pdrlearn.track.gait import stride_rows

    dz = pd.to_numeric(st["dz_m"], errors="coerce").to_numpy(float)
    # L179's n_stair_strides rows; decision L443: less a climb L302 calls "ramps" (under 20 % rise over run), as
    # floors_up_stairs / floors_up_ramps count it - a ramp, a hill or an inclined belt is no stair flight
    length = pd.to_numeric(st["length_m"], errors="coerce").to_numpy(float) if "length_m" in st else None
    plain, steep = flight_row_masks(st, dz, length)  # decision L466: L443's own stair rows, and with L455's
    stair = steep & stride_rows(st)
    from pdrlearn.track.trunk_pauses import COLUMN

    bouts = bout_rows(st.drop(columns=COLUMN, errors="ignore"))  # decision L687: a rest on a stair ends no flight
    return [(a, b, sign) for a, b, sign in flight_runs(dz, stair, bouts, length)
            if b - a >= MIN_STEEP_FLIGHT_STRIDES or plain[a:b].any()]  # decision L466


def flight_stride_counts(steps: pd.DataFrame, valid) -> tuple[int, int]:
    """Decision L705: the ``valid`` rows of a foot track's ``steps`` inside stairs.csv's flights up and down
    (:func:`flight_spans`, the rows in ``start_s`` order as :func:`flight_table` reads them), ``(up, down)``; (0, 0)
    on a declared inclined belt (L442: no flight) or without ``dz_m``."""
    from pdrlearn.track.belt import declared_incline

    if not len(steps) or "dz_m" not in steps or declared_incline() is not None:
        return 0, 0
    order = steps["start_s"].reset_index(drop=True).sort_values(kind="stable").index.to_numpy()
    ok = np.asarray(valid, dtype=bool)[order]
    counts = {1: 0, -1: 0}
    for a, b, sign in flight_spans(steps.iloc[order].reset_index(drop=True)):
        counts[sign] += int(ok[a:b].sum())
    return counts[1], counts[-1]


def flight_table(steps: pd.DataFrame, stair_rise_m: float | None = None) -> pd.DataFrame:
    """``stairs.csv`` (decision L432): one row per :func:`flight_runs` flight of a foot track's rows (decision L443:
    not of the climbs L302 calls ramps, :func:`pdrlearn.track.evaluate.ramp_climb_rows`) (in
    ``start_s`` order): its first row's ``start_s`` and last row's ``end_s``, ``time_s`` between them, ``height_m``
    (the strides' summed ``dz_m``, signed), ``cadence_spm`` (2 steps per stride of the tracked foot over
    ``time_s``, L176's 120 / stride time), ``vertical_speed_mps`` (|height| / time), the median and CV (L104's
    :func:`pdrlearn.track.clinical.cv_pct`) of the strides' |``dz_m``|, and with ``stair_rise_m`` ``n_stairs`` =
    round(|height| / rise) and ``stairs_per_min``. The header alone on a lower-back track (its rows are steps of
    either foot with a barometric height) and without ``dz_m``."""
    from pdrlearn.track.bouts import cadence_spm
    from pdrlearn.track.clinical import _is_lower_back, cv_pct

    if not len(steps) or "dz_m" not in steps or _is_lower_back(steps):
        return pd.DataFrame(columns=list(FLIGHT_COLUMNS))
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)  # bout_rows' row order
    dz = pd.to_numeric(st["dz_m"], errors="coerce").to_numpy(float)
    start, end = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    rows = []
    found = flight_spans(st)
    for k, (a, b, sign) in enumerate(found, start=1):
        t = float(end[b - 1] - start[a])
        height = float(np.nansum(dz[a:b]))
        size = np.abs(dz[a:b])
        stairs = round(abs(height) / stair_rise_m) if stair_rise_m else None
        rows.append({"flight": k, "start_s": float(start[a]), "end_s": float(end[b - 1]),
                     "direction": "up" if sign > 0 else "down", "n_strides": int(b - a), "height_m": height,
                     "time_s": t, "cadence_spm": cadence_spm(2 * (b - a), t),  # two steps per stride (L66)
                     "vertical_speed_mps": abs(height) / t if t > 0 else math.nan,
                     "median_stride_dz_m": float(np.median(size)), "stride_dz_cv_pct": cv_pct(size),
                     "n_stairs": stairs,
                     "stairs_per_min": 60.0 * stairs / t if stairs is not None and t > 0 else None})
    table = pd.DataFrame(rows, columns=list(FLIGHT_COLUMNS))
    return table.astype({"n_stairs": "Int64"}) if len(table) else table


def flight_summary(steps: pd.DataFrame) -> dict:
    """Decision L432: :data:`KEYS`, the flights up and down of :func:`flight_table` of a foot track's rows, and
    (decision L602) what they climb and descend, stairs.csv's ``height_m`` summed up / down (m, both >= 0); None on
    a lower-back track (no flights table)."""
    from pdrlearn.track.belt import declared_incline
    from pdrlearn.track.clinical import _is_lower_back

    if _is_lower_back(steps):
        return dict.fromkeys(KEYS)
    if declared_incline() is not None:  # decision L442: a declared inclined belt has no stair flight
        return dict.fromkeys(KEYS, 0)
    table = flight_table(steps)
    d = table["direction"].astype(str)
    height = pd.to_numeric(table["height_m"], errors="coerce").to_numpy(float)
    return {"n_flights_up": int((d == "up").sum()), "n_flights_down": int((d == "down").sum()),
            "flights_rise_m": float(np.nansum(height[height > 0])) + 0.0,  # decision L602
            "flights_drop_m": float(-np.nansum(height[height < 0])) + 0.0}


#: decision L440: what ``--stair-rise`` on a lower-back track says (once, as a warning), instead of ignoring it
LOWER_BACK_RISE_LINE = ("--stair-rise is not used: a lower-back track has no stair flights (its steps carry no "
                        "stride height), so no stairs.csv is written; stair flights need a foot unit (decision L440)")


def lower_back_rise_line(steps: pd.DataFrame) -> str | None:
    """Decision L440: :data:`LOWER_BACK_RISE_LINE` for a lower-back track's ``steps`` (``--stair-rise`` given), None
    for a foot track."""
    from pdrlearn.track.clinical import _is_lower_back

    return LOWER_BACK_RISE_LINE if _is_lower_back(steps) else None


def stair_rise(value: float | None) -> float | None:
    """Decision B348: ``track --stair-rise METRES`` checked once, before any session: None when not given, else a
    rise inside :data:`pdrlearn.sim.path.STAIR_RISE_RANGE_M` (one error line naming the option, the range and, for
    a rise written in centimetres, the metres it meant)."""
    if value is None:
        return None
    from pdrlearn.sim.path import stair_size_error

    msg = stair_size_error(value, None)
    if msg:
        from pdrlearn.errors import DataError

        raise DataError(f"--stair-rise {value:g}: {msg}")
    return float(value)
