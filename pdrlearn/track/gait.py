"""Gait parameters of the foot pipeline's strides (decision L66, docs/decisions/localization.md).

One foot's strides, one row each: ``stride_time_s`` (initial contact to initial contact, from the ``event_s``
of consecutive strides), ``cadence_spm`` (steps per minute: two steps per stride of one foot), ``speed_mps``
(``|length_m| / stride_time_s``) and ``turn_angle_rad`` (the foot's heading change over the stride, not wrapped: L690).
No stance/swing times: the pipeline's stance detection (the ZUPT rest, :func:`swing_times`) is the foot at
rest, not initial contact to toe-off; against the mocap of the gaitmap level walks its "swing" came out
+488 / +453 ms long (``experiments/gait_parameters.py``), so it is not given as the gait-lab swing (L66).
Decision L73: with ``toe_off`` (``track --toe-off``, not the default: its adoption rule was not met) the toe-off
from the foot gyroscope (``pdrlearn.track.toeoff``) splits the stride time into ``stance_time_s`` and
``swing_time_s`` (:data:`TOE_OFF_COLUMNS`).
A value that cannot be had is NaN (an empty cell in steps.csv): no stride time for the first stride, after a
gap row, when the initial contacts are more than :data:`MAX_STRIDE_S` apart (a stop, not a stride), or when
either stride's event lies outside its own window. A short rest between two strides (the foot standing a
little longer in a turn) no longer drops the stride time (decision L80).

The summary (decision L79, waist W70): ``walking_time_s`` (the strides' span, first start to last end, less
the rests over :data:`MAX_STRIDE_S` between strides), ``gait_speed_mps`` (``distance / walking_time_s``: a timed
walk from standing, gait initiation / termination and the rows' standing included, decision L250) and
``median_speed_straight_mps`` (the median speed of the strides that turn less than :data:`STRAIGHT_MAX_RAD`: an
instrumented walkway's steady speed).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

# decision E49: one implementation (numpy only), shared with the streaming runtime, which gives each stride its
# stride time as it emits it
from pdrlearn.kernels.contact import MAX_STRIDE_S, TOUCH_S, stride_times  # noqa: F401
from pdrlearn.kernels.gait_range import (  # noqa: F401  (decision E325: the lean kernels, re-exported)
    CADENCE_RANGE_SPM,
    MIN_STRAIGHT_FOR_RANGE,
    RUNNING_FIRST_SPEED_MPS,
    SPEED_RANGE_MPS,
    fast_gait,
    gait_ranges,
    range_side,
    reference_leg_m,
    slow_words,
    validated_text,
)

# decision E320: cadence / speed and the finite median, numpy only, shared with the lean runtime's gait values
from pdrlearn.kernels.gait_values import cadence_speed, median_finite, stance_swing  # noqa: F401  (E326: re-exported)

# decision L79: a stride turning less than STRAIGHT_MAX_RAD (|turn_angle_rad|) is straight for
# ``median_speed_straight_mps``: 15 deg, above the straight-pass strides' -10..+11 deg and below the turnaround
# strides' 20..121 deg of L66 (in the kernels since C91: the runtime's C88 rule reads it)
from pdrlearn.kernels.turn_length import STRAIGHT_MAX_RAD  # noqa: F401
from pdrlearn.track.flags import flag_values
from pdrlearn.warning_lines import coded

#: the gait columns, in the order steps.csv carries them (after the stride's own columns)
GAIT_COLUMNS = ("stride_time_s", "cadence_spm", "speed_mps", "turn_angle_rad")
#: decision L73: toe-off (terminal contact) and the stance/swing split of the stride time, after GAIT_COLUMNS;
#: decision L672: ``cycle_start_s``, the IC that opens the gait cycle the stance/swing belong to (the previous
#: stride's ``event_s``): a row's stance is that contact's, not its own ``event_s``'s (trial T3 finding F4)
TOE_OFF_COLUMNS = ("tc_s", "stance_time_s", "swing_time_s", "stance_pct", "cycle_start_s")


def stride_rows(table: pd.DataFrame) -> np.ndarray:
    """(B,) bool: the rows of a foot steps table that are strides for the gait parameters - not a gap row
    (``gap_s`` > 0, L67) and not a stride the last-line guard moved 0 m (``impossible``, decisions L94 / L97:
    its 0 m is no measurement, so it gives no stride time, cadence, speed or walking time, as a gap row)."""
    n = len(table)
    valid = (table["gap_s"].to_numpy(float) == 0) if "gap_s" in table else np.ones(n, bool)
    if "impossible" in table:
        valid = valid & ~table["impossible"].eq(True).to_numpy(bool)
    return valid


def turn_rows(table: pd.DataFrame) -> np.ndarray:
    """(B,) bool: the rows whose ``turn_angle_rad`` is the foot's measured turn - every row but a gap row
    (``gap_s`` > 0, L67: no foot yaw across it). A stride the last-line guard moved 0 m (``impossible``, L94)
    keeps its turn (decision L109): the guard judged its displacement; the foot's yaw over it was measured as
    every stride's, and the track's heading after it holds that turn."""
    return (table["gap_s"].to_numpy(float) == 0) if "gap_s" in table else np.ones(len(table), bool)


def swing_times(t: np.ndarray, stance: np.ndarray, i0: np.ndarray, i1: np.ndarray) -> np.ndarray:
    """(B,) s: per stride (sample indices ``i0``..``i1`` of ``t``, from rest to rest), the time from its first
    to its last sample outside ``stance`` (+ one sample interval): the foot off its rest. NaN when the stride
    has no stance sample at either end (it does not run from rest to rest) or no moving sample."""
    t = np.asarray(t, dtype=float)
    stance = np.asarray(stance, dtype=bool)
    dt = float(np.median(np.diff(t))) if len(t) > 1 else np.nan
    out = np.full(len(i0), np.nan)
    for k, (a, b) in enumerate(zip(np.asarray(i0, int), np.asarray(i1, int), strict=True)):
        m = stance[a:b + 1]
        if len(m) < 3 or not (m[0] and m[-1]):
            continue
        moving = np.flatnonzero(~m)
        if len(moving):
            out[k] = t[a + moving[-1]] - t[a + moving[0]] + dt
    return out


def cycle_starts(event_s, stride_s) -> np.ndarray:
    """Decision L672: (B,) s, the initial contact that opens each row's gait cycle, ``event_s - stride_s`` (the
    previous stride's IC): :func:`stance_swing`'s stance runs from it to the row's toe-off, and its swing from that
    toe-off to the row's own ``event_s``. NaN where the stride time is (a first stride, after a stop or a gap)."""
    return np.asarray(event_s, dtype=float) - np.asarray(stride_s, dtype=float)


def resumed_times(start_s, end_s, stride_s, valid=None) -> np.ndarray:
    """Decision L512 (L509 revised): (B,) s, the moving time ``speed_mps`` divides by: ``stride_s`` (IC to IC),
    except for a stride after a rest - the first valid row, or one whose ``start_s`` lies more than
    ``clinical.TOUCH_S`` (L500: one 100 Hz sample) after the previous valid row's ``end_s`` - which gets the shorter
    of its own and the next valid row's ``stride_s`` (a stop only lengthens an IC-to-IC; NaN when both are)."""
    from pdrlearn.track.clinical import TOUCH_S as REST_TOUCH_S  # L500: one 100 Hz sample

    st, en, sd = (np.asarray(v, dtype=float) for v in (start_s, end_s, stride_s))
    ok = np.ones(len(st), bool) if valid is None else np.asarray(valid, dtype=bool)
    out = sd.copy()
    idx = np.flatnonzero(ok)
    if not len(idx):
        return out
    after = np.r_[True, st[idx[1:]] > en[idx[:-1]] + REST_TOUCH_S]
    nxt = np.r_[sd[idx[1:]], np.nan]
    with np.errstate(invalid="ignore"):
        out[idx[after]] = np.fmin(sd[idx], nxt)[after]
    return out


def add_gait_columns(table: pd.DataFrame, *, turn_rad=None, valid=None, tc_s=None, turn_valid=None,
                     rest_speed: bool = False, max_stride_s: float = MAX_STRIDE_S) -> pd.DataFrame:
    """``table`` (a strides table with ``start_s``, ``end_s``, ``event_s``, ``length_m``) with the
    :data:`GAIT_COLUMNS` added in place and returned; ``turn_rad`` (B,) the foot's turn over each stride (NaN
    when None); ``valid`` (B,) bool: False for rows that are no stride (across a gap, or moved 0 m by the
    guard, L97). ``turn_valid`` (B,) bool: the rows whose turn was measured (:func:`turn_rows`: not a gap row,
    decision L109; default ``valid``); the others get a NaN turn. ``tc_s`` (B,): each
    stride's toe-off (``pdrlearn.track.toeoff``); given, the :data:`TOE_OFF_COLUMNS` are added too (L73).
    ``rest_speed`` (decisions L509/L512, not adopted: an opt-in keyword only, no module global, W401's pattern):
    True, a stride after a rest takes its speed over the shorter of its own and the next stride's IC-to-IC
    (:func:`resumed_times`); False (default), ``|length_m| / stride_time_s`` for every stride (the first one after a
    stop under 3 s reads low). ``stride_time_s`` stays IC to IC. ``max_stride_s``: the longest IC-to-IC time that is
    a stride (L80's 3 s; decision L605: the offline foot track passes its rhythm's
    :func:`~pdrlearn.kernels.contact.stride_cap_s`)."""
    n = len(table)
    stride = stride_times(table["start_s"], table["end_s"], table["event_s"], valid, max_s=max_stride_s)
    moving = resumed_times(table["start_s"], table["end_s"], stride, valid) if rest_speed else stride
    # decision L690: the turn as given (a spin of 180-360 deg inside one stride is itself; no wrap)
    turn = np.full(n, np.nan) if turn_rad is None else np.array(turn_rad, dtype=float)
    turn_valid = valid if turn_valid is None else turn_valid
    if turn_valid is not None:
        turn[~np.asarray(turn_valid, dtype=bool)] = np.nan
    table["stride_time_s"] = stride
    # decision E320: the lean runtime's kernel (L66: two steps per stride of one foot; decisions L509, L512)
    table["cadence_spm"], table["speed_mps"] = cadence_speed(table["length_m"].to_numpy(float), stride, moving)
    table["turn_angle_rad"] = turn
    if tc_s is not None:
        with np.errstate(invalid="ignore", divide="ignore"):
            cols = stance_swing(table["start_s"], table["end_s"], table["event_s"], tc_s, stride, valid)
        cols += (cycle_starts(table["event_s"], stride),)
        for name, col in zip(TOE_OFF_COLUMNS, cols, strict=True):
            table[name] = col
    return table


def streamed_gait_columns(table: pd.DataFrame, tc_s=None) -> pd.DataFrame:
    """Decision E51: the :data:`GAIT_COLUMNS` of a streamed foot table (``track --streaming``, ``pdrlearn run``:
    ``event_s`` the runtime's initial contact, E49, NaN on a gap row; ``turn_angle_rad`` the stride's own turn;
    ``gap_s``) by :func:`add_gait_columns` (a gap row, ``gap_s`` > 0, is no stride, L67), placed as offline's
    steps.csv places them (before ``gap_s`` and ``unit``). ``tc_s`` (decision E311: ``run --gait``'s L73 toe-offs):
    the :data:`TOE_OFF_COLUMNS` too, as offline ``--toe-off``. In place; returned."""
    valid = stride_rows(table) if "gap_s" in table or "impossible" in table else None  # L67, L97
    turn = table["turn_angle_rad"].to_numpy(float) if "turn_angle_rad" in table else None
    add_gait_columns(table, turn_rad=turn, valid=valid, turn_valid=turn_rows(table), tc_s=tc_s)  # L109
    tail = [c for c in ("impossible", "gap_s", "unit") if c in table]
    gait = [c for c in GAIT_COLUMNS if c in table]
    order = [c for c in table.columns if c not in gait and c not in tail] + gait + tail
    return table.reindex(columns=order) if list(table.columns) != order else table


def walking_time(start_s, end_s, valid=None, *, max_break_s: float = MAX_STRIDE_S) -> float | None:
    """Decision L79: the time spent walking (s): the rows' span from the first start to the last end, split
    where a row starts more than ``max_break_s`` after the previous row's end (a stop: mobgap WbAssembly
    MaxBreakCriteria(max_break_s=3)) or where an invalid row (a gap row, L67; a waist contact without a next
    one) lies between two rows, the pieces (:func:`walking_pieces`) summed. Rows with no positive duration are
    left out. None without a row."""
    pieces = walking_pieces(start_s, end_s, valid, max_break_s=max_break_s)
    return float(sum(t1 - t0 for t0, t1 in pieces)) if pieces else None


def walking_pieces(start_s, end_s, valid=None, *, max_break_s: float = MAX_STRIDE_S,
                   heading_rad=None, still_s=None) -> list[tuple[float, float]]:
    """The walking time's pieces ``(t0, t1)`` (s; :func:`walking_time`'s rule), in time order. With ``heading_rad``
    (each row's unwrapped heading), decision L194: a break (a gap over ``max_break_s``, or an invalid row) across
    which the heading turns by :data:`~pdrlearn.track.clinical.PAUSE_MAX_TURN_DEG` or more is a turn, not a stop,
    when it is no longer than ``max_break_s`` plus the turn's time at
    :data:`~pdrlearn.track.clinical.TURN_ON_SPOT_MIN_DPS` (L119's rule for pauses): its time is walking; with
    ``still_s`` (each row's still seconds before it, :func:`~pdrlearn.track.clinical.still_before`), decision L372:
    the turn's time is at most the break's time that was not still."""
    st, en = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    ok = np.isfinite(st) & np.isfinite(en) & (en > st)
    if valid is not None:
        ok &= np.asarray(valid, dtype=bool)
    h = None if heading_rad is None else np.asarray(heading_rad, dtype=float)
    pieces, t0, t1, last, broken = [], None, None, None, False
    for i in range(len(st)):
        if not ok[i]:  # an invalid row between two rows ends the piece (its time is not known to be walking)
            broken |= t0 is not None and bool(np.isfinite(en[i]) and en[i] > st[i])
            continue
        if t0 is not None and (broken or st[i] - t1 > max_break_s + 1e-9) \
                and not _turn_bridges(h, last, i, st[i] - t1, max_break_s,
                                      0.0 if still_s is None else float(still_s[i])):
            pieces.append((t0, t1))
            t0 = None
        broken = False
        if t0 is None:
            t0, t1 = st[i], en[i]
        t1 = max(en[i], t1)
        last = i
    if t0 is not None:
        pieces.append((t0, t1))
    return [(float(a), float(b)) for a, b in pieces]


def _turn_bridges(h, last: int | None, i: int, gap_s: float, max_break_s: float, still_s: float = 0.0) -> bool:
    """Decision L194: whether the break between rows ``last`` and ``i`` (``gap_s`` s) is a turn's time (L119); L372:
    the ``still_s`` seconds of it the unit was still are no turn's."""
    from pdrlearn.track.clinical import PAUSE_MAX_TURN_DEG, TURN_ON_SPOT_MIN_DPS

    if h is None or last is None or not (np.isfinite(h[last]) and np.isfinite(h[i])):
        return False
    turn_deg = abs(float(np.degrees(h[i] - h[last])))
    allow = min(turn_deg / TURN_ON_SPOT_MIN_DPS, max(gap_s - still_s, 0.0))  # decision L372
    return turn_deg >= PAUSE_MAX_TURN_DEG and gap_s <= max_break_s + allow + 1e-9


#: every summary carries these keys (None / 0 when the table cannot give them, B14)
SUMMARY_KEYS = ("n_stride_times", "median_stride_time_s", "median_cadence_spm", "median_speed_mps",
                "median_step_time_s", "walking_time_s", "gait_speed_mps", "median_speed_straight_mps",
                "n_straight_strides", "n_stance_times", "median_stance_time_s", "median_swing_time_s",
                "median_stance_pct", "walking_time_no_pauses_s", "walking_speed_mps", "n_stair_strides",
                "n_stair_strides_up", "n_stair_strides_down")  # decision L432


def stair_rows(steps: pd.DataFrame, ramp_not_stair: bool = False) -> np.ndarray:
    """Decision L179: the rows that climb or descend a stair, |``dz_m``| >= ``LEVEL_DZ_M`` (0.10 m, half a stair
    rise: L39's level rule, as the simulator's terrain label, decision S3); all False without ``dz_m``.
    ``ramp_not_stair`` (decision L303, an option, off: its rule was not met; decision L595: a keyword, no module
    switch): the rows of a climb walked under 20 % of rise over run (a ramp or a hill,
    :func:`pdrlearn.track.evaluate.ramp_climb_rows`) left out."""
    from pdrlearn.kernels.distance import LEVEL_DZ_M

    if "dz_m" not in steps:
        return np.zeros(len(steps), bool)
    dz = np.abs(pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float))
    stair = np.nan_to_num(dz, nan=0.0) >= LEVEL_DZ_M
    if ramp_not_stair:
        from pdrlearn.track.evaluate import ramp_climb_rows

        stair &= ~ramp_climb_rows(steps)
    return stair


def stair_counts(steps: pd.DataFrame, valid) -> tuple[int, int]:
    """Decisions L179, L432: the ``valid`` rows climbing and descending a stair, ``(up, down)``: :func:`stair_rows`
    by their own ``dz_m``'s sign. Decision W527: on a lower-back track (W108's ``climb`` column) the rows inside a
    barometric climb count by their climb's sign (W526's pieces, ``evaluate._climb_parts``) whatever their own dz -
    a step-to flight's steps split each riser ~0.03 / ~0.15 m - and only the rows outside a climb by L179's rule."""
    from pdrlearn.track.evaluate import _climb_parts

    valid = np.asarray(valid, dtype=bool)
    stair = stair_rows(steps) & valid
    rising = np.nan_to_num(pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float)) > 0 if "dz_m" in steps \
        else np.zeros(len(steps), bool)
    sign = _climb_parts(steps)[2] if len(steps) and "dz_m" in steps else None
    if sign is None:
        return int((stair & rising).sum()), int((stair & ~rising).sum())
    stair &= sign == 0  # W527: L179's rows outside W108's climbs
    return (int((stair & rising).sum() + ((sign > 0) & valid).sum()),
            int((stair & ~rising).sum() + ((sign < 0) & valid).sum()))


#: decision L705: the summary keys of :func:`stair_ramp_split`
RAMP_STRIDE_KEYS = ("n_ramp_strides_up", "n_ramp_strides_down")


def stair_ramp_split(steps: pd.DataFrame, ramps: list[dict]) -> dict:
    """Decision L705: a hill's strides are no stair strides (a 1.8 m stride on a 10 % hill rises 0.18 m, over
    L179's 0.10 m). ``n_stair_strides_up`` / ``_down``: a foot track's strides inside stairs.csv's flights
    (:func:`pdrlearn.track.stair_flights.flight_stride_counts`: L432's flights, which leave out the climbs L302 calls
    ramps, L443, with or without ramps.csv); a lower-back track (no flights, L440) W527's steps outside ramps.csv's
    ramps. ``n_ramp_strides_up`` / ``_down``: the rows inside ramps.csv's ramps (``ramps``:
    :func:`pdrlearn.track.grade.track_ramps`' dicts, rows ``first`` to ``last`` of ``steps``) by their ramp's
    direction (none without a ramp source: L717's :func:`pdrlearn.track.grade.ramp_source`). The rows are the
    summary's own (:func:`walking_rows` less ``--steady-trim``'s, L415; a lower-back track's are steps).
    ``n_stair_strides`` (L179's count, which the gait-range guards L179 / L435 read) is not changed here."""
    from pdrlearn.track.clinical import _is_lower_back
    from pdrlearn.track.stair_flights import flight_stride_counts
    from pdrlearn.track.steady import trimmed_rows

    valid = walking_rows(steps) & ~trimmed_rows(steps) if len(steps) else np.zeros(0, bool)
    sign = np.zeros(len(steps), int)
    for r in ramps:
        sign[int(r["first"]):int(r["last"]) + 1] = 1 if r["direction"] == "up" else -1
    up, down = stair_counts(steps, valid & (sign == 0)) if _is_lower_back(steps) else flight_stride_counts(steps, valid)
    return {"n_stair_strides_up": up, "n_stair_strides_down": down,
            "n_ramp_strides_up": int((valid & (sign > 0)).sum()),
            "n_ramp_strides_down": int((valid & (sign < 0)).sum())}


def sideways_rows(steps: pd.DataFrame) -> np.ndarray:
    """Decision L228: the foot rows L219's rule found in a side-stepping run (the steps table's ``sideways``
    column); all False without it (a lower-back table, a table from before L228 / L243). A streamed foot table
    (``track --streaming``, ``pdrlearn run``: its ``pivot_rad`` column, L106) flags a run from its third stride, as
    decided live (L243): its first two strides are added back here (:func:`~pdrlearn.kernels.sideways.whole_runs`)."""
    if "sideways" not in steps:
        return np.zeros(len(steps), bool)
    from pdrlearn.kernels.sideways import side_rows

    flags = flag_values(steps["sideways"])
    gap = pd.to_numeric(steps["gap_s"], errors="coerce").to_numpy(float) if "gap_s" in steps else None
    return side_rows(flags, gap, streamed="pivot_rad" in steps)


def not_straight_travel_rows(steps: pd.DataFrame) -> np.ndarray:
    """(B,) bool: the rows ``median_speed_straight_mps`` / ``n_straight_strides`` (and so L95's judged speed) leave
    out whatever their turn: a side step (decision L228, :func:`sideways_rows`) and, decision L580, a stride that
    travels backward (:func:`pdrlearn.track.evaluate.backward_travel`, L203: its own speed is
    ``median_backward_speed_mps``, L326); a lower-back table has no backward travel per step (side steps only)."""
    from pdrlearn.track.evaluate import backward_travel

    back = backward_travel(steps)
    side = sideways_rows(steps)
    return side if back is None else side | np.asarray(back, bool)


def _speed_fields(out: dict, steps: pd.DataFrame, length, valid, speed, straight) -> None:
    """``walking_time_s``, ``gait_speed_mps`` (the rows' |length| summed over ``valid`` rows / walking time),
    ``walking_time_no_pauses_s`` and ``walking_speed_mps`` (the same distance / the walking time outside the
    pauses of :func:`pdrlearn.track.clinical.pause_spans`, decision L110), ``median_speed_straight_mps``
    (median ``speed`` where ``straight``) and ``n_straight_strides``; decision L179: ``n_stair_strides``, the valid
    rows whose |``dz_m``| reaches :data:`pdrlearn.kernels.distance.LEVEL_DZ_M` (none without the column); they are
    never straight (a stair stride's horizontal speed is no walking speed), nor is a side step (decision L228) or a
    backward stride (decision L580, :func:`not_straight_travel_rows`)."""
    from pdrlearn.track.clinical import pause_spans

    pieces = session_walking_pieces(steps, valid)
    wt = float(sum(t1 - t0 for t0, t1 in pieces)) if pieces else None
    dist = float(np.nansum(np.abs(np.asarray(length, dtype=float))[np.asarray(valid, dtype=bool)]))
    out["walking_time_s"] = wt
    out["gait_speed_mps"] = dist / wt if wt else None
    if wt:  # L110: a pause's time inside the walking time (a stop over 3 s is outside it already, L79)
        moving = float(wt - sum(max(0.0, min(b, p1) - max(a, p0)) for a, b in pieces for p0, p1 in pause_spans(steps)))
        out["walking_time_no_pauses_s"] = moving
        out["walking_speed_mps"] = dist / moving if moving > 0 else None
    stair = stair_rows(steps) & np.asarray(valid, dtype=bool)  # decision L179: never straight
    up, down = stair_counts(steps, valid)  # decision W527: on the lower back, its climbs' steps
    out["n_stair_strides"] = up + down
    out["n_stair_strides_up"], out["n_stair_strides_down"] = up, down  # decision L432: split by direction
    # decision L228: no side step; L580: no backward stride
    sp = np.where(np.asarray(straight, dtype=bool) & ~stair & ~not_straight_travel_rows(steps),
                  np.asarray(speed, dtype=float), np.nan)
    out["n_straight_strides"] = int(np.isfinite(sp).sum())
    out["median_speed_straight_mps"] = median_finite(sp)


def session_walking_pieces(steps: pd.DataFrame, valid=None) -> list[tuple[float, float]]:
    """The pieces (s) of a step table's ``walking_time_s`` (:func:`walking_pieces` on the rows in their order, with
    decision L194's heading where the rows are in time order); ``valid`` None: :func:`walking_rows`. One definition
    for the summary's walking time and the time accounting of windows and periods (decision L275)."""
    from pdrlearn.track.clinical import still_before, unwrapped_heading

    if not len(steps):
        return []
    valid = walking_rows(steps) if valid is None else valid
    # decision L194: a turn across a break is walking (L119); the rows in time order, as the pause rule takes them
    heading = unwrapped_heading(steps) if "heading_rad" in steps and steps["start_s"].is_monotonic_increasing else None
    return walking_pieces(steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float), valid,
                          heading_rad=heading, still_s=None if heading is None else still_before(steps))  # L372


def walking_rows(steps: pd.DataFrame) -> np.ndarray:
    """(B,) bool: the rows :func:`gait_summary` times as walking - a lower-back table's contacts with a next one
    (``has_next``, W70), any other table's :func:`stride_rows` (L67, L97)."""
    if "has_next" in steps and "unit" in steps and len(steps) and (steps["unit"] == "waist").all():
        return steps["has_next"].to_numpy(bool)
    return stride_rows(steps)


def median_cadence(median_stride_s: float | None, fallback_spm: float | None) -> float | None:
    """Decision L176: a summary's ``median_cadence_spm`` - L164's formula (:func:`pdrlearn.track.bouts.cadence_spm`)
    on the two steps of the median stride, 120 / ``median_stride_s``: a stride holds one step of each foot, so its
    time stays unimodal on an asymmetric gait where the step times are bimodal and their median falls between the
    modes. ``fallback_spm`` (the waist's step-time median) without a stride time."""
    from pdrlearn.track.bouts import cadence_spm

    if median_stride_s is None or not np.isfinite(median_stride_s) or median_stride_s <= 0:
        return fallback_spm
    return float(cadence_spm(2, median_stride_s))


def waist_step_times(steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(step_s, has_next, touched)`` (B,) of a waist steps table (:func:`waist_gait_summary`'s rule): each
    contact's step time to the next one (NaN without a next contact, longer than half :data:`MAX_STRIDE_S`, or
    touched by a W27 fragment), whether the next contact is in the same sequence, and the fragments with their
    neighbours."""
    st, en = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    has_next = steps["has_next"].to_numpy(bool) if "has_next" in steps else np.ones(len(st), bool)
    dt = en - st
    # W27: a fragment merged into a neighbour (``merged``) gives its length to that neighbour, whose own row
    # then spans only part of the merged step: the fragment and both its neighbours leave the per-step values
    frag = steps["merged"].to_numpy(bool) if "merged" in steps else np.zeros(len(st), bool)
    touched = frag | np.concatenate([frag[1:], [False]]) | np.concatenate([[False], frag[:-1]])
    ok = has_next & ~touched & np.isfinite(dt) & (dt > 0) & (dt <= MAX_STRIDE_S / 2 + 1e-9)
    return np.where(ok, dt, np.nan), has_next, touched


def waist_gait_summary(steps: pd.DataFrame, cadence_from: str | None = None) -> dict:
    """Decision W70: the gait summary of a waist steps table (one row per initial contact, ``start_s`` this
    contact, ``end_s`` the next, ``has_next``): step time ``end_s - start_s`` of a contact with a next one (at
    most half of :data:`MAX_STRIDE_S`), ``median_stride_time_s`` from contact k to
    k + 2 inside a walking sequence (the same foot's next contact, W47), the straight steps those with
    ``turning`` 0 (the pipeline's turn flag; every step when the table has none). A W27 fragment (``merged``)
    and its two neighbours give no step time (the neighbour carries the merged step's length over part of
    its time), nor a stride time through them; walking time and gait speed keep them. Decisions W224/W225 (default,
    ``cadence_from`` None or ``"strides"``): ``median_cadence_spm`` = :func:`median_cadence` of the stride times
    (L176's formula; the step-time median without a stride time) and ``median_speed_mps`` /
    ``median_speed_straight_mps`` the medians of the stride speed (|length k| + |length k + 1|) / stride time (straight:
    both steps); ``"steps"``: W70's medians of 60 / step time and of ``length_m`` / step time (an option: on
    alternating short / long steps they land on the short steps' mode)."""
    from pdrlearn.track.steady import trimmed_rows
    from pdrlearn.waist.gait_rules import positional_strides

    st = steps["start_s"].to_numpy(float)
    step, has_next, touched = waist_step_times(steps)
    trim = trimmed_rows(steps)  # decision L415: --steady-trim's first / last contacts of each bout
    touched, has_next = touched | trim, has_next & ~trim
    step = np.where(trim, np.nan, step)
    length = np.abs(steps["length_m"].to_numpy(float)) if "length_m" in steps else np.full(len(st), np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        cadence, speed = 60.0 / step, length / step
    k0, k2 = positional_strides(has_next)
    k0, k2 = k0[~(touched[k0] | touched[k0 + 1])], k2[~(touched[k0] | touched[k0 + 1])]  # no spurious contact
    stride = st[k2] - st[k0] if len(k0) else np.zeros(0)
    ok = (stride > 0) & (stride <= MAX_STRIDE_S + 1e-9)
    k0, stride = k0[ok], stride[ok]
    straight = (steps["turning"].to_numpy(float) == 0) if "turning" in steps else np.ones(len(st), bool)
    if _waist_medians_from(cadence_from) == "strides":  # decisions W224/W225: a stride's speed, unimodal
        speed = np.full(len(st), np.nan)
        speed[k0] = (length[k0] + length[k0 + 1]) / stride  # one step of each foot over the stride's time
        # the stride is straight when both its steps are; a stair or side step (L179, L228) as its second step
        # leaves it out as its first step's row does in _speed_fields
        second = np.zeros(len(st), bool)
        second[:-1] = ~straight[1:] | stair_rows(steps)[1:] | sideways_rows(steps)[1:]
        straight = straight & ~second
    grid = _contact_grid(st)  # W359 amended (R1): classes one sample period of the contacts' own grid wide
    stride_med, step_med = _waist_time_median(stride, grid), _waist_time_median(step, grid)  # decision W359
    out: dict = {"n_stride_times": int(len(stride)), "median_stride_time_s": stride_med,
                 "median_cadence_spm": (median_cadence(stride_med, median_finite(cadence))
                                        if _waist_medians_from(cadence_from) == "strides"
                                        else median_finite(cadence)),  # W225: L176's formula is the default
                 "median_speed_mps": median_finite(speed),
                 "median_step_time_s": step_med}
    _speed_fields(out, steps, length, has_next, speed, straight)
    return out


def _contact_grid(start_s: np.ndarray) -> float | None:
    """W359 (amended after review R1): the sample period the table's contact times sit on (None: none found)."""
    from pdrlearn.kernels.grouped_median import sample_grid

    return sample_grid(start_s)


def _waist_time_median(times: np.ndarray, grid: float | None) -> float | None:
    """Decision W359 (adopted; decision L595: the rule, no module switch): the median of a lower-back table's
    whole-sample stride or step times is a grouped-data median (:func:`pdrlearn.kernels.grouped_median.grouped_median`)
    with classes one sample period (``grid``, the contacts' own: :func:`_contact_grid`) wide, not a sample value; the
    plain median without a grid."""
    from pdrlearn.kernels.grouped_median import grouped_median

    return grouped_median(times, grid) if grid else median_finite(times)


#: decisions W224/W225: the medians a lower-back summary takes by default - ``"strides"`` (cadence 120 / the median
#: stride time, speeds of the strides: robust to a hemiparetic walk's alternating short and long steps; adopted by
#: W225's rule: simulated A 0.4-0.95 walks' median |cadence error| 3.60 -> 0.44 steps/min on waist-pendulum) or W70's
#: ``"steps"`` (the median of 60 / step time and of length / step time: an option)
WAIST_MEDIANS_FROM = "strides"


def _waist_medians_from(cadence_from: str | None) -> str:
    """W224: ``cadence_from`` of a lower-back summary (None: :data:`WAIST_MEDIANS_FROM`); one clear error otherwise."""
    how = WAIST_MEDIANS_FROM if cadence_from is None else cadence_from
    if how not in ("steps", "strides"):
        raise ValueError(f"cadence_from={cadence_from!r}: give 'steps' or 'strides' (decision W224)")
    return how


def cycle_speeds(steps: pd.DataFrame) -> np.ndarray:
    """Decision L222: (rows,) a streamed foot stride's speed (m/s) from what it has - its |``length_m``| over the
    time from its ``start_s`` (its rest's end, the swing's start) to the next row's ``start_s``: one gait cycle,
    as an initial contact to the next is (L66). NaN for the last row, where this row or the next is no stride
    (:func:`stride_rows`: a gap row, L67, or an ``impossible`` one, L97), or where the cycle is over
    :data:`MAX_STRIDE_S` (a stop, L79). It gives ``median_speed_straight_mps`` (and so L95's judged speed) of a
    table without stride times; no stride time, cadence or ``speed_mps`` column is made of it (L204)."""
    n = len(steps)
    out = np.full(n, np.nan)
    if n < 2:
        return out
    start = steps["start_s"].to_numpy(float)
    valid = stride_rows(steps)
    dt = start[1:] - start[:-1]
    ok = valid[:-1] & valid[1:] & np.isfinite(dt) & (dt > 0) & (dt <= MAX_STRIDE_S + 1e-9)  # L79: a stop is no stride
    length = np.abs(steps["length_m"].to_numpy(float))[:-1]
    out[:-1] = np.where(ok, length / np.where(ok, dt, 1.0), np.nan)
    return out


def range_speeds(steps: pd.DataFrame, speed: np.ndarray) -> np.ndarray:
    """Decision L222: a foot table whose strides have no stride time (streamed without ``--contacts``, E51) takes
    :func:`cycle_speeds` for its straight-walking speed; any other table keeps its own ``speed_mps``."""
    foot = "unit" not in steps or (steps["unit"] == "foot").all()
    if foot and not np.isfinite(speed).any() and {"start_s", "length_m"} <= set(steps):
        return cycle_speeds(steps)
    return speed


def streamed_gait_summary(steps: pd.DataFrame) -> dict:
    """Decision E48: the L79 keys a streamed foot table (``pdrlearn run``, ``track --streaming``: rest-to-rest
    strides with ``start_s``, ``end_s``, ``length_m`` and ``gap_s``, no initial contact) can give:
    ``walking_time_s`` and ``gait_speed_mps`` from :func:`walking_time` (a gap row, ``gap_s`` > 0, ends a
    piece, L67/E46). Such a table (an older `run` output: no ``stride_time_s`` column) has no initial contact, so no
    stride time, cadence or per-stride speed (L66), and so no ``median_speed_straight_mps``: it stays None and
    ``n_straight_strides`` 0. Since E51 the streamed tables carry the gait columns (:func:`streamed_gait_columns`;
    empty without ``--contacts``) and take :func:`gait_summary`'s own path."""
    n = len(steps)
    valid = stride_rows(steps)  # decisions L67, L97
    out: dict = {}
    turn = np.abs(steps["turn_angle_rad"].to_numpy(float)) if "turn_angle_rad" in steps else np.full(n, np.inf)
    _speed_fields(out, steps, steps["length_m"].to_numpy(float), valid, cycle_speeds(steps),
                  turn < STRAIGHT_MAX_RAD)  # decision L222: the straight strides' speed from their gait cycle
    return out


def stance_share_warning(steps: pd.DataFrame, foot: str | None = None) -> str | None:
    """Decision L315: ``track --toe-off``'s one warning line when the foot's median ``stance_pct`` (L73) is under
    L285's :data:`pdrlearn.track.bilateral.STANCE_MIN_PCT` (the same bound ``pdrlearn gait`` warns on): implausible
    for a healthy walker, the toe-off (or the contact) misread, or (decision L685) a real short stance on this foot
    (an antalgic gait), which one foot's unit cannot tell apart. None without the column, with fewer than L123's
    :data:`MIN_STRAIGHT_FOR_RANGE` stance times, or at or above the bound. Decision L763: the line names the
    ``foot`` (meta.json's, L260; "this foot" without) and says a soft contact of *this* foot moves it, a prosthetic
    foot only if it is one (trial s50t2: the line fired on the intact foot and blamed a prosthesis)."""
    from pdrlearn.track.bilateral import STANCE_MIN_PCT

    if "stance_pct" not in steps:
        return None
    pct = steps["stance_pct"].to_numpy(float)
    pct = pct[np.isfinite(pct)]
    if len(pct) < MIN_STRAIGHT_FOR_RANGE or float(np.median(pct)) >= STANCE_MIN_PCT:
        return None
    who = f"the {foot} foot" if foot in ("left", "right") else "this foot"  # decision L763
    return coded(f"toe-off: median stance {float(np.median(pct)):.1f} % of the gait cycle of {who} over {len(pct)} "
                 f"strides, under {STANCE_MIN_PCT:.0f} % (walking: ~60 %, more when slower; decisions L285, L315): "
                 f"either {who}'s toe-off reads early or its contact late (a soft, low-impact contact of {who} moves "
                 "the contact - a prosthetic foot's, if it is one), and then median_stance_time_s, "
                 "median_swing_time_s and median_stance_pct are not measured values; or this foot's stance is really "
                 "short - an antalgic gait, which spares a painful or operated leg (after a knee or hip replacement, "
                 "an injury), or the simulator's --stance-time-asymmetry on this foot; one foot cannot tell which, "
                 "nor give a stance asymmetry: that needs a unit on each foot "
                 "(pdrlearn gait, L685)",
                 "L285")  # decision E170: L285, the first of "decisions L285, L315" (E168)


#: decision L426: the summary's walking time / gait speed keys kept over every stride under --steady-trim (their
#: documented meanings: gait_speed_mps = distance_m / walking_time_s); the trimmed ones go to STEADY_KEYS
WHOLE_WALK_KEYS = ("walking_time_s", "gait_speed_mps", "walking_time_no_pauses_s", "walking_speed_mps")
#: decision L426: ``--steady-trim N``'s own keys (None at N 0): the distance and time of the strides left in, and
#: steady_gait_speed_mps = steady_distance_m / steady_time_s
STEADY_KEYS = ("steady_distance_m", "steady_time_s", "steady_gait_speed_mps")


def gait_summary(steps: pd.DataFrame, cadence_from: str | None = None) -> dict:
    """:func:`trimmed_gait_summary` under the steady-trim in force, with decision L426's split: the
    :data:`WHOLE_WALK_KEYS` over every stride (as at ``--steady-trim 0``) and the trimmed strides' distance, time
    and speed in :data:`STEADY_KEYS` (None when no trim is in force)."""
    from pdrlearn.track.steady import steady_trim, steady_trim_set

    out = trimmed_gait_summary(steps, cadence_from)
    steady = dict.fromkeys(STEADY_KEYS)
    if steady_trim() > 0:  # decision L426: the trimmed speed and time under their own keys
        speed, time_s = out["gait_speed_mps"], out["walking_time_s"]
        steady = {"steady_distance_m": speed * time_s if speed is not None else (0.0 if time_s == 0 else None),
                  "steady_time_s": time_s, "steady_gait_speed_mps": speed}
        with steady_trim_set(0):
            whole = trimmed_gait_summary(steps, cadence_from)
        out.update({k: whole[k] for k in WHOLE_WALK_KEYS})
    out.update(steady)
    return out


def trimmed_gait_summary(steps: pd.DataFrame, cadence_from: str | None = None) -> dict:
    """Medians over the strides that have them: ``median_stride_time_s``, ``median_cadence_spm``,
    ``median_speed_mps`` and ``n_stride_times`` (how many strides have a stride time); decision L79 adds
    ``walking_time_s``, ``gait_speed_mps`` (distance / walking time: the clinical walking speed),
    ``median_speed_straight_mps`` (strides turning less than 15 deg) and ``n_straight_strides``; decision L73:
    ``median_stance_time_s``, ``median_swing_time_s``, ``median_stance_pct`` and ``n_stance_times`` (None / 0
    without the toe-off columns). A waist
    table (every row ``unit`` waist, with ``has_next``) gets :func:`waist_gait_summary` (W70); a foot table without
    gait columns (``--streaming``, ``pdrlearn run`` before E51) :func:`streamed_gait_summary` (E48: walking time
    and gait speed only). Every table gets the same keys, None and 0 where it cannot give them, so every
    summary has them (``run``'s summary carries every key of ``track``'s, B14). ``cadence_from``: a lower-back
    table's medians (:func:`waist_gait_summary`; None: :data:`WAIST_MEDIANS_FROM`, strides since W225); a foot
    table's cadence is the median of its strides' 120 / stride time, or with ``"strides"`` L176's 120 / the median
    stride time (an option: equal but for an even count's middle pair)."""
    out: dict = {k: (0 if k.startswith("n_") else None) for k in SUMMARY_KEYS}
    if not len(steps):
        return out
    if "stride_time_s" not in steps:
        if "has_next" in steps and "unit" in steps and (steps["unit"] == "waist").all():
            out.update(waist_gait_summary(steps, cadence_from))
        elif "unit" in steps and (steps["unit"] == "foot").all() and {"start_s", "end_s", "length_m"} <= set(steps):
            out.update(streamed_gait_summary(steps))
        return out
    from pdrlearn.track.steady import trimmed_rows
    from pdrlearn.track.trunk_pauses import stop_rows

    keep = ~trimmed_rows(steps)  # decision L415: --steady-trim leaves each bout's first / last strides out
    rhythm = keep & ~stop_rows(steps)  # decision L687: a stride holding the lower back's stop is no rhythm
    st = np.where(rhythm, steps["stride_time_s"].to_numpy(float), np.nan)
    out["n_stride_times"] = int(np.isfinite(st).sum())
    for key, col in (("median_stride_time_s", "stride_time_s"), ("median_cadence_spm", "cadence_spm"),
                     ("median_speed_mps", "speed_mps")):
        out[key] = median_finite(steps[col].to_numpy(float)[rhythm])
    if cadence_from == "strides":  # decision L176's formula on the foot (an option; W225 adopted it on the waist)
        out["median_cadence_spm"] = median_cadence(out["median_stride_time_s"], None)
    valid = stride_rows(steps) & keep  # decisions L67, L97; L415
    turn = np.abs(steps["turn_angle_rad"].to_numpy(float))
    _speed_fields(out, steps, steps["length_m"].to_numpy(float), valid,
                  range_speeds(steps, steps["speed_mps"].to_numpy(float)),  # decision L222
                  turn < STRAIGHT_MAX_RAD)
    if "stance_time_s" in steps:  # decision L73
        out["n_stance_times"] = int(np.isfinite(steps["stance_time_s"].to_numpy(float)).sum())
        for key, col in (("median_stance_time_s", "stance_time_s"), ("median_swing_time_s", "swing_time_s"),
                         ("median_stance_pct", "stance_pct")):
            out[key] = median_finite(steps[col].to_numpy(float))
    return out


# decision L123's MIN_STRAIGHT_FOR_RANGE: in pdrlearn.kernels.gait_range (E350: the live Tracker judges it too)


def leg_length(meta: dict | None) -> dict:
    """Decision L148: the walker's leg length for L95's range, from meta.json as the waist pendulum takes it
    (``leg_length_m``, then ``sensor_height_m``, the ``subject`` object's first; waist decision B155), else
    ``LEG_PER_HEIGHT`` x ``height_m``: ``{"leg_length_m", "leg_length_source"}``, empty when meta.json gives none of
    them (then L95's adult range stands)."""
    from pdrlearn.waist.params import LEG_PER_HEIGHT, _meta_numbers

    meta = meta or {}
    # decision B175: a foot-only session's sensor_height_m (written by imports before B175) is the foot unit's
    keys = ("leg_length_m",) if meta.get("placement") == "foot" else ("leg_length_m", "sensor_height_m")
    found = _meta_numbers(meta, *keys)
    if found:
        return {"leg_length_m": found[0][1], "leg_length_source": f"meta.json {found[0][0]}"}
    height = _meta_numbers(meta, "height_m")
    if height:
        return {"leg_length_m": LEG_PER_HEIGHT * height[0][1],
                "leg_length_source": f"{LEG_PER_HEIGHT} x meta.json {height[0][0]}"}
    return {}


#: decision L195: a bout is judged for L95's range with at least this many strides (L123's minimum for a speed)
BOUT_RANGE_MIN_STRIDES = MIN_STRAIGHT_FOR_RANGE


def _finite(v) -> float | None:
    """``v`` as a float when it is a finite number (numpy scalars too, as L95's check read them before), else None."""
    from pdrlearn.settings import is_number

    return float(v) if is_number(v) and np.isfinite(v) else None


def _leg(summary: dict) -> float | None:
    leg = _finite(summary.get("leg_length_m"))
    return leg if leg is not None and leg > 0 else None


#: decision L492: what L95's fast line (and W100's short-step line on the lower back) adds when meta.json gives no
#: height or leg length: a child's cadence is above the adult range L95 judges without one (L148 scales it)
NO_HEIGHT_HINT = ("if the walker is a child or short, give the height or the leg length (pdrlearn import "
                  "--subject-height M or --leg-length M, or meta.json height_m / leg_length_m): the walking range "
                  "scales with the leg (decisions L148, L492)")


#: decisions W144, W178, L197: the fast gaits' names, in L95's session line and in L195's bout line; decision C192:
#: a fast cadence at a walking speed is stated as the measured cadence above the validated range, the gaits it may be
#: named after it (a dancer's quickstep is neither running nor festination)
FAST_GAITS = {"running": ("this looks like running, and running is not supported: ", "looks like running"),
              "running_first": ("a cadence above the walking range the pipelines were validated on (running, or short "
                                "fast steps: quick dance steps, a festinating or shuffling gait): ",
                                "running, or short fast steps"),
              "short_fast": ("a cadence above the walking range the pipelines were validated on (short fast steps: "
                             "quick dance steps, a festinating or shuffling gait; or running): ",
                             "short fast steps or running")}


#: decision W549: the running-first gait's names on an uncalibrated ``waist-pendulum`` track (fast long strides too)
RACE_WALK_GAITS = ("a cadence above the walking range the pipelines were validated on (fast long strides: race walking "
                   "or running; or short fast steps: quick dance steps, a festinating or shuffling gait): ")
#: decision W549: what that line adds - the lower back alone cannot tell the two (the simulator's shufflers and race
#: walkers read about the same 0.63 m step at 160-215 steps/min) and they read in opposite directions (the ranges:
#: experiments/race_walk_s48_w549.py on fresh users 15840-15859, race and shuffling gaits, uncalibrated)
RACE_WALK_CLAUSE = ("; on the uncalibrated lower back fast long strides (race walking) read short (simulated race "
                    "walks: {race} % distance) and short fast steps read long (simulated shuffling: {shuffle} %), "
                    "so the distance is off either way: calibrate on this walker's own walk of known length "
                    "('pdrlearn calibrate DIR --distance M --out PARAMS.json', then track with --params "
                    "PARAMS.json; decision W549)")
RACE_WALK_RANGES = {"race": "-50.21 to -32.00", "shuffle": "+54.54 to +133.36"}  # W549, as printed


def race_walk_case(summary: dict, info: dict, gait: str) -> bool:
    """Decision W549: a running-first ``gait`` (W178) on an uncalibrated ``waist-pendulum`` track."""
    pipeline = str(summary.get("pipeline") or info.get("pipeline") or "")
    return gait == "running_first" and pipeline == "waist-pendulum" and info.get("params_source") == "defaults"


def _validated(summary: dict, leg: float | None) -> str:
    return validated_text(leg, summary.get("leg_length_source"))  # decisions L95 / L148 (E350: shared)


def _straight_judged(summary: dict) -> bool:
    """Decision L123: the summary has :data:`MIN_STRAIGHT_FOR_RANGE` straight strides with a finite median speed."""
    straight = summary.get("median_speed_straight_mps")
    return straight is not None and bool(np.isfinite(straight)) and (summary.get("n_straight_strides") or 0) >= \
        MIN_STRAIGHT_FOR_RANGE


def _stair_walk(summary: dict) -> bool:
    """Decision L179: too few level straight strides (L123) and at least as many stair strides: a walk of stairs,
    whose horizontal speeds are the stairs' and the landings' turns."""
    return not _straight_judged(summary) and (summary.get("n_stair_strides") or 0) >= MIN_STRAIGHT_FOR_RANGE


def _mostly_stairs(summary: dict) -> bool:
    """Decision L435: at least :data:`MIN_STRAIGHT_FOR_RANGE` stair strides and no fewer than the straight level
    strides L123 judges - a walk mostly of stairs, whose gait speed (distance / walking time, the flights' slow
    horizontal progress in it) is no level walking speed, even when L123 still has enough straight strides to judge
    (trial T3's step-to-step walk: 24 stair strides, 5 straight ones at 1.06 m/s, gait speed 0.38 m/s)."""
    stairs = summary.get("n_stair_strides") or 0
    return stairs >= MIN_STRAIGHT_FOR_RANGE and stairs >= (summary.get("n_straight_strides") or 0)


def steps_in_place(summary: dict, in_place_stride_m: float = 0.10) -> bool:
    """Decision L778 (our rule, no document gives one): L123's straight strides are steps in place - a shuffle or
    a march on the spot, no straight walking - when their median stride (``median_speed_straight_mps`` x the
    stride time 120 / ``median_cadence_spm``) is under ``in_place_stride_m`` (0.10 m: an eighth of the shortest
    stride L95's range holds, 0.5 m/s at 70 steps/min = 0.86 m; trial s50t1 F7's shuffle: 0.01 m/s at 93
    steps/min, 0.02 m). False when either figure is unknown."""
    speed, cad = _finite(summary.get("median_speed_straight_mps")), _finite(summary.get("median_cadence_spm"))
    if speed is None or cad is None or cad <= 0:
        return False
    return speed * 120.0 / cad < in_place_stride_m  # the stride time is 120 / cadence (L176)


def _judged(summary: dict, in_place_stride_m: float | None = 0.10) -> tuple[float | None, float | None, str]:
    """L95's figures of a summary: the median cadence and the judged speed with its name (L123, L179). Decision
    L778: straight strides that are steps in place (:func:`steps_in_place`, ``in_place_stride_m``; None: the rule
    before L778) have no walking speed to judge: the cadence alone is."""
    speed, what_speed = summary.get("median_speed_mps"), "speed"
    straight = summary.get("median_speed_straight_mps")
    if _straight_judged(summary) and in_place_stride_m is not None and steps_in_place(summary, in_place_stride_m):
        # decision L778: a shuffle on the spot is no slow walk; its cadence is still judged
        return _finite(summary.get("median_cadence_spm")), None, what_speed
    if _straight_judged(summary):
        speed, what_speed = straight, "straight-walking speed"
    elif _stair_walk(summary):
        # decision L179: too few level straight strides on a walk of stairs: its speeds are the stairs' and the
        # landings' turns, slow horizontally by nature; the cadence alone is judged
        speed = None
    elif speed is None:
        speed = summary.get("gait_speed_mps")
    return _finite(summary.get("median_cadence_spm")), _finite(speed), what_speed


def range_figures(summary: dict) -> str:
    """L95's figures of a summary as its line gives them: ``median cadence 92 steps/min, straight-walking speed
    0.41 m/s`` (:func:`_judged`'s cadence and judged speed; either left out when not known)."""
    cad, speed, what_speed = _judged(summary)
    return ", ".join([*([f"median cadence {cad:.0f} steps/min"] if cad is not None else []),
                      *([f"{what_speed} {speed:.2f} m/s"] if speed is not None else [])])


def session_range_side(summary: dict) -> str | None:
    """Decision L95: :func:`range_side` of the summary's own figures (the session line's verdict). Decision L409: a
    walk of stairs (L179, no speed judged) whose gait speed lies above L95's leg-scaled speed range is fast too."""
    cad, speed, _ = _judged(summary)
    side = range_side(cad, speed, _leg(summary))
    return "fast" if side is None and _stair_walk_too_fast(summary, speed) else side


def _stair_walk_too_fast(summary: dict, speed: float | None) -> bool:
    """Decision L409: L179 judged no speed (a walk of stairs: its horizontal speed is slow by nature) while the gait
    speed (distance / walking time) is above L95's speed range (2.5 m/s, leg-scaled by L148): no stair walk goes that
    fast, so the session line fires on it (a fast run read as stairs by its altitude, trial T3's 4.06 m/s)."""
    gait_speed = _finite(summary.get("gait_speed_mps"))
    return speed is None and _stair_walk(summary) and gait_speed is not None and \
        gait_speed > gait_ranges(_leg(summary))[1][1]


def gait_range_warning(summary: dict, *, consequence: str | None = None) -> str | None:
    """Decision L95: one line when the summary's median cadence or speed (``median_speed_mps``, else
    ``gait_speed_mps``) lies outside :data:`CADENCE_RANGE_SPM` / :data:`SPEED_RANGE_MPS`; None inside (or with
    neither figure); decision L148: the ranges scaled to the summary's ``leg_length_m`` (:func:`gait_ranges`, a
    child's walk is no run). Adds the out-of-domain fraction of a model's classes when the summary has one (C16).
    Decision L123: with at least :data:`MIN_STRAIGHT_FOR_RANGE` straight strides their median speed
    (``median_speed_straight_mps``) is judged instead, so turning on the spot does not read as a slow walk.
    Decision L179: stair strides are not straight (:func:`_speed_fields`); with fewer straight strides than that and
    at least as many stair strides (``n_stair_strides``) no speed is judged, only the cadence.
    Decision W144: a cadence above the range at a speed inside it or below is named short fast steps (festination)
    or running; "looks like running" needs the speed above the range (or a cadence unknown). ``consequence``
    (decision W617, calibrate's line): what the line says follows, instead of what of a track is not reliable."""
    info = summary.get("info") or {}
    if info.get("step_count_unusable") and session_range_side(summary) != "fast":
        # decision W480: W442's contacts are no step count (W476 withholds their cadence): a line that is not
        # W442's fast one judges and quotes the speed alone
        summary = {**summary, "median_cadence_spm": None}
    cad, speed, _ = _judged(summary)
    figs = range_figures(summary)
    leg = _leg(summary)
    side = session_range_side(summary)  # decision L148: the leg-scaled ranges; L409: a stair walk's gait speed
    if side is None:
        return None
    cad_range, speed_range = gait_ranges(leg)
    slow = (cad is not None and cad < cad_range[0]) or (speed is not None and speed < speed_range[0])
    validated = _validated(summary, leg)
    # decisions W144, W178, L197: which fast gait to name first
    gait_speed = _finite(summary.get("gait_speed_mps"))
    gait = fast_gait(cad, speed, leg, gait_speed)
    race = side == "fast" and race_walk_case(summary, info, gait) and not info.get("step_count_unusable")  # W549
    what = (RACE_WALK_GAITS if race else FAST_GAITS[gait][0] if side == "fast"
            else slow_words())
    if side == "fast" and info.get("step_count_unusable"):  # decision W442: the contacts are not steps here
        what = ("no gait to name: the lower back's contacts are no step count here (the steps are too small or too "
                "slow to count, decision W442), so this cadence is not the walker's: ")
    if side == "fast" and speed is None and cad is not None and gait_speed is not None and \
            gait_speed > speed_range[1]:  # decision L197: the figure that names it running
        figs += f", gait speed {gait_speed:.2f} m/s"
    ood = summary.get("out_of_domain_fraction")
    extra = (f"; {100 * float(ood):.0f} % of the strides lie outside the model's training range" if ood is not None
             else "")
    if slow and str(info.get("pipeline") or "").startswith("waist") and \
            info.get("params_source") == "defaults":
        # decision W77: an uncalibrated waist's step length at slow cadence is the default model's guess
        extra += ("; the waist step length is uncalibrated and the default model is not validated at slow "
                  "cadence: the distance and speed depend on a calibration on this walker's own walk of known "
                  "length ('pdrlearn calibrate DIR --distance M', e.g. a 10 m walk test)")
    if race:  # decision W549: which way each fast gait reads on the uncalibrated lower back
        extra += RACE_WALK_CLAUSE.format(**RACE_WALK_RANGES)
    if side == "fast" and leg is None:  # decision L492: no height or leg known, the adult range was judged
        extra += f"; {NO_HEIGHT_HINT}"
    fast_steps = side == "fast" and gait != "running" and \
        not info.get("step_count_unusable")  # decision C192: a fast cadence at a walking speed
    if consequence is not None:  # decision W617: calibrate's own consequence
        return f"{figs}: {what}{validated}; {consequence}"
    return f"{figs}: {what}{validated}; {_unreliable(summary, info, slow, fast_steps)}{extra}"


def contact_cadence_spm(event_s, unit: str = "foot") -> float | None:
    """Decision steps 44 (shared by L431): the cadence (steps/min) of a detections table's contacts ``event_s`` (s):
    a foot table's consecutive contacts are a stride apart (120 / the median interval, L176's formula), a waist
    table's a step (two consecutive intervals make a stride, W225); intervals longer than
    :data:`pdrlearn.kernels.contact.MAX_STRIDE_S` (half of it for a step) are pauses, not strides. None with fewer
    than L123's :data:`MIN_STRAIGHT_FOR_RANGE` intervals."""
    from pdrlearn.kernels.contact import MAX_STRIDE_S

    t = np.sort(np.asarray(event_s, dtype=float))
    t = t[np.isfinite(t)]
    if len(t) < 2:
        return None
    dt = np.diff(t)
    per_stride = 1 if unit == "foot" else 2  # a foot table's interval is a stride, a waist table's a step
    ok = (dt > 0) & (dt <= MAX_STRIDE_S / per_stride + 1e-9)
    if unit != "foot":  # decision W225: two consecutive steps make a stride (alternating short / long steps)
        dt, ok = dt[:-1] + dt[1:], ok[:-1] & ok[1:]
    dt = dt[ok]
    if len(dt) < MIN_STRAIGHT_FOR_RANGE:  # L123's minimum count for a judged median
        return None
    return median_cadence(float(np.median(dt)), None)  # L176: 120 / the median stride time


def contact_cadence_warning(summary: dict) -> str | None:
    """Decision L431: `track` judges L95's cadence on its foot contacts as `pdrlearn steps` does (steps decision 44,
    :func:`contact_cadence_spm`, kept in ``info["contact_cadence_spm"]`` by the foot pipeline), so the two commands
    agree: when the tracked strides' own figures pass L95 (:func:`session_range_side` None) but the contacts'
    cadence lies outside the leg-scaled range, one line naming both cadences. A stride split at a false rest (a slow
    swing's lull, S77) halves its stride time and doubles its cadence; the contacts are not split. None otherwise."""
    cad = _finite((summary.get("info") or {}).get("contact_cadence_spm"))
    if cad is None or session_range_side(summary) is not None:
        return None
    leg = _leg(summary)
    side = range_side(cad, None, leg)
    if side is None:
        return None
    own = _finite(summary.get("median_cadence_spm"))
    line = gait_range_warning({"median_cadence_spm": cad, "leg_length_m": leg,
                               "leg_length_source": summary.get("leg_length_source"), "info": summary.get("info")})
    return (f"the foot's contacts: {line}" + (f" (the tracked strides' own median cadence {own:.0f} steps/min is "
                                             "inside the range: strides were split between two contacts, as at a "
                                             "slow swing taken for a rest, decision S77)" if own is not None else "")
            + "; `pdrlearn steps` judges the same contacts (decision L431)")


def gait_speed_warning(summary: dict) -> str | None:
    """Decision L353 (L350's candidate): one line when the summary's ``gait_speed_mps`` (distance / walking time, the
    starts, stops, turns and pauses included) is below L95's leg-scaled speed range (L148's :func:`range_side`) while
    L95's own judged figures are inside it (:func:`session_range_side` None: L123's straight strides are walking
    speed); None otherwise, and None when L95 already fires (its line says it). Adopted by L353's rule (the default of
    :func:`pdrlearn.track.evaluate.summary_warnings`: `track`, `track-all`, `run`)."""
    gait_speed = _finite(summary.get("gait_speed_mps"))
    leg = _leg(summary)
    if gait_speed is None or range_side(None, gait_speed, leg) != "slow" or session_range_side(summary) is not None \
            or _stair_walk(summary) or _mostly_stairs(summary):  # L179, L435: stairs are slow horizontally by nature
        return None
    figs = range_figures(summary)
    return (f"the reported gait speed {gait_speed:.2f} m/s (distance / walking time: the starts, stops, turns and "
            f"pauses included) is below the walking the pipelines are validated on ({_validated(summary, leg)})"
            + (f"; the judged {figs} are inside it: the strides are validated walking, the gait speed is this "
               "walk's own" if figs else "") + " (decision L353)")


#: decision L247: what the offline foot track's distance did on simulated shuffling below L95's speed range (users
#: 4900-4919, 0.2-0.5 m/s, no model, with and without force sensors: experiments/results/foot_slow.txt)
SLOW_FOOT_DISTANCE = "-3.1 to +1.4 % on simulated shuffling at 0.2-0.5 m/s"
#: decision C192: what the offline foot track's distance did on simulated fast stepping above L95's cadence range at a
#: walking speed (users 14440-14442, 0.3 s steps of 0.4 / 0.5 / 0.6 m, no model; experiments/results/foot_fast_c192.txt)
FAST_FOOT_DISTANCE = "-0.23 to +0.44 % at 200 steps/min, 1.3-2.0 m/s"


def _unreliable(summary: dict, info: dict, slow: bool, fast_steps: bool = False) -> str:
    """What L95's line says is not reliable. Decision L247: a slow offline foot track without classes (the ZUPT
    strides of a foot unit, ``plasys`` with no model, not streamed) keeps its distance, measured at
    :data:`SLOW_FOOT_DISTANCE`; the line says so and names what stays unvalidated. Every other track: the distance
    too (the lower back reads slow steps long, W207; a streamed foot track read +11 % at 0.2 m/s, L120). Decision
    W227: a lower-back track calibrated at this gait (``info["calibration_covers_cadence"]``, W211's range covers its
    cadence) says its distance and speed are calibrated at this gait; the classes and floors stay unvalidated.
    Decision C192: ``fast_steps`` (a cadence above the range at a walking speed): the same offline foot track keeps
    its distance, measured at :data:`FAST_FOOT_DISTANCE`; a speed above the range (running, which the simulator
    cannot make, S48), a streamed or a lower-back track keeps the line."""
    foot = (str(summary.get("pipeline") or info.get("pipeline") or "") == "plasys" and not info.get("streaming")
            and info.get("classes_source") is None)
    if fast_steps and foot:
        return (f"the offline foot distance (ZUPT strides) held on simulated fast stepping ({FAST_FOOT_DISTANCE}, no "
                "model; decision C192), but the floors and any terrain / direction / length classes are not "
                "validated at this cadence")
    if slow and foot:
        return (f"the offline foot distance (ZUPT strides) stays usable ({SLOW_FOOT_DISTANCE}, no model; decision "
                "L247), but the floors and any terrain / direction / length classes are not validated at this speed")
    if slow and info.get("params_source") == "calibrated" and info.get("calibration_covers_cadence") is True:
        # decision W227: the walker calibrated on walks at this cadence (W211's range +-10 % covers it)
        return ("the distance and speed are calibrated at this gait (this walk's cadence lies inside the lower-back "
                "calibration walks' cadence range +-10 %, decisions W211, W227), but the terrain / direction / "
                "length classes and the floors are not validated at this speed" + _SLOW_COUNT_CALIBRATED)
    text = "the distance, the terrain / direction / length classes and the floors are not reliable"
    if slow and str(summary.get("pipeline") or info.get("pipeline") or "").startswith("waist"):
        # decision L351: slow lower-back contacts are missed now and then; a miss leaves a gap read as a pause
        text += (", nor are the lower back's walking bouts and pauses (a contact missed at a slow cadence reads as a "
                 "pause and splits a bout; decision L351)" + _SLOW_COUNT)
    return text


#: decision W399: what L95's slow lower-back line adds about the step count (T6: simulated 63 steps/min walks read
#: 55-63 steps for 51 true contacts, stride_length_m 0.54 m for 0.60 m)
_SLOW_COUNT = ("; n_steps, the cadence and bouts.csv's stride_length_m are not validated either (extra or missed "
               "contacts at a slow cadence change the count, and a stride's length is its two steps; W399)")
_SLOW_COUNT_CALIBRATED = ("; the calibration corrects the distance, not the step count: n_steps, the cadence and "
                          "bouts.csv's stride_length_m are not validated at this speed, W399)")


def bout_range_flags(table, leg_m: float | None) -> np.ndarray:
    """Decision L195: (bouts,) bool, the bouts of a bouts.csv table (:func:`pdrlearn.track.bouts.detected_bouts`)
    whose own ``cadence_spm`` or ``speed_mps`` is above L95's walking range (:func:`range_side`, leg-scaled by L148),
    judged on bouts of at least :data:`BOUT_RANGE_MIN_STRIDES` strides. Only the fast side: a bout's speed is
    distance / duration with its slower first and last steps and its turns in it (biased low), so a slow bout is
    left to the session's L95 / L123 check on straight strides."""
    if not len(table):
        return np.zeros(0, bool)
    n = table["n_strides"].to_numpy(float)
    return np.array([ni >= BOUT_RANGE_MIN_STRIDES and range_side(_finite(c), _finite(v), leg_m) == "fast"
                     for ni, c, v in zip(n, table["cadence_spm"], table["speed_mps"], strict=True)], dtype=bool)


def bout_range_warning(summary: dict) -> str | None:
    """Decision L195: one line naming the bouts (``bouts_out_of_range``: bouts.csv's number, span, cadence and
    speed) above L95's walking range when the session's own L95 line does not already say the session is fast;
    None otherwise."""
    bouts = summary.get("bouts_out_of_range") or []
    if not bouts or session_range_side(summary) == "fast":
        return None
    leg = _leg(summary)
    parts = []
    for b in bouts:
        cad, speed = _finite(b.get("cadence_spm")), _finite(b.get("speed_mps"))
        figs = ", ".join([*([f"cadence {cad:.0f} steps/min"] if cad is not None else []),
                          *([f"speed {speed:.2f} m/s"] if speed is not None else [])])
        what = FAST_GAITS[fast_gait(cad, speed, leg)][1]
        parts.append(f"bout {b['bout']} ({b['start_s']:.1f}-{b['end_s']:.1f} s, {figs}: {what})")
    cad, _, _ = _judged(summary)
    whole = f" (the session's median cadence {cad:.0f} steps/min is inside it)" if cad is not None else ""
    return (f"{len(bouts)} of {summary.get('n_bouts', len(bouts))} walking bout(s) lie above the walking range"
            f"{whole}: {'; '.join(parts)}; neither running nor short fast steps is supported: "
            f"{_validated(summary, leg)}; in those bouts the distance, the terrain / length classes and the floors "
            "are not reliable, and the session's medians mix both gaits (bouts.csv gait_out_of_range; decision "
            "L195)")
