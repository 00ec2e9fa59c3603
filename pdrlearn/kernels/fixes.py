"""Numerical kernels of the aiding filters (numpy only; imported as ``pdrlearn.aid._kernels`` too).

The functions hold no state. :class:`StepFixState` is the step-triggered position EKF of
:class:`pdrlearn.aid.sporadic.SporadicFixFusion` (seed 004 eqs. 16-28) one step at a time, and
:class:`LiveFixes` feeds it fixes pushed as they arrive and the steps as a live tracker reports them, with
decision D14's rule (every fix at the step whose interval holds it): ``SporadicFixFusion.run`` and the live trackers
of :mod:`pdrlearn.runtime` run this one implementation (decision D19).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def wrap_angle(a):
    """Wrap angle(s) to (-pi, pi] (rad)."""
    return (np.asarray(a) + np.pi) % (2.0 * np.pi) - np.pi


def step_increment(length_m: float, heading_rad: float) -> np.ndarray:
    """East/north displacement (m) of one step: seed 001 eq. 24 (heading 0 = east, counter-clockwise)."""
    return np.array([length_m * np.cos(heading_rad), length_m * np.sin(heading_rad)])


def fix_at_step(z: np.ndarray, t_fix: float, t_step: float, t_from: float, increment: np.ndarray) -> np.ndarray:
    """A fix taken at ``t_fix`` moved to the end of the step ``(t_from, t_step]``: plus the fraction of the step's
    displacement walked after the fix (seed 001 Sec. 2.2.6, "associate the last valid GNSS data with the last
    step"); a fix before ``t_from`` gets the whole step."""
    frac = (t_step - t_fix) / max(t_step - t_from, 1e-9)
    return np.asarray(z, float) + min(max(frac, 0.0), 1.0) * np.asarray(increment, float)


def kf_predict(
    x: np.ndarray,
    P: np.ndarray,
    length_m: float,
    heading_rad: float,
    *,
    sigma_length_m: float,
    sigma_heading_rad: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Step-triggered prediction of the east/north position (seed 001 eq. 24; seed 004 eq. 17).

    The process noise maps the step-length and heading variances through the Jacobian
    G = d(l [cos h, sin h]) / d(l, h):  P+ = P + G diag(s_l^2, s_h^2) G^T.
    """
    c, s = np.cos(heading_rad), np.sin(heading_rad)
    G = np.array([[c, -length_m * s], [s, length_m * c]])
    Q = G @ np.diag([sigma_length_m**2, sigma_heading_rad**2]) @ G.T
    return x + np.array([length_m * c, length_m * s]), P + Q


def kf_update(
    x: np.ndarray,
    P: np.ndarray,
    z: np.ndarray,
    sigma_m: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Size-varying measurement update with m position fixes (seed 001 Sec. 2.2.6; seed 004 eqs. 20-22).

    Parameters
    ----------
    x, P : state (2,) (m) and covariance (2, 2) (m^2)
    z : (m, 2) fixes east/north (m); m = 0 leaves the state unchanged (open loop, seed 004 eq. 23)
    sigma_m : (m,) per-axis standard deviation of each fix (m)

    Returns
    -------
    x, P, innovation (2m,), normalised innovation squared (chi-square with 2m degrees of freedom)
    """
    z = np.asarray(z, float).reshape(-1, 2)
    m = z.shape[0]
    if m == 0:
        return x, P, np.zeros(0), 0.0
    H = np.tile(np.eye(2), (m, 1))
    R = np.diag(np.repeat(np.asarray(sigma_m, float).reshape(-1) ** 2, 2))
    nu = z.reshape(-1) - H @ x
    S = H @ P @ H.T + R
    K = np.linalg.solve(S, H @ P).T  # P H^T S^-1 (S symmetric)
    x_new = x + K @ nu
    IKH = np.eye(2) - K @ H
    P_new = IKH @ P @ IKH.T + K @ R @ K.T  # Joseph form, stays symmetric positive definite
    nis = float(nu @ np.linalg.solve(S, nu))
    return x_new, P_new, nu, nis


def stretch_segment(
    increments: np.ndarray,
    l_start: np.ndarray,
    l_end: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Linear trajectory stretching between two adjustments (seed 004 eqs. 24-28).

    Parameters
    ----------
    increments : (m, 2) per-sample (or per-step) displacements T_c s(theta) v of the estimated path (m)
    l_start, l_end : offsets fix - estimate at the first and the last adjustment (m), l(k-m) and l(k)

    Returns
    -------
    stretched increments (m, 2), their speeds scale factor sqrt(1 + f + h) (eq. 27) and headings (rad,
    eq. 28). Each stretched increment is the original plus (l(k) - l(k-m)) / m (eq. 26).
    """
    d = np.asarray(increments, float).reshape(-1, 2)
    m = d.shape[0]
    if m == 0:
        return d, np.zeros(0), np.zeros(0)
    dl = np.asarray(l_end, float) - np.asarray(l_start, float)
    step = np.hypot(d[:, 0], d[:, 1])  # T_c v (m)
    theta = np.arctan2(d[:, 1], d[:, 0])
    with np.errstate(divide="ignore", invalid="ignore"):
        f = (dl @ dl) / (m * step) ** 2  # eq. 27, f(k, j, m)
        h = 2.0 * (np.cos(theta) * dl[0] + np.sin(theta) * dl[1]) / (m * step)  # eq. 27, h(k, j, m)
        scale = np.sqrt(np.maximum(1.0 + f + h, 0.0))
    scale = np.where(step > 0, scale, np.nan)
    phi = step * np.sin(theta) + dl[1] / m  # eq. 28, Phi
    psi = step * np.cos(theta) + dl[0] / m  # eq. 28, Psi
    return d + dl / m, scale, np.arctan2(phi, psi)


def scalar_kf(estimate: float, var: float, obs: float, obs_var: float, q: float) -> tuple[float, float]:
    """One random-walk predict (+ ``q``) and update of a scalar estimate; ``var = inf`` adopts ``obs``."""
    if not np.isfinite(var):
        return float(obs), float(obs_var)
    var = var + q
    gain = var / (var + obs_var)
    return float(estimate + gain * (obs - estimate)), float((1.0 - gain) * var)


#: Horizontal 68 % radius -> per-axis standard deviation: for a circular Gaussian, P(r <= 1.51 s) = 0.68
#: (``pdrlearn.aid.fixes.RADIUS68_PER_SIGMA``)
RADIUS68_PER_SIGMA = math.sqrt(-2.0 * math.log(1.0 - 0.68))
#: Second EKF defaults (seed 004 Sec. V): P_p(0) = diag(0.1, 0.1) m^2, Q_c(0) = diag(0.0025, 0.0025) m^2.
P_P0_M2 = 0.1
Q_C_M2 = 0.0025


#: decision D31: a fix whose normalised innovation squared (chi-square with 2 degrees of freedom: the innovation of
#: seed 004 eqs. 20-22 with S = P + R) exceeds this is rejected, P(chi2_2 > g) = 0.003, the 3-sigma tail (seeds 001
#: and 004 gate no fix: project choice)
GATE_CHI2_2DOF = -2.0 * math.log(0.003)


def innovation_nis(x: np.ndarray, P: np.ndarray, z: np.ndarray, sigma_m: float) -> float:
    """Decision D31: the normalised innovation squared of the fix ``z`` (m, per-axis SD ``sigma_m``) against the
    state ``x``, ``P``: nu^T (P + sigma^2 I)^-1 nu, nu = z - x (seed 004 eqs. 20-22's innovation and its covariance)."""
    nu = np.asarray(z, float) - np.asarray(x, float)
    S = np.asarray(P, float) + np.eye(2) * float(sigma_m) ** 2
    return float(nu @ np.linalg.solve(S, nu))


#: decisions D18, E212: the hint for a fix time outside the walk, offline (`track --fixes`) and live (`add_fix`)
FIX_TIME_HINT = "a fix's t is in seconds on the session clock (the session files' timestamps are milliseconds)"
#: decision E212: ``add_fix`` refuses a fix time more than this (s) after the newest pushed sample (a fix in ms)
FIX_AHEAD_MAX_S = 60.0


def rejected_phrase(rejected) -> str:
    """Decision D31: the rejected fixes ``(t, x, y, distance, sigma)`` named, for the offline and the live line."""
    return ", ".join(f"t {t:.1f} s at ({x:.1f}, {y:.1f}) {d:.1f} m from the estimate, accuracy "
                     f"{sg * RADIUS68_PER_SIGMA:.1f} m" for t, x, y, d, sg in rejected)


@dataclass(frozen=True)
class FixConfig:
    """The step EKF's settings, with :class:`pdrlearn.aid.sporadic.SporadicFixFusion`'s defaults (that class takes
    its defaults from here): per-step process noise (step length relative + absolute, m; heading, rad), the yaw /
    scale feedback, the heading-offset random walk (rad per step) and the start standard deviation (m)."""

    sigma_length_rel: float = 0.05
    sigma_length_m: float = 0.02
    sigma_heading_rad: float = math.radians(5.0)
    yaw_feedback: str | None = "chord"  # decision D24 (seed 004 eq. 28, j = 0: "last")
    scale_feedback: bool = False
    heading_drift_rad: float = math.radians(0.3)
    initial_sigma_m: float = math.sqrt(P_P0_M2)
    innovation_gate: bool = False  # decision D31: reject a fix beyond GATE_CHI2_2DOF
    stretch_to: str = "fix"  # decision D32: the stretched path ends at the "fix" (seed 004 eq. 26) or the "posterior"


def sigma_from_accuracy(accuracy_m) -> np.ndarray:
    """Per-axis standard deviation (m) of a fix whose reported 68 % horizontal radius is ``accuracy_m``."""
    return np.asarray(accuracy_m, dtype=float) / RADIUS68_PER_SIGMA


def initial_fix_sigma(*, start_known: bool, xy_fixes: bool, first_accuracy_m: float | None = None) -> float:
    """The step EKF's start standard deviation (m) in ``pdrlearn track --fixes`` and the live trackers (decision
    D19, amended): 1 m when the start is known (a given start, or fixes in the track's own x, y frame around its
    origin); else the first fix's per-axis sigma (the walk is assumed to start at the first fix)."""
    if start_known or xy_fixes:
        return 1.0
    return float(sigma_from_accuracy(first_accuracy_m))


def fixes_in_step(ft: np.ndarray, prev_t: float, t_k: float, first: bool) -> np.ndarray:
    """Decision D14: indices of the fixes (times ``ft``, s) in the step interval ``(prev_t, t_k]``; the first step
    also takes a fix at its very start (``prev_t`` itself, e.g. a start fix at t = 0). The step uses the last."""
    ft = np.asarray(ft, dtype=float)
    return np.flatnonzero(((ft > prev_t) | (first & (ft >= prev_t))) & (ft <= t_k))


def _geometry_var(obs: np.ndarray, sigma: float) -> float:
    """The variance (rad^2) a fix's per-axis SD ``sigma`` adds to the heading of a stretched segment whose sum is
    ``obs`` (two fixes at its ends; its length under 0.5 m counted as 0.5 m)."""
    return 2.0 * sigma**2 / max(float(np.hypot(*obs)), 0.5) ** 2


class StepFixState:
    """The state of the step-triggered position EKF with trajectory stretching and yaw / scale feedback (seed 004
    eqs. 16-28), advanced one step at a time: :meth:`predict` for each step, :meth:`correct` with a fix. ``cfg``:
    an object with :class:`~pdrlearn.aid.sporadic.SporadicFixFusion`'s parameters (``sigma_length_rel``,
    ``sigma_length_m``, ``sigma_heading_rad``, ``yaw_feedback``, ``scale_feedback``, ``heading_drift_rad``).
    ``x`` (2,) is the causal (real-time) estimate, ``raw`` the PDR position.

    ``segment=False`` (decision E121, the live trackers): the steps since the last adjustment are not kept, only
    their count, sum and last increment and heading -- what the "last" yaw feedback reads (eqs. 26 and 28 for the last
    increment) and the "chord" one (decision D24: the segment's sum before and after stretching) -- so the state stays
    a few numbers however many steps pass without a fix; :meth:`correct` then returns no stretched rows. It needs
    ``yaw_feedback`` "chord", "last" or None and no ``scale_feedback`` ("mean" and the scale read every step)."""

    def __init__(self, cfg, start_xy, initial_sigma_m: float, t0: float, segment: bool = True):
        if not segment and (cfg.yaw_feedback not in ("chord", "last", None) or cfg.scale_feedback):
            raise ValueError("StepFixState(segment=False) needs yaw_feedback 'chord', 'last' or None and no "
                             "scale_feedback")
        self.segment = segment
        self.cfg = cfg
        self.x = np.asarray(start_xy, float).copy()
        self.P = np.eye(2) * initial_sigma_m**2
        self.raw = self.x.copy()
        self.offset, self.p_off = 0.0, 0.0  # heading offset fed back from the stretched yaw, and its variance
        self.log_scale, self.p_scale = 0.0, 0.0  # log step-length scale fed back from the stretched speeds
        self.seg_inc: list[np.ndarray] = []
        self.seg_rows: list[int] = []
        self.seg_head: list[float] = []
        self._seg_n, self._seg_sum, self._seg_last, self._seg_last_head = 0, np.zeros(2), np.zeros(2), 0.0  # E121
        self.anchor_xy, self.anchor_row, self.l_start = self.x.copy(), 0, np.zeros(2)
        self.P_anchor = self.P.copy()
        self.prev_t = float(t0)
        self.yaw_corrections = 0
        self.rejected_last = False  # decision D31: the last fix the gate saw was rejected

    def predict(self, length: float, heading: float, row: int) -> np.ndarray:
        """One step (``length`` m, ``heading`` rad ENU) as output row ``row``: the PDR position moves, the EKF
        predicts with the fed-back heading offset and scale (seed 004 eqs. 16-17). Returns the estimate before."""
        c = self.cfg
        self.raw = self.raw + length * np.array([np.cos(heading), np.sin(heading)])
        hc = heading + self.offset
        length = length * np.exp(self.log_scale)
        x_prev = self.x
        self.x, self.P = kf_predict(self.x, self.P, length, hc,
                                    sigma_length_m=c.sigma_length_rel * abs(length) + c.sigma_length_m,
                                    sigma_heading_rad=c.sigma_heading_rad)  # seed 004 eqs. 16-17
        self.p_off += c.heading_drift_rad**2
        self.p_scale += (0.1 * c.heading_drift_rad) ** 2  # scale random walk, 1/10 of the heading's (rad ~ rel.)
        if self.segment:
            self.seg_inc.append(self.x - x_prev)
            self.seg_rows.append(row)
            self.seg_head.append(hc)
        else:  # decision E121: what the "last" yaw feedback reads of the segment
            self._seg_last = self.x - x_prev
            self._seg_sum = self._seg_sum + self._seg_last
            self._seg_n += 1
            self._seg_last_head = hc
        return x_prev

    def gate(self, z: np.ndarray, sigma: float) -> float | None:
        """Decision D31: the fix's normalised innovation squared when the gate (``cfg.innovation_gate``) rejects it,
        else None. A fix right after a rejected one is never rejected: two fixes in a row beyond the gate say the
        filter, not the fixes, is wrong (it would otherwise reject every later fix)."""
        if not getattr(self.cfg, "innovation_gate", False):
            return None
        nis = innovation_nis(self.x, self.P, z, sigma)
        if nis > GATE_CHI2_2DOF and not self.rejected_last:
            self.rejected_last = True
            return nis
        self.rejected_last = False
        return None

    def correct(self, z: np.ndarray, sigma: float, row: int) -> tuple[list[int], np.ndarray]:
        """Adjust at output row ``row`` with the fix ``z`` (m, per-axis SD ``sigma``): the segment since the last
        adjustment is stretched onto it (seed 004 eqs. 24-26), its yaw (eq. 28) and, optionally, its speed scale
        (eq. 27) fed back, then the EKF update (eqs. 20-22). Returns the segment's rows and their stretched
        positions (m, (n_rows, 2))."""
        c = self.cfg
        l_end = z - self.x  # seed 004: l(k) = L_b(bar) - L_b(hat)
        if not self.segment:
            return self._correct_last(z, sigma, row, l_end)
        inc = np.asarray(self.seg_inc)
        stretched, _, theta_bar = stretch_segment(inc, self.l_start, l_end)
        rows = list(self.seg_rows)
        pos = self.anchor_xy + self.l_start + np.cumsum(stretched, axis=0)
        if getattr(c, "stretch_to", "fix") == "posterior" and len(inc):
            # decision D32: stretched from posterior to posterior (seed 004 eq. 26 with l = the EKF's correction,
            # K nu of eqs. 20-22, instead of the whole fix - estimate): a fix moves the path as far as its accuracy
            # against the filter's covariance allows
            x_post = kf_update(self.x, self.P, z, np.array([sigma]))[0]
            pos = self.anchor_xy + np.cumsum(stretch_segment(inc, np.zeros(2), x_post - self.x)[0], axis=0)
        if c.yaw_feedback is not None and len(inc):
            lens = np.hypot(inc[:, 0], inc[:, 1])
            dth = wrap_angle(theta_bar - np.asarray(self.seg_head))
            est, obs = np.sum(inc, axis=0), np.sum(stretched, axis=0)
            if c.yaw_feedback == "mean":
                w = lens / max(lens.sum(), 1e-9)
                innov = float(np.arctan2(np.sum(w * np.sin(dth)), np.sum(w * np.cos(dth))))
                self._feed_yaw(innov, c.sigma_heading_rad**2 / len(inc) + _geometry_var(obs, sigma))
            else:
                self._feed_yaw(*self._innovation(est, obs, float(dth[-1]), sigma))
        if c.scale_feedback and len(inc):
            lens = np.hypot(inc[:, 0], inc[:, 1])
            ratio = np.hypot(stretched[:, 0], stretched[:, 1]).sum() / max(lens.sum(), 1e-9)
            if ratio > 0:
                r = c.sigma_length_rel**2 / len(inc) + 2.0 * sigma**2 / max(lens.sum(), 0.5) ** 2
                gain = self.p_scale / (self.p_scale + r) if self.p_scale > 0 else 0.0
                self.log_scale = float(np.clip(self.log_scale + gain * np.log(ratio), -0.7, 0.7))
                self.p_scale *= 1.0 - gain
        self._update(z, sigma, row)
        return rows, pos

    def _innovation(self, est: np.ndarray, obs: np.ndarray, last_dth: float, sigma: float) -> tuple[float, float]:
        """The yaw innovation and its variance of the "chord" (decision D24: the segment's rotation from its predicted
        sum ``est`` onto its stretched sum ``obs``, eq. 26's ends) or "last" feedback (seed 004 eq. 28: the last
        step's stretched heading less its own, ``last_dth``) -- one computation for :meth:`correct` and its compact
        form (E121)."""
        if self.cfg.yaw_feedback == "chord":
            innov = float(wrap_angle(np.arctan2(obs[1], obs[0]) - np.arctan2(est[1], est[0])))
            q_seg = 0.5 * float(np.trace(self.P - self.P_anchor))
            return innov, (2.0 * sigma**2 + q_seg) / max(float(np.hypot(*obs)), 0.5) ** 2
        return last_dth, self.cfg.sigma_heading_rad**2 + _geometry_var(obs, sigma)

    def _feed_yaw(self, innov: float, r: float) -> None:
        """The heading offset's scalar Kalman update with the innovation ``innov`` (rad) of variance ``r``."""
        gain = self.p_off / (self.p_off + r)
        self.offset = float(wrap_angle(self.offset + gain * innov))
        self.p_off *= 1.0 - gain
        self.yaw_corrections += 1

    def _correct_last(self, z: np.ndarray, sigma: float, row: int, l_end: np.ndarray) -> tuple[list[int], np.ndarray]:
        """:meth:`correct` without the segment's steps (decision E121): the "last" yaw feedback from the segment's
        count m, sum and last increment -- the stretched last increment is d_m + (l(k) - l(k-m)) / m (seed 004 eq.
        26), its heading eq. 28's, and the stretched segment's chord |sum d + l(k) - l(k-m)| -- as :meth:`correct`
        computes them from every step (equal to rounding)."""
        c, m = self.cfg, self._seg_n
        if c.yaw_feedback is not None and m:
            dl = np.asarray(l_end, float) - self.l_start
            last = self._seg_last + dl / m  # seed 004 eq. 26
            theta_bar = float(np.arctan2(last[1], last[0]))  # seed 004 eq. 28
            obs = self._seg_sum + dl  # the stretched segment's sum (eq. 26 adds l(k) - l(k-m) over its steps)
            self._feed_yaw(*self._innovation(self._seg_sum, obs, float(wrap_angle(theta_bar - self._seg_last_head)),
                                             sigma))
        self._update(z, sigma, row)
        return [], np.zeros((0, 2))

    def _update(self, z: np.ndarray, sigma: float, row: int) -> None:
        """The EKF update with the fix (seed 004 eqs. 20-22); the next segment starts here."""
        self.x, self.P, _, _ = kf_update(self.x, self.P, z, np.array([sigma]))  # seed 004 eqs. 20-22
        self.anchor_xy, self.anchor_row, self.l_start = self.x.copy(), row, z - self.x
        self.P_anchor = self.P.copy()
        self.seg_inc, self.seg_rows, self.seg_head = [], [], []
        self._seg_n, self._seg_sum = 0, np.zeros(2)


def start_fixes(fix_t, session_start_s: float, first_step_s: float) -> np.ndarray:
    """Decision D50: indices of the fixes (times ``fix_t``, session s) from the session start up to the track's first
    stride (``first_step_s``, the trajectory's first row), which D14 / D38 meant as start fixes: the last of them
    gives the track's start position (a foot track starts at its first stride, after the standstill, so a start fix
    at t = 0 had been "outside the track's steps"). Shared by ``aid_track`` and the live trackers' :class:`LiveFixes`
    (the live session start: the first pushed sample)."""
    ft = np.asarray(fix_t, dtype=float)
    return np.flatnonzero((ft >= session_start_s) & (ft <= first_step_s))


class LiveFixes:
    """Position fixes for a live tracker (decisions D19-D21): :meth:`add` a fix as it arrives, :meth:`step` each
    step the tracker reports. Every fix is used at the step whose interval ``(previous step end, step end]`` holds
    it, the latest when several do, moved to the step's end (D14, :func:`fix_at_step`), once (D15): what
    ``SporadicFixFusion(period_s=None)`` (``pdrlearn track --fixes``) does with the same steps, whose real-time
    estimate (``x_rt``, ``y_rt``) the steps then carry. Counters as ``track``'s (D17): :meth:`stats`."""

    def __init__(self, cfg, *, start_xy=(0.0, 0.0), initial_sigma_m: float | None = None):
        self.cfg = cfg
        #: the track's start time (s): offline ``aid_track``'s ``t_start`` (the trajectory's first row); None: the
        #: first step's start (a fix before it is outside the track, or a start fix: D50)
        self.t_start: float | None = None
        #: decision D50: the session start (s), the first pushed sample; None: no start fixes
        self.t_first: float | None = None
        self._start = np.asarray(start_xy, float)
        self._sigma0 = cfg.initial_sigma_m if initial_sigma_m is None else float(initial_sigma_m)
        self.state: StepFixState | None = None
        self._k = 0
        self._pending: list[tuple[float, np.ndarray, float]] = []  # (t, (x, y), sigma), in the order pushed
        self.read = self.used = self.superseded = self.late = 0
        self.rejected: list[tuple[float, float, float, float, float]] = []  # decision D31, as SporadicFixFusion's

    def add(self, t: float, xy: np.ndarray, sigma: float) -> None:
        self.read += 1
        if self.state is not None and t <= self.state.prev_t:  # D20: its step was reported already
            self.late += 1
            return
        self._pending.append((float(t), np.asarray(xy, float), float(sigma)))

    def step(self, start_s: float, end_s: float, length: float, heading: float) -> tuple[np.ndarray, bool]:
        """The fused (causal) position after one reported step and whether a fix was used at it."""
        if self.state is None:
            t0 = start_s if self.t_start is None else min(self.t_start, start_s)
            # decision E121: the live estimate reads no stretched rows, so the segment is kept as a few sums
            compact = self.cfg.yaw_feedback in ("chord", "last", None) and not self.cfg.scale_feedback
            self.state = StepFixState(self.cfg, self._start, self._sigma0, t0, segment=not compact)
            # decision D50 (as aid_track): the fixes from the first pushed sample up to the track's start are start
            # fixes, the last of them the start position with its own sigma, the earlier ones superseded
            ft = np.array([f[0] for f in self._pending])
            pre = [] if self.t_first is None or not len(ft) else start_fixes(ft, self.t_first, t0)
            if len(pre):
                order = pre[np.argsort(ft[pre], kind="stable")]  # as aid_track's table, sorted by t
                _, xy0, sigma0 = self._pending[int(order[-1])]
                self.state = StepFixState(self.cfg, xy0, sigma0, t0, segment=not compact)
                self.used += 1
                self.superseded += len(pre) - 1
                drop = set(pre.tolist())
                self._pending = [f for i, f in enumerate(self._pending) if i not in drop]
            outside = [f for f in self._pending if f[0] < t0]  # before the track: never used (D17)
            self._pending = [f for f in self._pending if f[0] >= t0]
            self.outside_before = len(outside)
        s = self.state
        self._k += 1
        x_prev = s.predict(length, heading, self._k)
        ft = np.array([f[0] for f in self._pending])
        order = np.argsort(ft, kind="stable")  # as the offline fix table, sorted by t
        inside = order[fixes_in_step(ft[order], s.prev_t, end_s, self._k == 1)]
        used = False
        if len(inside):
            c = int(inside[-1])
            self.superseded += len(inside) - 1
            t_from = max(s.prev_t, start_s)
            z = fix_at_step(self._pending[c][1], self._pending[c][0], end_s, t_from, s.x - x_prev)
            if s.gate(z, self._pending[c][2]) is not None:  # decision D31
                f = self._pending[c]
                self.rejected.append((f[0], float(f[1][0]), float(f[1][1]), float(np.hypot(*(z - s.x))), f[2]))
            else:
                s.correct(z, self._pending[c][2], self._k)
                self.used += 1
                used = True
            drop = set(inside.tolist())
            self._pending = [f for i, f in enumerate(self._pending) if i not in drop]
        s.prev_t = float(end_s)
        return s.x.copy(), used

    def stats(self) -> dict:
        """``fixes_read``, ``fixes_used``, ``fixes_unused`` (= read - used) split into ``fixes_superseded`` (a later
        fix in the same step), ``fixes_outside_track`` (before the first step, or after the last so far: still
        pending), ``fixes_late`` (pushed after the step its time falls in was reported, D20) and ``fixes_rejected``
        (the innovation gate's, D31)."""
        outside = getattr(self, "outside_before", 0) + len(self._pending)
        return {"fixes_read": self.read, "fixes_used": self.used, "fixes_unused": self.read - self.used,
                "fixes_superseded": self.superseded, "fixes_outside_track": outside, "fixes_late": self.late,
                "fixes_rejected": len(self.rejected)}


def stretch_between_fixes(causal: np.ndarray, prior: np.ndarray, used: np.ndarray, *,
                          start_anchor: bool) -> np.ndarray:
    """Decision D36: the offline path of a step-triggered fix filter from its causal one.

    ``causal`` (n, 2): the filter's position after each row (posterior where a fix was used); ``prior`` (n, 2): its
    prediction at each row before the update; ``used`` (n,): rows where a fix was used. Between two used rows a < b
    the jump at b (posterior - prior) is spread linearly over the segment's steps (seed 004 eq. 26: each increment
    plus (l(k) - l(k-m)) / m, with l = 0 after the posterior at a), so the path reaches b without a jump. Before the
    first used row: with ``start_anchor`` (the start is known) the same spread from row 0; without it the whole
    correction is applied to every earlier row (decision D38: the path before the first fix is the PDR's shape
    projected back from that fix, not drawn forward from the first fix's position). After the last used row the
    causal path continues from that posterior (no jump)."""
    out = np.array(causal, float, copy=True)
    prior = np.asarray(prior, float)
    prev = 0 if start_anchor else None
    for b in np.flatnonzero(np.asarray(used, bool)):
        jump = out[b] - prior[b]  # out[b] is still causal[b]: rows > prev are untouched so far
        if prev is None:
            out[:b] += jump
        elif b > prev:
            m = b - prev
            out[prev + 1 : b] += (np.arange(1, m) / m)[:, None] * jump
        prev = b
    return out


def length_scale_windows(fix_xy: np.ndarray, fix_t: np.ndarray, pdr_xy: np.ndarray, pdr_path_m: np.ndarray, *,
                         window_m: float = 200.0, max_gap_s: float = 5.0, straightness: float = 0.95
                         ) -> tuple[np.ndarray, np.ndarray]:
    """Decision D39: the windows :func:`fit_length_scale` fits on, as (the fixes' chord, the steps' summed length) per
    window (m, two arrays of the windows' count); the parameters are :func:`fit_length_scale`'s."""
    fix_xy, pdr_xy = np.asarray(fix_xy, float).reshape(-1, 2), np.asarray(pdr_xy, float).reshape(-1, 2)
    fix_t, path = np.asarray(fix_t, float), np.asarray(pdr_path_m, float)
    chords, lengths = [], []
    i0 = 0
    for j in range(1, len(fix_t)):
        if fix_t[j] - fix_t[j - 1] > max_gap_s:  # an outage: the next window starts after it
            i0 = j
            continue
        walked = path[j] - path[i0]
        if walked < window_m:
            continue
        if float(np.hypot(*(pdr_xy[j] - pdr_xy[i0]))) >= straightness * walked:
            chords.append(float(np.hypot(*(fix_xy[j] - fix_xy[i0]))))
            lengths.append(float(walked))
        i0 = j
    return np.asarray(chords, float), np.asarray(lengths, float)


def fit_length_scale(fix_xy: np.ndarray, fix_t: np.ndarray, pdr_xy: np.ndarray, pdr_path_m: np.ndarray, *,
                     window_m: float = 200.0, max_gap_s: float = 5.0, straightness: float = 0.95
                     ) -> tuple[float, float, int]:
    """Decision D39: the step-length scale that GNSS measures, on straight stretches of good fixes.

    ``fix_xy``/``fix_t``: the used fixes in order; ``pdr_xy``/``pdr_path_m``: the uncompensated PDR position and its
    path length (m, the sum of the step lengths) at each of those fixes' steps. Consecutive windows of at least
    ``window_m`` of PDR path, with no two fixes more than ``max_gap_s`` apart inside and a PDR chord at least
    ``straightness`` x its path (a straight walk, where the walked distance is the fixes' chord), each give the fixes'
    chord and the steps' summed length (:func:`length_scale_windows`); the scale is the sum of the chords over the sum
    of the lengths (a window's fix noise, ~ sqrt(2) x 3.4 m over 200 m, averages out over the windows). The PDR's
    chord is not the denominator: a lower-back track's heading sways from step to step, which shortens its chord, not
    its distance (D39's first candidate, +2.2 to +3.4 % on waist-pll tracks). Returns (scale or nan, PDR path covered
    by the windows (m), number of windows)."""
    return scale_from_windows(*length_scale_windows(fix_xy, fix_t, pdr_xy, pdr_path_m, window_m=window_m,
                                                    max_gap_s=max_gap_s, straightness=straightness))


def scale_from_windows(chords: np.ndarray, lengths: np.ndarray) -> tuple[float, float, int]:
    """Decision D39: (scale = sum(chords) / sum(lengths) or nan, the PDR path covered (m), number of windows) of
    :func:`length_scale_windows`' windows."""
    den = float(np.sum(lengths))
    return (float(np.sum(chords)) / den if den > 0 else float("nan")), den, int(len(lengths))


def length_scale_se(chords: np.ndarray, lengths: np.ndarray) -> float:
    """Decision D45: the standard error of :func:`fit_length_scale`'s scale R = sum(chords) / sum(lengths) from its
    windows' own scatter (the ratio estimator's: sqrt(n / (n - 1) x sum((c_i - R l_i)^2)) / sum(l_i), which for
    windows of equal length is the per-window ratios' standard deviation / sqrt(n)); nan with fewer than 2 windows."""
    c, length = np.asarray(chords, float), np.asarray(lengths, float)
    n, den = len(c), float(length.sum())
    if n < 2 or den <= 0:
        return float("nan")
    r = float(c.sum()) / den
    return float(np.sqrt(n / (n - 1) * np.sum((c - r * length) ** 2)) / den)
