"""Lower-back contacts without a step rhythm: involuntary trunk movements (decision W550).

Chorea-like trunk jerks (Huntington's disease; S114's simulated ones, the session 48 trial's T2-F1) pass every stage
of the lower-back step detection: a jerk's tilt and bump move the vertical and forward accelerations as a step does,
so the seed 003 detector marks a contact, the walking gate opens (the 2 s SD of the vertical acceleration is a
walk's), and W218's stand veto keeps them because a jerk bounces as strongly as a step. Without a walking stretch in
the recording its reference is the median of all the contacts - the jerks' own - so nothing is weak. On a quiet stand
the jerks make runs of 2-6 contacts at irregular intervals (a Poisson process of 0.3-0.8 s events), which W104's
walking sequences (contacts <= 1.5 s apart) chain and the bout rules turn into walking.

Walking repeats its step: a walking run holds a *rhythmic stretch*, :data:`MIN_RHYTHM_STEPS` consecutive step
intervals each within :data:`RHYTHM_TOL` of the run's median interval. :func:`rhythm_keep_mask` keeps every contact of
a run that holds one (its starts, stops and irregular steps too: only whole runs are judged) and leaves out the runs
that hold none (the track option ``trunk_rhythm_veto``: measured, not adopted - dense jerks still chain into runs
that pass, and an irregular patient-like walk can lose a real run). :func:`arrhythmic_line` says so in one
plain-language line (always, offline). Pure functions of contact times.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.waist.lengths import walking_sequences

#: decision W550: a run needs this many consecutive regular step intervals (5 contacts, two strides and a step; our
#: choice a priori: a 3 m TUG leg at a slow 0.45 m step holds 6-7 steps before its turn)
MIN_RHYTHM_STEPS = 4
#: decision W550: a step interval is regular within +-50 % of its run's median interval (W18's +-35 % left out every
#: contact of one irregular patient-like TUG of the trial's users 15661-15690, which the candidate was chosen on)
RHYTHM_TOL = 0.5
#: decision W550: the line names left-out contacts from this many on (a single dropped run of 2-3 contacts is a
#: stumble or a weight shift; 4 or more is a pattern; our choice)
LINE_MIN_CONTACTS = 4


def has_rhythm(event_s: np.ndarray, *, min_steps: int = MIN_RHYTHM_STEPS, tol: float = RHYTHM_TOL) -> bool:
    """True when the contact times ``event_s`` of one run hold ``min_steps`` consecutive step intervals each within
    ``tol`` of the run's median step interval."""
    d = np.diff(np.asarray(event_s, dtype=np.float64))
    if d.size < min_steps:
        return False
    med = float(np.median(d))
    regular = np.abs(d - med) <= tol * med + 1e-12
    best = cur = 0
    for r in regular:
        cur = cur + 1 if r else 0
        best = max(best, cur)
    return best >= min_steps


def rhythm_keep_mask(event_s: np.ndarray, has_next: np.ndarray, *, min_steps: int = MIN_RHYTHM_STEPS,
                     tol: float = RHYTHM_TOL) -> np.ndarray:
    """Per contact: True when its run (``has_next`` chain) holds a rhythmic stretch (:func:`has_rhythm`)."""
    t = np.asarray(event_s, dtype=np.float64)
    keep = np.zeros(t.size, dtype=bool)
    for run in walking_sequences(has_next):  # W104's walking sequences: contacts chained by has_next
        keep[run] = has_rhythm(t[run], min_steps=min_steps, tol=tol)
    return keep


def arrhythmic_line(n_out: int, n_all: int, dropped: bool) -> str | None:
    """Decision W550's plain-language line, or None under :data:`LINE_MIN_CONTACTS` contacts without a rhythm."""
    if n_out < LINE_MIN_CONTACTS:
        return None
    what = ("left out of the steps and walking bouts (trunk_rhythm_veto, decision W550)" if dropped else
            "still counted as steps; the track option trunk_rhythm_veto leaves them out (decision W550)")
    share = 100.0 * n_out / max(n_all, 1)  # the lead's ruling in W550: the share, and daily life's own such runs
    return (f"{n_out} of {n_all} lower-back contacts ({share:.0f} %) lie in runs with no {MIN_RHYTHM_STEPS} regular "
            "steps in a row: trunk movement without a step rhythm (involuntary movements, or the single steps and "
            f"shuffles of daily activity), {what}; lower-back step counts are unvalidated for involuntary movements")
