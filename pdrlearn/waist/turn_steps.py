"""Steps a lower-back track missed in its turns (decision W283), numpy only.

A turn on the spot bounces the pelvis weakly, so its steps are often not detected (W25 / W26), while the yaw rate
still finds and times the turn (L210, L345). Each El-Gohary yaw-rate turn of at least
:data:`pdrlearn.track.clinical.TURN_COUNT_MIN_DEG` over its 5-95 % span (L345's ``start_5_s`` / ``end_95_s``) of
duration D is expected to hold D / T steps, T the walk's step time (the median interval between consecutive contacts
under :data:`STEP_GAP_MAX_S`); the contacts inside the span are its counted steps, and max(0, round(D / T - counted))
its missing ones. Not from a seed: the rule and its thresholds are W283's, set before measuring (W284).
"""

from __future__ import annotations

import numpy as np

#: decision W283: intervals between contacts shorter than this (s) are the walk's step times
STEP_GAP_MAX_S = 1.5
#: decision W283: no judgement with fewer step-time intervals than this
MIN_INTERVALS = 4
#: decision W283: warn when the turns' missing steps sum to at least this many ...
WARN_MIN_STEPS = 2
#: ... and to at least this share of the track's step count
WARN_MIN_FRAC = 0.10


def missed_turn_steps(event_s, yaw_turns, min_deg: float | None = None) -> list[dict]:
    """Decision W283: per yaw-rate turn (records of ``info["yaw_turns"]``) of at least ``min_deg`` (None:
    :data:`pdrlearn.track.clinical.TURN_COUNT_MIN_DEG`) whose 5-95 % span is known: ``start_s``, ``end_s`` (that
    span), ``expected`` (D / T), ``counted`` (contacts ``event_s`` inside) and ``missing`` (module docstring); []
    without enough step intervals to know T."""
    if min_deg is None:  # the clinical turn count's bound (L104), read at call time: this module stays numpy only
        from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG as min_deg
    ev = np.sort(np.asarray(event_s, dtype=float))
    ev = ev[np.isfinite(ev)]
    gaps = np.diff(ev)
    gaps = gaps[(gaps > 0) & (gaps < STEP_GAP_MAX_S)]
    if gaps.size < MIN_INTERVALS:
        return []
    step_s = float(np.median(gaps))
    out = []
    for y in yaw_turns or []:
        a, b = y.get("start_5_s"), y.get("end_95_s")
        if abs(y.get("angle_deg", 0.0)) < min_deg or a is None or b is None or not b > a:
            continue
        expected = (b - a) / step_s
        counted = int(((ev >= a) & (ev <= b)).sum())
        out.append({"start_s": float(a), "end_s": float(b), "expected": float(expected), "counted": counted,
                    "missing": int(max(0, round(expected - counted)))})
    return out


def turn_steps_warning(event_s, yaw_turns, n_steps: int, min_deg: float | None = None) -> str | None:
    """Decision W283: the one warning line when the turns' missing steps (:func:`missed_turn_steps`) sum to at least
    :data:`WARN_MIN_STEPS` and :data:`WARN_MIN_FRAC` of ``n_steps``; None otherwise."""
    turns = [t for t in missed_turn_steps(event_s, yaw_turns, min_deg) if t["missing"]]
    m = sum(t["missing"] for t in turns)
    if m < WARN_MIN_STEPS or m < WARN_MIN_FRAC * max(n_steps, 1):
        return None
    spans = ", ".join(f"{t['start_s']:.1f}-{t['end_s']:.1f} s" for t in turns)
    return (f"about {m} steps missed in {len(turns)} turn(s) ({spans}): a turn's steps were not detected (a turn on "
            f"the spot bounces the pelvis weakly), so n_steps ({n_steps}), the cadence and the distance read low; the "
            "turns' times and angles (turns.csv, yaw rate) still hold (W283)")


#: decision W331: a turn whose expected steps (D / T, W283) reach this and whose span holds no contact is stepless
STEPLESS_MIN_STEPS = 2


def stepless_turns(event_s, yaw_turns, min_deg: float | None = None) -> list[dict]:
    """Decision W331: the turns of :func:`missed_turn_steps` that hold no contact at all in their 5-95 % span
    although their duration implies at least :data:`STEPLESS_MIN_STEPS` steps (a turn on the spot the motion gate,
    W4, read as standing); [] without a walk step time. Decision W488: a turn marked :data:`CARRIED` is left out."""
    own = [y for y in yaw_turns or [] if not y.get(CARRIED)]  # decision W488: not a turn made seated or riding
    return [t for t in missed_turn_steps(event_s, own, min_deg)
            if t["counted"] == 0 and round(t["expected"]) >= STEPLESS_MIN_STEPS]


#: decision W488: the key a yaw-rate turn record carries (True) when it was made seated or in a ride
CARRIED = "carried"


def mark_carried(yaw_turns, spans) -> list[dict] | None:
    """Decision W488: the records ``yaw_turns`` (L210's), each whose 5-95 % span (``start_5_s`` / ``end_95_s``, else
    ``start_s`` / ``end_s``) overlaps one of ``spans`` (``(start_s, end_s)``: seated, or a ride's dropped contacts)
    with ``CARRIED: True`` added (the others unchanged): the pelvis turned with a seat or a vehicle."""
    if yaw_turns is None or not spans:
        return yaw_turns
    out = []
    for y in yaw_turns:
        a = y.get("start_5_s") if y.get("start_5_s") is not None else y.get("start_s")
        b = y.get("end_95_s") if y.get("end_95_s") is not None else y.get("end_s")
        hit = a is not None and b is not None and any(a <= e and b >= s for s, e in spans)
        out.append({**y, CARRIED: True} if hit else y)
    return out


def stepless_summary(event_s, yaw_turns) -> dict:
    """Decision W331: summary.json's ``stepless_turns`` (turns of :func:`stepless_turns`) and
    ``turn_steps_missed`` (their D / T steps, rounded, summed); both None without yaw-rate turns (a foot track) or
    without a walk step time to judge them by."""
    turns = stepless_steps(event_s, yaw_turns)
    if turns is None:
        return {"stepless_turns": None, "turn_steps_missed": None}
    return {"stepless_turns": len(turns), "turn_steps_missed": int(sum(n for _, n in turns))}


def stepless_steps(event_s, yaw_turns) -> list[tuple[float, int]] | None:
    """Decisions W331 / W603: ``(midpoint_s, steps)`` of each stepless turn (:func:`stepless_turns`; its 5-95 %
    span's middle and its D / T steps, rounded) - the steps ``turn_steps_missed`` sums and periods.csv's
    ``n_steps_with_turns`` places; None where W331 cannot judge (no yaw-rate turns: a foot track; too few step
    intervals)."""
    if yaw_turns is None:
        return None
    ev = np.asarray(event_s, dtype=float)
    gaps = np.diff(np.sort(ev[np.isfinite(ev)]))
    if int(((gaps > 0) & (gaps < STEP_GAP_MAX_S)).sum()) < MIN_INTERVALS:
        return None
    return [(0.5 * (t["start_s"] + t["end_s"]), int(round(t["expected"]))) for t in stepless_turns(event_s, yaw_turns)]


def steps_with_turns(n_steps: int | None, turn_steps: int | None, withheld: bool = False) -> int | None:
    """Decision W603: ``n_steps_with_turns``, the detected steps and W331's turning steps on the spot
    (``turn_steps``) together; None where W331 could not judge (``turn_steps`` None) or W476 withheld the step
    count (``withheld``)."""
    if n_steps is None or turn_steps is None or withheld:
        return None
    return int(n_steps) + int(turn_steps)


def stepless_turns_warning(event_s, yaw_turns) -> str | None:
    """Decision W331: one line naming the stepless turns (:func:`stepless_turns`) and the steps they imply; None
    when there is none."""
    turns = stepless_turns(event_s, yaw_turns)
    if not turns:
        return None
    m = int(sum(round(t["expected"]) for t in turns))
    spans = ", ".join(f"{t['start_s']:.1f}-{t['end_s']:.1f} s" for t in turns)
    return (f"{len(turns)} turn(s) on the spot ({spans}) hold no detected step: the lower back's motion gate (W4) "
            f"reads a turn on the spot as standing, so about {m} turning steps are not in n_steps, the cadence or "
            "the distance (summary turn_steps_missed); the turns' times and angles (turns.csv) still hold (W331)")
