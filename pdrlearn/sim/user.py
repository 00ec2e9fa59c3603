"""Simulated users: anthropometry, gait parameters, sensor mounting and sensor biases."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from pdrlearn.errors import DataError

SPEEDS = ("slow", "normal", "fast")
GAITS = ("short", "normal", "long")

# Speed -> (step-length factor, step-duration factor) relative to the user's normal walk. Slow/fast
# walking changes both cadence and step length (thesis Table 1: stride grows with speed).
SPEED_FACTORS = {"slow": (0.85, 1.20), "normal": (1.0, 1.0), "fast": (1.12, 0.86)}
# Deliberately short/long steps of the length exercise (thesis ch.6.3) -> (length factor, duration factor).
GAIT_FACTORS = {"short": (0.55, 0.95), "normal": (1.0, 1.0), "long": (1.3, 1.08)}

#: decisions S35, S42: the leg of an asymmetric gait; the steps onto it are 1 + a times the steps onto the other (the
#: foot unit is on the right foot, so each of its strides spans one step onto each foot)
AFFECTED_FOOT = "left"


def asymmetry_factor(foot: str, asymmetry: float, affected: str = AFFECTED_FOOT) -> float:
    """Decisions S35 (step time) and S42 (step length): the factor on a step landing on ``foot`` for an asymmetry
    ``a`` = symmetry ratio - 1, the ratio being the step onto the ``affected`` foot (default :data:`AFFECTED_FOOT`;
    the ``paretic_side`` knob, decision S55) / the step onto the other
    (Patterson et al. 2010, Gait Posture 31:241-246, recommend the ratio for post-stroke gait). The two factors
    2 r / (1 + r) and 2 / (1 + r) (r = 1 + a) average 1, so a stride (one step onto each foot) keeps the user's
    length and time; a = 0 gives 1.0 exactly."""
    r = 1.0 + asymmetry
    return 2.0 * r / (1.0 + r) if foot == affected else 2.0 / (1.0 + r)


#: decision S119: the knobs of a one-sided (prosthetic) foot -> the :class:`UserProfile` field each replaces on the
#: ``prosthetic_side`` foot only, and its range. The users' own draws are -58 to -50 deg (toe-off), 17-26 deg (heel
#: strike) and 0.45-0.7 m/s (impact); a stiff prosthetic ankle rolls off at about -15 deg and lands at about 8 deg
#: (session 50 trial T2's lab values, assumptions); the ranges keep a plantarflexed toe-off (-80 to 0 deg, S115's
#: flattest heel lift to its steepest), a heel-first contact (0-40 deg; a forefoot contact is --contact forefoot,
#: S108) and a landing that stops (0.05-2 m/s)
PROSTHETIC_FOOT_FIELDS = {
    "prosthetic_toe_off_pitch_deg": ("toe_off_pitch_deg", (-80.0, 0.0)),
    "prosthetic_heel_strike_pitch_deg": ("heel_strike_pitch_deg", (0.0, 40.0)),
    "prosthetic_impact_speed_mps": ("impact_speed_mps", (0.05, 2.0)),
}


def side_foot(user: UserProfile, values: dict) -> UserProfile | None:
    """Decision S119: the profile of a one-sided (prosthetic) foot: ``user`` with the fields of
    :data:`PROSTHETIC_FOOT_FIELDS` that ``values`` (knob name -> number or None) gives; None when it gives none (both
    feet the user's own). The schedule (:func:`pdrlearn.sim.body.schedule`, ``feet``) reads the toe-off pitch (the
    push-off), the heel-strike pitch and the impact speed of the steps landing on that foot from it; everything
    else (the contacts' times, the other foot, meta.json's ``user``) stays the user's."""
    changes = {field_: float(values[k]) for k, (field_, _) in PROSTHETIC_FOOT_FIELDS.items()
               if values.get(k) is not None}
    return replace(user, **changes) if changes else None


# Foot-unit mounts (decisions S19): from a lateral mount below the ankle (gaitmap level recordings,
# "lateral shoe sensor": ~25-30 % of the foot length from the heel, 3-4 cm up) to the instep (PLASYS-style
# top-of-foot unit, gaitmap stairs recordings: ~45-50 %, 5-7 cm up).
FOOT_SENSOR_X_FRAC = (0.25, 0.5)
FOOT_SENSOR_HEIGHT_M = (0.03, 0.07)


def _foot_mount(rng: np.random.Generator) -> dict:
    x = float(rng.uniform(*FOOT_SENSOR_X_FRAC))
    # the height follows the position along the foot (low beside the heel, higher on the instep) +- 1 cm
    lo, hi = FOOT_SENSOR_HEIGHT_M
    u = (x - FOOT_SENSOR_X_FRAC[0]) / (FOOT_SENSOR_X_FRAC[1] - FOOT_SENSOR_X_FRAC[0])
    h = float(np.clip(lo + u * (hi - lo) + rng.uniform(-0.01, 0.01), lo, hi))
    return {"foot_sensor_x_frac": round(x, 4), "foot_sensor_height_m": round(h, 4)}


@dataclass
class UserProfile:
    """One simulated pedestrian.

    Attributes
    ----------
    seed : the user seed this profile was drawn from
    height_m, mass_kg : stature (m) and body mass (kg)
    leg_length_m : greater-trochanter height (m), ~0.53 x stature
    foot_length_m : heel-to-toe length (m)
    sensor_height_m : height of the waist unit above the floor when standing (m)
    step_width_m : lateral distance between the feet's centre lines (m)
    step_length_m : mean step length (one foot to the other, m) at normal speed on level ground
    step_time_s : mean step duration (initial contact to the next, s) at normal speed
    variability : coefficient of variation of step length and step time (fraction)
    stance_fraction : fraction of the gait cycle in stance at normal speed
    foot_misalignment_deg, waist_misalignment_deg : mounting rotation vectors of the units (deg)
    force_coverage : fraction of the heel/forefoot load that reaches the force sensors
    pelvis_bounce_m, pelvis_sway_m, pelvis_rotation_deg, pelvis_obliquity_deg : pelvis motion amplitudes
    foot_sensor_x_frac, foot_sensor_height_m : foot unit position in the foot frame: distance from the heel
        (fraction of the foot length) and height above the sole (m); see decisions S19
    toe_clearance_m : lowest height of the toe tip (or of the heel, when the foot is dorsiflexed) above
        the floor in the swing of a level step (m); see decisions S23
    shoe_toe_allowance_m : length of the shoe's sole beyond the tip of the toes (m); the push-off rolls over
        the front of the sole (decisions S25)
    class_step_length_m : the user's own step length (m) when ``step_length_m`` is a walk's override
        (``simulate --step-length``, S30): the stride-length class bounds stay this user's (decision S81); None
        (the default, not written by :meth:`to_dict`): ``step_length_m`` is the user's own
    length_bounds_m : [short/normal, normal/long] stride-length class bounds (m) given for this walker
        (``simulate --length-bounds``, decision S98), e.g. a slow walker's own; None (the default, not written by
        :meth:`to_dict`): the midpoints of the user's own short / normal / long strides (S81)
    """

    seed: int
    height_m: float
    mass_kg: float
    leg_length_m: float
    foot_length_m: float
    sensor_height_m: float
    step_width_m: float
    step_length_m: float
    step_time_s: float
    variability: float
    stance_fraction: float
    impact_speed_mps: float
    swing_height_m: float
    toe_off_pitch_deg: float
    heel_strike_pitch_deg: float
    foot_misalignment_deg: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0])
    waist_misalignment_deg: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0])
    force_coverage: float = 0.5
    pelvis_bounce_m: float = 0.045
    pelvis_sway_m: float = 0.025
    pelvis_rotation_deg: float = 4.0
    pelvis_obliquity_deg: float = 3.0
    foot_sensor_x_frac: float = 0.45
    foot_sensor_height_m: float = 0.06
    toe_clearance_m: float = 0.013
    shoe_toe_allowance_m: float = 0.02
    class_step_length_m: float | None = None
    length_bounds_m: list[float] | None = None

    @classmethod
    def from_seed(cls, seed: int) -> UserProfile:
        """Draw a healthy adult deterministically from ``seed`` (a non-negative integer)."""
        if not isinstance(seed, int | np.integer) or int(seed) < 0:
            raise DataError(f"user seed {seed!r}: must be a non-negative integer")
        rng = np.random.default_rng([int(seed), 0x5EED])
        # the thesis pedestrians were 1.65 m and 1.90 m tall (thesis ch.7.3, introduction)
        height = float(rng.uniform(1.55, 1.95))
        bmi = float(np.clip(rng.normal(23.0, 2.5), 18.5, 30.0))
        # step length ~0.41 x stature at a comfortable speed; cadence ~100-120 steps/min
        step_len = float(height * rng.normal(0.415, 0.02))
        step_time = float(60.0 / rng.uniform(100.0, 118.0))
        return cls(
            seed=int(seed),
            height_m=round(height, 4),
            mass_kg=round(bmi * height**2, 2),
            leg_length_m=round(0.53 * height, 4),
            foot_length_m=round(0.152 * height, 4),
            sensor_height_m=round(height * rng.uniform(0.55, 0.6), 4),
            step_width_m=round(float(rng.uniform(0.08, 0.14)), 4),
            step_length_m=round(step_len, 4),
            step_time_s=round(step_time, 4),
            variability=round(float(rng.uniform(0.02, 0.035)), 4),
            # stance 62-68 % of the cycle: gaitmap mocap and mobgap INDIP references ~67-68 %, force-plate
            # norms 60-62 % at a brisk 1.37 m/s (decisions S14)
            stance_fraction=round(float(rng.uniform(0.62, 0.68)), 4),
            impact_speed_mps=round(float(rng.uniform(0.45, 0.7)), 4),
            swing_height_m=round(float(rng.uniform(0.2, 0.28)), 4),
            toe_off_pitch_deg=round(float(rng.uniform(-58.0, -50.0)), 3),
            heel_strike_pitch_deg=round(float(rng.uniform(17.0, 26.0)), 3),
            foot_misalignment_deg=[round(float(v), 3) for v in rng.normal(0.0, 2.5, 3)],
            waist_misalignment_deg=[round(float(v), 3) for v in rng.normal(0.0, 2.5, 3)],
            force_coverage=round(float(rng.uniform(0.35, 0.6)), 4),
            pelvis_bounce_m=round(float(rng.uniform(0.03, 0.045)), 4),
            pelvis_sway_m=round(float(rng.uniform(0.025, 0.04)), 4),
            pelvis_rotation_deg=round(float(rng.uniform(3.0, 5.0)), 3),
            pelvis_obliquity_deg=round(float(rng.uniform(2.0, 4.0)), 3),
            # drawn last so that the earlier draws (and the users of earlier versions) are unchanged
            **_foot_mount(rng),
            # minimum toe clearance 1.29 +- 0.45 cm (Winter 1992, young adults), +-2 SD; drawn after the
            # mount so that the earlier draws stay as they were (decisions S23)
            toe_clearance_m=round(float(rng.uniform(0.004, 0.022)), 4),
            # shoe sizing allows ~1.5 cm beyond the longest toe (EU size = 1.5 x (foot length cm + 1.5)), plus
            # the sole's rim: 1-3 cm (decisions S25)
            shoe_toe_allowance_m=round(float(rng.uniform(0.01, 0.03)), 4),
        )

    def scaled(self, height_m: float, leg_length_m: float | None = None) -> UserProfile:
        """This user at another stature (decision S38): a child, or a shorter / taller adult.

        Body lengths (foot, waist-unit height, step width, swing height, toe clearance, pelvis bounce and sway)
        scale with the stature ratio ``height_m / self.height_m`` (geometric similarity) and the mass with its
        cube; the gait by dynamic similarity on the leg length L (Hof 1996, "Scaling gait data to body size",
        Gait & Posture 4:222-223: step length / L, step time / sqrt(L / g) and speed / sqrt(g L) are the same for
        the scaled walker): step length x L'/L, step time and impact speed x sqrt(L'/L). ``leg_length_m``:
        the new leg length (m; default the stature ratio times this user's). Children younger than about five
        step faster than dynamic similarity predicts: give their step time with ``dataclasses.replace`` or
        ``simulate --step-time``. The seed, mounting and sensor errors stay this user's.
        """
        if not (isinstance(height_m, int | float) and math.isfinite(height_m) and height_m > 0):
            raise DataError(f"height {height_m!r}: give the stature in metres, e.g. 0.95 for a 3-year-old")
        r = float(height_m) / self.height_m
        leg = self.leg_length_m * r if leg_length_m is None else leg_length_m
        if not (isinstance(leg, int | float) and math.isfinite(leg) and leg > 0):
            raise DataError(f"leg length {leg_length_m!r}: give the greater-trochanter height in metres, e.g. 0.45")
        rl = float(leg) / self.leg_length_m

        def by(v: float, f: float) -> float:
            return round(v * f, 4)

        return replace(
            self, height_m=round(float(height_m), 4), mass_kg=round(self.mass_kg * r**3, 2),
            leg_length_m=round(float(leg), 4),
            foot_length_m=by(self.foot_length_m, r), sensor_height_m=by(self.sensor_height_m, r),
            step_width_m=by(self.step_width_m, r), swing_height_m=by(self.swing_height_m, r),
            toe_clearance_m=by(self.toe_clearance_m, r), pelvis_bounce_m=by(self.pelvis_bounce_m, r),
            pelvis_sway_m=by(self.pelvis_sway_m, r),
            step_length_m=by(self.step_length_m, rl), step_time_s=by(self.step_time_s, math.sqrt(rl)),  # Hof 1996
            impact_speed_mps=by(self.impact_speed_mps, math.sqrt(rl)))

    # -- derived gait parameters -------------------------------------------------------------------
    def step_length(self, speed: str = "normal", gait: str = "normal") -> float:
        """Mean step length (m) at ``speed`` with the step ``gait`` (short/normal/long)."""
        return self.step_length_m * SPEED_FACTORS[speed][0] * GAIT_FACTORS[gait][0]

    def step_time(self, speed: str = "normal", gait: str = "normal") -> float:
        """Mean step duration (s) at ``speed`` with the step ``gait``."""
        return self.step_time_s * SPEED_FACTORS[speed][1] * GAIT_FACTORS[gait][1]

    def stride_length(self, speed: str = "normal", gait: str = "normal") -> float:
        return 2.0 * self.step_length(speed, gait)

    @property
    def length_class_bounds_m(self) -> tuple[float, float]:
        """(short/normal, normal/long) stride-length bounds (m), see docs/decisions/simulator.md.

        The thesis (ch.6.3) sets the bounds per user from the calibration exercises; the bounds are the
        midpoints between this user's mean short, normal and long stride lengths at normal speed.
        """
        if self.length_bounds_m is not None:  # decision S98: the walker's bounds, given
            lo, hi = self.length_bounds_m
            return (float(lo), float(hi))
        # decision S81: from the user's own step, not a walk's --step-length override (one user, one set of bounds)
        own = replace(self, step_length_m=self.class_step_length_m, class_step_length_m=None) \
            if self.class_step_length_m is not None else self
        s, n, l_ = (own.stride_length("normal", g) for g in GAITS)
        return (round(0.5 * (s + n), 4), round(0.5 * (n + l_), 4))

    def length_class(self, length_m: float) -> str:
        lo, hi = self.length_class_bounds_m
        return "short" if length_m <= lo else ("normal" if length_m <= hi else "long")

    def to_dict(self) -> dict:
        d = asdict(self)
        if d["class_step_length_m"] is None:  # decision S81: written only for an overridden step length
            del d["class_step_length_m"]
        if d["length_bounds_m"] is None:  # decision S98: written only when given
            del d["length_bounds_m"]
        return d
