"""Involuntary trunk movements (chorea-like jerks) of the waist unit (decision S114).

Huntington's chorea moves the trunk in brief, irregular, non-rhythmic jerks, standing and walking. The model is the
session 48 trial's script (T2, ``chorea.py``; our assumptions, not from a seed): jerks start at random times (a
Poisson process of ``rate_hz``, each next jerk drawn after the previous one ends), standing or walking, and last
:data:`JERK_DURATION_S` each. A jerk is

* a tilt of the pelvis about a random axis (uniform on the sphere) in its own frame, the angle rising from 0 to
  the peak (``deg`` range) and back to 0 as a raised cosine, so the gyroscope sees one full sine of angular rate
  and the gravity direction in the unit's frame turns with the tilt (the rigid body's pose is rotated; the unit's
  readings follow from the pose, :func:`pdrlearn.sim.simulate._unit_motion`);
* a vertical displacement (``m`` range, up or down with equal chance) of the same raised-cosine shape, which the
  accelerometer sees as a bump.

Only the waist unit moves: the feet do not step, so ``steps.csv`` / ``ics.csv`` are the walk's. The session gets
``trunk_jerks.csv`` (start_s, end_s, peak_deg, bump_m) on the foot clock.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError

#: decision S114: the duration range of one jerk (s): the trial's 0.3-0.8 s trunk tilts (T2)
JERK_DURATION_S = (0.3, 0.8)
#: decision S114: the default peak tilt (deg) and vertical bump (m) ranges: the trial's 4-12 deg and 1.5-4 cm (T2)
JERK_DEG = (4.0, 12.0)
JERK_M = (0.015, 0.04)
#: decision S114: the largest rate (jerks per second; ours: at 3/s the 0.3-0.8 s jerks nearly fill the time)
JERK_RATE_MAX_HZ = 3.0
#: decision S114: the largest peak tilt (deg) and bump (m) a session may ask for (ours: beyond them it is a fall)
JERK_DEG_MAX = 45.0
JERK_M_MAX = 0.2


@dataclass(frozen=True)
class TrunkJerk:
    """One jerk: start (s), duration (s), rotation axis (unit vector, pelvis frame), peak tilt (rad), bump (m)."""

    start_s: float
    dur_s: float
    axis: tuple[float, float, float]
    peak_rad: float
    bump_m: float
    direction: tuple[float, float, float] = (0.0, 0.0, 1.0)  # the bump's direction (ENU): up or down


def check_jerk_options(rate_hz, deg, m) -> tuple[float, tuple[float, float], tuple[float, float]]:
    """The knobs ``trunk_jerk_rate_hz``, ``trunk_jerk_deg``, ``trunk_jerk_m`` checked (one line, decision S114)."""
    if isinstance(rate_hz, bool) or not isinstance(rate_hz, int | float | np.number) or not (
            math.isfinite(rate_hz) and 0.0 <= rate_hz <= JERK_RATE_MAX_HZ):
        raise DataError(f"simulate: trunk_jerk_rate_hz={rate_hz!r} must be 0 (none) to {JERK_RATE_MAX_HZ:g} jerks per "
                        "second (1 = about one trunk jerk a second)")
    out = []
    for name, v, top, unit in (("trunk_jerk_deg", deg, JERK_DEG_MAX, "deg"), ("trunk_jerk_m", m, JERK_M_MAX, "m")):
        try:
            lo, hi = (float(x) for x in v)
            ok = math.isfinite(lo) and math.isfinite(hi) and 0.0 <= lo <= hi <= top
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise DataError(f"simulate: {name}={v!r} must be two numbers LO <= HI from 0 to {top:g} {unit}")
        out.append((lo, hi))
    return float(rate_hz), out[0], out[1]


def draw_jerks(t0: float, t1: float, rate_hz: float, deg: tuple[float, float], m: tuple[float, float],
               rng: np.random.Generator) -> list[TrunkJerk]:
    """The jerks of a session spanning ``t0``-``t1`` (s): Poisson starts at ``rate_hz``, none overlapping, each
    ending at least 1 s before ``t1`` (the trial's script)."""
    jerks: list[TrunkJerk] = []
    if rate_hz <= 0:
        return jerks
    s = t0 + rng.exponential(1.0 / rate_hz)
    while True:
        dur = float(rng.uniform(*JERK_DURATION_S))
        if s + dur > t1 - 1.0:
            return jerks
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        peak = math.radians(float(rng.uniform(*deg)))
        bump = float(rng.uniform(*m))
        up = 1.0 if rng.random() < 0.5 else -1.0  # up or down with equal chance
        jerks.append(TrunkJerk(float(s), dur, tuple(float(a) for a in axis), peak, bump, (0.0, 0.0, up)))
        s += dur + rng.exponential(1.0 / rate_hz)


def jerk_motion(t: np.ndarray, jerks: list[TrunkJerk]) -> tuple[np.ndarray, np.ndarray]:
    """The jerks' tilt rotation vectors (n, 3; pelvis frame, rad) and displacements (n, 3; ENU, m) at times ``t``:
    raised cosines ``(1 - cos(2 pi u / dur)) / 2`` of each jerk's peak, ``u`` the time since its start."""
    rotvec = np.zeros((len(t), 3))
    dp = np.zeros((len(t), 3))
    for j in jerks:
        inside = (t >= j.start_s) & (t < j.start_s + j.dur_s)
        if not inside.any():
            continue
        shape = 0.5 * (1.0 - np.cos(2.0 * np.pi * (t[inside] - j.start_s) / j.dur_s))
        rotvec[inside] += np.outer(shape * j.peak_rad, j.axis)
        dp[inside] += np.outer(shape * j.bump_m, j.direction)
    return rotvec, dp


def jerk_pose(t: np.ndarray, p_pel: np.ndarray, rot: np.ndarray, jerks: list[TrunkJerk]
              ) -> tuple[np.ndarray, np.ndarray]:
    """The pelvis pose ``(p_pel, rot)`` with the jerks: ``rot`` turned in its own frame by the tilt, ``p_pel``
    moved by the bump."""
    if not jerks:
        return p_pel, rot
    rotvec, dp = jerk_motion(t, jerks)
    moving = np.any(rotvec != 0, axis=1) | np.any(dp != 0, axis=1)
    if not moving.any():
        return p_pel, rot
    p_pel, rot = p_pel.copy(), rot.copy()
    rot[moving] = rot[moving] @ Rotation.from_rotvec(rotvec[moving]).as_matrix()
    p_pel += dp
    return p_pel, rot


def jerk_table(jerks: list[TrunkJerk]) -> list[dict]:
    """Rows of ``trunk_jerks.csv``: start and end (s), peak tilt (deg) and vertical bump (m, + up, - down)."""
    return [{"start_s": round(j.start_s, 4), "end_s": round(j.start_s + j.dur_s, 4),
             "peak_deg": round(math.degrees(j.peak_rad), 3), "bump_m": round(j.bump_m * j.direction[2], 5)}
            for j in jerks]
