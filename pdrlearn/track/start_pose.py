"""A start pose the user knows, applied to a finished track (decisions L635, L637).

``turn_to_start_heading``: a track whose heading is absolute (the offline foot track fused with the waist compass)
carries the compass's constant offset (hard iron, mounting yaw: 4-9 deg on trial T3's courses); a known start
heading (``track --initial-heading``) turns the whole track about its start so that its first straight strides head
that way (L635). ``shift_to_start_xy``: ``track --start-xy X,Y`` moves a track's local frame so it starts at X, Y
(L637). Both are pure functions of the :class:`~pdrlearn.track.base.TrackResult`; the pipelines stay untouched.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.orient._kernels import wrap_angle

#: decision L635: the first straight strides end where a stride's direction of travel leaves the first stride's by
#: more than this (rad), or after :data:`START_MAX_STRIDES` strides (a judgement, not from a document: a walker's
#: start is a stride or two of settling followed by the first corridor; 15 deg keeps a gentle drift, ends at a turn)
START_MAX_TURN_RAD = math.radians(15.0)
#: decision L635: at most this many strides measure the track's start direction (about 14 m of walking)
START_MAX_STRIDES = 10


def first_straight_heading(steps) -> tuple[float, int] | None:
    """The direction of travel (ENU rad) of a track's first straight strides and how many strides it was measured
    on (decision L635): the strides that move (non-zero finite ``length_m`` and ``heading_rad``), from the first,
    while each one's direction of travel stays within :data:`START_MAX_TURN_RAD` of the first one's, at most
    :data:`START_MAX_STRIDES`; the direction of their summed displacement. None: no stride moves."""
    if steps is None or not len(steps) or not {"length_m", "heading_rad"} <= set(steps.columns):
        return None
    length = steps["length_m"].to_numpy(float)
    head = steps["heading_rad"].to_numpy(float)
    ok = np.isfinite(length) & np.isfinite(head) & (length != 0)
    if not ok.any():
        return None
    dx, dy = (length * np.cos(head))[ok], (length * np.sin(head))[ok]  # a backward stride travels along head + pi
    travel = np.arctan2(dy, dx)
    off = np.abs(wrap_angle(travel - travel[0])) > START_MAX_TURN_RAD
    n = int(np.argmax(off)) if off.any() else len(travel)
    n = max(1, min(n, START_MAX_STRIDES))
    return float(math.atan2(dy[:n].sum(), dx[:n].sum())), n


def turn_to_start_heading(result, heading_rad: float, *, start=None):
    """``result`` turned about its first trajectory row so that its first straight strides head ``heading_rad``
    (ENU rad; decision L635): the trajectory's ``x``, ``y`` (and ``lat``, ``lon`` from ``start`` (lat, lon) by thesis
    eq. 56/57, when it has them) and the steps' ``heading_rad``. ``info["start_heading"]`` records the given heading,
    the track's own start direction, the turn (deg) and the strides measured. A track without a moving stride is
    returned as it is (``turn_deg`` None)."""
    measured = first_straight_heading(result.steps)
    info = dict(result.info)
    rec = {"given_deg": round(math.degrees(heading_rad), 3), "track_deg": None, "turn_deg": None, "n_strides": 0}
    if measured is None:
        info["start_heading"] = rec
        return dataclasses.replace(result, info=info)
    own, n = measured
    turn = float(wrap_angle(heading_rad - own))
    c, s = math.cos(turn), math.sin(turn)
    traj = result.trajectory.copy()
    if len(traj):
        x0, y0 = float(traj["x"].iloc[0]), float(traj["y"].iloc[0])
        dx, dy = traj["x"].to_numpy(float) - x0, traj["y"].to_numpy(float) - y0
        traj["x"], traj["y"] = x0 + c * dx - s * dy, y0 + s * dx + c * dy
    steps = result.steps.copy()
    steps["heading_rad"] = wrap_angle(steps["heading_rad"].to_numpy(float) + turn)
    if "lat" in traj and start is not None and len(traj) == len(steps) + 1:
        from pdrlearn.track.geodetic import geodetic_track

        ll = geodetic_track(tuple(start), steps["length_m"].to_numpy(float), steps["heading_rad"].to_numpy(float))
        traj["lat"], traj["lon"] = ll[:, 0], ll[:, 1]
    rec.update(track_deg=round(math.degrees(own), 3), turn_deg=round(math.degrees(turn), 3), n_strides=n)
    info["start_heading"] = rec
    return dataclasses.replace(result, steps=steps, trajectory=traj, info=info)


def parse_start_xy(text: str | None) -> tuple[float, float] | None:
    """``--start-xy X,Y`` (decision L637): the start in local metres (x east, y north), two finite numbers, or one
    line naming the option and the fix."""
    if text is None:
        return None
    parts = [p.strip() for p in str(text).split(",")]
    try:
        xy = tuple(float(p) for p in parts)
    except ValueError:
        xy = ()
    if len(xy) != 2 or not all(math.isfinite(v) for v in xy):
        raise DataError(f"--start-xy {text}: give the start in local metres as two finite numbers X,Y (x east, "
                        "y north), e.g. --start-xy 100,50")
    return float(xy[0]), float(xy[1])


def shift_to_start_xy(result, xy: tuple[float, float]):
    """``result`` with its trajectory's ``x``, ``y`` moved so its first row is at ``xy`` (decision L637); the
    steps are relative and stay. ``info["start_xy"]`` records it."""
    traj = result.trajectory.copy()
    if len(traj):
        traj["x"] = traj["x"] - float(traj["x"].iloc[0]) + xy[0]
        traj["y"] = traj["y"] - float(traj["y"].iloc[0]) + xy[1]
    return dataclasses.replace(result, trajectory=traj, info={**result.info, "start_xy": [xy[0], xy[1]]})
