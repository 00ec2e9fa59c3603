"""Is a waist track walking? Plausibility cues that do not depend on the estimated speed (decision W98).

A waist track's warnings on slow gait (L95, W77) read the estimated cadence and speed, which a wheelchair
user's arm pushes, a phantom contact inside a slow step or a cane strike corrupt themselves. Real steps move
the weight from one foot to the other: the pelvis's medio-lateral velocity at consecutive contacts has
opposite signs (W20). :func:`alternation_index` measures that from the contacts alone.
:func:`walk_ratio` (decision W100) relates the two estimates an uncalibrated track has, step length and cadence:
a short-stepping gait the default step-length model is not validated on, or a step implausibly long for its
cadence, falls outside the healthy walk ratio.
:func:`still_yaw_rate` (decision W105) reads the vertical rate while the unit stands still: a gyroscope bias (a
phone's uncalibrated gyroscope export) turns every heading and no other cue sees it.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io import Session
from pdrlearn.signal.conditioning import runs, standstill_mask
from pdrlearn.waist import _kernels as K

#: W98: an index under this (the midpoint between walking, ~1, and no lateral weight shift, ~0; a priori)
ALTERNATION_MIN = 0.5
#: W98: fewer consecutive-contact pairs than this are not judged
PLAUSIBILITY_MIN_PAIRS = 10
#: W100: the walk ratio (step length / cadence, m per steps/min) of healthy adults, about constant over walking
#: speeds (Sekiya & Nagasaki 1998, Gait & Posture 7:225-227; not in the seeds: the general gait literature's value)
WALK_RATIO_HEALTHY = 0.0064
#: W100: half and 1.5x the healthy walk ratio (a priori round factors, not fitted): outside warns
WALK_RATIO_BAND = (0.5 * WALK_RATIO_HEALTHY, 1.5 * WALK_RATIO_HEALTHY)
#: W116: the stature the healthy walk ratio stands for (an assumption: ``DEFAULT_HEIGHT_M``; Sekiya & Nagasaki's mean
#: stature is not in the seeds)
WALK_RATIO_HEIGHT_M = 1.70


def walk_ratio_scale(height_m: float) -> float:
    """Decision W116: the factor of the healthy walk ratio and its band for a walker ``height_m`` tall,
    ``(height_m / WALK_RATIO_HEIGHT_M) ** 1.5``: under dynamic similarity (Hof 1996, Gait & Posture 4:222-223) a step
    length scales with the leg length l0 and a cadence with ``sqrt(g / l0)``, so their ratio with ``l0 ** 1.5``
    (l0 a fixed fraction of the stature)."""
    return (float(height_m) / WALK_RATIO_HEIGHT_M) ** 1.5


def alternation_index(v_at: np.ndarray, has_next: np.ndarray) -> tuple[float | None, int]:
    """``(A, pairs)``: ``A = -sum v_k v_(k+1) / sum (v_k^2 + v_(k+1)^2) / 2`` over the consecutive contacts
    ``k, k+1`` of one walking sequence (``has_next[k]``), ``v_at`` the pelvis's lateral velocity at each
    contact (decision W98). 1 = the contacts alternate sides, ~0 = no lateral weight shift, -1 = same side.
    None when there is no pair or no lateral motion at all."""
    v = np.asarray(v_at, dtype=np.float64)
    hn = np.asarray(has_next, dtype=bool)
    if v.size < 2:
        return None, 0
    k = np.flatnonzero(hn[:-1])
    if k.size == 0:
        return None, 0
    a, b = v[k], v[k + 1]
    den = float(np.sum(0.5 * (a * a + b * b)))
    if not np.isfinite(den) or den <= 0.0:
        return None, int(k.size)
    return float(-np.sum(a * b) / den), int(k.size)


def contact_alternation(t: np.ndarray, acc_ml: np.ndarray, fs: float, event_s: np.ndarray,
                        has_next: np.ndarray, v_at: np.ndarray | None = None) -> tuple[float | None, int]:
    """:func:`alternation_index` of the contacts at ``event_s`` (s, on the sample times ``t``), with W20's
    :func:`~pdrlearn.waist._kernels.lateral_velocity` of the medio-lateral acceleration ``acc_ml`` (``v_at``: its
    values at the contacts when already read, :func:`contact_lateral_velocity`)."""
    ev = np.asarray(event_s, dtype=np.float64)
    if ev.size < 2:
        return None, 0
    return alternation_index(contact_lateral_velocity(t, acc_ml, fs, ev) if v_at is None else v_at, has_next)


def contact_lateral_velocity(t: np.ndarray, acc_ml: np.ndarray, fs: float, event_s: np.ndarray) -> np.ndarray:
    """W20's :func:`~pdrlearn.waist._kernels.lateral_velocity` of ``acc_ml`` at the sample of each contact
    ``event_s`` (s, on the sample times ``t``; shared by W98's index and W109's rhythm test)."""
    idx = np.clip(np.searchsorted(t, np.asarray(event_s, dtype=np.float64)), 0, len(t) - 1)
    return K.lateral_velocity(acc_ml, fs)[idx]


#: decision W129: the side labels of :func:`contact_sides` for W20's +1 / -1 / 0 (undecided; shared with the live
#: trackers' W138 side)
SIDE_LABELS = K.SIDE_LABELS


def contact_sides(t: np.ndarray, acc_ml: np.ndarray, fs: float, event_s: np.ndarray,
                  v_at: np.ndarray | None = None) -> np.ndarray:
    """Decision W129: ``"left"`` / ``"right"`` / ``""`` (undecided) for each contact at ``event_s`` (s), from W20's
    :func:`~pdrlearn.waist._kernels.step_sides` of the pelvis's lateral velocity at it (``v_at``, else
    :func:`contact_lateral_velocity`; ``acc_ml`` left +), decided against the median over these contacts. A priori sign
    (W129): at a foot's initial contact the pelvis moves towards that foot (it sways over the stance foot), so
    v > 0 is the left foot."""
    ev = np.asarray(event_s, dtype=np.float64)
    if ev.size == 0:
        return np.zeros(0, dtype=object)
    v = contact_lateral_velocity(t, acc_ml, fs, ev) if v_at is None else np.asarray(v_at, dtype=np.float64)
    side = K.step_sides(v, np.ones(ev.size, dtype=bool))
    return np.array([SIDE_LABELS[int(s)] for s in side], dtype=object)


#: decision W99: the waist IC count of a calibration walk and the pelvic-gyro detector's disagree when they differ
#: by more than this fraction of the pelvic-gyro count (the lead's 30 %)
STEP_COUNT_DISAGREE = 0.3
STEP_COUNT_MIN = 10  # W99: walks where both counts are under this are not judged
STEP_COUNT_MARGIN_S = 0.5  # W99: pelvic-gyro steps this far outside the first / last waist contact still count


def step_counts(session: Session, event_s: np.ndarray, gyro_s: np.ndarray | None = None,
                has_next: np.ndarray | None = None) -> tuple[int, int] | None:
    """Decision W99: ``(n_waist, n_gyro)``: the waist contacts ``event_s`` (s) of a calibration walk and the
    pelvic-gyro detector's steps between the first and last of them (+- :data:`STEP_COUNT_MARGIN_S`); None
    without two contacts or without a waist gyroscope. ``gyro_s``: the pelvic-gyro step times when already read
    (decision W441: the track reads them once, :func:`pdrlearn.waist.pelvic_rhythm.pelvic_steps`). ``has_next``
    (decision W441, a track's contacts): both counted only over its walking sequences (two or more contacts, each
    +- the margin), so the pelvis's rotations between walks (a daily recording's turns and reaching) are not steps."""
    from pdrlearn.waist.pelvic_rhythm import pelvic_steps

    ev = np.asarray(event_s, dtype=np.float64)
    if ev.size < 2:
        return None
    gyro = pelvic_steps(session) if gyro_s is None else np.asarray(gyro_s, dtype=np.float64)
    if gyro is None:  # no waist gyroscope: nothing to compare with
        return None
    if has_next is None:
        spans = [(0, ev.size - 1)]
    else:
        hn = np.asarray(has_next, dtype=bool)
        starts = np.flatnonzero(np.r_[True, ~hn[:-1]])
        ends = np.r_[starts[1:] - 1, ev.size - 1]
        spans = [(a, b) for a, b in zip(starts, ends, strict=True) if b > a]
        if not spans:
            return None
    n_w = sum(b - a + 1 for a, b in spans)
    n_g = sum(int(np.count_nonzero((gyro >= ev[a:b + 1].min() - STEP_COUNT_MARGIN_S) &
                                   (gyro <= ev[a:b + 1].max() + STEP_COUNT_MARGIN_S))) for a, b in spans)
    return int(n_w), n_g


#: decision W114: what a waist contact count well under the pelvic gyroscope's means
MISSED_STEPS_CAUSE = ("the waist detector misses steps, as when steps come faster than its shortest step (a young "
                      "child's or a very fast cadence), so the step count, cadence and distance read low")

#: decision W554: the other reading of fewer contacts than pelvic-gyro steps when the contacts alternate (W441's line):
#: the pelvic-gyro detector counts the trunk's sway as steps (session 48's trial T2, patient-like irregular wide-based
#: walks, users 15661-15663: pelvic-gyro 33 / 28 / 29 steps for 20 / 16 / 17)
GYRO_OVERCOUNT_CAUSE = ("or the pelvic-gyro detector counts the trunk's sway as steps, as in an irregular, "
                        "staggering or wide-based gait (it read 65-75 % high on simulated walks of that kind, "
                        "decision W554)")


def steps_missed(counts: tuple[int, int] | None) -> bool:
    """Decision W114: the pelvic-gyro count of :func:`step_counts` ``(n_waist, n_gyro)`` exceeds the waist contacts
    by more than :data:`STEP_COUNT_DISAGREE` of it (the larger at least :data:`STEP_COUNT_MIN`): the waist detector
    misses steps, it does not add any."""
    if counts is None:
        return False
    n_w, n_g = counts
    return max(n_w, n_g) >= STEP_COUNT_MIN and n_g - n_w > STEP_COUNT_DISAGREE * n_g


def steps_added(counts: tuple[int, int] | None) -> bool:
    """Decision W441: the waist contacts of :func:`step_counts` ``(n_waist, n_gyro)`` exceed the pelvic-gyro count by
    more than :data:`STEP_COUNT_DISAGREE` of it (the larger at least :data:`STEP_COUNT_MIN`): W114's test the other
    way round."""
    if counts is None:
        return False
    n_w, n_g = counts
    return max(n_w, n_g) >= STEP_COUNT_MIN and n_w - n_g > STEP_COUNT_DISAGREE * n_g


#: decision W442: waist contacts more than this times the pelvic-gyro count, with W98's alternation failed, are no
#: step count at all (the trial's x4-5 against W79's x1.4 of a countable slow walk; a priori, not fitted)
STEP_COUNT_UNUSABLE = 1.5


def steps_uncountable(counts: tuple[int, int] | None) -> bool:
    """Decision W442: :func:`steps_added`, the waist contacts more than :data:`STEP_COUNT_UNUSABLE` x the pelvic-gyro
    count, and that count at least :data:`STEP_COUNT_MIN` (the pelvis turns step by step: someone walks; a wheelchair
    user's pushes give no pelvic steps and keep W98's line). The caller adds W98's failed alternation."""
    return steps_added(counts) and counts[1] >= STEP_COUNT_MIN and counts[0] > STEP_COUNT_UNUSABLE * counts[1]


#: decision W441: what a waist contact count well over the pelvic gyroscope's means
ADDED_STEPS_CAUSE = ("the waist detector adds contacts inside steps, as at a very slow or small-stepping gait "
                     "(below ~70 steps/min the step's own vertical acceleration is small, decision W79) or with a "
                     "walking aid's strikes, so the step count and distance read high")
#: decision W442: why the contacts are no step count
UNCOUNTABLE_CAUSE = ("the steps are too small or too slow for the lower back to count (very small slow steps, such as "
                     "0.1 m every 1.5-2 s: the trunk's vertical motion at a step is no larger than its vibration; "
                     "else a walking aid's strikes or wheelchair propulsion beside the steps), so n_steps, the "
                     "cadence and the distance are not usable (not short fast steps and not running)")


#: decision W580: where the pelvic gyro's steps are had - a track on them (trial s50t3: steps +8..+10 %, speed
#: -3..+2 % with calibration) or their count alone
PELVIC_GYRO_ADVICE = ("'pdrlearn track DIR --units waist --detector pelvic-gyro' (with --params) for a track on its "
                      "steps, or 'pdrlearn steps DIR --detector pelvic-gyro' for the count")


def step_count_withheld_reason(counts: tuple[int, int], pelvic_period_s: float) -> str:
    """Decision W476: why a lower-back track whose contacts are :func:`steps_uncountable` (W442) withholds its
    cadence and step times (summary.json ``step_count_withheld``, the track's count line): the two counts and the
    pelvic-gyro detector's own cadence (60 / its median step interval ``pelvic_period_s``, s), named as its."""
    cadence = (f", its cadence {60.0 / pelvic_period_s:.1f} steps/min" if np.isfinite(pelvic_period_s)
               and pelvic_period_s > 0 else "")
    return (f"the {counts[0]} waist contacts are over {STEP_COUNT_UNUSABLE:g} x the pelvic-gyro detector's "
            f"{counts[1]} steps (decision W442): no step count, so median_cadence_spm, median_step_time_s and "
            f"median_stride_time_s are withheld and n_steps counts contacts (decision W476); the pelvic gyro counts "
            f"{counts[1]} steps{cadence} ({PELVIC_GYRO_ADVICE})")


def uncountable_steps_line(counts: tuple[int, int] | None, detector: str) -> str | None:
    """Decision W476: ``pdrlearn steps --detector NAME``'s (a lower-back detector other than pelvic-gyro) one line
    when its detections are over :data:`STEP_COUNT_UNUSABLE` x the pelvic-gyro detector's steps over the same span
    (W442's count test; the track adds W98's failed alternation, which `steps` does not read); None otherwise."""
    if not (steps_added(counts) and counts[1] >= STEP_COUNT_MIN and counts[0] > STEP_COUNT_UNUSABLE * counts[1]):
        return None
    return (f"{detector}: " + _counts_text(counts, f"over {STEP_COUNT_UNUSABLE:g} x warns, decisions W442, W476")
            + f": {ADDED_STEPS_CAUSE}; this count and its cadence are not the walker's: use 'pdrlearn steps DIR "
            "--detector pelvic-gyro' for the step count and cadence, or a foot unit")


#: decision W476: the summary.json keys a :func:`steps_uncountable` lower-back track withholds (None); decision
#: C246: its steps of both feet (the contacts are none); C247: its stride length (two contacts, W537)
WITHHELD_STEP_KEYS = ("median_cadence_spm", "median_step_time_s", "median_stride_time_s", "n_steps_both_feet",
                      "median_stride_length_m")


def withhold_step_count(summary: dict) -> dict:
    """Decision W476: ``summary`` (a track's summary.json dict, changed in place and returned) with
    :data:`WITHHELD_STEP_KEYS` None and ``step_count_withheld`` the reason when its ``info.step_count_withheld``
    says W442 fired; ``step_count_withheld`` None otherwise. Decision C247: W558's jitter-free stride-time CV (two
    contact intervals a stride) is withheld too."""
    reason = (summary.get("info") or {}).get("step_count_withheld")
    summary["step_count_withheld"] = reason or None
    if reason:
        summary.update(dict.fromkeys(WITHHELD_STEP_KEYS))
        cv = summary.get("stride_time_cv_withheld")
        if isinstance(cv, dict) and cv.get("jitter_free_cv_pct") is not None:  # decision C247
            cv.update(jitter_free_cv_pct=None, n_jitter_free_strides=None)
    return summary


#: decision C247: the flag of a speed or distance summed from contacts that W476 found no step count
CONTACTS_FLAG = ("from contacts that are no step count (W476): may read high; 'track --detector pelvic-gyro' "
                 "counts the steps (C247)")


def withheld_steps_text(summary: dict) -> str | None:
    """Decision C246 (W476's count line, shared by ``track`` and the reports): "618 contacts (no step count, decision
    W476; the pelvic gyro counts 344 steps)" for a summary whose ``step_count_withheld`` is set; None otherwise."""
    if not summary.get("step_count_withheld"):
        return None
    gyro = (summary.get("info") or {}).get("n_pelvic_gyro_steps")
    n = summary.get("n_steps")
    return (f"{n} contacts (no step count, decision W476"
            + (f"; the pelvic gyro counts {gyro} steps" if gyro is not None else "") + ")")


def _counts_text(counts: tuple[int, int], decision: str) -> str:
    return (f"the pelvic-gyro detector counts {counts[1]} steps over the same span, the waist contacts "
            f"{counts[0]} ({decision})")


def count_mismatch_message(counts: tuple[int, int] | None) -> str | None:
    """Decision W441's one line when the two counts of :func:`step_counts` disagree by more than
    :data:`STEP_COUNT_DISAGREE` of the pelvic-gyro count, in either direction (W114's line says it only with W98's);
    None when they agree or were not read."""
    if steps_missed(counts):  # decision W554: either detector may be the wrong one; a foot unit tells
        return (_counts_text(counts, "more than 30 % apart warns, decision W441") + f": either {MISSED_STEPS_CAUSE}, "
                f"{GYRO_OVERCOUNT_CAUSE}; check the step count with a foot unit or by counting the steps of a walk")
    if not steps_added(counts):
        return None
    return (_counts_text(counts, "more than 30 % apart warns, decision W441") + f": {ADDED_STEPS_CAUSE}; use "
            "'pdrlearn steps DIR --detector pelvic-gyro' for the step count and cadence, or a foot unit")


def not_alternating_message(index: float, pairs: int, counts: tuple[int, int] | None = None) -> str:
    """Decision W98's one warning line for a waist track whose steps do not alternate left/right; with the
    :func:`step_counts` ``counts`` of its contacts, decision W114: when the pelvic gyroscope counts more steps
    (:func:`steps_missed`) the contacts are every other step of a fast gait, and the line says so instead;
    decision W442: when the waist contacts are :func:`steps_uncountable`, the steps are too small or slow to count."""
    head = (f"the detected steps do not alternate left/right (alternation index {index:.2f} over {pairs} "
            f"consecutive steps; walking is ~1, under {ALTERNATION_MIN:g} warns, decision W98): ")
    use = "; use 'pdrlearn steps DIR --detector pelvic-gyro' for the step count and cadence, or a foot unit"
    if steps_missed(counts):
        return head + _counts_text(counts, "decision W114") + f": {MISSED_STEPS_CAUSE}" + use
    if steps_uncountable(counts):  # decision W580: the track on the pelvic gyro's steps named too
        return (head + _counts_text(counts, f"over {STEP_COUNT_UNUSABLE:g} x warns, decision W442") +
                f": {UNCOUNTABLE_CAUSE}; use {PELVIC_GYRO_ADVICE}, or a foot unit")
    return (head + "the pelvis shows no sideways weight shift from step to step, so the step count, distance and "
            "speed may not be walking (wheelchair propulsion, walking-aid strikes, phantom steps at very slow gait); "
            "check with a foot unit or 'pdrlearn steps DIR --detector pelvic-gyro'")


def walk_ratio(length_m: np.ndarray, step_s: np.ndarray) -> tuple[float | None, int, float | None, float | None]:
    """``(WR, n, length, cadence)``: the walk ratio ``WR = median length / median cadence`` (m per steps/min) over
    the ``n`` steps with a finite step time ``step_s`` (s; cadence ``60 / step_s``), the median step length (m)
    and the median cadence (steps/min) (decision W100). None when no step has a step time."""
    st = np.asarray(step_s, dtype=np.float64)
    ok = np.isfinite(st) & (st > 0)
    n = int(ok.sum())
    if n == 0:
        return None, 0, None, None
    length = float(np.median(np.abs(np.asarray(length_m, dtype=np.float64)[ok])))
    cadence = float(np.median(60.0 / st[ok]))
    return length / cadence, n, length, cadence


#: decision W207: an uncalibrated pendulum step (median) under this fraction of W6's comfortable step for the stature
#: (``STEP_PER_HEIGHT_AT_F0`` x height at seed 000 sec. II-C's free walking frequency) warns: W100's "far under" factor
#: (a priori, not fitted)
SHORT_STEP_FACTOR = 0.5


def short_step_limit(height_m: float = WALK_RATIO_HEIGHT_M) -> float:
    """Decision W207: the median step length (m) under which an uncalibrated pendulum reading warns for a walker
    ``height_m`` tall: :data:`SHORT_STEP_FACTOR` x W6's comfortable step ``STEP_PER_HEIGHT_AT_F0 x height``."""
    from pdrlearn.waist.params import STEP_PER_HEIGHT_AT_F0

    return SHORT_STEP_FACTOR * STEP_PER_HEIGHT_AT_F0 * float(height_m)


#: decision W207: why a short pendulum step is read long, and what to do (shared by the waist-pendulum and the
#: waist-pll lines)
SHORT_STEP_CAUSE = ("at such short steps the pelvis vaults by a few millimetres and the pendulum model (seed 003 "
                    "eq. 1: the step length grows with the square root of the vault) reads them long whatever the "
                    "cadence (simulated shuffling at 0.2-0.42 m/s read +21 to +101 %), so the distance, speed and "
                    "step lengths are not reliable even when the speed looks plausible; calibrate on this walker's "
                    "own walk of known length ('pdrlearn calibrate DIR --distance M --out PARAMS.json', e.g. a 10 m "
                    "walk test at this gait), then track with --params PARAMS.json, or use a foot unit")


def short_step_message(length: float | None, n: int, height_m: float = WALK_RATIO_HEIGHT_M, *,
                       pll_m: float | None = None, pendulum_m: float | None = None,
                       height_known: bool = True) -> str | None:
    """Decision W207's one warning line when the median uncalibrated pendulum step ``length`` (m, over ``n`` >=
    :data:`PLAUSIBILITY_MIN_PAIRS` steps with a step time) is under :func:`short_step_limit` of a walker ``height_m``
    tall; None otherwise. Decision W208: ``pll_m`` / ``pendulum_m``, the distances of a ``waist-pll`` track and of the
    pendulum reading of the same session it is judged on (W139); the line gives both."""
    lim = short_step_limit(height_m)
    if length is None or n < PLAUSIBILITY_MIN_PAIRS or length >= lim:
        return None
    head = (f"the uncalibrated pendulum model reads a median step of {length:.2f} m over {n} steps, under half the "
            f"comfortable step of a walker {height_m:.2f} m tall ({lim:.2f} m; 0.415 x height, decision W6; under it "
            "warns, decision W207): a short-stepping (shuffling) gait; ")
    if pll_m is not None and pendulum_m is not None:  # W208
        head = (f"waist-pll reads {pll_m:.2f} m ({_direction(pll_m, pendulum_m)} the pendulum model's {pendulum_m:.2f} "
                "m on the same session, which its step length is judged on: decision W139, W208); " + head)
    return head + SHORT_STEP_CAUSE


def _direction(a: float, b: float) -> str:
    """W208: ``a`` against ``b`` in words, so a line's direction is the reading's."""
    return "longer than" if a > b else "shorter than" if a < b else "the same as"


#: decision W208: an uncalibrated waist-pll track with more than this fraction fewer contacts than the pendulum
#: detector's on the same session misses steps (W99's disagreement of two step counts, the lead's 30 %)
PLL_MISSED_FRACTION = STEP_COUNT_DISAGREE


def pll_missed_steps_message(n_pll: int, n_pendulum: int, pll_m: float, pendulum_m: float,
                             n_gyro: int | None = None) -> str | None:
    """Decision W208's one warning line when a ``waist-pll`` track has ``n_pll`` contacts, more than
    :data:`PLL_MISSED_FRACTION` under the ``n_pendulum`` >= :data:`STEP_COUNT_MIN` of the pendulum detector on the
    same session (its distance ``pll_m`` against the pendulum reading's ``pendulum_m``); None otherwise.
    Decision W477: each direction is worded from the numbers (fewer steps; a distance longer or shorter), and with the
    pelvic-gyro detector's count ``n_gyro`` over the same span both counts are compared with it before a pipeline is
    recommended: the pendulum's only when it is the nearer and within W99's 30 %; waist-pll's when it is; else
    neither (the pelvic gyro for the count and cadence)."""
    if n_pendulum < STEP_COUNT_MIN or n_pendulum - n_pll <= PLL_MISSED_FRACTION * n_pendulum:
        return None
    head = (f"waist-pll found {n_pll} steps where the pendulum model's contact detector found {n_pendulum} on the "
            f"same session (more than {100 * PLL_MISSED_FRACTION:.0f} % fewer warns, decision W208, W99's "
            f"disagreement); its distance {pll_m:.2f} m is {_direction(pll_m, pendulum_m)} the pendulum's "
            f"{pendulum_m:.2f} m: ")
    calibrate = ("calibrated on this walker's own walk of known length ('pdrlearn calibrate DIR --pipeline PIPELINE "
                 "--distance M --out PARAMS.json')")
    lost = ("its phase-locked loop loses the step rhythm of this gait (slow walking), so it misses steps; its step "
            "count, cadence, distance, bouts and pauses are not reliable")
    if n_gyro is None or n_gyro < STEP_COUNT_MIN:  # no pelvic count to judge by: W208's advice
        return (head + lost + "; track with --pipeline waist-pendulum, "
                + calibrate.replace("PIPELINE", "waist-pendulum")
                + ", or use a foot unit")
    tol = STEP_COUNT_DISAGREE * n_gyro
    off_pll, off_pend = n_pll - n_gyro, n_pendulum - n_gyro
    judge = (f"the pelvic-gyro detector counts {n_gyro} steps over the same span (decision W477): waist-pll "
             f"{off_pll:+d}, the pendulum {off_pend:+d}; ")
    cause = (lost if off_pll < -tol else
             "both detectors add contacts inside steps (decision W441), the pendulum's more" if off_pll > tol else
             "the pendulum's detector adds contacts inside steps (decision W441), waist-pll's count is the nearer")
    if abs(off_pend) < abs(off_pll) and abs(off_pend) <= tol:
        advice = "track with --pipeline waist-pendulum, " + calibrate.replace("PIPELINE", "waist-pendulum")
    elif abs(off_pll) <= abs(off_pend) and abs(off_pll) <= tol:
        advice = ("keep --pipeline waist-pll (" + calibrate.replace("PIPELINE", "waist-pll") + " for the distance)")
    else:
        advice = ("neither pipeline's count is within 30 % of the pelvic gyro's: take the step count and cadence "
                  "from 'pdrlearn steps DIR --detector pelvic-gyro'; below 70 steps/min 'pdrlearn track DIR "
                  "--pipeline waist-pll --detector pll' (the PLL detector's own gate and slow band, decision W475) "
                  "may follow the steps")
    return head + cause + "; " + judge + advice + ", or use a foot unit"


#: decision W139: what the walk ratio of a ``waist-pll`` track is read from, and why
PLL_WALK_RATIO_BASIS = ("waist-pll's step length is a line in its step frequency, so its own walk ratio always looks "
                        "healthy; judged on the pendulum model's reading of the same session (decision W139; "
                        "simulated short-step walks read +51 to +574 % long on waist-pll): ")


#: decision W186: an uncalibrated waist-pll track reading more than this times the pendulum model's distance on the same
#: session warns (W139's size of error worth a line, "> +50 % long"; a priori, not fitted)
PLL_EXCESS_RATIO = 1.5
#: decision W186: the pendulum reading needs at least this many steps with a length to be compared
PLL_EXCESS_MIN_STEPS = 5
#: decision W186: a step whose frequency is over this times the track's median counts as a short contact interval
PLL_FAST_STEP_FACTOR = 1.5


def pll_excess(pll_length_m: np.ndarray, pll_frequency_hz: np.ndarray, pendulum_length_m: np.ndarray
               ) -> tuple[float | None, str | None]:
    """Decision W186: ``(ratio, line)`` - waist-pll's distance (the sum of ``pll_length_m``) over the pendulum
    model's reading of the same session (``pendulum_length_m``; None with fewer than :data:`PLL_EXCESS_MIN_STEPS`
    steps with a length or none at all) and the warning line when the ratio exceeds :data:`PLL_EXCESS_RATIO` (None
    otherwise). The line counts the pll steps with a frequency over :data:`PLL_FAST_STEP_FACTOR` x the median:
    the short contact intervals its frequency line (seed 000 sec. II-D) reads as fast, long steps."""
    pend = np.abs(np.asarray(pendulum_length_m, dtype=np.float64))
    pend_m = float(np.nansum(pend))
    if int(np.sum(pend > 0)) < PLL_EXCESS_MIN_STEPS or pend_m <= 0:
        return None, None
    pll_m = float(np.nansum(np.abs(np.asarray(pll_length_m, dtype=np.float64))))
    ratio = pll_m / pend_m
    if ratio <= PLL_EXCESS_RATIO:
        return ratio, None
    f = np.asarray(pll_frequency_hz, dtype=np.float64)
    f = f[np.isfinite(f) & (f > 0)]
    n_fast = int(np.sum(f > PLL_FAST_STEP_FACTOR * np.median(f))) if f.size else 0
    return ratio, (f"waist-pll reads {pll_m:.2f} m, {ratio:.2f} x the pendulum model's {pend_m:.2f} m on the same "
                   f"session ({n_fast} of {f.size} pll steps at over {PLL_FAST_STEP_FACTOR:g} x its median step "
                   "frequency): its step length is a line in each step's frequency (seed 000), so short contact "
                   "intervals - rising from a chair, a turn on the spot, starting and stopping (a TUG) - read as "
                   "fast, long steps; track with --pipeline waist-pendulum, or calibrate this walker "
                   "('pdrlearn calibrate DIR --distance M') (decision W186)")


#: decision W289: an uncalibrated waist-pll track reading more than this times the pendulum reading's distance at a slow
#: gait warns (W208's rule's "more than 25 % off"; a priori, not fitted)
PLL_SLOW_EXCESS_RATIO = 1.25
#: decision W289: "a slow gait" - the pendulum reading's speed (median step x median cadence) under this (m/s; the lower
#: end of the 1.0-1.4 m/s normal walkers of W207's rule; W186's fast walks, which read pll long too, are left out)
PLL_SLOW_SPEED_MPS = 1.0


#: decision W313: "a slow gait" judged by the pendulum reading's median cadence under this (steps/min): the lower end of
#: adults' normal walking cadence (Tudor-Locke et al. 2018, Br J Sports Med 52:776-788: 100 steps/min, the heuristic
#: threshold of moderate-intensity walking; a priori, not fitted)
PLL_SLOW_CADENCE_SPM = 100.0
#: decisions W289 / W313: the judges of "a slow gait" of :func:`pll_slow_excess_message` and their decision
PLL_SLOW_JUDGES = {"speed": "W289", "cadence": "W313"}


def pll_slow_excess_message(ratio: float | None, pll_m: float, pendulum_m: float, length: float | None,
                            cadence: float | None, n: int, *, judge: str = "speed") -> str | None:
    """Decision W289: the one warning line of an uncalibrated waist-pll track whose distance ``pll_m`` is more than
    :data:`PLL_SLOW_EXCESS_RATIO` x the pendulum reading's ``pendulum_m`` (``ratio``, W186's) while that reading's own
    speed, median step ``length`` (m) x median ``cadence`` (steps/min) / 60 over ``n`` >= :data:`STEP_COUNT_MIN` steps
    (W100's medians), is under :data:`PLL_SLOW_SPEED_MPS`; None otherwise. Decision W313: ``judge="cadence"`` judges
    the gait slow by the median ``cadence`` under :data:`PLL_SLOW_CADENCE_SPM` instead of the speed."""
    if ratio is None or not ratio > PLL_SLOW_EXCESS_RATIO or length is None or cadence is None or n < STEP_COUNT_MIN:
        return None
    speed = length * cadence / 60.0
    if not (cadence < PLL_SLOW_CADENCE_SPM if judge == "cadence" else speed < PLL_SLOW_SPEED_MPS):
        return None
    return (f"waist-pll reads {pll_m:.2f} m, {ratio:.2f} x the pendulum model's {pendulum_m:.2f} m on the same "
            f"session, at a slow gait (the pendulum reading: median step {length:.2f} m at {cadence:.0f} "
            f"steps/min, about {speed:.2f} m/s): uncalibrated, waist-pll's step length is a line in its step "
            "frequency set on normal walking, and slow walkers' steps read long on it (simulated 0.5-0.7 m/s "
            "walkers +23 to +72 %); the distance and gait speed are not reliable: track with --pipeline "
            "waist-pendulum, or calibrate this walker ('pdrlearn calibrate DIR --distance M') "
            f"(decision {PLL_SLOW_JUDGES[judge]})")


#: decision W491: an uncalibrated waist-pll track reading more than this times the pendulum reading's distance, with no
#: earlier length line, says its step length is a population model (W289 / W313's "more than 25 % off"; not fitted)
PLL_MODEL_RATIO = PLL_SLOW_EXCESS_RATIO


def pll_model_message(ratio: float | None, pll_m: float, pendulum_m: float) -> str | None:
    """Decision W491: the one line of an uncalibrated waist-pll track whose distance ``pll_m`` is more than
    :data:`PLL_MODEL_RATIO` x the pendulum reading's ``pendulum_m`` (``ratio``, W186's) at any gait; None otherwise.
    It states the disagreement of the two uncalibrated models and why waist-pll is the one to doubt on patients."""
    if ratio is None or not ratio > PLL_MODEL_RATIO:
        return None
    return (f"waist-pll reads {pll_m:.2f} m, {ratio:.2f} x the pendulum model's {pendulum_m:.2f} m on the same session "
            f"(over {PLL_MODEL_RATIO:g} x warns): uncalibrated, its step length is a population model, a line in each "
            "step's frequency (seed 000), which reads short-stepping walkers long (mobgap MS001 Test11, a patient with "
            "multiple sclerosis: waist-pll +103.60 % inside the reference walking bouts, waist-pendulum +33.50 %); "
            "the two uncalibrated readings disagree and a calibration on this walker's walk of known length settles "
            "it ('pdrlearn calibrate DIR --pipeline waist-pll --distance M --out PARAMS.json'); for patients track "
            "with --pipeline waist-pendulum (decision W491)")


def running_cadence(length: float | None, cadence: float | None, height_m: float = WALK_RATIO_HEIGHT_M) -> bool:
    """Decision W177: whether an uncalibrated waist track's median step ``length`` (m) at its median ``cadence``
    (steps/min) is a fast gait W178 names running first - the cadence above L95's range and the speed length x
    cadence / 60 at least :data:`pdrlearn.track.gait.RUNNING_FIRST_SPEED_MPS`, both scaled to the leg of a walker
    ``height_m`` tall (L148, W116's stature) - where a low walk ratio comes from the pendulum model's short reading
    of long steps, not from short steps."""
    from pdrlearn.track.gait import fast_gait, range_side
    from pdrlearn.waist.params import LEG_PER_HEIGHT

    if length is None or cadence is None:
        return False
    leg = LEG_PER_HEIGHT * height_m
    speed = length * cadence / 60.0
    return range_side(cadence, None, leg) == "fast" and fast_gait(cadence, speed, leg) != "short_fast"


#: decision W454: a walk ratio far under the band has two causes the ratio cannot tell apart, read in opposite
#: directions: short steps read long (W100's simulated festinating walks) and a trunk steadied by a walking aid reads
#: short (trial T2, session 40: the simulated waist's dynamic acceleration damped to x0.4, docs/waist.md's rollator
#: case, on three 12 m walks at 0.30-0.53 m/s: 4.71, 8.71 and 7.43 m)
LOW_RATIO_DIRECTION = ("and reads long on short steps (simulated festinating walks: +20 to +174 % distance) but short "
                       "on a trunk a rollator or cane steadies (a simulated trunk motion damped to x0.4: -27 to -61 % "
                       "distance), so the distance may be too long or too short (decision W454)")
#: decision W455: the start of every walk-ratio advice (:func:`walk_ratio_advice`); ``calibrate`` drops the line by it
WALK_RATIO_NEED = ("the distance, speed and step lengths need a calibration on this walker's own walk of known "
                   "length (a 10 m walk test, or this recording if you know the distance walked)")
#: decision W100: what an uncalibrated walk-ratio line asks for (the pipelines' own step-length models)
WALK_RATIO_ADVICE = (f"{WALK_RATIO_NEED}: 'pdrlearn calibrate DIR --distance M --out PARAMS.json', then track with "
                     "--params PARAMS.json")


def walk_ratio_advice(name: str, *, uses_profile: bool = True, gain_param: str | None = None) -> str:
    """Decision W461: what a walk-ratio line asks for, true of the step-length model ``name``: the pipelines'
    models (``uses_profile``) :data:`WALK_RATIO_ADVICE`; a model with a linear gain ``gain_param``
    ``calibrate --length-model`` (W460) or the gain by hand; a model that reads no calibration, its settings."""
    if uses_profile:
        return WALK_RATIO_ADVICE
    if gain_param:
        return (f"{WALK_RATIO_NEED}: 'pdrlearn calibrate DIR --distance M --length-model {name} --out PARAMS.json' "
                f"fits {name}'s gain {gain_param}, then track with --length-model {name} --params PARAMS.json "
                f"(or set it: --length-model {name}:{gain_param}=VALUE; decisions W460, W461)")
    return (f"the step-length model {name} reads no per-user calibration ('pdrlearn calibrate' and --params do not "
            "change it): check its settings (decision W461)")


def walk_ratio_message(ratio: float | None, n: int, length: float | None, cadence: float | None,
                       height_m: float = WALK_RATIO_HEIGHT_M, *, pll_length: float | None = None,
                       pll_m: float | None = None, pendulum_m: float | None = None,
                       height_known: bool = True, advice: str = WALK_RATIO_ADVICE) -> str | None:
    """Decision W100's one warning line for an uncalibrated waist track whose walk ratio lies outside
    :data:`WALK_RATIO_BAND` over at least :data:`PLAUSIBILITY_MIN_PAIRS` steps; None when it is inside or not
    judged. Decision W116: the band is that of a walker ``height_m`` tall (:func:`walk_ratio_scale`: a child's healthy
    walk ratio is smaller). Decision W139: ``pll_length`` (m), the median step of a ``waist-pll`` track whose
    ``ratio``, ``length`` and ``cadence`` are the pendulum model's reading of the same session; the line says so.
    Decision W208: with the pll track's distance ``pll_m`` and the pendulum reading's ``pendulum_m`` (m) the line gives
    both and says "reads long" only of a pll track that reads longer than the pendulum. Decision L492: a short-step
    line of a walker whose height meta.json does not give (``height_known`` False) says to give it (a child's band is
    smaller, W116). Decision W461: ``advice`` (:func:`walk_ratio_advice`) ends the line."""
    c = walk_ratio_scale(height_m)
    lo, hi, healthy = c * WALK_RATIO_BAND[0], c * WALK_RATIO_BAND[1], c * WALK_RATIO_HEALTHY
    if ratio is None or n < PLAUSIBILITY_MIN_PAIRS or lo <= ratio <= hi:
        return None
    what = ("far under healthy gait's: a short-stepping (shuffling, festinating) gait or a trunk steadied by a "
            f"walking aid, on which the uncalibrated waist step length is not validated {LOW_RATIO_DIRECTION}"
            if ratio < lo else
            "far over healthy gait's: the uncalibrated step length is implausibly long for this cadence")
    if ratio < lo and running_cadence(length, cadence, height_m):  # decision W177
        what = ("far under healthy gait's at a running cadence and an uncalibrated speed of "
                f"{length * cadence / 60.0:.2f} m/s: this looks like running, or short fast steps; the waist step "
                "model is validated on walking only, and on fast walking at running cadence it read the steps "
                "short, not long (simulated 167-200 steps/min: -41.7 to -47.6 % distance), so the distance is "
                "probably too short")
    if pll_length is not None:  # W139
        if pll_m is not None and pendulum_m is not None and not pll_m > pendulum_m and ratio < lo:  # W208
            what = what.replace(LOW_RATIO_DIRECTION, "and is not reliable")
        what = (f"{what}; waist-pll reads a median step of {pll_length:.2f} m, the pendulum {length:.2f} m")
        if pll_m is not None and pendulum_m is not None:  # W208: the direction is the reading's
            what += f" (distance {pll_m:.2f} m, {_direction(pll_m, pendulum_m)} the pendulum's {pendulum_m:.2f} m)"
    if ratio < lo and not height_known:  # decision L492
        from pdrlearn.track.gait import NO_HEIGHT_HINT

        what += f"; {NO_HEIGHT_HINT.replace('walking range', 'band')} (W116)"
    return (("" if pll_length is None else PLL_WALK_RATIO_BASIS) +
            f"walk ratio {ratio:.4f} m per step/min (median step {length:.2f} m at {cadence:.0f} steps/min over "
            f"{n} steps; healthy gait ~{healthy:.4f} at {height_m:.2f} m tall, outside {lo:.4f}-{hi:.4f} warns, "
            f"decision W100, scaled to the stature by W116) is {what}; {advice}")


#: decision W140: a calibrated track whose median cadence is outside this factor of its calibration walks' warns
#: (a priori: 4/3 either way, beyond one walker's own slow-to-fast cadence range, the simulator's 1/1.2-1/0.86 of
#: normal, and inside a change of gait such as a 150 steps/min shuffle against a 100-118 steps/min walk)
CALIBRATION_CADENCE_BAND = (0.75, 4.0 / 3.0)


def median_cadence(frequency_hz: np.ndarray) -> tuple[float | None, int]:
    """Decision W140: ``(cadence, n)``, the median cadence (steps/min, 60 x the step frequency) over the ``n`` steps
    with a finite positive ``frequency_hz`` (Hz: the steps table's, ``1 / (end_s - start_s)``); None without any."""
    f = np.asarray(frequency_hz, dtype=np.float64)
    f = f[np.isfinite(f) & (f > 0)]
    return (60.0 * float(np.median(f)) if f.size else None), int(f.size)


def calibration_gait(frequency_hz: np.ndarray, distance_m: float, walks_hz: list | None = None) -> dict | None:
    """Decision W140: the gait of the calibration walks whose counted steps have the step frequencies
    ``frequency_hz`` (Hz) and cover ``distance_m`` (the known lengths summed): ``median_cadence_spm``,
    ``step_length_m`` (the known distance over the counted steps), ``speed_mps`` (the distance over the steps'
    summed durations ``1 / f``) and ``n_steps``; decision W211: ``cadence_range_spm``, the lowest and highest median
    cadence of the walks (``walks_hz``: each walk's step frequencies; default one walk); None without a step."""
    f = np.asarray(frequency_hz, dtype=np.float64)
    f = f[np.isfinite(f) & (f > 0)]
    if not f.size:
        return None
    per_walk = [median_cadence(w)[0] for w in (walks_hz if walks_hz is not None else [f])]
    per_walk = [c for c in per_walk if c is not None] or [60.0 * float(np.median(f))]
    return {"median_cadence_spm": round(60.0 * float(np.median(f)), 2),
            "step_length_m": round(float(distance_m) / f.size, 4),
            "speed_mps": round(float(distance_m) / float(np.sum(1.0 / f)), 4), "n_steps": int(f.size),
            "cadence_range_spm": [round(min(per_walk), 2), round(max(per_walk), 2)]}


#: decision W211: a calibrated track whose median cadence is more than this fraction below the calibration walks'
#: lowest or above their highest warns (a priori: the trial's speed bias is ~1/3 of the cadence change, +9.6 % at
#: x0.77 and -8.2 % at x1.29, so 10 % of cadence is ~3 % of distance, a same-speed re-test's spread)
CALIBRATION_SPEED_MARGIN = 0.10


def calibration_covers(gait: dict | None, cadence: float | None, n: int) -> bool | None:
    """Decision W211's band, W227's verdict: True when the median ``cadence`` (steps/min, over ``n`` >=
    :data:`PLAUSIBILITY_MIN_PAIRS` steps) of a track calibrated on walks of ``gait`` (:func:`calibration_gait`; its
    ``cadence_range_spm``, else ``median_cadence_spm`` for both ends) lies inside that range widened by
    :data:`CALIBRATION_SPEED_MARGIN` either way, False outside it, None when not judged (no calibration gait, no
    cadence, too few steps)."""
    gait = gait or {}
    rng = gait.get("cadence_range_spm") or [gait.get("median_cadence_spm")] * 2
    if rng[0] is None or cadence is None or n < PLAUSIBILITY_MIN_PAIRS or not rng[0] > 0:
        return None
    lo, hi = float(rng[0]) * (1.0 - CALIBRATION_SPEED_MARGIN), float(rng[1]) * (1.0 + CALIBRATION_SPEED_MARGIN)
    return bool(lo <= cadence <= hi)


def calibration_speed_message(gait: dict | None, cadence: float | None, n: int, pipeline: str, *,
                               pelvic_gyro: bool = False) -> str | None:
    """Decision W211's one warning line when a track calibrated on walks of ``gait`` (:func:`calibration_gait`; its
    ``cadence_range_spm``, else ``median_cadence_spm`` for both ends; None: not judged) has a median ``cadence``
    (steps/min, over ``n`` >= :data:`PLAUSIBILITY_MIN_PAIRS` steps) outside the range widened by
    :data:`CALIBRATION_SPEED_MARGIN` either way. Decision W579: ``pelvic_gyro`` - the cadence and count are the
    pelvic-gyro detector's, read because W442 found the waist contacts no step count; the line says so."""
    gait = gait or {}
    rng = gait.get("cadence_range_spm") or [gait.get("median_cadence_spm")] * 2
    if calibration_covers(gait, cadence, n) is not False:
        return None
    cal = f"{float(rng[0]):.0f}" if rng[0] == rng[1] else f"{float(rng[0]):.0f}-{float(rng[1]):.0f}"
    speed = gait.get("speed_mps")
    at = f", {float(speed):.2f} m/s" if speed is not None else ""
    whose = ("the pelvic gyro's median cadence (the waist contacts are no step count, decisions W476, W579)"
             if pelvic_gyro else "this walk's median cadence")
    return (f"{whose} {cadence:.0f} steps/min ({n} steps) is outside the {pipeline} calibration's "
            f"{cal} steps/min{at} by more than {100 * CALIBRATION_SPEED_MARGIN:.0f} % (decision W211): a calibration "
            "holds near the speed it was made at (one at 1.0 m/s read +7..+10 % at 0.6 m/s and -8 % at 2.0 m/s); "
            "calibrate on walks at several speeds ('pdrlearn calibrate SLOW NORMAL FAST -d M -d M -d M', which "
            "separates K and F) or on a walk at this speed")


def calibration_gait_message(gait: dict | None, cadence: float | None, n: int, pipeline: str) -> str | None:
    """Decision W140's one warning line when a track calibrated on walks of ``gait`` (:func:`calibration_gait`;
    None: a params file written before W140, not judged) has a median ``cadence`` (steps/min, over ``n`` >=
    :data:`PLAUSIBILITY_MIN_PAIRS` steps) outside :data:`CALIBRATION_CADENCE_BAND` times the calibration's."""
    ref = (gait or {}).get("median_cadence_spm")
    if ref is None or cadence is None or n < PLAUSIBILITY_MIN_PAIRS or not ref > 0:
        return None
    ratio = cadence / float(ref)
    lo, hi = CALIBRATION_CADENCE_BAND
    if lo <= ratio <= hi:
        return None
    length, speed = gait.get("step_length_m"), gait.get("speed_mps")
    how = "".join([f", step {float(length):.2f} m" if length is not None else "",
                   f", {float(speed):.2f} m/s" if speed is not None else ""])
    return (f"this walk's median cadence {cadence:.0f} steps/min ({n} steps) is {ratio:.2f}x that of the walks the "
            f"{pipeline} parameters were calibrated on ({float(ref):.0f} steps/min{how}; outside x{lo:g}-x{hi:.2f} "
            "warns, decision W140): a calibration holds for the gait it was made on, and on a different gait "
            "(shuffling against normal walking, before against after a treatment) the calibrated step length is "
            "biased (a shuffle's calibration read normal walking -25 % on waist-pendulum, -85 % on waist-pll); "
            "calibrate on a walk of this gait ('pdrlearn calibrate DIR --distance M --out PARAMS.json') before "
            "comparing distances or speeds")



def calibration_line(gait: dict | None, cadence: float | None, n: int, pipeline: str, *, gait_check: bool = False,
                     speed_check: bool = True, pelvic: tuple[float, int] | None = None) -> str | None:
    """The one calibration line of a calibrated waist track (decisions W140, W211; E142: ``track`` and ``run`` alike):
    W140's change-of-gait line when the option ``gait_check`` is on and it fires (its band lies outside W211's, so
    one line, not two), else W211's speed line when ``speed_check`` (on by default) and it fires; None: neither.
    Decision W579: ``pelvic`` (the pelvic-gyro detector's cadence, steps/min, and count), given when W442 found the
    contacts no step count: both checks read it instead of the contacts' ``cadence`` and ``n``."""
    if pelvic is not None:  # decision W579: the contacts' cadence is not the walker's
        cadence, n = pelvic
    line = calibration_gait_message(gait, cadence, n, pipeline) if gait_check else None
    if line is None and speed_check:
        line = calibration_speed_message(gait, cadence, n, pipeline, pelvic_gyro=pelvic is not None)
    return line

#: W105: the still period read: the first standstill of at least 2 s (thesis ch.7.2's setup standstill, as
#: ``calibrate_standstill``), up to its first 5 s (thesis ch.4.4)
STILL_S = (2.0, 5.0)
#: W105: a mean vertical rate at rest above this (rad/s) warns: 1.5x the largest of the six real waist recordings
#: that start still (mobgap HA001/HA002/MS001: |rate| 0.0017-0.0104 rad/s; a priori factor, not fitted to a trial)
STILL_YAW_RATE_WARN_RPS = 0.015


def turns_bias_message(measured_turns, turns: float, bias_rps: float, *,
                       bound_rps: float = STILL_YAW_RATE_WARN_RPS, off_turns: float = 0.5) -> str | None:
    """Decision C262: the one line for ``calibrate --turns``'s fitted vertical gyro bias ``bias_rps`` (seed 003 eq. 2)
    when it exceeds ``bound_rps`` (W105's rate at rest: more than a MEMS gyroscope drifts still) or when a walk's
    measured turn (``measured_turns``: its ``int w dt / 2 pi`` per walk, bias included) is ``off_turns`` or more from
    ``turns``; else None. The line names the nearest half turn the walks measured when that differs from ``turns``."""
    from pdrlearn.decision_refs import decision_ref

    m = np.asarray(measured_turns, dtype=float).ravel()
    far = m.size > 0 and bool(np.any(np.abs(m - turns) >= off_turns))
    if not (far or abs(bias_rps) > bound_rps) or not np.isfinite(bias_rps):
        return None
    walked = ", ".join(f"{v:+.2f}" for v in m)
    half = round(2.0 * float(np.mean(m))) / 2.0 if m.size else turns
    hint = (f"if the walk turned {half:+g} turn(s) (an out-and-back is 0.5), calibrate with --turns {half:g}; "
            if half != turns else "")
    return (f"--turns {turns:+g}: the gyroscope measured {walked} turn(s) over the walk(s), so the fitted gyro bias "
            f"is {bias_rps:+.4f} rad/s ({np.degrees(bias_rps):+.2f} deg/s), "
            + ("over" if abs(bias_rps) > bound_rps else "under")
            + f" the {bound_rps:g} rad/s a MEMS gyroscope drifts at rest (W105): {hint}a bias this large is written "
            f"and turns every straight of the track ({decision_ref('C262', topic='cohort')})")


def still_yaw_rate(t: np.ndarray, acc_nav: np.ndarray, gyr_nav: np.ndarray, fs: float,
                   bias_rps: float = 0.0, *, vertical: np.ndarray | None = None,
                   still: np.ndarray | None = None) -> tuple[float, float, float] | None:
    """``(rate, t0, t1)``: the mean vertical angular rate (rad/s, ``gyr_nav[:, 2]``, or ``vertical`` when given,
    less the calibrated ``bias_rps``) over the first standstill of :data:`STILL_S` (``standstill_mask``: magnitudes,
    so any frame), and its times; None when the unit never stands still that long (decision W105). ``still``: that
    mask when the caller has it (decision W354)."""
    up = gyr_nav[:, 2] if vertical is None else np.asarray(vertical, dtype=float)
    for a, stop in still_periods(t, acc_nav, gyr_nav, fs, still=still):
        return float(np.mean(up[a:stop])) - bias_rps, float(t[a]), float(t[stop - 1])
    return None


def still_periods(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, fs: float, *, still: np.ndarray | None = None):
    """W105's still periods: ``(start, stop)`` sample indices (stop exclusive) of each standstill of at least
    ``STILL_S[0]`` s (``standstill_mask``, or ``still``, that mask already computed: W354), cut to its first
    ``STILL_S[1]`` s, in time order."""
    lo, hi = STILL_S
    for a, b in runs(standstill_mask(acc, gyr, fs) if still is None else still):
        if t[b - 1] - t[a] >= lo - 1.5 / fs:
            yield a, a + int(np.searchsorted(t[a:b], t[a] + hi, side="right"))


def waist_bias_line(session: Session) -> str | None:
    """Decision W125: W105's warning line for a session's waist unit as the two-unit tracks read it (``track``'s
    PLASYS path, ``run``): :func:`waist_rest_bias`'s first standstill; None without a waist unit, without a
    standstill, or under :data:`STILL_YAW_RATE_WARN_RPS`."""
    return waist_bias_check(session)[0]


def waist_bias_check(session: Session, fix: str | None = None):
    """Decisions W125/W421: ``(line, rest)``: W105's line on the waist unit's first standstill, else W421's on its
    later ones (``fix``: the way out, TWO_UNIT_FIX by default), or None; and :func:`waist_rest_bias`'s
    ``(first, rests)`` (None without a readable waist unit)."""
    rates = unit_rest_rates(session, "waist")
    if rates is None:
        return None, None
    rest = _first_and_rests(rates)
    line = still_yaw_rate_message(rest[0], fix or TWO_UNIT_FIX)
    return line or drifting_rest_message(rates, "waist", fix or TWO_UNIT_FIX), rest


def waist_rest_bias(session: Session) -> tuple[tuple[float, float, float] | None, np.ndarray] | None:
    """Decisions W125/W126: the waist unit's vertical rate at rest as the two-unit heading reads it: the waist
    gyroscope (body FLU, ``orient.unit_data``) on the low-passed accelerometer's up direction, as the waist
    heading's complementary filter turns by it (thesis ch.7.1). Returns ``(first, rests)``: W105's
    :func:`still_yaw_rate` over the first standstill (or None), and ``rests`` (k, 2) = (mid time s, mean rate rad/s)
    of every standstill of at least ``STILL_S[0]`` (its first ``STILL_S[1]`` s; W126's drifting-bias profile); None
    without a readable waist unit."""
    found = unit_rest_rates(session, "waist")
    return None if found is None else _first_and_rests(found)


def _first_and_rests(found: np.ndarray):
    """W105's first standstill ``(rate, t0, t1)`` (None without one) and W126's ``(mid time, rate)`` rows of
    :func:`unit_rest_rates`' ``found``."""
    first = None if not len(found) else (float(found[0, 2]), float(found[0, 0]), float(found[0, 1]))  # W105
    return first, np.column_stack([0.5 * (found[:, 0] + found[:, 1]), found[:, 2]])


def unit_rest_rates(session: Session, unit: str = "waist") -> np.ndarray | None:
    """Decisions W125/W421: ``(k, 3)`` = (start s, end s, mean vertical rate rad/s) of every standstill of at least
    ``STILL_S[0]`` s (its first ``STILL_S[1]`` s; W105's :func:`still_periods`) of the ``unit`` ("waist" / "foot"):
    its gyroscope on the low-passed accelerometer's up direction, the rate a heading turns by (thesis ch.7.1; a
    projection on the measured gravity, so the foot is read in its sensor axes, no frame needed). None without a
    readable unit."""
    from pdrlearn.errors import MissingSensorError
    from pdrlearn.orient import _kernels as OK
    from pdrlearn.orient import unit_data
    from pdrlearn.signal import lowpass

    prefix = "w" if unit == "waist" else "f"
    if not session.has(f"{prefix}Accelerometer", f"{prefix}Gyroscope"):
        return None
    try:
        u = unit_data(session, unit, purpose=f"{unit} gyroscope bias check", sensor_axes=unit == "foot")
    except (MissingSensorError, DataError):  # the heading that needs the unit says why it cannot read it
        return None
    up = OK.yaw_rate(lowpass(u.acc, min(1.0, 0.4 * u.fs), u.fs), u.gyr)  # as WaistHeading.estimate (thesis ch.7.1)
    rests = [(float(u.t[a]), float(u.t[stop - 1]), float(np.mean(up[a:stop])))
             for a, stop in still_periods(u.t, u.acc, u.gyr, u.fs)]
    return np.array(rests, dtype=float).reshape(-1, 3)


def rest_rate_excess(rates: np.ndarray, *, level: bool = True) -> tuple[float, int] | None:
    """Decision W421: ``(rate, k)``: the largest vertical rate at rest (rad/s) a heading keeps of the unit's
    standstills ``rates`` (:func:`unit_rest_rates`) and the standstill ``k`` it was read at: with ``level`` (the
    waist: nothing removes its bias) the largest ``|rate_k|`` or change ``|rate_k - rate_0|`` from the first rest;
    without (the foot: its pipeline removes the first rest's bias, thesis ch.7.2.1) the largest change only. None
    with fewer than one (``level``) or two rests."""
    r = np.asarray(rates, dtype=float).reshape(-1, 3)[:, 2]
    if len(r) < (1 if level else 2):
        return None
    cand = np.abs(r - r[0])
    if level:
        cand = np.maximum(cand, np.abs(r))
    k = int(np.argmax(cand))
    return float(cand[k]), k


def still_yaw_rate_message(found: tuple[float, float, float] | None, fix: str | None = None) -> str | None:
    """Decision W105's one warning line when the rate at rest exceeds :data:`STILL_YAW_RATE_WARN_RPS`."""
    if found is None or abs(found[0]) <= STILL_YAW_RATE_WARN_RPS:
        return None
    rate, t0, t1 = found
    deg = float(np.degrees(rate))
    return (f"the waist gyroscope reads {rate:+.4f} rad/s ({deg:+.2f} deg/s) about the vertical while the unit stands "
            f"still ({t0:.1f}-{t1:.1f} s; over {STILL_YAW_RATE_WARN_RPS:g} warns, decision W105): a gyroscope bias, "
            f"which turns the path by {abs(deg) * 60:.0f} deg a minute; a phone app's uncalibrated gyroscope "
            "(Android's 'gyroscope uncalibrated') has one: export the calibrated gyroscope; "
            + (fix or "for another IMU, calibrate the bias on a walk with whole turns ('pdrlearn calibrate DIR "
               "--turns N')"))


#: decision W421: X_foot as measured (1.25 x the largest foot value of the good data, 0.00539 rad/s)
FOOT_DRIFT_MEASURED_RPS = 0.00674
#: decision W421: a vertical rate at a rest (or its change from the first rest) over this (rad/s) warns. Measured,
#: NOT ADOPTED for the waist (inf: the daily-activity mobgap Test11 rests read -1.02 to +2.35 deg/s); the foot's
#: change from its first rest: decision L527, adopted
REST_RATE_WARN_RPS = {"waist": float("inf"), "foot": FOOT_DRIFT_MEASURED_RPS}


def drifting_rest_message(rates: np.ndarray, unit: str = "waist", fix: str | None = None, *,
                          threshold: float | None = None) -> str | None:
    """Decision W421's one warning line when :func:`rest_rate_excess` of the ``unit``'s standstills ``rates``
    exceeds ``threshold`` (rad/s; :data:`REST_RATE_WARN_RPS` by default): the size (deg/s, deg a minute), the unit,
    the rests and the remedy."""
    level = unit == "waist"
    found = rest_rate_excess(rates, level=level)
    threshold = REST_RATE_WARN_RPS[unit] if threshold is None else threshold
    if found is None or found[0] <= threshold:
        return None
    size, k = found
    r = np.asarray(rates, dtype=float).reshape(-1, 3)
    deg = np.degrees(r[:, 2])
    what = (f"reads {deg[k]:+.2f} deg/s about the vertical at the rest at {r[k, 0]:.1f}-{r[k, 1]:.1f} s "
            f"(the first rest, {r[0, 0]:.1f}-{r[0, 1]:.1f} s: {deg[0]:+.2f} deg/s)")
    kept = "" if level else ", less the first rest's bias its pipeline removes"
    remedy = fix if fix else (WAIST_BIAS_FIX if level else FOOT_DRIFT_FIX)
    return (f"the {unit} gyroscope {what}: a bias{' that drifts' if k else ''} of {np.degrees(size):.2f} deg/s"
            f"{kept}, which turns the path by about {np.degrees(size) * 60:.0f} deg a minute of walking (over "
            f"{np.degrees(threshold) * 60:.0f} deg a minute at any rest warns, decision "
            f"{'W421' if level else 'L527'}); "
            + remedy)


def foot_drift_line(session: Session) -> str | None:
    """Decision W421's line for the foot unit a foot heading turns by (its pipeline removes the first rest's bias,
    ``gyro_bias="standstill"``): the rate at a later rest changed by more than the threshold; None otherwise."""
    rates = unit_rest_rates(session, "foot")
    return None if rates is None else drifting_rest_message(rates, "foot")


#: decision W421: the remedies the rest-rate line names
WAIST_BIAS_FIX = ("let the sensor warm up before the walk, or calibrate the bias on a walk with whole turns "
                  "('pdrlearn calibrate DIR --turns N')")
FOOT_DRIFT_FIX = ("the foot pipeline removes only the bias read at the first rest, so a bias that drifts "
                  "(temperature) bends the foot's own heading: let the sensor warm up before the walk and stand "
                  "still 2-5 s before it, or re-record after the gyroscope offset is calibrated")


#: W125: the way out the two-unit tracks name (the foot's ZUPT-corrected yaw does not read the waist gyroscope);
#: W422: and the rest-bias removal (W126's ``waist_bias``, a ``--params`` key since W422)
WAIST_BIAS_PARAMS = "--params holding {\"waist_bias\": true}"
TWO_UNIT_FIX = ("the two-unit track heads by the waist unit: remove the bias read at its rests with "
                f"{WAIST_BIAS_PARAMS} (decisions W126, W422; offline), track the foot unit's own yaw with --units "
                "foot, or re-record after the waist unit's gyroscope offset is calibrated (decision W125)")


def bias_removed(line: str) -> str:
    """Decisions W422/W423: a W105 line of a two-unit track that removed the bias (``waist_bias`` on, the default
    since W423): its remedy replaced by what was done and how to undo it."""
    head = line.split("the two-unit track heads by the waist unit", 1)[0].rstrip("; ")
    return (head + "; waist_bias is on (the default since decision W423), so the heading turned by the waist "
            "gyroscope less the vertical rate read at each rest, interpolated between rests (the check of decision "
            "W125, the removal of W126, W422); "
            "it reads a rest as still, so if the walker turned or sat while standing, turn it off with "
            "--params holding {\"waist_bias\": false}, or track the foot unit's own yaw with --units foot")


#: decision W157: a walking sequence of at most this many steps (3 contacts after its first: under two strides of
#: each foot, Mobilise-D's shortest walking bout - Kluge et al. 2021, not in the seeds) is a start-stop micro-bout,
#: all gait initiation and termination, outside the steady walking both waist step-length models describe (seed 003
#: eq. 1's inverted pendulum, seed 000's line in the step frequency)
MICRO_BOUT_MAX_STEPS = 3
#: W157: at least this many micro-bouts and this share of the track's distance in them warn (a priori round values:
#: a queue's shuffle forward is a dozen, a walk with a few stops at doors has a few, carrying a small share)
MICRO_BOUT_MIN_COUNT = 5
MICRO_BOUT_MIN_SHARE = 0.5
#: decision W402: the distance errors measured where W157's line fired (experiments/startstop_w402.py, fresh users
#: 9556-9559, uncalibrated): normal steps between 2-3 s stands read short on waist-pendulum (-20.6 to -29.8 %) and
#: long on waist-pll (+46.1 to +137.9 %), a queue's 0.2 m steps long on both (+98.1 to +220.3 %)
STARTSTOP_ERROR_TEXT = ("too short or too long (simulated start-stop walks: -30 to +220 %; normal steps between "
                        "stands read short on waist-pendulum, a queue's 0.2 m shuffles long; decision W402)")


def micro_bouts(length_m: np.ndarray, has_next: np.ndarray) -> tuple[int, int, float, float]:
    """Decision W157: ``(n_micro, n_sequences, micro_m, total_m)`` of a waist steps table: its walking sequences
    (consecutive rows with a next contact plus the closing row), those of at most :data:`MICRO_BOUT_MAX_STEPS`
    steps, and the summed ``|length_m|`` (m) of those and of all rows."""
    from pdrlearn.waist.lengths import walking_sequences

    length = np.abs(np.nan_to_num(np.asarray(length_m, dtype=np.float64)))
    hn = np.asarray(has_next, dtype=bool)
    seqs = walking_sequences(hn)
    micro = [s for s in seqs if 0 < int(hn[s].sum()) <= MICRO_BOUT_MAX_STEPS]
    return (len(micro), len(seqs), float(sum(length[s].sum() for s in micro)), float(length.sum()))


def micro_bout_message(n_micro: int, n_sequences: int, micro_m: float, total_m: float) -> str | None:
    """Decision W157's one warning line when at least :data:`MICRO_BOUT_MIN_COUNT` of a waist track's walking
    sequences are micro-bouts (:func:`micro_bouts`) carrying :data:`MICRO_BOUT_MIN_SHARE` or more of its distance;
    None otherwise."""
    if n_micro < MICRO_BOUT_MIN_COUNT or not total_m > 0 or micro_m < MICRO_BOUT_MIN_SHARE * total_m:
        return None
    return (f"{n_micro} of the {n_sequences} walking sequences have {MICRO_BOUT_MAX_STEPS} steps or fewer between "
            f"standstills and carry {micro_m:.1f} of the {total_m:.1f} m ({100 * micro_m / total_m:.0f} %; "
            f"{MICRO_BOUT_MIN_COUNT} or more carrying half the distance warns, decision W157): start-stop "
            "shuffling (a queue, a crowded platform) is all gait initiation and termination, outside the steady "
            "walking the waist step-length models and a calibration describe: the waist distance of these "
            f"sequences is not reliable and may read {STARTSTOP_ERROR_TEXT}; a foot unit measures such steps "
            "(plasys pipeline)")


#: decision W405: a walker shorter than this (m, meta.json's height or the height its leg implies, W115) is warned that
#: an uncalibrated lower-back track reads them long (waist-pll) or off (waist-pendulum, W534): trial T1 (session 38)
#: measured simulated children of 1.15-1.45 m (the tallest 1.45 m) at the height-scaled default cadence
PLL_SHORT_HEIGHT_M = 1.5
#: decision W405: trial T1 (session 38), children of 1.15-1.45 m at the height-scaled default cadence: distance error
#: (%) of uncalibrated waist-pll (+43.6 to +50.3; an adult of 1.70 m +29.9) and waist-pendulum (-0.8 to -14.4); kept
#: for a walker stepping more slowly than :data:`CHILD_STEP_BANDS` measured, or with no step time
DEFAULT_CADENCE_RANGES = {"waist-pll": (43.6, 50.3), "waist-pendulum": (-14.4, -0.8)}
#: decision W533: uncalibrated distance error (%) of fresh simulated children (users 14970-14989: 1.15-1.45 m, step
#: times 0.34-0.45 s, step lengths 0.30-0.50 m, bounce constant / pendulum, 30 m walks;
#: experiments/children_waist_s47_w533.py, its results/children_waist_s47_w533.md) by the band of their tracked
#: median step time: (band's lower bound s, upper bound s, {pipeline: (smallest, largest)}, children in the band)
CHILD_STEP_BANDS = (
    (0.0, 0.38, {"waist-pll": (51.9, 100.7), "waist-pendulum": (-16.1, 29.9)}, 8),
    (0.38, 0.41, {"waist-pll": (40.6, 100.1), "waist-pendulum": (-7.0, 23.4)}, 6),
    (0.41, 0.45, {"waist-pll": (37.1, 124.6), "waist-pendulum": (-17.7, 49.2)}, 6),
)
_OTHER = {"waist-pll": "waist-pendulum", "waist-pendulum": "waist-pll"}


def _span(lo: float, hi: float) -> str:
    return f"{lo:+.1f} to {hi:+.1f} %"


def short_walker_ranges(step_time_s: float | None) -> tuple[str, dict[str, tuple[float, float]]]:
    """Decision W533: ``(what the figures are, {pipeline: (smallest, largest) distance error %})`` for a walker whose
    median step time is ``step_time_s`` (s): the :data:`CHILD_STEP_BANDS` band it falls in, else (slower than the
    children measured, or None) W405's :data:`DEFAULT_CADENCE_RANGES`."""
    if step_time_s is not None and np.isfinite(step_time_s):
        for lo, hi, ranges, n in CHILD_STEP_BANDS:
            if lo <= step_time_s < hi or (hi == CHILD_STEP_BANDS[-1][1] and step_time_s == hi):
                band = f"under {hi:.2f} s" if lo == 0.0 else f"{lo:.2f}-{hi:.2f} s"
                return (f"{n} simulated children of 1.15-1.45 m stepping every {band} (steps 0.30-0.50 m; decision "
                        "W533)", ranges)
    return ("simulated children of 1.15-1.45 m at the height-scaled default cadence (trial T1, decision W405)",
            DEFAULT_CADENCE_RANGES)


def short_walker_message(meta: dict | None, pipeline: str, step_time_s: float | None = None) -> str | None:
    """Decisions W405, W533, W534: the line of an uncalibrated ``pipeline`` (waist-pll, waist-pendulum) track of a
    walker whose height (meta.json ``height_m``, else the height its ``leg_length_m`` / ``sensor_height_m`` implies,
    W115) is under :data:`PLL_SHORT_HEIGHT_M`: the distance error both pipelines read on simulated children at the
    walker's median step time ``step_time_s`` (:func:`short_walker_ranges`) and the fix, calibrating waist-pendulum
    on a walk of known length (a waist-pll calibration on a short walk folds its edge contacts in, W393); None for a
    taller walker or none known."""
    from pdrlearn.waist.params import _meta_numbers, subject_height

    if not _meta_numbers(meta or {}, "height_m", "leg_length_m", "sensor_height_m"):
        return None
    height = subject_height(meta, infer=True)[0]
    if not height < PLL_SHORT_HEIGHT_M:
        return None
    what, ranges = short_walker_ranges(step_time_s)
    other = _OTHER[pipeline]
    pace = ("" if step_time_s is None or not np.isfinite(step_time_s) else
            f" stepping every {step_time_s:.2f} s ({60 / step_time_s:.0f} steps/min)")
    return (f"uncalibrated {pipeline} on a walker of about {height:.2f} m{pace}: {what} read "
            f"{_span(*ranges[pipeline])} in distance on it ({other} {_span(*ranges[other])}; decision W405), "
            "so this distance may be that far off; calibrate waist-pendulum on this walker's walk of known "
            "length, a 10 m walkway will do ('pdrlearn calibrate DIR --pipeline waist-pendulum --distance 10 "
            "--out PARAMS.json', then --params PARAMS.json --pipeline waist-pendulum; decision W534); a "
            "waist-pll calibration on so short a walk counts its edge contacts into the step length (decision "
            "W393)")
