"""Segmentation of detected steps into fixed stance-to-stance windows for the classifiers."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.signal.conditioning import UNIT_STREAMS, runs, standstill_mask
from pdrlearn.signal.filters import interp_rows


def _still_runs(session: Session, unit: str) -> tuple[np.ndarray, list[tuple[int, int]]]:
    acc_name, gyr_name = UNIT_STREAMS[unit]
    acc = session.require(acc_name, purpose=f"{unit} step segmentation")
    if gyr_name in session:
        session.require_cover(acc_name, gyr_name)  # B21: no held rates beyond the gyroscope's ends
        gyr = interp_rows(acc.t, session[gyr_name].t, session[gyr_name].values)
    else:
        gyr = np.zeros_like(acc.values)
    mask = standstill_mask(acc.values, gyr, acc.rate_hz, window_s=0.1, acc_tol=0.6, gyr_tol=0.6)
    return acc.t, runs(mask)


def segment_steps(session: Session, steps: pd.DataFrame, *, unit: str | None = None,
                  max_gap_s: float = 1.5) -> pd.DataFrame:
    """Replace each step's ``start_s``/``end_s`` by its stance-to-stance window.

    - ``foot``: the window runs from the middle of the foot's still (stance) period before the step's
      swing to the middle of the still period after its event (initial contact); still periods come from
      :func:`pdrlearn.signal.standstill_mask` on the foot accelerometer (+ gyroscope when present). When no
      still period lies within ``max_gap_s`` of the event, the window falls back to +-half the median
      stride around the swing (``end = event + T/4``, ``start = end - T``).
    - ``waist``: the window runs between the midpoints to the neighbouring step events (a waist step has
      no stance of its own), the first/last using the median step period.

    Returns a copy of ``steps`` with ``start_s``, ``end_s`` and ``segmented`` (``True`` where still
    periods were found, ``False`` for the fallback).
    """
    unit = unit or (str(steps["unit"].iloc[0]) if len(steps) else "foot")
    if unit not in UNIT_STREAMS:
        raise DataError(f"segment_steps: unknown unit '{unit}'; use 'foot' or 'waist'")
    out = steps.copy()
    ev = out["event_s"].to_numpy(float)
    if ev.size == 0:
        out["segmented"] = np.zeros(0, bool)
        return out
    period = float(np.median(np.diff(ev))) if ev.size > 1 else 1.0
    if unit == "waist":
        mids = (ev[1:] + ev[:-1]) / 2
        out["start_s"] = np.concatenate([[ev[0] - period / 2], mids])
        out["end_s"] = np.concatenate([mids, [ev[-1] + period / 2]])
        out["segmented"] = True
        return out
    t, still = _still_runs(session, "foot")
    centres = np.array([(t[a] + t[b - 1]) / 2 for a, b in still]) if still else np.zeros(0)
    ends_ = np.array([t[b - 1] for a, b in still]) if still else np.zeros(0)
    starts_ = np.array([t[a] for a, b in still]) if still else np.zeros(0)
    start = np.empty_like(ev)
    end = np.empty_like(ev)
    ok = np.zeros(ev.size, bool)
    for k, e in enumerate(ev):
        swing_start = float(out["start_s"].iloc[k]) if "start_s" in out else e - period / 2
        after = np.flatnonzero((starts_ >= swing_start) & (starts_ <= e + max_gap_s) & (ends_ > e))
        before = np.flatnonzero((ends_ <= max(swing_start, e - period / 2) + 0.05) & (ends_ >= e - max_gap_s))
        if after.size and before.size:
            # mid-stance; a long standing period is capped at 0.3 stride from the swing
            b, a = before[-1], after[0]
            start[k] = max(centres[b], ends_[b] - 0.3 * period)
            end[k] = min(centres[a], starts_[a] + 0.3 * period)
            ok[k] = True
        else:
            end[k] = e + period / 4
            start[k] = end[k] - period
    out["start_s"] = start
    out["end_s"] = end
    out["segmented"] = ok
    return out
