"""The gait arithmetic of one foot's strides, numpy only (decision E320): shared by the offline gait tables
(:mod:`pdrlearn.track.gait`, :mod:`pdrlearn.track.clinical`, :mod:`pdrlearn.track.bilateral`) and the lean runtime's
per-stride values (:mod:`pdrlearn.runtime.gait`), so both compute each value by the same function.

- :func:`cadence_speed`: a stride's cadence (steps/min) and speed (m/s) from its length and stride time (L66).
- :func:`median_finite`, :func:`mean_finite`: the median / mean of the finite values (None without one).
- :func:`cv_pct`: L104's coefficient of variation; :data:`CV_MIN_STRIDES` its minimum count (L113).
- :func:`symmetry_index_pct`, :func:`side_pair`: Robinson's symmetry index of two sides' values (L121, L259).
- :func:`stance_swing`: a stride's stance and swing from its toe-off (L73; decision E326 moved it here).
- :func:`cycle_flights`, :func:`cycle_support`: one gait cycle's flights (L729), stance and double / single support
  (L262, L327; decision E327 moved them here from ``track.gait_flight`` / ``track.bilateral.cycle_table``).

The stride time itself (initial contact to initial contact, L66 / L80) is :func:`pdrlearn.kernels.contact.stride_times`.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.kernels.contact import TOUCH_S

#: ``stride_time_cv_pct`` needs at least this many straight strides with a stride time (decision L113's minimum;
#: decision L461 reuses it for a symmetry index's steps per side)
CV_MIN_STRIDES = 10


def cadence_speed(length_m, stride_s, moving_s=None) -> tuple[np.ndarray, np.ndarray]:
    """Decision L66: ``(cadence_spm, speed_mps)``, each (B,): 120 / ``stride_s`` (two steps per stride of one foot,
    per minute) and |``length_m``| / ``moving_s`` (default ``stride_s``; decision L512's rest-speed option passes
    its :func:`~pdrlearn.track.gait.resumed_times`). NaN where the time is NaN."""
    stride = np.asarray(stride_s, dtype=float)
    moving = stride if moving_s is None else np.asarray(moving_s, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return 120.0 / stride, np.abs(np.asarray(length_m, dtype=float)) / moving


def median_finite(v) -> float | None:
    """The median of the finite values of ``v`` (None when it has none)."""
    v = np.asarray(v, dtype=float)
    v = v[np.isfinite(v)]
    return float(np.median(v)) if len(v) else None


def mean_finite(v) -> float | None:
    """The mean of the finite values of ``v`` (None when it has none): a side's value of a symmetry index (L259)."""
    v = np.asarray(v, dtype=float)
    v = v[np.isfinite(v)]
    return float(v.mean()) if len(v) else None


def cv_pct(x: np.ndarray) -> float:
    """100 x SD / mean (SD with n - 1) of ``x``; NaN with fewer than 2 values or a mean not above 0 (L104's CV)."""
    x = np.asarray(x, dtype=float)
    return float(100.0 * x.std(ddof=1) / x.mean()) if len(x) >= 2 and x.mean() > 0 else math.nan


def symmetry_index_pct(a: float, b: float) -> float:
    """The symmetry index of two sides' values, 100 x |a - b| / (0.5 x (a + b)) % (Robinson, Herzog & Nigg 1987,
    J Manipulative Physiol Ther 10(4):172-176, SI; 0 = symmetric; which side is which does not matter)."""
    return float(100.0 * abs(a - b) / (0.5 * (a + b)))


def side_pair(name: str, left: float | None, right: float | None) -> dict:
    """``{name}_left``, ``_right``, ``_si_pct`` (:func:`symmetry_index_pct`, Robinson 1987) and ``_ratio`` (L / R,
    Patterson et al. 2010); the index and the ratio None unless both sides have a value and their sum and the right
    one are above 0 (decision L259's walk measures, E320's lean summary)."""
    both = left is not None and right is not None and left + right > 0 and right > 0
    return {f"{name}_left": left, f"{name}_right": right,
            f"{name}_si_pct": symmetry_index_pct(left, right) if both else None,
            f"{name}_ratio": float(left / right) if both else None}


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


def cycle_flights(ic_f: float, tc_o: float, ic_o: float, tc_f: float, ic_next: float) -> tuple[float, float]:
    """Decision L729 (pure kernel): the flight times (s) of one gait cycle of foot F - after the other foot's
    toe-off ``tc_o`` until F's contact ``ic_f``, and after F's toe-off ``tc_f`` until the other's contact ``ic_o``
    (0 where the hand-over overlaps); NaN, NaN when a toe-off is missing or outside its own stride (``tc_o`` after
    ``ic_o`` or more than a cycle before it; ``tc_f`` not between ``ic_f`` and ``ic_next``)."""
    T = ic_next - ic_f
    if not all(map(math.isfinite, (ic_f, tc_o, ic_o, tc_f, ic_next))) or not (
            ic_o - T < tc_o < ic_o and ic_f < tc_f < ic_next):
        return math.nan, math.nan
    gaps = (ic_f - tc_o, ic_o - tc_f)  # a hand-over within TOUCH_S (two events of one instant) is no flight
    return tuple(g if g > TOUCH_S else 0.0 for g in gaps)


def cycle_support(ic_f: float, tc_o: float, ic_o: float, tc_f: float, ic_next: float
                  ) -> tuple[float, float, float, tuple[float, float]]:
    """Decisions L262 / L327 / L729 / L736: ``(stance_s, double_support_pct, single_support_pct, flights)`` of one
    gait cycle of foot F from its IC ``ic_f`` to its next ``ic_next``, with the other foot's toe-off ``tc_o`` and IC
    ``ic_o`` inside: the stance is F's IC to its toe-off ``tc_f`` (NaN unless inside the cycle); the double support
    the two hand-overs' overlaps in % of the cycle and the single support the other foot's swing (Perry & Burnfield
    2010's event order), both NaN unless :func:`cycle_flights` is (0, 0) (a hand-over on one instant: 0 %)."""
    T = ic_next - ic_f
    stance = tc_f - ic_f if ic_f < tc_f < ic_next else math.nan  # decision L327: one unit's clock
    fl = cycle_flights(ic_f, tc_o, ic_o, tc_f, ic_next)  # decision L729: a toe-off before the contact
    ds = ss = math.nan
    if fl == (0.0, 0.0):  # Perry & Burnfield 2010's event order; L736: a hand-over on one instant is 0 %
        ds = 100.0 * (max(tc_o - ic_f, 0.0) + max(tc_f - ic_o, 0.0)) / T
        ss = 100.0 * (ic_o - tc_o) / T
    return stance, ds, ss, fl
