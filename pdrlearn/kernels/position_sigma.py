"""Horizontal position uncertainty of a dead-reckoned track, propagated stride by stride (decision L128).

Pure numpy. The model linearises the position update ``p_k = p_{k-1} + L_k (cos psi_k, sin psi_k)`` (the
stride-and-heading PDR update of thesis ch.7) about the track: a heading error ``dpsi`` moves stride ``k`` across
itself by ``L_k dpsi``, a length error ``dL`` along itself. Four zero-mean, mutually independent sources:

- ``displacement_rel``: an error proportional to the displacement ``D_k`` from the start, of the same size along
  it (a stride-length scale error common to the track) and across it (a heading offset constant over the track:
  start direction, compass or mounting misalignment): ``P += displacement_rel^2 |D_k|^2 I``;
- ``heading_walk_rad``: the heading is a random walk, ``eta_k = eta_{k-1} + w_k``, step sd per stride (the
  gyroscope's noise integrated over one stride, after ZUPT/ZARU);
- ``bias_rps``: a residual heading rate ``b`` (rad/s, constant over the track: gyroscope bias about the vertical
  left after ZUPT/ZARU); the heading turns by ``b t``, also while the walker stands;
- ``point_m``: a point error that does not accumulate (sd per axis): the tracked point (the foot at rest, one
  stride's end) is not the walker's position at that time, and one stride's own placement error.
- ``path_rel`` (decision L220; 0 unless a regime sets it): an error proportional to the distance walked ``s_k``
  (the summed |stride length|), sd per axis ``path_rel s_k``: a heading error that depends on the place and the
  direction (a compass' indoor field disturbance, a hard-iron residual) repeats on every pass of a route that
  revisits its corridors, out and back, instead of averaging out or cancelling on a closed loop.
- ``path_diffusion_m2`` (decision L237; 0 unless a regime sets it): a random walk of the position per metre walked,
  per-axis variance ``path_diffusion_m2 s_k``: a compass error that depends on the place, integrated along the path
  (independent from place to place, so it does not cancel on a loop and grows like the square root of the distance).
- ``extent_heading_rad`` (decision L239; 0 unless a regime sets it): a heading error that does not grow with the walk
  (the compass's place- and direction-dependent error as a heading aligned to it over a window passes it on), sd
  ``extent_heading_rad``, acting on the route's extent so far ``R_k = max_{j<=k} |D_j|``: per-axis sd
  ``extent_heading_rad R_k``. It turns the track about its start by up to that error at the farthest point and,
  unlike ``displacement_rel``, does not return to 0 when a loop closes (the error going out is not the error coming
  back), nor grow with the laps of a route that stays within its extent.
- ``extent_return_rad`` (decision L241; 0 unless a regime sets it): the part of that extent term a heading error
  held the same along the walk would not give: per-axis variance ``extent_return_rad^2 (R_k^2 - |D_k|^2)``. A heading
  error that stays the same turns the track about its start (``displacement_rel``'s shape, on ``|D_k|``); only where
  the track has come back from its farthest point (``|D_k| < R_k``) can the error going out differ from the error
  coming back. 0 on a walk that only goes out from its start; ``extent_return_rad^2 R_k^2`` where a loop closes.
- ``held_var_m2`` (decision E127): per stride, an isotropic per-axis variance added at that stride and carried by
  every later one: a row whose position was held across a sensor gap misses the displacement walked in it.

Each gives a closed form of cumulative sums (O(N)). The 1-sigma radius is ``sqrt(trace P)`` (distance root mean
square): for a 2-D Gaussian a circle of twice that radius holds 95.4 % (round) to 98.2 % (a thin ellipse) of
the positions.
"""

from __future__ import annotations

import numpy as np


def position_covariance(length_m: np.ndarray, heading_rad: np.ndarray, t_end_s: np.ndarray, t0_s: float, *,
                        displacement_rel: float, heading_walk_rad: float, bias_rps: float,
                        point_m: float, path_rel: float = 0.0, path_diffusion_m2: float = 0.0,
                        extent_heading_rad: float = 0.0, extent_return_rad: float = 0.0,
                        held_var_m2: np.ndarray | None = None, heading_offset_rad: float = 0.0) -> np.ndarray:
    """Covariance (m^2) of the horizontal position after each stride, shape (N, 2, 2).

    Parameters
    ----------
    length_m : signed horizontal length of each stride (m; negative = placed against ``heading_rad``).
    heading_rad : ENU heading of each stride (rad, 0 = east, counter-clockwise).
    t_end_s : end time of each stride (s); ``t0_s`` the track's start time (s).
    displacement_rel : sd per axis of the error proportional to the displacement from the start (fraction).
    heading_walk_rad : sd of the heading random walk's step per stride (rad).
    bias_rps : sd of the residual heading rate (rad/s).
    point_m : sd per axis of the non-accumulating point error (m).
    path_rel : sd per axis of the error proportional to the distance walked (fraction; decision L220).
    path_diffusion_m2 : per-axis variance per metre walked (m^2/m; decision L237).
    extent_heading_rad : sd of the bounded heading error acting on the route's extent (rad; decision L239).
    extent_return_rad : sd of the bounded heading error on the part of the extent the track has come back from (rad;
        decision L241).
    held_var_m2 : per-stride per-axis variance added at the stride and kept after it (m^2; decision E127).
    heading_offset_rad : sd of a heading error held the same from the start (rad; decision E331): it moves the
        position by delta C_k, so P_k += delta^2 C_k C_k^T.

    The whole track through one fresh :class:`RadiusState` (decision E355: the live tracker carries one).
    """
    params = {"displacement_rel": displacement_rel, "heading_walk_rad": heading_walk_rad, "bias_rps": bias_rps,
              "point_m": point_m, "path_rel": path_rel, "path_diffusion_m2": path_diffusion_m2,
              "extent_heading_rad": extent_heading_rad, "extent_return_rad": extent_return_rad,
              "heading_offset_rad": heading_offset_rad}
    return RadiusState(t0_s, params).covariance(length_m, heading_rad, t_end_s, held_var_m2)


def _carried(carry, x: np.ndarray, op=np.add) -> np.ndarray:
    """Decision E355: ``op.accumulate`` of ``x`` along its first axis continued from ``carry`` (the value after the
    strides before): the same additions (or maxima), in the same order, as one accumulation over the whole track."""
    x = np.asarray(x, float)
    return op.accumulate(np.concatenate([np.asarray(carry, float)[None], x]), axis=0)[1:]


class RadiusState:
    """Decision E355: the state of L128's covariance, the never-decreasing radius and L333's cap after the strides
    given so far (cumulative sums, running maxima, the stride count), so a live tracker adds a stride in O(1)
    (:meth:`extend` with one stride) and gets, within floating point, what :func:`stride_radius` gives over the whole
    track so far; :func:`position_covariance`, :func:`stride_radius`, :func:`reach_bound`, :func:`missed_walk` and
    :func:`rest_clock` are one fresh state over the whole track (one mechanism). ``t0``: the track's start (s);
    ``params``: a model of :data:`SIGMA_PARAMS` (missing terms 0); ``rest_s``: L297's rest for :meth:`clock`."""

    #: L128's terms (:func:`position_covariance`'s keywords); another key is refused, as the keyword call refused it
    terms = ("displacement_rel", "heading_walk_rad", "bias_rps", "point_m", "path_rel", "path_diffusion_m2",
             "extent_heading_rad", "extent_return_rad", "heading_offset_rad")

    def __init__(self, t0: float, params: dict[str, float], *, rest_s: float | None = None):
        unknown = sorted(set(params) - set(self.terms))
        if unknown:
            raise TypeError(f"RadiusState: unknown position-sigma term(s) {', '.join(unknown)}")
        self.t0 = float(t0)
        self.params = {k: float(v) for k, v in params.items()}
        self.rest_s = rest_s
        self.n = 0  # strides so far
        self.C = np.zeros(2)  # L128: sum of L_k n_k (the displacement turned by 90 deg)
        self.B = np.zeros(2)  # and of L_k n_k t_k (the bias term)
        self.S1 = np.zeros(2)  # the random walk's sums of C_{i-1} and C_{i-1} C_{i-1}^T
        self.S2 = np.zeros((2, 2))
        self.walked = 0.0  # the summed |L| (L220, L237)
        self.extent = 0.0  # the farthest |D| so far (L239, L241)
        self.held = 0.0  # the summed held variance (E127)
        self.r_max = 0.0  # the radius so far (never decreasing)
        self.reach_walked = 0.0  # L333: the summed |L| and missed walk, the displacement D, the longest |L|
        self.reach_missed = 0.0
        self.D = np.zeros(2)
        self.longest = 0.0
        self.known_max: float | None = None  # the longest known |stride| (missed_walk)
        self.clock_prev: float | None = None  # L297: the last stride's end and the rest time taken out so far
        self.clock_skip = 0.0

    def covariance(self, length, heading, t_end, held_var_m2=None) -> np.ndarray:
        """L128's covariance (m^2, (N, 2, 2)) after each of the strides given, following those given before."""
        L = np.asarray(length, float)
        psi = np.asarray(heading, float)
        t = np.asarray(t_end, float) - self.t0
        if not (L.shape == psi.shape == t.shape) or L.ndim != 1:
            raise ValueError("length_m, heading_rad and t_end_s must be 1-D arrays of one length")
        q = self.params.get
        n = np.stack([-np.sin(psi), np.cos(psi)], axis=1) * L[:, None]  # d(stride displacement)/d(heading) = L_k n_k

        def outer(a: np.ndarray, b: np.ndarray) -> np.ndarray:
            return a[:, :, None] * b[:, None, :]

        C = _carried(self.C, n)  # the displacement from the start turned by 90 deg: |C_k| = |D_k|
        eye = np.eye(2)[None]
        P = (q("displacement_rel", 0.0) ** 2 * np.sum(C ** 2, axis=1))[:, None, None] * eye
        P = P + q("point_m", 0.0) ** 2 * eye
        B = _carried(self.B, n * t[:, None])  # bias: dpsi_j = b t_j, dp_k = b sum_j L_j n_j t_j
        P = P + q("bias_rps", 0.0) ** 2 * outer(B, B)
        walked = _carried(self.walked, np.abs(L))
        if q("path_rel", 0.0):  # decision L220: the distance walked, not the displacement from the start
            P = P + (q("path_rel") * walked)[:, None, None] ** 2 * eye
        if q("path_diffusion_m2", 0.0):  # decision L237: variance per metre walked
            P = P + (q("path_diffusion_m2") * walked)[:, None, None] * eye
        dist = np.hypot(C[:, 0], C[:, 1])  # |C_k| = |D_k|, the displacement from the start
        extent = _carried(self.extent, dist, np.maximum)  # the farthest the track has been from its start
        if q("extent_heading_rad", 0.0):  # decision L239
            P = P + (q("extent_heading_rad") * extent)[:, None, None] ** 2 * eye
        if q("extent_return_rad", 0.0):  # decision L241: what a heading error held the same (on |D_k|) would not give
            P = P + (q("extent_return_rad") ** 2 * np.maximum(extent ** 2 - dist ** 2, 0.0))[:, None, None] * eye
        if q("heading_offset_rad", 0.0):  # decision E331: one heading error from the first stride on, along C_k
            P = P + q("heading_offset_rad") ** 2 * outer(C, C)
        held = None
        if held_var_m2 is not None:  # decision E127: a held position's missed displacement, kept by later strides
            h = np.asarray(held_var_m2, float)
            if h.shape != L.shape:
                raise ValueError("held_var_m2 must have one value per stride")
            held = _carried(self.held, h)
            P = P + held[:, None, None] * eye
        # random walk: dp_k = sum_{i<=k} w_i (C_k - C_{i-1}) (C_0 = 0), so its covariance is
        # sum_i (C_k - C_{i-1})(C_k - C_{i-1})^T = k C_k C_k^T - C_k S1_k^T - S1_k C_k^T + S2_k, with the cumulative
        # sums S1_k = sum_{i<=k} C_{i-1}, S2_k = sum_{i<=k} C_{i-1} C_{i-1}^T
        C_prev = np.vstack([self.C[None], C[:-1]])
        S1 = _carried(self.S1, C_prev)
        S2 = _carried(self.S2, outer(C_prev, C_prev))
        k = np.arange(self.n + 1, self.n + len(L) + 1, dtype=float)[:, None, None]
        P = P + q("heading_walk_rad", 0.0) ** 2 * (k * outer(C, C) - outer(C, S1) - outer(S1, C) + S2)
        if len(L):  # the carry: the values after the last stride given
            self.n += len(L)
            self.C, self.B, self.S1, self.S2 = C[-1], B[-1], S1[-1], S2[-1]
            self.walked, self.extent = float(walked[-1]), float(extent[-1])
            if held is not None:
                self.held = float(held[-1])
        return 0.5 * (P + np.swapaxes(P, 1, 2))

    def reach(self, length, heading, missed_m=None) -> np.ndarray:
        """:func:`reach_bound` of the strides given, following those given before."""
        L = np.asarray(length, float)
        psi = np.asarray(heading, float)
        walked = _carried(self.reach_walked, np.abs(L))
        if len(L):
            self.reach_walked = float(walked[-1])
        if missed_m is not None:
            missed = _carried(self.reach_missed, np.asarray(missed_m, float))
            walked = walked + missed
            if len(L):
                self.reach_missed = float(missed[-1])
        D = _carried(self.D, np.stack([L * np.cos(psi), L * np.sin(psi)], axis=1).reshape(-1, 2))
        if not len(L):
            return walked
        longest = _carried(self.longest, np.abs(L), np.maximum)
        self.D, self.longest = D[-1], float(longest[-1])
        return walked + np.hypot(D[:, 0], D[:, 1]) + longest

    def missed(self, length, bad, held_var_m2=None) -> np.ndarray:
        """:func:`missed_walk` of the strides given: a bad stride reads the longest known |stride| of the strides given
        so far and in this call (one call over the whole track: the whole track's, as before E355)."""
        L = np.abs(np.asarray(length, float))
        bad = np.asarray(bad, bool)
        known = L[~bad & np.isfinite(L)]
        if known.size:
            self.known_max = max(float(known.max()), -np.inf if self.known_max is None else self.known_max)
        out = np.where(bad, 2.0 * (self.known_max if self.known_max is not None else 0.0), 0.0)
        return out if held_var_m2 is None else out + np.sqrt(2.0 * np.asarray(held_var_m2, float))

    def clock(self, start, end, rests=None) -> np.ndarray:
        """:func:`rest_clock` of the strides given (``start``, ``end`` s), following those given before: the end
        times less every rest over ``rest_s`` before each (L297; with ``rests`` only those overlapping a span, L306)."""
        start = np.asarray(start, float)
        end = np.asarray(end, float)
        if not len(end):
            return end
        prev = np.concatenate([[self.t0 if self.clock_prev is None else self.clock_prev], end[:-1]])
        gap = start - prev
        long = np.isfinite(gap) & (gap > self.rest_s)
        if rests is not None:  # decision L306: only the rests L296 corrected (and the lead-in: no heading yet)
            spans = np.asarray(rests, float).reshape(-1, 2)
            corrected = np.array([bool(np.any((np.minimum(b, spans[:, 1]) - np.maximum(a, spans[:, 0])) > 0))
                                  for a, b in zip(prev, start, strict=True)], dtype=bool)
            if self.clock_prev is None:
                corrected[0] = True
            long &= corrected
        skip = _carried(self.clock_skip, np.where(long, gap, 0.0))
        self.clock_prev, self.clock_skip = float(end[-1]), float(skip[-1])
        return end - skip

    def extend(self, length, heading, clock, *, raw=None, bad=None, held_var_m2=None) -> tuple[np.ndarray, bool]:
        """:func:`stride_radius` of the strides given, following those given before (decision E355)."""
        length = np.asarray(length, float)
        bad = np.zeros(len(length), bool) if bad is None else np.asarray(bad, bool)
        raw = length if raw is None else raw
        r = sigma_radius(self.covariance(length, heading, clock, held_var_m2))
        r = _carried(self.r_max, np.where(np.isfinite(r), r, 0.0), np.maximum)  # a radius never shrinks without a fix
        if len(r):
            self.r_max = float(r[-1])
        cap = 0.5 * self.reach(length, heading, self.missed(raw, bad, held_var_m2))  # L333: 2 sigma <= the sure radius
        cut = bool(len(r) and r[-1] > cap[-1])
        r = np.minimum(r, cap)
        r[bad] = np.nan
        return r, cut


def sigma_radius(cov: np.ndarray) -> np.ndarray:
    """1-sigma radius ``sqrt(trace P)`` (m) of each 2x2 covariance in ``cov`` (N, 2, 2)."""
    return np.sqrt(np.maximum(cov[:, 0, 0] + cov[:, 1, 1], 0.0))


#: decision L128: parameters per error regime, each the maximum-likelihood fit on simulated users 900-905
#: (``experiments/position_sigma.py fit --variant V``, printed values rounded to 2 significant digits); decision
#: L150: the streamed and foot-only regimes refitted on users 1160-1179, the maximum-likelihood parameters times
#: one coverage scale (95.5 % of the strides, 17/20 finals within 2 sigma on those users)
SIGMA_PARAMS: dict[str, dict[str, float]] = {
    # plasys offline with a waist unit: foot yaw aligned to the waist compass ("fused", L17)
    # (L220: the distance-walked term path_rel = 0.0149 was measured on top of these and not adopted, too large on
    # routes of 3-4 loops: 20/20 finals within 2 sigma against the rule's 16-19; the kernel keeps it, 0 here)
    # (L238: the per-metre compass term path_diffusion_m2 = PLACE_DIFFUSION_M2 was measured and not adopted, too small)
    # (L239/L240: the bounded heading error on the route's extent, extent_heading_rad = EXTENT_HEADING_RAD, measured
    # and not adopted: all its short-route strides within 2 sigma, over the rule's 99.5 %; sigma_params'
    # extent_heading)
    # (L241/L242: that error only on the part of the extent the track has come back from, extent_return_rad =
    # EXTENT_HEADING_RAD, measured and not adopted: 20/25 long-route finals within 2 sigma, under the rule's 90 %;
    # sigma_params' extent_return)
    "plasys-fused": {"displacement_rel": 0.026, "heading_walk_rad": 0.0034, "bias_rps": 0.0, "point_m": 1.5},
    # plasys with the foot's own yaw only (no waist unit, or `--units foot`; L150)
    "plasys-foot": {"displacement_rel": 0.0017, "heading_walk_rad": 0.026, "bias_rps": 9.6e-11, "point_m": 0.044},
    # plasys --streaming without a waist unit (or `--units foot`): the foot's own yaw, streamed. L150's refit
    # (0.0055, 0.030, 2.5e-07, 0.0096) failed its rule (89.5 % of the test strides within 2 sigma, rule 93-98.5 %):
    # L128's plasys-foot constants, as before L150 (uncalibrated, too large)
    "plasys-foot-streaming": {"displacement_rel": 0.0021, "heading_walk_rad": 0.062, "bias_rps": 0.0,
                              "point_m": 0.068},
    # plasys --streaming with a waist unit: the waist gyroscope's heading (L99; L150). Decision E331: its heading was
    # held off the walking direction from the first stride on (users 17870-17883: RMS 0.04674 rad, -2.10 to -3.18
    # deg), a constant offset term; decision E337: after E336 removed that offset's cause (the pelvis' yaw at the
    # stride's end) what remains (users 18400-18403: RMS 0.00723 rad), rounded up; decision E342 (E337's rule amended):
    # kept on the shipped E336 + E338 code (users 18900-18919: mean share within 2 sigma 1.000, worst run 0.994,
    # median sigma / RMS 1.38); a track with E336 off (info["cycle_yaw"] False) takes E331's 0.047 (sigma_params'
    # boundary_offset_rad)
    "plasys-streaming": {"displacement_rel": 0.029, "heading_walk_rad": 0.0070, "bias_rps": 0.00051,
                         "point_m": 5.1e-174, "heading_offset_rad": 0.0073},
    # decision L267: plasys offline after L226's fallback (L182 judged the compass disturbed): the heading is the
    # waist gyroscope's, as the streamed one, so its radius takes the streamed regime's four L150 constants (not
    # fitted on its own) without E331 / E337's heading_offset_rad: that offset was the streamed strides' (the pelvis'
    # yaw at the foot's rest, E336), and this offline track was not measured for it (E331, E342)
    "plasys-gyro-fallback": {"displacement_rel": 0.029, "heading_walk_rad": 0.0070, "bias_rps": 0.00051,
                             "point_m": 5.1e-174},
    # the lower-back pipelines (fitted on waist-pendulum; waist-pll shares them, not fitted)
    "waist": {"displacement_rel": 0.0, "heading_walk_rad": 0.0083, "bias_rps": 0.00085, "point_m": 3.1},
}


def reach_bound(length: np.ndarray, heading: np.ndarray, missed_m: np.ndarray | None = None) -> np.ndarray:
    """Decision L333: per stride, the radius R_k = s_k + |D_k| + l_k (m) about the track's position that holds the
    true position when the track's distance walked s_k is not under the walker's (decision L342: s_k is the track's
    own; a track that under-reads, e.g. a lower back's, can be cut below its error where the walker ended farther
    from the start than s_k + l_k): the walker, starting where the track starts, is at most the distance walked s_k
    (the summed |stride length|) from the start, and the track is |D_k| from it, so |error| <= s_k + |D_k|; l_k, the
    longest |stride| so far, is the margin for the tracked point (a foot at rest) not being the reference point (a
    pelvis between the feet: each within half a stride of the other, at the start and now). ``missed_m``: per stride,
    walk the lengths do not hold, added to s_k (:func:`missed_walk`). Never decreasing (|D_k| shrinks by at most
    |L_k| while s_k grows by it). Pure numpy; NaN-free inputs."""
    return RadiusState(0.0, {}).reach(length, heading, missed_m)


def missed_walk(length: np.ndarray, bad: np.ndarray, held_var_m2: np.ndarray | None) -> np.ndarray:
    """Decision L333: per stride, the walk (m) :func:`reach_bound` adds to the lengths: a held gap (E127) its speed
    x gap (sqrt(2 ``held_var_m2``)); a stride of unknown length or heading (L143, modelled as 0) twice the track's
    longest known |stride| (the walk it may have been, and the track's own step the model left out)."""
    return RadiusState(0.0, {}).missed(length, bad, held_var_m2)


def rest_clock(start: np.ndarray, end: np.ndarray, t0: float, rest_s: float, rests=None) -> np.ndarray:
    """Decisions L297, L306: the numpy core of :func:`pdrlearn.track.position_sigma.bias_clock` - the steps' end times
    ``end`` with every rest longer than ``rest_s`` between a step's end and the next one's ``start`` (before the first:
    from ``t0``) taken out; with ``rests`` only those overlapping one of these (start, end) spans (and the lead-in)."""
    return RadiusState(t0, {}, rest_s=rest_s).clock(start, end, rests)


def stride_radius(length: np.ndarray, heading: np.ndarray, clock: np.ndarray, t0: float, params: dict[str, float],
                  *, raw: np.ndarray | None = None, bad: np.ndarray | None = None,
                  held_var_m2: np.ndarray | None = None) -> tuple[np.ndarray, bool]:
    """The 1-sigma radius (m) after each stride (decision L128) under the model ``params``, never decreasing, and
    never over half :func:`reach_bound` (decision L333), with whether the last stride's radius was cut to it; NaN at
    the strides ``bad`` (L143: their ``length`` / ``heading`` given as 0, ``raw`` the lengths as tracked). ``clock``:
    the bias term's clock (the strides' end times, or :func:`rest_clock`'s). Shared by the offline tracks'
    ``pos_sigma_m`` (:func:`pdrlearn.track.position_sigma.sigma_per_row`) and the live waist tracker's per step
    (decision E352), so the two are equal."""
    return RadiusState(t0, params).extend(length, heading, clock, raw=raw, bad=bad, held_var_m2=held_var_m2)

