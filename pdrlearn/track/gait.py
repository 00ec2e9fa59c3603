"""Gait parameters of the foot pipeline's strides (decision L66, docs/decisions/localization.md).

One foot's strides, one row each: ``stride_time_s`` (initial contact to initial contact, from the ``event_s``
of consecutive strides), ``cadence_spm`` (steps per minute: two steps per stride of one foot), ``speed_mps``
(``|length_m| / stride_time_s``) and ``turn_angle_rad`` (the foot's heading change over the stride, wrapped).
No stance/swing times: the pipeline's stance detection (the ZUPT rest, :func:`swing_times`) is the foot at
rest, not initial contact to toe-off; against the mocap of the gaitmap level walks its "swing" came out
+488 / +453 ms long (``experiments/gait_parameters.py``), so it is not given as the gait-lab swing (L66).
Decision L73: with ``toe_off`` (``track --toe-off``, not the default: its adoption rule was not met) the toe-off
from the foot gyroscope (``pdrlearn.track.toeoff``) splits the stride time into ``stance_time_s`` and
``swing_time_s`` (:data:`TOE_OFF_COLUMNS`).
A value that cannot be had is NaN (an empty cell in steps.csv): no stride time at a bout
start (the previous stride does not end where this one starts: a rest longer than the stride bounds' reach, a
gap row, the first stride), or when either stride's event lies outside its own window.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: the gait columns, in the order steps.csv carries them (after the stride's own columns)
GAIT_COLUMNS = ("stride_time_s", "cadence_spm", "speed_mps", "turn_angle_rad")
#: decision L73: toe-off (terminal contact) and the stance/swing split of the stride time, after GAIT_COLUMNS
TOE_OFF_COLUMNS = ("tc_s", "stance_time_s", "swing_time_s", "stance_pct")
#: two strides touch when the first ends within this of the second's start (s; both are samples of one clock)
TOUCH_S = 1e-6


def stride_times(start_s, end_s, event_s, valid=None) -> np.ndarray:
    """(B,) s: ``event_s[i] - event_s[i-1]`` where stride ``i-1`` ends where stride ``i`` starts, both events lie
    inside their own windows, both strides are ``valid`` (not across a gap) and the difference is positive;
    else NaN (decision L66: initial contact to initial contact, the gait-lab stride time)."""
    st, en, ev = (np.asarray(v, dtype=float) for v in (start_s, end_s, event_s))
    n = len(st)
    out = np.full(n, np.nan)
    if n < 2:
        return out
    ok = (ev >= st) & (ev <= en) & np.isfinite(ev)
    if valid is not None:
        ok &= np.asarray(valid, dtype=bool)
    touch = np.abs(st[1:] - en[:-1]) <= TOUCH_S
    d = ev[1:] - ev[:-1]
    good = touch & ok[1:] & ok[:-1] & (d > 0)
    out[1:] = np.where(good, d, np.nan)
    return out


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


def stance_swing(start_s, end_s, event_s, tc_s, stride_s, valid=None) -> tuple[np.ndarray, ...]:
    """Decision L73: (tc, stance, swing, stance_pct), each (B,). ``tc`` is ``tc_s`` where it lies inside its
    stride window before the stride's own IC (``event_s``, itself inside the window) on a ``valid`` row, else
    NaN; swing = IC - tc; stance = ``stride_s`` (IC to IC, L66) - swing = tc - the previous stride's IC, kept
    only when positive; stance_pct = 100 x stance / ``stride_s``."""
    st, en, ev, tc, sd = (np.asarray(v, dtype=float) for v in (start_s, end_s, event_s, tc_s, stride_s))
    ok = np.isfinite(tc) & np.isfinite(ev) & (tc >= st) & (tc < ev) & (ev <= en)
    if valid is not None:
        ok &= np.asarray(valid, dtype=bool)
    tc = np.where(ok, tc, np.nan)
    swing = ev - tc
    stance = sd - swing
    stance = np.where(stance > 0, stance, np.nan)
    return tc, stance, swing, 100.0 * stance / sd


def add_gait_columns(table: pd.DataFrame, *, turn_rad=None, valid=None, tc_s=None) -> pd.DataFrame:
    """``table`` (a strides table with ``start_s``, ``end_s``, ``event_s``, ``length_m``) with the
    :data:`GAIT_COLUMNS` added in place and returned; ``turn_rad`` (B,) the foot's turn over each stride (NaN
    when None); ``valid`` (B,) bool: False for rows that are no stride (across a gap). ``tc_s`` (B,): each
    stride's toe-off (``pdrlearn.track.toeoff``); given, the :data:`TOE_OFF_COLUMNS` are added too (L73)."""
    n = len(table)
    stride = stride_times(table["start_s"], table["end_s"], table["event_s"], valid)
    turn = np.full(n, np.nan) if turn_rad is None else np.angle(np.exp(1j * np.asarray(turn_rad, dtype=float)))
    if valid is not None:
        turn[~np.asarray(valid, dtype=bool)] = np.nan
    with np.errstate(invalid="ignore", divide="ignore"):
        table["stride_time_s"] = stride
        table["cadence_spm"] = 120.0 / stride  # two steps per stride of one foot, per minute
        table["speed_mps"] = np.abs(table["length_m"].to_numpy(float)) / stride
    table["turn_angle_rad"] = turn
    if tc_s is not None:
        with np.errstate(invalid="ignore", divide="ignore"):
            cols = stance_swing(table["start_s"], table["end_s"], table["event_s"], tc_s, stride, valid)
        for name, col in zip(TOE_OFF_COLUMNS, cols, strict=True):
            table[name] = col
    return table


def gait_summary(steps: pd.DataFrame) -> dict:
    """Medians over the strides that have them: ``median_stride_time_s``, ``median_cadence_spm``,
    ``median_speed_mps`` and ``n_stride_times`` (how many strides have a stride time); decision L73:
    ``median_stance_time_s``, ``median_swing_time_s``, ``median_stance_pct`` and ``n_stance_times`` (None / 0
    without the toe-off columns). A table without the
    gait columns (waist pipelines, ``--streaming``, ``pdrlearn run``) gets the same keys, None and 0, so every
    summary has them (``run``'s summary carries every key of ``track``'s, B14)."""
    empty = {"n_stride_times": 0, "median_stride_time_s": None, "median_cadence_spm": None,
             "median_speed_mps": None, "n_stance_times": 0, "median_stance_time_s": None,
             "median_swing_time_s": None, "median_stance_pct": None}
    if "stride_time_s" not in steps or not len(steps):
        return empty
    st = steps["stride_time_s"].to_numpy(float)
    ok = np.isfinite(st)
    out: dict = {**empty, "n_stride_times": int(ok.sum())}
    for key, col in (("median_stride_time_s", "stride_time_s"), ("median_cadence_spm", "cadence_spm"),
                     ("median_speed_mps", "speed_mps")):
        v = steps[col].to_numpy(float)
        v = v[np.isfinite(v)]
        out[key] = float(np.median(v)) if len(v) else None
    if "stance_time_s" in steps:  # decision L73
        out["n_stance_times"] = int(np.isfinite(steps["stance_time_s"].to_numpy(float)).sum())
        for key, col in (("median_stance_time_s", "stance_time_s"), ("median_swing_time_s", "swing_time_s"),
                         ("median_stance_pct", "stance_pct")):
            v = steps[col].to_numpy(float)
            v = v[np.isfinite(v)]
            out[key] = float(np.median(v)) if len(v) else None
    return out
