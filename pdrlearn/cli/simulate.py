"""``pdrlearn simulate``: write a simulated PLASYS session folder with ground truth."""

from __future__ import annotations

import math
from pathlib import Path

import typer

from pdrlearn.cli.common import FORCE_HELP, json_safe, print_json, progress, replaced
from pdrlearn.errors import DataError
from pdrlearn.route_forms import route_help

#: decision S30: the step length (m) and step time (s) `simulate --step-length/--step-time` accept: from a 0.1 m
#: shuffle to a 1.0 m stride-long step, from 24 steps/min; the simulator walked all four corners with the steps
#: asked for. Decision S38: the shortest step time 0.25 s (240 steps/min, a fast 3-year-old; S30's 0.4 s was the
#: adults' walking range, not a simulator limit: it walks 0.25 s steps as asked, tests/test_sim_child.py)
STEP_LENGTH_RANGE_M, STEP_TIME_RANGE_S = (0.1, 1.0), (0.25, 2.5)
#: decision S38: `simulate --height` (m: a 1-year-old to a very tall adult) and `--leg-length` (as a fraction of
#: the stature: a toddler's ~0.4 to a long-legged adult's 0.6; the simulator's adults are 0.53)
HEIGHT_RANGE_M, LEG_PER_HEIGHT_RANGE = (0.7, 2.2), (0.35, 0.6)
#: decision S98: `simulate --length-bounds` (m, stride lengths): above 0, up to 4 m (twice the 2 m stride of the
#: longest step --step-length takes; a sanity range, not a gait limit)
LENGTH_BOUNDS_RANGE_M = (0.0, 4.0)
#: decision S97: `simulate --step-width` (m, between the feet's centre lines): 0 = a tandem walk (heel to toe on one
#: line) to 0.5 m, a wide base well past the 0.08-0.14 m the simulator's users draw
STEP_WIDTH_RANGE_M = (0.0, 0.5)
#: decision S33: `simulate --mag-disturbance` (uT, sd of the indoor field disturbances): from none to twice the
#: 45 uT Earth field the simulator uses (a steel-framed corridor); the Python knob has no upper bound
MAG_DISTURBANCE_MAX_UT = 90.0
#: decision S85: `simulate --baro-drift` (hPa/h, SD of the weather's drift rate): 5x the fastest weather's 2 hPa/h
#: (the WMO "very rapidly" tendency, W370), room to test a drift far beyond it; the Python knob has no upper bound
BARO_DRIFT_MAX_HPA_PER_H = 10.0
#: decision S34: the body axes `--waist-mount AXIS:DEG` turns the waist unit about (forward, left, up)
MOUNT_AXES = {"x": 0, "y": 1, "z": 2}
#: decision S48: a custom step faster than this (m/s) is warned: the simulator has no running gait (no flight
#: phase; walking stance, bounce and rockers), so it is fast walking at a running speed. 2.0 m/s is about the
#: preferred walk-to-run transition speed of adults (Hreljac 1993: 2.07 m/s; not a seed)
RUNNING_SPEED_MPS = 2.0
#: decision S43: `simulate --sit-start/--sit-end` (s seated at the start / end of the session); decision S61: up to a
#: day (was an hour, S43, set when a simulated hour took ~1 GB of memory, S44; S62 cut it further), as `lie:S`
SIT_MAX_S = 86_400.0  # = pdrlearn.sim.lying.MAX_LIE_S (tests/test_sim_lying.py)
#: decision S94: = pdrlearn.sim.body.STANCE_TIME_ASYMMETRY_MAX (kept here so the help needs no numpy import;
#: tests/test_sim_s40.py checks they agree)
STANCE_TIME_ASYMMETRY_MAX = 0.2
#: decision S90: `simulate --stand` (the standstill before and after the walk, Python's ``stand_s``, default 5 s,
#: thesis ch.8). 0.5 s: the trial's clinic TUG (the walker goes at once); under it the first swing would start
#: before the settled stance the body model begins with (an assumption: no seed gives a shortest standstill);
#: up to an hour
STAND_RANGE_S = (0.5, 3600.0)
#: decision S115: `simulate --swing-height` (m): the heel's swing apex on a level step at normal speed, up to 0.30 m
#: (past the drawn users' own, ours); decision S118: from 0.06 m - below it the unit's apex is set by the contact's
#: dorsiflexion and stopped falling (users 16700-16703), so a lower value would promise a lower foot than simulated
SWING_HEIGHT_RANGE_M = (0.06, 0.30)
#: decision S116: `simulate --pelvis-sway` (m, the amplitude of the pelvis's side-to-side sway): 0 (none) to
#: 0.15 m, past the widest walking sway we know of (ours; the users draw 0.025-0.04)
PELVIS_SWAY_RANGE_M = (0.0, 0.15)



def parse_gaps(texts: list[str]) -> tuple:
    """Decisions S83, B370: ``--gap UNIT:START:DURATION`` values split at ``:`` (the syntax only) and checked by
    :func:`pdrlearn.sim.simulate.check_gaps`, whose one line names the bad value and the form."""
    from pdrlearn.sim.simulate import check_gaps

    return check_gaps([tuple(str(text).split(":")) for text in texts or []], option="--gap")


def parse_jerk_size(text: str | None) -> dict:
    """Decision S114: ``--trunk-jerk-size DEG_LO:DEG_HI:CM_LO:CM_HI`` as the knobs ``trunk_jerk_deg`` and
    ``trunk_jerk_m``; one ``error:`` line naming the option otherwise (the ranges are checked by the knobs)."""
    if text is None:
        return {}
    from pdrlearn.sim.trunk_jerks import JERK_DEG_MAX, JERK_M_MAX, check_jerk_options

    try:
        d0, d1, c0, c1 = (float(x) for x in str(text).split(":"))
        check_jerk_options(0.0, (d0, d1), (c0 / 100.0, c1 / 100.0))
    except (ValueError, DataError):
        raise DataError(f"--trunk-jerk-size {text!r}: give DEG_LO:DEG_HI:CM_LO:CM_HI with 0 <= LO <= HI, tilts up to "
                        f"{JERK_DEG_MAX:g} deg and bumps up to {JERK_M_MAX * 100:g} cm, e.g. 4:12:1.5:4") from None
    return {"trunk_jerk_deg": (d0, d1), "trunk_jerk_m": (c0 / 100.0, c1 / 100.0)}


def parse_transfer_time(text: str) -> tuple[float, float]:
    """Decision S95: ``--transfer-time LO:HI`` as ``(lo, hi)`` seconds; one ``error:`` line naming the option and a
    valid form otherwise (the range is checked by :func:`pdrlearn.sim.simulate.check_transfer_s`)."""
    from pdrlearn.sim.transfer import TRANSFER_TIME_RANGE_S

    lo_ok, hi_ok = TRANSFER_TIME_RANGE_S
    try:
        lo, hi = (float(x) for x in str(text).split(":"))
    except ValueError:
        lo = hi = math.nan
    if not (math.isfinite(lo) and math.isfinite(hi) and lo_ok <= lo <= hi <= hi_ok):
        raise DataError(f"--transfer-time {text!r}: give LO:HI seconds with {lo_ok:g} <= LO <= HI <= {hi_ok:g}, e.g. "
                        "--transfer-time 3:6 for a frail person's slow sit-to-stand (default 1.5:2.5)")
    return lo, hi


def parse_gyro_bias_model(text: str) -> float | None:
    """Decision S110: ``--gyro-bias-model walk`` (S12's unbounded random walk: None) or ``gm:TAU`` (a first-order
    Gauss-Markov drift of correlation time TAU s, 1-100000: TAU); one ``error:`` line naming the option otherwise."""
    word = str(text).strip().lower()
    if word == "walk":
        return None
    head, _, tail = word.partition(":")
    try:
        tau = float(tail) if head == "gm" else math.nan
    except ValueError:
        tau = math.nan
    if not (math.isfinite(tau) and 1.0 <= tau <= 1e5):
        raise DataError(f"--gyro-bias-model {text!r}: give walk (S12's random walk, the default) or gm:TAU with TAU "
                        "1-100000 s, e.g. gm:288 (the foot's bias bounded at Table 6's sd; decision S110)")
    return tau


def simulate_cmd(
    scenario: str | None = typer.Option(
        None,
        "--scenario",
        "-s",
        help="A, B, C, D (thesis ch.7.3), terrain, direction, length (calibration "
        "exercises), standstill, rotations or walk. Give this or --route.",
    ),
    route: str | None = typer.Option(
        None,
        "--route",
        help=route_help(),  # decision S91: every item kind the parser accepts, from its table (S56: no emoji)
    ),
    user_seed: int = typer.Option(..., "--user-seed", "-u", help="Selects the simulated user (>= 0)."),
    out: Path = typer.Option(..., "--out", "-o", help="Session folder to create (must not exist or be empty; "
                             "--force replaces a session simulate wrote)."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP + " Only a session folder simulate wrote."),
    speed: str = typer.Option("normal", "--speed", help="slow, normal or fast."),
    rate: float = typer.Option(20.0, "--rate", help="Output rate in Hz: 100 divided by an integer (20 = PLASYS)."),
    seed: int = typer.Option(0, "--seed", help="Randomness of the walk and the sensors (>= 0)."),
    length_m: float = typer.Option(1000.0, "--length-m", help="Path length of the 'walk' scenario (m)."),
    clock_offset_s: float = typer.Option(0.0, "--clock-offset", help="Waist clock offset vs the foot unit (s)."),
    clock_drift_ppm: float = typer.Option(0.0, "--clock-drift-ppm", help="Waist clock drift (ppm)."),
    drop_rate: float = typer.Option(0.0, "--drop-rate", help="Fraction of foot packets lost (0-0.5)."),
    gap: list[str] = typer.Option([], "--gap", help="A data gap (a battery swap) UNIT:START:DURATION, seconds on "
                                  "the foot clock, UNIT foot, waist or both; repeatable (decision S83)."),
    irregular_rate: float = typer.Option(0.0, "--irregular-rate", help="Fraction of irregular steps (0-1)."),
    variability: float = typer.Option(
        1.0, "--variability", help="Scale of the stride-to-stride variability (step length / time CV 2-3.5 % at 1, "
        "the default; 0 = identical strides; 2.5 = a dual-task walk's ~2.5x CV; decision S76)."),
    foot_mount_pitch: float = typer.Option(
        0.0, "--foot-mount-pitch", help="Extra toes-down tilt of the foot unit (deg), e.g. 50 for an instep mount."
    ),
    pelvis: str = typer.Option(
        "model",
        "--pelvis",
        help="model (default) or realistic: the pelvis rolls toward the stance side with a smaller sway, "
        "drawn per user (decision S27).",
    ),
    step_length: float | None = typer.Option(
        None, "--step-length", help="With --route: the step length (m, one foot to the other) walked on the "
        f"route's normal-gait items at --speed, {STEP_LENGTH_RANGE_M[0]:g}-{STEP_LENGTH_RANGE_M[1]:g} "
        "(default: the user's own; short/long items scale it; decision S30)."),
    step_time: float | None = typer.Option(
        None, "--step-time", help="With --route: the step time (s, contact to the other foot's contact) at "
        f"--speed, {STEP_TIME_RANGE_S[0]:g}-{STEP_TIME_RANGE_S[1]:g} (cadence = 60 / step time; default: the "
        "user's own; decision S30)."),
    bounce: str = typer.Option(
        "constant",
        "--bounce",
        help="constant (default): the user's pelvis bounce on every step; pendulum: scaled by the inverted "
        "pendulum's rise for each step's length, so short slow steps bounce less (decision S29); population: "
        "the rise that real lower backs' population K (4.587/4) reads as the step, for checking the uncalibrated "
        "lower back (decision S74). A lower-back (waist) study should use population (a nurse trial's "
        "uncalibrated lower-back distance: -15 % with the default, -1.5 / -2.8 % with it; decision S124).",
    ),
    rocker: str = typer.Option(
        "hermite", "--rocker", help="The simulated heel rocker (initial contact -> foot flat): hermite (default) "
        "stops the foot at foot flat, which puts a second |acc| peak ~0.1 s after the contact that real feet do not "
        "have (steps decision 30); smooth comes to rest gradually (decision S31). Simulated feet WITHOUT force "
        "sensors time their contacts on that peak: use smooth for foot-only step times (decision S63).",
    ),
    contact: str = typer.Option(
        "heel", "--contact", help="heel (default): level steps land on the heel (the heel rocker); forefoot: they "
        "land on the forefoot, toes down 12 deg, the heel lowered about the ball after the contact - a toe walker "
        "(mild / moderate: the heel does touch down; decision S108). Stairs keep their own contacts."),
    foot_sensor_pos: float | None = typer.Option(
        None, "--foot-sensor-pos", help="The foot unit's distance from the heel as a share of the foot length, "
        "0.05-0.85 (default: the user's own, 0.25-0.50; 0.70 = on the forefoot dorsum; decision S109)."),
    foot_sensor_height: float | None = typer.Option(
        None, "--foot-sensor-height", metavar="METERS", help="The foot unit's height above the sole (m), 0.01-0.15 "
        "(default: the user's own, 0.03-0.07; meta.json's user.foot_sensor_height_m records it; decision S112)."),
    foot_mount_roll: float = typer.Option(
        0.0, "--foot-mount-roll", help="Sideways tilt of the foot unit about the foot's forward axis (deg, -90 to "
        "90; + lifts the unit's left edge), after --foot-mount-pitch (decision S113)."),
    pelvis_height: float | None = typer.Option(
        None, "--pelvis-height", help="The waist unit's standing height (m), 0.5-1.2 x the leg length (default: the "
        "user's own, 0.55-0.6 x height): lower it for a crouch-like pelvis (decision S109)."),
    gyro_bias_model: str = typer.Option(
        "walk", "--gyro-bias-model", help="The gyroscopes' bias drift: walk (default: S12's unbounded random walk) "
        "or gm:TAU, a first-order Gauss-Markov drift of correlation time TAU s with the same short-term steps, "
        "bounded (gm:288: the foot's vertical bias at thesis Table 6's sd, for walks over ~10 min; decision S110)."),
    bounce_scale: float = typer.Option(
        1.0, "--bounce-scale", help="A factor on the user's pelvis bounce, 0-3 (default 1; 0.5 = a damped bounce, "
        "e.g. crouch-like; decision S109)."),
    heading0: float = typer.Option(
        0.0, "--heading0", help="Initial walking direction (deg, ENU: 0 = east, 90 = north, counter-clockwise), "
        "-360 to 360; the magnetometer sees it, a waist-only track does not (decision S32)."),
    mag_disturbance: float = typer.Option(
        3.0, "--mag-disturbance", help=f"SD of the indoor magnetic field disturbances (uT), 0-"
        f"{MAG_DISTURBANCE_MAX_UT:g} (default 3; 0 = the clean Earth field; decision S33)."),
    baro_drift: float = typer.Option(
        0.3, "--baro-drift", metavar="HPA_PER_H", help="SD of the weather's barometric drift rate (hPa/h), drawn "
        f"once per session (default 0.3, decision S4; 2 = the fastest weather, W370), 0-{BARO_DRIFT_MAX_HPA_PER_H:g}; "
        "meta.json's sensor_errors.wBarometer.drift_hpa_per_h is the rate drawn (decision S85)."),
    waist_mount: str | None = typer.Option(
        None, "--waist-mount", help="Turn the waist unit on the belt, AXIS:DEG about the body's x (forward), y "
        "(left) or z (up), e.g. 'z:90' or 'z:90,x:180' (applied right to left as rotations of the unit); "
        "meta.json keeps the belt frame, so the tracker's frame inference and its warnings are what this "
        "exercises (decision S34)."),
    waist_mount_drift: str | None = typer.Option(
        None, "--waist-mount-drift", metavar="AXIS:DEG", help="A waist unit that turns on the belt during the "
        "session: the mount at the end of the recording, in --waist-mount's syntax (e.g. 'y:20'); the unit turns at "
        "a constant rate from --waist-mount (default none) at the first sample to it at the last (decision S117)."),
    waist_reclip: str | None = typer.Option(
        None, "--waist-reclip", metavar="T:AXIS:DEG", help="The waist unit re-clipped at once at T s: the mount "
        "turns within 0.5 s from --waist-mount (default none) to AXIS:DEG[,AXIS:DEG] (--waist-mount's syntax), e.g. "
        "'1800:z:90'; meta.json knobs.waist_reclip says when and how; not with --waist-mount-drift (decision S123)."),
    graded_slopes: bool = typer.Option(
        False, "--graded-slopes", help="Slopes walked with the grade's own gait: the speed x Tobler's hiking "
        "function (1 on the level, 0.42 at +25 %, 0.59 at -25 %), split evenly between a shorter step and a "
        "longer step time (default: level steps on every grade; decision S121)."),
    fatigue: float = typer.Option(
        0.0, "--fatigue", metavar="PCT", help="Gradual fatigue: the cadence (so the speed) falls linearly over the "
        "session's steps to (100 - PCT) % of the user's at the last step, the step lengths unchanged; 0-50 "
        "(default 0; decision S122)."),
    swing_height: float | None = typer.Option(
        None, "--swing-height", metavar="METRES", help="The heel's highest point in a level step's swing (m, "
        f"{SWING_HEIGHT_RANGE_M[0]:g}-{SWING_HEIGHT_RANGE_M[1]:g}; default the user's own, from the toe-off pitch): "
        "0.06 for a shuffler; sets the user's swing_height_m and toe_off_pitch_deg (meta.json user; decisions S115, "
        "S118)."),
    pelvis_sway: float | None = typer.Option(
        None, "--pelvis-sway", metavar="METRES", help="The pelvis's side-to-side sway amplitude (m, "
        f"{PELVIS_SWAY_RANGE_M[0]:g}-{PELVIS_SWAY_RANGE_M[1]:g}; default the user's own, 0.025-0.04); meta.json "
        "user.pelvis_sway_m; not with --pelvis realistic, whose sway is its own draw (decision S116)."),
    step_time_asymmetry: float = typer.Option(
        0.0, "--step-time-asymmetry", help="Hemiparetic gait: each step onto the left foot (--paretic-side) lasts "
        "1 + this times the step onto the other (symmetry ratio - 1, Patterson et al. 2010), e.g. 0.39; the "
        "cadence stays the user's; 0 (default) to below 1 (decision S35); the other side's: --paretic-side right. "
        "Each foot's stance follows its steps' time; --stance-time-asymmetry shortens the paretic side's (S94)."),
    step_length_asymmetry: float = typer.Option(
        0.0, "--step-length-asymmetry", help="Asymmetric steps (after a stroke, with a prosthesis): each step "
        "onto the left foot (--paretic-side) is 1 + this times as long as the step onto the other, e.g. 0.1; the "
        "stride length stays the user's; ics.csv gets each step's length; 0 (default) to below 1 (decision S42). "
        "Only the step times, lengths and (--stance-time-asymmetry) stance are asymmetric: both feet's kinematics "
        "(toe-off pitch, push-off, heel strike) are the same anatomical foot's (decision S94) unless "
        "--prosthetic-side gives one foot its own (S119)."),
    stance_time_asymmetry: float = typer.Option(
        0.0, "--stance-time-asymmetry", help="Shorter stance on the --paretic-side foot (a prosthesis user loads "
        "the prosthetic side for less time): its stance fraction is the user's / (1 + this), its swings longer, the "
        f"step times unchanged, so the other foot's stance is about 1 + this times its own; 0 (default) to below "
        f"{STANCE_TIME_ASYMMETRY_MAX:g} (double support stays; decision S94); the longer stance's foot: "
        "--longer-stance-side."),
    longer_stance_side: str | None = typer.Option(
        None, "--longer-stance-side", help="With --stance-time-asymmetry: the foot whose stance is the longer, left "
        "or right (default: the foot that is not --paretic-side), so a prosthetic side's longer stance needs no "
        "swapped --paretic-side (decision S120)."),
    prosthetic_side: str | None = typer.Option(
        None, "--prosthetic-side", help="One foot of its own, left or right (a prosthetic foot): its steps take "
        "the --prosthetic-* values below in place of the user's; the other foot, the contacts' times and meta.json's "
        "user stay the user's, and both feet's meta.json record the same knobs, so `pdrlearn gait` pairs the two "
        "folders simulated with the same arguments (decision S119)."),
    prosthetic_toe_off_pitch: float | None = typer.Option(
        None, "--prosthetic-toe-off-pitch", metavar="DEG", help="With --prosthetic-side: that foot's toe-off pitch "
        "(deg, -80 to 0; the users' own -58 to -50; a stiff prosthetic ankle about -15): less push-off, a lower "
        "heel in swing (decision S119)."),
    prosthetic_heel_strike_pitch: float | None = typer.Option(
        None, "--prosthetic-heel-strike-pitch", metavar="DEG", help="With --prosthetic-side: that foot's pitch at "
        "heel strike (deg, 0-40; the users' own 17-26; a stiff prosthetic heel about 8; decision S119)."),
    prosthetic_impact_speed: float | None = typer.Option(
        None, "--prosthetic-impact-speed", metavar="M_PER_S", help="With --prosthetic-side: that foot's speed at "
        "contact (m/s, 0.05-2; the users' own 0.45-0.7): the landing's impact (decision S119)."),
    foot: str = typer.Option(
        "right", "--foot", help="The foot that carries the foot unit: right (default) or left. The same arguments "
        "with --foot left give the other foot of the SAME walk (same contacts, waist and trajectory; the foot's "
        "own strides), so `pdrlearn gait LEFT RIGHT` pairs the two folders (decision S54)."),
    paretic_side: str = typer.Option(
        "left", "--paretic-side", help="The foot whose steps --step-time-asymmetry and --step-length-asymmetry "
        "lengthen: left (default) or right (decision S55)."),
    sit_start: float = typer.Option(
        0.0, "--sit-start", help=f"Start the session seated this long (s, 0-{SIT_MAX_S:g}; trunk leaning forward "
        "10-25 deg, feet flat), then stand up (a sit-to-stand) before the standstill and the walk; transfers.csv "
        "has the stand-up (decision S43)."),
    stand: float = typer.Option(
        5.0, "--stand", help=f"The standstill before the first and after the last movement (s, "
        f"{STAND_RANGE_S[0]:g}-{STAND_RANGE_S[1]:g}; default 5, thesis ch.8): with --sit-start / --sit-end it lies "
        "between the stand-up and the walk and between the walk and the sit-down, so it counts in a TUG time; "
        "--stand 0.5 for a clinic TUG's 'go' (decision S90)."),
    sit_end: float = typer.Option(
        0.0, "--sit-end", help=f"End the session by sitting down after the last standstill and staying seated "
        f"this long (s, 0-{SIT_MAX_S:g}; decision S43)."),
    trunk_jerks: float = typer.Option(
        0.0, "--trunk-jerks", help="Involuntary trunk jerks (chorea-like) of the waist unit, jerks per second at "
        "random times, standing and walking: 0.3-0.8 s trunk tilts about a random axis and vertical bumps; their "
        "times in trunk_jerks.csv (0 = none, the default; decision S114)."),
    trunk_jerk_size: str | None = typer.Option(
        None, "--trunk-jerk-size", help="With --trunk-jerks: DEG_LO:DEG_HI:CM_LO:CM_HI, the ranges of each jerk's "
        "peak tilt (deg) and vertical bump (cm); default 4:12:1.5:4 (decision S114)."),
    transfer_time: str | None = typer.Option(
        None, "--transfer-time", metavar="LO:HI", help="Draw each sit-down's and stand-up's duration (s) from LO to "
        "HI, e.g. '3:6' for a frail person's slow sit-to-stand (default 1.5:2.5; every sit:, lie: and "
        "--sit-start / --sit-end transfer; decision S95)."),
    height: float | None = typer.Option(
        None, "--height", help=f"The user at this stature (m, {HEIGHT_RANGE_M[0]:g}-{HEIGHT_RANGE_M[1]:g}, e.g. 0.95 "
        "for a 3-year-old): foot, waist-unit height, swing, pelvis bounce and sway scaled by stature, step length "
        "and step time by dynamic similarity on the leg length (Hof 1996; decision S38)."),
    leg_length: float | None = typer.Option(
        None, "--leg-length", help=f"With --height: the leg length (m, greater-trochanter height, "
        f"{LEG_PER_HEIGHT_RANGE[0]:g}-{LEG_PER_HEIGHT_RANGE[1]:g} x the height; default the user's own proportion, "
        "0.53)."),
    step_width: float | None = typer.Option(
        None, "--step-width", metavar="METERS", help=f"The lateral distance between the feet's centre lines (m, "
        f"{STEP_WIDTH_RANGE_M[0]:g}-{STEP_WIDTH_RANGE_M[1]:g}; default the user's own, 0.08-0.14, scaled with "
        "--height): 0 walks a tandem (heel-to-toe) line, 0.05 a narrow base. Only where the feet land changes; "
        "pdrlearn measures no step width (decision S97)."),
    length_bounds: str | None = typer.Option(
        None, "--length-bounds", metavar="SHORT_NORMAL,NORMAL_LONG", help="The stride-length class bounds (m) "
        "steps.csv's length_class labels by, e.g. 0.5,0.7 for a slow walker's own short / normal / long strides "
        "(default the user's own, from the user's step even under --step-length, S81; meta.json "
        "length_class_bounds_m; decision S98)."),
    no_noise: bool = typer.Option(False, "--no-noise", help="Exact physics: no noise, bias or quantisation."),
    subject: str = typer.Option(None, "--subject", help="The subject's id, written to meta.json \"subject\" "
                                "(track-all's sessions.csv and subjects.csv group by it; B364)."),
    visit: str = typer.Option(None, "--visit", help="The visit's name, written to meta.json \"visit\" (track-all "
                              "pairs each subject's visits by it in changes.csv; B364)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON summary object."),
) -> None:
    """Simulate a foot + waist session (thesis scenarios and calibration exercises) with ground truth.

    Examples:

        pdrlearn simulate --scenario A --user-seed 1 --out out/sim/A_u1

        pdrlearn simulate --scenario A --user-seed 2 --out out/sim/A_u1 --force   # replace a simulated session

        pdrlearn simulate --scenario D --user-seed 7 --speed fast --rate 100 --out out/sim/D_u7 --json

        pdrlearn simulate --route "stand:3, straight:60, stand:3" --speed slow --variability 2.5 \\
            --bounce pendulum --user-seed 4 --rate 100 --out out/sim/dual_u4   # a dual-task walk: 2.5x variability

        pdrlearn simulate --scenario walk --length-m 1000 --user-seed 3 --clock-offset 0.3 \\
            --clock-drift-ppm 50 --drop-rate 0.01 --out out/sim/walk1km

        pdrlearn simulate --route "stand:5, straight:200, stand:5" --gap foot:60:30 --gap both:120:10 \\
            --user-seed 3 --out out/sim/swap   # battery swaps: 30 s without the foot unit, 10 s without both

        pdrlearn simulate --route "straight:5, up:17, turn:180, down:17, backward:3" --user-seed 2 \\
            --out out/sim/floors_u2

        pdrlearn simulate --route "stand:3, straight:16, stand:3" --step-length 0.3 --step-time 0.75 \\
            --bounce pendulum --user-seed 1 --out out/sim/tenmwt_040   # a 0.4 m/s walker: 0.3 m steps at
            # 80 steps/min; --bounce pendulum: its short steps bounce the pelvis less, as a slow walker's do (the
            # default constant bounce gives them a normal step's bounce, which the lower back reads as long steps)

        pdrlearn simulate --route "stand:2, straight:20, stand:2" --height 0.95 --leg-length 0.45 \\
            --step-length 0.36 --step-time 0.3 --user-seed 1 --rate 100 --out out/sim/age3   # a 3-year-old

        pdrlearn simulate --route "straight:5, lift:+9, trolley:10, escalator:-9, straight:5" --user-seed 2 \\
            --out out/sim/mall_u2   # a lift up three storeys, a trolley pushed, an escalator down (S45, S46)
    """
    from pdrlearn.io import write_session
    from pdrlearn.io.meta_keys import label_option
    from pdrlearn.sim import SCENARIOS, SPEEDS, UserProfile, simulate, simulate_path

    labels = {k: label_option(v, "simulate", f"--{k}", what, example, "B364") for k, v, what, example in (
        ("subject", subject, "subject's id", "P07"), ("visit", visit, "visit's name", "visit1"))}
    from pdrlearn.sim.body import BOUNCE_MODES, CONTACT_MODES, PELVIS_MODES, ROCKER_MODES, STEP_TIME_ASYMMETRY_MAX
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import (
        BOUNCE_SCALE_MAX,
        FOOT_SENSOR_HEIGHT_RANGE_M,
        FOOT_SENSOR_POS_RANGE,
        STEP_LENGTH_ASYMMETRY_MAX,
    )

    if (scenario is None) == (route is None):
        raise DataError("simulate: give either --scenario NAME or --route 'straight:10, up:12, ...' (one of them)")
    if scenario is not None and scenario not in SCENARIOS:
        raise DataError(f"--scenario {scenario!r}: must be one of {', '.join(SCENARIOS)}")
    segments = None if route is None else parse_route(route)  # decision S28
    if speed not in SPEEDS:
        raise DataError(f"--speed {speed!r}: must be one of {', '.join(SPEEDS)}")
    if pelvis not in PELVIS_MODES:  # the simulator's own list (S27)
        raise DataError(f"--pelvis {pelvis!r}: must be {' or '.join(PELVIS_MODES)}")
    if bounce not in BOUNCE_MODES:  # decision S29
        raise DataError(f"--bounce {bounce!r}: must be {', '.join(BOUNCE_MODES[:-1])} or {BOUNCE_MODES[-1]}")
    if rocker not in ROCKER_MODES:  # decisions S31, S63
        raise DataError(f"--rocker {rocker!r}: must be {' or '.join(ROCKER_MODES)}")
    if contact not in CONTACT_MODES:  # decision S108
        raise DataError(f"--contact {contact!r}: must be {' or '.join(CONTACT_MODES)}")
    lo, hi = FOOT_SENSOR_POS_RANGE
    if foot_sensor_pos is not None and not (math.isfinite(foot_sensor_pos) and lo <= foot_sensor_pos <= hi):
        raise DataError(f"--foot-sensor-pos {foot_sensor_pos:g}: give the unit's distance from the heel as a share "
                        f"of the foot length, {lo:g} to {hi:g} (0.70 = forefoot dorsum; decision S109)")
    lo, hi = FOOT_SENSOR_HEIGHT_RANGE_M
    if foot_sensor_height is not None and not (math.isfinite(foot_sensor_height) and lo <= foot_sensor_height <= hi):
        raise DataError(f"--foot-sensor-height {foot_sensor_height:g}: give the foot unit's height above the sole in "
                        f"metres, {lo:g} to {hi:g} (0.06 = on the instep; decision S112)")
    if not (math.isfinite(foot_mount_roll) and -90.0 <= foot_mount_roll <= 90.0):  # decision S113
        raise DataError(f"--foot-mount-roll {foot_mount_roll:g}: give a sideways tilt between -90 and 90 degrees")
    if not (math.isfinite(bounce_scale) and 0.0 <= bounce_scale <= BOUNCE_SCALE_MAX):  # decision S109
        raise DataError(f"--bounce-scale {bounce_scale:g}: give a factor on the user's pelvis bounce, 0 to "
                        f"{BOUNCE_SCALE_MAX:g} (1 = the user's own)")
    if pelvis_height is not None and not (math.isfinite(pelvis_height) and pelvis_height > 0):
        raise DataError(f"--pelvis-height {pelvis_height:g}: give the waist unit's standing height in metres "
                        "(0.5-1.2 x the leg length; decision S109)")
    if user_seed < 0 or seed < 0:
        raise DataError("--user-seed and --seed must be non-negative integers")
    if not -90.0 <= foot_mount_pitch <= 90.0:  # beyond +-90 deg the unit would be mounted upside down
        raise DataError(f"--foot-mount-pitch {foot_mount_pitch:g}: give a tilt between -90 and 90 degrees")
    if not (math.isfinite(heading0) and -360.0 <= heading0 <= 360.0):  # decision S32
        raise DataError(f"--heading0 {heading0:g}: give the initial direction in degrees, -360 to 360 "
                        "(0 = east, 90 = north)")
    from pdrlearn.sim.simulate import VARIABILITY_MAX

    if not (math.isfinite(variability) and 0.0 <= variability <= VARIABILITY_MAX):  # S76: the Python knob's range
        raise DataError(f"--variability {variability:g}: give a finite scale from 0 to {VARIABILITY_MAX:g} (1 = the "
                        "user's own stride-to-stride variability, 0 = identical strides)")
    if not (math.isfinite(mag_disturbance) and 0.0 <= mag_disturbance <= MAG_DISTURBANCE_MAX_UT):  # S33
        raise DataError(f"--mag-disturbance {mag_disturbance:g}: give 0-{MAG_DISTURBANCE_MAX_UT:g} uT")
    if not (math.isfinite(baro_drift) and 0.0 <= baro_drift <= BARO_DRIFT_MAX_HPA_PER_H):  # decision S85
        raise DataError(f"--baro-drift {baro_drift:g}: give the SD of the weather's drift rate in hPa per hour, 0 "
                        f"(none) to {BARO_DRIFT_MAX_HPA_PER_H:g} (0.3 = the default, 2 = the fastest weather)")
    mount = parse_mount(waist_mount)  # decision S34
    for name, value, top, example in (("--step-time-asymmetry", step_time_asymmetry, STEP_TIME_ASYMMETRY_MAX,  # S35
                                       "0.39 = the --paretic-side foot's steps 39 % longer than the other's"),
                                      ("--step-length-asymmetry", step_length_asymmetry,  # decision S42
                                       STEP_LENGTH_ASYMMETRY_MAX,
                                       "0.1 = the --paretic-side foot's steps 10 % longer than the other's"),
                                      ("--stance-time-asymmetry", stance_time_asymmetry,  # decision S94
                                       STANCE_TIME_ASYMMETRY_MAX,
                                       "0.1 = the --paretic-side foot's stance fraction the user's / 1.1")):
        if not (math.isfinite(value) and 0.0 <= value < top):
            flip = "right" if paretic_side == "left" else "left"
            other = (f"; for the other foot's longer steps give --paretic-side {flip} {name} {-value:g} (decision "
                     "S93)" if math.isfinite(value) and -top < value < 0 else "")
            raise DataError(f"{name} {value:g}: give 0 (symmetric) to below {top:g} ({example}){other}")
    for name, v in (("--foot", foot), ("--paretic-side", paretic_side), ("--longer-stance-side",  # S54, S55, S120
                    longer_stance_side), ("--prosthetic-side", prosthetic_side)):  # decision S119
        if v not in ("left", "right") and (v is not None or name in ("--foot", "--paretic-side")):
            raise DataError(f"{name} {v!r}: give left or right")
    from pdrlearn.sim.simulate import check_prosthetic_foot

    prosthetic = {"prosthetic_side": prosthetic_side, "prosthetic_toe_off_pitch_deg": prosthetic_toe_off_pitch,
                  "prosthetic_heel_strike_pitch_deg": prosthetic_heel_strike_pitch,
                  "prosthetic_impact_speed_mps": prosthetic_impact_speed}
    check_prosthetic_foot(prosthetic, options={  # decision S119: the line names the CLI's options
        "prosthetic_side": "--prosthetic-side", "prosthetic_toe_off_pitch_deg": "--prosthetic-toe-off-pitch",
        "prosthetic_heel_strike_pitch_deg": "--prosthetic-heel-strike-pitch",
        "prosthetic_impact_speed_mps": "--prosthetic-impact-speed"})
    if not (math.isfinite(stand) and STAND_RANGE_S[0] <= stand <= STAND_RANGE_S[1]):  # decision S90
        raise DataError(f"--stand {stand:g}: give the standstill before and after the walk in seconds, "
                        f"{STAND_RANGE_S[0]:g} to {STAND_RANGE_S[1]:g} (e.g. --stand 0.5 for a clinic TUG)")
    from pdrlearn.sim.trunk_jerks import JERK_RATE_MAX_HZ

    if not (math.isfinite(trunk_jerks) and 0.0 <= trunk_jerks <= JERK_RATE_MAX_HZ):  # decision S114
        raise DataError(f"--trunk-jerks {trunk_jerks:g}: give the trunk jerks per second, 0 (none) to "
                        f"{JERK_RATE_MAX_HZ:g} (1 = about one a second)")
    for name, v in (("--sit-start", sit_start), ("--sit-end", sit_end)):  # decision S43
        if not (math.isfinite(v) and 0.0 <= v <= SIT_MAX_S):
            raise DataError(f"{name} {v:g}: give the seated time in seconds, 0 (none) to {SIT_MAX_S:g}")
    user = with_step_width(scaled_user(UserProfile.from_seed(user_seed), height, leg_length), step_width)  # S38, S97
    user = with_length_bounds(user, length_bounds)  # decision S98
    user = with_swing_and_sway(user, swing_height, pelvis_sway, pelvis)  # decisions S115, S116
    mount_end = None if waist_mount_drift is None else parse_mount(waist_mount_drift, "--waist-mount-drift")  # S117
    reclip = None if waist_reclip is None else parse_reclip(waist_reclip)  # decision S123
    if reclip is not None and mount_end is not None:
        raise DataError("--waist-reclip (an abrupt re-clip) and --waist-mount-drift (a slow slide) cannot be "
                        "combined; give one (decisions S117, S123)")
    if not (math.isfinite(fatigue) and 0.0 <= fatigue <= 50.0):  # decision S122
        raise DataError(f"--fatigue {fatigue:g}: give the percent the speed falls by over the session, 0 to 50 "
                        "(e.g. --fatigue 15)")
    custom = _custom_gait(user, speed, step_length, step_time, route)  # decision S30
    replace = check_sim_out(out, force)  # decision B292: --force replaces a session simulate wrote
    knobs = dict(
        clock_offset_s=clock_offset_s,
        clock_drift_ppm=clock_drift_ppm,
        drop_rate=drop_rate,
        gaps=parse_gaps(gap),  # decisions S83, B370
        irregular_rate=irregular_rate,
        variability=variability,  # decision S76
        foot_mount_pitch_deg=foot_mount_pitch,
        noise=not no_noise,
        pelvis=pelvis,
        bounce=bounce,
        rocker=rocker,
        contact=contact,  # decision S108
        foot_sensor_pos=foot_sensor_pos,  # decision S109
        foot_sensor_height_m=foot_sensor_height,  # decision S112
        foot_mount_roll_deg=foot_mount_roll,  # decision S113
        pelvis_height_m=pelvis_height,  # decision S109
        bounce_scale=bounce_scale,  # decision S109
        gyro_bias_tau_s=parse_gyro_bias_model(gyro_bias_model),  # decision S110
        heading0_deg=heading0,
        mag_disturbance_ut=mag_disturbance,
        baro_drift_hpa_per_h=baro_drift,  # decision S85
        waist_mount_deg=mount,
        **({} if mount_end is None else {"waist_mount_end_deg": mount_end}),  # decision S117
        **({} if reclip is None else {"waist_reclip": reclip}),  # decision S123
        **({"graded_slopes": True} if graded_slopes else {}),  # decision S121
        **({"fatigue_pct": fatigue} if fatigue else {}),  # decision S122
        step_time_asymmetry=step_time_asymmetry,
        step_length_asymmetry=step_length_asymmetry,
        stance_time_asymmetry=stance_time_asymmetry,  # decision S94
        sit_start_s=sit_start,
        sit_end_s=sit_end,
        stand_s=stand,  # decision S90
        **({} if transfer_time is None else {"transfer_s": parse_transfer_time(transfer_time)}),  # decision S95
        trunk_jerk_rate_hz=trunk_jerks,  # decision S114
        **parse_jerk_size(trunk_jerk_size),  # decision S114
        instrumented_foot=foot,
        paretic_side=paretic_side,
        longer_stance_side=longer_stance_side,  # decision S120
        **prosthetic,  # decision S119
    )
    label = scenario or "route"
    with progress(f"simulating {label}", total=2, enabled=not as_json) as advance:
        if segments is None:
            session = simulate(scenario, user, speed, rate_hz=rate, seed=seed, length_m=length_m, **knobs)  # S39
        else:
            session = simulate_path(
                segments,
                custom or user,
                speed=speed,
                rate_hz=rate,
                seed=seed,
                name=f"route_u{user_seed}_{speed}_s{seed}" + (f"_h{height:g}m" if height is not None else "") + (
                    f"_step{custom.step_length(speed):.3g}m_{custom.step_time(speed):.3g}s" if custom else "")
                + ("_left" if foot == "left" else ""),  # decision S54
                scenario="route",
                **knobs,
            )
        advance()
        session.meta.update({k: v for k, v in labels.items() if v is not None})  # decision B364: no JSON editing
        write_session(session, out, overwrite=replace)  # atomic: the old session stays until the new one is written
        advance()
    replaced(out, replace)  # decision B320: `replaced PATH` on stderr, as every other command's --force
    st = session.steps
    summary = {
        "out": str(out),
        "scenario": label,
        **({} if route is None else {"route": route}),
        "user_seed": user_seed,
        "speed": speed,
        "height_m": user.height_m,  # decision S38: the user's stature and leg length (scaled with --height)
        "leg_length_m": user.leg_length_m,
        # decision S30: the step length and time walked on normal-gait items (the user's own, or the given ones)
        "step_length_m": round((custom or user).step_length(speed), 4),
        "step_time_s": round((custom or user).step_time(speed), 4),
        "seed": seed,
        "rate_hz": rate,
        "duration_s": round(session.duration_s, 3),
        "instrumented_foot": foot,  # decision S54
        "strides": 0 if st is None else int(len(st)),
        "steps_both_feet": int(len(session.extras["ics"])),
        "distance_m": round(float(session.meta["distance_m"]), 3),
        "dropped_samples": session.meta["dropped_samples"],
        "terrain": {} if st is None else {str(k): int(v) for k, v in st["terrain"].value_counts().items()},
    }
    if as_json:
        print_json(json_safe(summary))
    else:
        what = "route" if route is not None else f"scenario {scenario}"
        typer.echo(
            f"{out}: {what}, user {user_seed}, {speed}, {summary['duration_s']:.1f} s, "
            f"{summary['strides']} strides of the {foot} foot, {summary['distance_m']:.1f} m, "
            f"{rate:g} Hz" + (f", steps {summary['step_length_m']:g} m in {summary['step_time_s']:g} s "
                              f"({summary['step_length_m'] / summary['step_time_s']:.2f} m/s)" if custom else "")
        )


def with_length_bounds(user, length_bounds: str | None):
    """Decision S98: ``user`` labelling strides by ``--length-bounds`` (``user`` itself without it); one error line
    for bounds that are not two increasing lengths within :data:`LENGTH_BOUNDS_RANGE_M`."""
    if length_bounds is None:
        return user
    import dataclasses

    from pdrlearn.cli.common import parse_length_bounds

    bounds = parse_length_bounds(length_bounds)
    lo, hi = LENGTH_BOUNDS_RANGE_M
    if len(bounds) != 2 or not all(math.isfinite(b) and lo < b <= hi for b in bounds) or bounds[0] >= bounds[1]:
        raise DataError(f"simulate: --length-bounds {length_bounds}: give the short/normal and normal/long "
                        f"stride-length bounds in metres, two increasing numbers above {lo:g} and up to {hi:g}, "
                        "e.g. 0.5,0.7")
    return dataclasses.replace(user, length_bounds_m=[float(b) for b in bounds])


def _metres(option: str, value: float, bounds: tuple[float, float], what: str) -> float:
    """Decisions S115, S116: ``value`` in ``bounds`` (m); one error line naming ``option`` and ``what`` otherwise."""
    lo, hi = bounds
    if not (math.isfinite(value) and lo <= value <= hi):
        raise DataError(f"simulate: {option} {value:g}: give {what} in metres, {lo:g} to {hi:g}")
    return float(value)


def with_swing_and_sway(user, swing_height: float | None, pelvis_sway: float | None, pelvis: str = "model"):
    """Decisions S115, S116: ``user`` with ``--swing-height`` (its ``swing_height_m`` and the toe-off pitch that
    lifts the heel to it on a level step, :func:`pdrlearn.sim.body.toe_off_pitch_for_apex`) and ``--pelvis-sway``
    (its ``pelvis_sway_m``); ``user`` itself without them; one error line for a value out of range or a sway with
    ``--pelvis realistic`` (S27 draws its own sway)."""
    changes = {}
    if swing_height is not None:
        from pdrlearn.sim.body import toe_off_pitch_for_apex

        apex = _metres("--swing-height", swing_height, SWING_HEIGHT_RANGE_M,
                       "the heel's highest point in a level step's swing")
        changes.update(swing_height_m=apex, toe_off_pitch_deg=toe_off_pitch_for_apex(user, apex))
    if pelvis_sway is not None:
        if pelvis == "realistic":
            raise DataError("simulate: --pelvis-sway sets the model pelvis's sway; --pelvis realistic draws its own "
                            "(decision S27) - leave out one of them")
        changes["pelvis_sway_m"] = _metres("--pelvis-sway", pelvis_sway, PELVIS_SWAY_RANGE_M,
                                           "the pelvis's side-to-side sway amplitude")
    if not changes:
        return user
    import dataclasses

    return dataclasses.replace(user, **changes)


def with_step_width(user, step_width: float | None):
    """Decision S97: ``user`` walking with ``--step-width`` between the feet's centre lines (``user`` itself without
    it); one error line for a value that is not finite or outside :data:`STEP_WIDTH_RANGE_M`."""
    if step_width is None:
        return user
    lo, hi = STEP_WIDTH_RANGE_M
    if not (math.isfinite(step_width) and lo <= step_width <= hi):
        raise DataError(f"simulate: --step-width {step_width:g}: give the distance between the feet's centre lines "
                        f"in metres, {lo:g} (a tandem walk) to {hi:g}")
    import dataclasses

    return dataclasses.replace(user, step_width_m=float(step_width))


def scaled_user(user, height: float | None, leg_length: float | None):
    """Decision S38: ``user`` at ``--height`` / ``--leg-length`` (:meth:`UserProfile.scaled`), ``user`` itself
    without them; one error line for a value outside :data:`HEIGHT_RANGE_M` / :data:`LEG_PER_HEIGHT_RANGE`."""
    if height is None:
        if leg_length is not None:
            raise DataError("simulate: --leg-length needs --height (the stature the body is scaled to), e.g. "
                            "--height 0.95 --leg-length 0.45")
        return user
    lo, hi = HEIGHT_RANGE_M
    if not (math.isfinite(height) and lo <= height <= hi):
        raise DataError(f"simulate: --height {height:g}: give the stature in metres, {lo:g}-{hi:g}")
    if leg_length is not None:
        lo, hi = (f * height for f in LEG_PER_HEIGHT_RANGE)
        if not (math.isfinite(leg_length) and lo <= leg_length <= hi):
            raise DataError(f"simulate: --leg-length {leg_length:g}: give {lo:.2f}-{hi:.2f} m for --height "
                            f"{height:g} ({LEG_PER_HEIGHT_RANGE[0]:g}-{LEG_PER_HEIGHT_RANGE[1]:g} x the height)")
    return user.scaled(height, leg_length)


def parse_mount(spec: str | None, option: str = "--waist-mount") -> tuple[float, float, float]:
    """Decision S34: ``--waist-mount 'z:90,x:180'`` -> the rotation vector (deg) of the unit's turn about the body
    axes (:data:`MOUNT_AXES`), the items applied right to left; None or empty -> no turn. One error line for a
    malformed item, naming ``option`` (S117: ``--waist-mount-drift`` has the same syntax)."""
    from scipy.spatial.transform import Rotation

    if spec is None or not spec.strip():
        return (0.0, 0.0, 0.0)
    rot = Rotation.identity()
    for item in spec.split(","):
        axis, _, deg = item.strip().partition(":")
        try:
            angle = float(deg)
        except ValueError:
            angle = math.nan
        if axis.strip().lower() not in MOUNT_AXES or not math.isfinite(angle) or not -360 <= angle <= 360:
            raise DataError(f"{option} {spec!r}: '{item.strip()}' is not AXIS:DEG; give x, y or z (forward, "
                            "left, up) and -360 to 360 degrees, e.g. 'z:90' or 'z:90,x:180'")
        vec = [0.0, 0.0, 0.0]
        vec[MOUNT_AXES[axis.strip().lower()]] = math.radians(angle)
        rot = rot * Rotation.from_rotvec(vec)
    return tuple(round(float(v), 9) for v in math.degrees(1.0) * rot.as_rotvec())


def parse_reclip(spec: str) -> tuple[float, tuple[float, float, float]]:
    """Decision S123: ``--waist-reclip 'T:AXIS:DEG[,AXIS:DEG]'`` -> (T s, the new mount's rotation vector, deg, as
    :func:`parse_mount`); one line for a malformed value."""
    head, _, mount = spec.partition(":")
    try:
        t_s = float(head)
    except ValueError:
        t_s = math.nan
    if not (math.isfinite(t_s) and t_s > 0) or not mount.strip():
        raise DataError(f"--waist-reclip {spec!r}: give T:AXIS:DEG, the time (s, > 0) and the new mount in "
                        "--waist-mount's syntax, e.g. '1800:z:90' or '600:y:20,x:5' (decision S123)")
    return t_s, parse_mount(mount, "--waist-reclip")


#: meta.json's ``source_project`` of a session ``pdrlearn simulate`` wrote (what --force may replace, B292)
SIM_SOURCE = "pdrlearn.sim"


def check_sim_out(out: Path, force: bool) -> bool:
    """Decision B292: whether ``--out`` is an existing session folder to replace (True) or an absent / empty folder
    (False), before any work; one :class:`DataError` line otherwise: a file, a folder in use without ``--force``, or
    with it anything but a session simulate wrote (meta.json ``source_project`` pdrlearn.sim) holding only session
    files (decision B422's :func:`pdrlearn.own_files.refuse_foreign`, as ``import --force``: nothing else deleted)."""
    import json

    from pdrlearn.own_files import OWN, refuse_foreign

    if out.exists() and not out.is_dir():
        raise DataError(f"{out}: is a file; --out must be a folder for the simulated session")
    from pdrlearn.outfolder import check_place

    check_place(out)  # decision B441: a read-only place before the simulation, naming --out (B317's line)
    if not out.is_dir() or not any(out.iterdir()):
        return False
    if not force:
        raise DataError(f"{out}: already exists and is not an empty folder; choose another --out, remove it, or pass "
                        "--force to replace a session simulate wrote")
    try:
        ours = json.loads((out / "meta.json").read_text(encoding="utf-8")).get("source_project") == SIM_SOURCE
    except (OSError, ValueError, AttributeError):
        ours = False
    if not ours:
        raise DataError(f"{out}: is not a session 'pdrlearn simulate' wrote (meta.json source_project "
                        f"{SIM_SOURCE}); --force replaces only that - choose another --out")
    refuse_foreign(out, OWN["session"], "pdrlearn simulate")  # decision B422: the one check of every --force
    return True


def _custom_gait(user, speed: str, step_length: float | None, step_time: float | None, route: str | None):
    """The user with the step length / time walked at ``speed`` set to the given values (decision S30), or None
    when neither is given; one error line for a value outside its range or without --route."""
    import dataclasses

    from pdrlearn.sim.user import SPEED_FACTORS

    if step_length is None and step_time is None:
        return None
    given = [o for o, v in (("--step-length", step_length), ("--step-time", step_time)) if v is not None]
    if route is None:
        verb = "sets" if len(given) == 1 else "set"
        raise DataError(f"simulate: {' and '.join(given)} {verb} the gait of a --route walk; the scenarios keep "
                        "the user's own gait - use --route 'stand:3, straight:16, stand:3' (docs/simulator.md)")
    for name, v, (lo, hi), unit in (("--step-length", step_length, STEP_LENGTH_RANGE_M, "m"),
                                    ("--step-time", step_time, STEP_TIME_RANGE_S, "s")):
        if v is not None and not (math.isfinite(v) and lo <= v <= hi):
            raise DataError(f"simulate: {name} {v:g}: give {lo:g}-{hi:g} {unit}")
    f_len, f_time = SPEED_FACTORS[speed]
    walked = dataclasses.replace(user, **{k: v for k, v in (("step_length_m", step_length and step_length / f_len),
                                                            ("step_time_s", step_time and step_time / f_time)) if v})
    mps = walked.step_length(speed) / walked.step_time(speed)
    if mps > RUNNING_SPEED_MPS:  # decision S48
        import logging

        logging.getLogger("pdrlearn.sim").warning(
            "simulate: steps of %.2f m/s: the simulator has no running gait (no flight phase; walking stance, "
            "bounce and foot roll), so this session is fast walking at a running speed and cadence, not running "
            "(decision S48)", mps)
    changes = {}
    if step_length is not None:
        changes["step_length_m"] = step_length / f_len
        changes["class_step_length_m"] = user.step_length_m  # decision S81: the length classes stay the user's
    if step_time is not None:
        changes["step_time_s"] = step_time / f_time
    return dataclasses.replace(user, **changes)


def register(app: typer.Typer) -> None:
    app.command("simulate")(simulate_cmd)
