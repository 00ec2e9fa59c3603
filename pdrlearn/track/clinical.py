"""Clinical walk measures of a tracked step table (decision L104, docs/decisions/localization.md): turns, pauses
and walking bouts, stride-time variability.

Every measure works on the rows of ``steps.csv`` of either pipeline: a foot track's rows are the tracked foot's
strides (rest to rest, ``start_s`` the rest before the stride), a lower-back track's rows its steps (``start_s``
the initial contact). Definitions (seconds and degrees, no sample counts):

* **pause**: the interval from one row's ``start_s`` to the next row's is at least :data:`PAUSE_MIN_S` longer than the
  walk's median such interval (the walker's own rhythm: one stride of the tracked foot, one step on the lower back; on
  a foot table, when that median exceeds the median of its movement windows (touching rows joined) by
  :data:`PAUSE_MIN_S` or more, that window median instead, decisions L482 and L500, so a stop-and-go walk whose
  intervals mostly hold a stand is not judged against the stand); the excess is the pause's length. So a pause is
  standing (no step of the tracked foot / of either foot) for about a second or more beyond the usual rhythm; the
  rests of a slow walker's ordinary stance are no pause. Rows across a foot-data gap (``gap_s`` > 0, L67) are not
  judged: a sensor gap is not a pause. An interval across which the heading turns :data:`PAUSE_MAX_TURN_DEG` or more
  holds a turn: the time that turn takes at :data:`TURN_ON_SPOT_MIN_DPS` is turning (a slow turn on the spot is no
  pause), only the excess beyond it is standing (decision L119: a long stand before or after a turn is a pause and the
  turn still counts).
* **walking bout**: the walk between pauses: ``n_walking_bouts`` = ``n_pauses`` + 1 (0 without a row); decision
  L269: a foot-data gap row longer than the pause threshold ends a bout too (the gap row in none); the time in data
  gaps is L275's ``time_no_data_s``.
* **turn**: a run of consecutive rows whose heading changes at :data:`TURN_RATE_MIN_DPS` deg/s or more from
  one row to the next (heading change / time between the rows' starts; one slower row between two such rows
  belongs to the turn, unless it walks - :func:`walking_rows`, decision L653), its angle the summed (signed)
  change, with the change of the row just before and just after the run when it turns the same way and belongs to
  no other turn (decision L181: a corner's edge strides);
  ``turn_count`` counts the turns of at least :data:`TURN_COUNT_MIN_DEG` degrees (turnarounds, corners); a gentle
  curve (below 15 deg/s, e.g. a 5 m radius at 1.2 m/s) or a pause is no turn; an interval holding a pause and a
  heading change of :data:`PAUSE_MAX_TURN_DEG` or more turns (L119: the turn took the time beside the
  standing). The heading of a foot row is the foot's own yaw, summed over ``turn_angle_rad`` where every row has
  it (the stride's displacement direction of a turn on the spot is short and noisy), else ``heading_rad``.
* **stride-time variability** (foot tracks): ``stride_time_cv_pct`` = 100 x SD / mean (SD with n - 1) of the
  stride times (initial contact to initial contact, L66) of the steady straight strides: a level (|``dz_m``|
  under 0.10 m, L179) forward (``direction`` not backward, where a model gave it; no side step of L219's
  runs, the foot table's ``sideways`` column, L228) stride turning under 15 deg
  (L79, L188) with a stride time, not next to a pause, whose previous and next strides are such strides too
  (the strides into and out of a turn or a stop slow down; a stride time across a short stop is no rhythm);
  None with fewer than :data:`CV_MIN_STRIDES` of them. None on the lower back: its contacts scatter (on
  simulated straight walks whose true CV is 1.7-2.1 % it gave 6.2-9.7 %). ``stride_time_cv_withheld`` says why
  (decisions L214, L215). ``stride_length_cv_pct`` (decision L212): the same strides' lengths' CV;
  ``stride_length_cv_within_segments_pct`` (decision L380): their lengths about each straight stretch's own mean.
* **contact timing check** (decision L113): the same strides' swing onsets (``start_s``) recur with the gait
  period too, so with contacts timed as well as the onsets the two stride-time SDs agree. Each contact's own
  timing scatter, estimated as sqrt((SD_contacts^2 - SD_onsets^2) / 2) (independent scatter of both contacts of
  a stride time adds twice its variance), of :data:`CONTACT_SCATTER_MAX_S` or more makes the CV the contacts'
  scatter rather than the walker's rhythm: ``stride_time_cv_pct`` is then None, ``stride_time_cv_withheld``
  holds both CVs and :func:`stride_cv_warning` says why (a foot IMU without force sensors whose contact moves
  between the heel strike and a later peak, trial of session 19). Not adopted as the default (L113's rule
  failed on one user): off unless ``contact_scatter_max_s`` is given (:data:`CONTACT_SCATTER_OPTION_S`).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

# decision E320: the CV, its minimum and the symmetry index, numpy only, shared with the lean runtime's gait values
from pdrlearn.kernels.gait_values import CV_MIN_STRIDES, cv_pct, symmetry_index_pct  # noqa: F401
from pdrlearn.kernels.rests import between_rows
from pdrlearn.kernels.yaw_turns import TURN_TIMING_FRACTIONS as _TURN_TIMING_FRACTIONS
from pdrlearn.track.flags import flag_values
from pdrlearn.track.turn_gaps import filled_intervals
from pdrlearn.waist.turn_steps import CARRIED

#: a pause is at least this much (s) longer than the walk's median row-to-row interval
PAUSE_MIN_S = 1.0
#: an interval across which the heading changes this much (deg) or more holds a turn: the time the turn may take
#: (:data:`TURN_ON_SPOT_MIN_DPS`) is no pause (decision L119)
PAUSE_MAX_TURN_DEG = 30.0
#: decision L119: the slowest turn on the spot the pause rule allows for (deg/s): a 180 deg turn in 9 s; the time
#: of an interval's turn at this rate is turning, the rest beyond the walk's rhythm standing
TURN_ON_SPOT_MIN_DPS = 20.0
#: a row turns when its heading changes at this rate (deg/s) or more from the previous row
TURN_RATE_MIN_DPS = 15.0
#: ``turn_count`` counts turns of at least this angle (deg)
TURN_COUNT_MIN_DEG = 80.0

#: decision L113's candidate: a contact timing scatter (s) of this much or more withholds ``stride_time_cv_pct``
#: (two contacts per stride time: it contributes sqrt(2) x 30 ms = 42 ms (in quadrature) to the SD of a ~1.1 s
#: stride, 3.9 %, more than a healthy walker's CV of 1-3 %)
CONTACT_SCATTER_OPTION_S = 0.030
#: the default: off (inf). L113's rule was not met (R2: one printed CV 3.89 % > 2 x 1.38 % + 1), so the check is
#: an option: ``clinical_summary(steps, contact_scatter_max_s=CONTACT_SCATTER_OPTION_S)``
CONTACT_SCATTER_MAX_S = math.inf
#: ``step_time_asymmetry_pct``: a walking sequence counts with at least this many step times of each foot
ASYMMETRY_MIN_STEPS = 4

#: decision L116: warn when rounding whole-sample contacts alone raises the reported stride-time CV by this much (%):
#: the simulated walkers at 100 Hz read 2.09 % for a true 2.01 % (+4 %), at 20 Hz 2.81 % (+40 %; session 20 trial);
#: at 10 % the rounding's SD is 0.46 of the walker's own stride-time SD
QUANTISATION_WARN_PCT = 10.0
#: decision L116: the summary's ``contact_timing`` values
WHOLE_SAMPLES, BETWEEN_SAMPLES = "whole samples", "between samples"

#: decision L196: a walking bout's own stride-time CV needs at least this many of the CV's steady strides in it
#: (L123's minimum of strides for a figure)
CV_BOUT_MIN_STRIDES = 5
#: decision L196: the pooled CV is named as pooling bouts of different rhythm when it exceeds the within-bout CV
#: by this factor (a priori: pooled^2 = within^2 + between^2, so the bouts' differences then carry more than three
#: quarters of the variance); the session-27 trial's walk / run / walk: 16.4 % pooled, ~2 % in each part
CV_POOLED_FACTOR = 2.0

#: the keys :func:`clinical_summary` gives every summary (None / 0 when the table cannot give them)
CLINICAL_KEYS = ("n_pauses", "pause_time_s", "longest_pause_s", "pause_seated_lying_s", "n_walking_bouts", "turn_count",
                 "turn_count_min_deg", "stride_time_cv_pct", "n_cv_strides", "stride_time_cv_withheld",
                 "stride_time_cv_within_bouts_pct", "stride_time_cv_bouts", "stride_length_cv_pct",
                 "stride_length_cv_within_segments_pct", "n_cv_segments", "stride_time_cv_direction")

#: decision L214: ``stride_time_cv_withheld["cause"]`` - the lower back (L104: never a CV), too few steady strides
#: (:data:`CV_MIN_STRIDES`), or the contacts' timing scatter (L113, an option)
CV_WITHHELD_CAUSES = ("lower_back", "too_few_strides", "contact_scatter")
#: decision W557 (measured, session 49): what the lower back's contacts make of the stride-time CV: steps.csv's
#: contacts of fresh simulated straight 60 m walks (users 16300-16311, 100 Hz) read 1.7-3.3 x the walker's
LOWER_BACK_CV_INFLATION = ("its contacts' timing reads the stride-time CV 1.7-3.3 x the walker's (simulated walks of "
                           "true CV 1.5-2.2 % read 3.6-5.8 %, the step-time CV 2.3-3.1 % read 6.4-11.9 %)")
#: decision L214: L104's reason the lower back gives no stride-time CV (decision W559: with W557's numbers, and not
#: to be taken from steps.csv's contacts either)
LOWER_BACK_CV_REASON = (f"not given on the lower back: {LOWER_BACK_CV_INFLATION}, so do not compute it from "
                        "steps.csv's contacts either (decisions L104, W557); a unit on the foot gives it")
#: decision W558: the lower back's jitter-corrected stride-time CV (:func:`jitter_free_cv`) is given from this many
#: strides on (the fewest of the 150 m walks it was adopted on; on 60 m walks, 67-86 strides, it failed its rule)
JITTER_FREE_MIN_STRIDES = 181
#: decision W558: a walking bout's contacts count from this many (W557's measurement: bouts of 8 contacts or more)
JITTER_FREE_MIN_CONTACTS = 8
#: decision W558 (review R2 F4): what JITTER_FREE_MIN_STRIDES counts: the stride intervals t[k+2] - t[k] of each run
#: (W598: a steady straight run of a bout, :func:`steady_runs`; n contacts give n - 6, :func:`jitter_free_cv`), not
#: one foot's strides
JITTER_FREE_WALK = (f"a walk of {JITTER_FREE_MIN_STRIDES} stride intervals or more (about "
                    f"{JITTER_FREE_MIN_STRIDES + 6} steps in one run; each steady straight run of "
                    f"{JITTER_FREE_MIN_CONTACTS} steps or more, W598: no turn, no extra or missed contact, gives its "
                    "steps less 6)")
#: decision L215: the withheld line names the level criterion (L188's |dz_m| < 0.10 m) when it removed more than
#: this share of the straight strides (the trial's MS walk: 49 of 74 strides over 0.10 m by attitude drift)
NOT_LEVEL_SHARE = 0.5


def _valid(steps: pd.DataFrame) -> np.ndarray:
    return (steps["gap_s"].to_numpy(float) == 0) if "gap_s" in steps else np.ones(len(steps), bool)


def pauses(steps: pd.DataFrame, *, min_s: float = PAUSE_MIN_S, turn_gaps=None) -> np.ndarray:
    """(P,) the lengths (s) of the walk's pauses (module docstring), in time order; ``turn_gaps`` (decision C180,
    :class:`~pdrlearn.track.turn_gaps.TurnGaps`): an interval a walker's turn fills is no pause."""
    if len(steps) < 2:
        return np.zeros(0)
    excess, is_pause = _intervals(steps.sort_values("start_s", kind="stable").reset_index(drop=True), min_s,
                                  turn_gaps)
    return excess[is_pause]


def pause_spans(steps: pd.DataFrame, *, min_s: float = PAUSE_MIN_S, turn_gaps=None) -> np.ndarray:
    """(P, 2) each pause's time span (s, the session's clock): the last ``excess`` seconds before the row that
    ends it starts - the standing before the walker sets off again (decision L110: the time
    ``walking_speed_mps`` leaves out). Its length is :func:`pauses`'s (``turn_gaps``: decision C180, as there)."""
    if len(steps) < 2:
        return np.zeros((0, 2))
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    excess, is_pause = _intervals(st, min_s, turn_gaps)
    t_next = st["start_s"].to_numpy(float)[1:][is_pause]
    return np.column_stack([t_next - excess[is_pause], t_next])


def bout_rows(steps: pd.DataFrame, *, min_s: float = PAUSE_MIN_S, turn_gaps=None) -> list[tuple[int, int]]:
    """The walk's walking bouts (module docstring: the rows between pauses of at least ``min_s``) as
    ``(first, last + 1)`` row ranges of the table in ``start_s`` order (decision L124's per-bout table); decision
    L269: a foot-data gap row longer than ``min_s`` ends a bout too (:func:`split_at_data_gaps`); decision C180:
    an interval a walker's turn of ``turn_gaps`` fills ends none (:func:`turn_filled`)."""
    if not len(steps):
        return []
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    if len(st) < 2:
        return split_at_data_gaps(st, [(0, 1)], min_s)
    _, is_pause = _intervals(st, min_s, turn_gaps)
    cuts = [0, *(np.flatnonzero(is_pause) + 1).tolist(), len(st)]
    return split_at_data_gaps(st, list(zip(cuts[:-1], cuts[1:], strict=True)), min_s)


def data_gap_lengths(steps: pd.DataFrame) -> np.ndarray:
    """(N,) each row's foot-data gap (s; ``gap_s`` of a gap row, L67), 0 for a stride and for a table without the
    column (a lower-back table)."""
    if "gap_s" not in steps:
        return np.zeros(len(steps))
    return np.nan_to_num(pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float))


def split_at_data_gaps(st: pd.DataFrame, ranges: list[tuple[int, int]], break_s: float) -> list[tuple[int, int]]:
    """Decision L269: the bout ranges ``[a, b)`` of ``st`` (rows in ``start_s`` order) cut at each gap row (L67)
    whose ``gap_s`` is longer than the bout rule's break ``break_s``: what the walker did in a data gap longer than
    a pause is not known to be walking, so the walks before and after it are two bouts, and the gap row itself
    (0 m, no stride) is in neither. A shorter gap row stays in its bout (bouts.csv's ``data_gap_s`` says so)."""
    long = data_gap_lengths(st) > break_s
    if not long.any():
        return ranges
    out = []
    for a, b in ranges:
        for g in (np.flatnonzero(long[a:b]) + a).tolist():
            if g > a:
                out.append((a, g))
            a = g + 1
        if b > a:
            out.append((a, b))
    return out


def _intervals(st: pd.DataFrame, min_s: float = PAUSE_MIN_S, turn_gaps=None) -> tuple[np.ndarray, np.ndarray]:
    """(N - 1,) each row-to-row interval's excess over the median interval (s) and whether it is a pause; rows
    in time order; decision C180: an interval a walker's turn of ``turn_gaps`` fills is no pause."""
    t = st["start_s"].to_numpy(float)
    ok = _valid(st)
    lo, hi = between_rows(t, t)  # start to start (np.diff's intervals)
    d = hi - lo
    pair = ok[:-1] & ok[1:] & np.isfinite(d)
    if not pair.any():
        return np.zeros(len(d)), np.zeros(len(d), bool)
    from pdrlearn.track.trunk_pauses import trunk_pauses

    trunk = trunk_pauses(st)  # decision L687: a two-unit foot table's pauses are the lower back's stops
    excess = d - rhythm_s(st, d, pair) if trunk is None else trunk[1:]
    if "heading_rad" in st:  # decision L119: a turn across the interval takes its time, the rest is standing
        with np.errstate(invalid="ignore"):
            dh = np.abs(np.diff(np.degrees(unwrapped_heading(st))))
            # decision L372: at most the interval's time that was not still (a still stretch is standing)
            allow = np.minimum(dh / TURN_ON_SPOT_MIN_DPS, np.maximum(d - still_before(st)[1:], 0.0))
            excess = excess - np.where(dh >= PAUSE_MAX_TURN_DEG, allow, 0.0)
    is_pause = pair & (excess >= min_s)
    if turn_gaps is not None and is_pause.any():  # decision C180: a turn fills the interval: walking, no pause
        is_pause &= ~filled_intervals(lo, hi, turn_gaps, rhythm_s(st, d, pair), min_s)
    return excess, is_pause


def turn_filled(steps: pd.DataFrame, *, min_s: float = PAUSE_MIN_S, turn_gaps=None) -> np.ndarray:
    """Decision C180: (N - 1,) for the rows in ``start_s`` order, whether each row-to-row interval is one that
    L104 / L119 read as a pause and a walker's turn of ``turn_gaps`` fills (so no pause: bouts.csv's cadence leaves
    it out); all False without ``turn_gaps``."""
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    if turn_gaps is None or len(st) < 2:
        return np.zeros(max(len(st) - 1, 0), dtype=bool)
    plain = _intervals(st, min_s)[1]
    return plain & ~_intervals(st, min_s, turn_gaps)[1]


def rhythm_s(st: pd.DataFrame, d: np.ndarray, pair: np.ndarray) -> float:
    """The walker's rhythm (s) a pause is judged against: the median of the valid row-to-row intervals ``d[pair]``
    (L104); decision L482: on a foot table at most the median of its valid rows' own rest-to-rest windows
    (``end_s - start_s``: one stride cycle, the standing between two strides lies outside it), so walks of 1-3
    strides between stands are not judged against a median that is the stand; decision L500: the windows are
    :func:`movement_windows` and bound the median only when it exceeds their median by ``PAUSE_MIN_S`` or more (the
    intervals are mostly stands), so a very slow continuous walk keeps L104's rhythm. Both rules were adopted (L482,
    L501) and are the rule itself (W413: no module switches; commit d3ffb129 holds them). Decision L605: the bound is
    at least :func:`slow_stride_rhythm` (a slow foot's own stride times over 3 s), so the ~1 s foot-flats of a
    continuous 3.5-5 s stride walk are not its pauses."""
    median = float(np.median(d[pair]))
    if "end_s" not in st or not is_foot_table(st):
        return median
    window = movement_windows(st)
    if not window.size:
        return median
    bound = max(float(np.median(window)), slow_stride_rhythm(st))
    if median - bound < PAUSE_MIN_S:  # L500: the intervals are not mostly stands
        return median
    return min(median, bound)


def slow_stride_rhythm(st: pd.DataFrame) -> float:
    """Decision L605: the median of a foot table's valid ``stride_time_s`` when any is over L80's
    :data:`~pdrlearn.kernels.contact.MAX_STRIDE_S` (only a slow foot's rhythm cap, L605, gives those: the walker's
    own strides, not stands), else 0 (s)."""
    from pdrlearn.kernels.contact import MAX_STRIDE_S

    if "stride_time_s" not in st:
        return 0.0
    s = pd.to_numeric(st["stride_time_s"], errors="coerce").to_numpy(float)[_valid(st)]
    s = s[np.isfinite(s)]
    return float(np.median(s)) if len(s) and s.max() > MAX_STRIDE_S + 1e-9 else 0.0


#: decision L500: rows whose windows are this close (s; one sample at the foot units' 100 Hz) are one movement
TOUCH_S = 0.01


def movement_windows(st: pd.DataFrame) -> np.ndarray:
    """Decision L500: (M,) the windows (s) of a foot table's movements (rows in ``start_s`` order): consecutive
    valid rows whose rest-to-rest windows touch or overlap (next ``start_s`` <= previous ``end_s`` +
    :data:`TOUCH_S`; a stride the tracker cut in two) are one movement from the first ``start_s`` to the last
    ``end_s``; gap rows and non-finite or non-positive windows are left out and end a movement."""
    start, end = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    ok = _valid(st) & np.isfinite(start) & np.isfinite(end) & (end > start)
    out, first, last = [], None, None
    for a, b, good in zip(start.tolist(), end.tolist(), ok.tolist(), strict=True):
        if not good:
            if first is not None:
                out.append(last - first)
            first = None
            continue
        if first is not None and a <= last + TOUCH_S:
            last = max(last, b)
            continue
        if first is not None:
            out.append(last - first)
        first, last = a, b
    if first is not None:
        out.append(last - first)
    return np.asarray(out, float)


def still_before(steps: pd.DataFrame) -> np.ndarray:
    """Decision L372: (N,) the seconds before each row (rows in their order; 0 for the first) that the unit was
    known to be still since the previous row, so no turn took them: a lower-back table's ``still_before_s`` (L296's
    still samples of the pelvis between the two contacts); a foot table's rest between the previous row's end and
    this row's start (no stride of the tracked foot covers it), unless a streamed row's ``pivot_rad`` turned the
    foot there by :data:`PAUSE_MAX_TURN_DEG` or more (L106); else 0 (nothing known). L373 adopted L372 (a still
    stretch is standing, not a turn's time); decision L594: the rule is the code."""
    n = len(steps)
    if "still_before_s" in steps:
        return np.nan_to_num(pd.to_numeric(steps["still_before_s"], errors="coerce").to_numpy(float))
    if not is_foot_table(steps) or "end_s" not in steps or n < 2:
        return np.zeros(n)
    rest = np.r_[0.0, steps["start_s"].to_numpy(float)[1:] - steps["end_s"].to_numpy(float)[:-1]]
    rest = np.maximum(np.nan_to_num(rest), 0.0)
    if "pivot_rad" in steps:
        pivot = np.abs(np.degrees(np.nan_to_num(steps["pivot_rad"].to_numpy(float))))
        rest = np.where(pivot >= PAUSE_MAX_TURN_DEG, 0.0, rest)
    return rest


def is_foot_table(steps: pd.DataFrame) -> bool:
    """Whether every row of a non-empty ``steps`` is a foot unit's (bouts.csv and L372 read foot tables apart)."""
    return "unit" in steps and len(steps) > 0 and bool((steps["unit"].astype(str) == "foot").all())


def _own_turns(steps: pd.DataFrame) -> np.ndarray | None:
    """(N,) a foot table's strides' own turns (rad, L104: ``turn_angle_rad`` plus a streamed row's ``pivot_rad``,
    L106; 0 on an invalid row) when every valid row has one, else None (the heading is ``heading_rad``)."""
    if "turn_angle_rad" in steps and "unit" in steps and (steps["unit"] == "foot").all():
        turn = steps["turn_angle_rad"].to_numpy(float)
        if "pivot_rad" in steps:  # L106: a streamed stride's own turn leaves out the pivot before it (E51)
            turn = turn + steps["pivot_rad"].to_numpy(float)
        ok = _valid(steps)
        if ok.any() and np.isfinite(turn[ok]).all():
            return np.where(ok, turn, 0.0)
    return None


def unwrapped_heading(steps: pd.DataFrame) -> np.ndarray:
    """Unwrapped heading (rad) of each row, time order: a foot table's summed ``turn_angle_rad`` when every
    valid row has one (a streamed table's plus its ``pivot_rad``, the turn between strides, decision L106), else
    ``heading_rad``. Shared by the turn and pause rules here and :mod:`pdrlearn.track.gait`'s walking time (L194),
    so that they all see the same heading."""
    turn = _own_turns(steps)
    if turn is not None:
        return np.cumsum(turn)
    return np.unwrap(steps["heading_rad"].to_numpy(float))


def turns(steps: pd.DataFrame, *, min_rate_dps: float = TURN_RATE_MIN_DPS, edges: bool = True) -> np.ndarray:
    """(T,) the signed angles (deg, left positive) of the walk's turns (module docstring), any size."""
    return turn_rows(steps, min_rate_dps=min_rate_dps, edges=edges)[0]


def turn_rows(steps: pd.DataFrame, *, min_rate_dps: float = TURN_RATE_MIN_DPS,
              edges: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """:func:`turns`'s angles (T,) and, for each turn, the row (index in ``start_s`` order) that ends its first
    turning interval - the row a per-bout table (decision L124) counts the turn in. ``edges`` (decision L181,
    adopted: a streamed corner spread over three rows, -10 / -74 / -6 deg, read 74 deg without it; False = L104's
    turning rows alone): a turn's angle also sums the interval just before and just after its turning intervals when
    that interval is valid, turns the same way and belongs to no other turn."""
    st, spans = _turn_spans(steps, min_rate_dps=min_rate_dps, edges=edges)
    lead = int(bool(len(st)) and bool(st["_lead"].iloc[0])) if "_lead" in st else 0  # decision L369's rest row
    return (np.asarray([s[0] for s in spans], dtype=float),
            np.asarray([s[1] + 1 - lead for s in spans], dtype=int))


def _with_lead_row(st: pd.DataFrame) -> pd.DataFrame:
    """Decision L369: a foot table (rows in ``start_s`` order, :func:`_own_turns`) with a rest row before its first
    row - no own turn, its heading the one before the first stride, its start one first-row span earlier (that row's
    ``end_s`` - ``start_s``, else the next row's start) - so that the first stride's own turn is the interval from it
    (``_lead`` True on that row); the table itself without a first row's own turn or of fewer than one row."""
    if not len(st) or _own_turns(st) is None:
        return st
    first = st.iloc[0]
    t0 = float(first["start_s"])
    t1 = float(first["end_s"]) if "end_s" in st and np.isfinite(first["end_s"]) else math.nan
    if not t1 > t0:
        t1 = float(st["start_s"].iloc[1]) if len(st) > 1 else math.nan
    if not (t1 > t0 and _valid(st)[0]):
        return st
    lead = first.copy()
    lead["start_s"], lead["end_s"], lead["turn_angle_rad"] = t0 - (t1 - t0), t0, 0.0
    if "pivot_rad" in st:
        lead["pivot_rad"] = 0.0
    lead["heading_rad"] = float(first["heading_rad"]) - float(_own_turns(st)[0])
    out = pd.concat([lead.to_frame().T.astype(st.dtypes.to_dict(), errors="ignore"), st], ignore_index=True)
    out["_lead"] = np.r_[True, np.zeros(len(st), bool)]
    return out


def split_reversals(dh: np.ndarray, a: int, b: int, min_deg: float = PAUSE_MAX_TURN_DEG) -> list[tuple[int, int]]:
    """Decision L368: the turning run ``[a, b)`` of heading changes ``dh`` (deg) cut before each interval whose
    change is at least ``min_deg`` against the turn's direction (the sign of its last such interval): each part
    turns one way; a smaller opposite change stays in its turn."""
    out, start, sign = [], a, 0.0
    for i in range(a, b):
        if np.isfinite(dh[i]) and abs(dh[i]) >= min_deg:
            if sign and np.sign(dh[i]) != sign:
                out.append((start, i))
                start = i
            sign = float(np.sign(dh[i]))
    out.append((start, b))
    return out


def split_sustained_reversals(dh: np.ndarray, a: int, b: int,
                              min_deg: float = TURN_COUNT_MIN_DEG) -> list[tuple[int, int]]:
    """Decision W466: the turning run ``[a, b)`` of heading changes ``dh`` (deg) cut after each extreme of its
    summed heading from which the heading then goes back by ``min_deg`` or more (the turn rate changes sign in a
    sustained way: the way back is itself a turn of ``turn_count``'s size) - a slow figure of eight whose two loops
    are one turning run of net ~0 deg gives its two loops. Hysteresis: a back-and-forth smaller than ``min_deg``
    (a step heading's wobble, L368's single-interval cut is not used) stays in its turn; NaN changes count 0."""
    cuts, h, trend, lo, hi, i_lo, i_hi = [], 0.0, 0, 0.0, 0.0, a, a
    for i in range(a, b):
        h += float(dh[i]) if np.isfinite(dh[i]) else 0.0
        if h > hi:
            hi, i_hi = h, i + 1
        if h < lo:
            lo, i_lo = h, i + 1
        if trend >= 0 and hi - h >= min_deg:
            if trend == 1 and a < i_hi < b:
                cuts.append(i_hi)  # the run turned left to its top, now back right by min_deg
            trend, lo, i_lo = -1, h, i + 1
        elif trend <= 0 and h - lo >= min_deg:
            if trend == -1 and a < i_lo < b:
                cuts.append(i_lo)
            trend, hi, i_hi = 1, h, i + 1
    edges = [a, *cuts, b]
    return list(zip(edges[:-1], edges[1:], strict=True))


def opposite_yaw_cuts(yaw_turns) -> np.ndarray:
    """Decision L370: the times (s) between each two consecutive yaw-rate turns (records with ``start_s``,
    ``end_s``, ``angle_deg``: a track's ``info["yaw_turns"]``, L210) of opposite sign - the middle of the first's end
    and the second's start (El-Gohary 2014: a turn ends where the low-passed rate falls under 5 deg/s)."""
    yaw = sorted(list(yaw_turns or []), key=lambda r: r["start_s"])
    return np.asarray([0.5 * (p["end_s"] + q["start_s"]) for p, q in zip(yaw[:-1], yaw[1:], strict=True)
                       if p["angle_deg"] * q["angle_deg"] < 0], dtype=float)


def _cut_at_times(t: np.ndarray, a: int, b: int, cut_s: np.ndarray) -> list[tuple[int, int]]:
    """Decision L370: the run ``[a, b)`` of intervals (interval i from row time ``t[i]`` to ``t[i + 1]``) cut before
    each interval after its first that spans one of ``cut_s`` (``t[i] <= c < t[i + 1]``)."""
    at = np.zeros(len(t), bool)
    at[[i for c in cut_s for i in range(a + 1, b) if t[i] <= c < t[i + 1]]] = True
    return _cut_before(a, b, at)


def foot_turn_stops(st: pd.DataFrame) -> np.ndarray:
    """Decision L577: (N - 1,) the intervals of a foot table (rows in ``start_s`` order) a turn does not run across:
    a pause (:func:`_intervals`, L104 / L119 / L372: also the bouts' boundary, :func:`bout_rows`) or a rest of
    the tracked foot between the two rows (:func:`still_before`: no stride covers it) :data:`PAUSE_MIN_S` or more
    longer than the table's median such rest (the walker's own rhythm, as L104's pause: a slow walker's turning
    strides rest long between them; L119's turn allowance makes a 1-2 s stand between two turns on the spot no
    pause); the turn after it starts with that interval (a foot row's own turn is its stride, after the rest). All
    False on a lower-back table (L210 / L370 time and cut its turns by the yaw rate) and on fewer than two rows."""
    n = max(len(st) - 1, 0)
    if n == 0 or not is_foot_table(st):
        return np.zeros(n, bool)
    rest = still_before(st)[1:]
    ok = _valid(st)
    pair = ok[:-1] & ok[1:] & np.isfinite(rest)
    usual = float(np.median(rest[pair])) if pair.any() else 0.0
    return _intervals(st)[1] | (pair & (rest - usual >= PAUSE_MIN_S))


#: decision L653: a stride longer than this (m) that travels forward or backward walks: the thesis' short steps are
#: at most 30 cm (seed 002, ch. 6.3: "short steps are the ones with a maximum distance of 30cm")
WALK_MIN_STRIDE_M = 0.30


def walking_rows(st: pd.DataFrame) -> np.ndarray:
    """Decision L653: (N,) bool, the rows of a foot table that walk - ``travel`` forward or backward (L412: not a
    side step, not a stride turning on the spot, L203) and ``|length_m|`` over :data:`WALK_MIN_STRIDE_M` - which
    :func:`_turn_spans` never takes as a turn's slower row (a turn on the spot, a 2 m walk, a turn on the spot are
    two turns, trial T2 finding F6); all False on a lower-back table (no travel per step)."""
    from pdrlearn.track.travel import travel_labels

    travel = travel_labels(st) if is_foot_table(st) and "length_m" in st else None
    if travel is None:
        return np.zeros(len(st), bool)
    length = np.abs(pd.to_numeric(st["length_m"], errors="coerce").to_numpy(float))
    with np.errstate(invalid="ignore"):
        return np.isin(travel, ("forward", "backward")) & (length > WALK_MIN_STRIDE_M)


#: decision L678: a healthy adult's gait cycle (s; Perry & Burnfield 2010, ~1.1 s, as
#: :mod:`pdrlearn.track.contact_quality` cites): at it :data:`TURN_RATE_MIN_DPS` is 16.5 deg per stride
TURN_RATE_STRIDE_S = 1.1


def turn_rate_threshold(st: pd.DataFrame, min_rate_dps: float = TURN_RATE_MIN_DPS) -> float:
    """Decision L678: the rate (deg/s) a row-to-row heading change of table ``st`` (rows in ``start_s`` order) turns
    at: on a foot table ``min_rate_dps`` x min(1, :data:`TURN_RATE_STRIDE_S` / T), T the walker's rhythm
    (:func:`rhythm_s`, the pause rule's), i.e. ``min_rate_dps`` x 1.1 s degrees per stride of a walker slower than a
    healthy one (a rollator walker turning 30 deg per 1.8-2 s stride turns at 14-17 deg/s, trial T1 finding F3);
    ``min_rate_dps`` itself on a lower-back table, a faster walker's or without two valid rows."""
    if len(st) < 2 or not is_foot_table(st):
        return min_rate_dps
    t = st["start_s"].to_numpy(float)
    ok = _valid(st)
    d = np.diff(t)
    pair = ok[:-1] & ok[1:] & np.isfinite(d) & (d > 0)
    if not pair.any():
        return min_rate_dps
    return min_rate_dps * min(1.0, TURN_RATE_STRIDE_S / rhythm_s(st, d, pair))


def _cut_before(a: int, b: int, stops: np.ndarray) -> list[tuple[int, int]]:
    """Decision L577: the run ``[a, b)`` of intervals cut before each interval after its first flagged in ``stops``."""
    edges = [a, *(i for i in range(a + 1, b) if stops[i]), b]
    return list(zip(edges[:-1], edges[1:], strict=True))


def _turn_spans(steps: pd.DataFrame, *, min_rate_dps: float = TURN_RATE_MIN_DPS, edges: bool = True,
                reversal: bool = False, first_own: bool = True, foot_split: bool = True,
                cut_s=None, sustained: bool = False) -> tuple[pd.DataFrame, list[tuple[float, int, int, int, int]]]:
    """The table in ``start_s`` order and each turn's ``(angle deg, a, b, first, last)``: its turning intervals
    ``[a, b)`` of the row-to-row heading changes (interval i runs from row i to row i + 1) and ``[first, last)``
    the intervals summed into its angle (``a``/``b`` widened by L181's edges). ``reversal`` (decision L368, an
    option, off: not adopted on every table, users 7140-7159: waist-pll's extra rows 0 -> 1, TUG / corners |angle
    error| 24.61 -> 37.81 deg): a run ends where the heading turns the other way (:func:`split_reversals`; a turn
    has one direction, El-Gohary et al. 2014); ``first_own`` (decision L369, adopted with L371; False = a turn on the
    spot from standing loses its first stride): a foot table's returned table starts with a rest row (``_lead``
    True, :func:`_with_lead_row`) so that its first stride's own turn is an interval; ``foot_split`` (decision L370,
    adopted by L371: users 7140-7159, 20 Hz, plasys 360 deg turns found 0/20 -> 20/20, none lost, no extra row):
    ``reversal`` on a foot table whose heading is its strides' own turns (:func:`_own_turns`); ``cut_s`` (L370):
    times (s) a run is cut at (:func:`opposite_yaw_cuts`, :func:`_cut_at_times`);
    ``sustained`` (decision W466, an option: its rule was not met on waist-pll): a lower-back table's run is
    cut where its heading goes back by :data:`TURN_COUNT_MIN_DEG` (:func:`split_sustained_reversals`); decision
    L577: a foot table's run ends at :func:`foot_turn_stops`."""
    if len(steps) < 2 or "heading_rad" not in steps:
        return steps, []
    reversal = bool(reversal)
    if foot_split:  # decision L370: the foot's own yaw
        reversal = reversal or _own_turns(steps) is not None
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    if first_own:
        st = _with_lead_row(st)
    h = np.degrees(unwrapped_heading(st))
    t = st["start_s"].to_numpy(float)
    ok = _valid(st)
    dh, dt = np.diff(h), np.diff(t)
    min_rate_dps = turn_rate_threshold(st, min_rate_dps)  # decision L678: per stride of the walker's rhythm
    with np.errstate(invalid="ignore", divide="ignore"):
        turning = ok[:-1] & ok[1:] & np.isfinite(dh) & (dt > 0) & (np.abs(dh) / dt >= min_rate_dps)
        # decision L119: a turn beside a pause turns in the time the pause rule left it (TURN_ON_SPOT_MIN_DPS)
        turning |= _intervals(st)[1] & (np.abs(dh) >= PAUSE_MAX_TURN_DEG)
    # one row under the rate between two turning rows (a turn's slower step) does not split the turn; decision L653:
    # a walking stride (walking_rows) is no slower step of a turn, it ends the turn before it
    turning[1:-1] |= (turning[:-2] & turning[2:] & ok[1:-2] & ok[2:-1] & ok[3:] & np.isfinite(dh[1:-1])
                      & ~walking_rows(st)[2:-1])
    stops = foot_turn_stops(st)  # decision L577: a foot turn ends at a pause / bout boundary / rest gap
    runs, a = [], None  # the turns' intervals [a, b) in dh
    for i, on in enumerate(np.r_[turning, False]):
        if on and a is None:
            a = i
        elif not on and a is not None:
            parts = _cut_at_times(t, a, i, np.asarray(cut_s, float)) if cut_s is not None else [(a, i)]  # L370
            parts = [q for p in parts for q in _cut_before(p[0], p[1], stops)]  # decision L577
            if sustained and not reversal and not is_foot_table(st):  # decision W466
                parts = [q for p in parts for q in split_sustained_reversals(dh, *p)]
            runs += [r for p in parts for r in (split_reversals(dh, *p) if reversal else [p])]  # decision L368
            a = None
    free = ok[:-1] & ok[1:] & np.isfinite(dh) & ~turning  # decision L181: an interval a turn may take in
    out = []
    for a, b in runs:
        angle = float(dh[a:b].sum())
        first, last = a, b
        if edges:
            for j in (a - 1, b):
                if 0 <= j < len(dh) and free[j] and dh[j] * angle > 0:
                    angle += float(dh[j])
                    free[j] = False  # one turn's edge only
                    first, last = min(first, j), max(last, j + 1)
        out.append((angle, a, b, first, last))
    return st, out


#: decision L208: turns.csv's timings: "rows" (L200: the first and last summed rows' start / end), "heading" (where
#: the turn's heading, spread over its rows' spans, has gone TURN_TIMING_FRACTIONS of its angle)
TURN_TIMINGS = ("rows", "heading")
#: decision L209: L208's rule met (fresh users 3870-3899, median |duration error| foot 1.82 -> 0.35 s, streamed foot
#: 2.41 -> 0.19 s, waist-pendulum 1.30 -> 0.74 s, waist-pll 4.45 -> 0.91 s; turns and angles unchanged)
TURN_TIMING = "heading"
#: decision L208: the fractions of a turn's angle at which "heading" timing starts and ends it (L201's truth
#: definition of a simulated turn: the body's heading 5 % to 95 % of its change); the lower back's yaw-rate turns
#: (L345, :func:`pdrlearn.kernels.yaw_turns.turn_fraction_times`) share the one tuple, defined in that kernel
TURN_TIMING_FRACTIONS = _TURN_TIMING_FRACTIONS


def heading_crossings(dh: np.ndarray, start: np.ndarray, end: np.ndarray, angle: float,
                      fractions: tuple[float, float] = TURN_TIMING_FRACTIONS) -> tuple[float, float]:
    """Decision L208: the first times (s) at which a heading made of the changes ``dh`` (deg), each spread linearly
    over ``[start, end]`` (an instant where ``end <= start``), has gone ``fractions`` of ``angle`` (deg, non-zero,
    the changes' sum) from its value before ``start.min()``; the heading is linear between the spans' knots."""
    dh, start, end = (np.asarray(a, float) for a in (dh, start, end))
    end = np.maximum(end, start)
    knots = np.unique(np.r_[start, end])
    width = end - start
    lin = width > 0

    def level(tau: np.ndarray, right: bool) -> np.ndarray:
        d = tau[:, None] - start[None, :]
        step = (d >= 0) if right else (d > 0)
        f = np.where(lin, np.clip(d / np.where(lin, width, 1.0), 0.0, 1.0), step)
        return (f * dh).sum(axis=1) * math.copysign(1.0, angle)

    after, before = level(knots, True), level(knots, False)  # at each knot and just before it (an instant's jump)
    out = []
    for frac in fractions:
        target = frac * abs(angle)
        k = int(np.argmax(after >= target - 1e-9 * abs(angle)))
        if k > 0 and before[k] >= target and before[k] > after[k - 1]:  # crossed on the linear piece before knot k
            a = (target - after[k - 1]) / (before[k] - after[k - 1])
            out.append(float(knots[k - 1] + a * (knots[k] - knots[k - 1])))
        else:
            out.append(float(knots[k]))
    return out[0], out[1]


def spread_peak_rate(dh: np.ndarray, start: np.ndarray, end: np.ndarray) -> float:
    """Decision L229: the largest |rate| (deg/s) of :func:`heading_crossings`' heading - the changes ``dh`` (deg),
    each spread linearly over ``[start, end]`` - between two of its knots (overlapping spans add up; an instant,
    ``end <= start``, has no rate); NaN when no change has a span. A turn's mean rate over any part of that heading
    is never above it."""
    dh, start, end = (np.asarray(a, float) for a in (dh, start, end))
    lin = end > start
    if not lin.any():
        return math.nan
    dh, start, end = dh[lin], start[lin], end[lin]
    knots = np.unique(np.r_[start, end])
    mid = 0.5 * (knots[:-1] + knots[1:])
    cover = (start[None, :] <= mid[:, None]) & (mid[:, None] < end[None, :])
    return float(np.abs((cover * (dh / (end - start))[None, :]).sum(axis=1)).max())


# The lower back's yaw-rate rules of :func:`turn_table` are its keywords (decision L594: no module switch), each
# with its decision's value:
# - L210 / L211 (adopted; fresh users 3900-3939, median |start / end / duration error| waist-pendulum 2.62 / 1.31 /
#   1.33 -> 0.45 / 0.43 / 0.88 s, waist-pll 3.23 / 2.50 / 1.77 -> 0.78 / 1.04 / 0.83 s): ``timing="yaw"`` whenever
#   ``yaw_turns`` is given;
# - L231 / L232 (adopted; users 4660-4699, wrong-sign turns waist-pendulum 11 -> 0, waist-pll 12 -> 1):
#   ``branch=True``, the whole turns (k * 360 deg) that bring a wrapped step-heading angle nearest its yaw-rate turn;
# - L233 / L234 (not adopted: waist-pll's extra rows 0 -> 1, though turns found rose 30 -> 40 / 29 -> 40; an
#   option): ``yaw_only=False``;
# - L235 / L236 (adopted; median |peak error| waist-pendulum 49.79 -> 18.52, waist-pll 68.21 -> 19.75 deg/s):
#   ``yaw_peak=True``;
# - L255 / L256 (adopted; users 4970-4999, 360 deg turns found waist-pendulum 3/38 -> 38/38, waist-pll 13/38 ->
#   37/38): ``whole=True``;
# - L345 / L346 (not adopted: the real INDIP turns read worse; El-Gohary's boundaries stay): ``yaw_fractions=False``;
# - W328 (adopted; users 7140-7159, TUG / corners |angle error| 3.96 -> 0.17 / 16.72 -> 0.17 deg): ``yaw_angle=True``,
#   and L370's cut between two opposite yaw-rate turns, ``yaw_split=True``.


def whole_turns(yaw_deg, step_deg: float):
    """Decision L231: the whole turns (deg, a multiple of 360) nearest ``yaw_deg - step_deg`` - what a wrapped step
    heading of ``step_deg`` lost against a yaw-rate angle (each of ``yaw_deg``, deg); 0 on the same branch."""
    return 360.0 * np.round((np.asarray(yaw_deg, float) - step_deg) / 360.0)


def rows_heading_change(steps: pd.DataFrame, lo: float, hi: float) -> float:
    """Decision L255: the unwrapped heading change (deg) of a step table (:func:`unwrapped_heading`) from its last
    valid row starting at or before ``lo`` to its first valid row starting at or after ``hi`` (the first / last
    valid row where there is none); 0 without two such rows."""
    if len(steps) < 2 or "heading_rad" not in steps:
        return 0.0
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    h = np.degrees(unwrapped_heading(st))
    t = st["start_s"].to_numpy(float)
    ok = _valid(st) & np.isfinite(h) & np.isfinite(t)
    t, h = t[ok], h[ok]
    if len(t) < 2:
        return 0.0
    i0 = max(int(np.searchsorted(t, lo, side="right")) - 1, 0)
    i1 = min(int(np.searchsorted(t, hi, side="left")), len(t) - 1)
    return float(h[i1] - h[i0]) if i1 > i0 else 0.0


def yaw_turn_match(lo: float, hi: float, angle: float, yaw: pd.DataFrame | None, *,
                   branch: bool = False) -> tuple[int, float] | None:
    """Decisions L210 / L231: the yaw-rate turn (a row of ``yaw``, records of
    :data:`pdrlearn.waist.heading.YAW_TURN_KEYS`) that times a step-heading turn of ``angle`` deg whose rows span
    ``[lo, hi]`` s, and the whole turns (deg, a multiple of 360) its angle takes: of those whose peak lies in the
    span and whose angle has the sign of ``angle`` plus that shift (``branch``: the multiple of 360 deg nearest
    their difference; else 0, L210's same-sign match), the one of largest |angle|; None without one."""
    if yaw is None or not len(yaw):
        return None
    peak, ang = yaw["peak_s"].to_numpy(float), yaw["angle_deg"].to_numpy(float)
    shift = whole_turns(ang, angle) if branch else np.zeros(len(ang))
    cand = np.flatnonzero((peak >= lo) & (peak <= hi) & (np.sign(ang) == np.copysign(1.0, angle + shift)))
    if not cand.size:
        return None
    k = int(cand[int(np.argmax(np.abs(ang[cand])))])
    return k, float(shift[k])


def yaw_turn_times(lo: float, hi: float, angle: float, yaw: pd.DataFrame | None) -> tuple[float, float] | None:
    """Decision L210: the ``(start_s, end_s)`` of :func:`yaw_turn_match`'s same-sign yaw-rate turn; None without
    one."""
    m = yaw_turn_match(lo, hi, angle, yaw)
    return None if m is None else (float(yaw["start_s"].iloc[m[0]]), float(yaw["end_s"].iloc[m[0]]))


#: turns.csv's columns (decision L200), in order
TURN_TABLE_COLUMNS = ("turn", "start_s", "end_s", "duration_s", "angle_deg", "peak_rate_dps", "n_rows", "bout",
                      "mean_rate_dps", "carried")


def turn_table(steps: pd.DataFrame, bouts: pd.DataFrame | None = None, *,
               min_deg: float = TURN_COUNT_MIN_DEG, timing: str | None = None,
               yaw_turns=None, branch: bool = True, yaw_only: bool = False,
               yaw_peak: bool = True, whole: bool = True,
               yaw_fractions: bool = False, reversal: bool = False,
               first_own: bool = True, foot_split: bool = True,
               yaw_split: bool = True, yaw_angle: bool = True,
               sustained: bool = False, gap_turns=None) -> pd.DataFrame:
    """Decision L200: one row per turn of at least ``min_deg`` (``turn_count``'s turns, :func:`turn_rows`) of a
    tracked step table (or of a :class:`~pdrlearn.track.base.TrackResult`, decision W330: its ``steps`` with its
    ``info["yaw_turns"]``; ``result.turns()`` adds its bouts): ``start_s`` / ``end_s`` the start of the first and
    the end of the last row whose heading change the turn's angle sums (a row's ``end_s``; the next row's ``start_s``
    where it has none), ``duration_s``
    their difference, ``angle_deg`` the signed angle (left +), ``peak_rate_dps`` the largest rate of its heading with
    each row's change spread over that row's span, :func:`heading_crossings`' heading (decision L229; L200 took
    |heading change| / time between two rows' starts, the rate :data:`TURN_RATE_MIN_DPS` is judged on, and read
    below the mean on slow foot turns on the spot) - except a turn timed by the yaw rate (``"yaw"``), which keeps
    L200's (a lower-back row's spread change overshoots the true peak), ``n_rows`` the
    rows it spans and ``bout`` the number of the ``bouts`` row (bouts.csv, L124) whose span holds the turn's first
    turning row (empty outside every bout, or without ``bouts``). The times are the rows' times: a foot row's
    ``start_s`` is the rest before its stride, a lower-back row's its initial contact. ``mean_rate_dps`` (decision
    L209): the heading change between ``start_s`` and ``end_s`` / ``duration_s`` (the whole |angle| under
    ``"rows"``, the 5-95 % part under ``"heading"``); empty for a turn of no duration.

    ``timing`` (decision L208; None = :data:`TURN_TIMING`): ``"rows"`` the times above (L200); ``"heading"``
    ``start_s`` / ``end_s`` where the turn's heading, each interval's change spread over its row's span, has gone
    :data:`TURN_TIMING_FRACTIONS` of the angle (:func:`heading_crossings`); ``"yaw"`` (decision L210) ``"heading"``'s
    times, except that a turn matched by one of ``yaw_turns`` (a lower-back track's ``info["yaw_turns"]``: the
    El-Gohary turns of its yaw rate) takes that turn's start and end (:func:`yaw_turn_times`; its rows' span from
    the start of the row before its first heading change to the end of its last row). Default: ``"yaw"`` when
    ``yaw_turns`` is given (L211), else :data:`TURN_TIMING`.

    Under ``"yaw"`` only (the defaults are the decisions' values, the comment before :func:`whole_turns`):
    ``branch`` (decision L231) a step-heading turn's angle takes the whole turns :func:`yaw_turn_match` gives it
    (before the ``min_deg`` cut);
    ``yaw_only`` (L233, an option) a yaw-rate turn of at least ``min_deg`` whose span overlaps no
    counted turn's rows (their span as the match's) is a row of its own: its times, angle and peak rate, ``n_rows``
    0, ``bout`` the bout whose span holds its peak; ``yaw_peak`` (L235) a yaw-timed turn's
    ``peak_rate_dps`` is its yaw-rate turn's ``peak_dps`` (El-Gohary's low-passed peak); ``whole`` (L255)
    ``yaw_only``'s row, but only for a yaw-rate turn whose rows' heading change over its span
    (:func:`rows_heading_change`) is on another branch (:func:`whole_turns` not 0: a full turn on the spot whose
    steps were missed); ``yaw_fractions`` (L345, an option) a yaw-timed or yaw-only row's times are
    its yaw-rate turn's ``start_5_s`` / ``end_95_s`` (El-Gohary's boundaries where a record has none) and its
    ``mean_rate_dps`` the 5-95 % share of the angle over them, as under ``"heading"``; ``yaw_split`` (L370 / W328) a
    run is cut between two consecutive opposite yaw-rate turns (:func:`opposite_yaw_cuts`); ``yaw_angle`` (W328) a
    matched turn's angle is its yaw-rate turn's. ``reversal`` / ``first_own`` / ``foot_split`` (decisions L368 /
    L369 / L370) and ``sustained`` (decision W466): :func:`_turn_spans`'s. ``gap_turns`` (decision L701): a foot
    track's ``info["waist_gap_turns"]``, the lower back's turns in the foot's rest gaps, each of at least ``min_deg``
    a row of its own (:func:`pdrlearn.track.gap_turns.gap_turn_row`, ``n_rows`` 0). The rows are in time order."""
    if hasattr(steps, "steps") and hasattr(steps, "info"):  # decision W330: a TrackResult, with its yaw-rate turns
        yaw_turns = steps.info.get("yaw_turns") if yaw_turns is None else yaw_turns
        steps = steps.steps
    if timing is None:
        timing = "yaw" if yaw_turns is not None else TURN_TIMING  # decision L211
    if timing not in (*TURN_TIMINGS, "yaw"):
        raise ValueError(f"turn_table timing must be one of {(*TURN_TIMINGS, 'yaw')}, not {timing!r}")
    fractions = bool(yaw_fractions)
    yaw = pd.DataFrame(list(yaw_turns or []), columns=["start_s", "end_s", "peak_s", "angle_deg", "peak_dps",
                                                       "start_5_s", "end_95_s", CARRIED]) if timing == "yaw" else None
    if yaw is not None:  # decision L622: W488's mark, False where a record has none
        yaw[CARRIED] = [v is True for v in yaw[CARRIED]]
    if yaw is not None:  # decision L345: the times a yaw-timed row takes, and the share of the angle between them
        yaw_share = TURN_TIMING_FRACTIONS[1] - TURN_TIMING_FRACTIONS[0] if fractions else 1.0
        t_on = yaw["start_5_s"].where(yaw["start_5_s"].notna(), yaw["start_s"]) if fractions else yaw["start_s"]
        t_off = yaw["end_95_s"].where(yaw["end_95_s"].notna(), yaw["end_s"]) if fractions else yaw["end_s"]
        yaw = yaw.assign(t_on=t_on.astype(float), t_off=t_off.astype(float))
    cut_s = opposite_yaw_cuts(yaw.to_dict("records")) if yaw_split and yaw is not None else None  # decision L370
    st, spans = _turn_spans(steps, reversal=reversal, first_own=first_own, foot_split=foot_split, cut_s=cut_s,
                            sustained=sustained)
    rows, claimed = [], []  # claimed: the counted turns' row spans (decision L233)
    by_yaw: dict[int, dict] = {}  # decision W403: the row each matched yaw-rate turn gave
    b_lo, b_hi, b_no = (np.zeros(0),) * 3
    if bouts is not None and len(bouts):
        b_lo, b_hi = bouts["start_s"].to_numpy(float), bouts["end_s"].to_numpy(float)
        b_no = bouts["bout"].to_numpy()

    def bout_of(tf: float):
        inside = np.flatnonzero((b_lo <= tf) & (tf <= b_hi))
        return int(b_no[inside[0]]) if inside.size else pd.NA

    if spans:
        t = st["start_s"].to_numpy(float)
        end = st["end_s"].to_numpy(float) if "end_s" in st else np.full(len(st), np.nan)
        h = np.degrees(unwrapped_heading(st))
        with np.errstate(invalid="ignore", divide="ignore"):
            rate = np.abs(np.diff(h)) / np.diff(t)  # L200's row-to-row rate (a yaw-timed turn's peak, L229)
        # a row's span: its end, else the next row's start (L200's end of a turn), else none (an instant)
        nxt = np.r_[t[1:], t[-1]]
        span_end = np.where(np.isfinite(end) & (end > t), end, np.maximum(nxt, t))
        for angle, a, b, first, last in spans:
            lo, hi = float(t[first]), float(span_end[last])  # decision L210's match window
            match = yaw_turn_match(lo, hi, angle, yaw, branch=branch)
            rows_angle = angle  # the rows' own heading change (what L208's crossings spread)
            if match is not None:  # decision L231: the whole turns the wrapped step heading lost (0 without it)
                angle += match[1]
                if yaw_angle:  # decision W328: El-Gohary's angle, the yaw rate integrated over the turn
                    angle = float(yaw["angle_deg"].iloc[match[0]])
            if match is not None and match[0] in by_yaw:  # decision W403: a yaw-rate turn whose steps two spans
                # share (a pause between them: a bout boundary) is one turn - the first span's row, in its bout,
                # with the later span's rows (and, when its angle is the rows', their change) added
                first_row = by_yaw[match[0]]
                first_row["n_rows"] += int(last - first)
                if not yaw_angle:
                    first_row["angle_deg"] += rows_angle
                claimed.append((lo, hi))
                continue
            if abs(angle) < min_deg:
                continue
            claimed.append((lo, hi))
            # interval i turns between row i and row i + 1: the change shows in row i + 1 (a foot row's own turn)
            t0 = float(t[first + 1])
            t1 = float(end[last]) if np.isfinite(end[last]) and end[last] > t[last] else float(
                t[min(last + 1, len(t) - 1)])
            ends_after_last = not t1 > t0  # decision L205: the turn ends after the track's last row (W187)
            share = TURN_TIMING_FRACTIONS[1] - TURN_TIMING_FRACTIONS[0] if timing != "rows" else 1.0
            if timing != "rows":  # decision L208: interval j's change spread over row j + 1's span
                j = np.arange(first, last)
                t0, t1 = heading_crossings(np.diff(h)[j], t[j + 1], span_end[j + 1], rows_angle,
                                           TURN_TIMING_FRACTIONS)
            if match is not None:  # decision L210
                # decision L345: its 5-95 % times with yaw_fractions, else El-Gohary's boundaries
                (t0, t1), share = (float(yaw["t_on"].iloc[match[0]]), float(yaw["t_off"].iloc[match[0]])), yaw_share
            elif ends_after_last:  # decision L205: without the yaw rate its end is unknown
                t1 = np.nan
            if match is None:  # decision L229: the peak of the heading L208 spreads over the rows' spans (L205's
                j = np.arange(first, last)  # last row: an instant)
                peak = spread_peak_rate(np.diff(h)[j], t[j + 1], span_end[j + 1])
            elif yaw_peak:  # decision L235: the yaw-rate turn's own peak
                peak = float(yaw["peak_dps"].iloc[match[0]])
            else:  # L229: a turn timed by the yaw rate keeps L200's peak (the lower back's spread rows overshoot)
                r = rate[a:b]
                r = r[np.isfinite(r)]
                peak = float(r.max()) if r.size else np.nan
            rows.append({"start_s": t0, "end_s": t1, "duration_s": t1 - t0,
                         "angle_deg": angle, "peak_rate_dps": peak,
                         "n_rows": int(last - first), "bout": bout_of(float(t[a + 1])),
                         # decision L209: the share of the angle turned between the two times (L208: 5 % to 95 %)
                         "mean_rate_dps": share * abs(angle) / (t1 - t0) if t1 > t0 else np.nan,
                         # decision L622: timed by a yaw-rate turn W488 marked made seated or riding
                         "carried": match is not None and bool(yaw[CARRIED].iloc[match[0]])})
            if match is not None:
                by_yaw[match[0]] = rows[-1]  # decision W403
    if (yaw_only or whole) and yaw is not None:  # decision L233: a yaw-rate turn no counted turn overlaps
        for y in yaw.itertuples():
            if abs(y.angle_deg) < min_deg or any(y.start_s <= hi and y.end_s >= lo for lo, hi in claimed):
                continue
            if not yaw_only and whole_turns(y.angle_deg, rows_heading_change(st, y.start_s, y.end_s)) == 0:
                continue  # decision L255: the rows' heading follows it (the steps saw it, under the rate or 80 deg)
            dur = y.t_off - y.t_on  # decision L345: the 5-95 % times with yaw_fractions
            rows.append({"start_s": y.t_on, "end_s": y.t_off, "duration_s": dur, "angle_deg": y.angle_deg,
                         "peak_rate_dps": y.peak_dps, "n_rows": 0, "bout": bout_of(y.peak_s),
                         "mean_rate_dps": yaw_share * abs(y.angle_deg) / dur if dur > 0 else np.nan,
                         "carried": bool(getattr(y, CARRIED))})  # decision L622
    if gap_turns:  # decision L701: the lower back's turn in a foot rest gap, no stride holding it (n_rows 0)
        from pdrlearn.track.gap_turns import gap_turn_row

        rows += [gap_turn_row(r, bout_of) for r in gap_turns if abs(float(r["angle_deg"])) >= min_deg]
    rows.sort(key=lambda r: r["start_s"])  # stable: step-heading turns keep their order
    out = pd.DataFrame([{"turn": i + 1, **r} for i, r in enumerate(rows)], columns=list(TURN_TABLE_COLUMNS))
    out["bout"] = out["bout"].astype("Int64")
    out["carried"] = out["carried"].astype(bool)
    return out


def walked_turns(table: pd.DataFrame) -> pd.DataFrame:
    """Decision L622: the rows of a :func:`turn_table` the walker made - those not ``carried`` (W488: a yaw-rate
    turn made seated or in a ride, the seat's or the vehicle's); ``turn_count``, the turn medians and periods.csv's
    ``n_turns`` count these, turns.csv keeps every row, marked."""
    if "carried" not in table or not len(table):
        return table
    return table[~table["carried"].astype(bool).to_numpy()]


def turn_summary(table: pd.DataFrame) -> dict:
    """Decision L200: the summary keys of a :func:`turn_table`: ``median_turn_duration_s``,
    ``median_turn_angle_deg`` (of |angle|), ``median_turn_peak_rate_dps``, ``turn_time_s`` (their durations
    summed), ``median_turn_mean_rate_dps`` (L209; of the turns with one); None without a turn."""
    if not len(table):
        return dict.fromkeys(TURN_SUMMARY_KEYS)
    known = table["duration_s"].dropna()  # decision L205: a turn ending after the last row has no duration
    rates = table["peak_rate_dps"].dropna()
    return {"median_turn_duration_s": float(known.median()) if len(known) else None,
            "median_turn_angle_deg": float(table["angle_deg"].abs().median()),
            "median_turn_peak_rate_dps": float(rates.median()) if len(rates) else None,
            "turn_time_s": float(known.sum()) if len(known) else None,
            "median_turn_mean_rate_dps": _median_or_none(table["mean_rate_dps"])}


def _median_or_none(x: pd.Series) -> float | None:
    x = x.to_numpy(float)
    x = x[np.isfinite(x)]
    return float(np.median(x)) if x.size else None


#: decision L200: :func:`turn_summary`'s keys
TURN_SUMMARY_KEYS = ("median_turn_duration_s", "median_turn_angle_deg", "median_turn_peak_rate_dps", "turn_time_s",
                     "median_turn_mean_rate_dps")


def cv_keeps_ramps() -> bool:
    """Decisions L322, L442: whether a ramp climb's strides (L303's :func:`pdrlearn.track.evaluate.ramp_climb_rows`:
    rise over run under 20 %) count as level for the stride-time and stride-length CVs (session, per bout, L196's
    pooling; a stair climb's strides stay out): on a declared inclined treadmill belt (meta.json
    ``belt_incline_pct``, :func:`pdrlearn.track.belt.declared_incline`; a Python scope:
    :func:`pdrlearn.track.belt.incline_scope`). Decision L594: L322's Python-only switch ``CV_KEEPS_RAMPS`` (off,
    not adopted) is gone; L442's declaration is its one way in."""
    from pdrlearn.track.belt import declared_incline

    return declared_incline() is not None


def _level_forward(steps: pd.DataFrame) -> np.ndarray:
    """Decision L188: the rows that walk level and forward: |``dz_m``| under ``LEVEL_DZ_M`` (0.10 m, L179's
    :func:`pdrlearn.track.gait.stair_rows`) and ``direction`` not backward (a row without a class, a track
    without a model, counts as forward) nor travelling backward (steps.csv ``backward_travel``, L203: decision L408,
    a model-free track's back-pedalling strides were in the CVs). A stair
    stride or a backward stride has its own rhythm (the trial route's level ~1.0 s, stairs down 0.85 s, the first
    backward stride 2.0 s), so pooling them is no steady walker's variability."""
    return _level(steps) & ~backward_rows(steps)


def _level(steps: pd.DataFrame) -> np.ndarray:
    """L188's level rows, either direction: not a stair stride (L322 / L442: a ramp's with :func:`cv_keeps_ramps`),
    not a side step (L228)."""
    from pdrlearn.track.gait import sideways_rows, stair_rows

    # decisions L322 / L442: on a declared inclined belt a ramp climb's strides are not stair strides here (L303's
    # rule)
    return ~stair_rows(steps, ramp_not_stair=cv_keeps_ramps()) & ~sideways_rows(steps)  # L228


def backward_rows(steps: pd.DataFrame) -> np.ndarray:
    """(B,) bool: the rows L188 calls backward - ``direction`` backward (a model's class) or travelling backward
    (L203 / L408's ``backward_travel`` of a model-free track)."""
    out = np.zeros(len(steps), bool)
    if "direction" in steps:
        out |= (steps["direction"].astype(str) == "backward").to_numpy()  # empty without a model: not backward
    from pdrlearn.track.evaluate import backward_travel

    back = backward_travel(steps)  # decision L408: a model-free track's backward strides (L203) are not forward
    return out if back is None else out | np.asarray(back, dtype=bool)


def steady_rows(steps: pd.DataFrame, *, one_source: bool = False) -> tuple[pd.DataFrame, np.ndarray]:
    """A foot table in ``start_s`` order and its steady straight level forward strides with a stride time (module
    docstring, L104 / L188), the strides the stride-time CV is taken over; no row for a table without stride times
    (a lower-back table: its contact timing scatters too much for a variability, decision L104). Shared by the
    session's stride-time CV here and :mod:`pdrlearn.track.bouts`' per-bout CV (L212), so both take the same
    strides. ``one_source`` (decision L405, not adopted: an option, off; decision L594: a keyword, no module switch):
    on a stitched foot track (L365's partial fallback, steps.csv ``contact_source``) no row whose ``contact_source``
    differs from the previous row's."""
    from pdrlearn.track.gait import STRAIGHT_MAX_RAD

    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    if "stride_time_s" not in steps:
        return st, np.zeros(len(st), bool)
    s = st["stride_time_s"].to_numpy(float)
    turn = st["turn_angle_rad"].to_numpy(float) if "turn_angle_rad" in st else np.zeros(len(s))
    with np.errstate(invalid="ignore"):
        straight = np.isfinite(s) & (np.abs(turn) < STRAIGHT_MAX_RAD) & _valid(st) & _level(st)
    back = backward_rows(st)
    steady = _steady(st, straight & ~back, one_source=one_source)
    if steady.sum() < CV_MIN_STRIDES:  # decision L444: a backward walk (a backward belt) has its own CV
        backward = _steady(st, straight & back, one_source=one_source)
        if backward.sum() >= CV_MIN_STRIDES:
            return st, backward
    return st, steady


def _rows(steps: pd.DataFrame, rows: tuple[pd.DataFrame, np.ndarray] | None) -> tuple[pd.DataFrame, np.ndarray]:
    """``rows`` (:func:`steady_rows` of ``steps`` already taken, e.g. by :func:`clinical_summary`, which takes it
    once for all its CVs) or :func:`steady_rows` of ``steps``."""
    return steady_rows(steps) if rows is None else rows


def cv_direction(steps: pd.DataFrame, *, rows: tuple[pd.DataFrame, np.ndarray] | None = None) -> str | None:
    """Decision L444: ``"backward"`` when :func:`steady_rows` took the backward strides (fewer than
    :data:`CV_MIN_STRIDES` steady forward ones, at least as many steady backward ones), ``"forward"`` when it took
    forward strides, None when it took none. ``rows``: :func:`steady_rows` of ``steps`` when already taken."""
    st, steady = _rows(steps, rows)
    if not steady.any():
        return None
    return "backward" if backward_rows(st)[steady].all() else "forward"


def _steady(st: pd.DataFrame, ok: np.ndarray, *, one_source: bool = False) -> np.ndarray:
    """L104's steady strides of ``st`` (in ``start_s`` order) among the straight level strides ``ok`` of one
    direction (L444): neither next to a pause nor to a row that is not such a stride, L405's one source (with
    ``one_source``), L415's trim."""
    ok = np.array(ok, dtype=bool)
    if len(st) > 1:  # a stride time across a pause (IC to IC over a short stop, L80) is no stride's rhythm
        _, is_pause = _intervals(st)
        ok &= ~np.concatenate([[False], is_pause]) & ~np.concatenate([is_pause, [False]])
    # steady: the strides before and after are straight strides with a stride time too (no turn, start
    # or stop next to it: the strides around a turn or a stop slow down)
    steady = ok & np.concatenate([[False], ok[:-1]]) & np.concatenate([ok[1:], [False]])
    if one_source and "contact_source" in st and len(st) > 1:  # decision L405: no stride time from one
        src = st["contact_source"].astype(object).to_numpy()  # detector's contact to the other's (two clocks)
        steady &= np.concatenate([[False], (src[1:] == src[:-1]) & pd.notna(src[1:])])
    from pdrlearn.track.steady import trimmed_rows

    steady &= ~trimmed_rows(st)  # decision L415: --steady-trim's first / last strides of each bout
    return steady


def _straight_stride_times(st: pd.DataFrame, steady: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The stride times (s) of a foot table's steady straight strides (:func:`steady_rows`' ``st``, ``steady``) and
    the same strides' swing-onset intervals (``start_s`` to the previous row's, s; decision L113); none for a
    lower-back table."""
    if "stride_time_s" not in st:
        return np.zeros(0), np.zeros(0)
    onset = np.diff(st["start_s"].to_numpy(float), prepend=np.nan)
    return st["stride_time_s"].to_numpy(float)[steady], onset[steady]


def jitter_free_cv(bouts: list[np.ndarray]) -> tuple[float, float, int]:
    """Decision W558: ``(raw CV %, corrected CV %, strides)`` of the lower back's strides t[k+2] - t[k] of each
    bout's contact times ``bouts`` (s; each bout's first and last two strides left out): each contact's timing jitter
    e_k adds 2 Var(e) to Var(S) and makes two strides sharing a contact (S_k, S_k+2) covary by -Var(e), so
    Var(true S) ~ Var(S) + 2 x their lag-2 autocovariance (a moment estimate; no document), W598: the variance about
    the pooled mean, the autocovariance about each run's own mean. NaN with fewer than 5 strides."""
    strides = [(t[2:] - t[:-2])[2:-2] for t in bouts]
    s = np.concatenate(strides) if strides else np.zeros(0)
    if len(s) < 5:
        return math.nan, math.nan, int(len(s))
    m, v = float(s.mean()), float(s.var(ddof=1))
    # decision W598: the lag-2 term about each run's own mean (about the pooled mean a pace change between runs
    # added its between-run variance twice more: trial s51t2 P18002 15.1 % for a true 8.8 %)
    lag = [(x[2:] - x.mean()) * (x[:-2] - x.mean()) for x in strides if len(x) > 2]
    g2 = float(np.concatenate(lag).mean()) if lag else 0.0
    return 100 * math.sqrt(v) / m, 100 * math.sqrt(max(v + 2 * g2, 0.0)) / m, int(len(s))


def steady_runs(t: np.ndarray, breaks: np.ndarray, *, step_band: float = 0.4,
                min_contacts: int = JITTER_FREE_MIN_CONTACTS) -> list[np.ndarray]:
    """Decision W598: the steady runs of one walking bout's contact times ``t`` (s, in order): the bout cut at every
    step interval outside [1 - ``step_band``, 1 + ``step_band``] x the bout's median step interval (an extra contact
    splits a step, one part at most half of it; a missed one makes two steps of one interval) and at every interval
    next to a contact of ``breaks`` (True: a turning row); the runs of ``min_contacts`` contacts or more."""
    t = np.asarray(t, float)
    if len(t) < min_contacts:
        return []
    d = np.diff(t)
    med = float(np.median(d))
    brk = np.asarray(breaks, bool)
    cut = (d < (1.0 - step_band) * med) | (d > (1.0 + step_band) * med) | brk[1:] | brk[:-1]
    edges = [0, *(np.flatnonzero(cut) + 1).tolist(), len(t)]
    return [t[a:b] for a, b in zip(edges[:-1], edges[1:], strict=True) if b - a >= min_contacts]


def lower_back_cv(steps: pd.DataFrame, *, turn_gaps=None, step_band: float | None = 0.4) -> dict:
    """Decision W558: the lower back's stride-time CV with its contacts' jitter taken out (:func:`jitter_free_cv`);
    decision W598: over the steady straight runs (:func:`steady_runs`, ``step_band``; None: W558's whole bouts) of
    each walking bout (:func:`bout_rows`) of :data:`JITTER_FREE_MIN_CONTACTS` contacts or more:
    ``{"jitter_free_cv_pct": CV or None under JITTER_FREE_MIN_STRIDES stride intervals, "n_jitter_free_strides": n}``
    (n: the stride intervals, :data:`JITTER_FREE_WALK`)."""
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    t = st["start_s"].to_numpy(float)
    turning = (pd.to_numeric(st["turning"], errors="coerce").fillna(0).to_numpy(float) != 0 if "turning" in st
               else np.zeros(len(st), bool))  # decision W598: steps.csv's turning rows
    ranges = [(a, b) for a, b in bout_rows(st, turn_gaps=turn_gaps) if b - a >= JITTER_FREE_MIN_CONTACTS]
    if step_band is None:  # W558 as adopted: each bout one run
        bouts = [t[a:b] for a, b in ranges]
    else:
        bouts = [r for a, b in ranges for r in steady_runs(t[a:b], turning[a:b], step_band=step_band)]
    _, cv, n = jitter_free_cv(bouts)
    return {"jitter_free_cv_pct": cv if n >= JITTER_FREE_MIN_STRIDES and math.isfinite(cv) else None,
            "n_jitter_free_strides": n}


def steady_stride_lengths(st: pd.DataFrame, steady: np.ndarray) -> np.ndarray:
    """Decision L212: the stride lengths (m, |``length_m``|) of :func:`steady_rows`' strides ``steady`` of ``st``
    (its table in ``start_s`` order), the strides the stride-time CV is taken over; NaN for a row without a length
    or one L94's guard made ``impossible`` (its length is zeroed, no stride's)."""
    if "length_m" not in st:
        return np.full(int(steady.sum()), np.nan)
    length = np.abs(st["length_m"].to_numpy(float))
    if "impossible" in st:
        length = np.where(flag_values(st["impossible"]), np.nan, length)
    return length[steady]


def _not_level(steps: pd.DataFrame) -> tuple[int, int]:
    """Decision L215: ``(straight strides with a stride time, how many of them L188's level criterion drops)``
    of a foot table: valid forward strides turning under 15 deg with a stride time, and those whose |``dz_m``|
    reaches 0.10 m (:func:`pdrlearn.track.gait.stair_rows`). Decision L456: forward is not :func:`backward_rows`
    (a model's ``direction`` backward or a model-free track's backward travel, L203 / L408), as the CV's strides."""
    from pdrlearn.track.gait import STRAIGHT_MAX_RAD, stair_rows

    if "stride_time_s" not in steps or not len(steps):
        return 0, 0
    turn = steps["turn_angle_rad"].to_numpy(float) if "turn_angle_rad" in steps else np.zeros(len(steps))
    with np.errstate(invalid="ignore"):
        straight = (np.isfinite(steps["stride_time_s"].to_numpy(float)) & (np.abs(turn) < STRAIGHT_MAX_RAD)
                    & _valid(steps))
    straight &= ~backward_rows(steps)  # decision L456: L188's backward rows, a model-free track's included
    return int(straight.sum()), int((straight & stair_rows(steps, ramp_not_stair=cv_keeps_ramps())
                                     ).sum())


def below_text(value: float, bound: float) -> str:
    """Decision W400: ``value`` (under ``bound``) with the fewest decimals, from one, that still print under
    ``bound`` (19.9987 against 20: "19.999", not "20.0")."""
    for digits in range(1, 7):
        text = f"{value:.{digits}f}"
        if float(text) < bound:
            return text
    return repr(float(value))


def add_turn_steps(turns: pd.DataFrame, steps: pd.DataFrame, info: dict | None = None) -> pd.DataFrame:
    """Decision W398: turns.csv's ``turn_steps`` on a lower-back track - the detected steps (steps.csv rows) whose
    contact ``event_s`` lies inside the turn (``start_s`` to ``end_s``), the clinical steps-per-turn, unlike
    ``n_rows`` (the rows whose heading change the turn sums). Decision L749: on a foot track (its rows are one foot's
    strides) :func:`pdrlearn.track.foot_turn_steps.foot_turn_steps` with the track's ``info`` - the lower back's
    contacts when the session has that unit, else 2 x the foot's strides; ``turn_steps_source`` names which
    (``waist`` / ``foot_x2``; empty with no count). Returns a new table."""
    from pdrlearn.track.foot_turn_steps import WAIST, contacts_in, foot_turn_steps

    spans = turns[["start_s", "end_s"]].to_numpy(float)
    if _is_lower_back(steps) and "event_s" in steps:
        counts, source = contacts_in(steps["event_s"], spans), WAIST
    elif _is_lower_back(steps):
        counts, source = None, ""
    else:
        counts, source = foot_turn_steps(turns, steps, info)
    if counts is None:
        return turns.assign(turn_steps=pd.array([pd.NA] * len(turns), dtype="Int64"),
                            turn_steps_source=pd.Series([""] * len(turns), index=turns.index, dtype=object))
    return turns.assign(turn_steps=counts, turn_steps_source=pd.Series([source] * len(turns), index=turns.index,
                                                                       dtype=object))


def _is_lower_back(steps: pd.DataFrame) -> bool:
    return "unit" in steps and len(steps) > 0 and bool((steps["unit"].astype(str) == "waist").all())


def pooled_cv(steps: pd.DataFrame, cv_pct: float, *, rows: tuple[pd.DataFrame, np.ndarray] | None = None
              ) -> dict | None:
    """Decision L196: whether the stride-time CV ``cv_pct`` of ``steps`` (over :func:`steady_rows`' strides) pools
    walking bouts of different rhythm. Per L104 bout (:func:`bout_rows`, bouts.csv's under the default definition)
    holding at least :data:`CV_BOUT_MIN_STRIDES` of those strides: its median stride time and own CV; the
    within-bout CV = 100 x sqrt(sum of (t / its bout's mean - 1)^2 / (n - bouts)) over them. With two or more such
    bouts and ``cv_pct`` above :data:`CV_POOLED_FACTOR` x the within-bout CV: ``{"within_bouts_cv_pct", "bouts":
    [{"bout", "start_s", "n_strides", "median_stride_time_s", "cv_pct"}, ...]}``; None otherwise. ``rows``:
    :func:`steady_rows` of ``steps`` when already taken."""
    st, steady = _rows(steps, rows)
    if not steady.any():
        return None
    s = st["stride_time_s"].to_numpy(float)
    groups = [(i + 1, a, s[a:b][steady[a:b]]) for i, (a, b) in enumerate(bout_rows(st))]
    groups = [(i, a, t) for i, a, t in groups if len(t) >= CV_BOUT_MIN_STRIDES and t.mean() > 0]
    if len(groups) < 2:
        return None
    within = within_groups_cv_pct([t for _, _, t in groups])
    if not cv_pct > CV_POOLED_FACTOR * within:
        return None
    return {"within_bouts_cv_pct": within,
            "bouts": [{"bout": i, "start_s": float(st["start_s"].iloc[a]), "n_strides": int(len(t)),
                       "median_stride_time_s": float(np.median(t)),
                       "cv_pct": float(100.0 * t.std(ddof=1) / t.mean())} for i, a, t in groups]}


def within_groups_cv_pct(groups: list[np.ndarray]) -> float:
    """Decision L196: the CV (%) of values about their own group's mean, 100 x sqrt(sum of (x / its group's mean -
    1)^2 / (n - groups)) over ``groups`` (each an array of positive values, at least one group with two); NaN
    without a degree of freedom. L196's within-bout stride-time CV and L380's within-segment stride-length CV."""
    groups = [np.asarray(g, float) for g in groups if len(g) and np.mean(g) > 0]
    n = sum(len(g) for g in groups)
    if n - len(groups) < 1:
        return math.nan
    dev = np.concatenate([g / g.mean() - 1.0 for g in groups])
    return float(100.0 * np.sqrt(np.sum(dev ** 2) / (n - len(groups))))


#: decision L380: the stride-length CV's own strides split into segments of consecutive steady strides (a straight
#: stretch between turns and stops); a segment counts with at least this many (L196's per-bout minimum)
CV_SEGMENT_MIN_STRIDES = CV_BOUT_MIN_STRIDES


def segment_length_cv(st: pd.DataFrame, steady: np.ndarray) -> tuple[float, int]:
    """Decision L380: ``(within-segment stride-length CV %, segments)`` of :func:`steady_rows`' strides ``steady``
    of ``st`` (its table in ``start_s`` order): the strides cut into runs of consecutive steady strides (a turn, a
    stop or a stair between two runs: the straight stretches of the walk), each run's lengths
    (:func:`steady_stride_lengths`, finite ones) about its own mean, :func:`within_groups_cv_pct` over the runs of at
    least :data:`CV_SEGMENT_MIN_STRIDES`; ``(NaN, 0)`` without one. A change of pace from one stretch to the next
    (a 6MWT's slower laps) is no stride-to-stride variability."""
    length = np.full(len(st), np.nan)
    length[steady] = steady_stride_lengths(st, steady)
    from pdrlearn.signal.conditioning import runs

    parts = [length[a:b][np.isfinite(length[a:b])] for a, b in runs(steady)]
    parts = [r for r in parts if len(r) >= CV_SEGMENT_MIN_STRIDES]
    return (within_groups_cv_pct(parts), len(parts)) if parts else (math.nan, 0)


def contact_scatter_s(stride_s: np.ndarray, onset_s: np.ndarray) -> float:
    """Decision L113: each contact's timing scatter (s) estimated from the stride times ``stride_s`` (contact to
    contact) and the same strides' swing-onset intervals ``onset_s``: sqrt((SD_contacts^2 - SD_onsets^2) / 2),
    0 when the contacts vary less than the onsets (SD with n - 1). Derived here (no document gives it):
    independent errors add variances, and a stride time holds two contacts' errors."""
    excess = float(np.var(stride_s, ddof=1) - np.var(onset_s, ddof=1))
    return float(np.sqrt(excess / 2.0)) if excess > 0 else 0.0


def step_time_asymmetry(step_s, has_next, broken=None, *, min_steps: int = ASYMMETRY_MIN_STEPS
                        ) -> tuple[float | None, int]:
    """Decision L111 (Python API only, not in the summary: its rule failed - on simulated symmetric walkers the
    lower back read 3.31 % on average, over 5 % on 3 of 20): ``(index %, step times used)`` of a lower-back step
    table (:func:`pdrlearn.track.gait.waist_step_times`), one row per initial contact in time order: ``step_s``
    (B,) each contact's step time to the next contact (NaN where none is measured), ``has_next`` (B,) whether
    the next contact is in the same walking sequence, ``broken`` (B,) rows that end a sequence too (a W27
    fragment and its neighbours: a spurious contact shifts the feet). Inside a sequence the contacts alternate
    feet (W20), so the step times at even and odd places are the two feet's (which is left is not known and does
    not matter to the index). Per sequence with at least ``min_steps`` step times of each foot,
    :func:`symmetry_index_pct` of the two feet's mean step times (a median of whole-sample step times moves in
    steps of ~10 % at 20 Hz); the sequences' indices averaged weighted by their step times (a new sequence may
    start on either foot, so the feet are not matched across sequences). ``(None, 0)`` without such a
    sequence."""
    step = np.asarray(step_s, dtype=float)
    hn = np.asarray(has_next, dtype=bool)
    cut = np.zeros(len(step), bool) if broken is None else np.asarray(broken, dtype=bool)
    indices, weights, start = [], [], 0
    for i in range(len(step)):
        if i + 1 == len(step) or not hn[i] or cut[i] or cut[i + 1]:  # the sequence ends after row i
            seq = step[start:i + 1]
            feet = [seq[0::2], seq[1::2]]
            feet = [f[np.isfinite(f)] for f in feet]
            if min(len(f) for f in feet) >= min_steps:
                indices.append(symmetry_index_pct(float(np.mean(feet[0])), float(np.mean(feet[1]))))
                weights.append(sum(len(f) for f in feet))
            start = i + 1
    if not indices:
        return None, 0
    return float(np.average(indices, weights=weights)), int(sum(weights))


#: decision L121: a lower-back step-time symmetry index under this (%) is not told apart from the detector's own
#: left/right contact timing (symmetric simulated walkers read up to 18.8 %: session 20's trial, festination)
ASYMMETRY_FLOOR_PCT = 20.0
#: decision L216: how far the lower back's index was from the simulated truth (raw - true, points) on fresh users
#: 3960-3979 (true 0.3-34.0 %; waist-pendulum, 100 Hz): said in the report's reason, not used in any computation
ASYMMETRY_ERROR_POINTS = "-8.4 to +17.0"


#: decision W436: the lower back's step-time index over the simulated truth, a factor (median of trial s40 T1's
#: three asymmetric walkers: 1.508, 1.477, 1.500; waist-pendulum, slow, 100 Hz); on fresh users 10810-10819 with a true
#: SI of 10 % or more the index / 1.5 was within 4.91 points of the truth (mean 2.52, raw 12.32 points off)
OVER_READ_FACTOR = 1.5
#: decision W436: what the fresh users' raw / true ranged over, said in the reason (text only)
OVER_READ_RANGE = "17-38 % read x1.24-x1.70 the truth, +4.3 to +26.1 points; divided by 1.5, -4.1 to +4.9 points"


def step_time_asymmetry_report(steps: pd.DataFrame) -> dict:
    """Decision L121 (Python API): what a tracked step table can honestly say about the step-time asymmetry.
    ``{"step_time_asymmetry_pct", "raw_pct", "n_step_times", "reason"}``:

    * a **foot** table (one foot's strides): ``None`` - a step time runs from one foot's contact to the other
      foot's, which a unit on one foot does not see (L104); ``reason`` says so;
    * a **lower-back** table: :func:`step_time_asymmetry`'s index (``raw_pct``) on its alternating contacts, given
      as ``step_time_asymmetry_pct`` only when it reaches :data:`ASYMMETRY_FLOOR_PCT` (then ``reason`` says it
      is misread, mostly over: a simulated 39.1 % read 55.2 %); under it ``None``: symmetric simulated walkers read
      3-19 % from the contacts' timing alone (L111, the session-20 trial), so a smaller index tells nothing -
      neither way: decision L216, the reason says a real asymmetry can read under it too (a simulated 24.7 % read
      19.9 %; the index was -8.4 to +17.0 points off the truth on users 3960-3979).
      A lower-back table of something that is no walk (a wheelchair's pushes, the trial's finding 1) still
      gives contacts: the index does not check that they are steps."""
    out = {"step_time_asymmetry_pct": None, "raw_pct": None, "n_step_times": 0, "reason": None}
    if "unit" in steps and len(steps) and (steps["unit"] == "foot").all() or "stride_time_s" in steps:
        out["reason"] = ("not observable from one foot's unit: a step time runs from one foot's contact to the "
                         "other foot's; use a unit on each foot (pdrlearn gait LEFT_DIR RIGHT_DIR, "
                         "decision L259) or a lower-back unit (pdrlearn track DIR --pipeline waist-pendulum; "
                         "decision L316)")
        return out
    pct, n = step_time_asymmetry(*rhythm_step_times(steps))  # decision W512: the gait's steady steps
    out["raw_pct"], out["n_step_times"] = pct, n
    if pct is None:
        out["reason"] = (f"no walking sequence with {ASYMMETRY_MIN_STEPS} step times of each foot")
    elif pct < ASYMMETRY_FLOOR_PCT:  # decision L216: not a finding of symmetry
        out["reason"] = (f"not judged, which is no evidence of symmetry: index {below_text(pct, ASYMMETRY_FLOOR_PCT)} "
                         f"% is below the {ASYMMETRY_FLOOR_PCT:.0f} % threshold (W400's digits), where the lower "
                         "back's contact timing alone reads up to 18.8 % on walkers whose feet step alike (decision "
                         "L121), and it can also miss a real asymmetry "
                         f"(its index is {ASYMMETRY_ERROR_POINTS} points off the truth: a simulated 24.7 % read "
                         "19.9 %, decision L216); time the steps with a unit on each foot")
    else:
        out["step_time_asymmetry_pct"] = pct
        out["reason"] = (f"asymmetric; the lower back misreads the size, mostly over (a simulated 39.1 % read 55.2 %, "
                         f"decision L121; {ASYMMETRY_ERROR_POINTS} points off the truth, decision L216), by a factor "
                         f"that grows the error with the asymmetry: about {pct / OVER_READ_FACTOR:.1f} % once the "
                         f"simulated x{OVER_READ_FACTOR:g} over-read is taken out (fresh simulated walkers of true "
                         f"{OVER_READ_RANGE}: W436), an estimate for a clinic's change scores, not a measurement")
    return out


#: decision W228: the per-leg keys of every summary (None where the table cannot give them): the lower back's steps
#: by ``side`` (W129's sway side; ``""`` undecided) and :func:`step_time_asymmetry_report`'s figures
LEG_KEYS = ("n_steps_left", "n_steps_right", "n_steps_side_undecided", "step_time_asymmetry_pct",
            "step_time_asymmetry_raw_pct", "n_step_time_asymmetry_steps", "step_time_asymmetry_reason",
            "step_time_s_left", "step_time_s_right", "step_time_s_ratio",  # W250: the asymmetry's direction
            "step_time_asymmetry_se_points",  # L671: L490's standard error of a foot + lower-back index
            "step_time_asymmetry_uncertain")  # C271: that index within noise or uncertain


def rhythm_step_times(steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Decision W512: :func:`pdrlearn.track.gait.waist_step_times` of a lower-back table with the steps that are
    not the gait's rhythm NaN: a turning step (the pipeline's ``turning`` flag, W70's straight steps) and one over
    :data:`~pdrlearn.track.labelled_asymmetry.MAX_STRIDE_FACTOR` x the median step time (a stop, or the step out
    of a turn on the spot, which lands on the same foot at every turn of one direction). The feet's parity inside a
    sequence is kept (NaN, as a W27 fragment's)."""
    from pdrlearn.track.gait import waist_step_times
    from pdrlearn.track.labelled_asymmetry import MAX_STRIDE_FACTOR

    step_s, has_next, touched = waist_step_times(steps)
    keep = np.isfinite(step_s)
    if keep.any():
        keep &= step_s <= MAX_STRIDE_FACTOR * float(np.median(step_s[keep]))
    if "turning" in steps:
        keep &= pd.to_numeric(steps["turning"], errors="coerce").fillna(0).to_numpy(float) == 0
    return np.where(keep, step_s, np.nan), has_next, touched


def side_step_times(steps: pd.DataFrame) -> dict:
    """Decision W250: the lower back's mean step time onto each foot - the step ending at a contact of that side
    (W129's ``side``), from the previous contact of its walking sequence (:func:`pdrlearn.track.gait.waist_step_times`:
    no step time across a pause or through a W27 fragment) - as ``pdrlearn gait``'s ``step_time_s_left`` /
    ``_right`` (the step landing on that foot, L259; means, as gait's) and ``step_time_s_ratio`` = left / right
    (Patterson et al. 2010, gait's convention). Each side's mean needs :data:`ASYMMETRY_MIN_STEPS` step times, else
    None; the ratio is given only with both."""
    out = {"step_time_s_left": None, "step_time_s_right": None, "step_time_s_ratio": None}
    if len(steps) < 2 or "side" not in steps:
        return out
    step_s, _, _ = rhythm_step_times(steps)  # decision W512: the gait's steady steps
    onto = steps["side"].fillna("").astype(str).to_numpy()[1:]  # the step from contact k - 1 lands at contact k
    prev = step_s[:-1]
    for s in ("left", "right"):
        x = prev[(onto == s) & np.isfinite(prev)]
        if len(x) >= ASYMMETRY_MIN_STEPS:
            out[f"step_time_s_{s}"] = float(np.mean(x))
    if out["step_time_s_left"] is not None and out["step_time_s_right"] is not None:
        out["step_time_s_ratio"] = out["step_time_s_left"] / out["step_time_s_right"]
    return out


def leg_summary(steps: pd.DataFrame) -> dict:
    """Decision W228: :data:`LEG_KEYS` of a tracked step table. A lower-back table (every row ``unit`` waist) with
    W129's ``side`` column: its rows counted by side (``n_steps_left``, ``n_steps_right`` and the rows whose side
    was undecided, ``n_steps_side_undecided``; they add up to ``n_steps``); any other table None (a foot unit sees
    one foot: ``n_strides_one_foot``). The step-time asymmetry: :func:`step_time_asymmetry_report` (L121, L216) -
    ``step_time_asymmetry_pct`` only from :data:`ASYMMETRY_FLOOR_PCT`, the raw index, its step times and the
    reason (a foot table's: not observable)."""
    out: dict = dict.fromkeys(LEG_KEYS)
    if not len(steps) or "start_s" not in steps:
        return out
    rep = step_time_asymmetry_report(steps)
    out.update(step_time_asymmetry_pct=rep["step_time_asymmetry_pct"], step_time_asymmetry_raw_pct=rep["raw_pct"],
               n_step_time_asymmetry_steps=rep["n_step_times"], step_time_asymmetry_reason=rep["reason"])
    if _is_lower_back(steps) and "side" in steps:
        side = steps["side"].fillna("").astype(str).to_numpy()
        out["n_steps_left"], out["n_steps_right"] = int((side == "left").sum()), int((side == "right").sum())
        out["n_steps_side_undecided"] = int(len(side) - out["n_steps_left"] - out["n_steps_right"])
        out.update(side_step_times(steps))  # decision W250
    return out


def standing_pauses(spans: np.ndarray, postures, *, min_s: float = PAUSE_MIN_S) -> tuple[np.ndarray, float]:
    """Decision C248: the pauses of ``spans`` (:func:`pause_spans`, s) less the seconds the posture runs
    ``postures`` (a lower-back track's ``info["postures"]``, ``[start_s, end_s, posture]``, W222) read as sitting or
    lying, those with at least ``min_s`` (L104's pause) left, in time order; and the seconds taken out."""
    from pdrlearn.waist.posture_time import LYING, SITTING

    seated = np.array([(float(a), float(b)) for a, b, p in postures if p in (SITTING, LYING)], float).reshape(-1, 2)
    spans = np.asarray(spans, float).reshape(-1, 2)
    cut = np.array([np.clip(np.minimum(seated[:, 1], b) - np.maximum(seated[:, 0], a), 0.0, None).sum()
                    for a, b in spans]) if len(spans) else np.zeros(0)
    left = spans[:, 1] - spans[:, 0] - cut
    return left[left >= min_s], float(cut.sum())


def clinical_summary(steps: pd.DataFrame, *, contact_scatter_max_s: float | None = None, turn_gaps=None,
                     postures=None) -> dict:
    """Decision L104: :data:`CLINICAL_KEYS` of a tracked step table (module docstring): ``n_pauses``,
    ``pause_time_s`` (summed), ``longest_pause_s``, ``n_walking_bouts``, ``turn_count`` (turns of at least
    ``turn_count_min_deg``), ``stride_time_cv_pct`` over ``n_cv_strides`` straight strides, withheld (decision
    L113) when the contacts' timing scatter reaches ``contact_scatter_max_s`` (s; None = the module's
    :data:`CONTACT_SCATTER_MAX_S`, off). Decision L212: ``stride_length_cv_pct``, the CV of the same strides'
    lengths (not withheld by L113: no contact timing in a length). Decision L214: with no stride-time CV,
    ``stride_time_cv_withheld`` says why - ``{"cause", "reason", ...}``, ``cause`` one of
    :data:`CV_WITHHELD_CAUSES` (too few strides: ``n_cv_strides``, ``needed``, and L215's ``n_straight_strides`` /
    ``n_not_level``, the straight strides and those L188's level criterion drops). Decision C180: ``turn_gaps``
    (a lower-back track's :class:`~pdrlearn.track.turn_gaps.TurnGaps`, an option: ``track`` passes none, so L104's
    pauses and walking bouts keep the fixed 1 s rule; C182's corridor fill is bouts.csv's): an interval a walker's
    turn fills is no pause. Decision C248: with ``postures`` (a lower-back track's ``info["postures"]``) the pauses
    are the standing time (:func:`standing_pauses`) and ``pause_seated_lying_s`` the sitting / lying seconds left
    out (None without ``postures``)."""
    limit = CONTACT_SCATTER_MAX_S if contact_scatter_max_s is None else float(contact_scatter_max_s)
    out: dict = {"n_pauses": 0, "pause_time_s": 0.0, "longest_pause_s": None, "pause_seated_lying_s": None,
                 "n_walking_bouts": 0,
                 "turn_count": 0, "turn_count_min_deg": TURN_COUNT_MIN_DEG, "stride_time_cv_pct": None,
                 "n_cv_strides": 0, "stride_time_cv_withheld": None, "stride_time_cv_within_bouts_pct": None,
                 "stride_time_cv_bouts": [], "stride_length_cv_pct": None,
                 "stride_length_cv_within_segments_pct": None, "n_cv_segments": 0, "stride_time_cv_direction": None}
    if not len(steps) or "start_s" not in steps:
        return out
    p = pauses(steps, turn_gaps=turn_gaps)
    if postures is not None:  # decision C248: a pause is standing; sitting and lying are left out
        p, out["pause_seated_lying_s"] = standing_pauses(pause_spans(steps, turn_gaps=turn_gaps), postures)
    out["n_pauses"], out["pause_time_s"] = int(len(p)), float(p.sum())
    out["longest_pause_s"] = float(p.max()) if len(p) else None
    # n_pauses + 1 without a data gap (L269: a long gap ends one)
    out["n_walking_bouts"] = len(bout_rows(steps, turn_gaps=turn_gaps))
    out["turn_count"] = int((np.abs(turns(steps)) >= TURN_COUNT_MIN_DEG).sum())
    if _is_lower_back(steps):  # decision L214: L104 gives no CV on the lower back; the summary says why
        out["stride_time_cv_withheld"] = {"cause": "lower_back", "reason": LOWER_BACK_CV_REASON,
                                          **lower_back_cv(steps, turn_gaps=turn_gaps)}  # decision W558
        return out
    st, steady = rows = steady_rows(steps)  # taken once: every CV below is over these strides
    s, onset = _straight_stride_times(st, steady)
    out["n_cv_strides"] = int(len(s))
    out["stride_time_cv_direction"] = cv_direction(steps, rows=rows) if len(s) else None  # decision L444
    if len(s) >= CV_MIN_STRIDES and s.mean() > 0:
        cv = float(100.0 * s.std(ddof=1) / s.mean())
        length = steady_stride_lengths(st, steady)
        length_cv = cv_pct(length[np.isfinite(length)]) if np.isfinite(length).sum() >= CV_MIN_STRIDES else math.nan
        out["stride_length_cv_pct"] = length_cv if math.isfinite(length_cv) else None  # decision L212
        seg_cv, n_seg = segment_length_cv(st, steady)  # decision L380: about each straight stretch's own mean
        out["stride_length_cv_within_segments_pct"] = seg_cv if math.isfinite(seg_cv) else None
        out["n_cv_segments"] = n_seg
        scatter = contact_scatter_s(s, onset) if np.isfinite(onset).all() else 0.0
        if scatter >= limit:  # decision L113: the contacts' timing, not the walker's rhythm
            out["stride_time_cv_withheld"] = {
                "cause": "contact_scatter", "contact_cv_pct": cv,
                "swing_onset_cv_pct": float(100.0 * onset.std(ddof=1) / onset.mean()), "contact_scatter_s": scatter,
                "reason": "the initial contacts' timing scatters (decision L113)"}
        else:
            out["stride_time_cv_pct"] = cv
            pooled = pooled_cv(steps, cv, rows=rows)  # decision L196: a CV over bouts of different rhythm
            if pooled:
                out["stride_time_cv_within_bouts_pct"] = pooled["within_bouts_cv_pct"]
                out["stride_time_cv_bouts"] = pooled["bouts"]
    elif "stride_time_s" in steps:  # decisions L214, L215: too few steady strides, and whether the level rule did it
        n_straight, n_not_level = _not_level(steps)
        w = {"cause": "too_few_strides", "n_cv_strides": int(len(s)), "needed": CV_MIN_STRIDES,
             "n_straight_strides": n_straight, "n_not_level": n_not_level,
             "level_note": None, "reason": f"{len(s)} steady level forward strides, {CV_MIN_STRIDES} needed"}
        if n_straight and n_not_level > NOT_LEVEL_SHARE * n_straight:
            w["level_note"] = (f"{n_not_level} of {n_straight} straight strides not level by their integrated "
                               "height (|dz_m| >= 0.10 m, L188"
                               + ("; a treadmill incline's strides count with meta.json belt_incline_pct, "
                                  "L322 / L442"
                                  if not cv_keeps_ramps() else "") + ")")
            w["reason"] += "; " + w["level_note"]
        out["stride_time_cv_withheld"] = w
    return out


def quantisation_cv_pct(resolution_s: float, stride_s: float) -> float:
    """Decision L116: the stride-time CV (%) that rounding both contacts of a stride time to whole samples of
    ``resolution_s`` (s) adds alone to a ``stride_s`` (s) stride: each rounding error uniform over one period,
    variance resolution^2 / 12 (Widrow & Kollar, Quantization Noise, 2008, ch. 4), two independent ones per stride
    time, so an SD of resolution / sqrt(6); it adds in quadrature to the walker's own CV."""
    return float(100.0 * resolution_s / math.sqrt(6.0) / stride_s)


def cadence_step_spm(resolution_s: float, stride_s: float) -> float:
    """Decision L116: how far (steps/min) the cadence 120 / stride time moves when a ``stride_s`` (s) stride time
    changes by one sample ``resolution_s`` (s): 120 / stride - 120 / (stride + resolution), the step in which a
    median of whole-sample stride times moves."""
    return float(120.0 / stride_s - 120.0 / (stride_s + resolution_s))


def contact_timing(session, steps: pd.DataFrame) -> dict:
    """Decision L116: ``timing_resolution_s`` (one period of the contacts' stream, s; None when the table has no
    unit or the stream no rate) and ``contact_timing`` (:data:`WHOLE_SAMPLES`, or :data:`BETWEEN_SAMPLES` for foot
    contacts under steps decision 32) of a tracked step table of ``session``; both None for a table without a
    contact time (``event_s``: ``run`` / ``--streaming`` without ``--contacts``)."""
    from pdrlearn.kernels import contact

    timed = "event_s" in steps and bool(np.isfinite(steps["event_s"].to_numpy(float)).any())
    unit = str(steps["unit"].iloc[0]) if timed and "unit" in steps else None
    name = {"foot": "fAccelerometer", "waist": "wAccelerometer"}.get(unit or "")
    rate = float(session.streams[name].rate_hz) if name and session.has(name) else math.nan
    if not (math.isfinite(rate) and rate > 0):
        return {"timing_resolution_s": None, "contact_timing": None}
    return {"timing_resolution_s": round(1.0 / rate, 9),  # the median period of timestamps in ms: 1e-9 s is noise
            "contact_timing": BETWEEN_SAMPLES if unit == "foot" and contact.SUBSAMPLE else WHOLE_SAMPLES}


def resolution_warning(summary: dict) -> str | None:
    """Decision L116: one line when the summary reports a stride-time CV from whole-sample contacts whose rounding
    alone (:func:`quantisation_cv_pct` at ``timing_resolution_s`` and ``median_stride_time_s``) raises it by
    :data:`QUANTISATION_WARN_PCT` % or more (reported / sqrt(reported^2 - rounding^2) - 1); None otherwise."""
    cv, dt, stride = (summary.get(k) for k in ("stride_time_cv_pct", "timing_resolution_s", "median_stride_time_s"))
    if cv is None or not dt or not stride or summary.get("contact_timing") != WHOLE_SAMPLES:
        return None
    q = quantisation_cv_pct(dt, stride)
    if cv > q and cv / math.sqrt(cv * cv - q * q) - 1.0 < QUANTISATION_WARN_PCT / 100.0:
        return None
    return (f"stride-time CV {cv:.2f} % from contacts timed to whole samples of {1000 * dt:.0f} ms ({1 / dt:g} Hz): "
            f"the rounding alone adds ~{q:.2f} % in quadrature (the walker's own would be ~"
            f"{math.sqrt(max(cv * cv - q * q, 0.0)):.2f} %) and the median cadence moves in steps of "
            f"~{cadence_step_spm(dt, stride):.1f} steps/min (decision L116); compare such values only between "
            f"sessions of the same rate, or record at 100 Hz")


#: decision L196: the pooled-CV line lists at most this many bouts
POOLED_CV_LISTED = 6


def pooled_cv_warning(summary: dict) -> str | None:
    """Decision L196: one line when the summary's stride-time CV pools walking bouts of different rhythm
    (``stride_time_cv_within_bouts_pct`` and ``stride_time_cv_bouts``, :func:`pooled_cv`); None otherwise. The CV
    itself is printed as before."""
    within, bouts = summary.get("stride_time_cv_within_bouts_pct"), summary.get("stride_time_cv_bouts") or []
    cv = summary.get("stride_time_cv_pct")
    if within is None or not bouts or cv is None:
        return None
    listed = "; ".join(f"bout {b['bout']} from {b['start_s']:.1f} s: median stride {b['median_stride_time_s']:.2f} s, "
                       f"CV {b['cv_pct']:.1f} % over {b['n_strides']}" for b in bouts[:POOLED_CV_LISTED])
    more = f"; {len(bouts) - POOLED_CV_LISTED} more" if len(bouts) > POOLED_CV_LISTED else ""
    return (f"stride-time CV {cv:.1f} % pools walking bouts of different rhythm: within the bouts it is "
            f"{within:.1f} % ({listed}{more}), so the session's CV measures the change of pace "
            "between bouts, not the stride-to-stride variability; take a bout's own CV with 'pdrlearn track DIR "
            "--window START,END' (bouts.csv gives the spans; decision L196)")


def pooled_length_cv_warning(summary: dict) -> str | None:
    """Decision L380: one line when the summary's stride-length CV exceeds :data:`CV_POOLED_FACTOR` (L196's a-priori
    factor) x its within-segment CV over two or more straight stretches (``stride_length_cv_within_segments_pct``,
    :func:`segment_length_cv`): the CV then measures a change of stride length between stretches (a change of
    pace), not the stride-to-stride variability; None otherwise. The CV itself is printed as before."""
    cv, within = summary.get("stride_length_cv_pct"), summary.get("stride_length_cv_within_segments_pct")
    n = summary.get("n_cv_segments") or 0
    if cv is None or within is None or n < 2 or not cv > CV_POOLED_FACTOR * within:
        return None
    return (f"stride-length CV {cv:.1f} % pools straight stretches of different stride length: about each "
            f"stretch's own mean it is {within:.1f} % ({n} stretches between turns and stops), so the session's "
            "CV measures a change of pace, not the stride-to-stride variability; periods.csv (--per) and bouts.csv "
            "show the pace over time (decision L380)")


def stride_cv_warning(summary: dict) -> str | None:
    """Decision L113: one line when the summary's stride-time CV was withheld for the contacts' timing scatter;
    None otherwise."""
    w = summary.get("stride_time_cv_withheld")
    if not w or "contact_scatter_s" not in w:  # decision L214: the other causes are said in the walk line
        return None
    return (f"stride-time CV withheld: the initial contacts' timing scatters by ~{1000 * w['contact_scatter_s']:.0f} "
            f"ms per contact (their stride-time CV {w['contact_cv_pct']:.1f} % against {w['swing_onset_cv_pct']:.1f} % "
            f"from the same strides' swing onsets; decision L113), so a CV would measure the detector, not the "
            f"walker; force sensors (fForceA/fForceB) time the contacts")
