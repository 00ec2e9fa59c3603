"""A walking path written as text, for ``pdrlearn simulate --route`` (decision S28).

``"straight:10, up:12, turn:180, down:12, backward:3, stand:2, curve:90:2"`` -> the segments of
:mod:`pdrlearn.sim.path`. Items are separated by commas; each is ``kind:value[:value...]``:

| item | meaning |
|---|---|
| ``straight:M[:GAIT][:PACE]`` | walk M m straight; GAIT short, normal (default), long; PACE slow/normal/fast (S88) |
| ``curve:DEG:RADIUS[:GAIT]`` | walk an arc turning DEG degrees (> 0 left) of RADIUS metres |
| ``up:N[:RISE:RUN][:step-to-step[:FOOT]][:PACE]`` / ``down:...`` | N stairs; ``step-to-step``: S80; FOOT leads: S92; |
| | PACE slow/normal/fast or ``pace=F`` (F x the level step time; S101) |
| ``slope:M:PCT[:GAIT][:PACE]`` | M m (horizontal) on a ramp of PCT % (< 0 downhill; S37); PACE as straight's (S121) |
| ``backward:N[:direct]`` | N backward steps (N >= 0.25, 0.5: half a step, S89); ``direct``: no stop (S67) |
| ``turn:DEG`` | turn DEG degrees on the spot (> 0 left) |
| ``pivot:DEG[:N[:STEP_M]]`` | turn DEG degrees on the spot inside the walk, N steps of STEP_M m (S41) |
| ``spin:DEG:SECONDS`` | stop, turn DEG degrees on the spot in SECONDS, no step: spinning on the tracked foot (S106) |
| ``inplace:N`` | N steps on the spot, marking time (a turning step's swing, no turn, no travel; S105) |
| ``stand:S`` | stand still S seconds |
| ``sit:S`` | sit down on a chair, stay seated S seconds, stand up (no steps; decision S36) |
| ``lie:S[:TURNS_PER_H]`` | sit on a bed edge, lie S s turning over TURNS_PER_H an hour (2), get up (no steps; S58) |
| ``lift:H`` | stand in a lift riding H metres (+H up, -H down; no steps; decision S45) |
| ``escalator:H`` | stand on an escalator rising H m (+H up, -H down; 1-60): 30 deg incline, level landings (S129) |
| ``vehicle:S[:RMS[:RISE]]`` | ride a bus or train for S s (20-3600), vibrating RMS (S71), climbing RISE m (S75) |
| ``cycle:S`` | get on a bicycle, pedal seated S s (20-3600; the foot round the crank), get off (no steps; S99) |
| ``trolley:M[:GAIT]`` | walk M metres straight pushing a trolley (pelvic rotation halved, S46; no walking aid, W456) |
| ``side:M`` | side-step M metres facing ahead (+M left, -M right; lead foot out, trail foot closes; decision S49) |
| ``freeze:S[:HZ[:ACC]]`` | stop, tremble in place S s at HZ (3-8) with the foot's peak ACC m/s^2 (no steps; S51) |

Angles are in degrees here (the Python segments take radians).
"""

from __future__ import annotations

import math

from pdrlearn.errors import DataError
from pdrlearn.route_forms import ROUTE_FORMS
from pdrlearn.sim.cycle import check_cycle
from pdrlearn.sim.freeze import check_freeze
from pdrlearn.sim.lying import check_lie
from pdrlearn.sim.path import (
    MAX_SLOPE_GRADE,
    Backward,
    Curve,
    Cycle,
    Escalator,
    Freeze,
    InPlace,
    Lie,
    Lift,
    Pivot,
    Segment,
    Side,
    Sit,
    Slope,
    Spin,
    Stairs,
    Stand,
    Straight,
    Trolley,
    Turn,
    Vehicle,
    check_pivot,
    stair_pace_error,
    stair_size_error,
)
from pdrlearn.sim.ride import check_rise
from pdrlearn.sim.spin import check_spin
from pdrlearn.sim.user import GAITS, SPEEDS
from pdrlearn.sim.vehicle import check_vehicle

#: decision S80: the stairs option of the step-to-step gait (``up:N[:RISE:RUN]:step-to-step``)
STEP_TO_STEP = "step-to-step"
#: decision S91: the kinds the parser accepts are route_forms.ROUTE_FORMS' (simulate --route's help lists them)
ROUTE_KINDS = tuple(ROUTE_FORMS)
_USAGE = "e.g. 'straight:10, up:12, turn:180, down:12, backward:3, stand:2, curve:90:2'"
#: decision L468: the example a bad item's error line gives for its own kind (else :data:`_USAGE`)
ITEM_EXAMPLES = {"straight": "straight:10", "curve": "curve:90:2", "slope": "slope:100:10 (100 m at a 10 % grade; "
                 "no % sign; -10 goes down)", "up": "up:12", "down": "down:12", "turn": "turn:180",
                 "backward": "backward:3", "stand": "stand:2", "spin": "spin:180:10 (180 deg to the left in 10 s; "
                 "decision S106)",
                 "side": "side:3 (3 m to the left, -3 to the right, at the walker's own pace: side takes no pace; "
                         "decision S49)"}


#: decision S89: the least ``backward:N`` (a quarter of the nominal backward step, ~0.1 m: a shuffle back; an
#: assumption, no seed gives a shortest step)
MIN_BACKWARD_STEPS = 0.25


def _usage(item: str) -> str:
    """Decision L468: the error line's example for the route ``item``'s kind, the general one for other kinds."""
    kind = str(item).split(":")[0].strip()
    return f"e.g. '{ITEM_EXAMPLES[kind]}'" if kind in ITEM_EXAMPLES else _USAGE


def _number(item: str, text: str, *, integer: bool = False, positive: bool = True) -> float:
    try:
        value = int(text) if integer else float(text)
    except ValueError:
        kind = "a whole number" if integer else "a number"
        raise DataError(f"--route item {item!r}: {text!r} is not {kind}; {_usage(item)}") from None
    if not math.isfinite(value) or (positive and value <= 0):  # B300: a signed value is asked to be finite
        want = "a positive number" if positive else "a finite number"
        raise DataError(f"--route item {item!r}: {text!r} must be {want}; {_usage(item)}")
    return value


def _backward_steps(item: str, text: str) -> int | float:
    """Decision S89: ``backward:N``'s N, a whole number of steps or a fraction of the nominal backward step (0.5 =
    half a step, taken as one short step); under :data:`MIN_BACKWARD_STEPS` is one line."""
    n = _number(item, text)
    if n < MIN_BACKWARD_STEPS:
        raise DataError(f"--route item {item!r}: {text!r} backward steps is under {MIN_BACKWARD_STEPS:g} of a step "
                        f"(N counts backward steps of 0.55 x the step length; 0.5 = half a step; decision S89), "
                        "e.g. 'backward:0.5'")
    return int(n) if float(n).is_integer() else n


def _gait(item: str, parts: list[str], at: int) -> str:
    if len(parts) <= at:
        return "normal"
    if parts[at] not in GAITS:
        raise DataError(f"--route item {item!r}: gait {parts[at]!r} must be one of {', '.join(GAITS)}")
    return parts[at]


def _gait_pace(item: str, rest: list[str]) -> tuple[str, str | None]:
    """Decisions S88, S121: a walk's trailing ``[:GAIT][:PACE]`` (``straight:`` / ``slope:``); a lone value that is
    a pace and no gait (``straight:10:fast``) is the pace. A pace outside :data:`SPEEDS` (``run``) is one line naming
    the paces and that there is no running gait (S48)."""
    if len(rest) == 1 and rest[0] not in GAITS and rest[0] in SPEEDS:
        rest = ["normal", rest[0]]
    pace = rest[1] if len(rest) == 2 else None
    if pace is not None and pace not in SPEEDS:
        raise DataError(f"--route item {item!r}: pace {pace!r} must be one of {', '.join(SPEEDS)} (this walk's own "
                        "speed, e.g. 'straight:10:fast'); the simulator has no running gait, no flight phase "
                        "(decisions S48, S88)")
    if len(rest) == 1 and rest[0] not in GAITS:
        raise DataError(f"--route item {item!r}: {rest[0]!r} must be a gait ({', '.join(GAITS)}) or a pace "
                        f"({', '.join(SPEEDS)}; decision S88); the simulator has no running gait (S48)")
    return _gait(item, ["", "", *rest], 2), pace


def _straight(item: str, parts: list[str]) -> Straight:
    """Decision S88: ``straight:M[:GAIT][:PACE]`` (:func:`_gait_pace`)."""
    gait, pace = _gait_pace(item, parts[2:])
    return Straight(_number(item, parts[1]), gait=gait, pace=pace)


def _arity(item: str, parts: list[str], allowed: tuple[int, ...]) -> None:
    if len(parts) - 1 not in allowed:
        want = " or ".join(str(n) for n in allowed)
        raise DataError(f"--route item {item!r}: '{parts[0]}' takes {want} value(s); {_usage(item)}")


#: decision S101: the numeric form of a stair flight's pace (``up:12:pace=1.5``: each stair step 1.5 x the level step)
PACE_PREFIX = "pace="


def _stair_pace(item: str, word: str) -> str | float:
    """Decision S101: a stair flight's trailing pace - an S88 word or ``pace=F`` - checked by the planner's rule."""
    pace: str | float = word
    if word.startswith(PACE_PREFIX):
        text = word[len(PACE_PREFIX):]
        try:
            pace = float(text)
        except ValueError:
            pace = text
    bad = stair_pace_error(pace)
    if bad:
        raise DataError(f"--route item {item!r}: {bad}, e.g. 'up:12:slow' or 'up:12:0.17:0.28:{STEP_TO_STEP}:left:"
                        f"{PACE_PREFIX}1.5'")
    return pace


def _stair_options(item: str, kind: str, parts: list[str]) -> tuple[list[str], bool, str | None, str | float | None]:
    """Decisions S80, S92, S101: ``up``/``down``'s trailing options - ``step-to-step`` (S80), then optionally the
    foot that leads every stair (``left`` / ``right``, S92: "up with the good, down with the bad" of a prosthesis
    user), then optionally the flight's pace (S101: ``slow`` / ``normal`` / ``fast`` or ``pace=F``, last).
    Returns the item's number parts, step-to-step, the leading foot (None: the foot that would step next) and the
    pace (None: the session's speed)."""
    words = []
    while len(parts) > 2 and parts[-1].strip()[:1].isalpha():
        words.insert(0, parts[-1].strip().lower())
        parts = parts[:-1]
    pace = None
    if words and (words[-1] in SPEEDS or words[-1].startswith(PACE_PREFIX)):
        pace = _stair_pace(item, words.pop())
    example = f"e.g. '{kind}:12:0.17:0.29:{STEP_TO_STEP}' or '{kind}:12:0.17:0.29:{STEP_TO_STEP}:left'"
    if not words:
        return parts, False, None, pace
    if words[0] != STEP_TO_STEP or len(words) > 2 or (len(words) == 2 and words[1] not in ("left", "right")):
        if words[0] in ("left", "right"):
            raise DataError(f"--route item {item!r}: a leading foot follows '{STEP_TO_STEP}' (step over step, the "
                            f"feet alternate; decision S92), {example}")
        raise DataError(f"--route item {item!r}: the options after N or RISE:RUN are '{STEP_TO_STEP}' (both feet on "
                        "each stair; decision S80), then the leading foot, 'left' or 'right' (decision S92), then "
                        f"a pace, {', '.join(SPEEDS)} or '{PACE_PREFIX}F' (decision S101), {example}")
    return parts, True, words[1] if len(words) == 2 else None, pace


def parse_route(spec: str) -> list[Segment]:
    """The path segments of a route text (module docstring); a bad item is one :class:`DataError` line."""
    items = [s.strip() for s in str(spec).split(",")]
    if not any(items):
        raise DataError(f"--route is empty; give walking segments, {_USAGE}")
    segments: list[Segment] = []
    for item in items:
        if not item:
            raise DataError(f"--route {spec!r}: an empty item between commas; {_USAGE}")
        parts = [p.strip() for p in item.split(":")]
        kind = parts[0].lower()
        if kind not in ROUTE_KINDS:
            raise DataError(f"--route item {item!r}: unknown kind {parts[0]!r}; use one of {', '.join(ROUTE_KINDS)}")
        if kind == "straight":  # decision S88: straight:M[:GAIT][:PACE]
            _arity(item, parts, (1, 2, 3))
            segments.append(_straight(item, parts))
        elif kind == "trolley":  # decision S46
            _arity(item, parts, (1, 2))
            segments.append(Trolley(_number(item, parts[1]), gait=_gait(item, parts, 2)))
        elif kind in ("lift", "escalator"):  # decision S45: the planner's limits, named after the item
            _arity(item, parts, (1,))
            rise = _number(item, parts[1], positive=False)
            check_rise(kind, rise, f"--route item {item!r}")
            segments.append((Lift if kind == "lift" else Escalator)(rise))
        elif kind == "vehicle":  # decision S71: the planner's limits, named after the item
            _arity(item, parts, (1, 2, 3))  # decision S75: vehicle:S:RMS:RISE (RMS empty: drawn) climbs RISE m
            rms = _number(item, parts[2], positive=False) if len(parts) > 2 and parts[2].strip() else None
            rise = _number(item, parts[3], positive=False) if len(parts) > 3 else 0.0
            seg = Vehicle(_number(item, parts[1]), rms, rise)
            check_vehicle(seg.duration_s, rms, f"--route item {item!r}", rise)
            segments.append(seg)
        elif kind == "cycle":  # decision S99: the planner's limits, named after the item
            _arity(item, parts, (1,))
            seg = Cycle(_number(item, parts[1]))
            check_cycle(seg.duration_s, f"--route item {item!r}")
            segments.append(seg)
        elif kind == "curve":
            _arity(item, parts, (2, 3))
            angle = _number(item, parts[1], positive=False)
            if angle == 0:
                raise DataError(f"--route item {item!r}: a curve needs a non-zero angle (use straight)")
            segments.append(Curve(math.radians(angle), _number(item, parts[2]), gait=_gait(item, parts, 3)))
        elif kind == "slope":
            _arity(item, parts, (2, 3, 4))  # decision S121: slope:M:PCT[:GAIT][:PACE]
            pct = _number(item, parts[2], positive=False)
            if not abs(pct) <= 100 * MAX_SLOPE_GRADE:  # decision S56: the route's unit (percent), named
                raise DataError(f"--route item {item!r}: PCT must be within +-{100 * MAX_SLOPE_GRADE:g} % "
                                "(S37: a steeper ramp is not walked with level steps)")
            grade = pct / 100.0
            gait, pace = _gait_pace(item, parts[3:])  # decision S121: a slope takes a pace as a straight (S88)
            segments.append(Slope(_number(item, parts[1]), grade, gait=gait, pace=pace))
        elif kind in ("up", "down"):
            parts, s2s, lead, pace = _stair_options(item, kind, parts)  # decisions S80, S92, S101
            if len(parts) - 1 not in (1, 3):
                raise DataError(f"--route item {item!r}: '{kind}' takes N or N:RISE:RUN, then optionally "
                                f"':{STEP_TO_STEP}' and the leading foot ':left' / ':right' (decisions S80, S92), "
                                f"e.g. '{kind}:12', '{kind}:12:0.17:0.29' or '{kind}:12:0.17:0.29:{STEP_TO_STEP}:left'")
            size = {} if len(parts) == 2 else {"rise_m": _number(item, parts[2]), "run_m": _number(item, parts[3])}
            if size:  # decision B347: a stair's size in metres, inside the building codes' range widened
                bad = stair_size_error(size["rise_m"], size["run_m"])
                if bad:
                    raise DataError(f"--route item {item!r}: {bad} (up:N:RISE:GOING, e.g. 'up:12:0.17:0.29')")
            segments.append(Stairs(int(_number(item, parts[1], integer=True)), up=kind == "up", step_to_step=s2s,
                                   lead=lead, pace=pace, **size))
        elif kind == "backward":
            _arity(item, parts, (1, 2))
            if len(parts) > 2 and parts[2].strip().lower() != "direct":  # decision S67
                raise DataError(f"--route item {item!r}: the option after N is 'direct' (a reversal straight out "
                                "of forward walking, no stop; decision S67), e.g. 'backward:8:direct'")
            segments.append(Backward(_backward_steps(item, parts[1]), direct=len(parts) > 2))
        elif kind == "turn":
            _arity(item, parts, (1,))
            angle = _number(item, parts[1], positive=False)
            if angle == 0:
                raise DataError(f"--route item {item!r}: a turn needs a non-zero angle")
            segments.append(Turn(math.radians(angle)))
        elif kind == "pivot":  # decision S41
            _arity(item, parts, (1, 2, 3))
            angle = _number(item, parts[1], positive=False)
            if angle == 0:
                raise DataError(f"--route item {item!r}: a pivot needs a non-zero angle")
            n = int(_number(item, parts[2], integer=True)) if len(parts) > 2 else 0
            step = _number(item, parts[3], positive=False) if len(parts) > 3 else 0.15
            check_pivot(math.radians(angle), n, step, f"--route item {item!r}", item)  # decision S103: its words
            segments.append(Pivot(math.radians(angle), n_steps=n, step_m=step))
        elif kind == "spin":  # decision S106: the planner's limits, named after the item
            _arity(item, parts, (2,))
            angle = _number(item, parts[1], positive=False)
            seconds = _number(item, parts[2])
            check_spin(angle, seconds, f"--route item {item!r}")
            segments.append(Spin(math.radians(angle), seconds))
        elif kind == "inplace":  # decision S105: steps on the spot
            _arity(item, parts, (1,))
            segments.append(InPlace(int(_number(item, parts[1], integer=True))))
        elif kind == "side":  # decision S49
            _arity(item, parts, (1,))
            metres = _number(item, parts[1], positive=False)
            if metres == 0:
                raise DataError(f"--route item {item!r}: side-stepping needs a non-zero distance (+M left, -M right)")
            segments.append(Side(metres))
        elif kind == "freeze":  # decision S51: the values are checked by the planner's own line
            _arity(item, parts, (1, 2, 3))
            hz = _number(item, parts[2]) if len(parts) > 2 else None
            acc = _number(item, parts[3]) if len(parts) > 3 else None
            seg = Freeze(_number(item, parts[1]), hz, acc)
            check_freeze(seg.duration_s, hz, acc, f"--route item {item!r}")
            segments.append(seg)
        elif kind == "lie":  # decisions S58, S59: the planner's limits, named after the item
            _arity(item, parts, (1, 2))
            rate = _number(item, parts[2], positive=False) if len(parts) > 2 else None
            seg = Lie(_number(item, parts[1]), rate)
            check_lie(seg.duration_s, rate, f"--route item {item!r}")
            segments.append(seg)
        elif kind == "sit":
            _arity(item, parts, (1,))
            segments.append(Sit(_number(item, parts[1])))
        else:  # stand
            _arity(item, parts, (1,))
            segments.append(Stand(_number(item, parts[1])))
    return segments
