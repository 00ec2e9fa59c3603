"""Backward steps on the lower back: the waist pipelines count every step as forward distance (decision W173).

A lower-back unit gives a step's length (W6/W10) and the unit's heading, not the way the step went: a backward step
is tracked forward, silently. Two cues say a stretch of steps looks backward, each the mechanism that infers a
forward sign elsewhere, reused:

- the foot unit's push-off (decision D9, per stride here): a forward stride pitches the foot toes-down much further
  than toes-up; a stride whose asymmetry is under D9's :data:`MIN_SWING_ASYMMETRY` has no forward push-off. Only
  with a declared foot frame (an inferred one assumes forward walking);
- the trunk's forward/vertical acceleration phase at step frequency (decision W2, summed over the walking sequence
  as W65's inference sums it): outside +-90 deg of 45 deg by D8's :data:`MIN_PHASE_MARGIN_DEG` the unit's forward
  axis points against the walking.

A run of at least :data:`MIN_BACKWARD_STEPS` consecutive steps with either cue gives one warning line (per run:
forward, backward, forward again gives one line for the backward part). The steps are not changed (their sign is
a default change that needs its own adoption rule, W173).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.frame_inference import (
    MIN_PHASE_MARGIN_DEG,
    MIN_SWING_ASYMMETRY,
    foot_push_off,
    trunk_forward_margin,
)
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.lengths import walking_sequences

#: decision W173: fewer consecutive backward-looking steps are no backward stretch (a stumble, a turn's step back)
MIN_BACKWARD_STEPS = 4


def backward_steps(steps: pd.DataFrame, imu: WaistIMU, session) -> tuple[np.ndarray, np.ndarray]:
    """Per step of a waist track: looks backward by the foot's push-off (D9), by the trunk's phase (W2)."""
    n = len(steps)
    ev = steps["event_s"].to_numpy(float)
    foot = np.zeros(n, dtype=bool)
    strides = foot_push_off(session)
    if strides is not None:
        t0, t1, asym = strides
        for a, b in zip(t0[asym < MIN_SWING_ASYMMETRY], t1[asym < MIN_SWING_ASYMMETRY], strict=True):
            foot |= (ev >= a) & (ev < b)
    trunk = np.zeros(n, dtype=bool)
    for seq in walking_sequences(steps["has_next"].to_numpy(bool)):
        a, b = np.searchsorted(imu.t, [steps["start_s"].iloc[seq[0]], _end(steps, seq[-1])])
        margin = trunk_forward_margin(imu.acc_v[a:b], imu.acc_ap[a:b], imu.acc_ml[a:b], imu.fs)
        if margin is not None and margin <= -MIN_PHASE_MARGIN_DEG:
            trunk[seq] = True
    return foot, trunk


def _end(steps: pd.DataFrame, i: int) -> float:
    """The end (s) of row ``i``: its step's end, its contact for a closing row without one."""
    end = float(steps["end_s"].iloc[i])
    return end if np.isfinite(end) else float(steps["event_s"].iloc[i])


def backward_runs(foot: np.ndarray, trunk: np.ndarray, has_next: np.ndarray) -> list[tuple[int, int, str]]:
    """Runs ``(first, last, cue)`` of at least :data:`MIN_BACKWARD_STEPS` consecutive backward-looking steps inside
    one walking sequence; ``cue`` names the evidence ("foot", "trunk" or "foot and trunk")."""
    out = []
    for seq in walking_sequences(np.asarray(has_next, bool)):
        back = foot[seq] | trunk[seq]
        edges = np.flatnonzero(np.diff(np.r_[0, back.astype(int), 0]))
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            if b - a >= MIN_BACKWARD_STEPS:
                rows = seq[a:b]
                cue = " and ".join(c for c, f in (("foot", foot), ("trunk", trunk)) if f[rows].any())
                out.append((int(rows[0]), int(rows[-1]), cue))
    return out


_CUES = {"foot": "the foot unit has no forward push-off (decision D9)",
         "trunk": "the trunk's forward/vertical acceleration phase points backward (decision W2)"}


def backward_message(steps: pd.DataFrame, first: int, last: int, cue: str) -> str:
    """Decision W173's one line for the backward-looking steps ``first..last`` of a waist track."""
    t0, t1 = float(steps["event_s"].iloc[first]), _end(steps, last)
    why = " and ".join(_CUES[c] for c in cue.split(" and "))
    n = last - first + 1
    return (f"{n} steps at {t0:.1f}-{t1:.1f} s look backward ({why}): the lower-back pipelines count every step as "
            "forward distance, so these move the track forward instead of back (decision W173)"
            + ("; if the walker walked forward there, the waist unit's forward axis may be reversed: check its "
               "\"frames\" in meta.json" if "trunk" in cue else ""))


def backward_warnings(steps: pd.DataFrame, imu: WaistIMU, session) -> list[str]:
    """Decision W173's warning lines of a waist track (none when no stretch looks backward)."""
    if not len(steps):
        return []
    foot, trunk = backward_steps(steps, imu, session)
    return [backward_message(steps, a, b, cue) for a, b, cue in backward_runs(foot, trunk, steps["has_next"])]
