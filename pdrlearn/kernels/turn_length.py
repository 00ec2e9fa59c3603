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
#: decision C191: a stride of any turn whose measured |length| lies outside its classified class's ``[lo, hi)`` by
#: more than this share of the nearest bound (and inside another class's bounds) takes the measured class; stated,
#: not fitted: about 4x the foot ZUPT stride MAE of 1.3 % that C88 cites (thesis ch. 5.1), so a measurement error
#: alone does not carry a stride across
CONTRADICTION_MARGIN = 0.05


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


def contradicts_by_margin(label, length_m: float, bounds) -> bool:
    """Decision C191: the measured ``|length_m|`` lies in another class's bounds than ``label``'s and outside
    ``label``'s ``[lo, hi)`` by more than :data:`CONTRADICTION_MARGIN` of the nearest bound (False for a label
    not in ``bounds``, a length in no class, NaN)."""
    measured = measured_class_one(length_m, bounds)
    if not isinstance(label, str) or label not in bounds or measured is None or measured == label:
        return False
    lo, hi = bounds[label]
    a = abs(float(length_m))
    return a < lo * (1 - CONTRADICTION_MARGIN) or a >= hi * (1 + CONTRADICTION_MARGIN)


def turn_length_class_one(label, proba, length_m: float, turn_rad: float, bounds):
    """Decision C88: ``(label, proba)`` of one stride's length task; a stride turning at least 15 deg (L79) that
    holds a class (``label`` a str) takes the class of its measured horizontal length (:func:`measured_class_one`)
    with one-hot probabilities over ``proba``'s classes (so the gate and the bayes rule weigh that class); decision
    C191: so does a straight stride whose measured length contradicts its class by the margin
    (:func:`contradicts_by_margin`); any other stride, or a length outside every bound, is returned unchanged."""
    if not isinstance(label, str) or not (turning(turn_rad) or contradicts_by_margin(label, length_m, bounds)):
        return label, proba
    measured = measured_class_one(length_m, bounds)
    if measured is None:
        return label, proba
    return measured, (None if proba is None else {c: float(c == measured) for c in proba})


def disagrees_one(label, length_m: float, turn_rad: float, bounds) -> bool | None:
    """Decision C89: does one stride's classified length class contradict its measured length? None when the
    stride is not compared: straight (L79), no classified class, or no measured class (R4's amendment)."""
    if not isinstance(label, str) or not turning(turn_rad):
        return None
    measured = measured_class_one(length_m, bounds)
    return None if measured is None else measured != label


class TurnTally:
    """Decisions C89 / C94: the classifier's length classes on turning strides, counted one stride at a time
    (``track --streaming`` and ``pdrlearn run`` call :meth:`add` with the classifier's class before C88 replaces
    it). ``off`` disagree, ``compared`` were compared, ``classified`` held a length class."""

    def __init__(self) -> None:
        self.off = self.compared = self.classified = 0

    def add(self, label, length_m: float, turn_rad: float, bounds) -> None:
        self.classified += isinstance(label, str)
        d = disagrees_one(label, length_m, turn_rad, bounds)
        if d is not None:
            self.compared += 1
            self.off += d

    def line(self, *, replaced: bool) -> str | None:
        """The C89 line for the strides added so far (of the strides holding a length class), else None."""
        return turning_length_line(self.off, self.compared, self.classified, replaced=replaced)


#: decision C89: the share of disagreeing turning strides at which ``track`` warns -- C16's tested
#: FRACTION_THRESHOLD (0.25), reused and not tuned (no measurement chose it)
TURN_DISAGREE_SHARE = 0.25
#: decision C89: fewest disagreeing turning strides for the line (one odd corner is no pattern)
TURN_DISAGREE_MIN = 3


def turning_length_line(n_off: int, n_turning: int, n_strides: int, *, replaced: bool = False) -> str | None:
    """Decision C89: the one warning line when :data:`TURN_DISAGREE_SHARE` or more of the classified turning strides
    (and at least :data:`TURN_DISAGREE_MIN`) carry a length class their measured length contradicts; else None.
    ``replaced``: C88 gave those strides the measured class (the line says so)."""
    if n_off < TURN_DISAGREE_MIN or n_off < TURN_DISAGREE_SHARE * n_turning:
        return None
    what = ("their length class now comes from the measured length (decision C88)" if replaced else
            "read length_class of turning strides with care, or compare raw_length_m with the model's length bounds")
    return (f"{n_off} of the {n_turning} strides turning 15 deg or more (of {n_strides}) got a length class from the "
            f"classifier that their measured length contradicts: the calibration exercises walk straight (their only "
            f"turns are short turnaround steps), so the length classifier's held-out accuracy does not hold on "
            f"corners and its out-of-domain check does not see them; {what} (decision C89)")


__all__ = ["STRAIGHT_MAX_RAD", "TURN_LENGTH_RULE", "CONTRADICTION_MARGIN", "contradicts_by_margin",
           "TURN_DISAGREE_SHARE", "TURN_DISAGREE_MIN", "measured_class_one", "turning", "turn_length_class_one",
           "disagrees_one", "TurnTally", "turning_length_line"]
