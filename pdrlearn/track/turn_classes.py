"""Decision C89: does the length classifier hold on the strides that turn?

The calibration exercises (thesis ch. 6.1) are straight walks whose only turning strides are the short turnaround
steps at the ends, so a walking turn (a 45 or 90 deg corner taken at normal length) is a stride the length
classifier never learned, yet its inputs lie inside the per-feature training ranges that C16 checks (trial T6:
``out_of_domain_fraction`` 0.04 while 14 of 75 strides of path D were called ``long``). The foot's own ZUPT
measurement of the stride (raw_length_m, thesis ch. 5.1) places each stride in a class against the model's length
bounds; on the turning strides (|turn_angle_rad| of at least 15 deg, the straight limit of decision L79) the share
whose classified length class differs from that measured class tells whether the classes can be trusted there.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.turn_length import TURN_DISAGREE_MIN, TURN_DISAGREE_SHARE, turning_length_line


def measured_length_class(length_m: np.ndarray, bounds: dict[str, tuple[float, float]]) -> np.ndarray:
    """The class whose ``[lo, hi)`` bounds (``parse_bounds`` form) hold each |length|; None outside every one
    (:func:`pdrlearn.kernels.turn_length.measured_class_one`, the runtime's, per stride)."""
    from pdrlearn.kernels.turn_length import measured_class_one

    out = np.full(len(np.atleast_1d(length_m)), None, dtype=object)
    out[:] = [measured_class_one(x, bounds) for x in np.asarray(length_m, dtype=float).ravel()]
    return out


def turning_length_disagreement(length_class, raw_length_m, turn_rad, bounds, valid=None) -> tuple[int, int]:
    """(disagreeing, compared) turning strides: strides turning at least L79's 15 deg with a classified length
    class, a measured class (:func:`measured_length_class` of their raw length) and, when given, ``valid``; those
    whose two classes differ disagree. A stride with no measured class (above the top bound, in a gap between
    bounds, NaN) is left out: nothing contradicts its class (decision C89 amended, review R4)."""
    from pdrlearn.kernels.turn_length import disagrees_one  # decision C94: the streamed and run paths' kernel

    lengths, turns = np.asarray(raw_length_m, dtype=float).ravel(), np.asarray(turn_rad, dtype=float).ravel()
    keep = np.ones(len(lengths), bool) if valid is None else np.asarray(valid, bool)
    d = [disagrees_one(c, x, t, bounds) for c, x, t, k in zip(length_class, lengths, turns, keep, strict=True) if k]
    return sum(x is True for x in d), sum(x is not None for x in d)


def measured_classes_on_turns(classes, length_m, turn_rad, bounds):
    """Decision C88: a copy of a stride classes table whose strides turning at least L79's 15 deg (and holding a
    length class) take the class of their measured length, with one-hot ``p_length_*`` so that the rules weigh
    that class; other strides unchanged. Stride by stride with the runtime's kernel
    (:func:`pdrlearn.kernels.turn_length.turn_length_class_one`; decision C91: offline, streamed and run)."""
    from pdrlearn.kernels.turn_length import turn_length_class_one

    out = classes.copy()
    pcols = {c[len("p_length_"):]: c for c in out.columns if c.startswith("p_length_")}
    cls = out["length_class"].to_numpy(dtype=object, copy=True)
    p = out[list(pcols.values())].to_numpy(dtype=float, copy=True) if pcols else None
    for i, (label, length, turn) in enumerate(zip(cls, np.asarray(length_m, float), np.asarray(turn_rad, float),
                                                  strict=True)):
        proba = dict(zip(pcols, p[i].tolist(), strict=True)) if pcols else None
        cls[i], proba = turn_length_class_one(label, proba, length, turn, bounds)
        if pcols:
            p[i] = list(proba.values())
    out["length_class"] = cls
    for k, c in enumerate(pcols.values()):
        out[c] = p[:, k]
    return out


__all__ = ["TURN_DISAGREE_SHARE", "TURN_DISAGREE_MIN", "measured_length_class", "measured_classes_on_turns",
           "turning_length_disagreement", "turning_length_line"]
