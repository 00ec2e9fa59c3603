"""The trunk's upright when the lower-back unit saw no walking: the gravity direction of the still standing between
chair transfers (decision W277, docs/decisions/waist.md).

W102's upright is the median trunk direction at the walking contacts. A five-times sit-to-stand (or any recording
without walking) has no walking contacts, only the one or two false contacts of each rise (W146), whose trunk is
flexed: the tilts and W104's flexion events read from that "upright" miss most transfers. This module's kernels:

* :func:`walking_is_reliable`: the walking upright is used when the contacts hold a walking sequence of at least
  :data:`MIN_WALKING_CONTACTS` contacts (two strides; a chair rise bounces as one or two contacts, W146);
* :func:`still_mask`: the samples at rest, where the angular rate's magnitude (mean over :data:`STILL_WINDOW_S`) is
  under :data:`STILL_RATE_RPS`, in runs of :data:`STILL_MIN_S` or more;
* :func:`standing_mask`: the still samples that the transfers around them call standing (after a sit-to-stand or
  before a stand-to-sit, and not the other way too), as :mod:`pdrlearn.waist.posture_time` votes.

:func:`pdrlearn.waist.transfers.chair_transfers_upright` iterates them. Not from a seed: the thresholds are this
module's choices (W277), set before measuring.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.signal import runs

#: decision W277: the walking upright needs a walking sequence of this many contacts (two strides) or more
MIN_WALKING_CONTACTS = 4
#: decision W277: at rest when the angular rate's magnitude (mean over STILL_WINDOW_S) is under this (rad/s, 5.7
#: deg/s): standing sway turns the trunk by a few deg/s, a chair transfer by 30-45 deg/s (W182's MOVING_DPS is 10)
STILL_RATE_RPS = 0.1
#: decision W277: the window (s) of that mean
STILL_WINDOW_S = 0.5
#: decision W277: a rest shorter than this (s) is not used (the top of a flexion pauses for less)
STILL_MIN_S = 1.0
#: decision W453: a still sample whose up direction lies this far (deg) or more from the unit frame's up (FLU z, the
#: declared or inferred frame's) is lying, not the standing W277 reads the upright from: W222's LYING_TILT_DEG (a
#: trunk nearer horizontal than upright); a mount is at most 35 deg off its nearest axes (frame_inference.MAX_SNAP_DEG)
NOT_LYING_DEG = 60.0
#: decision W277: at most this many passes of upright -> transfers -> standing upright
MAX_PASSES = 4
#: decision W277: the passes stop when the upright moves by less than this (deg)
CONVERGED_DEG = 1.0


def walking_is_reliable(has_next: np.ndarray) -> bool:
    """Decision W277: True when ``has_next`` (per contact, in time order) holds a run of at least
    :data:`MIN_WALKING_CONTACTS` - 1 consecutive True: a walking sequence of :data:`MIN_WALKING_CONTACTS` contacts."""
    hn = np.asarray(has_next, dtype=bool)
    return any(b - a >= MIN_WALKING_CONTACTS - 1 for a, b in runs(hn))


def flexion_free_walking(has_next: np.ndarray, flexed: np.ndarray) -> np.ndarray:
    """Decision W309: ``has_next`` (per contact, in time order) with the steps that start or end at a ``flexed``
    contact (within W104's flexion window) taken out: only steps between two unflexed contacts stay (a pure
    kernel)."""
    hn = np.asarray(has_next, dtype=bool)
    ok = ~np.asarray(flexed, dtype=bool)
    return hn & ok & np.r_[ok[1:], True]


def still_mask(gyr: np.ndarray, fs: float) -> np.ndarray:
    """Decision W277: per sample, at rest (module docstring; ``gyr`` (n, 3) rad/s in any frame; a pure kernel)."""
    g = np.linalg.norm(np.asarray(gyr, dtype=float), axis=1)
    w = max(int(round(STILL_WINDOW_S * fs)), 1)
    calm = np.convolve(np.where(np.isfinite(g), g, np.inf), np.ones(w) / w, mode="same") < STILL_RATE_RPS
    out = np.zeros(g.size, dtype=bool)
    for a, b in runs(calm):
        if b - a >= STILL_MIN_S * fs:
            out[a:b] = True
    return out


def not_lying(up_body: np.ndarray) -> np.ndarray:
    """Decision W453: per sample, the up direction ``up_body`` (n, 3, body FLU) within :data:`NOT_LYING_DEG` of the
    frame's up (a pure kernel; a non-finite row is False). A night's hours in bed outweigh its minutes upright, and
    W277's median of every still sample was the lying trunk's direction."""
    u = np.asarray(up_body, dtype=float)
    with np.errstate(invalid="ignore"):
        cos = u[:, 2] / np.linalg.norm(u, axis=1)
    return np.isfinite(cos) & (cos > np.cos(np.radians(NOT_LYING_DEG)))


def standing_mask(t: np.ndarray, still: np.ndarray, transfers: pd.DataFrame, rise: str, sit: str) -> np.ndarray:
    """Decision W277: per sample, still and standing by the transfers' vote: the transfer before it (by its end)
    is a ``rise`` or the one after it (by its start) a ``sit``, and neither says seated (a pure kernel)."""
    out = np.zeros(t.size, dtype=bool)
    if not len(transfers):
        return out
    tr = transfers.sort_values("start_s")
    ends, starts, kinds = (tr["end_s"].to_numpy(float), tr["start_s"].to_numpy(float), tr["kind"].to_numpy())
    ks = tr["kind"].to_numpy()[np.argsort(ends, kind="stable")]
    ends = np.sort(ends)
    i_prev = np.searchsorted(ends, t, side="right") - 1  # the last transfer that ended at or before t
    i_next = np.searchsorted(starts, t, side="left")  # the first that starts at or after t
    prev = np.where(i_prev >= 0, ks[np.clip(i_prev, 0, len(ks) - 1)], "")
    nxt = np.where(i_next < len(kinds), kinds[np.clip(i_next, 0, len(kinds) - 1)], "")
    stand = (prev == rise) | (nxt == sit)
    seat = (prev == sit) | (nxt == rise)
    return still & stand & ~seat


def mean_direction(up_body: np.ndarray, mask: np.ndarray) -> np.ndarray | None:
    """The normalised median of ``up_body``'s finite rows in ``mask`` (None when there are none)."""
    u = np.asarray(up_body, dtype=float)[np.asarray(mask, dtype=bool)]
    u = u[np.isfinite(u).all(axis=1)]
    if not len(u):
        return None
    m = np.median(u, axis=0)
    n = float(np.linalg.norm(m))
    return m / n if n > 0 else None
