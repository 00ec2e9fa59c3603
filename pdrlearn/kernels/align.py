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


#: the largest clock drift (s/s) a clock may be moved by (``apply_alignment``, ``--clock-drift-ppm`` B265, the
#: Tracker's ``waist_clock_drift_ppm`` E229): 10 %, far beyond any crystal's
MAX_CLOCK_DRIFT = 0.1


def to_foot_clock(t_waist, offset_s: float, drift: float = 0.0, ref_s: float = 0.0):
    """Waist-clock times moved onto the foot clock: ``ref_s + (t_waist - offset_s - ref_s) / (1 + drift)`` (the
    module's model solved for ``t_f``; ``apply_alignment`` and decision L447's contacts share it)."""
    return ref_s + (t_waist - offset_s - ref_s) / (1.0 + drift)


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


#: steps decision 64: the foot events are cut into windows of at most this span (foot clock, s; 60 s x 250 ppm = 15 ms
#: of drift inside one, under the 0.12 s matching tolerance); L446 checks the estimate against these windows
ALIGN_WINDOW_S = 60.0
#: ... a window with fewer foot events than this tells no offset (L183's least lock, MIN_LOCK_PAIRS)
MIN_WINDOW_EVENTS = MIN_LOCK_PAIRS
#: ... and a window whose offset lies further than this (s) from the line of the windows before it is inconsistent
#: (a quarter of a 0.55 s step period: halfway between the right branch and the half-period point)
WINDOW_JUMP_S = 0.15


def _grid_heads(f: np.ndarray, w: np.ndarray, centre: float, max_offset_s: float, step_s: float,
                tolerance_s: float) -> np.ndarray:
    """The candidate offsets of foot events ``f`` against waist events ``w`` on a grid of ``step_s`` over
    ``centre`` +-``max_offset_s``: the local optimum (smallest mean distance) of each run of adjacent offsets whose
    matched count is within 10 % of the best (a walk's periodic steps give one run per step period)."""
    grid = centre + np.arange(-max_offset_s, max_offset_s + step_s / 2, step_s)
    dist = nearest_distance(f[None, :] + grid[:, None], w)  # (n_grid, n_foot)
    ok = dist <= tolerance_s
    counts = ok.sum(axis=1)
    mean_d = np.where(counts > 0, np.where(ok, dist, 0).sum(axis=1) / np.maximum(counts, 1), np.inf)
    cand = np.flatnonzero(counts >= counts.max() - max(1, int(0.1 * f.size)))
    groups = np.split(cand, np.flatnonzero(np.diff(cand) > 1) + 1)
    return grid[[g[np.argmin(mean_d[g])] for g in groups]]


def _refine(f: np.ndarray, w: np.ndarray, o: float, drift: float, ref: float, tolerance_s: float, fit_drift: bool,
            min_span_s: float) -> tuple[float, float, float, np.ndarray, np.ndarray]:
    """The least-squares clock line over the foot events matched within ``tolerance_s`` of the line ``o + drift * (f -
    ref)`` (two passes to settle the matching): ``(offset_s, drift, ref_s, matched foot, matched waist)``."""
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
        new_ref = float(pairs_f.mean())  # decision L198: the fit's origin inside the recording, not the clock's 0
        if fit_drift and pairs_f.size >= 5 and np.ptp(pairs_f) >= min_span_s:
            drift, o = (float(v) for v in np.polyfit(pairs_f - new_ref, d, 1))
        else:
            o, drift = float(np.median(d)), 0.0
        ref = new_ref
    return o, drift, ref, pairs_f, pairs_w


def _line(t: np.ndarray, o: np.ndarray, n: np.ndarray, fit_drift: bool,
          min_span_s: float) -> tuple[float, float, float]:
    """Steps decision 64: the clock line ``(offset at ref, drift, ref)`` through window offsets ``o`` at times ``t``
    weighted by their event counts ``n`` (their weighted mean when they span under ``min_span_s``)."""
    ref = float(np.average(t, weights=n))
    if fit_drift and t.size >= 2 and np.ptp(t) >= min_span_s:
        drift, off = np.polyfit(t - ref, o, 1, w=np.sqrt(n))
        return float(off), float(drift), ref
    return float(np.average(o, weights=n)), 0.0, ref


def window_offsets(f: np.ndarray, w: np.ndarray, *, window_s: float, max_offset_s: float, step_s: float,
                   tolerance_s: float, fit_drift: bool, min_span_s: float) -> dict:
    """Steps decision 64: the offsets of the foot events' windows of at most ``window_s`` (with
    :data:`MIN_WINDOW_EVENTS` or more), unwrapped across step periods from the recording's start: the first window's
    candidate closest to 0, every later one's closest to the line of the accepted windows before it (its grid centred
    there); a window more than :data:`WINDOW_JUMP_S` from that line is inconsistent and left out. Returns ``t``,
    ``offset``, ``n`` (accepted windows), ``inconsistent`` (count) and ``line`` (offset, drift, ref) or None."""
    starts = [0]
    for i in range(1, f.size):
        if f[i] - f[starts[-1]] > window_s:
            starts.append(i)
    bounds = [*starts, f.size]
    t_acc, o_acc, n_acc, bad = [], [], [], 0
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        fw = f[a:b]
        if fw.size < MIN_WINDOW_EVENTS:
            continue
        tc = float(fw.mean())
        if not o_acc:  # the recording's start: the units were started together (the old rule; L670's twin)
            heads = _grid_heads(fw, w, 0.0, max_offset_s, step_s, tolerance_s)
            o = toward_zero(fw, w, float(heads[np.argmin(np.abs(heads))]), step_s, tolerance_s)
        else:
            lo, dr, ref = _line(np.array(t_acc), np.array(o_acc), np.array(n_acc), fit_drift, min_span_s)
            pred = lo + dr * (tc - ref)
            heads = _grid_heads(fw, w, pred, max_offset_s, step_s, tolerance_s)
            o = float(heads[np.argmin(np.abs(heads - pred))])
            if abs(o - pred) > WINDOW_JUMP_S:
                bad += 1
                continue
        t_acc.append(tc)
        o_acc.append(o)
        n_acc.append(fw.size)
    line = _line(np.array(t_acc), np.array(o_acc), np.array(n_acc), fit_drift, min_span_s) if t_acc else None
    return {"t": np.array(t_acc), "offset": np.array(o_acc), "n": np.array(n_acc), "inconsistent": bad,
            "line": line}


#: decision L670: a step twin's local optimum is searched over the twin +- this (s): the waist's step period is a
#: median, so the optimum one period away lies within a few grid steps of it
TWIN_SEARCH_S = 0.1


def toward_zero(f: np.ndarray, w: np.ndarray, o: float, step_s: float, tolerance_s: float) -> float:
    """Decision L670: ``o`` (the candidate closest to 0 of :func:`_grid_heads`) or, while its step twin one waist
    step period toward and past 0 (:func:`step_twin`) is closer to 0 and locks, that twin: its local optimum over
    :data:`TWIN_SEARCH_S`, refined as the estimate is (no drift), matching at least :data:`MIN_LOCK_PAIRS` and
    :data:`MIN_MATCHED_FRACTION` of the foot events ``f`` with a residual SD of at most
    :data:`LOCK_MAX_RESIDUAL_SD_S` (L183 / L446's bars for applying an estimate). A walk's periodic steps cannot
    tell the two apart (E228), so L161's prior, the units started together, decides."""
    period = step_period(w)
    while np.isfinite(period):
        twin = step_twin(o, period)
        if not abs(twin) < abs(o):
            break
        heads = _grid_heads(f, w, twin, TWIN_SEARCH_S, step_s, tolerance_s)
        cand = float(heads[np.argmin(np.abs(heads - twin))])
        c, _, _, pf, pw = _refine(f, w, cand, 0.0, float(f[0]), tolerance_s, False, np.inf)
        sd = float(np.std(pw - pf - c)) if pf.size > 1 else float("nan")
        if not (pf.size >= max(MIN_LOCK_PAIRS, MIN_MATCHED_FRACTION * f.size) and sd <= LOCK_MAX_RESIDUAL_SD_S
                and abs(cand) < abs(o)):
            break
        o = cand
    return o


def step_period(w: np.ndarray) -> float:
    """Steps decision 64: the waist's step period (s), the median interval between its events under 1.5 s (a walk's;
    the longer ones are pauses); NaN without such intervals."""
    d = np.diff(w)
    d = d[(d > 0) & (d < 1.5)]
    return float(np.median(d)) if d.size else float("nan")


def align_events(foot_times, waist_times, *, max_offset_s: float = 2.0, step_s: float = 0.005,
                 tolerance_s: float = 0.12, fit_drift: bool = True, min_span_s: float = 60.0,
                 window_s: float | None = None) -> dict:
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

    Steps decision 64 (an option, not adopted: decisions 64, 66): with ``window_s``, a recording longer than it is
    estimated window by window (:func:`window_offsets`): the offset closest to 0 at the recording's start, then
    followed along the recording across step periods, so a drift that moves the clock by more than half a step over
    hours is not read as the other foot's offset. Without it the windows of :data:`ALIGN_WINDOW_S` are still
    estimated, for decision L446's check of the one-offset line (:func:`untrusted_reason`).

    Limitation (docs/decisions/steps.md): a walk's step events are periodic, so offsets that differ by
    one step period (~0.5 s) match almost as well; bout starts and ends break the tie only when the
    waist and the foot see them differently. The estimate is reliable when the offset at the recording's start is
    below half a step period (decision 64) and for changes of the offset (relative alignment).

    Returns
    -------
    dict with ``offset_s`` (at ``ref_s``), ``drift`` (s/s), ``ref_s`` (foot clock, s), ``matched`` (pairs),
    ``foot_events``, ``residual_sd_s``, ``windows`` / ``windows_inconsistent`` (decision 64's windows with enough
    events, and those left out; 1 / 0 for one window), ``step_period_s`` (:func:`step_period`).
    """
    f = np.sort(np.asarray(foot_times, dtype=float))
    w = np.sort(np.asarray(waist_times, dtype=float))
    if f.size < 3 or w.size < 3:
        raise DataError(f"align_units: need at least 3 foot and 3 waist step events (got {f.size} and "
                        f"{w.size}); record a longer walk")
    wins = None
    span = ALIGN_WINDOW_S if window_s is None else window_s
    if np.ptp(f) > span:  # steps decision 64's windows: the estimate with window_s, L446's check always
        wins = window_offsets(f, w, window_s=span, max_offset_s=max_offset_s, step_s=step_s,
                              tolerance_s=tolerance_s, fit_drift=fit_drift, min_span_s=min_span_s)
    if window_s is not None and wins is not None and wins["line"] is not None:
        o, drift, ref = wins["line"]
    else:  # one window: the offset closest to 0 of the most matches (ties -> the smallest mean distance; L670)
        heads = _grid_heads(f, w, 0.0, max_offset_s, step_s, tolerance_s)
        o, drift, ref = toward_zero(f, w, float(heads[np.argmin(np.abs(heads))]), step_s, tolerance_s), 0.0, float(f[0])
    o, drift, ref, pairs_f, pairs_w = _refine(f, w, o, drift, ref, tolerance_s, fit_drift, min_span_s)
    resid = (pairs_w - pairs_f) - (o + drift * (pairs_f - ref)) if pairs_f.size else np.zeros(0)
    n_win = 1 if wins is None else int(wins["offset"].size + wins["inconsistent"])
    # decision L446: how far the accepted windows lie from the final line (s)
    far = (float(np.max(np.abs(wins["offset"] - (o + drift * (wins["t"] - ref)))))
           if wins is not None and wins["offset"].size else 0.0)
    return {"offset_s": o, "drift": drift, "ref_s": ref, "matched": int(pairs_f.size), "foot_events": int(f.size),
            "residual_sd_s": float(resid.std()) if resid.size > 1 else float("nan"), "windows": n_win,
            "windows_inconsistent": 0 if wins is None else int(wins["inconsistent"]),
            "window_residual_max_s": far, "step_period_s": step_period(w),
            # decision L457: how far the fitted drift moves the clock over the matched events (s); 0 for the windowed
            # option, which follows the clock from the recording's start (steps 64)
            "drift_span_s": (0.0 if wins is not None and window_s is not None and wins["line"] is not None
                             else abs(drift) * float(np.ptp(pairs_f)) if pairs_f.size else 0.0),
            # decision L446: the accepted windows' line (steps 64), named in the untrusted line as the likely clock
            "window_line": None if wins is None or wins["line"] is None else [float(v) for v in wins["line"]]}


#: decision L446: an estimate matching fewer than this fraction of the foot events cannot be trusted (bout ends cost at
#: most ~20 % of a walk's strides; under 60 % the line follows only part of the recording)
MIN_MATCHED_FRACTION = 0.6


def untrusted_reason(estimate: dict) -> str | None:
    """Decision L446: why :func:`align_events`' ``estimate`` cannot be trusted (too few foot events matched, walking
    windows inconsistent with the clock line, a window a quarter step from the final line), with its numbers; None
    when it can. Only estimates that locked (L183, :func:`offset_locked`) are asked."""
    matched, n = int(estimate.get("matched", 0)), int(estimate.get("foot_events", 0))
    wins, bad = int(estimate.get("windows", 1)), int(estimate.get("windows_inconsistent", 0))
    far = float(estimate.get("window_residual_max_s", 0.0))
    why = []
    if n and matched < MIN_MATCHED_FRACTION * n:
        why.append(f"{matched} of {n} foot events matched (at least {MIN_MATCHED_FRACTION:.0%} needed)")
    if bad > wins / 4:
        why.append(f"{bad} of {wins} walking windows jumped over {WINDOW_JUMP_S:g} s from the clock line (the "
                   "clock moved about half a step between walks)")
    if far > WINDOW_JUMP_S:
        why.append(f"a window lies {far:.2f} s from the fitted clock (over {WINDOW_JUMP_S:g} s)")
    if half_step_ambiguous(estimate):
        why.append(f"the fitted drift moves the clock {float(estimate['drift_span_s']):.2f} s over the walks, more "
                   f"than half the {float(estimate['step_period_s']):.2f} s step period, so the estimate may be a step "
                   "off (decision L457)")
    return "; ".join(why) or None


def half_step_ambiguous(estimate: dict) -> bool:
    """Decision L457: whether the one-offset estimate's clock line moves by more than half a step period over the
    matched events (``drift_span_s`` of :func:`align_events`): the line and the one a step beside it then both
    cross the half-step point, so which foot's events the waist steps are cannot be told from the start."""
    period = float(estimate.get("step_period_s", float("nan")))
    return bool(float(estimate.get("drift_span_s", 0.0)) > period / 2)  # NaN period: False


def candidate_offsets(estimate: dict) -> tuple[float, float]:
    """Decision L457: the estimate's ``--clock-offset`` (the waist clock at its 0, E111) and the one a step period
    beside it on the other side of 0 (at ``ref_s``): the two offsets a walk cannot tell apart."""
    o, drift, ref = (float(estimate[k]) for k in ("offset_s", "drift", "ref_s"))
    return o - drift * ref, step_twin(o, float(estimate["step_period_s"])) - drift * ref


def step_twin(offset_s: float, period_s: float) -> float:
    """Decisions L457 / E228: the offset one step period ``period_s`` from ``offset_s`` on the other side of 0, which a
    walk's periodic step events match as well as ``offset_s`` (NaN with a NaN period)."""
    return offset_s - period_s if offset_s > 0 else offset_s + period_s


def twin_of(offset_s: float, estimate: dict | None) -> float | None:
    """Decision E228: :func:`step_twin` of ``offset_s`` with ``estimate``'s step period when ``offset_s`` is over
    :data:`UNIT_OFFSET_WARN_S` (the estimate is the candidate closest to 0, L161; an offset that far from 0 says the
    units were not started together, so closest-to-0 no longer tells it from its twin); None otherwise, or without a
    step period."""
    period = float("nan") if estimate is None else float(estimate.get("step_period_s", float("nan")))
    if not (abs(offset_s) > UNIT_OFFSET_WARN_S and np.isfinite(period)):
        return None
    return step_twin(offset_s, period)


def twin_line(estimate: dict, option: str = "--align-units") -> str | None:
    """Decision E228: the line ``option`` adds when it applied ``estimate`` (locked and trusted) whose offset has a
    twin one step period away (:func:`twin_of`): which of the two is right cannot be told from the steps; None when it
    has none."""
    twin = twin_of(float(estimate["offset_s"]), estimate)
    if twin is None:
        return None
    a, b = candidate_offsets(estimate)
    ppm = f" --clock-drift-ppm {float(estimate['drift']) * 1e6:.0f}" if float(estimate["drift"]) else ""
    return (f"{option} moved the waist clock by the estimate, {float(estimate['offset_s']):+.3f} s; "
            f"{twin:+.3f} s, one {float(estimate['step_period_s']):.2f} s step period away, matches a walk's periodic "
            "steps as well, so the steps cannot tell which is right (the estimate is the one closer to 0, L161): if "
            f"the track is worse than without it, give the other by hand, --clock-offset {b:.3f}{ppm} instead of "
            f"{option} (--clock-offset {a:.3f}{ppm} is the one applied; decision E228)")


def untrusted_message(estimate: dict, option: str = "--align-units") -> str | None:
    """Decision L446: the line saying that ``estimate`` cannot be trusted and what to do (``option`` kept the clocks,
    or None for L161's check without it); None when it can be trusted."""
    why = untrusted_reason(estimate)
    if why is None:
        return None
    head = (f"{option} kept the unit clocks" if option else "the unit clocks could not be checked")
    period = float(estimate.get("step_period_s", float("nan")))
    line = estimate.get("window_line")
    hint = ""
    if line is not None and int(estimate.get("windows_inconsistent", 0)) <= int(estimate.get("windows", 1)) / 4:
        off0, drift, ref = line  # steps 64's windows followed from the recording's start: at the clock's 0 (E111)
        hint = (f"; the walking windows followed from the recording's start read --clock-offset "
                f"{off0 - drift * ref:.3f} --clock-drift-ppm {drift * 1e6:.0f} (right if the units were started "
                "within half a step of each other, steps decision 64)")
    if half_step_ambiguous(estimate):  # decision L457: the two candidates, same drift
        a, b = candidate_offsets(estimate)
        hint += (f"; the two candidates a step apart read --clock-offset {a:.3f} or {b:.3f} --clock-drift-ppm "
                 f"{float(estimate['drift']) * 1e6:.0f} (decision L457)")
    return (f"{head}: the clock estimate cannot be trusted ({why}; it read {float(estimate['offset_s']):+.2f} s, "
            f"drift {float(estimate['drift']) * 1e6:+.0f} ppm, with a {period:.2f} s step period, and offsets a step "
            "apart look alike, decision L446); if the clocks are offset, give them by hand: --clock-offset SECONDS "
            f"--clock-drift-ppm PPM (the waist clock at its 0 and its drift, decisions E111, B265){hint}")


def unit_offset_message(offset_s: float, drift: float, command: str = "pdrlearn track",
                        remedy=None, estimate: dict | None = None) -> str | None:
    """Decision L161: the warning line for an estimated offset (s) and drift (s/s) over :data:`UNIT_OFFSET_WARN_S`,
    else None. ``command``: the one whose ``--align-units`` the line names (``pdrlearn run``, decision L170);
    ``remedy``: another fix to name instead, a callable of the offset (the live Tracker's keyword, decision L177);
    ``estimate``: :func:`align_events`' dict, None when it is not locked (decision L183, :func:`offset_locked`).
    Decision E228: with an estimate, the line names both the offset and its twin one step period away
    (:func:`twin_of`) and the fix for each, since a walk's periodic steps cannot tell them apart."""
    if abs(offset_s) <= UNIT_OFFSET_WARN_S or (estimate is not None and not offset_locked(estimate)):
        return None
    twin = twin_of(offset_s, estimate)
    head = f"the waist unit's steps fall {offset_s:+.2f} s from the foot unit's"
    note = f"(drift {drift * 1e6:+.0f} ppm; over {UNIT_OFFSET_WARN_S:g} s warns, decision L161)"
    cause = ("the unit clocks are offset (a unit switched on later that counts from 0, or a drifting clock), and the "
             "waist heading is read at the foot's strides")
    if twin is None:
        fix = remedy(offset_s) if remedy is not None else f"`{command} --align-units`"
        return (f"{head} {note}: {cause}; align them with {fix} (an offset one step period from this one reads as "
                "this one, decision E228)")
    period = float(estimate["step_period_s"])
    if remedy is not None:
        fixes = remedy(offset_s), remedy(twin)
    else:  # E111's offsets at the waist clock's 0, with the drift (B265) when one was fitted
        ppm = f" --clock-drift-ppm {drift * 1e6:.0f}" if drift else ""
        at0 = drift * float(estimate.get("ref_s", 0.0))
        fixes = (f"`{command} --clock-offset {offset_s - at0:.3f}{ppm}`",
                 f"`{command} --clock-offset {twin - at0:.3f}{ppm}`")
    ahead = ("ahead of", "behind") if offset_s > 0 else ("behind", "ahead of")
    applies = "" if remedy is not None else f"; `{command} --align-units` applies the first, L162"
    return (f"{head}, or {twin:+.2f} s {note}: offsets one {period:.2f} s step period apart match a walk's periodic "
            f"steps alike, so the steps cannot tell which (decision E228); {cause}; align them with {fixes[0]} if "
            f"the waist clock is {ahead[0]} the foot's, or {fixes[1]} if it is {ahead[1]} it (stamp both units on "
            f"one clock to be sure{applies})")


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
