"""The waist compass's direction-dependent heading error, fitted against the foot's relative heading (decision L770).

An uncalibrated horizontal hard-iron offset ``b`` turns a compass heading by about asin(|b| / H) sin(psi - phi): a
sinusoid of the walking direction psi (decision L707). The fused heading (L17) follows the compass over +-60 s, so on
a walk out and back the two legs carry opposite errors and the loop does not close (trial s50t1 F3).
:func:`direction_sinusoid` fits that sinusoid from the walk itself, jointly with a line in time for the foot's own
drift, in heading space (no magnetometer model). numpy only.
"""

from __future__ import annotations

import numpy as np


def direction_sinusoid(relative, absolute, clock, keep=None, *, min_strides: int = 8, max_resultant: float = 0.5,
                       with_residual: bool = False) -> tuple:
    """Decision L770: per stride the sinusoid ``a cos(psi) + b sin(psi)`` (rad) of the absolute (compass) heading
    ``absolute`` = psi, fitted by least squares together with an offset and a line in ``clock`` (s, sorted; L471's
    walking clock: the foot's drift, as L266's line) to the difference ``absolute - relative`` of the ``keep``
    strides (None = all; L589's straight ones), unwrapped along the walk; and its amplitude hypot(a, b) (rad).
    Gates as L84's (``min_strides`` 8, ``max_resultant`` 0.5 of the kept psi): a walk that turns too little or has
    too few strides returns zeros and None (the sinusoid is not observable). ``with_residual`` (decision L785): a third
    value, the SD (rad) of the regression's residual over the kept strides (None when the gates refuse): how much of
    the difference the offset, the drift line and the sinusoid leave unexplained."""
    relative, absolute, clock = (np.asarray(v, dtype=float) for v in (relative, absolute, clock))
    n = len(relative)
    kept = np.ones(n, bool) if keep is None else np.asarray(keep, bool).copy()
    kept &= np.isfinite(relative) & np.isfinite(absolute) & np.isfinite(clock)
    psi = absolute[kept]
    if kept.sum() < min_strides or np.hypot(np.mean(np.cos(psi)), np.mean(np.sin(psi))) > max_resultant:
        return (np.zeros(n), None, None) if with_residual else (np.zeros(n), None)
    d = np.unwrap(absolute[kept] - relative[kept])  # consecutive strides differ by the compass error's change
    t = clock[kept]
    X = np.column_stack([np.ones(len(t)), (t - t.mean()) / max(float(np.ptp(t)), 1.0), np.cos(psi), np.sin(psi)])
    coef = np.linalg.lstsq(X, d, rcond=None)[0]
    a, b = coef[2:]
    out = a * np.cos(absolute) + b * np.sin(absolute), float(np.hypot(a, b))
    return (*out, float(np.std(d - X @ coef))) if with_residual else out
