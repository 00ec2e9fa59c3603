"""Walking paths as segments, and the planner that turns them into footprints of both feet.

A path is a list of segments (:class:`Straight`, :class:`Curve`, :class:`Stairs`, :class:`Slope`, :class:`Backward`,
:class:`Turn`, :class:`Pivot`, :class:`Stand`, :class:`Sit`, :class:`Lift`, :class:`Escalator`, :class:`Trolley`,
:class:`Side`, :class:`Freeze`, :class:`Lie`, :class:`Spin`).
:func:`plan_footsteps` walks them with a user's step
length and returns one :class:`Footstep` per foot placement (heel position, heading, kind), alternating feet.
Walking bouts start and end with both feet side by side (gait initiation and a closing step).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.sim.cycle import check_cycle, draw_cycle
from pdrlearn.sim.freeze import FREEZE_MARGIN_S, FreezeEpisode, check_freeze, draw_freeze
from pdrlearn.sim.lying import BED_SIT_S, LyingEpisode, check_lie, draw_lying
from pdrlearn.sim.ride import RIDE_MARGIN_S, Ride, check_rise, draw_ride
from pdrlearn.sim.spin import SPIN_MARGIN_S, SpinEpisode, check_spin
from pdrlearn.sim.transfer import SIT_MARGIN_S, TRANSFER_S, Transfer, draw_transfer
from pdrlearn.sim.user import GAITS, SPEEDS, UserProfile, asymmetry_factor
from pdrlearn.sim.vehicle import check_vehicle, draw_vehicle


# -- segments --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Straight:
    """Walk straight ahead ``length_m`` metres with ``gait`` steps (short/normal/long); ``pace`` (slow/normal/fast,
    decision S88) this walk's own speed instead of the session's (None: the session's)."""

    length_m: float
    gait: str = "normal"
    pace: str | None = None


@dataclass(frozen=True)
class Curve:
    """Walk along an arc turning ``angle_rad`` (> 0 = left, counter-clockwise) with ``radius_m``."""

    angle_rad: float
    radius_m: float
    gait: str = "normal"


@dataclass(frozen=True)
class Stairs:
    """Climb (``up=True``) or descend ``n`` stairs of ``rise_m`` x ``run_m``, one stair per step (step over step,
    a stride spans two stairs). ``step_to_step`` (decision S80): both feet on each stair, the same foot leading every
    stair, so a stride spans one stair (the non-reciprocal gait of frail older adults). ``lead`` (decision S92): the
    foot that leads every stair of a step-to-step flight ("left" / "right"; None: the foot that would step next, as
    before S92). ``pace`` (decision S101): the flight's own pace - a word of S88's (slow / normal / fast: the
    flight's speed instead of the session's, as a Straight's) or a number F, each stair step taking F times the
    session's level step time (within :data:`STAIR_PACE_RANGE`); None: the session's speed. The stair fixes the
    step's length, so a pace changes only its time."""

    n: int
    up: bool = True
    rise_m: float = 0.17
    run_m: float = 0.28
    step_to_step: bool = False
    lead: str | None = None
    pace: str | float | None = None


#: decision S101: the step-time factor a stair flight's numeric pace may take (an assumption: from twice as brisk
#: to four times the level step, a patient with crutches resting on each stair being the slow end; no seed gives a
#: stair step time)
STAIR_PACE_RANGE = (0.5, 4.0)


def stair_pace_error(pace: object) -> str | None:
    """Decision S101: why ``pace`` is not a stair flight's pace (an S88 word or a factor within
    :data:`STAIR_PACE_RANGE`), or None."""
    if pace is None or pace in SPEEDS:
        return None
    lo, hi = STAIR_PACE_RANGE
    if isinstance(pace, int | float) and not isinstance(pace, bool) and math.isfinite(pace) and lo <= pace <= hi:
        return None
    return (f"a stair pace must be one of {', '.join(SPEEDS)} or a step-time factor within {lo:g}-{hi:g} x the level "
            f"step (decision S101), not {pace!r}")


#: decision B347: the stair rise (m) the simulator accepts: building codes give 0.10-0.22 m (IBC 2018 sec. 1011.5.2:
#: risers 4-7 in = 0.102-0.178 m; IRC 2018 R311.7.5.1: at most 7.75 in = 0.197 m; UK Approved Document K 2013
#: Table 1.1: 150-220 mm), widened to half the lowest (a half stair per contact, the step-to-like imitation of
#: decision L314's ``up:34:0.085:0.14``) and twice the highest (a skipped stair in one step, trial T3's
#: ``up:1:0.34:0.58``)
STAIR_RISE_RANGE_M = (0.05, 0.44)
#: decision B347: the stair going (tread, m) accepted: codes give 0.22-0.43 m (IBC 2018 sec. 1011.5.2: at least 11 in
#: = 0.279 m; IRC 2018 R311.7.5.2: at least 10 in = 0.254 m; UK Approved Document K 2013 Table 1.1: 220-425 mm),
#: widened the same way (half of 0.22 m: L314's 0.14 m per contact; twice 0.43 m: a skipped stair); a 0.10 m tread
#: is shorter than half a shoe (trial T3 finding 5)
STAIR_GOING_RANGE_M = (0.11, 0.86)


def stair_size_error(rise_m: float | None, run_m: float | None) -> str | None:
    """Decision B347: why a stair of ``rise_m`` x ``run_m`` (m; None: not checked) is not one the simulator walks -
    outside :data:`STAIR_RISE_RANGE_M` / :data:`STAIR_GOING_RANGE_M`, naming the range and, for a value that reads
    as centimetres (1 or more, whose hundredth is inside the range), the metres it meant - or None."""
    for what, value, (lo, hi) in (("rise", rise_m, STAIR_RISE_RANGE_M), ("going (tread)", run_m, STAIR_GOING_RANGE_M)):
        if value is None or lo <= value <= hi:
            continue
        msg = (f"a stair's {what} of {value:g} m is outside {lo:g}-{hi:g} m (metres; building codes give a rise of "
               "0.10-0.22 m and a going of 0.22-0.43 m, widened to half a stair and to a skipped stair; "
               "decision B347)")
        if value >= 1 and lo <= value / 100 <= hi:
            msg += f": {value:g} looks like centimetres - write {value / 100:g}"
        elif what == "rise" and 0 < value < lo:
            msg += ": for a gentle incline use slope:M:PCT (decision S37)"
        return msg
    return None


@dataclass(frozen=True)
class Slope:
    """Walk ``length_m`` metres (horizontal) straight ahead on a ramp of ``grade`` (rise / run; > 0 uphill,
    < 0 downhill) with level-walking steps (decision S37): each footprint is ``grade`` x its distance higher."""

    length_m: float
    grade: float
    gait: str = "normal"
    pace: str | None = None  # decision S121: the slope's own pace (as a Straight's, S88), None: the session's


def grade_speed_ratio(grade: float) -> float:
    """Decision S121: the walking speed on a ramp of ``grade`` (rise / run) over the level speed - Tobler's hiking
    function ``6 exp(-3.5 |g + 0.05|)`` km/h (Tobler 1993, NCGIA technical report 93-1) over its value at 0: 1 on the
    level, the fastest (1.19) at -5 %, 0.42 at +25 %, 0.59 at -25 %."""
    return math.exp(-3.5 * (abs(grade + 0.05) - 0.05))  # Tobler 1993's hiking function, normalised to g = 0


def graded_step(grade: float) -> tuple[float, float]:
    """Decision S121: the (step length, step time) factors of a step on a ramp of ``grade``: the speed ratio
    :func:`grade_speed_ratio` split evenly, ``sqrt r`` and ``1 / sqrt r`` (the even split is a plain assumption)."""
    root = math.sqrt(grade_speed_ratio(grade))
    return root, 1.0 / root


@dataclass(frozen=True)
class Backward:
    """``n_steps`` backward steps (the body keeps facing forward). ``direct`` (decision S67): straight out of forward
    level walking, with no closing step and no pause - the foot that landed last steps back past the other one."""

    n_steps: int | float  # decision S89: a fraction is that share of the nominal backward step (0.5: half a step)
    direct: bool = False


@dataclass(frozen=True)
class Turn:
    """Turn ``angle_rad`` in place (> 0 = left) with stepping turns of at most 60 degrees each."""

    angle_rad: float


@dataclass(frozen=True)
class Pivot:
    """Turn ``angle_rad`` (> 0 = left) on the spot without stopping (decision S41): ``n_steps`` short steps inside
    the walk (no closing step, no pause; 0 = one step per :data:`PIVOT_STEP_RAD`), each moving the body centre
    ``step_m`` along its new heading. A real walker turning in place between two walks (HA001 Test11's turns)."""

    angle_rad: float
    n_steps: int = 0
    step_m: float = 0.15


@dataclass(frozen=True)
class Spin:
    """Decision S106: stop, then turn ``angle_rad`` (> 0 = left) on the spot in ``duration_s`` seconds without a
    step: the body spins about the instrumented foot, which stays planted (:mod:`pdrlearn.sim.spin`)."""

    angle_rad: float
    duration_s: float


@dataclass(frozen=True)
class InPlace:
    """Decision S105: ``n_steps`` steps on the spot (marking time): each foot lifts and is set down beside the other,
    alternating, with a turning step's kinematics (S9: a short, low swing) and no turn; the body does not move."""

    n_steps: int


@dataclass(frozen=True)
class Side:
    """Side-step ``length_m`` metres (> 0 = to the left, < 0 = to the right) facing ahead (decision S49): the lead
    foot steps sideways, the trail foot closes beside it; the heading does not change."""

    length_m: float


IRREGULAR_SHORTENING = 0.4  # an irregular step lands this fraction of a step short
MAX_TURN_STEP_RAD = math.pi / 3  # largest heading change of one stepping-turn step
#: decision S41: the heading change of one step of a :class:`Pivot` when its step count is not given: the real
#: turns on the spot of HA001 Test11 turn the pelvis 30-45 deg per step (experiments/waist_turn_spot.py)
PIVOT_STEP_RAD = math.pi / 4
#: decision S41: the largest body-centre displacement of one pivot step (m): a turn on the spot moves the body
#: 0.1-0.2 m per step; beyond this it is a curve (``Curve``)
PIVOT_MAX_STEP_M = 0.3
#: decision S49: a side step moves the lead foot (and, after the trail foot closed, the body) this fraction of the
#: user's forward step length sideways: 0.35-0.47 m for the drawn adults (0.64-0.86 m steps), inside the 0.3-0.5 m
#: of a comfortable lateral step (an assumption, not from a seed; the backward steps' 0.55 reused)
SIDE_STEP_FRACTION = 0.55
#: decision S49: standing pause (s) before and after a side-stepping stretch (a walker stops to side-step)
SIDE_PAUSE_S = 0.3
#: decision S37: the steepest ramp walked with level steps (30 %, 17 deg; steeper streets are climbed otherwise)
MAX_SLOPE_GRADE = 0.30


@dataclass(frozen=True)
class Stand:
    """Stand still, feet side by side, for ``duration_s`` seconds."""

    duration_s: float


@dataclass(frozen=True)
class Sit:
    """Stop, sit down on a chair, stay seated ``duration_s`` seconds, stand up (no footstep; decision S36)."""

    duration_s: float


@dataclass(frozen=True)
class Lift:
    """Stand in a lift that rides ``rise_m`` metres (> 0 up, < 0 down) without a step (decision S45,
    :mod:`pdrlearn.sim.ride`)."""

    rise_m: float


@dataclass(frozen=True)
class Escalator:
    """Stand on an escalator that rises ``rise_m`` metres (> 0 up, < 0 down) on a 30 deg incline straight ahead:
    horizontal and vertical travel without a step (decision S45, :mod:`pdrlearn.sim.ride`). Decision S129: the
    incline is 30 deg; the level landings' 0.8 m runs and the 1 m transitions add horizontal travel, so a 5 m rise
    travels 10.8 m ahead (24.9 deg overall, :func:`pdrlearn.sim.ride.escalator_travel_m`)."""

    rise_m: float


@dataclass(frozen=True)
class Vehicle:
    """Stand in a bus or train that drives ``duration_s`` seconds (drive off, an S-bend, stop) with a vertical
    vibration of ``rms_mps2`` m/s^2 RMS (None = drawn): carried without a step (decision S71,
    :mod:`pdrlearn.sim.vehicle`)."""

    duration_s: float
    rms_mps2: float | None = None
    rise_m: float = 0.0  # decision S75: the vehicle climbs this far (m, + up) in its cruise


@dataclass(frozen=True)
class Cycle:
    """Get on a bicycle, pedal seated on the saddle for ``duration_s`` seconds (ride off, an S-bend, stop) and get
    off: carried without a step, the instrumented foot going round the crank (decision S99,
    :mod:`pdrlearn.sim.cycle`)."""

    duration_s: float


@dataclass(frozen=True)
class Trolley:
    """Walk ``length_m`` metres straight ahead pushing a trolley (decision S46): the hands on the handle damp the
    pelvic rotation (:data:`pdrlearn.sim.body.PUSHING_ROTATION_GAIN`); the steps are level walking steps."""

    length_m: float
    gait: str = "normal"


@dataclass(frozen=True)
class Freeze:
    """Freezing of gait (decision S51, :mod:`pdrlearn.sim.freeze`): stop, tremble in place ``duration_s`` seconds at
    ``hz`` (3-8 Hz; None = drawn) with the foot's peak acceleration ``acc_mps2`` (None = drawn), no step."""

    duration_s: float
    hz: float | None = None
    acc_mps2: float | None = None


@dataclass(frozen=True)
class Lie:
    """Stop, sit down on the edge of a bed, lie down, lie ``duration_s`` seconds turning over ``turns_per_h`` times
    an hour (None = :data:`pdrlearn.sim.lying.TURNS_PER_H`), sit up and stand up (no footstep; decisions S58, S59)."""

    duration_s: float
    turns_per_h: float | None = None


Segment = (Straight | Curve | Stairs | Slope | Backward | Turn | Pivot | InPlace | Stand | Sit | Lift | Escalator
           | Trolley | Side | Freeze | Lie | Vehicle | Cycle | Spin)


@dataclass
class Footstep:
    """One foot placement: the foot lands with its heel at ``heel`` (ENU, m) facing ``yaw`` (rad)."""

    foot: str  # "left" | "right"
    heel: np.ndarray
    yaw: float
    kind: str  # walk | stairs_up | stairs_down | backward | turn | close | side
    gait: str = "normal"
    direction: str = "forward"
    pause_before_s: float = 0.0
    irregular: bool = False
    pushing: bool = False  # decision S46: a step of a Trolley walk (hands on a trolley's handle)
    pace: str | None = None  # decision S88: the step's own speed (a Straight's pace), None: the session's
    time_factor: float = 1.0  # decision S101: a stair flight's numeric pace, the step time's factor


def _normal(psi: float) -> np.ndarray:
    """Unit vector to the left of heading ``psi``."""
    return np.array([-math.sin(psi), math.cos(psi)])


def _ahead(psi: float) -> np.ndarray:
    return np.array([math.cos(psi), math.sin(psi)])


class _Walker:
    """Mutable planner state (the centre point between the heels, floor height, heading, feet)."""

    def __init__(
        self,
        user: UserProfile,
        speed: str,
        rng: np.random.Generator,
        heading0: float,
        irregular_rate: float,
        variability: float,
        length_asymmetry: float = 0.0,
        affected: str = "left",
        transfer_s: tuple[float, float] = TRANSFER_S,
    ):
        self.user, self.speed, self.rng = user, speed, rng
        self.transfer_s = transfer_s  # decision S95: the sitting-down / standing-up durations' range (s)
        self.length_asymmetry = length_asymmetry
        self.affected = affected  # decision S55: the foot whose steps are the long ones
        self.c = np.zeros(2)
        self.z = 0.0
        self.psi = heading0
        self.irregular_rate = irregular_rate
        self.var = user.variability * variability
        self.steps: list[Footstep] = []
        self.feet = {f: (self._heel(self.c, self.z, self.psi, f), self.psi) for f in ("left", "right")}
        self.together = True
        self.last_moved: str | None = None
        self.pending_pause = 0.0
        self.direction = "forward"
        self.transfers: list[Transfer | Ride | FreezeEpisode | LyingEpisode | SpinEpisode] = []
        self.pushing = False
        self.graded_slopes = False  # decision S121: a slope's steps with its grade's own length and time

    def _heel(self, c: np.ndarray, z: float, psi: float, foot: str) -> np.ndarray:
        side = 1.0 if foot == "left" else -1.0
        xy = c + side * 0.5 * self.user.step_width_m * _normal(psi)
        return np.array([xy[0], xy[1], z])

    def _next_foot(self, lead: str | None = None) -> str:
        if self.together:
            if lead is not None:
                return lead
            return "right" if self.last_moved in (None, "left") else "left"
        return "left" if self.last_moved == "right" else "right"

    def step(
        self,
        c: np.ndarray,
        z: float,
        psi: float,
        kind: str,
        *,
        gait: str = "normal",
        direction: str = "forward",
        foot: str | None = None,
        irregular: bool = False,
        pace: str | None = None,
        time_factor: float = 1.0,
    ) -> None:
        foot = foot or self._next_foot()
        heel = self._heel(c, z, psi, foot)
        if not self.together or kind != "close":
            # lateral placement variability
            heel[:2] += self.rng.normal(0.0, 0.01 * self.var / 0.03) * _normal(psi)
        self.steps.append(Footstep(foot, heel, float(psi), kind, gait, direction, self.pending_pause, irregular,
                                   self.pushing, pace, time_factor))
        self.pending_pause = 0.0
        self.feet[foot] = (heel, psi)
        self.last_moved = foot
        self.c, self.z, self.psi = np.asarray(c, float).copy(), z, psi
        self.together = kind == "close"

    def close(self, pause: float = 0.0) -> None:
        """Bring the trailing foot beside the leading one (closing step), then optionally pause."""
        if not self.together:
            trailing = "left" if self.last_moved == "right" else "right"
            kind = (
                "stairs_up"
                if self.feet[trailing][0][2] < self.z - 0.05
                else ("stairs_down" if self.feet[trailing][0][2] > self.z + 0.05 else "close")
            )
            self.step(self.c, self.z, self.psi, kind, foot=trailing, direction=self.direction)
            self.together = True
        self.pending_pause += pause

    def _change_direction(self, direction: str) -> None:
        if direction != self.direction:
            self.close(pause=0.6)
            self.direction = direction

    # -- segments ---------------------------------------------------------------------------------
    def _progress(self, length: float, nominal: float, asymmetric: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """Arc positions of the steps along a segment and which of them are irregular.

        An irregular step (stumble, hesitation) lands 40 % of a step short; the next step makes up for it.
        ``asymmetric``: the steps onto each foot get :func:`asymmetry_factor` of the walker's length asymmetry
        (decision S42), scaled so that the segment keeps its length.
        """
        n = max(1, int(round(length / nominal)))
        base = length / n
        s = base * np.arange(1, n + 1, dtype=float)
        if asymmetric and self.length_asymmetry:  # decision S42 (skipped at 0: default sessions bit for bit)
            first = self._next_foot()
            other = "left" if first == "right" else "right"
            inc = np.array([asymmetry_factor(first if j % 2 == 0 else other, self.length_asymmetry, self.affected)
                            for j in range(n)])
            s = np.cumsum(inc) * (length / inc.sum())
        s[:-1] += self.rng.normal(0.0, self.var * base, n - 1)
        irregular = np.zeros(n, dtype=bool)
        if self.irregular_rate > 0:
            irregular[:-1] = self.rng.random(n - 1) < self.irregular_rate
        s[irregular] -= IRREGULAR_SHORTENING * base
        return s, irregular

    def straight(self, seg: Straight) -> None:
        self._change_direction("forward")
        c0, u = self.c.copy(), _ahead(self.psi)
        pace = getattr(seg, "pace", None)  # decision S88: a Straight's own pace (a Trolley has none)
        for s, irr in zip(*self._progress(seg.length_m, self.user.step_length(pace or self.speed, seg.gait),
                                            True), strict=True):
            self.step(c0 + s * u, self.z, self.psi, "walk", gait=seg.gait, irregular=bool(irr), pace=pace)

    def curve(self, seg: Curve) -> None:
        self._change_direction("forward")
        if seg.radius_m <= 0:
            raise DataError(f"Curve radius {seg.radius_m} m: must be > 0 (use Turn for turning in place)")
        sigma = 1.0 if seg.angle_rad >= 0 else -1.0
        r, psi0 = seg.radius_m, self.psi
        centre = self.c + sigma * r * _normal(psi0)
        for s, irr in zip(
            *self._progress(abs(seg.angle_rad) * r, self.user.step_length(self.speed, seg.gait), True), strict=True
        ):
            psi = psi0 + sigma * s / r
            self.step(centre - sigma * r * _normal(psi), self.z, psi, "walk", gait=seg.gait, irregular=bool(irr))

    def stairs(self, seg: Stairs) -> None:
        self._change_direction("forward")
        if seg.n < 1 or seg.rise_m <= 0 or seg.run_m <= 0:
            raise DataError(f"{seg}: needs n >= 1, rise_m > 0 and run_m > 0")
        size = stair_size_error(seg.rise_m, seg.run_m)  # decision B347
        if size:
            raise DataError(f"{seg}: {size}")
        bad_pace = stair_pace_error(seg.pace)  # decision S101
        if bad_pace:
            raise DataError(f"{seg}: {bad_pace}")
        pace = {"pace": seg.pace} if isinstance(seg.pace, str) else {"time_factor": float(seg.pace or 1.0)}
        c0, z0, u = self.c.copy(), self.z, _ahead(self.psi)
        sign = 1.0 if seg.up else -1.0
        kind = "stairs_up" if seg.up else "stairs_down"
        if seg.lead is not None and not seg.step_to_step:
            raise DataError(f"{seg}: a leading foot is for step-to-step stairs (step over step, the feet alternate; "
                            "decision S92)")
        if seg.step_to_step:  # decision S80: the lead foot onto each stair, the trail foot beside it
            self.close()
            if seg.lead not in (None, "left", "right"):
                raise DataError(f"{seg}: lead must be 'left', 'right' or None (decision S92)")
            lead = self._next_foot(seg.lead)  # decision S92: the feet are together here, so the chosen foot leads
            trail = "left" if lead == "right" else "right"
            for j in range(1, seg.n + 1):
                c, z = c0 + j * seg.run_m * u, z0 + sign * j * seg.rise_m
                self.step(c, z, self.psi, kind, foot=lead, **pace)
                self.step(c, z, self.psi, kind, foot=trail, **pace)
            self.together = True  # both feet on the last stair
            return
        for j in range(1, seg.n + 1):
            self.step(c0 + j * seg.run_m * u, z0 + sign * j * seg.rise_m, self.psi, kind, **pace)

    def trolley(self, seg: Trolley) -> None:
        """Decision S46: a straight walk whose steps are flagged as pushing (the body model damps the pelvic
        rotation); the closing step that ends the segment's bout, if any, is not."""
        self.pushing = True
        try:
            self.straight(Straight(seg.length_m, seg.gait))
        finally:
            self.pushing = False

    def slope(self, seg: Slope) -> None:
        """Decision S37: level-walking steps whose footprints follow the ramp's height; the swing takes the
        geometric branch of the height change (toe-led rise or straight-line drop, :mod:`pdrlearn.sim.body`)
        and the foot lands level (a ramp's few-degree foot tilt is not modelled)."""
        self._change_direction("forward")
        if not (math.isfinite(seg.grade) and abs(seg.grade) <= MAX_SLOPE_GRADE):
            raise DataError(f"{seg}: grade must be finite and within +-{MAX_SLOPE_GRADE:g} (rise / run)")
        c0, z0, u = self.c.copy(), self.z, _ahead(self.psi)
        pace = getattr(seg, "pace", None)  # decision S121: a slope's own pace, as a Straight's (S88)
        if pace is not None and pace not in SPEEDS:
            raise DataError(f"{seg}: pace must be one of {', '.join(SPEEDS)} (or None: the session's speed)")
        f_len, f_time = graded_step(seg.grade) if self.graded_slopes else (1.0, 1.0)  # decision S121 (opt-in)
        nominal = self.user.step_length(pace or self.speed, seg.gait)
        for s, irr in zip(*self._progress(seg.length_m, nominal * f_len if self.graded_slopes else nominal, True),
                          strict=True):
            self.step(c0 + s * u, z0 + seg.grade * s, self.psi, "walk", gait=seg.gait, irregular=bool(irr),
                      pace=pace, time_factor=f_time)

    def backward(self, seg: Backward) -> None:
        reverse = self._reversal() if seg.direct else None  # decision S67
        if seg.direct and reverse is None and self.direction == "forward":  # decision S70: the stop it did not ask
            import logging  # for is said (after backward steps there is none: the walker goes on stepping back)

            logging.getLogger("pdrlearn.sim").warning(
                "simulate: backward:%g:direct %s: there is no forward level walking to reverse, so it starts as "
                "backward:%g does, with S64's stop (a closing step where the feet are apart, then 0.6 s still; "
                "decision S70)", seg.n_steps, self._no_reversal_why(), seg.n_steps)
        if reverse is None:
            self._change_direction("backward")
            c0, first = self.c.copy(), None
        else:
            c0, first = reverse
            self.direction = "backward"
        u = -_ahead(self.psi)
        nominal = 0.55 * self.user.step_length(self.speed)
        for j, s in enumerate(self._progress(seg.n_steps * nominal, nominal)[0]):
            self.step(c0 + s * u, self.z, self.psi, "backward", direction="backward", foot=first if j == 0 else None)

    def _reversal(self) -> tuple[np.ndarray, str] | None:
        """Decision S67: where a direct reversal's backward steps are measured from - the other foot's point on the
        walking line - and the foot that steps first (the one that landed last, in front); None unless the walker
        is mid-way through forward level walking (feet apart, last step a ``walk``): then S64's stop applies."""
        if self.direction != "forward" or self.together or not self.steps or self.steps[-1].kind != "walk":
            return None
        front = self.steps[-1].foot
        rear = "left" if front == "right" else "right"
        ahead = _ahead(self.psi)
        along = float(np.dot(self.feet[rear][0][:2] - self.c, ahead))  # the rear foot, on the walking line
        return self.c + along * ahead, front

    def _no_reversal_why(self) -> str:
        """Decision S70: where the walker is when :meth:`_reversal` finds no forward level walking to reverse."""
        if not self.steps:
            return "before any step"
        if self.together:
            return "after a stop (feet together: standing, a turn, a sit, a side step or a ride)"
        kind = self.steps[-1].kind
        return "after stairs" if kind.startswith("stairs") else f"after a {kind} step"

    def side(self, seg: Side) -> None:
        """Decision S49: stop, then per side step the lead foot (the left one going left) lands ``w`` sideways and
        the trail foot closes beside it, both facing the heading (kind ``side``, direction ``forward``: the body
        faces ahead and does not walk backward); ``w`` is :data:`SIDE_STEP_FRACTION` x the step length, with the
        forward steps' variability, the stretch keeping its length; then stop again."""
        self._change_direction("forward")
        if not (math.isfinite(seg.length_m) and seg.length_m != 0):
            raise DataError(f"{seg}: side-stepping needs a finite, non-zero distance (> 0 left, < 0 right)")
        self.close(pause=SIDE_PAUSE_S)
        sigma = 1.0 if seg.length_m > 0 else -1.0
        lead = "left" if sigma > 0 else "right"
        trail = "right" if lead == "left" else "left"
        c0, nrm = self.c.copy(), sigma * _normal(self.psi)
        nominal = SIDE_STEP_FRACTION * self.user.step_length(self.speed)
        for s in self._progress(abs(seg.length_m), nominal)[0]:
            self.step(c0 + s * nrm, self.z, self.psi, "side", foot=lead)
            self.step(c0 + s * nrm, self.z, self.psi, "side", foot=trail)
        self.together = True
        self.pending_pause += SIDE_PAUSE_S

    def turn(self, seg: Turn) -> None:
        self._change_direction("forward")
        if abs(seg.angle_rad) < 1e-6:
            return
        self.close(pause=0.3)
        n = max(1, math.ceil(abs(seg.angle_rad) / MAX_TURN_STEP_RAD - 1e-9))
        lead = "left" if seg.angle_rad > 0 else "right"
        psi0 = self.psi
        for k in range(1, n + 1):
            foot = lead if k % 2 == 1 else ("right" if lead == "left" else "left")
            self.step(self.c, self.z, psi0 + k * seg.angle_rad / n, "turn", foot=foot)
        self.close(pause=0.3)

    def pivot(self, seg: Pivot) -> None:
        """Decision S41: the turn's steps continue the walk's alternation (a walk-through turn, no stop); each
        moves the body centre ``step_m`` along the heading it turns to."""
        self._change_direction("forward")
        n = check_pivot(seg.angle_rad, seg.n_steps, seg.step_m, str(seg))
        psi0, c = self.psi, self.c.copy()
        for k in range(1, n + 1):
            psi = psi0 + k * seg.angle_rad / n
            c = c + seg.step_m * _ahead(psi)
            self.step(c, self.z, psi, "turn")

    def spin(self, seg: Spin) -> None:
        """Decision S106: feet together, then a :class:`SpinEpisode` inside the pause before the next step, with
        :data:`SPIN_MARGIN_S` of standing before and after it. The planner's heading and feet stay as they are: the
        spin turns everything after it (:func:`pdrlearn.sim.spin.spin_carry`)."""
        check_spin(math.degrees(seg.angle_rad) if math.isfinite(seg.angle_rad) else seg.angle_rad,
                   seg.duration_s, str(seg))
        self._change_direction("forward")
        self.close()
        feet = tuple((f, float(h[0]), float(h[1]), float(y)) for f, (h, y) in self.feet.items())
        self.transfers.append(SpinEpisode(len(self.steps), self.pending_pause + SPIN_MARGIN_S, float(seg.angle_rad),
                                          float(seg.duration_s), feet))
        self.pending_pause += SPIN_MARGIN_S + float(seg.duration_s) + SPIN_MARGIN_S

    def in_place(self, seg: InPlace) -> None:
        """Decision S105: the steps on the spot continue the walk's alternation (a walk that marks time, no stop);
        each sets the foot down where it stands beside the other, heading kept."""
        if not (isinstance(seg.n_steps, int | np.integer) and seg.n_steps >= 1):
            raise DataError(f"{seg}: n_steps must be a whole number >= 1")
        self._change_direction("forward")
        for _ in range(int(seg.n_steps)):
            self.step(self.c, self.z, self.psi, "turn")

    def stand(self, seg: Stand) -> None:
        self.close(pause=max(0.0, float(seg.duration_s)))

    def sit(self, seg: Sit) -> None:
        """Feet together, then a :class:`Transfer` inside the pause before the next step (decision S36)."""
        if not (math.isfinite(seg.duration_s) and seg.duration_s >= 0):
            raise DataError(f"{seg}: the seated time must be a finite number of seconds >= 0")
        self.close()
        tr = draw_transfer(len(self.steps), self.pending_pause + SIT_MARGIN_S, float(seg.duration_s), self.rng,
                           self.transfer_s)
        self.transfers.append(tr)
        self.pending_pause += SIT_MARGIN_S + tr.total_s + SIT_MARGIN_S

    def lie(self, seg: Lie) -> None:
        """Decisions S58, S59: feet together, then S36's :class:`Transfer` onto the bed edge whose seated time holds
        a :class:`LyingEpisode` (sit, lie down, lie turning over, sit up, sit), inside the pause before the next step.
        The transfer's draws come first, as a ``sit``'s, then the bed-edge sitting times and the lying's."""
        check_lie(float(seg.duration_s), seg.turns_per_h, str(seg))
        self.close()
        tr = draw_transfer(len(self.steps), self.pending_pause + SIT_MARGIN_S, 0.0, self.rng, self.transfer_s)
        before, after = (BED_SIT_S[0] + x * (BED_SIT_S[1] - BED_SIT_S[0]) for x in self.rng.uniform(0.0, 1.0, 2))
        ep = draw_lying(len(self.steps), tr.delay_s + tr.down_s + before, float(seg.duration_s), seg.turns_per_h,
                        tr.recline_rad, self.psi, self.rng)
        tr = replace(tr, seat_s=before + ep.total_s + after)
        self.transfers += [tr, ep]
        self.pending_pause += SIT_MARGIN_S + tr.total_s + SIT_MARGIN_S

    def freeze(self, seg: Freeze) -> None:
        """Decision S51: feet together, then a :class:`FreezeEpisode` (trembling, no step) inside the pause before
        the next step, with :data:`FREEZE_MARGIN_S` of standing before and after it."""
        check_freeze(seg.duration_s, seg.hz, seg.acc_mps2, str(seg))
        self.close()
        fz = draw_freeze(len(self.steps), float(seg.duration_s), seg.hz, seg.acc_mps2, self.psi, self.rng,
                         delay_s=self.pending_pause + FREEZE_MARGIN_S)
        self.transfers.append(fz)
        self.pending_pause += FREEZE_MARGIN_S + fz.duration_s + FREEZE_MARGIN_S

    def ride(self, seg: Lift | Escalator) -> None:
        """Decision S45: feet together, then a :class:`Ride` inside the pause before the next step; the planner's
        positions stay on the floor walked (the ride's displacement is added to the poses, ``ride.ride_offset``)."""
        kind = "lift" if isinstance(seg, Lift) else "escalator"
        check_rise(kind, seg.rise_m, str(seg))
        self.close()
        ride = draw_ride(len(self.steps), kind, float(seg.rise_m), self.psi, self.rng,
                         delay_s=self.pending_pause + RIDE_MARGIN_S)
        self.transfers.append(ride)
        self.pending_pause += RIDE_MARGIN_S + ride.duration_s + RIDE_MARGIN_S

    def vehicle(self, seg: Vehicle) -> None:
        """Decision S71: S45's ride (feet together, the ride inside the pause before the next step) in a vehicle,
        turning the walker about the point between the feet."""
        check_vehicle(seg.duration_s, seg.rms_mps2, str(seg), seg.rise_m)
        self.close()
        ride = draw_vehicle(len(self.steps), float(seg.duration_s), seg.rms_mps2, self.psi, self.c, self.rng,
                            delay_s=self.pending_pause + RIDE_MARGIN_S, rise_m=float(seg.rise_m))
        self.transfers.append(ride)
        self.pending_pause += RIDE_MARGIN_S + ride.duration_s + RIDE_MARGIN_S

    def cycle(self, seg: Cycle) -> None:
        """Decision S99: S71's vehicle ride (feet together, inside the pause before the next step) on a bicycle."""
        check_cycle(seg.duration_s, str(seg))
        self.close()
        ride = draw_cycle(len(self.steps), float(seg.duration_s), self.psi, self.c, self.rng,
                          delay_s=self.pending_pause + RIDE_MARGIN_S)
        self.transfers.append(ride)
        self.pending_pause += RIDE_MARGIN_S + ride.duration_s + RIDE_MARGIN_S


def check_pivot(angle_rad: float, n_steps: int, step_m: float, where: str, item: str | None = None) -> int:
    """Decision S41's limits of a :class:`Pivot`, its number of steps (``n_steps`` 0: one per
    :data:`PIVOT_STEP_RAD`), else one :class:`DataError` line starting ``where``. Decision S103: the route parser calls
    it with the route ``item`` (its own words, degrees), the planner with the segment; decision S104: a pivot turns at
    most :data:`MAX_TURN_STEP_RAD` per step (a spin inside one stride is ``curve:DEG:R`` with a small R)."""
    deg = math.degrees(angle_rad) if math.isfinite(angle_rad) else angle_rad
    if not (math.isfinite(angle_rad) and angle_rad != 0):
        raise DataError(f"{where}: a pivot needs a finite, non-zero angle")
    if not (math.isfinite(step_m) and 0 <= step_m <= PIVOT_MAX_STEP_M):
        raise DataError(f"{where}: the step must be 0-{PIVOT_MAX_STEP_M:g} m (a longer turning step is a "
                        f"{'curve' if item else 'Curve'}; decision S41)")
    n = int(n_steps) or max(1, math.ceil(abs(angle_rad) / PIVOT_STEP_RAD - 1e-9))
    if n < 1 or abs(angle_rad) / n > MAX_TURN_STEP_RAD + 1e-9:
        cap = math.degrees(MAX_TURN_STEP_RAD)
        least = max(1, math.ceil(abs(angle_rad) / MAX_TURN_STEP_RAD - 1e-9))
        fix = (f"use pivot:{deg:g}:{least} or more steps, or for a spin turning more per step curve:{deg:g}:0.3 "
               "(decision S104)" if item else f"n_steps >= {least}")
        raise DataError(f"{where}: a pivot turns at most {cap:.0f} deg per step ({abs(deg):g} deg in {n} step(s) "
                        f"is {abs(deg) / max(n, 1):.0f} deg per step); {fix}")
    return n


def path_length(segments: list[Segment], user: UserProfile | None = None) -> float:
    """Horizontal length (m) of the centre line of ``segments`` (backward steps at 0.55 step length); walked only:
    an escalator's horizontal travel is not counted (decision S45)."""
    total = 0.0
    for seg in segments:
        if isinstance(seg, Straight | Trolley):
            total += seg.length_m
        elif isinstance(seg, Curve):
            total += abs(seg.angle_rad) * seg.radius_m
        elif isinstance(seg, Stairs):
            total += seg.n * seg.run_m
        elif isinstance(seg, Slope):
            total += seg.length_m
        elif isinstance(seg, Pivot):
            total += (int(seg.n_steps) or max(1, math.ceil(abs(seg.angle_rad) / PIVOT_STEP_RAD - 1e-9))) * seg.step_m
        elif isinstance(seg, Side):  # decision S49: the body's sideways travel
            total += abs(seg.length_m)
        elif isinstance(seg, Backward) and user is not None:
            total += seg.n_steps * 0.55 * user.step_length_m
    return total


def plan_footsteps(
    segments: list[Segment],
    user: UserProfile,
    *,
    speed: str = "normal",
    rng: np.random.Generator,
    heading0_rad: float = 0.0,
    irregular_rate: float = 0.0,
    variability: float = 1.0,
    step_length_asymmetry: float = 0.0,
    paretic_side: str = "left",
    transfer_s: tuple[float, float] = TRANSFER_S,
    graded_slopes: bool = False,
) -> tuple[list[Footstep], dict, float, list[Transfer | Ride | FreezeEpisode | LyingEpisode | SpinEpisode]]:
    """Footprints of both feet along ``segments``.

    ``step_length_asymmetry``: on level, curved and sloped walking the steps onto the ``paretic_side`` foot (default
    left, decision S55) are 1 + this times the steps onto the other, the segment's length and number of steps
    unchanged (decision S42). ``transfer_s``: the range (s) each sitting-down and standing-up duration is drawn from
    (decision S95). ``graded_slopes`` (decision S121): a :class:`Slope`'s steps take :func:`graded_step`'s length and
    time factors for its grade (False: S37's level steps).

    Returns
    -------
    steps : the footprints in temporal order (alternating feet within a bout)
    initial : foot -> (heel position, yaw) before the first step
    end_pause_s : standing (or sitting) time requested after the last step (trailing :class:`Stand` / :class:`Sit`)
    transfers : the episodes inside the pauses: sit-down / stand-up of :class:`Sit` segments
        (:mod:`pdrlearn.sim.transfer`) and the rides of :class:`Lift` / :class:`Escalator` ones
        (:mod:`pdrlearn.sim.ride`) and the freezes of :class:`Freeze` ones (:mod:`pdrlearn.sim.freeze`, S51); a
        :class:`Lie` gives a transfer followed by its :class:`~pdrlearn.sim.lying.LyingEpisode` (S58); a
        :class:`Spin` its :class:`~pdrlearn.sim.spin.SpinEpisode` (S106)
    """
    w = _Walker(user, speed, rng, heading0_rad, irregular_rate, variability, step_length_asymmetry, paretic_side,
                transfer_s)
    w.graded_slopes = bool(graded_slopes)  # decision S121
    initial = {f: (h.copy(), y) for f, (h, y) in w.feet.items()}
    handlers = {
        Straight: w.straight,
        Curve: w.curve,
        Stairs: w.stairs,
        Slope: w.slope,
        Backward: w.backward,
        Turn: w.turn,
        Pivot: w.pivot,
        InPlace: w.in_place,
        Stand: w.stand,
        Sit: w.sit,
        Lift: w.ride,
        Escalator: w.ride,
        Trolley: w.trolley,
        Side: w.side,
        Freeze: w.freeze,
        Lie: w.lie,
        Vehicle: w.vehicle,
        Cycle: w.cycle,
        Spin: w.spin,  # decision S106
    }
    for seg in segments:
        if isinstance(seg, Straight | Curve | Slope | Trolley) and seg.gait not in GAITS:
            raise DataError(f"{seg}: gait must be one of {', '.join(GAITS)}")
        if isinstance(seg, Straight) and seg.pace is not None and seg.pace not in SPEEDS:  # decision S88
            raise DataError(f"{seg}: pace must be one of {', '.join(SPEEDS)} (or None: the session's speed)")
        try:
            handlers[type(seg)](seg)
        except KeyError:
            raise DataError(
                f"unknown path segment {seg!r}; use Straight, Curve, Stairs, Slope, Backward, Turn, Pivot, Stand, Sit, "
                "Lift, Escalator, Trolley, Side, Freeze, Lie, Vehicle, Cycle, Spin"
            ) from None
    w.close()
    return w.steps, initial, w.pending_pause, w.transfers
