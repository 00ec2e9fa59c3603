"""Decision E320: gait values of the streamed strides on the lean runtime (numpy only).

:class:`StrideGait` collects one foot's :class:`~pdrlearn.runtime.tracker.Step` rows as ``Tracker.push`` /
``flush`` return them (``Tracker(gait=True)`` keeps one) and gives what ``pdrlearn run``'s steps.csv and ``gait``'s
per-foot tables give per stride - the stride time (initial contact to initial contact, decisions L66 / L80:
:func:`pdrlearn.kernels.contact.stride_times`), cadence, speed (:func:`pdrlearn.kernels.gait_values.cadence_speed`),
length and turn - and a session summary: medians, the CV of the stride time and length (L104's formula, withheld
under L113's minimum) and, with the other foot's strides, each side's mean and Robinson's symmetry index
(:func:`pdrlearn.kernels.gait_values.side_pair`; L461's minimum per side; decision E321: the stride lengths' means,
CV and index without gait initiation's and termination's half strides, L317). The arithmetic is the offline tables'
(``pdrlearn.track.gait``, ``pdrlearn.track.bilateral`` import the same kernels). Decision E326: with each stride's
toe-off (``Tracker(gait=True)`` reads it by L73's kernel, :class:`pdrlearn.kernels.toeoff.LiveToeOff`) the stance,
swing and stance % per stride (:func:`pdrlearn.kernels.gait_values.stance_swing`, offline ``--toe-off``'s); decision
E327: with the other foot, the double support of the two feet's gait cycles
(:func:`pdrlearn.kernels.gait_values.cycle_support`, ``gait``'s ``cycle_table`` kernel) and the stance / swing
symmetry indices.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.kernels.contact import MAX_STRIDE_S, stride_times
from pdrlearn.kernels.gait_values import (
    CV_MIN_STRIDES,
    cadence_speed,
    cv_pct,
    cycle_support,
    mean_finite,
    median_finite,
    side_pair,
    stance_swing,
)

#: the per-stride columns of :meth:`StrideGait.strides`, in order
STRIDE_COLUMNS = ("start_s", "end_s", "event_s", "length_m", "stride_length_m", "stride_time_s", "cadence_spm",
                  "speed_mps", "turn_angle_rad", "tc_s", "stance_s", "swing_s", "stance_pct")  # E326: the last four


class StrideGait:
    """One foot's streamed strides and their gait values (decision E320). ``add`` the steps a ``Tracker`` returns,
    in the order it returns them; ``max_stride_s``: the longest initial contact to the next that is a stride (L80's
    3 s, as ``run``'s steps.csv)."""

    def __init__(self, *, max_stride_s: float = MAX_STRIDE_S):
        self.max_stride_s = float(max_stride_s)
        self._rows: list[tuple] = []

    def __len__(self) -> int:
        return len(self._rows)

    def add(self, steps, tc_s=None) -> None:
        """Append the runtime ``steps`` (:class:`~pdrlearn.runtime.tracker.Step`): a gap row (``gap_s`` > 0, L67)
        and a stride L94's guard moved 0 m (``impossible``, L97) are rows without gait values, as in steps.csv.
        ``tc_s``: each step's toe-off (s; decision E326, L73's; default NaN: no stance / swing)."""
        tcs = [math.nan] * len(steps) if tc_s is None else list(tc_s)
        for st, tc in zip(steps, tcs, strict=True):
            gap = st.gap_s > 0
            self._rows.append((st.start_s, st.end_s, st.event_s, st.length_m, st.turn_angle_rad,
                               not gap and not st.impossible, not gap, tc))

    def strides(self) -> dict[str, np.ndarray]:
        """The per-stride values, one (B,) array per :data:`STRIDE_COLUMNS` name, row for row with the added steps:
        ``stride_time_s`` IC to IC (L66, L80; NaN for a first stride, after a stop, a gap row or an invalid row),
        ``cadence_spm`` 120 / stride time, ``speed_mps`` |length| / stride time, ``stride_length_m`` |length_m|
        (NaN on an invalid row), ``turn_angle_rad`` the stride's own turn (NaN on a gap row, L109); decision E326:
        ``tc_s`` the toe-off inside the stride before its IC, ``swing_s`` toe-off to IC, ``stance_s`` the previous
        IC to the toe-off and ``stance_pct`` its % of the stride time (L73's :func:`stance_swing`, offline
        ``--toe-off``'s ``tc_s`` / ``swing_time_s`` / ``stance_time_s`` / ``stance_pct``; NaN without a toe-off)."""
        if not self._rows:
            return {c: np.zeros(0) for c in STRIDE_COLUMNS}
        st, en, ev, length, turn, valid, turn_ok, tc = (np.array(c) for c in zip(*self._rows, strict=True))
        st, en, ev, length, turn, tc = (np.asarray(c, dtype=float) for c in (st, en, ev, length, turn, tc))
        valid, turn_ok = valid.astype(bool), turn_ok.astype(bool)
        stride = stride_times(st, en, ev, valid, max_s=self.max_stride_s)  # decisions L66, L80, E51
        cadence, speed = cadence_speed(length, stride)  # decision L66, as offline's add_gait_columns
        with np.errstate(invalid="ignore", divide="ignore"):  # decision E326 (L73), as offline's add_gait_columns
            tc, stance, swing, pct = stance_swing(st, en, ev, tc, stride, valid)
        return {"start_s": st, "end_s": en, "event_s": ev, "length_m": length,
                "stride_length_m": np.where(valid, np.abs(length), np.nan), "stride_time_s": stride,
                "cadence_spm": cadence, "speed_mps": speed, "turn_angle_rad": np.where(turn_ok, turn, np.nan),
                "tc_s": tc, "stance_s": stance, "swing_s": swing, "stance_pct": pct}

    def bout_ends(self) -> np.ndarray:
        """Decision E321: (B,) bool, this foot's strides that are the first or the last of a bout of its own
        (:func:`bout_end_rows` on its contacts): one foot cannot tell which of them is the half stride (L317)."""
        s = self.strides()
        return bout_end_rows(s["event_s"], np.isfinite(s["stride_length_m"]), self.max_stride_s)

    def summary(self, partial=None) -> dict:
        """The session's values of this foot: ``n_strides`` (rows with gait values), ``n_stride_times``, the medians
        ``median_stride_time_s``, ``median_cadence_spm``, ``median_speed_mps``, ``median_stride_length_m``,
        ``distance_m`` (the strides' |length| summed), ``mean_stride_time_s``, ``mean_stride_length_m`` (a symmetry
        index's values) and ``cv_stride_time_pct`` / ``cv_stride_length_pct`` (L104's 100 x SD / mean over every
        stride that has the value; None under L113's :data:`~pdrlearn.kernels.gait_values.CV_MIN_STRIDES` of them;
        not summary.json's ``stride_time_cv_pct``, which takes the steady straight strides only). Decision E321: the
        stride length's mean and CV leave out the ``partial`` rows ((B,) bool; default :meth:`bout_ends`), gait
        initiation's and termination's half strides (L317); ``n_full_strides`` counts the rest. None without a
        value. Decision E326: ``n_stance_times`` and the medians ``median_stance_s``, ``median_swing_s``,
        ``median_stance_pct`` over every stride that has them (offline ``gait_summary``'s)."""
        s = self.strides()
        length, stride = s["stride_length_m"], s["stride_time_s"]
        partial = self.bout_ends() if partial is None else np.asarray(partial, dtype=bool)
        full = np.where(partial, np.nan, length)  # decision E321 (L317)
        out = {"n_strides": int(np.isfinite(length).sum()), "n_stride_times": int(np.isfinite(stride).sum()),
               "n_full_strides": int(np.isfinite(full).sum()),
               "median_stride_time_s": median_finite(stride), "median_cadence_spm": median_finite(s["cadence_spm"]),
               "median_speed_mps": median_finite(s["speed_mps"]), "median_stride_length_m": median_finite(length),
               "distance_m": float(np.nansum(length)) if len(length) else 0.0,
               "mean_stride_time_s": mean_finite(stride), "mean_stride_length_m": mean_finite(full),
               "n_stance_times": int(np.isfinite(s["stance_s"]).sum()),  # decision E326
               "median_stance_s": median_finite(s["stance_s"]), "median_swing_s": median_finite(s["swing_s"]),
               "median_stance_pct": median_finite(s["stance_pct"])}
        for key, v in (("cv_stride_time_pct", stride), ("cv_stride_length_pct", full)):
            v = v[np.isfinite(v)]
            cv = cv_pct(v) if len(v) >= CV_MIN_STRIDES else math.nan  # decisions L104, L113
            out[key] = cv if math.isfinite(cv) else None
        return out


def bout_end_rows(event_s, valid, max_stride_s: float = MAX_STRIDE_S) -> np.ndarray:
    """Decision E321: (B,) bool, the rows that open or close a bout - L317's partial contacts (gait initiation's and
    termination's half strides) - of rows ``event_s`` (any order; NaN: no contact) that are ``valid`` (a row that
    is not - a gap row, a guarded stride - ends a bout, as a stop does): a bout ends where the next contact comes
    more than ``max_stride_s`` (L79's stop, :data:`~pdrlearn.kernels.contact.MAX_STRIDE_S`) after it."""
    bouts = bout_ids(event_s, valid, max_stride_s)
    ev = np.asarray(event_s, dtype=float)
    out = np.zeros(len(bouts), bool)
    for k in set(bouts[bouts > 0].tolist()):
        rows = np.flatnonzero(bouts == k)
        rows = rows[np.argsort(ev[rows], kind="stable")]  # the bout's first and last contact in time
        out[[rows[0], rows[-1]]] = True
    return out


def bout_ids(event_s, valid, max_stride_s: float = MAX_STRIDE_S) -> np.ndarray:
    """Decisions E321 / E327: (B,) int, each row's bout (1, 2 ... in time order; 0: no bout - not ``valid`` or no
    contact) by :func:`bout_end_rows`' rule: a bout ends at an invalid row or where the next contact comes more than
    ``max_stride_s`` after it. Rows of one bout are in time order of ``event_s``."""
    ev = np.asarray(event_s, dtype=float)
    ok = np.asarray(valid, dtype=bool) & np.isfinite(ev)
    out = np.zeros(len(ev), int)
    order = np.argsort(np.where(np.isfinite(ev), ev, np.inf), kind="stable")
    order = order[np.isfinite(ev[order])]
    k, last = 0, None
    for i in order.tolist():
        if not ok[i]:
            last = None
            continue
        if last is None or ev[i] - ev[last] > max_stride_s + 1e-9:
            k += 1
        out[i], last = k, i
    return out


def support_measures(a: dict, b: dict, max_stride_s: float = MAX_STRIDE_S) -> dict:
    """Decision E327: the two feet's support measures from their :meth:`StrideGait.strides` ``a`` (left) and ``b``
    (right): the merged contacts (each foot's rows with a contact and a stride length, in time order) in bouts
    (:func:`bout_ids`); a gait cycle is one foot's contact to its next with exactly one contact of the other foot
    between, in one bout (L262, ``gait``'s ``cycle_table``), its stance, double and single support by
    :func:`~pdrlearn.kernels.gait_values.cycle_support` (L327, L729, L736); a step is a contact after the other
    foot's in one bout, its swing the landing foot's toe-off to its contact (L284). As E321, a cycle or step with a
    bout's first or last contact (L317's half strides) is left out. ``double_support_pct`` (the cycles' mean),
    ``n_support_cycles`` and ``stance_time_s_*`` / ``swing_time_s_*`` (:func:`side_pair`: the sides' means, SI,
    ratio)."""
    ev = np.r_[a["event_s"], b["event_s"]]
    valid = np.isfinite(np.r_[a["stride_length_m"], b["stride_length_m"]])
    tc = np.r_[a["tc_s"], b["tc_s"]]
    side = np.r_[np.zeros(len(a["event_s"]), int), np.ones(len(b["event_s"]), int)]
    bout = bout_ids(ev, valid, max_stride_s)
    keep = np.flatnonzero(bout > 0)
    keep = keep[np.argsort(ev[keep], kind="stable")]
    t, tc, side, bout = ev[keep], tc[keep], side[keep], bout[keep]
    partial = np.zeros(len(t), bool)
    for k in set(bout.tolist()):
        rows = np.flatnonzero(bout == k)
        partial[[rows[0], rows[-1]]] = True  # decision L317 (E321)
    stance: list[list[float]] = [[], []]
    swing: list[list[float]] = [[], []]
    ds = []
    for i in range(1, len(t)):
        if side[i] != side[i - 1] and bout[i] == bout[i - 1] and not (partial[i] or partial[i - 1]):
            if tc[i] < t[i]:  # decision L284: one unit's toe-off to its contact
                swing[side[i]].append(t[i] - tc[i])
        j = i - 2
        if j < 0 or side[j] != side[i] or side[j + 1] == side[i] or bout[j] != bout[i] or partial[i] or partial[j + 1]:
            continue
        st, d, _, _ = cycle_support(t[j], tc[j + 1], t[j + 1], tc[i], t[i])  # decisions L262, L327, L729
        stance[side[i]].append(st)
        ds.append(d)
    out = {"n_support_cycles": int(np.isfinite(ds).sum()) if ds else 0,
           "double_support_pct": mean_finite(ds) if ds else None}
    out.update(side_pair("stance_time_s", *(mean_finite(v) if v else None for v in stance)))
    out.update(side_pair("swing_time_s", *(mean_finite(v) if v else None for v in swing)))
    return out


def gait_summary(left: StrideGait, right: StrideGait | None = None) -> dict:
    """Decision E320: the session summary of one foot (``left``: the only foot, whichever it is) or of two feet of
    one walk: ``{"left": ..., "right": ...}`` (each :meth:`StrideGait.summary`) with ``stride_time_s_left`` /
    ``_right`` / ``_si_pct`` / ``_ratio`` and ``stride_length_m_*`` (the sides' means, Robinson's index,
    :func:`~pdrlearn.kernels.gait_values.side_pair`, as ``gait``'s walk measures; decision E321: the stride lengths
    without each bout's first and last contact of the two feet, :func:`bout_end_rows`) and ``si_withheld``: the reason
    when a side has fewer than L461's minimum (:data:`~pdrlearn.kernels.gait_values.CV_MIN_STRIDES`) stride times,
    the indices and ratios then None."""
    if right is None:
        return left.summary()
    # decision E321: L317's half strides of the two feet's merged contacts, each foot's rows of them
    a, b = left.strides(), right.strides()
    ends = bout_end_rows(np.r_[a["event_s"], b["event_s"]],
                         np.isfinite(np.r_[a["stride_length_m"], b["stride_length_m"]]), left.max_stride_s)
    sides = {"left": left.summary(ends[:len(left)]), "right": right.summary(ends[len(left):])}
    out: dict = dict(sides)
    out.update(side_pair("stride_time_s", sides["left"]["mean_stride_time_s"], sides["right"]["mean_stride_time_s"]))
    out.update(side_pair("stride_length_m", sides["left"]["mean_stride_length_m"],
                         sides["right"]["mean_stride_length_m"]))
    out.update(support_measures(a, b, left.max_stride_s))  # decision E327
    n = min(sides["left"]["n_stride_times"], sides["right"]["n_stride_times"])
    out["si_withheld"] = None
    if n < CV_MIN_STRIDES:  # decision L461: an index of a few strides is noise
        for k in [k for k in out if k.endswith(("_si_pct", "_ratio"))]:
            out[k] = None
        out["si_withheld"] = (f"symmetry indices and ratios withheld: {n} stride times on a side, {CV_MIN_STRIDES} "
                              "needed on each side (decision L461)")
    return out
