"""Pure numerical kernels of the aiding filters (no state, no I/O)."""

from __future__ import annotations

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
