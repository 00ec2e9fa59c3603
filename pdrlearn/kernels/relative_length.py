"""Decision C117: a stride's length class relative to the median of the session's own strides.

The thesis (ch.6.3) defines short / normal / long per pedestrian, from the average of that pedestrian's strides; a
model trained on other walkers has no input that says what a new walker's normal stride is. The median measured
stride length of the session's flat, forward, straight strides is taken as that walker's normal, and a stride's
class is its measured length against :data:`RELATIVE_BOUNDS` times it. :class:`SessionLength` does it one stride at a
time (the runtime :class:`~pdrlearn.runtime.Tracker`'s ``length_reference="session"``); :func:`session_length_classes`
on a whole stride table (the same running rule, or with ``causal=False`` the median of the whole session). Standard
library only, as every kernel the lean runtime imports.
"""

from __future__ import annotations

import bisect
import math

from pdrlearn.errors import DataError
from pdrlearn.kernels.turn_length import measured_class_one, turning

#: thesis ch.6.3: short <= 30 cm, normal 30-45 cm, long > 45 cm; over the middle of the normal interval (37.5 cm)
#: the bounds are 0.8 and 1.2 times the normal stride (decision C117)
RELATIVE_BOUNDS = (30.0 / 37.5, 45.0 / 37.5)
#: decision C117: the model's class stays until this many eligible strides are in the median (about one straight
#: pass of a calibration exercise, 12 strides; not chosen by data)
WARMUP_STRIDES = 10
#: the values of the tracker's ``length_reference`` (decision C117)
LENGTH_REFERENCES = ("model", "session")


def check_warmup(warmup) -> int:
    """``warmup`` as a whole number >= 1, else one DataError line."""
    if isinstance(warmup, bool) or not isinstance(warmup, int) or warmup < 1:
        raise DataError(f"warmup={warmup!r}: give the number of strides before the session's median is used, a whole "
                        f"number >= 1 (default {WARMUP_STRIDES}, decision C117)")
    return warmup


def check_length_reference(value) -> str:
    """``length_reference`` (decision C117) checked, else one DataError line naming the values."""
    if value not in LENGTH_REFERENCES:
        raise DataError(f"length_reference={value!r} is not one of {', '.join(LENGTH_REFERENCES)} (\"session\": the "
                        "length class against the median of the session's own strides, decision C117)")
    return value


#: decision C131: the tasks length_reference="session" needs: the length class it replaces, and the terrain and
#: direction classes that make a stride eligible (:func:`eligible`)
SESSION_TASKS = ("length", "terrain", "direction")


def check_session_tasks(tasks, where, model_tasks=None) -> None:
    """Decision C131: ``length_reference="session"`` with a model lacking one of :data:`SESSION_TASKS` would change
    nothing and say nothing; one DataError line instead. ``model_tasks``: the bundle's own tasks when the caller
    chose ``tasks`` (decision E291 amended, review R3 F6: the line then names the caller's list, not the model)."""
    missing = [t for t in SESSION_TASKS if t not in tasks]
    if missing and model_tasks is not None and not [t for t in missing if t not in model_tasks]:
        raise DataError(f"length_reference=\"session\" (--length-reference session): tasks=[{', '.join(tasks)}] "
                        f"leaves out {', '.join(missing)}, which the session-relative length class needs (model "
                        f"{where} classifies {', '.join(model_tasks)}); add them to tasks or drop the option "
                        "(decisions C131, E291)")
    if missing:
        raise DataError(f"length_reference=\"session\" (--length-reference session): model {where} classifies no "
                        f"{', '.join(missing)} (its tasks: {', '.join(tasks)}), and the session-relative length class "
                        "needs the length class and, to pick flat forward strides, the terrain and direction classes; "
                        "use a model trained with --tasks terrain,direction,length or drop the option (decision C131)")


def relative_bounds(reference_m: float) -> dict[str, tuple[float, float]]:
    """The class bounds ``{name: (lo, hi)}`` (m) around the normal stride ``reference_m`` (:data:`RELATIVE_BOUNDS`)."""
    lo, hi = RELATIVE_BOUNDS
    return {"short": (0.0, lo * reference_m), "normal": (lo * reference_m, hi * reference_m),
            "long": (hi * reference_m, math.inf)}


def eligible(terrain, direction, length_m: float, turn_rad: float) -> bool:
    """A stride whose length enters the session's median: the model's terrain ``flat`` and direction ``forward``, a
    finite length (its size: a signed steps.csv ``length_m`` too) > 0, turning less than 15 deg (decision L79)."""
    a = abs(float(length_m))
    return terrain == "flat" and direction == "forward" and math.isfinite(a) and a > 0 and not turning(turn_rad)


def relative_class_one(label, proba, length_m: float, reference_m: float):
    """``(label, proba)`` of a stride classed by ``length_m`` against :func:`relative_bounds` of ``reference_m``,
    probabilities one-hot over ``proba``'s classes (as decision C88)."""
    measured = measured_class_one(length_m, relative_bounds(reference_m))
    if measured is None:
        return label, proba
    return measured, (None if proba is None else {c: float(c == measured) for c in proba})


class SessionLength:
    """Decision C117, one stride at a time: the running median of the eligible strides' measured lengths (the
    stride itself included) and the class of each eligible stride against it, once :attr:`warmup` are in."""

    def __init__(self, warmup: int = WARMUP_STRIDES) -> None:
        self.warmup = check_warmup(warmup)
        self._sorted: list[float] = []

    @property
    def n(self) -> int:
        return len(self._sorted)

    def median(self) -> float:
        s, n = self._sorted, len(self._sorted)
        if not n:
            return math.nan
        return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])

    def stride(self, label, proba, length_m: float, *, terrain, direction, turn_rad: float = 0.0):
        """``(label, proba)`` of one stride: the model's for a stride that is not eligible (:func:`eligible`),
        holds no length class, or comes before the warm-up ends; else the session-relative class."""
        if not eligible(terrain, direction, length_m, turn_rad):
            return label, proba
        bisect.insort(self._sorted, abs(float(length_m)))
        if not isinstance(label, str) or self.n < self.warmup:
            return label, proba
        return relative_class_one(label, proba, length_m, self.median())


#: the stride table columns :func:`session_length_classes` reads
TABLE_COLUMNS = ("length_m", "terrain", "direction", "length_class")


def median_is_normal(rows) -> bool:
    """Decision C126's guard: True when the model itself classes fewer than half of the session's eligible strides
    (:func:`eligible`, with a length class) ``short`` and fewer than half ``long``, so that the session's median
    stride lies among the strides the model calls ``normal`` (for classes ordered by length); False for a walk the
    model sees as mostly short or mostly long strides, whose median is not the walker's normal stride. No
    threshold: "half" is the median's own definition."""
    classes = [r["length_class"] for r in rows if isinstance(r["length_class"], str)
               and eligible(r["terrain"], r["direction"], r["length_m"], r.get("turn_angle_rad", 0.0))]
    return all(2 * classes.count(c) < len(classes) for c in ("short", "long"))


def session_length_classes(rows, *, causal: bool = True, warmup: int = WARMUP_STRIDES, guard: bool = False,
                           source: str = "stride table") -> list:
    """Decision C117 on a stride table (a list of dicts, or a DataFrame's ``to_dict("records")``; columns
    :data:`TABLE_COLUMNS`, ``turn_angle_rad`` optional, in walking order): each stride's length class.
    ``causal=True``: :class:`SessionLength` row by row (what the tracker gives, stride by stride); ``False``: the
    median of all the session's eligible strides (offline), and no class changes with fewer than ``warmup`` of them;
    with ``guard=True`` (decision C126, offline only) no class changes either unless :func:`median_is_normal`.
    A missing column is one DataError line naming ``source``."""
    check_warmup(warmup)
    rows = list(rows)
    missing = [c for c in TABLE_COLUMNS if rows and any(c not in r for r in rows)]
    if missing:
        raise DataError(f"{source}: no column {', '.join(missing)}; give the strides of pdrlearn run (steps.csv: "
                        f"{', '.join(TABLE_COLUMNS)}) in walking order")

    def args(r):
        return dict(terrain=r["terrain"], direction=r["direction"], turn_rad=r.get("turn_angle_rad", 0.0))

    if causal:
        run = SessionLength(warmup)
        return [run.stride(r["length_class"], None, r["length_m"], **args(r))[0] for r in rows]
    ref = SessionLength(warmup)
    for r in rows:
        ref.stride(None, None, r["length_m"], **args(r))
    if ref.n < warmup or (guard and not median_is_normal(rows)):
        return [r["length_class"] for r in rows]
    med = ref.median()
    return [relative_class_one(r["length_class"], None, r["length_m"], med)[0]
            if isinstance(r["length_class"], str) and eligible(r["terrain"], r["direction"], r["length_m"],
                                                               r.get("turn_angle_rad", 0.0))
            else r["length_class"] for r in rows]


__all__ = ["RELATIVE_BOUNDS", "WARMUP_STRIDES", "LENGTH_REFERENCES", "TABLE_COLUMNS", "check_warmup",
           "check_length_reference", "relative_bounds", "eligible", "relative_class_one", "SessionLength",
           "median_is_normal", "session_length_classes"]
