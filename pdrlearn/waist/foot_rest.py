"""Lower-back contacts while the foot unit does not walk (decision W336).

A standing passenger's lower back bounces with a bus or train (T1 finding 1: 149 phantom steps for 46 in a simulated
bus), and a lower-back detector cannot tell the vehicle's 1-3 Hz bounce from a walking step. A foot unit in the same
session can: a walking foot swings every stride, a standing one does not. The foot's strides are its swings between
two rests (the ZUPT stance of :func:`pdrlearn.displace.foot.inertial_stance`,
:func:`pdrlearn.track.frame_inference.rest_swings`, decision W342: D9's rest-to-rest strides next to a long rest are
over 3 s and a 2-stride bout had none) that turn the foot by :data:`MIN_SWING_RAD` or more in all (a vehicle's
vibration may break the foot's rest into "strides" that do not turn it). A run of at least
:data:`MIN_STILL_CONTACTS` consecutive lower-back contacts none of which lies within :data:`FOOT_MARGIN_S` of such a
stride, inside the foot's recording, is no walking: one warning line per run; the track option ``foot_rest_veto``
drops them (W337 measured whether it is the default).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.signal.conditioning import runs
from pdrlearn.track.frame_inference import foot_swing_strides

#: decision W336: a stride turning the foot by less than this in all (integral of |w|, rad; 0.5 rad = 29 deg) is no
#: walking stride: under the least toes-down push-off of the real foot recordings alone, 51 deg (decision D9 /
#: W173's frame_inference docstring), while a standing foot turns only with the vehicle (0.1-0.2 rad/s)
MIN_SWING_RAD = 0.5
#: decision W336: "several of the waist's step periods": fewer consecutive contacts without the foot are a bout's
#: first or last step of the other foot, a weight shift (W173's MIN_BACKWARD_STEPS, the same count)
MIN_STILL_CONTACTS = 4
#: decision W336: a contact within this of a foot stride belongs to it (s): the uninstrumented foot's step between
#: two strides, and a bout's first / last step before / after the instrumented foot moves (one slow step time)
FOOT_MARGIN_S = 1.0


def still_foot_runs(event_s: np.ndarray, strides: tuple[np.ndarray, np.ndarray, np.ndarray] | None,
                    span: tuple[float, float] | None) -> list[tuple[int, int]]:
    """Runs ``(first, last)`` of at least :data:`MIN_STILL_CONTACTS` consecutive contacts at ``event_s`` (s) inside
    the foot's recording ``span`` with no foot stride (``strides``: :func:`foot_swing_strides`) turning at least
    :data:`MIN_SWING_RAD` within :data:`FOOT_MARGIN_S` (empty without a foot unit)."""
    ev = np.asarray(event_s, float)
    if strides is None or span is None or not ev.size:
        return []
    t0, t1, turn = strides
    walk = turn >= MIN_SWING_RAD
    a, b = t0[walk] - FOOT_MARGIN_S, t1[walk] + FOOT_MARGIN_S
    near = np.array([bool(np.any((a <= e) & (e <= b))) for e in ev])
    still = ~near & (ev >= span[0] + FOOT_MARGIN_S) & (ev <= span[1] - FOOT_MARGIN_S)
    return [(i, j - 1) for i, j in runs(still) if j - i >= MIN_STILL_CONTACTS]


def foot_rest_runs(steps: pd.DataFrame, session, strides=False) -> list[tuple[int, int]]:
    """Decision W336's runs of a waist track's ``steps`` (``event_s``) on ``session``'s foot unit (``strides``: its
    :func:`foot_swing_strides` when already read)."""
    from pdrlearn.track.units import unit_span

    if not len(steps):
        return []
    strides = foot_swing_strides(session) if strides is False else strides
    return still_foot_runs(steps["event_s"].to_numpy(float), strides, unit_span(session, "foot"))


def strideless_spans(spans: list[tuple[float, float]], strides: tuple[np.ndarray, np.ndarray, np.ndarray] | None,
                     span: tuple[float, float] | None) -> list[tuple[float, float]]:
    """Decision W488: those of ``spans`` (s; a lower-back turn's) inside the foot's recording ``span`` with no foot
    stride turning at least :data:`MIN_SWING_RAD` within :data:`FOOT_MARGIN_S` (W336's test of a contact, applied to
    a span): the foot was at rest while the pelvis turned - a seat's or a vehicle's turn, no turn on the spot."""
    if strides is None or span is None:
        return []
    t0, t1, turn = strides
    walk = turn >= MIN_SWING_RAD
    a, b = t0[walk] - FOOT_MARGIN_S, t1[walk] + FOOT_MARGIN_S
    return [(s0, s1) for s0, s1 in spans if s0 >= span[0] + FOOT_MARGIN_S and s1 <= span[1] - FOOT_MARGIN_S
            and not np.any((a <= s1) & (b >= s0))]


def foot_rest_message(steps: pd.DataFrame, first: int, last: int, dropped: bool) -> str:
    """Decision W336's one line for the contacts ``first..last`` of a waist track."""
    ev = steps["event_s"].to_numpy(float)
    what = ("dropped (foot_rest_veto, decision W336)" if dropped else
            "still counted as steps and distance; the track option foot_rest_veto drops them (decision W336)")
    return (f"{last - first + 1} lower-back contacts at {ev[first]:.1f}-{ev[last]:.1f} s while the foot unit made no "
            "stride (it was at rest: standing in a moving vehicle, or swaying on the spot): no walking, " + what)


def foot_rest_keep(n: int, runs: list[tuple[int, int]]) -> np.ndarray:
    """Per contact: False inside one of ``runs``."""
    keep = np.ones(n, dtype=bool)
    for a, b in runs:
        keep[a:b + 1] = False
    return keep
