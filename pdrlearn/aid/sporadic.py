"""Sporadic absolute fixes with heading stretching (seed 004, Colombo et al. 2014), step-triggered.

The planar position EKF (seed 004 eqs. 16-23) is driven by PDR steps; an external infrastructure is
queried every ``period_s`` (T_p) only while the walker moves (eq. 19), or, with ``period_s=None``, every
fix of the stream is used at the step it falls in (sporadic fixes: map matching at doors, beacons;
decision D14); each fix is used at most once (D15). Between two adjustments the
estimated path is linearly stretched onto the fixes (eqs. 24-26) and the stretched yaw (eq. 28) is fed
back to the heading of the following steps. The per-sample version of the same EKF, with the attitude
EKF and the hybrid-automaton velocity, is :class:`pdrlearn.aid.colombo.ColomboTracker`.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.aid._base import ParamsMixin, stretched_trajectory
from pdrlearn.aid._kernels import P_P0_M2, Q_C_M2, FixConfig, StepFixState, fix_at_step, fixes_in_step  # noqa: F401
from pdrlearn.aid.fixes import sigma_from_accuracy
from pdrlearn.aid.gnss import check_steps
from pdrlearn.errors import DataError

_D = FixConfig()  # the defaults (decision D19: one set, shared with the live trackers)


class SporadicFixFusion(ParamsMixin):
    """Position EKF with fixes every T_p seconds while moving, trajectory stretching and yaw feedback.

    Parameters (keyword-only)
    ----------
    period_s : T_p, the infrastructure query period (s); seed 004 tests 1-16 s. ``None``: no query policy,
        every fix is used at the step whose interval holds it (moved to the step's end, D14), the latest
        when one step interval holds several.
    moving_gap_s : the walker counts as moving at a query instant when two steps are at most this far
        apart (s) around it (the step-level form of the guard sigma_a > sigma_a_min of seed 004 eq. 19).
    query_tolerance_s : the fix closest to the query instant must be at most this far from it (s).
    sigma_length_rel, sigma_length_m, sigma_heading_rad : per-step process noise (see
        :class:`~pdrlearn.aid.gnss.GnssPdrFusion`).
    stretch : output the stretched trajectory between adjustments (seed 004 eq. 24).
    yaw_feedback : ``"chord"`` (default, decision D24: the rotation from the segment's predicted chord to its
        stretched one, fix to fix, with variance (2 sigma_fix^2 + the segment's process noise) / chord^2),
        ``"last"`` (the stretched yaw of the last step, seed 004 eq. 28 with j = 0: a pivot stride or a step
        walking back against the segment kicks it, D24), ``"mean"`` (length-weighted mean correction over the
        segment) or ``None``.
    scale_feedback : also feed back the step-length scale implied by the stretched speeds (eq. 27),
        length-weighted over the segment (an extension: the paper feeds back only the yaw).
    heading_drift_rad : standard deviation (rad) of the heading-offset random walk per step.
    initial_sigma_m : start standard deviation (m); default sqrt(P_p(0)) of seed 004.
    fix_sigma_m : per-axis fix standard deviation (m); ``None`` = from each fix's ``accuracy_m``.
    innovation_gate : decision D31: reject a fix whose normalised innovation squared exceeds the chi-square 0.997
        quantile (2 degrees of freedom; never two fixes in a row); ``rejected_`` lists them.
    stretch_to : decision D32: ``"fix"`` (seed 004 eq. 26: the stretched path passes through every fix) or
        ``"posterior"`` (it ends each segment at the filter's updated estimate, as far toward the fix as its
        accuracy allows).
    """

    def __init__(
        self,
        *,
        period_s: float | None = 8.0,
        moving_gap_s: float = 1.5,
        query_tolerance_s: float = 0.5,
        sigma_length_rel: float = _D.sigma_length_rel,
        sigma_length_m: float = _D.sigma_length_m,
        sigma_heading_rad: float = _D.sigma_heading_rad,
        stretch: bool = True,
        yaw_feedback: str | None = _D.yaw_feedback,
        scale_feedback: bool = False,
        heading_drift_rad: float = _D.heading_drift_rad,
        initial_sigma_m: float = _D.initial_sigma_m,
        fix_sigma_m: float | None = None,
        innovation_gate: bool = _D.innovation_gate,
        stretch_to: str = _D.stretch_to,
    ):
        self.period_s = period_s
        self.moving_gap_s = moving_gap_s
        self.query_tolerance_s = query_tolerance_s
        self.sigma_length_rel = sigma_length_rel
        self.sigma_length_m = sigma_length_m
        self.sigma_heading_rad = sigma_heading_rad
        self.stretch = stretch
        self.yaw_feedback = yaw_feedback
        self.scale_feedback = scale_feedback
        self.heading_drift_rad = heading_drift_rad
        self.initial_sigma_m = initial_sigma_m
        self.fix_sigma_m = fix_sigma_m
        self.innovation_gate = innovation_gate
        self.stretch_to = stretch_to

    def run(
        self,
        steps: pd.DataFrame,
        fixes: pd.DataFrame | None,
        *,
        start_xy=(0.0, 0.0),
        t_start: float | None = None,
    ) -> SporadicFixFusion:
        """Fuse steps with a fix stream (``t``, ``x``, ``y``, ``accuracy_m``); returns ``self``.

        Results: ``trajectory_`` (``t``, ``x``, ``y`` = stretched where two adjustments bracket the step,
        else real-time; ``x_rt``, ``y_rt`` real-time EKF; ``x_pdr``, ``y_pdr``; ``fix_used``),
        ``stats_`` (counts, below), ``heading_offset_rad_``.

        ``stats_``: ``fixes_used`` (adjustments made, one fix each), ``fixes_unused`` (fixes of the stream
        never used) split into ``fixes_outside_track`` (before the first step's interval or after the last
        step), ``fixes_not_queried`` (no T_p query instant within ``query_tolerance_s``; T_p mode only) and
        ``fixes_superseded`` (a later fix in the same step interval; ``period_s=None`` only);
        ``queries`` / ``fixes_missing`` / ``stops_skipped`` (T_p mode: query instants while moving, those
        without an unused fix within ``query_tolerance_s``, those skipped while standing), ``yaw_corrections``,
        ``queries_per_min``.
        """
        if self.period_s is not None and not self.period_s > 0:
            raise DataError(f"SporadicFixFusion: period_s (T_p) must be > 0 s, got {self.period_s}")
        if self.yaw_feedback not in ("last", "mean", "chord", None):
            raise DataError(f"SporadicFixFusion: yaw_feedback '{self.yaw_feedback}' unknown; use chord, last, mean "
                            "or None")
        st = check_steps(steps)
        fx = (
            pd.DataFrame(columns=["t", "x", "y", "accuracy_m"], dtype=float)
            if fixes is None
            else fixes.sort_values("t", kind="stable").reset_index(drop=True)
        )
        ft, fxy = fx["t"].to_numpy(float), fx[["x", "y"]].to_numpy(float)
        fsig = (
            np.full(len(fx), self.fix_sigma_m)
            if self.fix_sigma_m is not None
            else sigma_from_accuracy(fx["accuracy_m"].to_numpy(float))
        )
        t0 = float(st["start_s"].iloc[0]) if t_start is None and len(st) else float(t_start or 0.0)
        s = StepFixState(self, start_xy, self.initial_sigma_m, t0)  # the one step-wise EKF (decision D19)
        n = len(st)
        out = np.zeros((n + 1, 6))  # x, y (stretched), x_rt, y_rt, x_pdr, y_pdr
        out[0] = [s.x[0], s.x[1], s.x[0], s.x[1], s.raw[0], s.raw[1]]
        used = np.zeros(n + 1, bool)
        counts = dict(queries=0, fixes_used=0, fixes_missing=0, yaw_corrections=0, stops_skipped=0)
        fix_done = np.zeros(len(ft), bool)  # D15: a fix is one measurement, used (or passed over) once
        applied = np.zeros(len(ft), bool)
        superseded = 0
        self.rejected_ = []  # decision D31: (t, x, y, distance m, per-axis sigma m) of each fix the gate rejected
        for k in range(n):
            t_k, prev_t = float(st.at[k, "end_s"]), s.prev_t
            x_prev = s.predict(float(st.at[k, "length_m"]), float(st.at[k, "heading_rad"]), k + 1)
            out[k + 1, 2:4] = s.x
            out[k + 1, 4:6] = s.raw
            c = None
            if self.period_s is None:  # D14: every fix in (prev_t, t_k], the latest one, at the step's end
                inside = fixes_in_step(ft, prev_t, t_k, k == 0)
                if len(inside):
                    c = int(inside[-1])
                    superseded += len(inside) - 1
                    fix_done[inside] = True
                    t_from = max(prev_t, float(st.at[k, "start_s"]))
                    z = fix_at_step(fxy[c], ft[c], t_k, t_from, s.x - x_prev)
            # query instant i*T_p inside (prev_t, t_k] while moving (seed 004 eq. 19)
            elif np.floor(t_k / self.period_s) * self.period_s > prev_t:
                moving = t_k - prev_t <= self.moving_gap_s
                if not moving:
                    counts["stops_skipped"] += 1
                else:
                    counts["queries"] += 1
                    j = int(np.searchsorted(ft, t_k))
                    best = [c for c in (j - 1, j) if 0 <= c < len(ft) and not fix_done[c]
                            and abs(ft[c] - t_k) <= self.query_tolerance_s]
                    if not best:
                        counts["fixes_missing"] += 1
                    else:
                        c = min(best, key=lambda c: abs(ft[c] - t_k))
                        fix_done[c] = True
                        z = fxy[c]
            if c is not None and s.gate(z, float(fsig[c])) is not None:  # decision D31
                self.rejected_.append((float(ft[c]), float(fxy[c][0]), float(fxy[c][1]),
                                       float(np.hypot(*(z - s.x))), float(fsig[c])))
                c = None
            if c is not None:
                rows, pos = s.correct(z, float(fsig[c]), k + 1)
                if self.stretch:
                    out[rows, 0:2] = pos
                out[k + 1, 2:4] = s.x
                used[k + 1] = True
                counts["fixes_used"] += 1
                applied[c] = True
            s.prev_t = t_k
        counts["yaw_corrections"] = s.yaw_corrections
        anchor_row, offset = s.anchor_row, s.offset
        # rows after the last adjustment (or all rows without stretching) keep the real-time estimate
        tail = np.ones(n + 1, bool)
        if self.stretch:
            tail[: anchor_row + 1] = False
            tail[0] = True
        t = np.r_[t0, st["end_s"].to_numpy(float)]
        self.trajectory_ = stretched_trajectory(t, out, used, keep_causal=tail,
                                                extra={"x_pdr": out[:, 4], "y_pdr": out[:, 5]})
        dur = max(t[-1] - t0, 1e-9)
        counts["queries_per_min"] = counts["queries"] / dur * 60.0
        unused = ~applied
        outside = unused & ((ft < t0) | (ft > t[-1]) | ((ft == t0) & (self.period_s is not None)))
        counts["fixes_unused"] = int(unused.sum())
        counts["fixes_outside_track"] = int(outside.sum())
        counts["fixes_superseded"] = superseded
        counts["fixes_rejected"] = len(self.rejected_)  # decision D31
        counts["fixes_not_queried"] = int(np.sum(unused & ~outside)) - superseded - len(self.rejected_)
        self.stats_ = counts
        self.heading_offset_rad_ = offset
        return self
