"""Trunk posture of the lower-back unit: a contact made while the trunk is far from its walking upright is no step.

Decision W102 (docs/decisions/waist.md): rising from a chair or bending forward bounces the lower back like a step
and passes the motion gate (W4 / W76) and the IC rules; the trunk's tilt tells them apart. Not from the seeds: the
lower trunk leans about 10-20 deg from upright while walking, and 40 deg and more when rising from a chair or
bending (general gait physiology); :data:`MAX_TILT_DEG` is twice the walking range's upper end, chosen before
measuring.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.waist.ahrs import WaistIMU

#: A contact whose trunk direction is further than this from the session's walking upright is no step (deg; W102).
MAX_TILT_DEG = 40.0
#: Half-width of the window around a contact over which its trunk direction is averaged (s; one step, W102).
TILT_HALF_WINDOW_S = 0.5


def contact_tilt_deg(imu: WaistIMU, event_s: np.ndarray, walking: np.ndarray) -> np.ndarray:
    """Tilt (deg) of the trunk at each contact: the angle between the AHRS's up direction in the body frame
    (``imu.up_body``) averaged over +-:data:`TILT_HALF_WINDOW_S` around the contact, and the session's upright,
    the normalised median of those directions over the ``walking`` contacts (those that start a step). The
    upright is the session's own, so any mounting of the unit and a walker's constant stoop read 0 (W102)."""
    event_s = np.asarray(event_s, dtype=float)
    if imu.up_body is None or event_s.size == 0:
        return np.zeros(event_s.size)
    walking = np.asarray(walking, dtype=bool)
    if not walking.any():
        walking = np.ones(event_s.size, dtype=bool)
    # window means by cumulative sums: O(n) for any number of contacts
    csum = np.vstack([np.zeros((1, 3)), np.cumsum(imu.up_body, axis=0)])
    lo = np.clip(np.searchsorted(imu.t, event_s - TILT_HALF_WINDOW_S), 0, len(imu.t) - 1)
    hi = np.clip(np.searchsorted(imu.t, event_s + TILT_HALF_WINDOW_S, side="right"), lo + 1, len(imu.t))
    d = (csum[hi] - csum[lo]) / (hi - lo)[:, None]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    up = np.median(d[walking], axis=0)
    up /= np.linalg.norm(up)
    return np.degrees(np.arccos(np.clip(d @ up, -1.0, 1.0)))


def tilt_gate(steps: pd.DataFrame, imu: WaistIMU, max_tilt_deg: float = MAX_TILT_DEG) -> pd.DataFrame:
    """``steps`` (one row per contact, :func:`pdrlearn.waist.events.steps_from_events`' columns) without the
    contacts whose trunk tilt (:func:`contact_tilt_deg`) exceeds ``max_tilt_deg``; a kept step whose next contact
    is dropped ends its walking sequence (``end_s`` = its start, no ``has_next``, confidence 0.5, as
    :func:`pdrlearn.kernels.waist.contact_rows` closes a sequence). ``attrs["n_tilted"]`` counts the dropped."""
    if steps.empty:
        out = steps.copy()
        out.attrs["n_tilted"] = 0
        return out
    has_next = steps["has_next"].to_numpy(bool)
    tilt = contact_tilt_deg(imu, steps["event_s"].to_numpy(float), has_next)
    keep = tilt <= max_tilt_deg
    before_dropped = has_next & np.append(~keep[1:], False)  # the step that ended on a dropped contact
    out = steps.copy()
    out.loc[before_dropped, "end_s"] = out.loc[before_dropped, "start_s"]
    out.loc[before_dropped, "has_next"] = False
    if "confidence" in out:
        out.loc[before_dropped, "confidence"] = 0.5
    out = out[keep].reset_index(drop=True)
    out.attrs.update(steps.attrs)
    out.attrs["n_tilted"] = int((~keep).sum())
    return out
