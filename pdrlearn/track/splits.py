"""Split times at given distances along the tracked path (``track --splits 5,10,20``; decisions L411, B307,
docs/decisions/localization.md and bad-input.md).

A sprint or shuttle test is timed at distance marks (5 / 10 / 20 m). From a track: the path distance grows along
each row of the step table from the row's start (the distance before it) to its contact (its cumulative |length|),
and stays put between rows (a rest adds no distance) - :func:`pdrlearn.track.corridor._distance_in_time`, the
corridor laps' own clock. The time a mark is passed is interpolated linearly within the row that crosses it, and
counted from the first row's start. Pure functions of the step table.

Decision L553: ``--splits every:1000`` marks every 1000 m up to the path's end and ends with the final partial
split at the path's end (a 9163 m march: 1000, ..., 9000 and 9163 m); L554: each split's pace (min/km).

Decision L725: each split's strides - the rows whose middle (in time) lies between the previous mark's crossing and
this mark's (the last split holding its end), segments.csv's and periods.csv's interval rule - give its ``n_steps``
and, by the summary's own rules (:func:`pdrlearn.track.periods.interval_medians`, without periods.csv's CVs), its
median cadence, stride length and stance %. The laps are the tracked distance's: a 1 % distance error moves a 400 m
mark by 4 m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.warning_lines import coded

#: decision L411: splits.csv's columns
#: decision L725: each split's strides (periods.csv's and segments.csv's quantities, and L73's stance %)
STRIDE_KEYS = ("n_steps", "median_cadence_spm", "median_stride_length_m", "median_stance_pct")
SPLIT_COLUMNS = ("split", "distance_m", "time_s", "split_time_s", "speed_mps", "pace_min_per_km",  # L554: pace
                 *STRIDE_KEYS)
#: decision L411: the summary keys :func:`split_table` gives
KEYS = ("splits_m", "split_times_s")


#: decision L553: the step form's prefix (``--splits every:1000``)
EVERY = "every:"
#: decision B420: the shortest ``every:STEP`` (m): about a step (a foot track's row is a stride, ~1.4 m); a finer mark
#: is only interpolated within one row, and every:0.01 wrote 24,029 rows for a 240 m walk
MIN_EVERY_M = 1.0
#: decision L563: the console's split line names at most this many marks (the first ones and the last two); every
#: mark stays in splits.csv and summary.json ``splits_m``
MAX_LINE_SPLITS = 12


@dataclass(frozen=True)
class EverySplit:
    """Decision L553: ``--splits every:STEP``: a mark every ``step_m`` metres up to the path's end, then the end."""

    step_m: float

    def marks(self, path_m: float) -> np.ndarray:
        """The marks of a path ``path_m`` long: each whole step on it, then ``path_m`` itself (the final partial
        split, rounded down to the cm so the path reaches it) when the path goes on past the last whole step."""
        n = int(math.floor(path_m / self.step_m + 1e-9))
        whole = self.step_m * np.arange(1, n + 1)
        end = math.floor(path_m * 100.0 + 1e-6) / 100.0  # + 1e-6: a sum of 13.3 m is 13.2999...
        return np.append(whole, end) if end > (whole[-1] if n else 0.0) else whole


def parse_splits(text: str | None) -> tuple[float, ...] | EverySplit | None:
    """Decision B307: ``--splits`` as distances in metres (``5,10,20``): positive, finite and increasing, else one
    error line naming the option and the fix; None when not given. Decision L553: ``every:STEP`` (one positive
    distance in metres) gives an :class:`EverySplit`."""
    if text is None:
        return None
    fix = ("give increasing distances in metres along the path from the first step, e.g. --splits 5,10,20, or a "
           "mark every STEP metres, e.g. --splits every:1000")
    if str(text).strip().lower().startswith(EVERY):  # decision L553
        step = str(text).strip()[len(EVERY):].strip()
        try:
            step_m = float(step)
        except ValueError:
            step_m = float("nan")
        if not math.isfinite(step_m) or step_m <= 0:
            raise DataError(f"--splits {text!r}: {step!r} is not a positive distance; {fix}")
        if step_m < MIN_EVERY_M:  # decision B420
            raise DataError(f"--splits {text!r}: a mark every {step_m:g} m is finer than a step (at least "
                            f"every:{MIN_EVERY_M:g}); give a mark every {MIN_EVERY_M:g} m or more, e.g. --splits "
                            "every:100, or list the marks, e.g. --splits 5,10,20")
        return EverySplit(step_m)
    parts = [p.strip() for p in str(text).split(",")]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise DataError(f"--splits {text!r}: not a list of numbers; {fix}") from None
    bad = [p for p, v in zip(parts, values, strict=True) if not math.isfinite(v) or v <= 0]
    if bad:
        raise DataError(f"--splits {text!r}: {', '.join(bad)} {'is' if len(bad) == 1 else 'are'} not a positive "
                        f"distance; {fix}")
    if any(b <= a for a, b in zip(values, values[1:], strict=False)):
        raise DataError(f"--splits {text!r}: the distances do not increase; {fix}")
    return tuple(values)


def _crossing_times(steps: pd.DataFrame, marks: np.ndarray) -> tuple[np.ndarray, float, float]:
    """Times (s, from the first row's start) at which the path passes each of ``marks`` (m; NaN beyond the path),
    the path's length (m) and the first row's start (s)."""
    from pdrlearn.track.corridor import _distance_in_time  # the corridor laps' distance clock (L384)

    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    t, d = _distance_in_time(st)
    marks = np.asarray(marks, float)
    out = np.full(len(marks), np.nan)
    k = np.searchsorted(d, marks, side="left")  # the first point at or past each mark
    on = k < len(d)
    k, m = k[on], marks[on]
    b = np.maximum(k - 1, 0)
    flat = (k == 0) | (d[k] == d[b])  # the mark is a point of the clock itself
    span = np.where(flat, 1.0, d[k] - d[b])
    # linear within the row that crosses it (its start at d[k-1], its contact at d[k]); decision L563: one pass
    out[on] = np.where(flat, t[k], t[b] + (m - d[b]) / span * (t[k] - t[b]))
    return out - float(t[0]), float(d[-1]), float(t[0])


def split_table(steps: pd.DataFrame, marks) -> tuple[pd.DataFrame, dict, list[str]]:
    """Decision L411: ``(splits, summary, warnings)`` of a tracked step table timed at the distance ``marks`` (m):
    splits.csv's rows (:data:`SPLIT_COLUMNS`, one per mark the path reaches), the summary's :data:`KEYS` (a mark
    beyond the path has a None time) and one warning line naming the marks beyond the tracked path. ``marks`` may be
    an :class:`EverySplit` (decision L553): its marks on this path, the last one the path's end."""
    if isinstance(marks, EverySplit):  # decision L553: the marks depend on the path's length
        ok = len(steps) and {"start_s", "end_s", "length_m"} <= set(steps.columns)
        marks = marks.marks(_crossing_times(steps, np.empty(0))[1]) if ok else np.array([marks.step_m])
    marks = np.asarray(list(marks), float)
    keys = {"splits_m": [float(m) for m in marks], "split_times_s": [None] * len(marks)}
    empty = pd.DataFrame(columns=list(SPLIT_COLUMNS))
    if not len(steps) or not {"start_s", "end_s", "length_m"} <= set(steps.columns):
        return empty, keys, [coded("--splits: no steps; no split times (decision L411)", "L411")]
    times, path_m, t0 = _crossing_times(steps, marks)
    reached = np.isfinite(times)
    rows = []
    prev_d, prev_t = 0.0, 0.0
    strides = _split_strides(steps, t0, times[reached])  # decision L725
    for n, (m, t) in enumerate(zip(marks[reached], times[reached], strict=True), start=1):
        dt = float(t - prev_t)
        rows.append({"split": n, "distance_m": float(m), "time_s": float(t), "split_time_s": dt,
                     "speed_mps": float((m - prev_d) / dt) if dt > 0 else float("nan"),
                     # decision L554: minutes per kilometre of this split (a march's pace)
                     "pace_min_per_km": float(dt / 60.0 / ((m - prev_d) / 1000.0)) if m > prev_d else float("nan"),
                     **strides[n - 1]})
        prev_d, prev_t = float(m), float(t)
    keys["split_times_s"] = [float(t) if np.isfinite(t) else None for t in times]
    lines = []
    if (~reached).any():
        beyond = ", ".join(f"{m:g}" for m in marks[~reached])
        lines.append(coded(f"--splits: the tracked path is {path_m:.2f} m long; no split time at {beyond} m beyond "
                           "it (decision L411)", "L411"))
    return (pd.DataFrame(rows, columns=list(SPLIT_COLUMNS)) if rows else empty), keys, lines


def _split_strides(steps: pd.DataFrame, t0: float, times: np.ndarray) -> list[dict]:
    """Decision L725: per split (crossing ``times``, s from the first row's start ``t0``) its :data:`STRIDE_KEYS`:
    the rows whose middle (a lower-back contact row: its start, where the clock credits its length; review R2 F4)
    lies in ``[previous crossing, this crossing)`` (the last split ``[.., ..]``, as periods.csv's last period, L277)
    and their medians by :func:`pdrlearn.track.periods.interval_medians` (not the CVs periods.csv adds: with them
    ``every:10`` on a 2.8 km walk took 4.05 s CPU for its 280 splits, 1.13 s without)."""
    from pdrlearn.track.clinical import _is_lower_back
    from pdrlearn.track.periods import interval_medians

    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float)) - t0
    if _is_lower_back(st):  # review R2 F4 (session 48): the clock credits a contact's length at its start
        mid = st["start_s"].to_numpy(float) - t0
    out, prev = [], 0.0
    for k, t in enumerate(times):
        rows = (mid >= prev) & ((mid <= t) if k == len(times) - 1 else (mid < t))
        gait = interval_medians(st, rows)
        out.append({"n_steps": int(rows.sum()), **{key: gait.get(key) for key in STRIDE_KEYS[1:]}})
        prev = float(t)
    return out


def splits_line(summary: dict) -> str | None:
    """Decision L411: the summary's one line of split times (``splits 5 m 1.83 s, 10 m 3.35 s (+1.52 s)``), None
    without ``--splits``."""
    marks, times = summary.get("splits_m"), summary.get("split_times_s")
    if not marks:
        return None
    parts, prev = [], None
    for m, t in zip(marks, times or [None] * len(marks), strict=True):
        if t is None:
            parts.append(f"{m:g} m not reached")
            continue
        parts.append(f"{m:g} m {t:.2f} s" + (f" (+{t - prev:.2f} s)" if prev is not None else ""))
        prev = t
    if len(parts) > MAX_LINE_SPLITS:  # decision L563: the first marks, how many are left out, the last two
        left = len(parts) - MAX_LINE_SPLITS
        parts = [*parts[:MAX_LINE_SPLITS - 2], f"... {left} more ...", *parts[-2:]]
        return f"splits from the first step: {', '.join(parts)} ({len(marks)} marks; all in splits.csv)"
    return "splits from the first step: " + ", ".join(parts) + " (splits.csv)"
