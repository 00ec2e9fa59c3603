"""A lower-back unit that turns on the belt during a recording (decisions W565, W566, docs/decisions/waist.md).

W102's upright is one direction for the whole recording: the median trunk direction at the walking contacts. A unit
that slides on the belt moves the walking trunk's direction in the unit frame, and every tilt read from that one
upright (W104's flexion events, W182's transfers, W222's postures) drifts with it. This module's pure kernels:

* :func:`bout_uprights`: each walking bout's own upright (W102's median over its contacts), at the bout's mid-time;
* :func:`drift_deg`: the angle between the first and the last bout's uprights (W565's warning above
  :data:`MOUNT_DRIFT_DEG`);
* :func:`turned_up`: the up direction turned, per sample, by the smallest rotation that takes the instant's upright
  (the bouts' uprights interpolated in time) onto one reference (W566's candidate);
* :func:`standing_follows`: whether the quiet standing before the first bout and after the last moved with the
  walking upright (W576: a slide moves every posture, a walking trunk's lean does not).

Not from a seed: the threshold is this module's choice (W565), set before measuring.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.signal import runs
from pdrlearn.waist.posture import contact_directions, walking_upright
from pdrlearn.waist.upright import MIN_WALKING_CONTACTS, mean_direction, still_mask

#: decision W565: a mount drifting more than this (deg) between the first and the last walking bout is said: half of
#: W222's 15 deg sitting tilt (a drift that large eats half the margin between standing and sitting); our choice
MOUNT_DRIFT_DEG = 7.5


def walking_bouts(t: np.ndarray, up_body: np.ndarray, event_s: np.ndarray,
                  has_next: np.ndarray) -> list[tuple[float, float, np.ndarray]]:
    """Decisions W565 / W576: ``(first_contact_s, last_contact_s, upright)`` of each walking bout (a run of at least
    W277's :data:`~pdrlearn.waist.upright.MIN_WALKING_CONTACTS` contacts joined by ``has_next``), in time order:
    W102's upright (:func:`~pdrlearn.waist.posture.walking_upright`) over the bout's contacts alone."""
    e = np.asarray(event_s, dtype=float)
    hn = np.asarray(has_next, dtype=bool)
    if e.size == 0 or up_body is None:
        return []
    d = contact_directions(t, up_body, e)
    out = []
    for a, b in runs(hn):
        if b - a < MIN_WALKING_CONTACTS - 1:
            continue
        b = min(b, e.size - 1)  # contacts a..b are the bout's (has_next joins b - 1 to b)
        seg = d[a:b + 1]
        seg = seg[np.isfinite(seg).all(axis=1)]
        if len(seg) >= MIN_WALKING_CONTACTS:
            out.append((float(e[a]), float(e[b]), walking_upright(seg, np.ones(len(seg), bool))))
    return out


def bout_uprights(t: np.ndarray, up_body: np.ndarray, event_s: np.ndarray,
                  has_next: np.ndarray) -> list[tuple[float, np.ndarray]]:
    """Decision W565: ``(mid_s, upright)`` of each walking bout (:func:`walking_bouts`), in time order."""
    return [(0.5 * (a + b), u) for a, b, u in walking_bouts(t, up_body, event_s, has_next)]


def drift_deg(bouts: list[tuple[float, np.ndarray]]) -> float:
    """Decision W565: the angle (deg) between the first and the last bout's uprights (0 with fewer than two)."""
    if len(bouts) < 2:
        return 0.0
    return float(np.degrees(np.arccos(np.clip(bouts[0][1] @ bouts[-1][1], -1.0, 1.0))))


def drift_message(deg: float, bouts: list[tuple[float, np.ndarray]], corrected: bool) -> str:
    """Decisions W565 / W566: the one line of a drifting mount."""
    then = (f"the posture and the chair transfers read each walking bout's upright ({decision_ref('W566')})"
            if corrected else
            "the posture times and chair transfers, read from one upright, may be wrong late in the recording")
    return (f"the lower-back unit turned on the belt: the walking trunk's upright moved {deg:.1f} deg in the unit "
            f"between the first walking bout (at {bouts[0][0]:.1f} s) and the last (at {bouts[-1][0]:.1f} s); "
            f"{then}; fasten the unit so that it cannot slide ({decision_ref('W565')})")


def turn_onto(v: np.ndarray, u: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Decisions W566 / W576: the rows of ``v`` (n, 3) turned by the smallest rotation taking the matching row of
    ``u`` (n, 3 unit vectors) onto ``reference`` (3,)."""
    u = np.asarray(u, dtype=float)
    ref = np.asarray(reference, dtype=float) / np.linalg.norm(reference)
    axis = np.cross(u, ref)
    s = np.linalg.norm(axis, axis=1)
    c = u @ ref
    k = np.divide(axis, s[:, None], out=np.zeros_like(axis), where=s[:, None] > 1e-12)
    v = np.asarray(v, dtype=float)
    # Rodrigues: v cos + (k x v) sin + k (k . v)(1 - cos)
    return v * c[:, None] + np.cross(k, v) * s[:, None] + k * (k * v).sum(axis=1)[:, None] * (1.0 - c)[:, None]


def turned_up(t: np.ndarray, up_body: np.ndarray, bouts: list[tuple[float, np.ndarray]],
              reference: np.ndarray) -> np.ndarray:
    """Decision W566: ``up_body`` (n, 3) turned per sample by the smallest rotation taking the instant's upright
    (the ``bouts``' uprights interpolated linearly between their mid-times, held outside them) onto ``reference``."""
    mids = np.array([m for m, _ in bouts], dtype=float)
    ups = np.array([u for _, u in bouts], dtype=float)
    u = np.column_stack([np.interp(t, mids, ups[:, k]) for k in range(3)])
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    return turn_onto(up_body, u, reference)


def standing_around(t: np.ndarray, up_body: np.ndarray, still: np.ndarray, first_s: float, last_s: float,
                    gap_s: float) -> tuple[np.ndarray, np.ndarray] | None:
    """Decision W576: the up directions (normalised medians) of the still span that ends at most ``gap_s`` before
    ``first_s`` (the first walking bout's first contact) and of the one that starts at most ``gap_s`` after ``last_s``
    (the last bout's last contact); None when either is missing. ``still``: W277's per-sample mask."""
    t = np.asarray(t, dtype=float)
    before = after = None
    for a, b in runs(np.asarray(still, dtype=bool)):
        if t[b - 1] <= first_s and first_s - t[b - 1] <= gap_s:
            before = (a, b)  # the last one that qualifies
        if after is None and t[a] >= last_s and t[a] - last_s <= gap_s:
            after = (a, b)
    if before is None or after is None:
        return None
    idx = np.arange(t.size)
    s_b, s_a = (mean_direction(up_body, (idx >= a) & (idx < b)) for a, b in (before, after))
    return None if s_b is None or s_a is None else (s_b, s_a)


def standing_follows(t: np.ndarray, up_body: np.ndarray, still: np.ndarray,
                     bouts: list[tuple[float, float, np.ndarray]], *, gap_s: float = 1.5) -> bool:
    """Decision W576: whether the quiet standing moved with the walking upright between the first and the last of
    ``bouts`` (:func:`walking_bouts`): the standing after the last bout lies nearer than half the walking drift to
    the standing before the first turned by the walking drift's rotation (:func:`turn_onto`). A slide of the unit
    on the belt moves every posture; a walking trunk's lean leaves the standing where it was. False without the two
    standing spans (:func:`standing_around`; ``gap_s`` 1.5 s: nearer to walking than the shortest sit-down, S95)."""
    if len(bouts) < 2:
        return False
    around = standing_around(t, up_body, still, bouts[0][0], bouts[-1][1], gap_s)
    if around is None:
        return False
    s_b, s_a = around
    u0, u1 = bouts[0][2], bouts[-1][2]
    drift = np.degrees(np.arccos(np.clip(u0 @ u1, -1.0, 1.0)))
    moved = turn_onto(s_b[None, :], u0[None, :], u1)[0]
    return bool(np.degrees(np.arccos(np.clip(moved @ s_a / np.linalg.norm(moved), -1.0, 1.0))) < 0.5 * drift)


def drift_imu(imu, event_s: np.ndarray, has_next: np.ndarray, *, correct: bool = True, standing: bool = False):
    """Decisions W565 / W566 / W576: ``(imu, line)``: the lower-back IMU the posture code reads and W565's line (None
    when the mount did not drift more than :data:`MOUNT_DRIFT_DEG`, or, with ``standing`` (W576), when the quiet
    standing did not follow the walking upright: :func:`standing_follows`). When it did and ``correct`` (decision
    W566, adopted: fresh users 16790-16819 with a drifting mount, misses + false transfers 6 -> 0; False, the
    measurement's baseline, is a keyword, not a module switch: W413), a copy whose ``up_body`` is :func:`turned_up`
    onto W102's whole-recording upright."""
    if imu.up_body is None:
        return imu, None
    walks = walking_bouts(imu.t, imu.up_body, event_s, has_next)
    bouts = [(0.5 * (a + b), u) for a, b, u in walks]
    deg = drift_deg(bouts)
    if not deg > MOUNT_DRIFT_DEG:
        return imu, None
    if standing and not standing_follows(imu.t, imu.up_body, still_mask(imu.gyr_nav, imu.fs), walks):
        return imu, None
    line = drift_message(deg, bouts, correct)
    if not correct:
        return imu, line
    ref = walking_upright(contact_directions(imu.t, imu.up_body, np.asarray(event_s, float)),
                          np.asarray(has_next, bool))
    return dataclasses.replace(imu, up_body=turned_up(imu.t, imu.up_body, bouts, ref)), line
