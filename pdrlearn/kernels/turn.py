"""Decision L690: a stride's own turn, not wrapped.

The foot's turn over a stride is measured as the twist about the vertical of its attitude change from rest to rest
(decision L30): exact, but only modulo one turn (an angle in (-pi, pi]). A dancer's spin of 180-360 deg inside one
stride then reads as the opposite turn (trial T2 finding F1). The foot's vertical rate integrated over the same
samples counts every turn but drifts by a few degrees within a stride; :func:`unwrapped_turn` keeps the twist's
value on the branch the integral points to. Offline (:class:`pdrlearn.displace.foot.FootDisplacement`), ``track
--streaming`` and the runtime (:func:`pdrlearn.kernels.window.stride_dpsi` / ``stride_headings``) call it.
"""

from __future__ import annotations

import math

import numpy as np

TWO_PI = 2.0 * math.pi


def unwrapped_turn(wrapped, integrated):
    """Decision L690: ``wrapped`` (rad, a twist known modulo 2 pi) plus the whole turns that bring it nearest to
    ``integrated`` (rad, the vertical rate's integral over the same samples). Floats or arrays (broadcast); a NaN
    ``integrated`` leaves ``wrapped`` as it is."""
    if np.ndim(wrapped) == 0 and np.ndim(integrated) == 0:  # the runtime's stride: Python floats (runtime E16)
        w, a = float(wrapped), float(integrated)
        return w if not math.isfinite(a) else w + TWO_PI * round((a - w) / TWO_PI)
    w, a = np.asarray(wrapped, dtype=float), np.asarray(integrated, dtype=float)
    k = np.where(np.isfinite(a), np.round((a - w) / TWO_PI), 0.0)
    return w + TWO_PI * k


def integrated_yaw(t: np.ndarray, rate_z: np.ndarray) -> float:
    """Decision L690: the trapezoidal integral (rad) of the levelled vertical rate ``rate_z`` (rad/s) over the
    samples ``t`` (s); 0.0 with fewer than two samples."""
    if len(t) < 2:
        return 0.0
    r = np.asarray(rate_z, dtype=float)
    return 0.5 * float((r[1:] + r[:-1]).dot(np.diff(np.asarray(t, dtype=float))))


def unwrapped_twists(twist: np.ndarray) -> np.ndarray:
    """Decision L690 (offline): ``twist`` (B, L) each stride sample's twist about the vertical relative to the stride's
    first sample (rad, wrapped), unwrapped along the stride: the last column is the stride's yaw integrated over its
    samples (padded samples repeat the last attitude, so the last column is the last sample's)."""
    return np.unwrap(np.asarray(twist, dtype=float), axis=1)


__all__ = ["unwrapped_turn", "integrated_yaw", "unwrapped_twists"]
