"""The thesis' test paths (ch.7.3.2.1) and calibration exercises (ch.6, ch.7.2.2) as segment lists."""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.sim.path import Backward, Curve, Segment, Stairs, Stand, Straight, Turn, path_length
from pdrlearn.sim.user import UserProfile

HALF_PI = math.pi / 2


def _room(total_m: float, turns: list[float], radius: float = 0.8) -> list[Segment]:
    """A walk of ``total_m`` metres with the given curves (rad), straights spread evenly in between."""
    arcs = sum(abs(a) * radius for a in turns)
    straight = (total_m - arcs) / (len(turns) + 1)
    segs: list[Segment] = [Straight(straight)]
    for a in turns:
        segs += [Curve(a, radius), Straight(straight)]
    return segs


def scenario_a(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Scenario A: 20 m straight on a flat surface (thesis ch.7.3.2.1)."""
    return [Straight(20.0)]


def scenario_b(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Scenario B: ~15 m straight, two pi/2 curves in opposite directions, ~6 m straight; 25 m (ch.7.3.2.1)."""
    r = 2.0 / HALF_PI  # each curve covers 2 m so the total is 25 m
    return [Straight(15.0), Curve(HALF_PI, r), Curve(-HALF_PI, r), Straight(6.0)]


def _c_walk() -> list[Segment]:
    """Scenario C as in ch.7.3.2.1: 6 m, left curve, 10 m, room (14 m, 5 curves), 10 m, left curve,
    room (22 m, 6 curves), room (14 m). The curves' directions are not given (Fig. 91 is not in the text);
    the choice here is recorded in docs/decisions/simulator.md."""
    r = 0.8
    segs: list[Segment] = [Straight(6.0 - HALF_PI * r / 2), Curve(HALF_PI, r), Straight(10.0 - HALF_PI * r / 2)]
    segs += _room(14.0, [-HALF_PI, -HALF_PI, HALF_PI / 2, -HALF_PI / 2, -HALF_PI])
    segs += [Straight(10.0 - HALF_PI * r / 2), Curve(HALF_PI, r)]
    segs += _room(22.0 - HALF_PI * r / 2, [HALF_PI, HALF_PI, -HALF_PI, HALF_PI, HALF_PI, -HALF_PI])
    segs += _room(14.0, [-HALF_PI, -HALF_PI, -HALF_PI])
    return segs


def scenario_c(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Scenario C: 76 m around a building with many curves (thesis ch.7.3.2.1)."""
    return _c_walk()


def scenario_d(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Scenario D: ~11 m straight, 21 stairs up (3.8 m) with three sharp pi/2 curves, then a walk like C;
    ~90 m in total (thesis ch.7.3.2.1). Stair run 0.30 m ("each stair has a size of about 30 cm")."""
    rise, run, r = 3.8 / 21, 0.30, 0.5  # thesis ch.7.3.2.1: 21 stairs, 3.8 m
    segs: list[Segment] = [Straight(11.0)]
    for _ in range(3):
        segs += [Stairs(7, True, rise, run), Curve(HALF_PI, r)]
    rest = 90.0 - path_length(segs)
    c = _c_walk()
    scale = rest / path_length(c)
    return segs + [Straight(s.length_m * scale) if isinstance(s, Straight) else s for s in c]


def terrain_exercise(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Terrain calibration exercise: ~75 strides of the instrumented foot, ~25 each flat/up/down
    (thesis ch.7.2.2: "75 steps in the different types of terrain"). Five rounds of a level walk, a
    flight of 10 stairs up, a turn on the landing and the flight down."""
    segs: list[Segment] = []
    for _ in range(5):
        segs += [
            Straight(4.0 * user.stride_length(speed)),
            Stairs(10, True),
            Turn(math.pi),
            Stairs(10, False),
            Turn(math.pi),
        ]
    return segs


def direction_exercise(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Direction exercise: ~50 strides, half forward, half backward (thesis ch.7.2.2)."""
    segs: list[Segment] = []
    for _ in range(5):
        segs += [Straight(4.0 * user.stride_length(speed)), Stand(1.0), Backward(9), Stand(1.0)]
    return segs


def length_exercise(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Length exercise: ~90 strides, ~30 each with short, normal and long steps (thesis ch.7.2.2)."""
    segs: list[Segment] = []
    for gait in ("short", "normal", "long"):
        for _ in range(2):
            segs += [Straight(12.0 * user.stride_length(speed, gait), gait), Turn(math.pi)]
    return segs


def standstill(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """60 s standing still (thesis Table 34); the start/end standstills make up the whole recording."""
    return []


def rotations(user: UserProfile, speed: str, rng: np.random.Generator, **_) -> list[Segment]:
    """Four pi/2 rotations in place: anticlockwise, two clockwise, anticlockwise (thesis ch.4.3.1.2, Table 35)."""
    return [Turn(HALF_PI), Stand(3.0), Turn(-HALF_PI), Stand(3.0), Turn(-HALF_PI), Stand(3.0), Turn(HALF_PI)]


def random_walk(
    user: UserProfile, speed: str, rng: np.random.Generator, *, length_m: float = 1000.0, **_
) -> list[Segment]:
    """A long walk of ``length_m`` metres: straights of 5-30 m joined by curves of 20-120 degrees."""
    segs: list[Segment] = []
    total = 0.0
    while total < length_m:
        s = float(min(rng.uniform(5.0, 30.0), max(length_m - total, 1.0)))
        segs.append(Straight(s))
        total += s
        if total >= length_m:
            break
        a = float(rng.choice([-1.0, 1.0]) * np.radians(rng.uniform(20.0, 120.0)))
        r = float(rng.uniform(1.5, 8.0))
        segs.append(Curve(a, r))
        total += abs(a) * r
    return segs


SCENARIOS = {
    "A": scenario_a,
    "B": scenario_b,
    "C": scenario_c,
    "D": scenario_d,
    "terrain": terrain_exercise,
    "direction": direction_exercise,
    "length": length_exercise,
    "standstill": standstill,
    "rotations": rotations,
    "walk": random_walk,
}
