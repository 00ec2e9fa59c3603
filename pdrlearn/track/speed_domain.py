"""Decision L474 (trial T5 finding 3): strides walked at speeds outside the model's training strides.

A model trained on exercises at one speed classed 42 of 162 strides of a fast mission (median 1.9 m/s) wrongly with
a median confidence 0.73, and C16's feature-range scores did not flag them. ``pdrlearn train``'s distance calibration
tracks the training sessions (``displace.calibration``) and records the 1 % / 99 % quantiles of its strides'
``speed_mps`` (C16's quantiles) as ``speed_range_mps``; a tracked stride more than :data:`SPEED_MARGIN` outside it
gets ``speed_out_of_range`` True in steps.csv and the track one warning line. Decisions L480 / L481: the range is
taken over, and compared on, the same cruise strides (:func:`cruise_strides`: level, forward, straight, not at a
bout's ends, touching both neighbours), so a slow walk is flagged and a start from standing is not; a model
trained before L481 records no ``speed_range_strides`` and is compared on every stride as before.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L474: the relative margin (10 %) outside the training strides' 1-99 % speed range before a stride is
#: flagged; stated, not fitted (a walk at the training speed has 2 % of its strides outside its own quantiles)
SPEED_MARGIN = 0.10
#: decision L480: the strides left out at each end of each walking bout (the start from standing and the stop; a
#: project choice: the simulator's and a walker's first stride is a half stride, Lindemann et al. 2008 in L415)
CRUISE_TRIM = 1
#: decision L481 (rule B): a cruise stride touches both neighbours (the gap between one stride's end and the next's
#: start at most this, s: one sample at 20 Hz; a project choice): strides of a continuous walk share their boundary,
#: so a gap is standing or turning on the spot between them, which the bout split (a pause of >= 1 s) may not see
CRUISE_GAP_S = 0.05


def cruise_strides(steps: pd.DataFrame) -> np.ndarray:
    """Decision L480: (rows,) bool, the strides a speed range is taken over at train time and compared at track time:
    level, forward, straight (:func:`pdrlearn.displace.calibration.straight_level_forward`: measured height change,
    length and heading, no model class, so a wrong class does not hide a stride) and not among the
    :data:`CRUISE_TRIM` first or last strides of a walking bout (:func:`pdrlearn.track.steady.trimmed_rows`: a
    start from standing, the stride before and after a pause); decision L481 (rule B, adopted; W413: no module
    switch) also touching both neighbours (:func:`contiguous_strides`)."""
    from pdrlearn.displace.calibration import straight_level_forward
    from pdrlearn.track.steady import trimmed_rows

    if not len(steps):
        return np.zeros(0, bool)
    out = straight_level_forward(steps) & ~trimmed_rows(steps, CRUISE_TRIM)
    return out & contiguous_strides(steps)


def contiguous_strides(steps: pd.DataFrame, gap_s: float = CRUISE_GAP_S) -> np.ndarray:
    """Decision L481 (rule B): (rows,) bool, the rows (in the table's order, by ``start_s`` / ``end_s``) whose start
    is the previous row's end and whose end the next row's start, within ``gap_s``; the first and last row are not."""
    t0, t1 = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    with np.errstate(invalid="ignore"):
        touch = np.abs(t0[1:] - t1[:-1]) <= gap_s
    return np.r_[False, touch] & np.r_[touch, False]


def training_speed_range(speeds) -> list[float] | None:
    """Decision L474: the (1 %, 99 %) quantiles (C16's ``QUANTILES``) of the finite positive stride speeds (m/s) of
    the training sessions' tracked strides; None with fewer than 10."""
    return _quantile_range(speeds)


def training_stride_time_range(times) -> list[float] | None:
    """Decision C191: L474's range (:func:`training_speed_range`'s quantiles) of the training sessions' cruise
    strides' ``stride_time_s`` (s), so a walk at another tempo than the calibration's is flagged."""
    return _quantile_range(times)


def _quantile_range(values) -> list[float] | None:
    from pdrlearn.classify.domain import QUANTILES

    v = np.asarray(values, float)
    v = v[np.isfinite(v) & (v > 0)]
    if len(v) < 10:
        return None
    lo, hi = np.quantile(v, QUANTILES)
    return [round(float(lo), 4), round(float(hi), 4)]


def model_speed_range(model) -> list[float] | None:
    """The ``speed_range_mps`` a trained model recorded (None: oracle labels, no model, or trained before L474)."""
    rng = _calibration(model).get("speed_range_mps")
    return [float(rng[0]), float(rng[1])] if rng is not None and len(rng) == 2 else None


def model_stride_time_range(model) -> list[float] | None:
    """Decision C191: the ``stride_time_range_s`` a trained model recorded (None: trained before C191, or no model)."""
    rng = _calibration(model).get("stride_time_range_s")
    return [float(rng[0]), float(rng[1])] if rng is not None and len(rng) == 2 else None


def model_speed_strides(model) -> str:
    """Decision L480: which strides the model's ``speed_range_mps`` was taken over, ``"cruise"``
    (:func:`cruise_strides`) or ``"all"`` (L474; a model trained before L480 records nothing)."""
    return str(_calibration(model).get("speed_range_strides") or "all")


def _calibration(model) -> dict:
    summary = getattr(model, "data_summary", None) or {}
    return summary.get("distance_calibration") or {}


def flag_speeds(table: pd.DataFrame, speed_range, warnings: list[str], strides: str = "all") -> dict | None:
    """Decision L474: add ``speed_out_of_range`` to the stride ``table`` (``speed_mps`` more than
    :data:`SPEED_MARGIN` outside ``speed_range``; False where the speed is unknown) and, when any is, one line to
    ``warnings``; returns ``info.out_of_domain.speed`` (None without a range or a ``speed_mps`` column).
    ``strides`` ``"cruise"`` (decision L480: the range was taken over :func:`cruise_strides`): only those strides are
    compared (a start, a turn, a stair stride is not flagged)."""
    if speed_range is None:
        return None
    lo, hi = speed_range
    return _flag_range(table, "speed_mps", "speed_out_of_range", speed_range, warnings, strides, (
        f"at speeds outside the model's training strides ({lo:.2f}-{hi:.2f} m/s, +-{100 * SPEED_MARGIN:g} %; "
        "steps.csv speed_out_of_range): their terrain, direction and length classes can be wrong with a high "
        "confidence; record the calibration exercises at the speed of use and retrain (decision L474)"), "range_mps")


def flag_stride_times(table: pd.DataFrame, model, warnings: list[str]) -> dict | None:
    """Decision C191: L474's check (:func:`flag_speeds`, the same margin and cruise strides) on ``stride_time_s``
    against the model's ``stride_time_range_s``: adds ``stride_time_out_of_range`` and, when any is, one line; a
    model with L474's speed range but no stride-time range (trained before C191) gets one line saying the tempo is
    not checked. Returns ``info.out_of_domain.stride_time`` (None without a range)."""
    rng = model_stride_time_range(model)
    if rng is None:
        if model_speed_range(model) is not None:
            warnings.append("the model records no stride-time range (trained before decision C191), so the walk's "
                            "tempo is not compared with the calibration's (steps.csv has no stride_time_out_of_range); "
                            "retrain with pdrlearn train to check it")
        return None
    lo, hi = rng
    return _flag_range(table, "stride_time_s", "stride_time_out_of_range", rng, warnings,
                       model_speed_strides(model), (
                           f"at stride times outside the model's training strides ({lo:.2f}-{hi:.2f} s, "
                           f"{120 / hi:.0f}-{120 / lo:.0f} steps/min, +-{100 * SPEED_MARGIN:g} %; steps.csv "
                           "stride_time_out_of_range): a tempo the calibration exercises did not walk, where the "
                           "terrain, direction and length classes can be wrong with a high confidence (compare "
                           "length_class with length_m); record the calibration exercises at the tempo of use and "
                           "retrain (decision C191)"), "range_s")


def _flag_range(table: pd.DataFrame, column: str, flag: str, rng, warnings: list[str], strides: str, text: str,
                key: str) -> dict | None:
    """Decisions L474 / C191: the shared check: ``flag`` True where ``column`` lies more than :data:`SPEED_MARGIN`
    outside ``rng`` on the judged strides (:func:`cruise_strides` for ``strides`` "cruise"); one line ``f"{n} of
    {m} {what} {text}"`` when any does."""
    if column not in table:
        return None
    lo, hi = rng
    v = pd.to_numeric(table[column], errors="coerce").to_numpy(float)
    judged = np.isfinite(v) & (cruise_strides(table) if strides == "cruise" else True)
    out = judged & ((v < lo * (1 - SPEED_MARGIN)) | (v > hi * (1 + SPEED_MARGIN)))
    table[flag] = out
    n, m = int(out.sum()), int(judged.sum())
    what = "level straight strides" if strides == "cruise" else "strides"
    if n and "travel" in table:  # trial T3 finding 9: a side or backward stride is counted as such, not as a walk's
        travel = table["travel"].astype(str).to_numpy()
        other = [f"{int((out & (travel == t)).sum())} {t}" for t in ("side", "backward") if (out & (travel == t)).any()]
        what += f" (of them {', '.join(other)} steps, not forward walking)" if other else ""
    if n:
        warnings.append(f"{n} of {m} {what} {text}")
    return {key: [lo, hi], "margin": SPEED_MARGIN, "strides": strides, "n_out": n, "n_strides": m,
            "fraction": n / m if m else None}
