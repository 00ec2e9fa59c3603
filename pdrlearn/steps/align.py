"""Clock alignment of the foot and waist units from their step events (thesis ch.7: the units are
aligned with the gyroscope step detector; here any waist detector).

Model: at one physical instant the waist clock reads ``t_w = t_f + offset_s + drift * (t_f - ref_s)`` where
``t_f`` is the foot clock (the foot clock is the reference: labels and foot steps are kept on it) and ``ref_s`` the
estimate's reference time inside the recording (decision L198; 0 is the simulator's convention).
"""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels.align import (
    MAX_CLOCK_DRIFT,
    align_events,  # noqa: F401 (numpy only, shared with the runtime: L177)
    to_foot_clock,
)

log = logging.getLogger(__name__)


def align_units(session: Session, *, foot_detector=None, waist_detector=None, max_offset_s: float = 2.0,
                tolerance_s: float = 0.12, fit_drift: bool = True,
                min_span_s: float = 60.0) -> tuple[float, float]:
    """``(offset_s, drift)`` of :func:`align_estimate` (its other keys: ``ref_s``, the time ``offset_s`` holds at,
    decision L198; ``matched``, ``residual_sd_s``, ...)."""
    res = align_estimate(session, foot_detector=foot_detector, waist_detector=waist_detector,
                         max_offset_s=max_offset_s, tolerance_s=tolerance_s, fit_drift=fit_drift, min_span_s=min_span_s)
    return res["offset_s"], res["drift"]


def align_estimate(session: Session, *, foot_detector=None, waist_detector=None, max_offset_s: float = 2.0,
                   tolerance_s: float = 0.12, fit_drift: bool = True, min_span_s: float = 60.0,
                   force_table=None) -> dict:
    """Estimate the clock offset and drift between the foot and waist units of ``session``.

    Foot events: the accelerometer + force detector when force sensors are present, else the
    accelerometer detector; waist events: the PLL detector (both replaceable). Returns
    :func:`~pdrlearn.kernels.align.align_events`' dict (``offset_s``, ``drift``, ``ref_s`` with ``t_waist = t_foot +
    offset_s + drift * (t_foot - ref_s)``, decision L198; ``matched``, ``residual_sd_s``: decision L183's lock test);
    details are logged; the session is left untouched. ``force_table``: the default accelerometer + force
    detector's table on this session when the caller has it (steps decision 55: used instead of detecting again
    when that detector is the one chosen).
    """
    from pdrlearn.steps.detectors import AccelForceStepDetector, AccelStepDetector, PLLStepDetector

    reuse = foot_detector is None and force_table is not None and session.has("fForceA", "fForceB")
    if foot_detector is None:
        has_force = session.has("fForceA", "fForceB")
        foot_detector = AccelForceStepDetector() if has_force else AccelStepDetector()
    waist_detector = waist_detector or PLLStepDetector()
    fe = (force_table if reuse else foot_detector.detect(session))["event_s"].to_numpy(float)
    we = waist_detector.detect(session)["event_s"].to_numpy(float)
    res = align_events(fe, we, max_offset_s=max_offset_s, tolerance_s=tolerance_s, fit_drift=fit_drift,
                       min_span_s=min_span_s)
    log.info("%s alignment: %s", session.name, res)
    return res


def apply_alignment(session: Session, offset_s: float, drift: float = 0.0, ref_s: float = 0.0) -> Session:
    """Copy of ``session`` with the waist streams moved onto the foot clock:
    ``t_foot = ref_s + (t_waist - offset_s - ref_s) / (1 + drift)`` (the model above solved for ``t_foot``; give
    :func:`align_estimate`'s ``ref_s`` with its ``offset_s`` and ``drift``, decision L198). Labels are left as they
    are (foot clock)."""
    out = session.copy()
    if not np.isfinite(offset_s) or not np.isfinite(drift) or not np.isfinite(ref_s) or abs(drift) > MAX_CLOCK_DRIFT:
        raise DataError(f"apply_alignment: implausible offset {offset_s} s / drift {drift} / reference {ref_s} s; "
                        "re-run align_units")
    for s in out.streams.values():
        if s.placement == "waist":
            s.t = to_foot_clock(s.t, offset_s, drift, ref_s)
    if (out.meta or {}).get("clock_offset_s") or (out.meta or {}).get("clock_drift_ppm"):
        # W380 (review R5): the waist is on the foot clock now, so the simulator's recorded clock no longer moves labels
        out.meta = {**out.meta, "clock_offset_s": 0.0, "clock_drift_ppm": 0.0}
    return out
