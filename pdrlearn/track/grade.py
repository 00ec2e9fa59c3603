"""Decisions L300-L302: the grade of a walked slope - steps.csv's per-row ``grade_pct`` (rise over horizontal run,
signed), the ramps table (``ramps.csv``: runs of consistent grade joined across their landings), the summary's
``distance_along_slope_m`` / ``n_ramps`` / ``grade_source``, and the floor counts split by what climbed (stairs,
ramps, rides: ``floors_up_stairs`` ...), whose sums are L127's ``floors_up`` / ``floors_down``.

A grade is read only where the altitude measures a slope: a lower-back track with its barometer (W89) or a foot
track with ``--altitude fused`` (L154). A foot track's own altitude does not: L39 levels every stride under 0.10 m
(a 1:12 ramp stride of 1.2 m rises 0.10 m) and a terrain model's flat class keeps the altitude (thesis ch. 7.2.2),
so its ``grade_pct`` is empty and ``grade_source`` is None (decision L300). The option ``foot_ramps`` reads its ramps
where its heights are L39's (no terrain classes): the strides of 0.10 m or more keep theirs, a 1:12 ramp's at strides
of 1.2 m or more (decision L717, not the default: :func:`ramp_source`)."""

from __future__ import annotations

import contextvars
import math
from contextlib import contextmanager

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.signal import runs as signal_runs

#: decision L300: a row shorter than this (m, horizontal) has no grade - a turn on the spot or a shuffle moves a few
#: cm, and its height change over it would read as a wall (a 2 cm barometric step over 5 cm is 40 %)
GRADE_MIN_LENGTH_M = 0.2
#: decision L301: a ramp row's (smoothed) grade is at least this in size (%): above a level walkway's 1:48 = 2.1 %
#: cross-slope bound (ADA 2010 sec. 403.3) and below the 1:20 = 5 % that makes a walking surface a ramp (sec. 405),
#: so a 1:20 route measured a little low (trial s30 F7: 4.74 % for 5 %) still is one
RAMP_MIN_GRADE_PCT = 3.0
#: decision L301: a climb steeper than this (%, rise over horizontal run) is a stair, not a ramp: the steepest ramp
#: allowed is 1:12 = 8.33 % (ADA 2010 sec. 405.2) and a stair's riser over tread is ~60 % (0.17 / 0.28 m, the
#: simulator's stair, S3); a waist track's stair steps, whose horizontal length the pendulum overestimates, measured
#: 30 % (decision L301's measurement)
STAIR_MIN_GRADE_PCT = 20.0
#: decision L463 rule B, an option since L469 (``--stair-grade 30``): a trail walk's stair grade (%, rise over run):
#: stairs are built at 30-50 deg (OSHA 29 CFR 1910.25, standard stairs), 58-119 %, a foot track reads real flights
#: at 34-39 %, and trail slopes up to 30 % then stay ramps. A project choice: the top of the 15-30 % trail range
TRAIL_STAIR_GRADE_PCT = 30.0
#: decision L469: ``--stair-grade``'s accepted values (%): a positive grade, at most a 45 deg rise over run
STAIR_GRADE_MAX_PCT = 100.0
_STAIR_GRADE = contextvars.ContextVar("pdrlearn_stair_grade", default=None)
#: decision L469: the track's info key (summary.json ``info``) of a given ``--stair-grade``
STAIR_GRADE_KEY = "stair_grade_pct"
#: decision L301: a run of ramp rows is a ramp run when its horizontal length is at least this (m): two foot strides
RAMP_MIN_RUN_M = 2.0
#: decision L301: a level stretch of at most this horizontal length (m) between two runs of one sign is a landing of
#: one ramp (ADA 2010 sec. 405.7.3: a landing is at least 60 in = 1.52 m long; two of them with a turn)
LANDING_MAX_M = 3.5
#: decision L301: rows of the centred window a foot track's ramp rows are judged on - a stride alone (the lower back's
#: three steps, L301 / W465, gave way to W517's slope over :data:`WAIST_SLOPE_WINDOW_M`)
GRADE_WINDOW_ROWS = {"foot": 1}
#: decision W517: the lower back judges its ramp (and stair) rows on the least-squares slope of its walked barometric
#: altitude over this centred horizontal window (m): one slow step's barometric change is noise of tens of %
#: (trial T1 F4: -24 ... +33 % step to step on a 1:12 ramp). A project choice, fixed before measuring: 5-6 normal
#: steps or 12+ slow ones, under a 1:12 run's 9 m between landings (ADA 2010 sec. 405.6: 30 in of rise)
WAIST_SLOPE_WINDOW_M = 4.0
#: decision W519: a lower-back ramp's |rise| is at least this many times the track's rest swing
#: (:func:`rest_swing_m`): a stand's barometric change and a ramp's rise are the same kind of difference, so a rise
#: within twice the stands' median is not told apart from the barometer's own swing (Test11's 3-4 s swing of +-0.18 m
#: read two ramps on a lab floor). A project choice, fixed before measuring
RAMP_REST_SWING_FACTOR = 2.0
#: decision W519: a standstill the rest swing reads is at least this long (s; L104's pause)
REST_SWING_MIN_STILL_S = 1.0
#: decision W519: the rest swing needs at least this many standstills (else no floor)
REST_SWING_MIN_STANDS = 3

RAMP_COLUMNS = ("ramp", "start_s", "end_s", "direction", "n_runs", "landings", "horizontal_run_m", "landing_m",
                "along_slope_m", "rise_m", "mean_grade_pct", "max_run_grade_pct", "n_steps",
                "duration_s", "speed_mps",  # decision L467
                "max_run_rise_m", "over_1_12", "over_1_20", "run_rise_over_0_76",  # decision L569
                "near_limit",  # decision L588
                "start_x_m", "start_y_m", "start_lat", "start_lon", "end_x_m", "end_y_m", "end_lat",
                "end_lon")  # decision L570


def grade_source(steps: pd.DataFrame, info: dict | None) -> str | None:
    """Decision L300: where the rows' altitude measures a slope - ``"fused"`` (a foot track fused with the waist
    barometer, L154), ``"barometer"`` (a lower-back track whose barometer was read: its ``dz_m`` is not all 0, W90) -
    or None (a foot track's own altitude, which L39 / the terrain classes level; mixed or empty tables)."""
    if not len(steps) or "dz_m" not in steps or "length_m" not in steps:
        return None
    units = set(steps["unit"].astype(str)) if "unit" in steps else {"foot"}
    if units == {"foot"}:
        return "fused" if (info or {}).get("altitude_source") == "fused" else None
    if units == {"waist"}:
        dz = pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float)
        return "barometer" if np.any(np.nan_to_num(dz) != 0) else None
    return None


#: decision L717: :func:`ramp_source`'s value for a foot track's own heights (L39's, no terrain classes)
FOOT_RAMP_SOURCE = "foot"
#: decision L717: the track's info key (``track_plasys(foot_ramps=True)``, ``--params '{"foot_ramps": true}'``) that
#: reads a foot track's ramps from its own heights - an option: its adoption rule failed (16 of 20 users, 18 asked)
FOOT_RAMPS_KEY = "foot_ramps"


def ramp_source(steps: pd.DataFrame, info: dict | None) -> str | None:
    """Decision L717: where the rows' ramps (ramps.csv, L301) are read from - :func:`grade_source` where it names
    one; else, where the track's ``info`` sets the option :data:`FOOT_RAMPS_KEY` (not the default: L717's rule
    failed), :data:`FOOT_RAMP_SOURCE` for a foot track whose altitude is its integrated height levelled by L39 (no
    terrain classes: L69's ``info["altitude_check"]`` with ``levelled``), whose strides of 0.10 m or more keep their
    height (a 1:12 ramp's at strides of 1.2 m or more); else None (the default, a terrain model's classes, a streamed
    model without terrain classes - unlevelled heights, C17 -, mixed units). Steps.csv's ``grade_pct`` and the
    summary's ``grade_source`` stay L300's: a levelled stride has no grade."""
    src = grade_source(steps, info)
    if src is not None or not len(steps) or "dz_m" not in steps or "length_m" not in steps:
        return src
    units = set(steps["unit"].astype(str)) if "unit" in steps else {"foot"}
    check = (info or {}).get("altitude_check")
    levelled = isinstance(check, dict) and bool(check.get("levelled"))
    wanted = bool((info or {}).get(FOOT_RAMPS_KEY))
    return FOOT_RAMP_SOURCE if wanted and units == {"foot"} and levelled else None


def check_stair_grade(value) -> float | None:
    """Decision L469: ``--stair-grade``'s value as a grade in (0, :data:`STAIR_GRADE_MAX_PCT`] %; None: not given;
    one clear line otherwise."""
    if value is None:
        return None
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if isinstance(value, bool) or not (math.isfinite(v) and 0.0 < v <= STAIR_GRADE_MAX_PCT):
        raise DataError(f"--stair-grade {value!r}: give the rise over run (%) from which a foot track's climb is a "
                        f"stair, a number in (0, {STAIR_GRADE_MAX_PCT:g}] (e.g. {TRAIL_STAIR_GRADE_PCT:g} for a trail "
                        f"walk; default {STAIR_MIN_GRADE_PCT:g}, decision L469)")
    return v


@contextmanager
def stair_grade_set(pct: float | None):
    """Decision L469: a foot track's measures computed inside call a climb a stair from ``pct`` % of rise over run
    (None: L301's :data:`STAIR_MIN_GRADE_PCT`). A :class:`contextvars.ContextVar`, so the threads of
    ``track-all --jobs`` do not share it (as L415's steady trim)."""
    token = _STAIR_GRADE.set(check_stair_grade(pct))
    try:
        yield
    finally:
        _STAIR_GRADE.reset(token)


@contextmanager
def info_stair_grade(info: dict | None):
    """Decision L469: a scope in which the grade a track's ``info`` records (:data:`STAIR_GRADE_KEY`, set by
    ``--stair-grade``) is in force; without it, the one in force already (:func:`stair_grade_set`)."""
    given = (info or {}).get(STAIR_GRADE_KEY)
    with stair_grade_set(given_stair_grade() if given is None else given):
        yield


#: decision L469: what ``--stair-grade`` on a lower-back track says (once, as a warning), instead of ignoring it
LOWER_BACK_GRADE_LINE = ("--stair-grade is not used: a lower-back track keeps L301's 20 % stair grade (its pendulum "
                         "step lengths read real stairs at about 30 %); the option sets a foot track's (decision L469)")


def record_stair_grade(result, pct: float | None) -> str | None:
    """Decision L469: ``--stair-grade`` ``pct`` recorded in a foot track's ``result.info`` (:data:`STAIR_GRADE_KEY`,
    read by the summary and the tables, :func:`info_stair_grade`); on a lower-back track nothing is recorded and
    :data:`LOWER_BACK_GRADE_LINE` is returned (None otherwise)."""
    from pdrlearn.track.clinical import _is_lower_back

    if pct is None:
        return None
    if _is_lower_back(result.steps):
        return LOWER_BACK_GRADE_LINE
    result.info[STAIR_GRADE_KEY] = check_stair_grade(pct)
    return None


def given_stair_grade() -> float | None:
    """Decision L469: the ``--stair-grade`` in force (:func:`stair_grade_set`); None: the default."""
    return _STAIR_GRADE.get()


def stair_min_grade_pct(steps: pd.DataFrame | None = None) -> float:
    """Decisions L463, L469: the rise over run (%) from which the rows' climb is a stair - the ``--stair-grade`` in
    force (:func:`stair_grade_set`) for a foot track's rows (a table without ``unit``: a foot track), else L301's
    :data:`STAIR_MIN_GRADE_PCT` (the default; the lower back and mixed units always)."""
    units = {"foot"} if steps is None or "unit" not in steps else set(steps["unit"].astype(str))
    given = given_stair_grade()
    return given if given is not None and units == {"foot"} else STAIR_MIN_GRADE_PCT


def grades_pct(length, dz, min_length_m: float = GRADE_MIN_LENGTH_M) -> np.ndarray:
    """Decision L300: ``100 dz / |length|`` per row (%, + up), NaN where ``|length| < min_length_m`` or either is
    not finite. A pure kernel."""
    length = np.abs(np.asarray(length, dtype=float))
    dz = np.asarray(dz, dtype=float)
    ok = np.isfinite(length) & np.isfinite(dz) & (length >= min_length_m)
    return np.where(ok, 100.0 * np.where(ok, dz, 0.0) / np.where(ok, length, 1.0), np.nan)


def add_grade(steps: pd.DataFrame, info: dict | None) -> str | None:
    """Steps.csv's ``grade_pct`` (decision L300), in place: :func:`grades_pct` where :func:`grade_source` names the
    altitude, empty (NaN) on every row where it does not; gap rows (``gap_s`` > 0) and impossible strides empty.
    Returns the source."""
    if not len(steps):
        return None
    src = grade_source(steps, info)
    if src is None:
        steps["grade_pct"] = np.nan
        return None
    g = grades_pct(pd.to_numeric(steps["length_m"], errors="coerce"), pd.to_numeric(steps["dz_m"], errors="coerce"))
    steps["grade_pct"] = np.where(_valid(steps), g, np.nan)
    return src


def _valid(steps: pd.DataFrame) -> np.ndarray:
    ok = np.ones(len(steps), bool)
    if "gap_s" in steps:
        ok &= ~(pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float) > 0)
    if "impossible" in steps:
        ok &= ~steps["impossible"].eq(True).to_numpy(bool)
    return ok


def along_slope_m(length, dz) -> float:
    """Decision L300: the distance along the walked surface, ``sum sqrt(length^2 + dz^2)`` (m) over the finite rows."""
    d = np.hypot(np.asarray(length, dtype=float), np.asarray(dz, dtype=float))
    return float(np.nansum(d))


def window_grades_pct(length, dz, window: int = 1) -> np.ndarray:
    """Decisions L301, L337: per row, the grade (%) of the centred ``window`` rows around it - their summed ``dz`` over
    their summed ``|length|`` (NaN read as 0), 0 where that length is 0; clipped at the ends. A pure kernel."""
    length = np.nan_to_num(np.abs(np.asarray(length, dtype=float)))
    dz = np.nan_to_num(np.asarray(dz, dtype=float))
    n = len(length)
    half = max(int(window), 1) // 2
    csum_l, csum_z = np.concatenate([[0.0], np.cumsum(length)]), np.concatenate([[0.0], np.cumsum(dz)])
    lo, hi = np.clip(np.arange(n) - half, 0, n), np.clip(np.arange(n) + half + 1, 0, n)
    wl, wz = csum_l[hi] - csum_l[lo], csum_z[hi] - csum_z[lo]
    return np.where(wl > 0, 100.0 * wz / np.where(wl > 0, wl, 1.0), 0.0)


def fitted_grades_pct(length, dz, window_m: float, ends=None) -> np.ndarray:
    """Decision W517: per row, the least-squares slope (%) of the walked altitude (cumulated ``dz``) against the
    cumulated horizontal ``|length|`` over the step boundaries within ``window_m / 2`` of the row's middle, inside
    its walking sequence (``ends``: True on a sequence's last row; None: one sequence); the row's own two boundaries
    always count, so a row as long as the window has its own grade; 0 where the boundaries span no length. NaN read as
    0. A pure kernel."""
    length = np.nan_to_num(np.abs(np.asarray(length, dtype=float)))
    dz = np.nan_to_num(np.asarray(dz, dtype=float))
    n = len(length)
    if not n:
        return np.zeros(0)
    x = np.concatenate([[0.0], np.cumsum(length)])  # boundary k: the start of row k (k = n: the last row's end)
    z = np.concatenate([[0.0], np.cumsum(dz)])
    last = np.zeros(n, bool) if ends is None else np.asarray(ends, bool).copy()
    last[-1] = True
    seq = np.concatenate([[0], np.cumsum(last)[:-1]])  # each row's walking sequence
    first_row = np.searchsorted(seq, seq, side="left")
    last_row = np.searchsorted(seq, seq, side="right") - 1
    mid = 0.5 * (x[:-1] + x[1:])
    rows = np.arange(n)
    lo = np.maximum(np.minimum(np.searchsorted(x, mid - 0.5 * window_m, side="left"), rows), first_row)
    hi = np.minimum(np.maximum(np.searchsorted(x, mid + 0.5 * window_m, side="right") - 1, rows + 1), last_row + 1)
    c = [np.concatenate([[0.0], np.cumsum(v)]) for v in (np.ones_like(x), x, z, x * x, x * z)]
    k, sx, sz, sxx, sxz = (s[hi + 1] - s[lo] for s in c)
    den = k * sxx - sx * sx
    ok = den > 1e-12 * np.maximum(k * sxx, 1e-12)
    return np.where(ok, 100.0 * (k * sxz - sx * sz) / np.where(ok, den, 1.0), 0.0)


def rest_swing_m(still_s, pause_dz, ride=None) -> float | None:
    """Decision W519: the median |altitude change| (m) over the standstills of a track - rows whose ``still_s``
    (steps.csv ``still_before_s``) is at least :data:`REST_SWING_MIN_STILL_S` with a finite ``pause_dz``
    (``pause_dz_m``, W158: the change while the walker stood before the row) and no ``ride`` (True rows of a ride,
    None: none) - what the barometer alone does in a few seconds on one floor; None with fewer than
    :data:`REST_SWING_MIN_STANDS` of them. A pure kernel."""
    still = np.asarray(still_s, dtype=float)
    dz = np.asarray(pause_dz, dtype=float)
    ok = np.isfinite(still) & (still >= REST_SWING_MIN_STILL_S) & np.isfinite(dz)
    if ride is not None:
        ok &= ~np.asarray(ride, dtype=bool)
    if int(ok.sum()) < REST_SWING_MIN_STANDS:
        return None
    return float(np.median(np.abs(dz[ok])))


def ramp_runs(length, dz, window: int = 1, min_grade_pct: float = RAMP_MIN_GRADE_PCT,
              stair_grade_pct: float = STAIR_MIN_GRADE_PCT, min_run_m: float = RAMP_MIN_RUN_M,
              landing_max_m: float = LANDING_MAX_M, on_stairs=None, lone_stair_joins: bool = False,
              window_m: float | None = None, ends=None, min_rise_m: float | None = None,
              stair_ends: bool = False, min_ramp_m: float | None = None, stops=None,
              long_slopes: bool = False) -> list[dict]:
    """Decision L301: the ramps of rows (horizontal ``length`` m, height change ``dz`` m, walking order) - a pure
    kernel. A row is a ramp row of sign s when the grade of the centred ``window`` rows around it (their summed dz
    over their summed |length|) is at least ``min_grade_pct`` in size, under ``stair_grade_pct`` (steeper: a stair),
    and its own |length| reaches :data:`GRADE_MIN_LENGTH_M`; consecutive ramp rows of one sign with at least
    ``min_run_m`` of horizontal length are a run; runs of one sign separated by at most ``landing_max_m`` of rows
    that are no ramp rows of the other sign or stair rows are one ramp, the rows between them its landings. Each
    ramp: its first and last row (``first``, ``last``), ``runs`` (``(first, last)`` per run) and the table's
    numbers (:data:`RAMP_COLUMNS` but ``ramp`` and the times). ``on_stairs`` (decision L314; None: none): rows known to
    be on stairs whatever their grade - a lower-back track's W108 climbs, whose pendulum lengths read a stair's
    riser over a long step - are stair rows. ``lone_stair_joins`` (decision W464, the lower back's): a stair row with
    no stair row next to it does not keep two runs of one sign from joining (a lower-back step's barometric change
    is noise of several %, L300: one step of 0.15 m over 0.7 m split T3's 1:12 ramp in three). Decision L633: a ramp
    between two stair rows of its own direction is a stair's landing and left out. ``window_m`` (decision W517, the
    lower back's): the rows are judged on :func:`fitted_grades_pct` over that many metres of each walking sequence
    (``ends``) instead of ``window`` rows, and a row is a stair row when that grade (not its own) is a stair's.
    ``min_rise_m`` (decision W519, the lower back's; None: none): a ramp whose |rise| is under it is left out.
    ``stair_ends`` (decision W530, the lower back's, with ``window_m``): a ramp next to a stair row climbing its own
    way whose horizontal run is at most ``window_m`` is that flight's end (:func:`_stair_end`), left out.
    ``min_ramp_m`` (decision W539, measured and not adopted, an option; None: none): a ramp whose horizontal run
    (its runs summed) is under it is left out - ``WAIST_SLOPE_WINDOW_M`` drops a lower-back track's lone 2 m ramps
    (one fitted window's noise) but also a slow walker's ramp read in short pieces.
    ``stops`` (decision L787; None: none): True on a row the walker stood still before (:func:`stop_rows`) - it
    starts a new run and no ramp joins across it (a stop is not walked, so no landing). ``long_slopes`` (decision
    L788, a foot track's): the rows of :func:`long_slope_rows` of L179's stair rows (|dz| >= 0.10 m; a run far
    longer than a building's flight at a slope's grade) are ramp rows of their sign, none a stair row."""
    length = np.nan_to_num(np.abs(np.asarray(length, dtype=float)))
    dz = np.nan_to_num(np.asarray(dz, dtype=float))
    n = len(length)
    if not n:
        return []
    if window_m is None:
        g = window_grades_pct(length, dz, window)
        own = np.where(length >= GRADE_MIN_LENGTH_M, 100.0 * dz / np.where(length > 0, length, 1.0), np.inf)
    else:  # decision W517
        g = fitted_grades_pct(length, dz, window_m, ends)
        own = np.where(length >= GRADE_MIN_LENGTH_M, g, np.inf)
    stair = np.abs(own) >= stair_grade_pct
    if on_stairs is not None:  # decision L314
        stair |= np.asarray(on_stairs, dtype=bool)
    slope = None
    if long_slopes:  # decision L788: runs of L179's stair strides (|dz| >= 0.10 m), as flights and climbs read them
        from pdrlearn.kernels.distance import LEVEL_DZ_M

        slope = long_slope_rows(dz, length, (np.abs(dz) >= LEVEL_DZ_M) & (length >= GRADE_MIN_LENGTH_M))
    if slope is not None:
        stair &= ~slope
    sign = np.where((np.abs(g) >= min_grade_pct) & (np.abs(g) < stair_grade_pct) & ~stair
                    & (length >= GRADE_MIN_LENGTH_M), np.sign(g), 0).astype(int)
    if slope is not None:
        sign = np.where(slope, np.sign(dz), sign).astype(int)  # decision L788: a slope's rows are ramp rows
    stops = None if stops is None else np.asarray(stops, dtype=bool)
    blocks = stair & ~_lone(stair) if lone_stair_joins else stair  # decision W464
    runs = sorted((a0, b0 - 1, s) for s in (1, -1) for a, b in signal_runs(sign == s)
                  for a0, b0 in _split_at(a, b, stops)  # decision L787: a stop ends a run
                  if length[a0:b0].sum() >= min_run_m)  # maximal rows of one sign, in walking order
    ramps: list[list[tuple[int, int, int]]] = []
    for r in runs:
        if ramps:
            p = ramps[-1][-1]
            between = slice(p[1] + 1, r[0])
            if (p[2] == r[2] and length[between].sum() <= landing_max_m
                    and not np.any(blocks[between] | (sign[between] == -r[2]))
                    and (stops is None or not stops[p[1] + 1:r[0] + 1].any())):  # decision L787
                ramps[-1].append(r)
                continue
        ramps.append([r])
    out = []
    for rs in ramps:
        if _stair_landing(stair, dz, rs[0][0] - 1, rs[-1][1] + 1, rs[0][2]):  # decision L633
            continue
        rows = np.concatenate([np.arange(a, b + 1) for a, b, _ in rs])
        run_l, rise = float(length[rows].sum()), float(dz[rows].sum())
        if stair_ends and window_m is not None and run_l <= window_m and _stair_end(
                stair, dz, rs[0][0] - 1, rs[-1][1] + 1, rs[0][2]):  # decision W530
            continue
        if min_rise_m is not None and abs(rise) < min_rise_m:  # decision W519: within the barometer's rest swing
            continue
        if min_ramp_m is not None and run_l < min_ramp_m:  # decision W539: under one fitted window
            continue
        grades = [100.0 * dz[a:b + 1].sum() / length[a:b + 1].sum() for a, b, _ in rs]
        rises = [float(dz[a:b + 1].sum()) for a, b, _ in rs]  # decision L569: each run's own rise
        out.append({"first": rs[0][0], "last": rs[-1][1], "runs": [(a, b) for a, b, _ in rs],
                    "direction": "up" if rs[0][2] > 0 else "down", "n_runs": len(rs), "landings": len(rs) - 1,
                    "horizontal_run_m": run_l,
                    "landing_m": float(length[rs[0][0]:rs[-1][1] + 1].sum() - run_l),
                    "along_slope_m": float(np.hypot(length[rows], dz[rows]).sum()), "rise_m": rise,
                    "mean_grade_pct": 100.0 * rise / run_l,
                    "max_run_grade_pct": float(max(grades, key=abs)), "n_steps": int(rs[-1][1] - rs[0][0] + 1),
                    "max_run_rise_m": max(rises, key=abs)})
    return out


def long_slope_rows(dz, length, stair, *, max_flight_strides: int = 24,
                    slope_grade_pct: float = TRAIL_STAIR_GRADE_PCT) -> np.ndarray:
    """Decision L788: (rows,) bool, the ``stair`` rows (walking order, height change ``dz`` and horizontal
    ``length``, m) in a run of consecutive stair rows of one sign of more than ``max_flight_strides`` rows (IBC 2018
    sec. 1011.8: a flight rises at most 12 ft = 3.66 m between landings, ~21 risers: ~21 strides step-to-step, + 3)
    whose rise over run (summed |dz| / summed |length|) is under ``slope_grade_pct`` (L463's trail grade: a foot
    track reads real flights at 34-39 %): a slope, not a stair - less the run's strides whose own grade reaches
    ``slope_grade_pct`` (a stair section inside a trail climb stays a stair, L466). NaN read as 0. A pure kernel."""
    dz = np.nan_to_num(np.asarray(dz, dtype=float))
    length = np.nan_to_num(np.abs(np.asarray(length, dtype=float)))
    stair = np.asarray(stair, dtype=bool)
    out = np.zeros(len(dz), bool)
    for sign in (1, -1):
        for a, b in signal_runs(stair & (sign * dz > 0)):
            run = float(length[a:b].sum())
            if b - a > max_flight_strides and run > 0 and 100.0 * float(np.abs(dz[a:b]).sum()) / run < slope_grade_pct:
                out[a:b] = 100.0 * np.abs(dz[a:b]) < slope_grade_pct * length[a:b]
    return out


def stop_rows(start_s, end_s, *, stop_s: float = 30.0) -> np.ndarray:
    """Decision L787: (rows,) bool, True on a row (walking order) that starts at least ``stop_s`` seconds after the
    previous row ended - the walker stood (a map or a food stop, longer than a breath-catching pause): it starts a
    new ramp (:func:`ramp_runs`' ``stops``). A pure kernel; NaN times stop nothing."""
    start, end = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    out = np.zeros(len(start), bool)
    if len(start) > 1:
        with np.errstate(invalid="ignore"):
            out[1:] = (start[1:] - end[:-1]) >= stop_s
    return out


def _split_at(a: int, b: int, stops) -> list[tuple[int, int]]:
    """The row range ``[a, b)`` cut before each row of ``stops`` (True) inside it (decision L787)."""
    if stops is None:
        return [(a, b)]
    cuts = [a, *(k for k in range(a + 1, b) if stops[k]), b]
    return list(zip(cuts[:-1], cuts[1:], strict=True))


def _stair_landing(stair: np.ndarray, dz: np.ndarray, before: int, after: int, sign: int) -> bool:
    """Decision L633: a ramp whose rows ``before`` and ``after`` it are both stair rows climbing its own way (``sign``)
    is one stair's landing (the strides onto and off it carry a stair's part), not a ramp."""
    if before < 0 or after >= len(stair):
        return False
    return bool(stair[before] and stair[after] and np.sign(dz[before]) == sign == np.sign(dz[after]))


def _stair_end(stair: np.ndarray, dz: np.ndarray, before: int, after: int, sign: int) -> bool:
    """Decision W530: whether the row ``before`` or the row ``after`` a ramp is a stair row climbing its own way
    (``sign``): the flight the fitted slope blurred the ramp's rows from."""
    return any(0 <= k < len(stair) and bool(stair[k]) and np.sign(dz[k]) == sign for k in (before, after))


def _lone(mask: np.ndarray) -> np.ndarray:
    """The True rows of ``mask`` with no True row next to them."""
    m = np.asarray(mask, bool)
    near = np.zeros(len(m), bool)
    near[1:] |= m[:-1]
    near[:-1] |= m[1:]
    return m & ~near


#: session 42 (implementer I2): what :func:`track_ramps` returns - the ramps, the rows' |length| and dz it read - and
#: what its callers take as ``found=`` so a written track finds its ramps once
FoundRamps = tuple[list[dict], np.ndarray, np.ndarray]


def track_ramps(steps: pd.DataFrame, info: dict | None) -> FoundRamps:
    """Decisions L301, L568: :func:`ramp_runs` of a track's rows (the valid rows' ``length_m`` / ``dz_m``, the
    unit's window - the lower back's W517 slope over :data:`WAIST_SLOPE_WINDOW_M` of each walking sequence, ended
    where ``has_next`` is False -, L314's stair rows, the stair grade in force) with the rows' lengths and height
    changes it read; no ramps where :func:`ramp_source` is None (decision L717: a foot track's own L39 heights are
    one with the option ``foot_ramps``). The tables and the summary take it as ``found=`` (session 42): computed
    once, inside the stair grade in force (:func:`info_stair_grade`)."""
    if ramp_source(steps, info) is None:
        return [], np.zeros(0), np.zeros(0)
    valid = _valid(steps)
    length = np.where(valid, pd.to_numeric(steps["length_m"], errors="coerce").to_numpy(float), 0.0)
    dz = np.where(valid, pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float), 0.0)
    unit = str(steps["unit"].iloc[0]) if "unit" in steps else "foot"
    waist = unit == "waist"
    ends = ~steps["has_next"].astype(bool).to_numpy() if waist and "has_next" in steps else None
    found = ramp_runs(length, dz, GRADE_WINDOW_ROWS.get(unit, 1), on_stairs=climb_rows(steps, info),
                      stair_grade_pct=stair_min_grade_pct(steps),  # decision L463
                      lone_stair_joins=waist,  # decision W464: one noisy barometric step splits no ramp
                      window_m=WAIST_SLOPE_WINDOW_M if waist else None, ends=ends,  # decision W517
                      min_rise_m=rest_rise_floor_m(steps) if waist else None,  # decision W519
                      stair_ends=waist,  # decision W530: a flight's blurred ends are no ramps
                      stops=(stop_rows(pd.to_numeric(steps["start_s"], errors="coerce"),
                                       pd.to_numeric(steps["end_s"], errors="coerce"))
                             if "start_s" in steps and "end_s" in steps else None),  # decision L787
                      long_slopes=not waist)  # decision L788: a foot track's long shallow "flight" is a slope
    return found, np.abs(length), dz


def rest_rise_floor_m(steps: pd.DataFrame) -> float | None:
    """Decision W519: the smallest |rise| (m) of a lower-back track's ramp - :data:`RAMP_REST_SWING_FACTOR` x
    :func:`rest_swing_m` of its rows (``still_before_s``, ``pause_dz_m``, the ride rows) - or None (no floor) when
    the table lacks those columns or holds too few standstills."""
    if "still_before_s" not in steps or "pause_dz_m" not in steps:
        return None
    ride = None
    if "ride" in steps:
        r = steps["ride"]
        ride = (r.notna() & r.astype(str).ne("")).to_numpy(bool)  # a ride row, as curbs.py reads it
    swing = rest_swing_m(pd.to_numeric(steps["still_before_s"], errors="coerce").to_numpy(float),
                         pd.to_numeric(steps["pause_dz_m"], errors="coerce").to_numpy(float), ride)
    return None if swing is None else RAMP_REST_SWING_FACTOR * swing


def ramp_table(steps: pd.DataFrame, info: dict | None, trajectory: pd.DataFrame | None = None, *,
               found: FoundRamps | None = None) -> pd.DataFrame:
    """``ramps.csv`` (decision L301): one row per ramp of :func:`ramp_runs` on the rows' ``length_m`` / ``dz_m``
    (numbered from 1, with its first row's ``start_s`` and last row's ``end_s``), L569's compliance flags and
    (L570) its ends' positions on ``trajectory`` (empty without one); no rows (the header alone) where
    :func:`ramp_source` is None (L717). ``found``: :func:`track_ramps` of these rows, when the caller has it."""
    from pdrlearn.track.ramp_audit import audit_flags, with_end_positions

    rows = []
    for k, r in enumerate(table_ramps(steps, info, found), start=1):
        t0, t1 = float(steps["start_s"].iloc[r["first"]]), float(steps["end_s"].iloc[r["last"]])
        rows.append({"ramp": k, "start_s": t0, "end_s": t1, **{c: r[c] for c in RAMP_COLUMNS if c in r},
                     "duration_s": t1 - t0,  # decision L467
                     "speed_mps": r["along_slope_m"] / (t1 - t0) if t1 > t0 else np.nan,
                     **audit_flags(r["max_run_grade_pct"], r["max_run_rise_m"])})  # decisions L569, L588
    return with_end_positions(pd.DataFrame(rows, columns=list(RAMP_COLUMNS)), trajectory)


def table_ramps(steps: pd.DataFrame, info: dict | None, found: FoundRamps | None = None) -> list[dict]:
    """Decision L301: the ramps of :func:`track_ramps` as ramps.csv lists them (and decision L573's curbs leave
    out); none where :func:`ramp_source` is None (L717). ``found``: :func:`track_ramps` of these rows, already found."""
    return (track_ramps(steps, info) if found is None else found)[0]


def climb_rows(steps: pd.DataFrame, info: dict | None = None) -> np.ndarray | None:
    """Decision L314: the rows a lower-back track's W108 puts on stairs (steps.csv's ``climb``: inside a barometric
    climb of 1.5 m or more, the steps its "N steps are on stairs" warning counts), None without the column (a foot
    track: its strides' own grade tells a stair). No ramp is made of them (:func:`ramp_runs`) and no climb of
    them is "ramps" (:func:`pdrlearn.track.evaluate.climb_kind`). Decision L330: only where the track's options
    (``info["options"]``) set ``climb_veto`` - a ramp walked at a normal pace rises W108's 0.1 m/s, so the veto is
    opt-in; None otherwise (the column is still written)."""
    if "climb" not in steps or not ((info or {}).get("options") or {}).get("climb_veto"):
        return None
    from pdrlearn.track.flags import flag_values

    return flag_values(steps["climb"])


def grade_summary(steps: pd.DataFrame, info: dict | None, *, found: FoundRamps | None = None) -> dict:
    """Decision L300: ``grade_source`` (:func:`grade_source`), ``distance_along_slope_m`` (:func:`along_slope_m` of
    the valid rows; None without a source) and ``n_ramps`` (rows of :func:`ramp_table`; None without a source).
    ``found``: :func:`track_ramps` of these rows, when the caller has it. Decision L717: ``ramp_source``
    (:func:`ramp_source`), and ``n_ramps`` / ``max_ramp_grade_pct`` / ``ramps_rise_m`` / ``ramps_drop_m`` (the ramps'
    ``rise_m`` summed up / down, positive) wherever it is not None - a foot track's own ramps too, whose
    ``grade_source`` and ``distance_along_slope_m`` stay None."""
    src, rsrc = grade_source(steps, info), ramp_source(steps, info)
    out = {"grade_source": src, "distance_along_slope_m": None, "n_ramps": None, "max_ramp_grade_pct": None,
           "ramp_source": rsrc, "ramps_rise_m": None, "ramps_drop_m": None}
    if src is not None:
        valid = _valid(steps)
        length = pd.to_numeric(steps["length_m"], errors="coerce").to_numpy(float)[valid]
        dz = pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float)[valid]
        out["distance_along_slope_m"] = along_slope_m(length, dz)
    if rsrc is None:
        return out
    ramps = table_ramps(steps, info, found)
    steepest = max((abs(r["max_run_grade_pct"]) for r in ramps), default=None)  # decision L572
    rises = np.array([r["rise_m"] for r in ramps], dtype=float)
    return {**out, "n_ramps": len(ramps), "max_ramp_grade_pct": steepest,
            "ramps_rise_m": float(rises[rises > 0].sum()), "ramps_drop_m": float(-rises[rises < 0].sum()) + 0.0}
