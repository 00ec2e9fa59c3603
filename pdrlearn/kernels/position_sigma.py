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
    """
    L = np.asarray(length_m, float)
    psi = np.asarray(heading_rad, float)
    t = np.asarray(t_end_s, float) - float(t0_s)
    if not (L.shape == psi.shape == t.shape) or L.ndim != 1:
        raise ValueError("length_m, heading_rad and t_end_s must be 1-D arrays of one length")
    n = np.stack([-np.sin(psi), np.cos(psi)], axis=1) * L[:, None]  # d(stride displacement)/d(heading) = L_k n_k

    def outer(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return a[:, :, None] * b[:, None, :]

    C = np.cumsum(n, axis=0)  # the displacement from the start turned by 90 deg: |C_k| = |D_k|
    eye = np.eye(2)[None]
    P = (displacement_rel ** 2 * np.sum(C ** 2, axis=1))[:, None, None] * eye + point_m ** 2 * eye
    B = np.cumsum(n * t[:, None], axis=0)  # bias: dpsi_j = b t_j, dp_k = b sum_j L_j n_j t_j
    P = P + bias_rps ** 2 * outer(B, B)
    if path_rel:  # decision L220: the distance walked, not the displacement from the start
        P = P + (path_rel * np.cumsum(np.abs(L)))[:, None, None] ** 2 * eye
    if path_diffusion_m2:  # decision L237: variance per metre walked
        P = P + (path_diffusion_m2 * np.cumsum(np.abs(L)))[:, None, None] * eye
    dist = np.hypot(C[:, 0], C[:, 1])  # |C_k| = |D_k|, the displacement from the start
    extent = np.maximum.accumulate(dist)  # the farthest the track has been from its start
    if extent_heading_rad:  # decision L239
        P = P + (extent_heading_rad * extent)[:, None, None] ** 2 * eye
    if extent_return_rad:  # decision L241: what a heading error held the same (on |D_k|) would not give
        P = P + (extent_return_rad ** 2 * np.maximum(extent ** 2 - dist ** 2, 0.0))[:, None, None] * eye
    if heading_offset_rad:  # decision E331: one heading error from the first stride on, along C_k
        P = P + heading_offset_rad ** 2 * outer(C, C)
    if held_var_m2 is not None:  # decision E127: a held position's missed displacement, kept by later strides
        held = np.asarray(held_var_m2, float)
        if held.shape != L.shape:
            raise ValueError("held_var_m2 must have one value per stride")
        P = P + np.cumsum(held)[:, None, None] * eye
    # random walk: dp_k = sum_{i<=k} w_i (C_k - C_{i-1}) (C_0 = 0), so its covariance is
    # sum_i (C_k - C_{i-1})(C_k - C_{i-1})^T = k C_k C_k^T - C_k S1_k^T - S1_k C_k^T + S2_k, with the cumulative
    # sums S1_k = sum_{i<=k} C_{i-1}, S2_k = sum_{i<=k} C_{i-1} C_{i-1}^T
    C_prev = np.vstack([np.zeros((1, 2)), C[:-1]])
    S1 = np.cumsum(C_prev, axis=0)
    S2 = np.cumsum(outer(C_prev, C_prev), axis=0)
    k = np.arange(1, len(L) + 1, dtype=float)[:, None, None]
    P = P + heading_walk_rad ** 2 * (k * outer(C, C) - outer(C, S1) - outer(S1, C) + S2)
    return 0.5 * (P + np.swapaxes(P, 1, 2))


def sigma_radius(cov: np.ndarray) -> np.ndarray:
    """1-sigma radius ``sqrt(trace P)`` (m) of each 2x2 covariance in ``cov`` (N, 2, 2)."""
    return np.sqrt(np.maximum(cov[:, 0, 0] + cov[:, 1, 1], 0.0))
