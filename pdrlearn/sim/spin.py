"""A slow turn on the spot without a step of the tracked foot: the body spins on it (decision S106).

The ``spin:DEG:SECONDS`` route item (:class:`pdrlearn.sim.path.Spin`) plans, like S45's rides
(:mod:`pdrlearn.sim.ride`), a :class:`SpinEpisode` inside the pause between two walking bouts: the feet are side by
side and at rest, and the whole body turns DEG degrees (> 0 left) about the vertical through the instrumented foot's
unit, which stays planted (its position does not move; it only rotates about the vertical at the body's rate). The
turn follows a C2 quintic ramp (:func:`pdrlearn.sim.kernels.smoothstep`) over SECONDS, so the yaw rate peaks at
:data:`SPIN_PEAK_FACTOR` x DEG / SECONDS. The lower back yaws with the body (it circles the planted foot by the
half step width); the other foot is carried round the planted one on the same rigid turn, with no step of its own
(decision S106: no shuffle - the other foot carries no unit, and shuffle steps would add contacts the lower back's
step detector may count, mixing a stepping turn into the stepless one this item exists to measure).

Unlike a vehicle's S-bend (S71), the turn stays: the walker faces DEG further after it, and everything the planner
lays out afterwards (in its own frame, which does not know the spin) is turned by it about the planted foot
(:func:`spin_carry`). Truth: the trajectories carry the turn (``trajectory.csv``'s ``heading_rad`` turns by DEG),
``spins.csv`` has one row per spin (start, end, angle, peak rate); ``steps.csv``'s strides are the walked
ones (a stride's ``heading_change_deg`` is its own, footprint to footprint, without the spin before it).

Values (assumptions, not from a seed): a spin lasts :data:`SPIN_S` seconds and turns at most
:data:`SPIN_MAX_DEG`; its peak rate is at most :data:`SPIN_MAX_PEAK_DPS` (a turn on planted feet that fast would be
a jump).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.settings import is_number
from pdrlearn.sim.kernels import smoothstep

#: decision S106: the quintic ramp's (:func:`smoothstep`) peak slope per unit of its argument: 15 / 8
SPIN_PEAK_FACTOR = 1.875
#: decision S106: a spin's duration range (s): from a quick turn on the spot to a very slow one (assumption)
SPIN_S = (1.0, 120.0)
#: decision S106: the largest turn of one spin (deg; a full turn on the spot)
SPIN_MAX_DEG = 360.0
#: decision S106: the largest peak yaw rate of a spin (deg/s; assumption: faster than a walker's turn on the spot)
SPIN_MAX_PEAK_DPS = 400.0
#: decision S106: standing still before and after a spin (s), as a ride's margin (S45)
SPIN_MARGIN_S = 1.0


def check_spin(angle_deg: float, duration_s: float, what: str) -> None:
    """One :class:`DataError` line naming ``what`` when ``angle_deg`` / ``duration_s`` are not a spin's (S106)."""
    if not (is_number(angle_deg) and math.isfinite(angle_deg) and 0 < abs(angle_deg) <= SPIN_MAX_DEG):
        raise DataError(f"{what}: a spin turns a non-zero angle of at most {SPIN_MAX_DEG:g} deg (+ left, - right; "
                        f"decision S106), not {angle_deg!r}, e.g. 'spin:180:10'")
    lo, hi = SPIN_S
    if not (is_number(duration_s) and math.isfinite(duration_s) and lo <= duration_s <= hi):
        raise DataError(f"{what}: a spin lasts {lo:g}-{hi:g} s (decision S106), not {duration_s!r}, e.g. "
                        "'spin:180:10'")
    peak = SPIN_PEAK_FACTOR * abs(angle_deg) / duration_s
    if peak > SPIN_MAX_PEAK_DPS + 1e-9:
        least = SPIN_PEAK_FACTOR * abs(angle_deg) / SPIN_MAX_PEAK_DPS
        raise DataError(f"{what}: {abs(angle_deg):g} deg in {duration_s:g} s peaks at {peak:.0f} deg/s, over "
                        f"{SPIN_MAX_PEAK_DPS:g} deg/s (decision S106); give it at least {least:.2f} s")


@dataclass(frozen=True)
class SpinEpisode:
    """One spin after the first ``after`` footsteps of the plan, ``delay_s`` after the feet came to rest.

    ``angle_rad`` (> 0 left), ``duration_s``; ``feet``: foot -> (heel x, y, yaw) where each foot stands (the
    planner's frame), from which the simulator takes the instrumented foot's unit as the pivot."""

    after: int
    delay_s: float
    angle_rad: float
    duration_s: float
    feet: tuple[tuple[str, float, float, float], ...]
    kind: str = "spin"

    def foot(self, name: str) -> tuple[np.ndarray, float]:
        """Heel position (x, y) and yaw of the foot ``name`` during the spin (planner's frame)."""
        for f, x, y, yaw in self.feet:
            if f == name:
                return np.array([x, y]), yaw
        raise KeyError(name)

    def yaw(self, tau: np.ndarray) -> np.ndarray:
        """The body's turn (rad) ``tau`` s after the spin's start: 0 before, ``angle_rad`` after (C2 quintic)."""
        return self.angle_rad * smoothstep(np.asarray(tau, float) / self.duration_s)


def spin_carry(t: np.ndarray, pos: np.ndarray, rot: np.ndarray, spin: SpinEpisode, t0: float,
               centre: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Positions (n, 3) and orientations (n, 3, 3) of a unit at times ``t`` turned by the spin (started at ``t0``)
    about the vertical through ``centre`` (x, y): from its start on, and by the whole angle after it."""
    yaw = spin.yaw(t - t0)
    turning = yaw != 0
    if not turning.any():
        return pos, rot
    c, s = np.cos(yaw[turning]), np.sin(yaw[turning])
    rz = np.zeros((int(turning.sum()), 3, 3))
    rz[:, 0, 0], rz[:, 0, 1], rz[:, 1, 0], rz[:, 1, 1], rz[:, 2, 2] = c, -s, s, c, 1.0
    ctr = np.array([float(centre[0]), float(centre[1]), 0.0])
    pos, rot = pos.copy(), rot.copy()
    pos[turning] = ctr + np.einsum("nij,nj->ni", rz, pos[turning] - ctr)
    rot[turning] = rz @ rot[turning]
    return pos, rot


def spin_table(spins: list[SpinEpisode], starts: np.ndarray) -> list[dict]:
    """Rows of ``spins.csv`` (S106): start and end of the turn (s), its angle (deg, + left) and peak yaw rate
    (deg/s)."""
    return [{"start_s": float(t0), "end_s": float(t0 + sp.duration_s),
             "angle_deg": round(math.degrees(sp.angle_rad), 6),
             "peak_rate_dps": round(SPIN_PEAK_FACTOR * abs(math.degrees(sp.angle_rad)) / sp.duration_s, 6)}
            for sp, t0 in zip(spins, starts, strict=True)]
