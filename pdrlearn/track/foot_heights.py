"""Decisions L436 / L437: the two feet of one walk climbed the same stairs, so their tracked height changes must
agree; one line when they differ by more than their own per-stride height error explains.

Numpy / pandas only; :func:`pdrlearn.track.bilateral.pair_sessions` (``pdrlearn gait LEFT RIGHT``) calls it.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pdrlearn.kernels.distance import LEVEL_DZ_M

#: decision L437: the limits of agreement of two measurements of one quantity are the mean difference +-1.96 SD of
#: the differences (Bland & Altman 1986, Lancet 1(8476):307-310): 95 % of two correct feet's totals agree within it
AGREEMENT_Z = 1.96
#: decision L437: a direction is compared when each foot has at least this many climbing strides (a robust SD of
#: fewer is not a spread)
MIN_CLIMB_STRIDES = 3
#: scale of the median absolute deviation to the SD of a normal distribution
MAD_TO_SD = 1.4826


def _climbs(dz: np.ndarray, sign: float) -> np.ndarray:
    x = sign * dz[np.isfinite(dz)]
    return x[x > 0]


def height_agreement(left: pd.DataFrame, right: pd.DataFrame) -> dict:
    """Decision L437: per direction (``up``, ``down``) the two feet's summed height change (m, > 0), their climbing
    strides' counts and medians, the per-stride SD (the median absolute deviation of each foot's climbing strides
    from its own median, pooled, x 1.4826: a biased foot does not widen it) and the bound: 1.96 SD x sqrt(n_left +
    n_right) (the SD of the difference of two sums of independent per-stride errors), at least L39's 0.10 m (a foot
    track levels a stride under it, so either foot may drop one). A direction with under
    :data:`MIN_CLIMB_STRIDES` climbing strides on either foot is left out."""
    out = {}
    for name, sign in (("up", 1.0), ("down", -1.0)):
        x = [_climbs(s["dz_m"].to_numpy(float) if "dz_m" in s else np.zeros(0), sign) for s in (left, right)]
        if min(len(v) for v in x) < MIN_CLIMB_STRIDES:
            continue
        med = [float(np.median(v)) for v in x]
        sd = MAD_TO_SD * float(np.median(np.abs(np.concatenate([v - m for v, m in zip(x, med, strict=True)]))))
        bound = max(LEVEL_DZ_M, AGREEMENT_Z * sd * math.sqrt(len(x[0]) + len(x[1])))
        out[name] = {"total_m": [float(v.sum()) for v in x], "n": [len(v) for v in x], "median_m": med,
                     "sd_m": sd, "bound_m": bound}
    return out


def height_warning(left: pd.DataFrame, right: pd.DataFrame) -> str | None:
    """Decision L436: one line when the two feet's ascent or descent differ by more than :func:`height_agreement`'s
    bound, naming both totals, the bound and each foot's median stride height; None otherwise."""
    parts = []
    for name, a in height_agreement(left, right).items():
        (tl, tr), diff = a["total_m"], abs(a["total_m"][0] - a["total_m"][1])
        if diff > a["bound_m"]:
            word = "ascent" if name == "up" else "descent"
            parts.append(f"{word} left {tl:.2f} m / right {tr:.2f} m differ by {diff:.2f} m, over the "
                         f"{a['bound_m']:.2f} m their per-stride height spread explains (SD {a['sd_m']:.3f} m over "
                         f"{a['n'][0]} + {a['n'][1]} climbing strides; median stride {a['median_m'][0]:.3f} / "
                         f"{a['median_m'][1]:.3f} m)")
    if not parts:
        return None
    return ("bilateral gait: the two feet climbed the same stairs, but their tracked heights disagree: "
            + "; ".join(parts) + " (decisions L436, L437): one foot's stride heights are biased (its mounting, its "
            "integration) or "
            "strides were missed, so neither total is a measured height; compare a known flight (rise x stairs)")
