"""A bicycle ride: the walker mounts, pedals seated on a saddle and rides off, then dismounts (decision S99).

The ``cycle:SECONDS`` route item (:class:`pdrlearn.sim.path.Cycle`) is planned as S71's vehicle ride
(:mod:`pdrlearn.sim.vehicle`: the pause between two walking bouts, the whole body carried along an S-bend at S45's
speed profile, no footstep, no contact), at a bicycle's speed, with two things a passenger does not do:

- the instrumented foot goes round the crank: its unit rises from the floor to the pedal circle and follows it
  (:data:`CRANK_M` radius, its lowest point :data:`PEDAL_LOW_M` above the floor) at the drawn cadence, the ankle
  pitching :data:`ANKLE_PITCH_DEG` (trial T3's crank model, as ``tests/test_pedal_s43_l611.py`` splices it); the
  insoles: the heel unloaded, the forefoot pressing on the downstroke;
- the pelvis is seated on the saddle: tilted forward by the drawn :data:`PELVIS_TILT_DEG` and rocking
  :data:`PELVIS_ROLL_DEG` in roll once per crank turn; its height is the standing one (a saddle set at about hip
  height; an assumption).

The foot and the pelvis move onto the bike over the first :data:`MOUNT_S` seconds of the motion and off it over the
last (a C2 ramp), and the crank turns at the cadence times that ramp, so the foot never jumps.

Truth (S99): ``rides.csv`` has a ``cycle`` row (start, end, displacement, cruise speed, peak acceleration) as a
vehicle's; ``steps.csv`` / ``ics.csv`` / ``distance_m`` are the walked ones, so a ride has no step, no contact and no
walked metre.

Values (assumptions, not from a seed): cruise 3.5-6.5 m/s (13-23 km/h, urban cycling), peak acceleration 0.3-1.0
m/s^2, cadence 60-90 rpm (recreational cycling, as recalled), crank 0.17 m (T3's; cranks are 165-175 mm), the road's
vertical vibration 0.2-0.6 m/s^2 RMS through the saddle in S71's 1-3 Hz band.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, fields

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.settings import is_number
from pdrlearn.sim.kernels import smoothstep
from pdrlearn.sim.vehicle import VEHICLE_MAX_S, VEHICLE_MIN_S, VehicleRide, draw_vehicle

CYCLE_SPEED_MPS = (3.5, 6.5)  # cruise speed, 13-23 km/h (assumption: urban cycling)
CYCLE_ACC_MPS2 = (0.3, 1.0)  # peak acceleration / braking (assumption)
CYCLE_VIB_RMS_MPS2 = (0.2, 0.6)  # the road's vertical vibration through the saddle (assumption)
CYCLE_CADENCE_RPM = (60.0, 90.0)  # crank turns a minute (recreational cycling, as recalled; assumption)
CRANK_M = 0.17  # crank radius (trial T3's crank model; cranks are 165-175 mm)
PEDAL_LOW_M = 0.10  # the pedal circle's lowest point above the floor: bottom bracket ~0.27 m less the crank
ANKLE_PITCH_DEG = 15.0  # the ankle's pitch swing on the pedal (trial T3's crank model)
ANKLE_PHASE_RAD = 0.8  # its lead on the crank angle (trial T3's crank model)
PELVIS_TILT_DEG = (10.0, 25.0)  # the pelvis's forward tilt seated on a saddle (assumption)
PELVIS_ROLL_DEG = 2.0  # the pelvis's roll rocking once per crank turn (assumption)
#: the forefoot's load at the downstroke's peak, as a fraction of its standing load (a quarter of the body weight,
#: body.foot_loads): a pedal force of about body weight / 4, ~170 N for 70 kg (assumption, as recalled for easy riding)
PEDAL_PRESS = 1.0
MOUNT_S = 2.0  # getting on (and off) the bike at the start (end) of the motion (assumption)


def check_cycle(duration_s: float, what: str) -> None:
    """One :class:`DataError` line naming ``what`` when the ride's duration is out of S71's range."""
    if not (is_number(duration_s) and VEHICLE_MIN_S <= duration_s <= VEHICLE_MAX_S):
        raise DataError(f"{what}: a bicycle ride lasts {VEHICLE_MIN_S:g}-{VEHICLE_MAX_S:g} s (mount, ride, "
                        f"dismount; decision S99), not {duration_s!r}")


@dataclass(frozen=True)
class CycleRide(VehicleRide):
    """A :class:`VehicleRide` on a bicycle (module docstring): ``cadence_hz`` crank turns a second, ``tilt_rad``
    the pelvis's forward tilt on the saddle."""

    kind: str = "cycle"
    cadence_hz: float = 1.25
    tilt_rad: float = math.radians(15.0)

    def mount(self, tau: np.ndarray) -> np.ndarray:
        """0 off the bike, 1 on it: a C2 ramp over the first and the last :data:`MOUNT_S` s of the motion."""
        tau = np.asarray(tau, float)
        return smoothstep(tau / MOUNT_S) * smoothstep((self.duration_s - tau) / MOUNT_S)

    def crank(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The mount ramp and the crank angle (rad; 0 at the bottom, turning back, up and forward) at ``tau``."""
        tau = np.asarray(tau, float)
        grid, turns = self._turns
        return self.mount(tau), 2 * math.pi * self.cadence_hz * np.interp(tau, grid, turns)

    @functools.cached_property
    def _turns(self) -> tuple[np.ndarray, np.ndarray]:
        """The integral of the ramp over the motion on a 200 Hz grid (trapezoids; the ramp's integral has no short
        closed form): every part of the simulator's grid gets the same angle at the same tau."""
        grid = np.linspace(0.0, self.duration_s, int(math.ceil(self.duration_s * 200)) + 1)
        eg = self.mount(grid)
        return grid, np.concatenate([[0.0], np.cumsum(0.5 * (eg[1:] + eg[:-1]) * np.diff(grid))])


def draw_cycle(after: int, duration_s: float, heading_rad: float, centre: np.ndarray, rng: np.random.Generator, *,
               delay_s: float) -> CycleRide:
    """A :class:`CycleRide` of ``duration_s`` s: S71's vehicle draws at the bicycle's ranges, then the cadence and
    the pelvis's tilt."""
    ride = draw_vehicle(after, duration_s, None, heading_rad, centre, rng, delay_s=delay_s,
                        ranges={"acc": CYCLE_ACC_MPS2, "speed": CYCLE_SPEED_MPS, "rms": CYCLE_VIB_RMS_MPS2})
    u = rng.uniform(0.0, 1.0, 2)
    rpm = CYCLE_CADENCE_RPM[0] + u[0] * (CYCLE_CADENCE_RPM[1] - CYCLE_CADENCE_RPM[0])
    tilt = PELVIS_TILT_DEG[0] + u[1] * (PELVIS_TILT_DEG[1] - PELVIS_TILT_DEG[0])
    base = {f.name: getattr(ride, f.name) for f in fields(VehicleRide) if f.name != "kind"}
    return CycleRide(**base, cadence_hz=rpm / 60.0, tilt_rad=math.radians(tilt))


def _cycling(t: np.ndarray, rides: list, starts: np.ndarray):
    """(ride, the samples of ``t`` inside its motion, the ramp and crank angle there) of each bicycle ride."""
    for ride, t0 in zip(rides, starts, strict=True):
        if not isinstance(ride, CycleRide):
            continue
        on = (t > t0) & (t < t0 + ride.duration_s)
        if on.any():
            yield ride, on, *ride.crank(t[on] - t0)


def cycle_foot(t: np.ndarray, rides: list, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The foot unit on the pedal at ``t`` (before the ride's carry): ENU position offset (n, 3) from its place on
    the floor and pitch (n,) rad about the unit (the sign of :func:`pdrlearn.sim.freeze.freeze_foot`'s)."""
    pos, pitch = np.zeros((t.size, 3)), np.zeros(t.size)
    for ride, on, e, phi in _cycling(t, rides, starts):
        fwd = -CRANK_M * np.sin(phi)  # bottom (0) -> back -> top (pi) -> front: the pedal's way round
        up = PEDAL_LOW_M + CRANK_M * (1.0 - np.cos(phi))
        pos[on, 0] += e * fwd * math.cos(ride.heading_rad)
        pos[on, 1] += e * fwd * math.sin(ride.heading_rad)
        pos[on, 2] += e * up
        pitch[on] += e * math.radians(ANKLE_PITCH_DEG) * np.sin(phi + ANKLE_PHASE_RAD)
    return pos, pitch


def cycle_loads(t: np.ndarray, heel: np.ndarray, toe: np.ndarray, rides: list, starts: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """The insoles' loads at ``t`` on the bike: the heel off the pedal, the forefoot pressing on the downstroke
    (the crank from the top, pi, through the front to the bottom) at up to :data:`PEDAL_PRESS` of its standing
    load."""
    heel, toe = heel.copy(), toe.copy()
    for _, on, e, phi in _cycling(t, rides, starts):
        press = PEDAL_PRESS * np.clip(-np.sin(phi), 0.0, None)
        heel[on] *= 1.0 - e
        toe[on] *= 1.0 - e + e * press
    return heel, toe


def cycle_pelvis(t: np.ndarray, rides: list, starts: np.ndarray) -> np.ndarray:
    """The pelvis's rotation (n, 3, 3) in its body frame on the saddle at ``t`` (identity off the bike): tilted
    forward (pitch about the left axis) and rocking in roll once per crank turn."""
    out = np.broadcast_to(np.eye(3), (t.size, 3, 3)).copy()
    for ride, on, e, phi in _cycling(t, rides, starts):
        p = e * ride.tilt_rad
        r = e * math.radians(PELVIS_ROLL_DEG) * np.sin(phi)
        cp, sp, cr, sr = np.cos(p), np.sin(p), np.cos(r), np.sin(r)
        ry = np.zeros((p.size, 3, 3))
        ry[:, 0, 0], ry[:, 0, 2], ry[:, 1, 1], ry[:, 2, 0], ry[:, 2, 2] = cp, sp, 1.0, -sp, cp
        rx = np.zeros((p.size, 3, 3))
        rx[:, 0, 0], rx[:, 1, 1], rx[:, 1, 2], rx[:, 2, 1], rx[:, 2, 2] = 1.0, cr, -sr, sr, cr
        out[on] = ry @ rx
    return out
