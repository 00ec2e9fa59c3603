"""A vehicle ride: the walker stands in a bus or a train that drives off, takes an S-bend and stops (decision S71).

The ``vehicle:SECONDS[:RMS]`` route item (:class:`pdrlearn.sim.path.Vehicle`) plans, like S45's lifts and escalators
(:mod:`pdrlearn.sim.ride`), a :class:`VehicleRide` inside the pause between two walking bouts: the feet are side by
side and at rest, no footstep happens, and the whole body is carried. The vehicle's speed along its path follows
S45's symmetric profile (:func:`pdrlearn.sim.ride.ride_distance`: a ``(1 - cos)`` rise to the cruise speed, cruise,
the same fall), the path an S-bend in the cruise (the heading turns left by ``bend_rad`` and back, C2, so the walker
faces the same way after the ride and the next bout's planned steps only move by the ride's displacement), and the
floor vibrates (vertical band-limited "body bounce", fore-aft at half its RMS). The carried pose is a rigid motion:
the walker turns with the vehicle about the point they stand on (the gyroscopes read the vehicle's yaw rate, the
accelerometers its longitudinal, lateral and vertical accelerations).

Truth (S71): the trajectories follow the vehicle (they carry the ride, as S45's), ``rides.csv`` has a ``vehicle`` row
with its displacement, and ``steps.csv`` / ``ics.csv`` / the summary's ``distance_m`` are the walked ones: no step,
no contact and no walked metre during the ride.

Values (assumptions, not from a seed): peak longitudinal acceleration 0.5-1.5 m/s^2 (the brief's range for buses and
trams pulling off and braking), cruise 6-14 m/s (22-50 km/h, urban), an S-bend of 15-45 deg per side with a peak
lateral acceleration of 0.5-1.5 m/s^2; vertical vibration 0.3-1.0 m/s^2 RMS drawn per ride (ISO 2631-1:1997's
comfort scale, as recalled and not checked against the text: 0.315-0.63 m/s^2 "a little uncomfortable", 0.5-1
"fairly uncomfortable", the range public transport is usually reported in) in 1-3 Hz (a bus body's bounce on its
suspension, about 1-2 Hz, as recalled; our choice of band).

Decision S75 (opt-in, ``vehicle:S:RMS:RISE``): the vehicle climbs (RISE > 0) or descends RISE m in the middle of its
cruise, a C2 (quintic) ramp of its altitude along the path at a peak road grade drawn in :data:`VEHICLE_GRADE` (a
bus going up a street or a ramp), so the barometer sees a short smooth climb while the walker stands. The body is
carried up, not pitched with the road (a standing passenger keeps upright; the grade's 2-5 deg are left out).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.settings import is_number
from pdrlearn.sim.kernels import smoothstep
from pdrlearn.sim.ride import RIDE_SWAY_HZ, ride_distance
from pdrlearn.sim.transfer import _bell

VEHICLE_ACC_MPS2 = (0.5, 1.5)  # peak longitudinal acceleration / braking (brief's range; assumption)
VEHICLE_SPEED_MPS = (6.0, 14.0)  # cruise speed, 22-50 km/h (assumption: urban bus / tram)
VEHICLE_BEND_DEG = (15.0, 45.0)  # each half of the S-bend turns this far (assumption)
VEHICLE_LAT_MPS2 = (0.5, 1.5)  # peak lateral acceleration in the bend (assumption, as the longitudinal)
VEHICLE_VIB_RMS_MPS2 = (0.3, 1.0)  # vertical vibration RMS drawn per ride (ISO 2631-1 comfort scale, as recalled)
VEHICLE_VIB_HZ = (1.0, 3.0)  # the vibration's band: a bus body's bounce (as recalled; our choice)
VEHICLE_VIB_FORE_AFT = 0.5  # fore-aft vibration RMS as a fraction of the vertical (T1's recipe; assumption)
VEHICLE_VIB_TONES = 8  # the band is a sum of this many sinusoids of random frequency and phase
VEHICLE_VIB_FADE_S = 1.0  # the vibration fades in over the first and out over the last second of the motion
VEHICLE_MIN_S = 20.0  # shortest ride accepted (s): a stop-to-stop hop
VEHICLE_MAX_S = 3600.0  # longest ride accepted (s)
#: decision S75: peak road grade of a vehicle's climb, drawn (assumption: urban streets and ramps, 3-8 %)
VEHICLE_GRADE = (0.03, 0.08)
#: decision S75: the steepest grade a climb may need to fit in the cruise (a steep street; assumption)
VEHICLE_MAX_GRADE = 0.2
#: decision S75: the largest climb accepted (m): a hill street, far above a ride's half storey
VEHICLE_MAX_RISE_M = 100.0
#: decision S75: the quintic ramp's (:func:`smoothstep`) peak slope per unit of its argument: 15 / 8
_RAMP_SLOPE = 1.875
VEHICLE_MAX_RMS_MPS2 = 3.0  # highest vibration RMS accepted (m/s^2; ISO 2631-1's "extremely uncomfortable" > 2)
#: the C2 bell 0 -> 1 -> 0 of the bend's heading (:func:`_bell`) has a slope of at most 3.75 per unit of its argument
_BELL_SLOPE = 3.75
_GRID_M = 0.05  # the path's positions are integrated on this grid of distance along it (m)


def check_vehicle(duration_s: float, rms: float | None, what: str, rise_m: float = 0.0) -> None:
    """One :class:`DataError` line naming ``what`` when the ride's duration, vibration RMS or climb (S75) is out of
    range."""
    if not (is_number(duration_s) and VEHICLE_MIN_S <= duration_s <= VEHICLE_MAX_S):
        raise DataError(f"{what}: a vehicle ride lasts {VEHICLE_MIN_S:g}-{VEHICLE_MAX_S:g} s (drive off, cruise with "
                        f"a bend, stop; decision S71), not {duration_s!r}")
    if rms is not None and not (is_number(rms) and 0.0 <= rms <= VEHICLE_MAX_RMS_MPS2):
        raise DataError(f"{what}: the vibration RMS must be 0-{VEHICLE_MAX_RMS_MPS2:g} m/s^2 (public transport is "
                        f"usually 0.3-1; decision S71), not {rms!r}")
    if not (is_number(rise_m) and abs(rise_m) <= VEHICLE_MAX_RISE_M):
        raise DataError(f"{what}: a vehicle's climb RISE is -{VEHICLE_MAX_RISE_M:g} to +{VEHICLE_MAX_RISE_M:g} m "
                        f"(+ up, - down, 0 level; decision S75), not {rise_m!r}")


@dataclass(frozen=True)
class VehicleRide:
    """One vehicle ride after the first ``after`` footsteps of the plan (module docstring).

    ``duration_s``: from the start of the motion to the stop; ``heading_rad``: the vehicle's (and walker's) heading;
    ``centre``: the planned point (x, y) the walker stands on, about which the body turns with the vehicle;
    ``bend_rad``, ``bend_start_m``, ``bend_m``: the S-bend's turn each way, where it starts along the path and its
    length; ``vib_rms``: the vertical vibration's RMS (m/s^2); ``tones``: (frequency Hz, vertical phase, fore-aft
    phase) of each of the band's sinusoids; ``sway``: as :class:`pdrlearn.sim.ride.Ride`'s."""

    after: int
    delay_s: float
    duration_s: float
    heading_rad: float
    centre: tuple[float, float]
    speed_mps: float
    acc_mps2: float
    bend_rad: float
    bend_start_m: float
    bend_m: float
    vib_rms: float
    tones: tuple[tuple[float, float, float], ...]
    sway: tuple[float, float, float, float]
    kind: str = "vehicle"
    rise_m: float = 0.0
    climb_start_m: float = 0.0
    climb_m: float = 0.0

    @property
    def ramp_s(self) -> float:
        """Duration of the speed's rise (and of its fall), s (S45's profile)."""
        return math.pi * self.speed_mps / (2.0 * self.acc_mps2)

    @property
    def path_m(self) -> float:
        """Distance driven (m)."""
        return self.speed_mps * (self.duration_s - self.ramp_s)

    @functools.cached_property
    def _track(self) -> tuple[np.ndarray, np.ndarray]:
        """The path in the vehicle's start frame (x ahead, y left) on a grid of distance: (s, (n, 2))."""
        s = np.arange(0.0, self.path_m + 2 * _GRID_M, _GRID_M)
        th = self.heading_at(s)
        step = np.column_stack([np.cos(th), np.sin(th)])
        xy = np.vstack([[0.0, 0.0], np.cumsum(0.5 * (step[1:] + step[:-1]) * _GRID_M, axis=0)])  # trapezoids
        return s, xy

    def heading_at(self, s: np.ndarray) -> np.ndarray:
        """The vehicle's turn (rad, left +) from its start heading at the distance ``s`` along the path."""
        if self.bend_m <= 0 or self.bend_rad == 0:
            return np.zeros_like(np.asarray(s, float))
        return self.bend_rad * _bell((np.asarray(s, float) - self.bend_start_m) / self.bend_m)

    @property
    def displacement(self) -> np.ndarray:
        """ENU displacement of the whole ride (m)."""
        return self.carry(np.array([self.duration_s + 1.0]))[0][0]

    def _vibration(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vertical and fore-aft floor displacement (m) at ``tau`` s after the start (an acceleration of
        :attr:`vib_rms` RMS: each tone's amplitude a_k / (2 pi f_k)^2), faded in and out over
        :data:`VEHICLE_VIB_FADE_S`."""
        up, fwd = np.zeros(tau.size), np.zeros(tau.size)
        on = (tau > 0) & (tau < self.duration_s)
        if not on.any() or self.vib_rms <= 0:
            return up, fwd
        x = tau[on]
        fade = smoothstep(x / VEHICLE_VIB_FADE_S) * smoothstep((self.duration_s - x) / VEHICLE_VIB_FADE_S)
        a_k = self.vib_rms * math.sqrt(2.0 / len(self.tones))  # n tones of amplitude a_k: RMS a_k sqrt(n / 2)
        for f, p_up, p_fwd in self.tones:
            d = a_k / (2 * math.pi * f) ** 2 * fade
            up[on] += d * np.sin(2 * math.pi * f * x + p_up)
            fwd[on] += VEHICLE_VIB_FORE_AFT * d * np.sin(2 * math.pi * f * x + p_fwd)
        return up, fwd

    def carry(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The ride at ``tau`` s after its start: ENU offset (n, 3) of the standing point and the body's yaw (n,)
        about it (0 before the ride; after it, the whole displacement and no yaw)."""
        tau = np.asarray(tau, float)
        s = ride_distance(self, tau)  # S45's speed profile
        grid, xy = self._track
        x, y = np.interp(s, grid, xy[:, 0]), np.interp(s, grid, xy[:, 1])
        yaw = self.heading_at(s)
        up, fwd = self._vibration(tau)
        if self.rise_m and self.climb_m > 0:  # decision S75: the climb, a quintic ramp along the path
            up = up + self.rise_m * smoothstep((s - self.climb_start_m) / self.climb_m)
        x, y = x + fwd * np.cos(yaw), y + fwd * np.sin(yaw)
        c, sn = math.cos(self.heading_rad), math.sin(self.heading_rad)
        return np.column_stack([c * x - sn * y, sn * x + c * y, up]), yaw


def draw_vehicle(after: int, duration_s: float, rms: float | None, heading_rad: float, centre: np.ndarray,
                 rng: np.random.Generator, *, delay_s: float, rise_m: float = 0.0,
                 ranges: dict[str, tuple[float, float]] | None = None) -> VehicleRide:
    """A :class:`VehicleRide` of ``duration_s`` seconds with the module's ranges drawn from ``rng`` (``rms`` None:
    drawn from :data:`VEHICLE_VIB_RMS_MPS2`). The cruise speed is capped so that the ramps take at most half the
    ride, the bend's turn so that it fits in the cruise. Decision S75: ``rise_m`` != 0 climbs that far in the middle
    of the cruise at a peak grade drawn from :data:`VEHICLE_GRADE` (steeper when the cruise is too short for it; one
    :class:`DataError` line past :data:`VEHICLE_MAX_GRADE`). The draws are those of a level ride (the grade takes
    the one spare uniform), so a ride without a climb is unchanged. ``ranges`` (decision S99, a bicycle's): any of
    ``acc``, ``speed`` and ``rms`` in place of :data:`VEHICLE_ACC_MPS2`, :data:`VEHICLE_SPEED_MPS` and
    :data:`VEHICLE_VIB_RMS_MPS2` (the same draws)."""
    u = rng.uniform(0.0, 1.0, 10)
    ranges = {"acc": VEHICLE_ACC_MPS2, "speed": VEHICLE_SPEED_MPS, "rms": VEHICLE_VIB_RMS_MPS2, **(ranges or {})}

    def pick(rangeof: tuple[float, float], x: float) -> float:
        return rangeof[0] + x * (rangeof[1] - rangeof[0])

    acc = pick(ranges["acc"], u[0])
    speed = min(pick(ranges["speed"], u[1]), acc * duration_s / (2.0 * math.pi))  # ramp pi v / (2 a) <= T / 4
    lat = pick(VEHICLE_LAT_MPS2, u[2])
    bend = math.radians(pick(VEHICLE_BEND_DEG, u[3]))
    ramp_m = 0.5 * speed * math.pi * speed / (2.0 * acc)  # distance of the speed's rise: v T_a / 2
    cruise_m = speed * (duration_s - math.pi * speed / (2.0 * acc)) - 2.0 * ramp_m
    # peak curvature of the bend: bend * 3.75 / L; lateral acceleration v^2 x curvature
    bend = min(bend, 0.8 * cruise_m * lat / (_BELL_SLOPE * speed**2))
    bend_m = _BELL_SLOPE * bend * speed**2 / lat
    start = ramp_m + 0.5 * (cruise_m - bend_m)
    vib = pick(ranges["rms"], u[4]) if rms is None else float(rms)
    t_rng = np.random.default_rng(rng.integers(2**32))
    tones = tuple((float(f), float(a), float(b)) for f, a, b in zip(
        t_rng.uniform(*VEHICLE_VIB_HZ, VEHICLE_VIB_TONES), t_rng.uniform(0, 2 * math.pi, VEHICLE_VIB_TONES),
        t_rng.uniform(0, 2 * math.pi, VEHICLE_VIB_TONES), strict=True))
    sway = (2 * math.pi * u[5], 2 * math.pi * u[6], *(RIDE_SWAY_HZ[0] + u[7:9] * (RIDE_SWAY_HZ[1] - RIDE_SWAY_HZ[0])))
    climb_m = climb_start = 0.0
    if rise_m:  # decision S75: the climb's length along the path at the drawn peak grade, fitted in the cruise
        climb_m = min(_RAMP_SLOPE * abs(rise_m) / pick(VEHICLE_GRADE, u[9]), cruise_m)
        if _RAMP_SLOPE * abs(rise_m) / max(climb_m, 1e-9) > VEHICLE_MAX_GRADE + 1e-9:
            raise DataError(f"vehicle ride of {duration_s:g} s climbing {rise_m:+g} m: its cruise ({cruise_m:.0f} m) "
                            f"is too short for a grade of at most {VEHICLE_MAX_GRADE:.0%}; give a longer ride or a "
                            "smaller climb (decision S75)")
        climb_start = ramp_m + 0.5 * (cruise_m - climb_m)
    return VehicleRide(int(after), float(delay_s), float(duration_s), float(heading_rad),
                       (float(centre[0]), float(centre[1])), float(speed), float(acc), float(bend), float(start),
                       float(bend_m), float(vib), tones, tuple(float(v) for v in sway), rise_m=float(rise_m),
                       climb_start_m=float(climb_start), climb_m=float(climb_m))


def vehicle_carry(t: np.ndarray, pos: np.ndarray, rot: np.ndarray, rides: list, starts: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Positions (n, 3) and orientations (n, 3, 3) of a unit at times ``t`` carried by the :class:`VehicleRide` s
    among ``rides`` (started at ``starts``; S45's lifts and escalators are :func:`pdrlearn.sim.ride.ride_offset`'s):
    turned with the vehicle about the planned standing point, then moved by the rides' offsets (the sum of the rides
    begun; at most one turns at a time)."""
    moved = np.zeros_like(pos)
    for ride, t0 in zip(rides, starts, strict=True):
        if not isinstance(ride, VehicleRide):
            continue
        tau = t - t0
        if not (tau > 0).any():
            continue
        off, yaw = ride.carry(tau)
        moved += off
        turning = yaw != 0
        if turning.any():  # about the planned standing point (the other rides' offsets are constant meanwhile)
            c, s = np.cos(yaw[turning]), np.sin(yaw[turning])
            rz = np.zeros((int(turning.sum()), 3, 3))
            rz[:, 0, 0], rz[:, 0, 1], rz[:, 1, 0], rz[:, 1, 1], rz[:, 2, 2] = c, -s, s, c, 1.0
            centre = np.array([*ride.centre, 0.0])
            pos, rot = pos.copy(), rot.copy()
            pos[turning] = centre + np.einsum("nij,nj->ni", rz, pos[turning] - centre)
            rot[turning] = rz @ rot[turning]
    return pos + moved, rot
