"""Where a track's time went, and its totals per period (decisions L275-L279, docs/decisions/localization.md).

Decision L275 (time accounting): the time of a window ``[a, b]`` of a session's clock (``track --window``, one
row of periods.csv, or the whole recording of the tracked unit) splits into four parts that sum to ``b - a``:

* ``time_walking_s``: the whole session's walking pieces (:func:`pdrlearn.track.gait.session_walking_pieces`, the
  pieces ``walking_time_s`` sums, decision L79) inside the window, less any data gap;
* ``time_no_data_s``: the tracked unit's stream gaps longer than :data:`pdrlearn.kernels.gaps.MIN_GAP_S` (the gaps
  the track warns of, decision B11) inside the window: nothing is known of what the walker did;
* ``time_between_steps_s``: from the first to the last step counted in the window (the steps whose middle lies
  inside, L105's rule; a gap row is no step), the time that is neither walking nor data gap: standing (or sitting)
  between the window's steps;
* ``time_no_steps_s``: the rest - before the window's first step and after its last (a seated stretch at the
  window's edge, the time before the walk starts): no step of the window bounds it.

Walking and data gap add up over consecutive windows (they are the whole session's, cut); between-steps and
no-step time add up only together (a stop across a window's edge is between steps in the whole session and no-step
time in each window holding a part of it). The session's ``time_walking_s`` is its ``walking_time_s``.

Decision W222 (a lower-back track): the time that is not walking also splits by posture, ``standing_time_s``,
``sitting_time_s``, ``lying_time_s`` and ``unknown_time_s`` (:data:`~pdrlearn.waist.posture_time.POSTURE_KEYS`),
which with ``time_walking_s`` sum to ``b - a`` and add up over consecutive windows; None for a foot track.

Decision L277 (periods.csv, ``track --per 1h``): the whole-session track cut into consecutive periods from the
recording's start (the last one shorter, ``partial``); each row's time columns are L275's for that period, its
steps those whose middle lies inside (distance, n_steps), its bouts those that start inside, its turns (turns.csv)
those whose start lies inside, its storeys those of the climbs whose last stair stride lies inside, its backward and
side strides (decision L484, a foot track's) those whose middle lies inside. Totals equal
the summary's (decision L278). Not re-tracked per period: a re-track would restart the tracker's start-up (the
foot's first rest, its heading), drop the strides across each edge and the position it reached, and cost one
track per period.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.waist.posture_time import POSTURE_KEYS, POSTURES
from pdrlearn.warning_lines import coded

#: decision L275: the summary's time-accounting keys, which sum to ``time_span_s``
TIME_KEYS = ("time_walking_s", "time_between_steps_s", "time_no_steps_s", "time_no_data_s")
#: decision L340: periods.csv's stride length, speed and variability, each the summary's own rule on the period's steps
PERIOD_GAIT_KEYS = ("median_stride_length_m", "median_speed_mps", "stride_time_cv_pct", "stride_length_cv_pct",
                    "n_cv_strides")
#: decision L514: periods.csv's positions at each period's start and end and its net displacement (m)
POSITION_KEYS = ("start_x_m", "start_y_m", "end_x_m", "end_y_m", "dx_m", "dy_m")
#: decisions W476, C246, C247: the periods.csv / segments.csv keys left empty where W442 found the lower back's
#: contacts no step count (summary.json's ``step_count_withheld``)
PERIOD_WITHHELD_KEYS = ("n_steps_both_feet", "median_cadence_spm", "median_stride_time_s", "median_stride_length_m")
#: periods.csv's columns, in order (docs/columns.md; ``session`` / ``subject`` first, bouts.csv's key, L165)
PERIOD_COLUMNS = ("session", "subject", "visit", "period", "start_s", "end_s", "duration_s", "partial", "distance_m",
                  "n_steps", "n_steps_counts", "n_steps_both_feet", "median_stride_time_s", "median_cadence_spm",
                  *PERIOD_GAIT_KEYS, *TIME_KEYS,
                  *POSTURE_KEYS, "floors_up", "floors_down", "ascent_m", "descent_m", "n_bouts", "n_turns",
                  "n_backward_strides", "n_side_strides", "data_gap", "position_sigma_end_m",
                  *POSITION_KEYS, "n_sit_to_stand",  # decision W448: after the columns before it, kept in place
                  "n_turns_left", "n_turns_right", "net_rotation_deg",  # decision L691: W448's way, last
                  "median_stance_pct",  # decision L725: splits.csv's, here too (trial T1: segments.csv had none)
                  "n_steps_with_turns")  # decision W603: W448's way, last
#: decision L277: ``--per`` units (s); decision B305: no "m" (every distance the tool prints is in metres)
PER_UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}
PER_USAGE = "give --per a period such as 1h, 30min, 15min or 3600 (seconds)"
#: decision B329: the shortest --per (s). A period is a row of steps and strides; a step lasts 0.2 s or more even at
#: a 300 steps/min sprint cadence, so a shorter period holds no whole step, and 0.1 s is 10 samples at the 100 Hz
#: the sessions are recorded at. A fixed floor is checked before any session is read (one line, nothing written).
PER_MIN_S = 0.1


def parse_per(text: str | None) -> float | None:
    """``"1h"`` / ``"30min"`` / ``"90s"`` / ``"3600"`` -> seconds; None for None. One :class:`DataError` line for
    anything else (decision L277), for metres (``5m``, ``10M``, a bare ``m``: B305, B329) and for a period under
    :data:`PER_MIN_S` (B329)."""
    if text is None:
        return None
    metres = re.fullmatch(r"\s*([0-9]*\.?[0-9]+)?\s*[mM]\s*", str(text))
    if metres:  # decision B305: "5m" reads as 5 metres next to the metres the tool prints; --per is a time
        n = metres.group(1) or "N"
        raise DataError(f"--per {text!r}: --per is a time, and 'm' reads as metres; give {n}min for "
                        f"minutes (or {n}s, {n}h)")
    m = re.fullmatch(r"\s*([0-9]*\.?[0-9]+)\s*(s|min|h)?\s*", str(text))
    per = float(m.group(1)) * PER_UNITS[m.group(2) or "s"] if m else math.nan
    if not (math.isfinite(per) and per > 0):
        raise DataError(f"--per {text!r}: not a positive period; {PER_USAGE}")
    if per < PER_MIN_S:  # decision B329
        raise DataError(f"--per {text!r}: {per:g} s is shorter than a step; give --per {PER_MIN_S:g}s or more "
                        "(decision B329)")
    return per


def _union(iv) -> np.ndarray:
    """(K, 2) the union of intervals ``iv`` (rows ``(t0, t1)``), sorted and disjoint; empty ones dropped."""
    iv = np.asarray(iv, dtype=float).reshape(-1, 2)
    iv = iv[iv[:, 1] > iv[:, 0]]
    if not len(iv):
        return iv
    iv = iv[np.argsort(iv[:, 0], kind="stable")]
    out = [list(iv[0])]
    for t0, t1 in iv[1:]:
        if t0 <= out[-1][1]:
            out[-1][1] = max(out[-1][1], t1)
        else:
            out.append([t0, t1])
    return np.asarray(out)


def _measure(iv: np.ndarray, a: float, b: float) -> float:
    """Total length (s) of the disjoint intervals ``iv`` inside ``[a, b]``."""
    if not len(iv) or b <= a:
        return 0.0
    return float(np.clip(np.minimum(iv[:, 1], b) - np.maximum(iv[:, 0], a), 0.0, None).sum())


def _minus(iv: np.ndarray, cut: np.ndarray) -> np.ndarray:
    """The disjoint intervals ``iv`` less the disjoint intervals ``cut``."""
    out = []
    for t0, t1 in iv:
        for c0, c1 in cut:
            if c1 <= t0 or c0 >= t1:
                continue
            if c0 > t0:
                out.append((t0, c0))
            t0 = max(t0, c1)
            if t0 >= t1:
                break
        if t1 > t0:
            out.append((t0, t1))
    return _union(out)


def _intersect(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The intersection of two sets of disjoint sorted intervals (two pointers, O(len(x) + len(y)))."""
    out, i, j = [], 0, 0
    while i < len(x) and j < len(y):
        t0, t1 = max(x[i, 0], y[j, 0]), min(x[i, 1], y[j, 1])
        if t1 > t0:
            out.append((t0, t1))
        if x[i, 1] < y[j, 1]:
            i += 1
        else:
            j += 1
    return np.asarray(out, dtype=float).reshape(-1, 2)


def _complement(iv: np.ndarray) -> np.ndarray:
    """The disjoint sorted intervals ``iv``'s complement on the real line."""
    bounds = np.concatenate([[-np.inf], iv.ravel(), [np.inf]])
    return _union(bounds.reshape(-1, 2))


def posture_intervals(postures, busy: np.ndarray) -> dict[str, np.ndarray] | None:
    """Decision W222: per posture (:data:`~pdrlearn.waist.posture_time.POSTURES`), the disjoint intervals of a
    lower-back track's ``info["postures"]`` runs (``[start_s, end_s, posture]``) outside ``busy`` (walking and data
    gaps); None for None (a track without the lower back)."""
    if postures is None:
        return None
    free = _complement(busy)
    out = {}
    for name in POSTURES:
        out[name] = _intersect(_union([(a, b) for a, b, p in postures if p == name]), free)
    return out


def track_postures(info: dict):
    """Decision W222: the posture runs a track's time splits by - a lower-back track's ``info["postures"]``; decision
    W586: on a foot + lower-back track the lower-back unit's own runs (``info["trunk_postures"]``, read by W418 /
    W428's inner waist-pendulum work, the runs a waist-only track of that unit has), split outside the foot's walking;
    None without a lower back."""
    own = info.get("postures")
    return own if own is not None else info.get("trunk_postures")


@dataclass(frozen=True)
class Timeline:
    """A whole-session track's time (decision L275): its walking pieces and data gaps (disjoint, s of the session's
    clock) and its steps' spans (``start``, ``end``; ``is_step`` False on a gap row); ``postures`` (decision W222)
    the standing / sitting / lying intervals outside walking and gaps, None without the lower back."""

    walking: np.ndarray
    no_data: np.ndarray
    start: np.ndarray
    end: np.ndarray
    is_step: np.ndarray
    postures: dict | None = None

    @classmethod
    def of(cls, steps: pd.DataFrame, gaps, postures=None) -> Timeline:
        """From a whole-session step table, ``gaps`` (``(t0, t1)`` intervals of the tracked unit's data gaps) and a
        lower-back track's ``info["postures"]`` (decision W222; None: the posture keys are None)."""
        from pdrlearn.track.gait import session_walking_pieces

        st = steps.sort_values("start_s", kind="stable").reset_index(drop=True) if len(steps) else steps
        no_data = _union(gaps)
        walking = _minus(_union(session_walking_pieces(st)), no_data)
        gap_row = (pd.to_numeric(st["gap_s"], errors="coerce").fillna(0.0).to_numpy(float) > 0 if "gap_s" in st
                   else np.zeros(len(st), bool))
        start = st["start_s"].to_numpy(float) if len(st) else np.zeros(0)
        end = st["end_s"].to_numpy(float) if len(st) else np.zeros(0)
        return cls(walking, no_data, start, end, ~gap_row,
                   posture_intervals(postures, _union(np.vstack([walking, no_data]))))

    def budget(self, a: float, b: float) -> dict:
        """L275's four times (s) of ``[a, b]`` (:data:`TIME_KEYS`), summing to ``b - a``."""
        walk, gap = _measure(self.walking, a, b), _measure(self.no_data, a, b)
        mid = 0.5 * (self.start + self.end)
        inside = self.is_step & (mid >= a) & (mid <= b)  # L105's rule: the steps the window counts
        between = 0.0
        if inside.any():
            f, la = max(a, float(self.start[inside].min())), min(b, float(self.end[inside].max()))
            if la > f:
                between = max(0.0, (la - f) - _measure(self.walking, f, la) - _measure(self.no_data, f, la))
        return {"time_walking_s": walk, "time_between_steps_s": between,
                "time_no_steps_s": max(0.0, (b - a) - walk - gap - between), "time_no_data_s": gap}

    def posture_budget(self, a: float, b: float) -> dict:
        """Decision W222: :data:`POSTURE_KEYS` of ``[a, b]`` (None without the lower back): each posture's time
        outside walking and gaps, and the rest (gaps, no upright) unknown; they sum with L275's
        ``time_walking_s`` to ``b - a``."""
        if self.postures is None:
            return dict.fromkeys(POSTURE_KEYS)
        walk = _measure(self.walking, a, b)
        out = {f"{p}_time_s": _measure(iv, a, b) for p, iv in self.postures.items()}
        out["unknown_time_s"] = max(0.0, (b - a) - walk - sum(out.values()))
        return out


def unit_gaps(session, unit: str | None) -> list[tuple[float, float]]:
    """The data gaps (s) the track warns of (over ``MIN_GAP_S``, decision B11) in the tracked ``unit``'s IMU streams
    (foot: ``fAccelerometer`` / ``fGyroscope``; waist: ``wAccelerometer`` / ``wGyroscope``)."""
    from pdrlearn.track.gaps import long_gaps

    names = ("wAccelerometer", "wGyroscope") if unit == "waist" else ("fAccelerometer", "fGyroscope")
    return [iv for g in long_gaps(session, names).values() for iv in g]


def session_span(session, unit: str | None) -> tuple[float, float]:
    """The whole recording of the tracked ``unit`` (s of the session's clock; the session's start, as
    ``--window``'s seconds count from it, decision B81, to the unit's last sample)."""
    from pdrlearn.track.units import unit_span

    span = unit_span(session, unit) if unit is not None else None
    return float(session.t_recording_start), float(span[1] if span is not None else session.t_end)


def time_summary(timeline: Timeline, a: float, b: float) -> dict:
    """Decision L275: the summary's :data:`TIME_KEYS` of ``[a, b]`` and ``time_span_s`` (= ``b - a``, their sum);
    decision W222: and the :data:`POSTURE_KEYS`."""
    return {**timeline.budget(a, b), **timeline.posture_budget(a, b), "time_span_s": float(b - a)}


def time_accounting(result, session, unit: str | None = None, window: tuple[float, float] | None = None) -> dict:
    """Decision L275: :func:`time_summary` of a whole-session ``result`` over ``window`` (s of the session's clock;
    None = the tracked unit's recording), as ``track`` and ``run`` (B14: the same keys) give it; ``unit`` None:
    the steps' own (waist when every row is the lower back's, else foot). Without a session (a live stream) every
    key is None: no recording's extent or gaps are known."""
    if session is None:
        return {**{k: None for k in (*TIME_KEYS, *POSTURE_KEYS)}, "time_span_s": None}
    steps = result.steps
    if unit is None:
        unit = "waist" if "unit" in steps and len(steps) and (steps["unit"] == "waist").all() else "foot"
    timeline = Timeline.of(steps, unit_gaps(session, unit), track_postures(result.info))
    return time_summary(timeline, *(window if window is not None else held_span(session, unit)))


def held_span(session, unit: str | None) -> tuple[float, float]:
    """Decision C185: the span ``time_span_s`` accounts for without ``--window``: :func:`session_span`'s end, from
    the first sample the session holds - after a ``--common-span`` cut the cut's start (the seconds cut off are
    ``common_span_cut_s``, B267, not time the walker stood: trial T1 finding F8, a cut to 0-246.69 s read
    ``time 248.7 s``), else the recording's first sample as :func:`session_span`'s."""
    return float(session.t_start), session_span(session, unit)[1]


#: decision S69: the lower-back step-length models that read the pelvis's vertical excursion (the inverted pendulum,
#: seed 003 eq. 1), which the simulator's default bounce keeps the same on every step (S29)
BOUNCE_LENGTH_MODELS = ("pendulum",)


def constant_bounce_line(meta: dict, info: dict) -> str | None:
    """Decision S69: the one line ``track --per`` adds when a lower-back track whose step length reads the pelvis's
    bounce (:data:`BOUNCE_LENGTH_MODELS`, ``info["methods"]["length"]``) is of a session meta.json says the simulator
    made (``source_project`` "pdrlearn.sim", with its ``knobs``) with the default constant bounce (``knobs`` has no
    ``bounce``, S29 leaves the default out, or "constant"): its periods' step lengths cannot follow a changing stride.
    meta.json does not record the route (``:long`` / ``:short`` items), so the line is on every such session, whether
    its step length changes or not, and says so (session 32 review item 6). None otherwise (a real recording, a foot
    track, ``--bounce pendulum``, a meta.json without knobs)."""
    knobs = meta.get("knobs")
    if meta.get("source_project") != "pdrlearn.sim" or not isinstance(knobs, dict):
        return None
    if ((info or {}).get("methods") or {}).get("length") not in BOUNCE_LENGTH_MODELS:
        return None
    if knobs.get("bounce", "constant") != "constant":
        return None
    return coded("periods.csv: this simulated session's pelvis bounces the same on every step (simulate's default "
                 "constant bounce, S29) and the lower back's pendulum step length reads that bounce, so where the "
                 "simulated step length changes (:long / :short route items, --step-length) its steps stay about as "
                 "long and a per-period trend in distance, speed or step length is the simulator's, not the walker's "
                 "(trial s32: true median stride 2.05 -> 0.87 m, waist steps 0.685-0.688 m in every period); "
                 "meta.json does not record the route, so this is said on every simulated constant-bounce session, "
                 "whether its step length changes or not; simulate with --bounce pendulum for a study of a changing "
                 "step length, or read the foot's periods (decision S69)", "S69")


#: decision L725: the medians :func:`interval_medians` gives (splits.csv reads them without the CVs)
MEDIAN_KEYS = ("median_stride_time_s", "median_cadence_spm", "median_stride_length_m", "median_speed_mps",
               "median_stance_pct")


def interval_medians(steps: pd.DataFrame, rows: np.ndarray) -> dict:
    """Decision L320: the median stride time and cadence of the interval's steps (``rows``), by the summary's own
    rule (:func:`pdrlearn.track.gait.gait_summary`, its default medians) on those rows; None without a stride time.
    Decision L340: the median stride length (``evaluate.median_stride_length``; lower back: W537) and per-stride
    speed (``gait_summary``) by the summary's rules too. Decision L725: and ``median_stance_pct`` (L73's, None
    without the toe-off columns). :data:`MEDIAN_KEYS`, all None for no row."""
    from pdrlearn.track.evaluate import median_stride_length
    from pdrlearn.track.gait import gait_summary

    if not rows.any():
        return dict.fromkeys(MEDIAN_KEYS)
    st = steps[rows].reset_index(drop=True)
    g = gait_summary(st)
    return {**{k: g.get(k) for k in MEDIAN_KEYS}, "median_stride_length_m": median_stride_length(st)}


def interval_gait(steps: pd.DataFrame, rows: np.ndarray) -> dict:
    """Periods.csv's and segments.csv's gait of the interval's steps (``rows``): :func:`interval_medians` and (decision
    L340) the stride-time and stride-length CVs and their ``n_cv_strides`` (``clinical.clinical_summary``: steady
    straight level forward strides, 10 needed, L104 / L212; foot only, L214) - :data:`PERIOD_GAIT_KEYS` and the rest
    by the summary's own rules on those rows."""
    from pdrlearn.track.clinical import clinical_summary

    out = interval_medians(steps, rows)
    if not rows.any():
        return {**out, **dict.fromkeys(PERIOD_GAIT_KEYS[2:])}
    c = clinical_summary(steps[rows].reset_index(drop=True))
    return {**out, "stride_time_cv_pct": c.get("stride_time_cv_pct"),
            "stride_length_cv_pct": c.get("stride_length_cv_pct"),
            "n_cv_strides": None if (c.get("stride_time_cv_withheld") or {}).get("cause") == "lower_back"
            else c.get("n_cv_strides")}


def period_span(result, session, unit: str | None, window: tuple[float, float] | None = None, *,
                first_step: bool = False) -> tuple[float, float]:
    """Decision L381: the span (s) periods.csv cuts into periods - the tracked ``unit``'s recording
    (:func:`session_span`), or the ``window`` (``--window``, as tracked); ``first_step``: from the first tracked
    step in it (the first row whose middle lies in the span, its ``start_s``: a walk test's "go"). No such step is
    one :class:`DataError` line (decision B292)."""
    from pdrlearn.errors import DataError

    a, b = session_span(session, unit) if window is None else (float(window[0]), float(window[1]))
    if not first_step:
        return a, b
    st = result.steps
    if len(st):
        mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
        inside = (mid >= a) & (mid <= b)
        if inside.any():
            return max(a, float(st["start_s"].to_numpy(float)[inside].min())), b
    where = f"the window {a:g},{b:g} s" if window is not None else "the track"
    raise DataError(f"{session.where}: --per-align first-step: {where} has no step to start the periods from; use "
                    "--per-align start (decision B292)")


def climb_times(steps: pd.DataFrame, info: dict, storey_height_m: float = 3.0) -> tuple[np.ndarray, np.ndarray] | None:
    """The summary's floor climbs (decisions L374-L376; L337: a ramp's climb too) as ``(time_s, storeys)`` arrays, a
    climb at the middle of its last stair row (L394: a ride after the last step is one row more, at its middle;
    ``storeys`` > 0 up, < 0 down), for periods.csv (L277) and bouts.csv (L450); ``None`` when the summary's floors
    come from the altitude (L64). ``steps`` sorted by ``start_s``."""
    from pdrlearn.track.evaluate import _climb_dz, _climb_parts, _with_after, climb_slope_rows, floor_climbs

    mid = 0.5 * (steps["start_s"].to_numpy(float) + steps["end_s"].to_numpy(float)) if len(steps) else np.zeros(0)
    dz, bridge = _climb_dz(steps)
    if dz is None:
        return None
    dz, parts, slope_rows = _with_after(steps, info, dz, _climb_parts(steps), climb_slope_rows(steps, info))
    at = np.concatenate([mid, [0.5 * (float(r["start_s"]) + float(r["end_s"])) for r in info.get("rides") or []
                               if int(r.get("row", -1)) >= len(steps)]])
    climbs = floor_climbs(dz, storey_height_m, bridge=bridge, slope_rows=slope_rows, parts=parts)
    return (np.array([at[i] for i, _ in climbs], dtype=float), np.array([n for _, n in climbs], dtype=float)) \
        if climbs else (np.zeros(0), np.zeros(0))


def bout_floors(bouts: pd.DataFrame, steps: pd.DataFrame, info: dict, storey_height_m: float = 3.0) -> pd.DataFrame:
    """Decision L450: bouts.csv's ``floors_up`` / ``floors_down``, the summary's floor climbs (:func:`climb_times`)
    whose time lies in the bout (``start_s`` to ``end_s``); left empty when the summary's floors come from the
    altitude (L64). A climb outside every bout (a ride between bouts) is in no bout. On a declared inclined belt
    (L442, :func:`pdrlearn.track.belt.declared_incline`) every bout's floors are 0, as the summary's."""
    from pdrlearn.track.belt import declared_incline

    if not len(bouts):
        return bouts
    if declared_incline() is not None:  # decision L442: the belt's virtual climb is no storey
        bouts["floors_up"], bouts["floors_down"] = 0, 0
        return bouts
    steps = steps.sort_values("start_s", kind="stable").reset_index(drop=True) if len(steps) else steps
    climbs = climb_times(steps, info, storey_height_m)
    if climbs is None:
        return bouts
    t, n = climbs
    a, b = bouts["start_s"].to_numpy(float), bouts["end_s"].to_numpy(float)
    inside = (t[None, :] >= a[:, None]) & (t[None, :] <= b[:, None])
    bouts["floors_up"] = [int(n[m & (n > 0)].sum()) for m in inside]
    bouts["floors_down"] = [int(-n[m & (n < 0)].sum()) for m in inside]
    return bouts


def bout_ascent(bouts: pd.DataFrame, result) -> pd.DataFrame:
    """Decision L467: bouts.csv's ``ascent_m`` / ``descent_m``, the summary's rule
    (:func:`pdrlearn.track.evaluate.interval_ascent`) on the trajectory from each bout's ``start_s`` to ``end_s``."""
    from pdrlearn.track.evaluate import interval_ascent

    if len(bouts):
        got = [interval_ascent(result, float(a), float(b)) for a, b in zip(bouts["start_s"], bouts["end_s"],
                                                                            strict=True)]
        bouts["ascent_m"], bouts["descent_m"] = [u for u, _ in got], [d for _, d in got]
    return bouts


def period_displacement(traj: pd.DataFrame, start, end, a: float, b: float, *, last: bool = False) -> dict:
    """Decision L514: :data:`POSITION_KEYS` of the period ``[a, b)`` (``[a, b]`` when ``last``) and their difference;
    None each without trajectory rows. Decision L528: the positions follow ``distance_m``'s stride rule (L277: the
    steps ``start`` / ``end`` (s) whose middle lies inside): the start is the track's position at the end of the last
    step counted before ``a`` (at the first step's start when none is), the end its position at the end of the last
    step counted up to ``b`` (the start when none is), each the last ``traj`` row at or before that instant, so the
    net displacement sums the period's own steps and is never longer than ``distance_m``."""
    if not len(traj) or not {"t", "x", "y"} <= set(traj.columns):
        return dict.fromkeys(POSITION_KEYS)
    start, end = np.asarray(start, float), np.asarray(end, float)
    t_a, t_b = a, b  # no step at all: the instants themselves
    if len(start):
        mid = 0.5 * (start + end)
        before, upto = mid < a, (mid <= b) if last else (mid < b)
        t_a = float(end[before][np.argmax(mid[before])]) if before.any() else float(start.min())
        t_b = float(end[upto][np.argmax(mid[upto])]) if upto.any() else t_a
    tt = traj["t"].to_numpy(float)
    xy = traj[["x", "y"]].to_numpy(float)
    i, j = (max(int(np.searchsorted(tt, v + 1e-9, side="right")) - 1, 0) for v in (t_a, t_b))
    return {"start_x_m": float(xy[i, 0]), "start_y_m": float(xy[i, 1]), "end_x_m": float(xy[j, 0]),
            "end_y_m": float(xy[j, 1]), "dx_m": float(xy[j, 0] - xy[i, 0]), "dy_m": float(xy[j, 1] - xy[i, 1])}


def turn_totals(angle_deg) -> dict:
    """Decision L691: ``n_turns_left`` / ``n_turns_right`` (turns.csv's ``angle_deg`` positive / negative: left +)
    and ``net_rotation_deg`` (their signed sum, deg; 0.0 without a turn) of an interval's turns."""
    a = np.asarray(angle_deg, dtype=float)
    return {"n_turns_left": int((a > 0).sum()), "n_turns_right": int((a < 0).sum()),
            "net_rotation_deg": float(a.sum())}


def rise_times(transfers) -> np.ndarray | None:
    """Decision W448: the start times (s) of a track's sit-to-stand transfers (``info["transfers"]``, a table or
    its records); None without transfers (a foot track: not measured, not zero)."""
    if transfers is None:
        return None
    from pdrlearn.waist.transfers import SIT_TO_STAND

    tr = pd.DataFrame(list(transfers) if not isinstance(transfers, pd.DataFrame) else transfers)
    if not len(tr):
        return np.zeros(0)
    return tr.loc[tr["kind"] == SIT_TO_STAND, "start_s"].to_numpy(float)


def held_starts(session, starts, ends) -> tuple[np.ndarray, np.ndarray]:
    """Decision C185 (amended) / D53: intervals ``[starts, ends)`` (s of the session's clock) accounted from the first
    sample the session holds (after a ``--common-span`` cut the cut's start: its seconds are ``common_span_cut_s``,
    not "no steps"): the starts moved up to it, and whether each interval holds any time after it."""
    lo = float(session.t_start)
    return np.maximum(np.asarray(starts, float), lo), np.asarray(ends, float) > lo + 1e-9


def interval_rows(result, session, starts, ends, closed, *, unit: str | None, bouts: pd.DataFrame | None,
                  turns: pd.DataFrame | None, storey_height_m: float = 3.0) -> list[dict]:
    """Decision L277's row mechanism, shared by periods.csv (:func:`period_table`) and segments.csv (decision L619,
    :func:`segment_table`): one dict per interval ``[starts[k], ends[k])`` of a whole-session track (``[a, b]``
    where ``closed[k]``: each instant in one interval), with the interval's ``start_s`` / ``end_s`` /
    ``duration_s`` and every total of :data:`PERIOD_COLUMNS` after ``partial`` (module docstring); the caller adds
    its own key (``period`` and ``partial``, or ``segment`` and ``label``)."""
    from pdrlearn.track.bouts import session_key
    from pdrlearn.track.evaluate import interval_ascent, step_counts, travel_masks

    steps = result.steps.sort_values("start_s", kind="stable").reset_index(drop=True) if len(result.steps) \
        else result.steps
    timeline = Timeline.of(steps, unit_gaps(session, unit), track_postures(result.info))
    mid = 0.5 * (steps["start_s"].to_numpy(float) + steps["end_s"].to_numpy(float)) if len(steps) else np.zeros(0)
    length = steps["length_m"].abs().to_numpy(float) if len(steps) else np.zeros(0)
    climbs = climb_times(steps, result.info, storey_height_m)
    climb_t, climb_n = climbs if climbs is not None else (np.zeros(0), np.zeros(0))
    bout_t = bouts["start_s"].to_numpy(float) if bouts is not None and len(bouts) else np.zeros(0)
    from pdrlearn.track.clinical import walked_turns

    turns = None if turns is None else walked_turns(turns)  # decision L622: n_turns sums to turn_count
    turn_t = turns["start_s"].to_numpy(float) if turns is not None and len(turns) else np.zeros(0)
    turn_deg = turns["angle_deg"].to_numpy(float) if turns is not None and len(turns) else np.zeros(0)  # L691
    rise_t = rise_times(result.info.get("transfers"))  # decision W448: None on a track without a trunk unit
    traj = result.trajectory
    sigma = traj["pos_sigma_m"].to_numpy(float) if "pos_sigma_m" in traj and len(traj) else None
    tt = traj["t"].to_numpy(float) if len(traj) else np.zeros(0)
    counts = step_counts(steps)["n_steps_counts"]  # decision L320: what n_steps counts, as the summary's
    withheld = bool(result.info.get("step_count_unusable"))  # decision C246: W442's contacts (W476)
    travel = travel_masks(steps)  # decision L484: the backward / side strides of the summary's counts
    starts_s, stops_s = (steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)) if len(steps) \
        else (np.zeros(0), np.zeros(0))
    from pdrlearn.waist.turn_steps import stepless_steps, steps_with_turns

    # decision W603: W331's stepless turns' steps, each in the interval holding its midpoint (None: not judged)
    stepless = stepless_steps(steps["event_s"] if "event_s" in steps else [], result.info.get("yaw_turns"))
    turn_mid, turn_n = (np.array([t for t, _ in stepless], float), np.array([n for _, n in stepless], int)) \
        if stepless else (np.zeros(0), np.zeros(0, int))
    rows = []
    for a, b, last in zip(starts, ends, closed, strict=True):
        a, b, last = float(a), float(b), bool(last)

        def inside(t, a=a, b=b, last=last):  # each time in one interval: [a, b), a closed one [a, b]
            return (t >= a) & ((t <= b) if last else (t < b))

        m = inside(mid)
        row = {**session_key(session), "start_s": a, "end_s": b, "duration_s": b - a,
               "distance_m": float(length[m].sum()), "n_steps": int(m.sum()), "n_steps_counts": counts,
               # decision L449: both feet's steps whatever the unit, as the summary's (2 per foot stride)
               "n_steps_both_feet": step_counts(steps[m])["n_steps_both_feet"],
               **interval_gait(steps, m), **timeline.budget(a, b), **timeline.posture_budget(a, b)}
        c = inside(climb_t)
        row["floors_up"] = int(climb_n[c & (climb_n > 0)].sum()) if climbs is not None else None  # L277
        row["floors_down"] = int(-climb_n[c & (climb_n < 0)].sum()) if climbs is not None else None
        row["ascent_m"], row["descent_m"] = interval_ascent(result, a, b)  # decision L467
        row["n_bouts"], row["n_turns"] = int(inside(bout_t).sum()), int(inside(turn_t).sum())
        row.update(turn_totals(turn_deg[inside(turn_t)]))  # decision L691: the same turns, by side and summed
        row["n_sit_to_stand"] = None if rise_t is None else int(inside(rise_t).sum())  # decision W448
        row["n_backward_strides"], row["n_side_strides"] = ((None, None) if travel is None  # L484: lower back
                                                            else (int(travel[0][m].sum()), int(travel[1][m].sum())))
        row["data_gap"] = row["time_no_data_s"] > 0
        j = int(np.searchsorted(tt, b + 1e-9, side="right")) - 1
        row["position_sigma_end_m"] = float(sigma[j]) if sigma is not None and j >= 0 else None
        row.update(period_displacement(traj, starts_s, stops_s, a, b, last=last))  # L514, L528
        row["n_steps_with_turns"] = steps_with_turns(row["n_steps"], None if stepless is None else int(
            turn_n[inside(turn_mid)].sum()), withheld)  # decision W603
        if withheld:  # decisions W476, C246, C247: the contacts are no step count, nor their cadence or strides
            row.update(dict.fromkeys(PERIOD_WITHHELD_KEYS))
        rows.append(row)
    return rows


def period_table(result, session, per_s: float, *, unit: str | None, bouts: pd.DataFrame | None,
                 turns: pd.DataFrame | None, storey_height_m: float = 3.0, clock=None,
                 span: tuple[float, float] | None = None) -> pd.DataFrame:
    """Decision L277: periods.csv of a whole-session track (:data:`PERIOD_COLUMNS`, module docstring), periods of
    ``per_s`` seconds from the recording's start to the tracked ``unit``'s end; ``bouts`` bouts.csv's table,
    ``turns`` turns.csv's. Decision L299: ``clock`` (the clock time of the session's 0 s, a datetime) cuts them at
    the clock's whole periods instead (``--per-align clock``: 1h = the clock hours), the first and last partial.
    Decision L381: ``span`` (s, :func:`period_span`: a ``--window`` or the first step) replaces the recording's.
    Decision C185 (amended): no period accounts for time before the session's first held sample (a
    ``--common-span`` cut's seconds are ``common_span_cut_s``, not "no steps"); the first period starts there."""
    from pdrlearn.track.clock import clock_edges

    t0, t1 = session_span(session, unit) if span is None else span
    edges = np.arange(t0, t1, per_s) if clock is None else clock_edges(t0, t1, per_s, clock)
    ends = np.minimum(edges + per_s, t1) if clock is None else np.r_[edges[1:], t1]
    closed = np.arange(len(edges)) == len(edges) - 1  # the last period holds its end
    # decision C185 amended (review R2 finding 5): the edges stay the recording's (B81), but each period is accounted
    # from the first sample the session holds (held_span: after a --common-span cut its start), so the periods add up
    # to time_span_s; a period wholly cut off is none
    starts, held = held_starts(session, edges, ends)
    starts, ends, closed = starts[held], ends[held], closed[held]
    rows = interval_rows(result, session, starts, ends, closed, unit=unit, bouts=bouts, turns=turns,
                         storey_height_m=storey_height_m)
    for k, row in enumerate(rows):
        row["period"] = k + 1
        row["partial"] = bool(row["duration_s"] < per_s - 1e-9)
    return pd.DataFrame(rows, columns=list(PERIOD_COLUMNS))


#: decision W563: periods.csv's columns on the corridor's scale (a lower-back track with a scored corridor walk test)
CORRIDOR_COLUMNS = ("distance_corridor_m", "speed_corridor_mps")


def with_corridor_scale(periods: pd.DataFrame, scale: float) -> pd.DataFrame:
    """Decision W563: periods.csv with :data:`CORRIDOR_COLUMNS`: ``distance_m`` x ``scale`` (W562's
    ``walk_test_scale``, the corridor's scale of the lower back's step lengths) and that over ``time_walking_s``
    (empty without walking); the step lengths' own ``distance_m`` stays."""
    out = periods.copy()
    dist = pd.to_numeric(out["distance_m"], errors="coerce") * float(scale)
    walking = pd.to_numeric(out["time_walking_s"], errors="coerce") if "time_walking_s" in out else None
    out["distance_corridor_m"] = dist
    out["speed_corridor_mps"] = dist / walking.where(walking > 0) if walking is not None else np.nan
    return out
