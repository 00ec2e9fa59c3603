"""Decision L474 (trial T5 finding 3): strides walked at speeds outside the model's training strides.

A model trained on exercises at one speed classed 42 of 162 strides of a fast mission (median 1.9 m/s) wrongly with
a median confidence 0.73, and C16's feature-range scores did not flag them. ``pdrlearn train``'s distance calibration
tracks the training sessions (``displace.calibration``) and records the 1 % / 99 % quantiles of its strides'
``speed_mps`` (C16's quantiles) as ``speed_range_mps``; a tracked stride more than :data:`SPEED_MARGIN` outside it
gets ``speed_out_of_range`` True in steps.csv and the track one warning line.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L474: the relative margin (10 %) outside the training strides' 1-99 % speed range before a stride is
#: flagged; stated, not fitted (a walk at the training speed has 2 % of its strides outside its own quantiles)
SPEED_MARGIN = 0.10


def training_speed_range(speeds) -> list[float] | None:
    """Decision L474: the (1 %, 99 %) quantiles (C16's ``QUANTILES``) of the finite positive stride speeds (m/s) of
    the training sessions' tracked strides; None with fewer than 10."""
    from pdrlearn.classify.domain import QUANTILES

    v = np.asarray(speeds, float)
    v = v[np.isfinite(v) & (v > 0)]
    if len(v) < 10:
        return None
    lo, hi = np.quantile(v, QUANTILES)
    return [round(float(lo), 4), round(float(hi), 4)]


def model_speed_range(model) -> list[float] | None:
    """The ``speed_range_mps`` a trained model recorded (None: oracle labels, no model, or trained before L474)."""
    summary = getattr(model, "data_summary", None) or {}
    rng = (summary.get("distance_calibration") or {}).get("speed_range_mps")
    return [float(rng[0]), float(rng[1])] if rng is not None and len(rng) == 2 else None


def flag_speeds(table: pd.DataFrame, speed_range, warnings: list[str]) -> dict | None:
    """Decision L474: add ``speed_out_of_range`` to the stride ``table`` (``speed_mps`` more than
    :data:`SPEED_MARGIN` outside ``speed_range``; False where the speed is unknown) and, when any is, one line to
    ``warnings``; returns ``info.out_of_domain.speed`` (None without a range or a ``speed_mps`` column)."""
    if speed_range is None or "speed_mps" not in table:
        return None
    lo, hi = speed_range
    v = pd.to_numeric(table["speed_mps"], errors="coerce").to_numpy(float)
    out = np.isfinite(v) & ((v < lo * (1 - SPEED_MARGIN)) | (v > hi * (1 + SPEED_MARGIN)))
    table["speed_out_of_range"] = out
    n, m = int(out.sum()), int(np.isfinite(v).sum())
    if n:
        warnings.append(
            f"{n} of {m} strides at speeds outside the model's training strides ({lo:.2f}-{hi:.2f} m/s, "
            f"+-{100 * SPEED_MARGIN:g} %; steps.csv speed_out_of_range): their terrain, direction and length classes "
            "can be wrong with a high confidence; record the calibration exercises at the speed of use and retrain "
            "(decision L474)")
    return {"range_mps": [lo, hi], "margin": SPEED_MARGIN, "n_out": n, "n_strides": m,
            "fraction": n / m if m else None}
