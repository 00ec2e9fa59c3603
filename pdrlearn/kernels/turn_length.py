"""Decision C88: a stride that turns takes the length class of its measured length, one stride at a time.

The calibration exercises (thesis ch. 6.1) walk straight, so the length classifier never saw a corner walked at
normal length; the foot's ZUPT stride (thesis ch. 5.1) places such a stride in a class against the user's bounds
directly. Offline ``track`` (:func:`pdrlearn.track.turn_classes.measured_classes_on_turns`), ``track --streaming``
and the runtime :class:`~pdrlearn.runtime.Tracker` (``pdrlearn run``) all call :func:`turn_length_class_one`
(decision C91: one rule on every path). Standard library only, as every kernel the lean runtime imports.
"""

from __future__ import annotations

import math

#: decision L79: a stride turning less than this (rad) is straight (L66 measured the straight-pass strides)
STRAIGHT_MAX_RAD = math.radians(15.0)
#: decisions C88 / C91: a stride turning :data:`STRAIGHT_MAX_RAD` or more takes the length class of its measured
#: length (offline, streamed and run; False: the classifier's class, as before session 35)
TURN_LENGTH_RULE = True


def measured_class_one(length_m: float, bounds) -> str | None:
    """The class whose ``[lo, hi)`` bounds (``{name: (lo, hi)}``) hold ``|length_m|``; None outside every one (a
    later class wins where two overlap)."""
    a = abs(float(length_m))
    out = None
    for name, (lo, hi) in bounds.items():
        if lo <= a < hi:
            out = name
    return out


def turning(turn_rad: float) -> bool:
    """Decision L79: the stride turns :data:`STRAIGHT_MAX_RAD` or more (NaN: straight)."""
    t = float(turn_rad)
    return t == t and abs(t) >= STRAIGHT_MAX_RAD


def turn_length_class_one(label, proba, length_m: float, turn_rad: float, bounds):
    """Decision C88: ``(label, proba)`` of one stride's length task; a stride turning at least 15 deg (L79) that
    holds a class (``label`` a str) takes the class of its measured horizontal length (:func:`measured_class_one`)
    with one-hot probabilities over ``proba``'s classes (so the gate and the bayes rule weigh that class); any
    other stride, or a length outside every bound, is returned unchanged."""
    if not isinstance(label, str) or not turning(turn_rad):
        return label, proba
    measured = measured_class_one(length_m, bounds)
    if measured is None:
        return label, proba
    return measured, (None if proba is None else {c: float(c == measured) for c in proba})


__all__ = ["STRAIGHT_MAX_RAD", "TURN_LENGTH_RULE", "measured_class_one", "turning", "turn_length_class_one"]
