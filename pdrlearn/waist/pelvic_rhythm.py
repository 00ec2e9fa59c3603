"""The pelvic gyroscope's step rhythm against the lower back's contacts at a very slow gait (decisions W440-W442).

At 40-70 steps/min the step's own vertical acceleration is small and the seed 003 detector adds contacts inside
a step (W79), while the pelvis still rotates once per step (thesis ch.5.3: the pelvic-gyro detector).
:func:`rhythm_keep` (W440) drops a contact that comes sooner after the previous one than the local pelvic step period
allows (an option, ``pelvic_rhythm_veto``: its adoption rule was not met on the real daily-activity recordings);
:func:`pdrlearn.waist.plausibility.count_mismatch_message` (W441, W442) compares the two counts in both
directions. Pure numerical kernels on event times; the track reads the pelvic-gyro events once
(:func:`pelvic_steps`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io import Session
from pdrlearn.kernels.waist import SHORTEST_STEP_FRAC
from pdrlearn.waist.plausibility import STEP_COUNT_MIN

#: decision W440: a contact sooner than this fraction of the local pelvic step period after the previous contact of
#: its walking sequence is an extra contact (a priori: above half a period, so a doubled count is caught, and far
#: below one, so an irregular real step is not; not fitted to the fresh users W440 was measured on)
RHYTHM_FRACTION = 0.6
#: decision W440: the pelvic-gyro step intervals whose midpoints lie within this many seconds of a contact give its
#: local step period (a few steps either side at 40-70 steps/min)
RHYTHM_WINDOW_S = 3.0
#: decision W440: pelvic-gyro intervals longer than this are pauses, not steps (s; the longest step interval of one
#: walking sequence of the waist detector, ``pdrlearn.track.waist.MAX_STEP_S``, is 1.5 s; at 40 steps/min a step
#: lasts 1.5 s, so a little above it)
RHYTHM_MAX_STEP_S = 2.0
#: decision W440's second candidate: the veto judges a pair only where the local pelvic step period is at least this
#: (s): 60 / L95's lowest validated cadence, 70 steps/min
SLOW_PERIOD_S = 60.0 / 70.0
#: decision W440: the option value of the veto judged only below 70 steps/min
RHYTHM_SLOW = "slow"


def pelvic_steps(session: Session) -> np.ndarray | None:
    """The pelvic-gyro detector's step times (s) of ``session`` (thesis ch.5.3), None without a waist gyroscope.
    An internal cross-check (W440, W441): the detector's own lines (e.g. its "no standstill calibration") are kept
    out of the track's warnings (decision W441, amended by the lead: a detector the user did not ask for)."""
    from pdrlearn.steps.detectors import PelvicGyroStepDetector
    from pdrlearn.warning_lines import isolated_warnings

    try:
        with isolated_warnings("pdrlearn.steps"):
            return PelvicGyroStepDetector().detect(session)["event_s"].to_numpy(float)
    except DataError:
        return None


def median_step_period(gyro_s: np.ndarray, max_step_s: float = RHYTHM_MAX_STEP_S) -> float:
    """Decision W475: the median of the pelvic-gyro step intervals (``gyro_s``, s) no longer than ``max_step_s``
    (W440's pauses excluded); NaN with fewer than two such intervals."""
    iv = np.diff(np.sort(np.asarray(gyro_s, dtype=np.float64)))
    iv = iv[iv <= max_step_s]
    return float(np.median(iv)) if iv.size >= 2 else float("nan")


def pelvic_step_period_s(session: Session, gyro_s: np.ndarray | None = None) -> float:
    """Decision W475: :func:`median_step_period` of the session's :func:`pelvic_steps` (NaN without a waist
    gyroscope); ``gyro_s``: those steps when already read (decision W485)."""
    g = pelvic_steps(session) if gyro_s is None else gyro_s
    return float("nan") if g is None else median_step_period(g)


def read_once(det, session: Session) -> np.ndarray | None:
    """Decision W485: the session's :func:`pelvic_steps`, read once per session: the ones the step detector ``det``
    read while detecting this very ``session`` (the PLL's slow band, W475: its ``pelvic_steps_read_``, set by
    :meth:`remember`), else read now. W441's / W476's count check and W440's veto take them from here, so a track or
    ``steps`` with ``--detector pll`` runs the pelvic-gyro detector once, not twice."""
    read = getattr(det, "pelvic_steps_read_", None)
    if read is not None and read[0]() is session:
        return read[1]
    return pelvic_steps(session)


def remember(det, session: Session, gyro_s: np.ndarray | None) -> None:
    """Decision W485: keep on ``det`` the pelvic-gyro steps it read for ``session`` (a weak reference to the
    session, so a detector kept for the next session neither holds this one nor hands its steps to another)."""
    import weakref

    det.pelvic_steps_read_ = (weakref.ref(session), gyro_s)


def slow_shortest_step_s(gyro_s: np.ndarray | None, min_steps: int = STEP_COUNT_MIN) -> float | None:
    """Decision W591 (``slow_min_step``): the offline contact detector's shortest step (s) for a session whose
    pelvic-gyro steps are ``gyro_s`` (s): W113's fraction (0.75) of their median step (:func:`median_step_period`,
    W475) when that step is at least :data:`SLOW_PERIOD_S` (slower than L95's 70 steps/min) and the pelvic gyro counts
    at least ``min_steps`` (W99's 10); None otherwise (W113's own shortest step, at most W16's 0.3 s, stands). A slow
    step's own vertical bounce is small (W79) and the heel strike's maxima inside it are no contacts (W590)."""
    if gyro_s is None or np.asarray(gyro_s).size < min_steps:
        return None
    period = median_step_period(gyro_s)
    if not np.isfinite(period) or period < SLOW_PERIOD_S:
        return None
    return SHORTEST_STEP_FRAC * period  # W113's fraction, without W16's cap


def local_step_period(gyro_s: np.ndarray, at_s: np.ndarray, window_s: float = RHYTHM_WINDOW_S,
                      max_step_s: float = RHYTHM_MAX_STEP_S) -> np.ndarray:
    """Decision W440: at each time ``at_s`` the median of the pelvic-gyro step intervals (``gyro_s`` sorted, s) no
    longer than ``max_step_s`` whose midpoints lie within ``window_s``; NaN where fewer than two such intervals."""
    g = np.sort(np.asarray(gyro_s, dtype=np.float64))
    at = np.asarray(at_s, dtype=np.float64)
    out = np.full(at.shape, np.nan)
    if g.size < 3:
        return out
    iv, mid = np.diff(g), 0.5 * (g[1:] + g[:-1])
    ok = iv <= max_step_s
    iv, mid = iv[ok], mid[ok]
    for k, t in enumerate(at):
        w = np.abs(mid - t) <= window_s
        if np.count_nonzero(w) >= 2:
            out[k] = float(np.median(iv[w]))
    return out


def rhythm_keep(event_s: np.ndarray, has_next: np.ndarray, gyro_s: np.ndarray,
                fraction: float = RHYTHM_FRACTION, window_s: float = RHYTHM_WINDOW_S,
                min_period_s: float = 0.0) -> np.ndarray:
    """Decision W440: which contacts ``event_s`` (s, sorted; ``has_next[k]``: contact k+1 follows k in one walking
    sequence) to keep. While two consecutive kept contacts of one sequence lie closer than ``fraction`` x the local
    pelvic step period (:func:`local_step_period` at the later one), the one farther from its nearest pelvic-gyro
    step is dropped (the later on a tie), and the pair is judged again with the next kept contact. ``min_period_s``:
    only where that period is at least this (:data:`SLOW_PERIOD_S`: a walk slower than L95's 70 steps/min)."""
    ev = np.asarray(event_s, dtype=np.float64)
    hn = np.asarray(has_next, dtype=bool)
    keep = np.ones(ev.size, dtype=bool)
    g = np.sort(np.asarray(gyro_s, dtype=np.float64))
    if ev.size < 2 or g.size < 3:
        return keep
    period = local_step_period(g, ev, window_s)
    j = np.clip(np.searchsorted(g, ev), 1, g.size - 1)
    dist = np.minimum(np.abs(ev - g[j - 1]), np.abs(g[j] - ev))
    a = 0
    for b in range(1, ev.size):
        if not hn[b - 1]:  # a new walking sequence starts at b
            a = b
            continue
        if np.isfinite(period[b]) and period[b] >= min_period_s and ev[b] - ev[a] < fraction * period[b]:
            if dist[a] > dist[b]:
                keep[a] = False
                a = b
            else:
                keep[b] = False
            continue
        a = b
    return keep


def merge_dropped(steps: pd.DataFrame, keep: np.ndarray, count: str) -> pd.DataFrame:
    """``steps`` without the contacts not in ``keep``, each kept step extended over the dropped contacts that follow
    it in its walking sequence (its ``end_s`` and ``has_next`` those of the last of them; a kept step whose last such
contact closed the sequence closes it), so a dropped extra contact
    joins its neighbours' step instead of ending the walk (decision W440; W214's veto ends it,
    :func:`pdrlearn.waist.posture.drop_contacts`). ``attrs[count]`` counts the dropped."""
    keep = np.asarray(keep, dtype=bool)
    out = steps.copy()
    start, end = out["start_s"].to_numpy(float), out["end_s"].to_numpy(float).copy()
    hn = out["has_next"].to_numpy(bool).copy()
    last = None
    for k in range(len(out)):
        if keep[k]:
            last = k
        elif last is not None and hn[last]:  # a dropped contact inside the kept one's sequence
            # a sequence's closing contact ends at its start (as pdrlearn.kernels.waist.contact_rows closes one)
            end[last], hn[last] = (end[k], True) if hn[k] else (start[last], False)
    out = out.assign(end_s=end, has_next=hn)
    if "confidence" in out:  # a closing contact's confidence, as contact_rows gives it
        out.loc[~hn & steps["has_next"].to_numpy(bool), "confidence"] = 0.5
    out = out[keep].reset_index(drop=True)
    out.attrs.update(steps.attrs)
    out.attrs[count] = int((~keep).sum())
    return out
