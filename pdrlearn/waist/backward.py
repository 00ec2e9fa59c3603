"""Backward steps on the lower back: the waist pipelines count every step as forward distance (decision W173).

A lower-back unit gives a step's length (W6/W10) and the unit's heading, not the way the step went: a backward step
is tracked forward, silently. The cue is the foot unit's push-off, D9's swing-pitch asymmetry
(:func:`pdrlearn.track.frame_inference.foot_push_off`, per stride here): a forward stride pitches the foot
toes-down at push-off further than toes-up before the contact; a stride whose toes-up pitch is the larger
(asymmetry under :data:`BACKWARD_ASYMMETRY`) walks heel-last, backward. Only with a foot unit and its declared frame.
Decision W581: and its ZUPT displacement points behind the foot's facing (L219's travel angle,
:func:`pdrlearn.track.frame_inference.foot_travel_angles`, more than ``max_travel_deg`` from forward): a low-swing
shuffle lifts the toes less at push-off than at the heel strike, so its forward strides read an asymmetry under 0 too.
The trunk's W2 phase was measured as a second cue and is not used (W173: it points backward on real forward walking).

A run of at least :data:`MIN_BACKWARD_STEPS` consecutive backward-looking steps in one walking sequence is a backward
stretch (forward, backward, forward again: the backward part); a track gives at most one line for all its stretches
(decision W582). The steps are not changed.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.frame_inference import foot_push_off, foot_travel_angles
from pdrlearn.waist.lengths import walking_sequences

#: decision W173: fewer consecutive backward-looking steps are no backward stretch (a stumble, a turn's step back)
MIN_BACKWARD_STEPS = 4
#: decision W173 (revised after its first measurement): a stride whose swing pitches the foot toes-up further than
#: toes-down (asymmetry < 0, the reverse of a forward push-off) is backward; D9's 0.25 (a recording's median) also
#: took single weak strides of forward walking (turns, stairs)
BACKWARD_ASYMMETRY = 0.0


def backward_steps(steps: pd.DataFrame, session, *, max_travel_deg: float | None = 135.0) -> np.ndarray:
    """Per step of a waist track: its contact lies in a foot stride without a forward push-off (all False without
    a foot unit with a declared frame). ``max_travel_deg`` (decision W581): and whose ZUPT displacement points more
    than this (deg) from the foot's facing (135: halfway from L219's side step at 90 to a backward one at 180);
    None: the push-off alone (W173 as first adopted)."""
    ev = steps["event_s"].to_numpy(float)
    back = np.zeros(len(ev), dtype=bool)
    strides = foot_push_off(session)
    if strides is not None:
        t0, t1, asym = strides
        cue = asym < BACKWARD_ASYMMETRY
        if max_travel_deg is not None and cue.any():
            travel = foot_travel_angles(session)  # decision W581: the same rest-to-rest strides (L219's)
            if travel is not None and len(travel[2]) == len(cue):
                cue &= np.abs(travel[2]) > np.radians(max_travel_deg)
        for a, b in zip(t0[cue], t1[cue], strict=True):
            back |= (ev >= a) & (ev < b)
    return back


def backward_runs(back: np.ndarray, has_next: np.ndarray) -> list[tuple[int, int]]:
    """Runs ``(first, last)`` of at least :data:`MIN_BACKWARD_STEPS` consecutive ``back`` steps inside one walking
    sequence (``has_next``: :func:`pdrlearn.waist.lengths.walking_sequences`)."""
    out = []
    for seq in walking_sequences(np.asarray(has_next, bool)):
        edges = np.flatnonzero(np.diff(np.r_[0, back[seq].astype(int), 0]))
        out += [(int(seq[a]), int(seq[b - 1])) for a, b in zip(edges[::2], edges[1::2], strict=True)
                if b - a >= MIN_BACKWARD_STEPS]
    return out


def backward_message(steps: pd.DataFrame, runs: list[tuple[int, int]]) -> str:
    """Decision W173's one line for the backward-looking stretches ``runs`` (``(first, last)`` step indices, in time
    order) of a waist track; decision W582: one line for all of them (the first three spans named)."""
    def span(first: int, last: int) -> str:
        end = float(steps["end_s"].iloc[last])
        t1 = end if np.isfinite(end) else float(steps["event_s"].iloc[last])
        return f"{float(steps['event_s'].iloc[first]):.1f}-{t1:.1f} s"

    n = sum(b - a + 1 for a, b in runs)
    where = (f"at {span(*runs[0])}" if len(runs) == 1 else
             f"in {len(runs)} stretches at " + ", ".join(span(a, b) for a, b in runs[:3])
             + (", ..." if len(runs) > 3 else ""))
    return (f"{n} steps {where} look backward (the foot unit pitches toes-up more than toes-down and its stride "
            "travels behind its facing: no forward push-off, decisions D9, W581): the lower-back pipelines count "
            "every step as forward distance, so these move the track forward instead of back (decision W173)")


def backward_warnings(steps: pd.DataFrame, session, *, max_travel_deg: float | None = 135.0) -> list[str]:
    """Decision W173's warning line of a waist track: at most one (W582), none when no stretch looks backward;
    ``max_travel_deg``: :func:`backward_steps`' (W581)."""
    if not len(steps):
        return []
    back = backward_steps(steps, session, max_travel_deg=max_travel_deg)
    runs = backward_runs(back, steps["has_next"].to_numpy(bool))
    return [backward_message(steps, runs)] if runs else []
