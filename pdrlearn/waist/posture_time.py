"""Where a lower-back track's time went by posture: standing, sitting, lying (decisions W222, W223,
docs/decisions/waist.md).

The lower-back unit's trunk tilt from the session's walking upright (W102's upright, the normalised median of the
AHRS's up direction at the walking contacts; W104's tilt) and the chair transfers (W182) label every instant that
is not walking:

* **lying**: the tilt, the up direction averaged over +-:data:`POSTURE_HALF_WINDOW_S`, is :data:`LYING_TILT_DEG` or
  more (the trunk is nearer horizontal than upright);
* **sitting / standing from a transfer**: a stretch of rest (no walking contact, no lying) is cut at the tilt peak
  of each transfer inside it; a piece that starts at a stand-to-sit or ends at a sit-to-stand is sitting, one that
  starts at a sit-to-stand or ends at a stand-to-sit is standing (the transfer says what the body went to or came
  from); a piece bounded by two transfers that disagree (two rises in a row: one is wrong) is left to the tilt;
* **sitting / standing from the tilt** (no transfer bounds the piece): sitting where the averaged tilt is
  :data:`SITTING_TILT_DEG` (15 deg, W222; W248's 8 deg not kept, W257) or more, standing below it.

Walking and the data gaps are the track's own (decision L275's pieces and gaps, :mod:`pdrlearn.track.periods`):
this module labels every instant of the recording, and the time accounting counts a posture only outside the
walking pieces and the gaps. Without an upright (no contact, no AHRS up direction) every instant is unknown, and
so is an instant whose averaged up direction is not finite (W234).

Not from a seed (the thesis only names Lee & Mase 2002 as classifying sitting, standing and walking): the thresholds
are this module's choices (W222), set before measuring.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.signal import runs
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.posture import contact_directions, walking_upright, window_directions
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT

#: decision W222: the up direction is averaged over +- this (s) before its tilt is read: a posture lasts seconds,
#: a step's rocking and a transfer's flexion peak (W104's 2 s movement) are shorter
POSTURE_HALF_WINDOW_S = 1.0
#: decision W222: lying when the averaged tilt from the walking upright is at least this (deg): a lying trunk is
#: ~90 deg from upright, a reclined or slumped seat well under 60; the 30 deg margin on each side is our choice
LYING_TILT_DEG = 60.0
#: decision W222: without a transfer to go by, sitting when the averaged tilt is at least this (deg): standing
#: still reads within a few degrees of the walking upright (W102: the walking pelvis's range), a seated pelvis tilts
#: back (or the trunk leans forward over a desk) by more. W222 set 15 deg; decision W248 re-chose 8 deg on HAPT
#: users 1-10 (held-out users 11-30: mean sitting / standing agreement 79.0 -> 83.8 %), but HAPT is a belt phone and
#: on the real lower back 8 deg labelled ~3 s of each standing Test5 walk trial sitting: not kept (decision W257)
SITTING_TILT_DEG = 15.0
STANDING, SITTING, LYING = "standing", "sitting", "lying"
POSTURES = (STANDING, SITTING, LYING)
#: decision W222: the summary's and periods.csv's posture keys; with the walking time they sum to the span
POSTURE_KEYS = ("standing_time_s", "sitting_time_s", "lying_time_s", "unknown_time_s")
_CODE = {STANDING: 1, SITTING: 2, LYING: 3}
_NAME = {v: k for k, v in _CODE.items()}
#: decision W234: the code of an instant without a posture (a non-finite tilt); it has no run, so the time
#: accounting counts it unknown
_UNKNOWN = 0


def averaged_tilt_deg(t: np.ndarray, up_body: np.ndarray, upright: np.ndarray,
                      half_s: float = POSTURE_HALF_WINDOW_S) -> np.ndarray:
    """Per sample: the angle (deg) between ``upright`` and the up direction ``up_body`` averaged over +-``half_s``
    (:func:`pdrlearn.waist.posture.window_directions` at every sample; a pure kernel). Decision W234: a non-finite up
    direction is left out of the windows; a sample whose window holds none finite gets a NaN tilt, which
    :func:`label_postures` codes unknown."""
    d = window_directions(t, up_body, t, half_s)
    return np.degrees(np.arccos(np.clip(d @ upright, -1.0, 1.0)))


def label_postures(t: np.ndarray, tilt: np.ndarray, walking: np.ndarray, transfers: pd.DataFrame) -> np.ndarray:
    """Per sample: 1 standing, 2 sitting, 3 lying, 0 unknown (module docstring; a pure kernel). ``tilt`` is the
    averaged tilt (deg), ``walking`` (bool) the samples inside a walking contact's step, ``transfers`` W182's rows
    (``kind``, ``start_s``, ``end_s``, ``peak_s``); a walking sample gets its tilt's label (the time accounting counts
    walking apart). Decision W234: a non-finite tilt (no up direction) is unknown (0), transfers or not."""
    tilt = np.asarray(tilt, dtype=float)
    lying = tilt >= LYING_TILT_DEG
    code = np.where(lying, _CODE[LYING], np.where(tilt >= SITTING_TILT_DEG, _CODE[SITTING], _CODE[STANDING]))
    moving = np.zeros(t.size, dtype=bool)  # a transfer's own contacts are no walking (W146: a rise reads as a step)
    if len(transfers):  # decision W245: only the chair transfers vote (a lying kind is read from these labels)
        transfers = transfers[transfers["kind"].isin((SIT_TO_STAND, STAND_TO_SIT))]
    tr = transfers.sort_values("peak_s") if len(transfers) else transfers
    for r in tr.itertuples():
        moving |= (t >= r.start_s) & (t <= r.end_s)
    rest = ~((np.asarray(walking, dtype=bool) & ~moving) | lying)
    peaks = np.searchsorted(t, tr["peak_s"].to_numpy(float)) if len(tr) else np.zeros(0, int)
    kinds = tr["kind"].to_numpy() if len(tr) else np.zeros(0, object)
    for a, b in runs(rest):
        inside = np.flatnonzero((peaks >= a) & (peaks < b))
        cuts = [a, *peaks[inside].tolist(), b]
        for j in range(len(cuts) - 1):
            votes = set()
            if j > 0:  # the piece starts at a transfer: the posture it went to
                votes.add(SITTING if kinds[inside[j - 1]] == STAND_TO_SIT else STANDING)
            if j < len(inside):  # the piece ends at a transfer: the posture it came from
                votes.add(SITTING if kinds[inside[j]] == SIT_TO_STAND else STANDING)
            if len(votes) == 1:
                code[cuts[j]:cuts[j + 1]] = _CODE[votes.pop()]
    code[~np.isfinite(tilt)] = _UNKNOWN  # decision W234: no up direction, no posture (W222's "unknown")
    return code


def posture_runs(t: np.ndarray, code: np.ndarray) -> list[list]:
    """``[start_s, end_s, posture]`` of each run of equal labels (a run ends where the next starts; the last at
    ``t[-1]``); an unknown run (W234) has no row."""
    if not t.size:
        return []
    edges = np.r_[0, np.flatnonzero(np.diff(code)) + 1]
    ends = np.r_[t[edges[1:]], t[-1]]
    return [[float(t[i]), float(e), _NAME[int(code[i])]] for i, e in zip(edges, ends, strict=True)
            if int(code[i]) != _UNKNOWN]


def session_labels(imu: WaistIMU, steps: pd.DataFrame, transfers: pd.DataFrame,
                   upright: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray] | None:
    """Decision W222: ``(upright, code)`` of a lower-back track - the walking upright from ``steps``' walking
    contacts (``event_s``, ``has_next``) and :func:`label_postures` of the averaged tilt at every IMU sample; None
    when there is no upright (no contact, no AHRS up direction). Decision W277: ``upright`` given (the still
    standing upright of a session without walking) is used instead of the contacts'."""
    if imu.up_body is None or (not len(steps) and upright is None):
        return None
    ev = steps["event_s"].to_numpy(float) if len(steps) else np.zeros(0)
    hn = steps["has_next"].to_numpy(bool) if len(steps) else np.zeros(0, dtype=bool)
    if upright is None:
        upright = walking_upright(contact_directions(imu.t, imu.up_body, ev), hn)
    walking = np.zeros(imu.t.size, dtype=bool)
    for a, b in (zip(steps["start_s"].to_numpy(float)[hn], steps["end_s"].to_numpy(float)[hn], strict=True)
                 if len(steps) else ()):
        walking[np.searchsorted(imu.t, a):np.searchsorted(imu.t, b, side="right")] = True
    tilt = averaged_tilt_deg(imu.t, imu.up_body, upright)
    return upright, label_postures(imu.t, tilt, walking, transfers)


def session_postures(imu: WaistIMU, steps: pd.DataFrame, transfers: pd.DataFrame) -> list[list]:
    """Decision W222: ``info["postures"]`` of a lower-back track - :func:`posture_runs` of :func:`session_labels`;
    ``[]`` when there is no upright: every instant unknown."""
    lab = session_labels(imu, steps, transfers)
    return [] if lab is None else posture_runs(imu.t, lab[1])
