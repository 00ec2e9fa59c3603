"""Clock alignment of the foot and waist units from their step events, numpy only (thesis ch.7: the units are
aligned with the gyroscope step detector): :func:`align_events` (``pdrlearn.steps.align_units``' estimate) and
L161's warning line, shared by ``track``, ``run`` (L170) and the lean runtime's :class:`~pdrlearn.runtime.Tracker`
(decision L177).

Model: at one physical instant the waist clock reads ``t_w = t_f + offset_s + drift * (t_f - ref_s)`` where
``t_f`` is the foot clock (the foot clock is the reference: labels and foot steps are kept on it) and ``ref_s`` a
foot-clock time inside the recording (decision L198: the matched foot events' mean, so ``offset_s`` is the offset
over the recording whatever the clock's origin, uptime or epoch; ``ref_s = 0`` is the simulator's convention).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError

#: decision L161: a foot-to-waist clock offset (s) over this warns on an unaligned two-unit track (a priori: under
#: half the step period of the slowest validated walk, 70 steps/min, L95 -- :func:`align_events` cannot tell offsets
#: a whole step apart -- and 5x the -0.04 s the simulated clean sessions read)
UNIT_OFFSET_WARN_S = 0.2
#: decision L183: an estimate is locked on at least this many matched foot events (the least :func:`align_events`'
#: drift fit reads) ...
MIN_LOCK_PAIRS = 5
#: ... whose residual SD (s) is at most this: chance coincidences within the 0.12 s tolerance spread 0.12 / sqrt(3) =
#: 0.069 s (uniform); walks lock at 0.021-0.037 s (L183); a priori ~0.7 of chance and 1.35x the largest walk's
LOCK_MAX_RESIDUAL_SD_S = 0.05


def offset_locked(estimate: dict) -> bool:
    """Decision L183: whether :func:`align_events`' ``estimate`` locked the two event trains (enough matched events,
    matched tighter than chance); an estimate that did not (a queue's start-stop shuffles, 1-2 strides a bout) tells
    no offset, and L161's check warns nothing on it."""
    sd = float(estimate.get("residual_sd_s", float("nan")))
    return int(estimate.get("matched", 0)) >= MIN_LOCK_PAIRS and bool(sd <= LOCK_MAX_RESIDUAL_SD_S)


def nearest_distance(times: np.ndarray, events: np.ndarray) -> np.ndarray:
    """The distance (s) from each of ``times`` (any shape) to the nearest of the sorted ``events`` (2 or more)."""
    idx = np.clip(np.searchsorted(events, times), 1, events.size - 1)
    return np.minimum(np.abs(events[idx] - times), np.abs(events[idx - 1] - times))


def align_events(foot_times, waist_times, *, max_offset_s: float = 2.0, step_s: float = 0.005,
                 tolerance_s: float = 0.12, fit_drift: bool = True, min_span_s: float = 60.0) -> dict:
    """Estimate ``offset_s`` (and ``drift``) so that ``foot + offset + drift * (foot - ref_s)`` meets waist events.

    Every foot stride event should coincide with one waist step event (the waist sees both feet), so the
    offset that matches the most foot events within ``tolerance_s`` wins (grid of ``step_s`` over
    +-``max_offset_s``; among offsets within 10 % of the best count, the local optimum closest to 0,
    because the units are roughly synchronised). The matched pairs are then
    fitted by least squares, ``t_w - t_f = offset + drift * (t_f - ref_s)`` (drift only when they span at least
    ``min_span_s`` seconds, else the median offset and ``drift = 0``). Decision L198: ``ref_s`` is the matched
    foot events' mean, so ``offset_s`` is the least-squares offset over the recording (the mean ``t_w - t_f``)
    and does not depend on where the clocks start (a drift fitted on absolute times extrapolated its noise to
    t = 0: +184649 s on an epoch-ms clock); a constant shift by ``offset_s`` (``waist_clock_offset_s``,
    ``--clock-offset``) is the best drift-free alignment.

    Limitation (docs/decisions/steps.md): a walk's step events are periodic, so offsets that differ by
    one step period (~0.5 s) match almost as well; bout starts and ends break the tie only when the
    waist and the foot see them differently. The estimate is reliable for offsets below half a step
    period and for changes of the offset (relative alignment).

    Returns
    -------
    dict with ``offset_s`` (at ``ref_s``), ``drift`` (s/s), ``ref_s`` (foot clock, s), ``matched`` (pairs),
    ``foot_events``, ``residual_sd_s``.
    """
    f = np.sort(np.asarray(foot_times, dtype=float))
    w = np.sort(np.asarray(waist_times, dtype=float))
    if f.size < 3 or w.size < 3:
        raise DataError(f"align_units: need at least 3 foot and 3 waist step events (got {f.size} and "
                        f"{w.size}); record a longer walk")
    grid = np.arange(-max_offset_s, max_offset_s + step_s / 2, step_s)
    dist = nearest_distance(f[None, :] + grid[:, None], w)  # (n_grid, n_foot)
    ok = dist <= tolerance_s
    counts = ok.sum(axis=1)
    mean_d = np.where(counts > 0, np.where(ok, dist, 0).sum(axis=1) / np.maximum(counts, 1), np.inf)
    # most matches wins; ties -> the smallest |offset| (the units are roughly synchronised: the phone
    # timestamps both streams), then the smallest mean distance
    best_count = counts.max()
    cand = np.flatnonzero(counts >= best_count - max(1, int(0.1 * f.size)))
    # keep the local optimum (smallest mean distance) of each run of adjacent candidates
    groups = np.split(cand, np.flatnonzero(np.diff(cand) > 1) + 1)
    heads = [g[np.argmin(mean_d[g])] for g in groups]
    o = float(grid[min(heads, key=lambda i: abs(grid[i]))])
    # least-squares refinement over the matched pairs (two passes to settle the matching)
    drift, ref = 0.0, float(f[0])
    pairs_f = pairs_w = np.zeros(0)
    for _ in range(2):
        pred = f + o + drift * (f - ref)
        j = np.clip(np.searchsorted(w, pred), 1, w.size - 1)
        jj = np.where(np.abs(w[j] - pred) < np.abs(w[j - 1] - pred), j, j - 1)
        m = np.abs(w[jj] - pred) <= tolerance_s
        pairs_f, pairs_w = f[m], w[jj[m]]
        if pairs_f.size < 2:
            break
        d = pairs_w - pairs_f
        ref = float(pairs_f.mean())  # decision L198: the fit's origin inside the recording, not the clock's 0
        if fit_drift and pairs_f.size >= 5 and np.ptp(pairs_f) >= min_span_s:
            drift, o = (float(v) for v in np.polyfit(pairs_f - ref, d, 1))
        else:
            o, drift = float(np.median(d)), 0.0
    resid = (pairs_w - pairs_f) - (o + drift * (pairs_f - ref)) if pairs_f.size else np.zeros(0)
    return {"offset_s": o, "drift": drift, "ref_s": ref, "matched": int(pairs_f.size), "foot_events": int(f.size),
            "residual_sd_s": float(resid.std()) if resid.size > 1 else float("nan")}


def unit_offset_message(offset_s: float, drift: float, command: str = "pdrlearn track",
                        remedy: str | None = None, estimate: dict | None = None) -> str | None:
    """Decision L161: the warning line for an estimated offset (s) and drift (s/s) over :data:`UNIT_OFFSET_WARN_S`,
    else None. ``command``: the one whose ``--align-units`` the line names (``pdrlearn run``, decision L170);
    ``remedy``: another fix to name instead (the live Tracker's keyword, decision L177); ``estimate``:
    :func:`align_events`' dict, None when it is not locked (decision L183, :func:`offset_locked`)."""
    if abs(offset_s) <= UNIT_OFFSET_WARN_S or (estimate is not None and not offset_locked(estimate)):
        return None
    fix = remedy if remedy is not None else f"`{command} --align-units`"
    return (f"the waist unit's steps fall {offset_s:+.2f} s from the foot unit's (drift {drift * 1e6:+.0f} ppm; over "
            f"{UNIT_OFFSET_WARN_S:g} s warns, decision L161): the unit clocks are offset (a unit switched on later "
            "that counts from 0, or a drifting clock), and the waist heading is read at the foot's strides; align "
            f"them with {fix} (an offset a whole step period apart is not seen)")


def unlocked_message(estimate: dict, option: str = "--align-units") -> str | None:
    """Decision L186: the line ``option`` (``track`` / ``run --align-units``) says when it keeps the clocks because
    :func:`align_events`' ``estimate`` did not lock (:func:`offset_locked`, L183: a start-stop queue's shuffles read
    an offset there is not); None when it locked."""
    if offset_locked(estimate):
        return None
    return (f"{option} kept the unit clocks: the step events did not lock (L183: {int(estimate.get('matched', 0))} "
            f"of {int(estimate.get('foot_events', 0))} foot events matched, scatter "
            f"{float(estimate.get('residual_sd_s', float('nan'))):.3f} s; locked: >= {MIN_LOCK_PAIRS} within "
            f"{LOCK_MAX_RESIDUAL_SD_S:g} s), so the {float(estimate.get('offset_s', float('nan'))):+.2f} s read is no "
            "offset; if you know the waist clock's offset, give it by hand (--clock-offset SECONDS instead of "
            f"{option}, decision E111; Tracker(..., waist_clock_offset_s=...) in Python), else drop --align-units "
            "(decision L186)")
