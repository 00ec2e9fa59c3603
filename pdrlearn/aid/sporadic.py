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
from pdrlearn.aid._kernels import fix_at_step, kf_predict, kf_update, stretch_segment, wrap_angle
from pdrlearn.aid.fixes import sigma_from_accuracy
from pdrlearn.aid.gnss import check_steps
from pdrlearn.errors import DataError

#: Second EKF defaults (seed 004 Sec. V): P_p(0) = diag(0.1, 0.1) m^2, Q_c(0) = diag(0.0025, 0.0025) m^2.
P_P0_M2 = 0.1
Q_C_M2 = 0.0025


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
    yaw_feedback : ``"last"`` (the stretched yaw of the last step, seed 004 eq. 28 with j = 0),
        ``"mean"`` (length-weighted mean correction over the segment) or ``None``.
    scale_feedback : also feed back the step-length scale implied by the stretched speeds (eq. 27),
        length-weighted over the segment (an extension: the paper feeds back only the yaw).
    heading_drift_rad : standard deviation (rad) of the heading-offset random walk per step.
    initial_sigma_m : start standard deviation (m); default sqrt(P_p(0)) of seed 004.
    fix_sigma_m : per-axis fix standard deviation (m); ``None`` = from each fix's ``accuracy_m``.
    """

    def __init__(
        self,
        *,
        period_s: float | None = 8.0,
        moving_gap_s: float = 1.5,
        query_tolerance_s: float = 0.5,
        sigma_length_rel: float = 0.05,
        sigma_length_m: float = 0.02,
        sigma_heading_rad: float = np.radians(5.0),
        stretch: bool = True,
        yaw_feedback: str | None = "last",
        scale_feedback: bool = False,
        heading_drift_rad: float = np.radians(0.3),
        initial_sigma_m: float = float(np.sqrt(P_P0_M2)),
        fix_sigma_m: float | None = None,
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
        if self.yaw_feedback not in ("last", "mean", None):
            raise DataError(f"SporadicFixFusion: yaw_feedback '{self.yaw_feedback}' unknown; use last, mean or None")
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
        x = np.asarray(start_xy, float).copy()
        P = np.eye(2) * self.initial_sigma_m**2
        raw = x.copy()
        offset, p_off = 0.0, 0.0  # heading offset fed back from the stretched yaw, and its variance
        log_scale, p_scale = 0.0, 0.0  # log step-length scale fed back from the stretched speeds
        n = len(st)
        out = np.zeros((n + 1, 6))  # x, y (stretched), x_rt, y_rt, x_pdr, y_pdr
        out[0] = [x[0], x[1], x[0], x[1], raw[0], raw[1]]
        used = np.zeros(n + 1, bool)
        seg_inc: list[np.ndarray] = []
        seg_rows: list[int] = []
        seg_head: list[float] = []
        anchor_xy, anchor_row, l_start = x.copy(), 0, np.zeros(2)
        counts = dict(queries=0, fixes_used=0, fixes_missing=0, yaw_corrections=0, stops_skipped=0)
        fix_done = np.zeros(len(ft), bool)  # D15: a fix is one measurement, used (or passed over) once
        applied = np.zeros(len(ft), bool)
        superseded = 0
        prev_t = t0
        for k in range(n):
            t_k = float(st.at[k, "end_s"])
            length, heading = float(st.at[k, "length_m"]), float(st.at[k, "heading_rad"])
            raw = raw + length * np.array([np.cos(heading), np.sin(heading)])
            hc = heading + offset
            length = length * np.exp(log_scale)
            x_prev = x
            x, P = kf_predict(
                x,
                P,
                length,
                hc,
                sigma_length_m=self.sigma_length_rel * abs(length) + self.sigma_length_m,
                sigma_heading_rad=self.sigma_heading_rad,
            )  # seed 004 eqs. 16-17
            p_off += self.heading_drift_rad**2
            p_scale += (0.1 * self.heading_drift_rad) ** 2  # scale random walk, 1/10 of the heading's (rad ~ rel.)
            seg_inc.append(x - x_prev)
            seg_rows.append(k + 1)
            seg_head.append(hc)
            out[k + 1, 2:4] = x
            out[k + 1, 4:6] = raw
            c = None
            if self.period_s is None:  # D14: every fix in (prev_t, t_k], the latest one, at the step's end
                # the first step also takes a fix at its very start (t0, e.g. a start fix at t = 0)
                inside = np.flatnonzero(((ft > prev_t) | ((k == 0) & (ft >= prev_t))) & (ft <= t_k))
                if len(inside):
                    c = int(inside[-1])
                    superseded += len(inside) - 1
                    fix_done[inside] = True
                    t_from = max(prev_t, float(st.at[k, "start_s"]))
                    z = fix_at_step(fxy[c], ft[c], t_k, t_from, x - x_prev)
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
            if c is not None:
                l_end = z - x  # seed 004: l(k) = L_b(bar) - L_b(hat)
                inc = np.asarray(seg_inc)
                stretched, _, theta_bar = stretch_segment(inc, l_start, l_end)
                if self.stretch:
                    out[seg_rows, 0:2] = anchor_xy + l_start + np.cumsum(stretched, axis=0)
                if self.yaw_feedback is not None and len(inc):
                    lens = np.hypot(inc[:, 0], inc[:, 1])
                    dth = wrap_angle(theta_bar - np.asarray(seg_head))
                    chord = float(np.hypot(*np.sum(stretched, axis=0)))
                    geo = 2.0 * fsig[c] ** 2 / max(chord, 0.5) ** 2
                    if self.yaw_feedback == "last":
                        innov, r = float(dth[-1]), self.sigma_heading_rad**2 + geo
                    else:
                        w = lens / max(lens.sum(), 1e-9)
                        innov = float(np.arctan2(np.sum(w * np.sin(dth)), np.sum(w * np.cos(dth))))
                        r = self.sigma_heading_rad**2 / len(inc) + geo
                    gain = p_off / (p_off + r)
                    offset = float(wrap_angle(offset + gain * innov))
                    p_off *= 1.0 - gain
                    counts["yaw_corrections"] += 1
                if self.scale_feedback and len(inc):
                    lens = np.hypot(inc[:, 0], inc[:, 1])
                    ratio = np.hypot(stretched[:, 0], stretched[:, 1]).sum() / max(lens.sum(), 1e-9)
                    if ratio > 0:
                        r = self.sigma_length_rel**2 / len(inc) + 2.0 * fsig[c] ** 2 / max(lens.sum(), 0.5) ** 2
                        gain = p_scale / (p_scale + r) if p_scale > 0 else 0.0
                        log_scale = float(np.clip(log_scale + gain * np.log(ratio), -0.7, 0.7))
                        p_scale *= 1.0 - gain
                x, P, _, _ = kf_update(x, P, z, fsig[c : c + 1])  # seed 004 eqs. 20-22
                out[k + 1, 2:4] = x
                used[k + 1] = True
                counts["fixes_used"] += 1
                applied[c] = True
                anchor_xy, anchor_row, l_start = x.copy(), k + 1, z - x
                seg_inc, seg_rows, seg_head = [], [], []
            prev_t = t_k
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
        counts["fixes_not_queried"] = int(np.sum(unused & ~outside)) - superseded
        self.stats_ = counts
        self.heading_offset_rad_ = offset
        return self
