"""The gait arithmetic of one foot's strides, numpy only (decision E320): shared by the offline gait tables
(:mod:`pdrlearn.track.gait`, :mod:`pdrlearn.track.clinical`, :mod:`pdrlearn.track.bilateral`) and the lean runtime's
per-stride values (:mod:`pdrlearn.runtime.gait`), so both compute each value by the same function.

- :func:`cadence_speed`: a stride's cadence (steps/min) and speed (m/s) from its length and stride time (L66).
- :func:`median_finite`, :func:`mean_finite`: the median / mean of the finite values (None without one).
- :func:`cv_pct`: L104's coefficient of variation; :data:`CV_MIN_STRIDES` its minimum count (L113).
- :func:`symmetry_index_pct`, :func:`side_pair`: Robinson's symmetry index of two sides' values (L121, L259).

The stride time itself (initial contact to initial contact, L66 / L80) is :func:`pdrlearn.kernels.contact.stride_times`.
"""

from __future__ import annotations

import math

import numpy as np

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
