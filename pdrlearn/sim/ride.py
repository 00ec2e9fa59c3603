"""Rides without steps: a lift or an escalator carries the standing walker (decision S45).

A :class:`Ride` is planned by the ``lift:H`` / ``escalator:H`` route items (:class:`pdrlearn.sim.path.Lift`,
:class:`pdrlearn.sim.path.Escalator`) between two walking bouts, like S36's transfers: the feet are side by side and
at rest, no footstep happens, and the whole body (both feet, the pelvis) is translated by the ride's displacement
:func:`ride_offset`, which is added to the planned poses (the planner's own positions stay those of the floor the
walker stands on: a step's length and height in ``steps.csv`` are the walked ones, the ride is in ``rides.csv`` and
in the trajectories). Only the waist gets a small postural sway while riding (standing passengers sway; the feet
stand on the floor).

The speed profile along the ride is symmetric: the speed rises as ``v (1 - cos(pi t / T_a)) / 2`` to its cruise
value ``v`` (peak acceleration ``a = pi v / (2 T_a)``), cruises, and falls the same way. Values (assumptions, not
from a seed): a lift's peak acceleration 0.5-1.0 m/s^2 and rated speed 1.0-2.5 m/s (the brief's ranges; passenger
lifts of low and mid-rise buildings), drawn per ride; a short ride does not reach the rated speed. An escalator moves
at 0.5 m/s (the usual nominal speed) on a 30 deg incline, with 0.8 m of horizontal run at each landing and 1 m
transition radii (EN 115-1's minima for 0.5 m/s as recalled, not checked against the text); boarding brings the
walker to the step's speed within ``ESCALATOR_BOARD_S``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.settings import is_number

#: standing still before a ride starts (doors closing, stepping on and settling) and after it ends (s)
RIDE_MARGIN_S = 1.0
LIFT_ACC_MPS2 = (0.5, 1.0)  # the peak acceleration / deceleration of a passenger lift (brief; assumption)
LIFT_SPEED_MPS = (1.0, 2.5)  # its rated speed (brief; assumption)
LIFT_MAX_RISE_M = 300.0  # the highest ride accepted (m; a skyscraper's express lift)
ESCALATOR_SPEED_MPS = 0.5  # nominal escalator speed (EN 115-1 allows up to 0.75 m/s at <= 30 deg; as recalled)
ESCALATOR_INCLINE_DEG = 30.0  # the common incline (brief; EN 115-1's maximum above 6 m rise, as recalled)
ESCALATOR_FLAT_M = 0.8  # horizontal run of the steps at each landing (EN 115-1 minimum at 0.5 m/s, as recalled)
ESCALATOR_RADIUS_M = 1.0  # radius of the transitions between the landings and the incline (as recalled)
ESCALATOR_BOARD_S = 0.8  # time to reach the steps' speed on boarding (and to stop on leaving; assumption)
ESCALATOR_MIN_RISE_M = 1.0  # lowest rise accepted (m): below, the transitions alone would climb it
ESCALATOR_MAX_RISE_M = 60.0  # the highest rise accepted (m; the deepest metro escalators)
#: the waist's postural sway while riding: amplitude (m) fore-aft and sideways, frequency range (Hz); quiet standing
#: sways the trunk by a few millimetres below 1 Hz (assumption)
RIDE_SWAY_M = 0.004
RIDE_SWAY_HZ = (0.2, 0.6)
#: decisions S71, S99: the kinds whose carry (turning the body with the path) is
#: :func:`pdrlearn.sim.vehicle.vehicle_carry`'s, not :func:`ride_offset`'s straight geometry
CARRIED_KINDS = ("vehicle", "cycle")


@dataclass(frozen=True)
class Ride:
    """One lift or escalator ride after the first ``after`` footsteps of the plan.

    It starts ``delay_s`` after the feet have come to rest following footstep ``after - 1`` (as
    :class:`pdrlearn.sim.transfer.Transfer`). ``rise_m`` > 0 up, < 0 down; ``heading_rad``: the horizontal direction
    of an escalator's travel; ``speed_mps`` the cruise speed, ``acc_mps2`` the peak acceleration;
    ``sway``: (fore-aft phase, sideways phase, fore-aft Hz, sideways Hz) of the waist's sway."""

    after: int
    delay_s: float
    kind: str  # "lift" | "escalator"
    rise_m: float
    heading_rad: float
    speed_mps: float
    acc_mps2: float
    sway: tuple[float, float, float, float]

    @property
    def path_m(self) -> float:
        """Distance travelled along the ride (m)."""
        if self.kind == "lift":
            return abs(self.rise_m)
        th, r = math.radians(ESCALATOR_INCLINE_DEG), ESCALATOR_RADIUS_M
        return 2 * ESCALATOR_FLAT_M + 2 * r * th + _incline_m(abs(self.rise_m))

    @property
    def ramp_s(self) -> float:
        """Duration of the speed's rise (and of its fall), s."""
        return math.pi * self.speed_mps / (2.0 * self.acc_mps2)

    @property
    def duration_s(self) -> float:
        """From the start of the motion to its end (s)."""
        return self.ramp_s + self.path_m / self.speed_mps

    @property
    def displacement(self) -> np.ndarray:
        """ENU displacement of the whole ride (m)."""
        return _geometry(self, np.array([self.path_m]))[0]


def check_rise(kind: str, rise_m: float, what: str) -> None:
    """One :class:`DataError` line naming ``what`` when ``rise_m`` is not a ride's rise: non-zero, finite, at most
    :data:`LIFT_MAX_RISE_M` (lift) or :data:`ESCALATOR_MIN_RISE_M`-:data:`ESCALATOR_MAX_RISE_M` (escalator)."""
    low, top = (0.0, LIFT_MAX_RISE_M) if kind == "lift" else (ESCALATOR_MIN_RISE_M, ESCALATOR_MAX_RISE_M)
    if not (is_number(rise_m) and math.isfinite(rise_m) and rise_m != 0 and low <= abs(rise_m) <= top):
        ride = "a lift" if kind == "lift" else "an escalator"
        raise DataError(f"{what}: {ride} ride's rise must be a non-zero number of metres up to {top:g}"
                        + (f", at least {low:g}" if low else "") + f" (+H up, -H down), not {rise_m!r}")


def escalator_travel_m(rise_m: float) -> float:
    """Decision S129: the horizontal travel (m) of an escalator ride rising ``rise_m`` (either sign): the
    :data:`ESCALATOR_INCLINE_DEG` incline plus the two landings' :data:`ESCALATOR_FLAT_M` runs and the
    :data:`ESCALATOR_RADIUS_M` transitions (5 m: 10.8 m, 24.9 deg overall; ``rise / tan 30 deg`` alone is 8.7 m)."""
    th, r = math.radians(ESCALATOR_INCLINE_DEG), ESCALATOR_RADIUS_M
    return 2 * ESCALATOR_FLAT_M + 2 * r * math.sin(th) + _incline_m(abs(rise_m)) * math.cos(th)


def _incline_m(rise: float) -> float:
    th, r = math.radians(ESCALATOR_INCLINE_DEG), ESCALATOR_RADIUS_M
    return (rise - 2.0 * r * (1.0 - math.cos(th))) / math.sin(th)


def draw_ride(after: int, kind: str, rise_m: float, heading_rad: float, rng: np.random.Generator, *,
              delay_s: float = RIDE_MARGIN_S) -> Ride:
    """A :class:`Ride` with the module's ranges drawn from ``rng`` (a lift's acceleration and rated speed, capped
    so that the ride reaches it; the sway's phases and frequencies)."""
    u = rng.uniform(0.0, 1.0, 6)
    if kind == "lift":
        acc = LIFT_ACC_MPS2[0] + u[0] * (LIFT_ACC_MPS2[1] - LIFT_ACC_MPS2[0])
        rated = LIFT_SPEED_MPS[0] + u[1] * (LIFT_SPEED_MPS[1] - LIFT_SPEED_MPS[0])
        # the ramps up and down cover v * T_a = pi v^2 / (2 a) metres: a short ride peaks below the rated speed
        speed = min(rated, math.sqrt(2.0 * acc * abs(rise_m) / math.pi))
    else:
        speed = ESCALATOR_SPEED_MPS
        acc = math.pi * speed / (2.0 * ESCALATOR_BOARD_S)
    sway = (2 * math.pi * u[2], 2 * math.pi * u[3], *(RIDE_SWAY_HZ[0] + u[4:6] * (RIDE_SWAY_HZ[1] - RIDE_SWAY_HZ[0])))
    return Ride(int(after), float(delay_s), kind, float(rise_m), float(heading_rad), float(speed), float(acc),
                tuple(float(v) for v in sway))


def ride_distance(ride: Ride, tau: np.ndarray) -> np.ndarray:
    """Distance (m) along the ride ``tau`` seconds after its start (0 before, the whole path after)."""
    v, ta, total = ride.speed_mps, ride.ramp_s, ride.path_m

    def ramp(x: np.ndarray) -> np.ndarray:  # distance of the speed's rise, x in [0, T_a]
        return 0.5 * v * (x - ta / math.pi * np.sin(math.pi * x / ta))

    tau = np.clip(tau, 0.0, ride.duration_s)
    end = ride.duration_s
    return np.where(tau < ta, ramp(np.minimum(tau, ta)),
                    np.where(tau > end - ta, total - ramp(np.clip(end - tau, 0.0, ta)), 0.5 * v * ta + v * (tau - ta)))


def _geometry(ride: Ride, s: np.ndarray) -> np.ndarray:
    """ENU position (n, 3) at the distance ``s`` along the ride, from its start."""
    out = np.zeros((s.size, 3))
    sign = 1.0 if ride.rise_m > 0 else -1.0
    if ride.kind == "lift":
        out[:, 2] = sign * s
        return out
    th, r, flat = math.radians(ESCALATOR_INCLINE_DEG), ESCALATOR_RADIUS_M, ESCALATOR_FLAT_M
    arc, inc = r * th, _incline_m(abs(ride.rise_m))
    b = np.cumsum([flat, arc, inc, arc])  # ends of the landing, lower / upper transition, incline, transition
    h, z = np.array(s, float), np.zeros(s.size)
    # (horizontal, height) at the ends of the pieces
    h1, z1 = flat + r * math.sin(th), r * (1 - math.cos(th))
    h2, z2 = h1 + inc * math.cos(th), z1 + inc * math.sin(th)
    h3, z3 = h2 + r * math.sin(th), z2 + r * (1 - math.cos(th))
    m = (s > b[0]) & (s <= b[1])  # transition onto the incline: turning up by (s - flat) / r
    phi = (s[m] - b[0]) / r
    h[m], z[m] = flat + r * np.sin(phi), r * (1 - np.cos(phi))
    m = (s > b[1]) & (s <= b[2])
    h[m], z[m] = h1 + (s[m] - b[1]) * math.cos(th), z1 + (s[m] - b[1]) * math.sin(th)
    m = (s > b[2]) & (s <= b[3])  # transition back to level
    phi = th - (s[m] - b[2]) / r
    h[m], z[m] = h2 + r * (math.sin(th) - np.sin(phi)), z2 + r * (np.cos(phi) - math.cos(th))
    m = s > b[3]
    h[m], z[m] = h3 + (s[m] - b[3]), z3
    out[:, 0], out[:, 1], out[:, 2] = h * math.cos(ride.heading_rad), h * math.sin(ride.heading_rad), sign * z
    return out


def ride_offset(t: np.ndarray, rides: list[Ride], starts: np.ndarray, *, sway: bool = False) -> np.ndarray:
    """The rides' ENU displacement (n, 3) at times ``t`` (the sum of the rides begun; a finished ride's whole
    displacement). ``sway``: add the waist's postural sway, faded in and out over the ride's ramps."""
    out = np.zeros((t.size, 3))
    for ride, t0 in zip(rides, starts, strict=True):
        tau = t - t0
        if not (tau > 0).any():
            continue
        if ride.kind not in CARRIED_KINDS:  # S71, S99: a vehicle's carry is pdrlearn.sim.vehicle.vehicle_carry's
            out += _geometry(ride, ride_distance(ride, tau))
        if sway:
            on = (tau > 0) & (tau < ride.duration_s)
            if on.any():
                x = tau[on]
                fade = np.sin(np.pi * x / ride.duration_s) ** 2  # C1 in and out: no jump in the acceleration
                p1, p2, f1, f2 = ride.sway
                fwd = RIDE_SWAY_M * fade * np.sin(2 * np.pi * f1 * x + p1)
                side = RIDE_SWAY_M * fade * np.sin(2 * np.pi * f2 * x + p2)
                c, s_ = math.cos(ride.heading_rad), math.sin(ride.heading_rad)
                out[on, 0] += c * fwd - s_ * side
                out[on, 1] += s_ * fwd + c * side
    return out


def ride_table(rides: list[Ride], starts: np.ndarray) -> list[dict]:
    """Rows of the ``rides`` label table: start and end of the motion (s), kind, ENU displacement (m), speed,
    peak acceleration."""
    rows = []
    for ride, t0 in zip(rides, starts, strict=True):
        d = ride.displacement
        rows.append({
            "start_s": float(t0),
            "end_s": float(t0 + ride.duration_s),
            "kind": ride.kind,
            "dx_m": round(float(d[0]), 6),
            "dy_m": round(float(d[1]), 6),
            "dz_m": round(float(d[2]), 6),
            "speed_mps": round(ride.speed_mps, 6),
            "acc_mps2": round(ride.acc_mps2, 6),
        })
    return rows
