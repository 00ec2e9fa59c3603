"""Gait timing, foot and pelvis kinematics of the simulated walker.

The foot is a rigid body moved by a three-rocker model: heel rocker (initial contact -> foot flat,
rotation about the heel; toe-first contacts rotate about the ball), foot flat (still), forefoot rocker
(heel-off -> toe-off, rotation about the ball of the foot) and swing (clamped cubic splines for the heel
path and the pitch). At initial contact the contact point stops abruptly: the velocity jump is the
impact that real foot accelerometers record. The pelvis follows the mid-point between the feet (smooth
monotone interpolation between initial contacts) plus gait-phase oscillations: vertical bounce, forward
surge, lateral sway, pelvic rotation about the vertical, obliquity and tilt, and a short heel-strike
transient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from pdrlearn.sim.kernels import (
    clamped_spline,
    decaying_rocker,
    euler_zyx,
    foot_rotate,
    foot_rotate_dtheta,
    foot_rotation,
    hermite,
    sawtooth_surge,
    skewed_phase,
    smoothstep,
)
from pdrlearn.sim.path import Footstep
from pdrlearn.sim.user import AFFECTED_FOOT, GAIT_FACTORS, UserProfile, asymmetry_factor  # noqa: F401 (S35 name)


@dataclass(frozen=True)
class StepKind:
    """Swing parameters of one kind of step.

    duration : step-duration factor (x the user's step time)
    toe_off : toe-off pitch factor (x the user's toe-off pitch; < 0 lifts the toes first: backward)
    contact_deg : pitch at initial contact (deg; None = the user's heel-strike pitch; < 0 = toe first)
    mid_swing_deg : pitch at mid-swing (deg, at 85 % of swing; None = 95 % of the contact pitch)
    impact : (forward, vertical) velocity of the contact point just before contact (x user impact speed)
    clearance_m : heel height above the higher footprint at early swing (None = the user's swing height)
    pitch_hold : fraction of swing during which the foot keeps its toe-off plantarflexion before it
        dorsiflexes (the second knot of ``SWING_PITCH_KNOTS``)
    loading_rate : pitch rate at initial contact / mean rate of the loading rocker (0 = the foot reaches
        its largest contact pitch at contact and the rocker starts from rest, decisions S23)
    """

    duration: float
    toe_off: float
    contact_deg: float | None
    mid_swing_deg: float | None
    impact: tuple[float, float]
    clearance_m: float | None
    pitch_hold: float = 0.2
    loading_rate: float = 1.2


WALK_IMPACT = (0.85, -0.5)  # (forward, vertical) heel velocity before a level contact / user impact speed
# Values follow the thesis' qualitative descriptions (ch.6.1.1, Figs. 59-60): on stairs the force is
# concentrated on the forefoot and the heel load is negligible (thesis ch.2.1.2, ref [115]); descending
# steps land toe first with a higher impact force; ascending steps rotate the foot up then down and
# descending ones the opposite. Magnitudes are set so that peak |acc|, peak pitch rate and stride time
# fall in the range of the real foot recordings (tests/test_sim_vs_real.py).
KINDS = {
    # level walk (decisions S23): the heel approaches the floor mostly forward (before (0.55, -0.85)), and
    # the foot is at its largest pitch at heel strike: the heel rocker's plantarflexion starts after contact
    "walk": StepKind(1.00, 1.00, None, None, WALK_IMPACT, None, loading_rate=0.0),
    "close": StepKind(1.00, 0.60, None, None, (0.35, -0.6), 0.15),
    # stairs up: fore/midfoot placement on the tread, no heel rocker (decisions S15)
    # ... and the foot stays pointed through early swing (the knee and hip lift it over the nosing), then
    # dorsiflexes in mid-late swing to place the forefoot (decisions S18)
    "stairs_up": StepKind(0.95, 0.75, -2.0, -5.0, (0.9, -1.5), 0.11, pitch_hold=0.45),
    # stairs down: the foot is plantarflexed early in swing and lowered toes first (decisions S15)
    "stairs_down": StepKind(0.82, 0.85, -22.0, -20.0, (0.3, -1.1), 0.09),
    "backward": StepKind(1.20, -0.30, -15.0, None, (0.30, -0.6), 0.09),
    "turn": StepKind(1.10, 0.25, 3.0, None, (0.05, -0.3), 0.05),
    # side step (decision S49, an assumption, not from a seed): slower than a forward step (as backward), little
    # push-off (the foot is lifted, not rolled over the toes), landing flat on the forefoot, a soft sideways impact
    "side": StepKind(1.20, 0.30, -3.0, None, (0.30, -0.6), 0.06),
}
SPEED_PITCH = {"slow": 0.88, "normal": 1.0, "fast": 1.08}
LOAD_FRACTION = 0.10  # initial contact -> foot flat, fraction of the gait cycle
# The gradually decaying heel rocker (decisions S31, `rocker="smooth"`): the foot is still from ROCKER_FRACTION
# of the cycle after the contact; its pitch rate rises within ROCKER_RISE and decays with ROCKER_DECAY (both x the
# rocker's duration). The foot-flat event of the labels and loads stays at LOAD_FRACTION.
ROCKER_MODES = ("hermite", "smooth")
#: decision S108: the level walk's first contact: "heel" (the heel rocker, S23) or "forefoot" - a toe walker's
#: forefoot-first contact with the ankle plantarflexed and no heel rocker (Brasiliano et al. 2023, Healthcare 11:873:
#: "forefoot contact with the ground"; Alvarez et al. 2007, Gait Posture 26:428, grade toe walking by its rockers);
#: the foot lands pitched toes-down by FOREFOOT_CONTACT_DEG and the heel comes down about the ball (the stair
#: ascent's pivot, S15), so stance keeps a foot flat (a mild / moderate toe walker; no persistent tip-toe stance)
CONTACT_MODES = ("heel", "forefoot")
#: decision S108 (ours, not from a document): the toes-down foot pitch at a forefoot contact - T1's stand-in value
#: (-12 deg), between the stair ascent's near-flat forefoot placement (-2 deg, S15) and the stair descent's -22 deg
FOREFOOT_CONTACT_DEG = -12.0
#: decision S108: the step kinds whose contact --contact forefoot moves to the forefoot (level walking)
FOREFOOT_KINDS = ("walk", "close")
ROCKER_FRACTION = 0.20
ROCKER_RISE = 0.05
ROCKER_DECAY = 0.5
HEEL_OFF_FRACTION = 0.45  # heel-off instant, fraction of the gait cycle (decisions S14)
TOE_TIP_FRACTION = 0.97  # push-off pivot (toe rocker: the foot rolls over the tip of the hallux), x foot length
PUSH_OFF_RATE = 2.2  # pitch rate at toe-off / mean rate of the forefoot rocker (fast push-off)
SWING_ROLL_DEG = 12.0  # peak inversion of the swinging foot
SWING_YAW_DEG = 6.0  # peak toe-out of the swinging foot
CONTACT_ROLL_DEG = 6.0  # inversion at initial contact, removed quickly in the first third of loading
IMPACT_RING_HZ = 25.0  # rotational ringing after contact (shoe/strap), seen as gyro spikes in real data
IMPACT_RING_DECAY_S = 0.015
IMPACT_RING_RAD = (0.035, 0.02, 0.02)  # roll, yaw, pitch amplitude (rad)
SWING_PITCH_KNOTS = (0.0, 0.2, 0.5, 0.85, 1.0)  # normalised swing times of the pitch knots (steady
# dorsiflexion between 15 % and 85 % of swing, as the plateau of the real foot gyroscope)
SWING_HEEL_KNOTS = (0.38, 0.72)  # normalised swing times of the two inner knots of the heel path
STAIR_TOE_CLEARANCE = 2.0  # toe clearance over a stair nosing / the user's level toe clearance (S24)


#: decision S35: ``step_time_asymmetry`` must be below this: at 1 (symmetry ratio 2) the affected leg's stance is
#: (1/2 + 2 s - 1) / (2 (1 - s)) = 0.97-1.34 x its swing for the users' stance fractions s 0.62-0.68; beyond, its
#: swing outlasts its stance (a hop over the sound leg, not a walk)
STEP_TIME_ASYMMETRY_MAX = 1.0


#: decision S94: ``stance_time_asymmetry`` must be below this: the paretic-side foot's stance fraction is the user's
#: / (1 + a), and at the users' least stance fraction 0.62 (:mod:`pdrlearn.sim.user`) a = 0.2 leaves it 0.517 - still
#: above 0.5, so its swing (1 - fraction of the stride) stays shorter than a step and the feet keep a double support
#: (an assumption of this simulator, no seed gives a limit)
STANCE_TIME_ASYMMETRY_MAX = 0.2


def step_time_factor(foot: str, asymmetry: float, affected: str = AFFECTED_FOOT) -> float:
    """Decision S35: the factor on the step time of a step landing on ``foot`` for a step-time asymmetry ``a``
    (:func:`pdrlearn.sim.user.asymmetry_factor`, shared with S42's step lengths): a = 0.39 makes each step onto the
    affected foot (``affected``, default :data:`AFFECTED_FOOT`; decision S55) 1.39 x the step onto the other, the
    stride time unchanged."""
    return asymmetry_factor(foot, asymmetry, affected)


@dataclass
class Events:
    """Per-footstep gait events (s) and swing parameters, arrays aligned with the footstep list."""

    ho: np.ndarray
    to: np.ndarray
    ic: np.ndarray
    ff: np.ndarray
    step_s: np.ndarray  # nominal step duration
    theta_to: np.ndarray
    theta_ic: np.ndarray
    theta_mid: np.ndarray
    swing_roll: np.ndarray  # peak roll in swing (rad)
    swing_yaw: np.ndarray  # peak extra yaw in swing (rad)
    contact_roll: np.ndarray  # roll at initial contact (rad)
    impact: np.ndarray  # (n, 2): forward, vertical pivot velocity before contact (m/s)
    clearance: np.ndarray
    bout_start: np.ndarray  # bool: first step after a standstill
    rest: np.ndarray  # end of the loading rocker: the foot is still from here (= ff for the Hermite rocker)
    rocker: str = "hermite"  # loading rocker shape (ROCKER_MODES, decisions S31)

    @property
    def end_s(self) -> float:
        return float(self.rest.max()) if len(self.rest) else 0.0


def schedule(
    steps: list[Footstep],
    user: UserProfile,
    *,
    speed: str,
    rng: np.random.Generator,
    stand_s: float,
    variability: float = 1.0,
    rocker: str = "hermite",
    step_time_asymmetry: float = 0.0,
    affected: str = AFFECTED_FOOT,
    stance_time_asymmetry: float = 0.0,
    contact: str = "heel",
    feet: dict[str, UserProfile] | None = None,
    short_stance: str | None = None,
    fatigue_pct: float = 0.0,
) -> Events:
    """Assign gait-event times to the footsteps (both feet) and draw per-step swing parameters.

    ``step_time_asymmetry``: the steps onto the ``affected`` foot (default :data:`AFFECTED_FOOT`, decision S55) are
    1 + this times as long as the others (:func:`step_time_factor`, decision S35).

    ``stance_time_asymmetry`` (decision S94): the ``affected`` foot's stance fraction is the user's / (1 + this) - its
    swings before landing are longer, its stance shorter, the step times unchanged - so the other foot's stance is
    about 1 + this times its own (a prosthesis user loads the prosthetic side for less time). ``short_stance``
    (decision S120): the foot whose stance is shortened, when it is not the ``affected`` one (None: ``affected``).

    ``feet`` (decision S119): a foot's own profile (``{"left": ...}``, :func:`pdrlearn.sim.user.side_foot`): the
    steps landing on it take their toe-off pitch, heel-strike pitch and impact speed from it, the other foot's and
    every time from ``user``; no random draw changes, so the other foot's steps are the same to the bit.

    ``fatigue_pct`` (decision S122): the k-th of the n steps takes its step time / (1 - fatigue_pct / 100 x k /
    (n - 1)): the cadence, so the speed, falls linearly in the step count to (1 - fatigue_pct / 100) x the user's at
    the last step; the footprints are the planner's (0: no change, bit for bit).

    ``rocker``: "hermite" (the foot is flat and still ``LOAD_FRACTION`` of the cycle after the contact) or "smooth"
    (still only ``ROCKER_FRACTION`` after it, decisions S31; the foot-flat event stays at ``LOAD_FRACTION``).

    ``contact`` (decision S108): "heel" or "forefoot" - level steps (:data:`FOREFOOT_KINDS`) land on the forefoot
    pitched :data:`FOREFOOT_CONTACT_DEG` (a toe walker); the contact, toe-off and foot-flat times are unchanged.
    """
    n = len(steps)
    names = (
        "ho",
        "to",
        "ic",
        "ff",
        "step_s",
        "theta_to",
        "theta_ic",
        "theta_mid",
        "clearance",
        "swing_roll",
        "swing_yaw",
        "contact_roll",
    )
    ev = {k: np.zeros(n) for k in (*names, "rest")}
    impact = np.zeros((n, 2))
    bout_start = np.zeros(n, dtype=bool)
    cv = user.variability * variability
    last_ff = {"left": stand_s - 1.0, "right": stand_s - 1.0}
    settle = stand_s  # time at which all feet are flat after the last bout
    for k, st in enumerate(steps):
        stance = user.stance_fraction  # decision S94: the affected foot's shortened (skipped at 0: bit for bit)
        if stance_time_asymmetry and st.foot == (short_stance or affected):  # decision S120: or the named one
            stance = user.stance_fraction / (1.0 + stance_time_asymmetry)
        kd = KINDS[st.kind]
        dfac, pfac, (vf, vz), clear = kd.duration, kd.toe_off, kd.impact, kd.clearance_m
        ic_pitch = None if kd.contact_deg is None else np.radians(kd.contact_deg)
        # decision S88: a Straight's own pace (st.pace), else the session's speed
        d = user.step_time(st.pace or speed, st.gait) * dfac * max(0.7, 1.0 + rng.normal(0.0, cv))
        if st.time_factor != 1.0:  # decision S101: a stair flight's numeric pace (skipped at 1: bit for bit)
            d *= st.time_factor
        if fatigue_pct:  # decision S122: a linear decline of the cadence over the session's steps (0: bit for bit)
            d /= 1.0 - fatigue_pct / 100.0 * k / max(1, n - 1)
        if step_time_asymmetry:  # decision S35 (skipped at 0: default sessions bit for bit)
            d *= step_time_factor(st.foot, step_time_asymmetry, affected)
        if st.irregular:
            d *= 1.3
        T = 2.0 * d
        swing, rock, load = (1 - stance) * T, (stance - HEEL_OFF_FRACTION) * T, LOAD_FRACTION * T
        still = ROCKER_FRACTION * T if rocker == "smooth" else load  # contact -> the foot at rest
        start = k == 0 or st.pause_before_s > 0 or steps[k - 1].foot == st.foot
        if start:
            ho = max(settle + st.pause_before_s, last_ff[st.foot] + 0.05)
            ic = ho + rock + swing
        else:
            ic = ev["ic"][k - 1] + d
            ic = max(ic, ev["ic"][k - 1] + swing + 0.02, last_ff[st.foot] + 0.05 + rock + swing)
        bout_start[k] = start
        ev["ic"][k], ev["to"][k], ev["ho"][k], ev["ff"][k] = ic, ic - swing, ic - swing - rock, ic + load
        ev["rest"][k] = ic + still
        ev["step_s"][k] = d
        last_ff[st.foot] = ic + still
        settle = max(settle, ic + still)
        jit = 1.0 + 0.05 * variability * rng.normal()
        gait_pitch = 0.6 if st.gait == "short" else (1.1 if st.gait == "long" else 1.0)
        fu = feet.get(st.foot, user) if feet else user  # decision S119: a one-sided foot's own pitches and impact
        ev["theta_to"][k] = np.radians(fu.toe_off_pitch_deg) * pfac * SPEED_PITCH[speed] * gait_pitch * jit
        if ic_pitch is None and contact == "forefoot" and st.kind in FOREFOOT_KINDS:  # decision S108
            ic_pitch = np.radians(FOREFOOT_CONTACT_DEG) * (0.6 if st.kind == "close" else 1.0)
        if ic_pitch is None:
            ic_pitch = (
                np.radians(fu.heel_strike_pitch_deg)
                * (0.6 if st.kind == "close" else 1.0)
                * SPEED_PITCH[speed]
                * gait_pitch
            )
        ev["theta_ic"][k] = ic_pitch * (1.0 + 0.05 * variability * rng.normal())
        # swing wobble: inversion (medial edge up) and toe-out, a few degrees
        inward = 1.0 if st.foot == "right" else -1.0  # roll > 0 lifts the left edge
        wob = 0.3 if st.kind == "turn" else (0.6 if st.kind.startswith("stairs") else 1.0)
        ev["swing_roll"][k] = inward * wob * np.radians(SWING_ROLL_DEG) * (1.0 + 0.2 * variability * rng.normal())
        ev["contact_roll"][k] = inward * wob * np.radians(CONTACT_ROLL_DEG) * (1.0 + 0.2 * variability * rng.normal())
        ev["swing_yaw"][k] = -inward * wob * np.radians(SWING_YAW_DEG) * (1.0 + 0.3 * variability * rng.normal())
        ev["theta_mid"][k] = (
            0.95 * ev["theta_ic"][k] if kd.mid_swing_deg is None else np.radians(kd.mid_swing_deg) * jit
        )
        sp = fu.impact_speed_mps * np.exp(rng.normal(0.0, 0.25 * variability))
        sp *= {"slow": 0.8, "normal": 1.0, "fast": 1.2}[speed] * GAIT_FACTORS[st.gait][0] ** 0.5
        if st.irregular:
            sp *= 0.5
        impact[k] = (vf * sp, vz * sp)
        clear = user.swing_height_m if clear is None else clear
        ev["clearance"][k] = clear * (0.5 if st.irregular else 1.0)
    return Events(impact=impact, bout_start=bout_start, rocker=rocker, **ev)


# -- foot ---------------------------------------------------------------------------------------
def toe_tip_m(user: UserProfile) -> float:
    """Distance (m) from the heel to the push-off pivot: the tip of the hallux (``TOE_TIP_FRACTION`` x foot
    length) plus the shoe's length beyond the toes: the foot rolls over the front of the shoe's sole (decisions
    S25)."""
    return TOE_TIP_FRACTION * user.foot_length_m + user.shoe_toe_allowance_m


def toe_off_pitch_for_apex(user: UserProfile, apex_m: float) -> float:
    """Decision S115: the toe-off pitch (deg, < 0 = plantarflexed) whose heel lift puts the heel's swing apex of a
    level step at normal speed ``apex_m`` above the floor: the heel path's height over the floor is the toe
    clearance plus the toe-tip distance x sin(plantarflexion) (decisions S23), highest at the toe-off knot. The
    ratio is kept to 0.02-0.98 (a foot left almost flat, or almost vertical)."""
    ratio = min(max((float(apex_m) - user.toe_clearance_m) / toe_tip_m(user), 0.02), 0.98)
    return round(-math.degrees(math.asin(ratio)), 3)


def _toe_lift(pitch_tk, pk, w_ends, t_to: float, swing: float, user: UserProfile) -> np.ndarray:
    """Height (m) of the heel above the toe tip at the two inner heel-path knots of a swing: toe-tip
    distance x sin(plantarflexion) from the swing pitch spline (0 when the toes are up: the heel is lowest).
    """
    th = clamped_spline(pitch_tk, pk[:, None], *w_ends, t_to + np.asarray(SWING_HEEL_KNOTS) * swing)[:, 0]
    return np.maximum(0.0, np.sin(-th)) * toe_tip_m(user)


def _pivot(theta: float, ball: np.ndarray) -> np.ndarray:
    """Foot-frame pivot: the ball of the foot when the toes point down (theta < 0), else the heel."""
    return ball if theta < 0 else np.zeros(3)


def foot_pose(
    t: np.ndarray,
    foot: str,
    steps: list[Footstep],
    ev: Events,
    initial: dict,
    user: UserProfile,
    *,
    vibration: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Heel position (n, 3) and orientation (n, 3, 3, body FLU -> ENU) of one foot on the time grid ``t``.

    ``vibration`` scales a short damped rotational ringing of the shoe after each contact (0 = none).
    """
    n = t.size
    heel = np.empty((n, 3))
    yaw = np.empty(n)
    theta = np.zeros(n)
    roll = np.zeros(n)
    ball = np.array([0.72 * user.foot_length_m, 0.0, 0.0])  # ball of the foot, ~72 % of foot length
    toe = np.array([toe_tip_m(user), 0.0, 0.0])  # front of the shoe's sole (decisions S21, S25)
    h_a, y_a = initial[foot]
    h_a = np.asarray(h_a, float)
    pos = 0
    for k in np.flatnonzero([s.foot == foot for s in steps]):
        st = steps[k]
        h_b, y_b = st.heel, st.yaw
        if n and ev.rest[k] < t[0]:  # decision S44: a step before this part of the grid only moves the foot
            h_a, y_a = np.asarray(h_b, float), y_b
            continue
        if n and ev.ho[k] > t[-1]:  # ... and none after it is reached (the foot stays at h_a: the fill below)
            break
        i_ho, i_to, i_ic, i_ff = np.searchsorted(t, [ev.ho[k], ev.to[k], ev.ic[k], ev.rest[k]])
        heel[pos:i_ho], yaw[pos:i_ho], theta[pos:i_ho] = h_a, y_a, 0.0
        # forefoot (or heel) rocker: heel-off -> toe-off, pivot fixed on footprint A
        th_to, th_ic = ev.theta_to[k], ev.theta_ic[k]
        rock, load = ev.to[k] - ev.ho[k], ev.ff[k] - ev.ic[k]
        w_to = PUSH_OFF_RATE * th_to / rock
        w_ic = -KINDS[st.kind].loading_rate * th_ic / load
        r_a = _pivot(th_to, toe)  # push-off ends on the toe rocker (decisions S21)
        p_a = h_a + foot_rotate(y_a, 0.0, r_a)
        sl = slice(i_ho, i_to)
        th = hermite((t[sl] - ev.ho[k]) / rock, 0.0, th_to, 0.0, w_to, rock)
        heel[sl] = p_a - foot_rotate(y_a, th, r_a)
        yaw[sl], theta[sl] = y_a, th
        # swing: toe-off -> initial contact
        heel_to = p_a - foot_rotate(y_a, th_to, r_a)
        v_to = -foot_rotate_dtheta(y_a, th_to, r_a) * w_to
        r_b = ball if th_ic < 0 else np.zeros(3)
        p_b = h_b + foot_rotate(y_b, 0.0, r_b)
        heel_ic = p_b - foot_rotate(y_b, th_ic, r_b)
        d_xy = heel_ic[:2] - heel_to[:2]
        dist = float(np.linalg.norm(d_xy))
        fwd = np.append(d_xy / dist, 0.0) if dist > 1e-6 else np.array([np.cos(y_b), np.sin(y_b), 0.0])
        v_pivot = ev.impact[k, 0] * fwd + np.array([0.0, 0.0, ev.impact[k, 1]])
        v_ic = v_pivot - foot_rotate_dtheta(y_b, th_ic, r_b) * w_ic
        swing = ev.ic[k] - ev.to[k]
        zmax = max(h_a[2], h_b[2])
        clear = ev.clearance[k]
        # swing pitch: clamped spline through the toe-off, hold, mid-swing and contact pitches
        th_early = 1.05 * th_to
        pk = np.array([th_to, th_early, 0.5 * (th_early + ev.theta_mid[k]), ev.theta_mid[k], th_ic])
        hold = KINDS[st.kind].pitch_hold
        knots = (0.0, hold, 0.5 * (hold + SWING_PITCH_KNOTS[3]), *SWING_PITCH_KNOTS[3:])
        pitch_tk, w_ends = ev.to[k] + np.array(knots) * swing, (np.array([w_to]), np.array([w_ic]))
        knots_u = np.array([0.0, *SWING_HEEL_KNOTS, 1.0])
        frac = np.array([0.0, 0.3, 0.8, 1.0])
        kp = heel_to[None, :] + frac[:, None] * (heel_ic - heel_to)[None, :]
        drop = max(0.0, h_a[2] - h_b[2])
        if drop > 0:
            # descent: past the nosing of its own tread the foot is over the void, so it travels on the
            # straight line from toe-off to contact, lifted by part of the clearance (decisions S15)
            kp[1:3, 2] = kp[1:3, 2] + np.array([0.5, 0.25]) * clear
        elif th_to < 0 and zmax - h_a[2] < 0.01:
            # level forward step (decisions S23): the toes stay just above the floor through swing and the
            # heel height is set by the foot's pitch: toe clearance + toe-tip distance x sin(plantarflexion)
            # (dorsiflexed: the heel is the lowest point). The heel falls from its toe-off height as the
            # foot dorsiflexes in early swing and skims the floor in terminal swing, as in the mocap heel
            # trajectories (Winter 1992: minimum toe clearance ~1.3 cm at mid-swing).
            kp[1:3, 2] = zmax + user.toe_clearance_m + _toe_lift(pitch_tk, pk, w_ends, ev.to[k], swing, user)
            kp[1, 2] = min(kp[1, 2], heel_to[2])  # never lifted above its toe-off height (decisions S21)
        elif th_to < 0:
            # stair ascent (decisions S24): the riser of the next step stands right in front of the toes at
            # toe-off, so the toes must rise above its nosing before they move forward (early-swing knot:
            # half the rise, the intermediate step of a two-step stride) and be above the landing tread by
            # late swing; the heel follows from the pitch as on level ground. The foot is lifted right
            # after toe-off instead of gradually through swing.
            toe_z = np.array([h_a[2] + 0.5 * (zmax - h_a[2]), zmax]) + STAIR_TOE_CLEARANCE * user.toe_clearance_m
            kp[1:3, 2] = toe_z + _toe_lift(pitch_tk, pk, w_ends, ev.to[k], swing, user)
        else:
            # a toe-off without plantarflexion (th_to >= 0): early swing: half of any rise to the next tread
            # plus the clearance (stairs are climbed gradually); late swing: over the landing tread
            kp[1, 2] = max(h_a[2] + clear + 0.5 * (zmax - h_a[2]), heel_to[2] + 0.3 * clear)
            kp[2, 2] = zmax + 0.3 * clear
        kp[0], kp[3] = heel_to, heel_ic
        sl = slice(i_to, i_ic)
        heel[sl] = clamped_spline(ev.to[k] + knots_u * swing, kp, v_to, v_ic, t[sl])
        tu = (t[sl] - ev.to[k]) / swing
        # swing wobble: inversion and toe-in/out peaking mid-swing, zero with zero rate at both ends
        bump = np.sin(np.pi * tu) ** 2
        yaw[sl] = y_a + (y_b - y_a) * smoothstep(tu) + ev.swing_yaw[k] * bump
        roll[sl] = ev.swing_roll[k] * bump + ev.contact_roll[k] * smoothstep(tu)
        theta[sl] = clamped_spline(pitch_tk, pk[:, None], *w_ends, t[sl])[:, 0]
        # loading rocker: initial contact -> foot flat, pivot fixed on footprint B
        sl = slice(i_ic, i_ff)
        if ev.rocker == "smooth":  # decisions S31: the pitch comes to rest gradually
            still = ev.rest[k] - ev.ic[k]
            th = decaying_rocker(t[sl] - ev.ic[k], th_ic, w_ic, still, ROCKER_RISE * still, ROCKER_DECAY * still)
        else:
            th = hermite((t[sl] - ev.ic[k]) / load, th_ic, 0.0, w_ic, 0.0, load)
        heel[sl] = p_b - foot_rotate(y_b, th, r_b)
        yaw[sl], theta[sl] = y_b, th
        tau = t[sl] - ev.ic[k]
        roll[sl] = ev.contact_roll[k] * (1.0 - smoothstep(3.0 * tau / load))
        if vibration > 0:  # impact ringing of shoe and sensor strap: ~25 Hz, decays in ~15 ms
            ring = vibration * np.exp(-tau / IMPACT_RING_DECAY_S) * np.sin(2 * np.pi * IMPACT_RING_HZ * tau)
            roll[sl] += ring * IMPACT_RING_RAD[0] * np.sign(ev.contact_roll[k] or 1.0)
            yaw[sl] += ring * IMPACT_RING_RAD[1]
            theta[sl] += ring * IMPACT_RING_RAD[2]
        h_a, y_a, pos = np.asarray(h_b, float), y_b, i_ff
    heel[pos:], yaw[pos:], theta[pos:], roll[pos:] = h_a, y_a, 0.0, 0.0
    return heel, foot_rotation(yaw, theta, roll)


# -- pelvis -------------------------------------------------------------------------------------
TRUNK_ACC_SD = (0.5, 0.45, 0.6)  # m/s^2 forward, left, up: irregular trunk accelerations while walking
TRUNK_RATE_SD = (0.08, 0.06, 0.06)  # rad/s yaw, pitch, roll
TRUNK_BAND_HZ = (1.5, 7.0)
SURGE_DROP_STEP = 2 * LOAD_FRACTION / 2  # centre of the loading response (LOAD_FRACTION of a cycle), in steps
PELVIS_YAW_LEAD_STEP = -0.2  # pelvic rotation extreme 0.2 step before contact (terminal swing)
PELVIS_YAW_SKEW = 0.6  # reversal rate 1.6x the mean around contact, 0.4x in mid single support
# Gains on the user's pelvic obliquity (roll) and lateral sway (decision S26, NOT adopted: 1.0 = the model
# above). The real lower backs' roll is in phase with their lateral acceleration at the stride frequency
# (the unit leans toward the stance side), the simulated obliquity against it: a negative roll gain
# reverses it (experiments/waist_tilt_coupling.py measures the proposal).
PELVIS_ROLL_GAIN = 1.0
PELVIS_SWAY_GAIN = 1.0
# Opt-in realistic pelvis (decision S27, from S26's measurements of 9 real lower-back recordings: g roll
# 0.07-0.34 m/s^2 at the stride frequency, roll -43..+52 deg from the lateral acceleration, lateral
# acceleration 0.40-0.93 m/s^2). Drawn per user, uniform over these ranges.
PELVIS_MODES = ("model", "realistic")
BOUNCE_MODES = ("constant", "pendulum", "population")  # decisions S29, S74
#: mobgap SlZijlstra's population factor K0 = 4.587 / 4, fitted on real lower-back recordings (decision W46); the
#: "population" bounce (S74) rises as much as seed 003 eq. 1 with K0 reads as the step
POPULATION_K = 4.587 / 4
#: the middle of UserProfile.from_seed's 3-4.5 cm pelvis bounce draw: a user's bounce relative to it (S74)
MID_PELVIS_BOUNCE_M = 0.0375
COMFORTABLE_STEP_PER_HEIGHT = 0.415  # step length / stature at a comfortable speed (UserProfile.from_seed's mean)
REALISTIC_ROLL_DEG = (0.4, 2.0)  # roll amplitude toward the stance side
REALISTIC_ROLL_PHASE_DEG = (-45.0, 45.0)  # roll phase ahead of the sway acceleration
REALISTIC_SWAY_ACC_MPS2 = (0.4, 0.9)  # lateral sway acceleration amplitude
#: decision S46: pushing a trolley (hands on the handle, no arm swing), the pelvic rotation about the vertical and the
#: trunk's yaw vibration are this fraction of the free walk's (an assumption, not from a seed: the arms no longer
#: swing to balance the pelvis's rotation and the handle holds the trunk's heading)
PUSHING_ROTATION_GAIN = 0.5
#: decision S49: side-stepping, the pelvic rotation about the vertical is this fraction of the free walk's and the
#: forward surge is gone (the legs swing sideways, not forward; an assumption, not from a seed); the pelvis moves
#: sideways with the feet (the base line between them) and keeps its bounce and sway
SIDE_ROTATION_GAIN = 0.3


@dataclass(frozen=True)
class PelvisParams:
    """Per-user parameters of the realistic pelvis (decision S27).

    roll_deg : amplitude of the roll toward the stance side (deg)
    roll_phase_deg : phase of the roll ahead of the lateral sway acceleration (deg)
    sway_acc_mps2 : amplitude of the lateral sway acceleration at the user's normal step time (m/s^2)
    sway_m : the sway amplitude that gives it (m)
    """

    roll_deg: float
    roll_phase_deg: float
    sway_acc_mps2: float
    sway_m: float


def realistic_pelvis(user: UserProfile) -> PelvisParams:
    """The realistic pelvis of ``user`` (decision S27), drawn from the user seed on a stream of its own so
    that the profile's other draws (and every default session) are unchanged."""
    rng = np.random.default_rng([int(user.seed), 0x9E1715])
    roll = float(rng.uniform(*REALISTIC_ROLL_DEG))
    phase = float(rng.uniform(*REALISTIC_ROLL_PHASE_DEG))
    acc = float(rng.uniform(*REALISTIC_SWAY_ACC_MPS2))
    # sway = -A sin(pi ph), ph advancing by one per step: a sinusoid of angular rate pi / step time
    omega = np.pi / user.step_time_s
    return PelvisParams(round(roll, 4), round(phase, 3), round(acc, 4), round(acc / omega**2, 6))


def trunk_vibration_source(t0: float, t1: float, rng: np.random.Generator,
                           target_sd: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray] | None:
    """The 100 Hz samples (times, values (m, k)) of :func:`trunk_vibration` over ``t0``..``t1``, None for a span too
    short to filter (decision S44: drawn once, interpolated to any part of the time grid)."""
    from scipy.signal import butter, sosfiltfilt

    t_c = np.arange(t0, t1 + 0.01, 0.01)
    if t_c.size < 50:
        return None
    sos = butter(2, TRUNK_BAND_HZ, btype="bandpass", fs=100.0, output="sos")
    x = sosfiltfilt(sos, rng.normal(0.0, 1.0, (t_c.size, len(target_sd))), axis=0)
    for j, sd in enumerate(target_sd):
        d = np.diff(x[:, j], n=2 if j < 3 else 1) / 0.01 ** (2 if j < 3 else 1)
        x[:, j] = x[:, j] * sd / max(float(d.std()), 1e-12)
    return t_c, x


def trunk_vibration(t: np.ndarray, rng: np.random.Generator, target_sd: tuple[float, ...],
                    source: tuple[np.ndarray, np.ndarray] | None | bool = False) -> np.ndarray:
    """Band-limited random displacements/angles (n, k) whose 2nd (displacements, first 3 columns) or 1st
    (angles, last 3) time derivative has the standard deviation ``target_sd``; computed at 100 Hz and
    interpolated to ``t`` (from ``source``, :func:`trunk_vibration_source`, when given)."""
    if source is False:
        source = trunk_vibration_source(float(t[0]), float(t[-1]), rng, target_sd)
    out = np.zeros((t.size, len(target_sd)))
    if source is not None:
        t_c, x = source
        for j in range(len(target_sd)):
            out[:, j] = np.interp(t, t_c, x[:, j])
    return out


def _foot_centre(heel: np.ndarray, yaw: float, user: UserProfile) -> np.ndarray:
    return heel + np.array([np.cos(yaw), np.sin(yaw), 0.0]) * 0.4 * user.foot_length_m


def _bouts(steps: list[Footstep], ev: Events) -> list[tuple[int, int]]:
    starts = list(np.flatnonzero(ev.bout_start)) + [len(steps)]
    return [(starts[i], starts[i + 1] - 1) for i in range(len(starts) - 1)]


def _edge_phase_knots(steps: list[Footstep], ev: Events, ph_k: list) -> tuple[np.ndarray, np.ndarray]:
    """Decision W612: the gait phase's knots (times, phases) with one more a step before each bout's first contact
    (its phase - 1) and a step after its last (+ 1), where they fit between the bouts, so the phase runs at the bout's
    step rate through its edge contacts instead of flattening toward the stands between bouts."""
    t_k, p_k = list(map(float, ev.ic)), [float(v) for v in ph_k]
    bouts = _bouts(steps, ev)
    for i, (a, b) in enumerate(bouts):
        before = float(ev.ic[a] - ev.step_s[a])
        if i == 0 or before > ev.ic[bouts[i - 1][1]] + ev.step_s[bouts[i - 1][1]]:
            t_k.append(before)
            p_k.append(p_k[a] - 1.0)
        after = float(ev.ic[b] + ev.step_s[b])
        if i == len(bouts) - 1 or after < ev.ic[bouts[i + 1][0]] - ev.step_s[bouts[i + 1][0]]:
            t_k.append(after)
            p_k.append(p_k[b] + 1.0)
    order = np.argsort(t_k, kind="stable")
    return np.asarray(t_k)[order], np.asarray(p_k)[order]


def pendulum_rise(step_m: np.ndarray, leg_m: float) -> np.ndarray:
    """Rise (m) of an inverted pendulum of length ``leg_m`` vaulting over a step ``step_m`` (m):
    ``h = L - sqrt(L^2 - (s/2)^2)`` (seed 003 eq. 1 solved for h; Zijlstra & Hof 2003)."""
    half = np.minimum(0.5 * np.abs(np.asarray(step_m, float)), 0.999 * leg_m)
    return leg_m - np.sqrt(leg_m**2 - half**2)


def _heel_offsets(steps: list[Footstep], initial: dict) -> np.ndarray:
    """(n, 3) offset (m, ENU) of each footstep's landing heel from the other foot's heel at that moment (decisions
    S29, S42, S101)."""
    last = {f: np.asarray(h, float) for f, (h, _) in initial.items()}
    d = np.zeros((len(steps), 3))
    for k, st in enumerate(steps):
        other = "left" if st.foot == "right" else "right"
        d[k] = np.asarray(st.heel, float) - last[other]
        last[st.foot] = np.asarray(st.heel, float)
    return d


def step_lengths(steps: list[Footstep], initial: dict) -> np.ndarray:
    """Length (m) of each footstep: the heel-to-heel distance from the other foot's heel to the landing heel along
    the landing foot's heading (decisions S29, S42; ``abs``: a backward step is as long as its forward twin)."""
    d = _heel_offsets(steps, initial)
    return np.array([abs(dk[0] * np.cos(st.yaw) + dk[1] * np.sin(st.yaw)) for dk, st in zip(d, steps, strict=True)])


def step_heights(steps: list[Footstep], initial: dict) -> np.ndarray:
    """Rise (m, + up, - down) of each footstep (decision S101): the landing heel's height above the other foot's
    heel, so a step-to-step stair's lead step rises one stair and the trail step onto the same stair is 0."""
    return _heel_offsets(steps, initial)[:, 2]


def pendulum_bounce(steps: list[Footstep], ev: Events, initial: dict, user: UserProfile) -> np.ndarray:
    """Peak-to-peak pelvis bounce (m) of each step (decision S29): ``pelvis_bounce_m x h(s_k) / h(s_user)``, with
    ``h`` :func:`pendulum_rise` of the user's leg, ``s_k`` the step's heel-to-heel distance along the landing
    foot's heading and ``s_user`` the comfortable step of the user's stature, 0.415 x height (the mean that
    :meth:`UserProfile.from_seed` draws around): a comfortable step keeps the user's bounce, and a profile whose
    ``step_length_m`` was shortened (a slow patient) bounces as its steps, not as its stature."""
    s = step_lengths(steps, initial)
    ref = float(pendulum_rise(np.array([COMFORTABLE_STEP_PER_HEIGHT * user.height_m]), user.leg_length_m)[0])
    return user.pelvis_bounce_m * pendulum_rise(s, user.leg_length_m) / max(ref, 1e-9)


def population_bounce(steps: list[Footstep], initial: dict, user: UserProfile) -> np.ndarray:
    """Peak-to-peak pelvis bounce (m) of each step (decision S74): ``(pelvis_bounce_m / 0.0375) x h(s_k / K0, L)``,
    the rise that seed 003 eq. 1 with mobgap's population K0 = 4.587/4 (W46) reads as the step ``s_k`` (seed 003
    eq. 1 solved for h, :func:`pendulum_rise`), ``L`` the waist unit's height (the leg the pipeline uses, W62),
    scaled by the user's bounce relative to the middle of its draw so that users still differ (S73: the pendulum
    bounce rose about 1.19 x too little for its step compared with real lower-back recordings)."""
    s = step_lengths(steps, initial)
    return (user.pelvis_bounce_m / MID_PELVIS_BOUNCE_M) * pendulum_rise(s / POPULATION_K, user.sensor_height_m)


def pelvis_knots(steps: list[Footstep], ev: Events, initial: dict, user: UserProfile, t_first: float,
                 t_last: float) -> np.ndarray:
    """The pelvis's base knots (k, 5): time, the middle of the two feet's centres (x, y, z) and their mean yaw, at
    ``t_first``, each bout's heel-off, each initial contact, 0.1 s after each bout's last foot flat and ``t_last``
    (knots closer than 1e-6 s to the previous one dropped), which :func:`pelvis_pose` interpolates (PCHIP). Decision
    S125: one session's knots, built once and shared by the parts of its grid."""
    feet = {f: (np.asarray(h, float), y) for f, (h, y) in initial.items()}

    def config() -> tuple[float, ...]:
        c = [_foot_centre(h, y, user) for h, y in feet.values()]
        yaws = [y for _, y in feet.values()]
        return (*(0.5 * (c[0] + c[1])), 0.5 * (yaws[0] + yaws[1]))

    knots = [(t_first, *config())]
    for k, st in enumerate(steps):
        if ev.bout_start[k]:
            knots.append((float(ev.ho[k]), *config()))
        feet[st.foot] = (np.asarray(st.heel, float), st.yaw)
        knots.append((float(ev.ic[k]), *config()))
        last_of_bout = k == len(steps) - 1 or ev.bout_start[k + 1]
        if last_of_bout:
            knots.append((float(ev.ff[k] + 0.1), *config()))
    knots.append((t_last, *config()))
    kept = [knots[0]]
    for kt in knots[1:]:
        if kt[0] > kept[-1][0] + 1e-6:
            kept.append(kt)
    return np.array(kept)


def pelvis_pose(
    t: np.ndarray,
    steps: list[Footstep],
    ev: Events,
    initial: dict,
    user: UserProfile,
    rng: np.random.Generator | None = None,
    trunk_noise: float = 1.0,
    pelvis: PelvisParams | None = None,
    bounce_mode: str = "constant",
    transfer_offsets: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
    span: tuple[float, float] | None = None,
    vibration_source: tuple[np.ndarray, np.ndarray] | None | bool = False,
    knots: np.ndarray | None = None,
    bout_envelope: str = "step",
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pelvis reference point (n, 3) at the waist-unit height, orientation (n, 3, 3) and base heading (n,).

    ``bout_envelope`` (decision W612): the gait oscillations' envelope over a walking bout - ``"step"`` rises from the
    first swing's heel-off to half a step after the first contact and fades from half a step before the last contact
    to its foot flat, the phase interpolated between the contacts only; ``"contact"`` is at full amplitude from the
    first contact to the last (rising over the half step before the first, from the bounce's crest, and fading over the
    half step after the last, to its crest) and the phase runs at the bout's step rate through its edge contacts
    (:func:`_edge_phase_knots`), as the real lower back marks a bout's edge contacts (W611).

    ``transfer_offsets``: (backward m, lowering m, forward pitch rad) at ``t`` of sit-to-stand transfers
    (:func:`pdrlearn.sim.transfer.transfer_motion`, decision S36), added to the standing pelvis.

    ``pelvis``: None = the model's sway and obliquity; :func:`realistic_pelvis` = decision S27's.
    ``bounce_mode``: ``"constant"`` = the user's ``pelvis_bounce_m`` on every step; ``"pendulum"`` = scaled per
    step by the inverted pendulum's rise for the step's length (decision S29, :func:`pendulum_bounce`);
    ``"population"`` = the rise the real lower back's population K reads as the step (S74, :func:`population_bounce`).

    Decision S44, evaluation in parts: ``span`` = (first, last) time of the whole grid that ``t`` is a part of, and
    ``vibration_source`` = :func:`trunk_vibration_source` over that span (drawn once): every value at a time is then
    the one the whole grid gets there. Decision S125: ``knots`` = :func:`pelvis_knots` over that span, built once for
    all the parts (None: built here)."""
    t_first, t_last = (float(t[0]), float(t[-1])) if span is None else span
    bounce_amp = (pendulum_bounce(steps, ev, initial, user) if bounce_mode == "pendulum"
                  else population_bounce(steps, initial, user) if bounce_mode == "population" else None)
    kn = pelvis_knots(steps, ev, initial, user, t_first, t_last) if knots is None else knots  # decision S125
    base = PchipInterpolator(kn[:, 0], kn[:, 1:], axis=0, extrapolate=True)(t)
    heading = base[:, 3]

    # gait-phase oscillations: phase even at right initial contacts, odd at left ones
    ph_k, prev = [], -1.0
    for st in steps:
        want = 0 if st.foot == "right" else 1
        v = prev + 1
        v += (int(v) % 2) != want
        ph_k.append(v)
        prev = v
    env = np.zeros_like(t)
    for a, b in _bouts(steps, ev):
        if bout_envelope == "contact":  # decision W612: full from the first contact to the last
            half_a, half_b = max(0.5 * ev.step_s[a], 1e-3), max(0.5 * ev.step_s[b], 1e-3)  # crest to trough
            rise_at, rise_s, fall_at, fall_s = ev.ic[a] - half_a, half_a, ev.ic[b], half_b
        else:
            rise_at, rise_s = ev.ho[a], max(ev.ic[a] + 0.5 * ev.step_s[a] - ev.ho[a], 1e-3)
            fall_at, fall_s = ev.ic[b] - 0.5 * ev.step_s[b], max(ev.ff[b] - ev.ic[b] + 0.5 * ev.step_s[b], 1e-3)
        # decision S125: the bout's envelope is 0 before its rise and after its fall (rise or fall clipped to
        # 0 exactly): evaluated on its own samples (one more each side), not on the whole part for every bout
        i0 = max(int(np.searchsorted(t, rise_at)) - 1, 0)
        i1 = int(np.searchsorted(t, fall_at + fall_s, side="right")) + 1
        if i1 <= i0:
            continue
        tb = t[i0:i1]
        kinds = {steps[i].kind for i in range(a, b + 1)}
        amp = 0.3 if kinds <= {"turn", "close"} else 1.0
        rise = smoothstep((tb - rise_at) / rise_s)
        fall = 1.0 - smoothstep((tb - fall_at) / fall_s)
        env[i0:i1] = np.maximum(env[i0:i1], amp * np.minimum(rise, fall))
    if len(steps) > 1 and bout_envelope == "contact":  # decision W612: the phase at the bout's own step rate
        ph = PchipInterpolator(*_edge_phase_knots(steps, ev, ph_k), extrapolate=True)(t)
    elif len(steps) > 1:
        ph = PchipInterpolator(ev.ic, np.array(ph_k, float), extrapolate=True)(t)
    else:
        ph = np.zeros_like(t)
    if bounce_amp is None or not len(steps):  # no step: no bounce envelope either
        amp_t = user.pelvis_bounce_m
    else:  # S29: each step's amplitude at its mid-stance, interpolated between the steps
        amp_t = np.interp(t, ev.ic - 0.5 * ev.step_s, bounce_amp)
    bounce = -env * 0.5 * amp_t * (1.0 + np.cos(2 * np.pi * ph))
    # forward surge of an inverted pendulum: the trunk accelerates forward through single support until
    # the next contact and is braked in the loading response (lower-trunk forward acceleration peaks at
    # initial contact, Zijlstra & Hof 2003); the drop is centred in the loading response (decisions S17)
    surge = env * 0.012 * sawtooth_surge(ph, drop=SURGE_DROP_STEP)
    if pelvis is None:
        sway = -env * PELVIS_SWAY_GAIN * user.pelvis_sway_m * np.sin(np.pi * ph)
    else:  # S27: the model's sway shape (toward the stance foot) with the user's smaller amplitude
        sway = -env * pelvis.sway_m * np.sin(np.pi * ph)
    # pelvic rotation: extreme in terminal swing, reversed quickly around contact and slowly through
    # single support, so the yaw rate peaks near initial contact as on the real lower back (S17)
    yaw_ph = skewed_phase(ph, shift=PELVIS_YAW_LEAD_STEP, skew=PELVIS_YAW_SKEW, centre=0.1)
    yaw_osc = env * np.radians(user.pelvis_rotation_deg) * np.cos(np.pi * yaw_ph)
    pushing = [st.pushing for st in steps]
    rot_gain = (np.interp(t, ev.ic, np.where(pushing, PUSHING_ROTATION_GAIN, 1.0)) if any(pushing)
                else None)  # decision S46 (None: sessions without a trolley bit for bit)
    if rot_gain is not None:
        yaw_osc = yaw_osc * rot_gain
    side = [st.kind == "side" for st in steps]
    if any(side):  # decision S49 (skipped without side steps: other sessions bit for bit)
        side_w = np.interp(t, ev.ic, np.asarray(side, float))
        surge = surge * (1.0 - side_w)
        yaw_osc = yaw_osc * (1.0 - (1.0 - SIDE_ROTATION_GAIN) * side_w)
    if pelvis is None:
        roll = -env * PELVIS_ROLL_GAIN * np.radians(user.pelvis_obliquity_deg) * np.sin(np.pi * ph)
    else:  # S27: the unit leans toward the stance side (right stance: ph in (0, 1), roll > 0 = right side down)
        roll = env * np.radians(pelvis.roll_deg) * np.sin(np.pi * ph + np.radians(pelvis.roll_phase_deg))
    tilt = env * np.radians(1.5) * np.cos(2 * np.pi * ph)

    # heel-strike transient: a short damped velocity kick (braking forward, upward push)
    kick_v = np.zeros_like(t)
    kick_f = np.zeros_like(t)
    kick_l = np.zeros_like(t)
    tau0 = 0.025
    edges = np.searchsorted(t, np.stack([ev.ic, ev.ic + 8 * tau0], axis=1)) if len(steps) else np.zeros((0, 2), int)
    for k in np.flatnonzero(edges[:, 1] > edges[:, 0]):  # decision S125: only the part's own kicks
        st, (i0, i1) = steps[k], edges[k]
        tau = t[i0:i1] - ev.ic[k]
        g = tau * np.exp(-tau / tau0)
        s = 0.3 if st.kind == "turn" else (1.6 if st.kind == "stairs_down" else 1.0)
        kick_v[i0:i1] += 0.05 * s * g
        kick_f[i0:i1] -= 0.03 * s * g
        kick_l[i0:i1] += (0.02 if st.foot == "left" else -0.02) * s * g

    # trunk vibration: band-limited random motion while walking (fwd, left, up in m; yaw, pitch, roll in rad)
    if rng is not None and trunk_noise > 0:
        if vibration_source is False:
            vibration_source = trunk_vibration_source(t_first, t_last, rng, TRUNK_ACC_SD + TRUNK_RATE_SD)
        vib = env[:, None] * trunk_noise * trunk_vibration(t, rng, TRUNK_ACC_SD + TRUNK_RATE_SD, vibration_source)
        if rot_gain is not None:  # decision S46
            vib[:, 3] *= rot_gain
    else:
        vib = np.zeros((t.size, 6))
    ca, sa = np.cos(heading), np.sin(heading)
    pos = np.empty((t.size, 3))
    fwd = surge + kick_f + vib[:, 0]
    sway = sway + kick_l + vib[:, 1]
    if transfer_offsets is not None:  # decision S36: sitting down and standing up
        back, lower, pitch = transfer_offsets
        fwd, bounce, tilt = fwd - back, bounce - lower, tilt + pitch
    pos[:, 0] = base[:, 0] + ca * fwd - sa * sway
    pos[:, 1] = base[:, 1] + sa * fwd + ca * sway
    pos[:, 2] = base[:, 2] + user.sensor_height_m + bounce + kick_v + vib[:, 2]
    rot = euler_zyx(heading + yaw_osc + vib[:, 3], tilt + vib[:, 4], roll + vib[:, 5])
    return pos, rot, heading


# -- force sensors -------------------------------------------------------------------------------
def _ramp(t: np.ndarray, a: float, b: float) -> np.ndarray:
    """Smooth 0 -> 1 between ``a`` and ``b`` (a step at ``a`` when ``b <= a``)."""
    return smoothstep((t - a) / max(b - a, 1e-6))


def foot_loads(
    t: np.ndarray,
    foot: str,
    steps: list[Footstep],
    ev: Events,
    user: UserProfile,
) -> tuple[np.ndarray, np.ndarray]:
    """Heel and forefoot load (N) reaching one foot's force sensors; exactly 0 while the foot is in the air.

    Heel-first contact: the heel loads from initial contact to foot flat and unloads by heel-off; the
    forefoot loads from foot flat and peaks in push-off, ending at toe-off. Toe-first contacts (stairs
    down, backward) load the forefoot first. On stairs the heel load is negligible (thesis ch.2.1.2 [115]).
    Standing (foot flat for more than 1 s): each foot carries half the body weight, half on the heel.
    """
    bw = user.mass_kg * 9.80665
    heel = np.zeros_like(t)
    toe = np.zeros_like(t)
    idx = [int(k) for k in np.flatnonzero([s.foot == foot for s in steps])]
    # contact intervals: (initial contact, foot flat) of the landing, then (heel-off, toe-off) of the next swing
    far = 1e9
    contacts = [(-far, -far, True, False)] + [
        (ev.ic[k], ev.ff[k], ev.theta_ic[k] > 0, steps[k].kind.startswith("stairs")) for k in idx
    ]
    lifts = [(ev.ho[k], ev.to[k]) for k in idx] + [(far, far)]
    ordered = bool(np.all(t[1:] >= t[:-1]))  # decision S126: a sorted grid's interval is a slice (the same samples)
    for (c0, ff, heel_first, stairs), (ho, to) in zip(contacts, lifts, strict=True):
        m = slice(*np.searchsorted(t, [c0, to])) if ordered else (t >= c0) & (t < to)
        tt = t[m]
        mid = 0.5 * (ho + to)
        off = 1.0 - _ramp(tt, mid, to)
        push = _ramp(tt, ff, mid)
        h_scale = 0.1 if stairs else 1.0
        if heel_first:
            h = _ramp(tt, c0, ff) * (0.25 + 0.85 * (1.0 - _ramp(tt, ff, ho))) * (tt < ho)
            f = _ramp(tt, c0 + 0.5 * (ff - c0), ff) * (0.4 + 0.7 * push) * off
        else:
            f = _ramp(tt, c0, ff) * (0.7 + 0.5 * push) * off
            h = _ramp(tt, ff, ff + 0.1) * 0.5 * (1.0 - _ramp(tt, ff, ho)) * (tt < ho)
        h = h * h_scale
        if ho - ff > 1.0:  # standing: blend towards the static share away from the walking events
            s = _ramp(tt, ff, ff + 0.4) * (1.0 - _ramp(tt, ho - 0.4, ho))
            h = (1 - s) * h + s * 0.25
            f = (1 - s) * f + s * 0.25
        heel[m], toe[m] = h * bw, f * bw
    return heel * user.force_coverage, toe * user.force_coverage
