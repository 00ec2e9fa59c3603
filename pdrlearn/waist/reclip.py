"""A lower-back unit re-clipped on the belt mid-recording (decision W623, docs/decisions/waist.md).

A unit taken off and clipped back at another angle turns in its own frame: the gyroscope counts that turn as the
walker's (a re-clip about the vertical reads as a heading turn) and the data after it are no longer in the frame
the recording declared (a unit upside down or on its side). A real turn turns the body and the unit together, so
the unit's walking frame - gravity while walking and the step-frequency forward, as D8's waist inference measures
them (:func:`pdrlearn.track.frame_inference.infer_waist_frame`) - stays where it is; a re-clip moves it. This
module's pure kernels:

* :func:`split_rotations`: on a grid of split times, the rotation taking the walking frame measured after each split
  onto the one measured before it;
* :func:`find_reclips`: the splits whose rotation reaches a bound, one per re-clip, each with its time window (the
  largest integrated rotation of the gyroscope near it, or the data gap there);
* :func:`reframe`: the body-frame samples after each re-clip turned back into the first frame, the gyroscope held
  at 0 inside the re-clip's window (its rotation is the unit's on the belt, not a heading turn);
* :func:`reclip_message`: the one warning line of a re-clip.

Not from a seed: the bounds are this module's choices (W623), written before measuring.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.kernels.reclip import (  # W623's numpy kernels, shared with the live trackers
    rotation_angle_deg,
    tilt_rotation,
    two_vector_rotation,
    walking_samples,
)
from pdrlearn.kernels.waist_stream import LONG_GAP_S
from pdrlearn.signal import runs
from pdrlearn.track.frame_inference import (
    MIN_JUDGED_POWER_RATIO,
    NEAREST_SNAP_DEG,
    FrameInferenceError,
    infer_waist_frame,
)


@dataclass
class Reclip:
    """One re-clip: the window ``[t0_s, t1_s]`` (s) the unit turned in, the angle (deg) of its turn, ``rotation``
    (3, 3) taking a vector in the unit's frame after it into the frame before it (``v_before = rotation @ v_after``),
    and whether the window is a data gap."""

    t0_s: float
    t1_s: float
    angle_deg: float
    rotation: np.ndarray
    gap: bool = False


def _frame(acc: np.ndarray, gyr: np.ndarray, fs: float, min_walk_s: float):
    """D8's inference with W394's open snap on at least ``min_walk_s`` of walking samples: ``(up, forward,
    power ratio)``, whatever axes they lie near; None when they do not fix it."""
    if len(acc) < min_walk_s * fs:
        return None
    try:
        f = infer_waist_frame(acc, gyr, fs, max_snap_deg=NEAREST_SNAP_DEG)
    except FrameInferenceError:
        return None
    return f.up, f.forward, f.ap_power_ratio


def frame_rotation(after: tuple, before: tuple, min_ratio: float) -> np.ndarray:
    """Decision W623: the rotation taking the ``after`` frame (:func:`_frame`) onto the ``before`` one: up and
    forward (:func:`two_vector_rotation`) when both forwards were measured with W435's step-frequency power ratio of
    at least ``min_ratio`` (a judged forward), else the smallest rotation taking up onto up (the tilt alone: an uneven
    gait turns the measured forward, W435)."""
    if min(after[2] or 0.0, before[2] or 0.0) >= min_ratio:
        return two_vector_rotation(after[0], after[1], before[0], before[1])
    return tilt_rotation(after[0], before[0])


def split_rotations(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, fs: float, *, step_s: float = 2.0,
                    span_s: float = 20.0, guard_s: float = 1.0, skip: np.ndarray | None = None,
                    min_walk_s: float = 10.0, min_ratio: float = MIN_JUDGED_POWER_RATIO
                    ) -> list[tuple[float, float, np.ndarray]]:
    """Decision W623: ``(split_s, angle_deg, rotation)`` for each split time on a ``step_s`` grid whose last
    ``span_s`` of walking before it and first ``span_s`` of walking after it (:func:`walking_samples`; ``guard_s``
    left out on either side; ``skip``, a sample mask, left out too: bridged samples of a gap) both fix a walking
    frame from at least ``min_walk_s`` of walking; ``rotation`` takes the after frame onto the before frame
    (:func:`frame_rotation`, ``min_ratio``)."""
    t = np.asarray(t, dtype=float)
    walk = np.flatnonzero(walking_samples(acc, fs, skip=skip))
    n = max(int(round(span_s * fs)), 1)
    out = []
    cache: dict = {}

    def frame(i: int, j: int):  # the walking samples walk[i:j]
        if (i, j) not in cache:
            sel = walk[i:j]
            cache[(i, j)] = _frame(acc[sel], gyr[sel], fs, min_walk_s)
        return cache[(i, j)]

    tw = t[walk]
    for c in np.arange(t[0] + step_s, t[-1] - step_s, step_s):
        b = int(np.searchsorted(tw, c - guard_s, "left"))
        a = int(np.searchsorted(tw, c + guard_s, "right"))
        before = frame(max(b - n, 0), b)
        if before is None:
            continue
        after = frame(a, min(a + n, len(walk)))
        if after is None:
            continue
        R = frame_rotation(after, before, min_ratio)
        out.append((float(c), rotation_angle_deg(R), R))
    return out


def may_reclip(acc: np.ndarray, gyr: np.ndarray, fs: float, walk: np.ndarray, *, span_s: float = 20.0,
               min_walk_s: float = 10.0, min_ratio: float = MIN_JUDGED_POWER_RATIO, min_deg: float = 10.0) -> bool:
    """Decision W623's cheap first pass: the walking samples ``walk`` (indices) cut into blocks of ``span_s``; whether
    a block's frame (:func:`_frame`) turns at least ``min_deg`` onto one of the next two measured (a re-clip inside a
    block shows between its neighbours). Each sample is read once, so a recording with no re-clip costs a tenth of
    :func:`split_rotations`' grid."""
    n = max(int(round(span_s * fs)), 1)
    frames = [f for f in (_frame(acc[walk[i:i + n]], gyr[walk[i:i + n]], fs, min_walk_s)
                          for i in range(0, len(walk), n)) if f is not None]
    return any(rotation_angle_deg(frame_rotation(frames[j], frames[k], min_ratio)) >= min_deg
               for k in range(len(frames)) for j in range(k + 1, min(k + 3, len(frames))))


def _window(t: np.ndarray, gyr: np.ndarray, fs: float, lo: float, hi: float, window_s: float,
            skip: np.ndarray | None) -> tuple[float, float, bool]:
    """The re-clip's window in ``[lo, hi]`` s: the bridged gap there (``skip``), else the ``window_s`` window of the
    largest integrated rotation |sum of w dt|."""
    near = (t >= lo) & (t <= hi)
    gaps = [] if skip is None else [(a, b) for a, b in runs(near & skip) if (b - a) / fs > LONG_GAP_S]
    if gaps:  # the longest gap of B11's (over LONG_GAP_S, filled as a rest) there
        a, b = max(gaps, key=lambda r: r[1] - r[0])
        return float(t[max(a - 1, 0)]), float(t[min(b, len(t) - 1)]), True
    idx = np.flatnonzero(near)
    n = max(int(round(window_s * fs)), 1)
    if len(idx) <= n:
        return float(t[idx[0]]), float(t[idx[-1]]), False
    cs = np.vstack([np.zeros(3), np.cumsum(gyr[idx], axis=0)]) / fs
    mag = np.linalg.norm(cs[n:] - cs[:-n], axis=1)
    k = int(np.argmax(mag))
    return float(t[idx[k]]), float(t[idx[k + n - 1]]), False


def find_reclips(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, fs: float, *, min_deg: float = 25.0,
                 scan_deg: float = 20.0,
                 step_s: float = 2.0, span_s: float = 20.0, guard_s: float = 1.0, near_s: float = 3.0,
                 window_s: float = 1.0, skip: np.ndarray | None = None, min_walk_s: float = 10.0,
                 min_ratio: float = MIN_JUDGED_POWER_RATIO) -> list[Reclip]:
    """Decision W623: the re-clips of a body-frame (FLU) waist recording, in time order: each run of neighbouring
    splits (:func:`split_rotations`) whose rotation reaches ``scan_deg``, the largest first; its window
    (:func:`_window`, within ``near_s`` of the run) and the rotation measured across it (the last and first
    ``span_s`` of walking before and after the window, not across a re-clip already found), a re-clip when that
    reaches ``min_deg``."""
    t = np.asarray(t, dtype=float)
    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    walk = np.flatnonzero(walking_samples(acc, fs, skip=skip))
    if len(walk) < 2 * min_walk_s * fs or not may_reclip(acc, gyr, fs, walk, span_s=span_s, min_walk_s=min_walk_s,
                                                          min_ratio=min_ratio, min_deg=scan_deg / 2.0):
        return []  # too little walking for a frame either side, or no block turns (the cheap first pass)
    rots = split_rotations(t, acc, gyr, fs, step_s=step_s, span_s=span_s, guard_s=guard_s, skip=skip,
                           min_walk_s=min_walk_s, min_ratio=min_ratio)
    found: list[list] = []
    for c, ang, R in rots:
        if ang < scan_deg:
            continue
        if found and c - found[-1][-1][0] <= step_s * 1.5:
            found[-1].append((c, ang, R))
        else:
            found.append([(c, ang, R)])
    n = max(int(round(span_s * fs)), 1)
    out: list[Reclip] = []
    for run in sorted(found, key=lambda r: -max(x[1] for x in r)):  # the largest first
        t0, t1, gap = _window(t, gyr, fs, run[0][0] - near_s, run[-1][0] + near_s, window_s, skip)
        # the walking just before and after the window, not across a re-clip already found
        lo = max([r.t1_s for r in out if r.t1_s <= t0], default=-np.inf)
        hi = min([r.t0_s for r in out if r.t0_s >= t1], default=np.inf)
        if any(r.t0_s < t1 and t0 < r.t1_s for r in out):
            continue
        tw = t[walk]
        b_sel = walk[(tw > lo) & (tw < t0)][-n:]
        a_sel = walk[(tw > t1) & (tw < hi)][:n]
        before = _frame(acc[b_sel], gyr[b_sel], fs, min_walk_s)
        after = _frame(acc[a_sel], gyr[a_sel], fs, min_walk_s)
        if before is None or after is None:
            continue
        R = frame_rotation(after, before, min_ratio)
        if rotation_angle_deg(R) >= min_deg:
            out.append(Reclip(t0, t1, rotation_angle_deg(R), R, gap))
    return sorted(out, key=lambda r: r.t0_s)


def reframe(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, reclips: list[Reclip]
            ) -> tuple[np.ndarray, np.ndarray]:
    """Decision W623: copies of the body-frame ``acc`` and ``gyr`` with the samples after each re-clip turned back
    into the first frame (the re-clips' rotations composed in time order) and the gyroscope held at 0 inside each
    re-clip's window."""
    acc, gyr = np.array(acc, dtype=float), np.array(gyr, dtype=float)
    t = np.asarray(t, dtype=float)
    rot = np.tile(np.eye(3), (len(t), 1, 1))
    total = np.eye(3)
    for r in sorted(reclips, key=lambda r: r.t0_s):
        total = total @ r.rotation
        rot[t > r.t1_s] = total
        gyr[(t >= r.t0_s) & (t <= r.t1_s)] = 0.0
    acc = np.einsum("nij,nj->ni", rot, acc)
    gyr = np.einsum("nij,nj->ni", rot, gyr)
    return acc, gyr


def reclipped_imu(session, imu, *, correct: bool = True, **find):
    """Decision W623: ``(imu, lines)``: the lower-back IMU of ``session`` with its re-clips taken out
    (:func:`find_reclips` on :func:`~pdrlearn.waist.ahrs.body_data`, the samples :func:`reframe` turned, the AHRS
    run again) and one line per re-clip; ``imu`` itself and no line when none is found. ``correct=False`` (the
    measurement's baseline, a keyword: W413) says the re-clips and leaves ``imu`` as it is; ``find``: keywords of
    :func:`find_reclips`."""
    from pdrlearn.waist.ahrs import body_data, bridged_samples, imu_from_body

    t, acc, gyr = body_data(session)
    skip = bridged_samples(session, t)
    found = find_reclips(t, acc, gyr, imu.fs, skip=skip if skip.any() else None, **find)
    lines = [reclip_message(r, correct) for r in found]
    if not found or not correct:
        return imu, lines
    acc, gyr = reframe(t, acc, gyr, found)
    out = imu_from_body(t, acc, gyr)
    out.bridged = imu.bridged
    return out, lines


def reclip_message(r: Reclip, corrected: bool) -> str:
    """Decision W623: the one line of a re-clip."""
    then = ("its turn is not counted as a heading turn and the data after it are tracked in the frame before it"
            if corrected else "its turn may be counted as a heading turn and the data after it read in the wrong "
            "frame (the correction is off: '{\"options\": {\"reclip\": true}}')")
    where = "in a data gap" if r.gap else "on the belt"
    return (f"the lower-back unit was re-clipped at {r.t0_s:.1f}-{r.t1_s:.1f} s: its walking frame turned "
            f"{r.angle_deg:.0f} deg {where}; {then} ({decision_ref('W623')})")


__all__ = ["Reclip", "frame_rotation", "split_rotations", "may_reclip", "find_reclips", "reframe", "reclip_message",
           "reclipped_imu"]
