"""Decision L416: the step-time asymmetry of a walk recorded with a foot unit and a lower-back unit together.

The foot unit times one foot's initial contacts precisely; the lower back sees the contacts of both feet. Each
lower-back contact within :data:`LABEL_TOLERANCE_STEPS` of a step of a foot contact is the instrumented foot's,
the others the other foot's; the lower back's lag behind the foot (the median over the labelled own contacts) is
taken off the other foot's contacts, and the median phase of the other foot's contact inside the foot's strides
gives the two step times and :func:`pdrlearn.track.clinical.symmetry_index_pct` of them (L121's index).
"""

from __future__ import annotations

import logging

import numpy as np

#: decision L416: a lower-back contact within this fraction of a step (half the foot's median stride) of a foot
#: contact is that foot's: its own contacts scatter ~0.04 s (SD) about the foot's, the other foot's lie a step away
LABEL_TOLERANCE_STEPS = 0.25
#: decision L490: an index whose standard error (:func:`index_standard_error_pct`) is over this many points is given
#: with a note that it is uncertain (L493's gate withholding it, and L490's window centred on the lower back's lag,
#: were not adopted; L507 removed those options, commit d3ffb129 holds them)
UNCERTAIN_SE_POINTS = 3.0
#: decision L671: an index under this many standard errors (L490's) is within noise: its two-sided 95 % interval
#: reaches 0 (the normal quantile)
WITHIN_NOISE_SE = 1.96


def asymmetry_flags(pct: float, se: float) -> list[str]:
    """Decisions L671, L677: the words a step-time asymmetry index ``pct`` (%) with standard error ``se`` (points,
    L490) carries - "within noise" under :data:`WITHIN_NOISE_SE` standard errors, "uncertain: over 3 points" over
    :data:`UNCERTAIN_SE_POINTS`; the console's gait line and clinical.md (decision C190) say the same."""
    return ((["within noise"] if pct < WITHIN_NOISE_SE * se else [])
            + ([f"uncertain: over {UNCERTAIN_SE_POINTS:g} points"] if se > UNCERTAIN_SE_POINTS else []))


#: decision L416: a foot stride longer than this times the median stride (a stop, a missed contact) gives no phase
MAX_STRIDE_FACTOR = 1.5
#: decision L416: the fewest strides with one other-foot contact for an index (L123's minimum for a figure)
MIN_STRIDES = 10
#: decision L686: the foot's median step (s, half its median stride) from which the index's standard error carries
#: :data:`ASYMMETRY_BIAS_FRACTION` of the index (the slowest step of L416's validation users 8044-8055 is 0.598 s)
BIAS_STEP_S = 0.6
#: decision L686: the share of a slow walk's index the lower back may add to it (its contact ending the shorter step
#: is dated earlier; development users 14200-14219 at 0.7-0.8 s steps: 90th percentile 0.44 of the estimate)
ASYMMETRY_BIAS_FRACTION = 0.45
#: decision W532: the foot's shortest median step (s, half its median stride) with an index: under it (a child's
#: 0.34-0.41 s steps) the lower back's contacts read symmetric children 2.8-13 % (W531's users 14940-14959; the
#: upper end of docs/simulator.md's children, 0.36-0.45 s); a unit on each foot (``pdrlearn gait``) times them
MIN_STEP_S = 0.45
#: decision L416: the lower-back stream's lowest rate (Hz) for the index (its 20 Hz contacts failed on development
#: users 8040-8042)
LABELLED_MIN_RATE_HZ = 50.0


def label_contacts(foot_ic_s, waist_ic_s, *,
                   tolerance_steps: float = LABEL_TOLERANCE_STEPS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(foot, waist, own)``: the foot contacts and the lower-back contacts (finite, sorted, s) and (W,) bool, True
    for a lower-back contact within ``tolerance_steps`` x half the foot's median stride of a foot contact (decision
    L416). Fewer than 2 foot contacts: no contact is the foot's."""
    f = np.sort(np.asarray(foot_ic_s, dtype=float)[np.isfinite(np.asarray(foot_ic_s, dtype=float))])
    w = np.sort(np.asarray(waist_ic_s, dtype=float)[np.isfinite(np.asarray(waist_ic_s, dtype=float))])
    if len(f) < 2 or not len(w):
        return f, w, np.zeros(len(w), bool)
    step = float(np.median(np.diff(f))) / 2.0
    return f, w, np.abs(_offsets(f, w)) <= tolerance_steps * step


def _offsets(f: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(W,) each of ``w`` minus its nearest of the sorted ``f`` (at least 2), s."""
    j = np.clip(np.searchsorted(f, w), 1, len(f) - 1)
    return w - np.where(np.abs(w - f[j - 1]) <= np.abs(w - f[j]), f[j - 1], f[j])


def other_foot_phases(foot_ic_s, waist_ic_s, *, tolerance_steps: float = LABEL_TOLERANCE_STEPS) -> np.ndarray:
    """(S,) the phase (0-1) of the other foot's contact inside each of the foot's strides that holds exactly one
    (:func:`label_contacts`; the lower back's median lag behind the foot's own contacts taken off; strides over
    :data:`MAX_STRIDE_FACTOR` x the median left out); empty without an own contact."""
    return _phases_and_lags(foot_ic_s, waist_ic_s, tolerance_steps=tolerance_steps)[0]


def _phases_and_lags(foot_ic_s, waist_ic_s, *, tolerance_steps: float) -> tuple[np.ndarray, np.ndarray]:
    """``(phases, lags)``: :func:`other_foot_phases` and (O,) the own contacts' offsets from their foot contacts (s),
    whose median is the lag taken off (decision L677: its standard error counts too); both empty without an own
    contact or without another foot's."""
    f, w, own = label_contacts(foot_ic_s, waist_ic_s, tolerance_steps=tolerance_steps)
    if not own.any() or own.all():
        return np.zeros(0), np.zeros(0)
    j = np.clip(np.searchsorted(f, w[own]), 1, len(f) - 1)
    near = np.where(np.abs(w[own] - f[j - 1]) <= np.abs(w[own] - f[j]), j - 1, j)
    lags = w[own] - f[near]
    other = w[~own] - float(np.median(lags))
    k = np.searchsorted(f, other)
    ok = (k >= 1) & (k < len(f))
    other, k = other[ok], k[ok]
    stride = f[k] - f[k - 1]
    ok = stride <= MAX_STRIDE_FACTOR * float(np.median(np.diff(f)))
    other, k, stride = other[ok], k[ok], stride[ok]
    idx, counts = np.unique(k, return_counts=True)
    single = np.isin(k, idx[counts == 1])
    return ((other - f[k - 1]) / stride)[single], lags


def median_standard_error(x) -> float:
    """Decision L490: the standard error of the median of ``x``: 1.2533 x the robust SD (1.4826 x the median absolute
    deviation) / sqrt(n) (the median's asymptotic efficiency, 1.2533 = sqrt(pi / 2)); nan for fewer than 2 values."""
    x = np.asarray(x, dtype=float)
    if len(x) < 2:
        return float("nan")
    return float(1.2533 * 1.4826 * np.median(np.abs(x - np.median(x))) / np.sqrt(len(x)))


def index_standard_error_pct(phases, lags=None, stride_s: float | None = None) -> float:
    """Decision L490: the standard error (points) of :func:`labelled_step_asymmetry`'s index from the other foot's
    phases: the index is 200 |1 - 2 phi| (L121's symmetry index of phi T and (1 - phi) T), so 400 x the median
    phase's standard error (:func:`median_standard_error`); nan for fewer than 2 phases. Decision L677: with the own
    contacts' offsets ``lags`` (s, their median the lag taken off the other foot's) and the foot's median stride
    ``stride_s``, the lag's standard error / ``stride_s`` is added in quadrature (phi = (t_other - lag - t_ic) / T:
    the two medians come from different contacts)."""
    se_phi = median_standard_error(phases)
    if lags is not None and stride_s is not None and len(np.asarray(lags)) >= 2:
        se_phi = float(np.hypot(se_phi, median_standard_error(lags) / float(stride_s)))
    return 400.0 * se_phi


def labelled_step_asymmetry(foot_ic_s, waist_ic_s, *, tolerance_steps: float = LABEL_TOLERANCE_STEPS,
                            min_strides: int = MIN_STRIDES) -> dict:
    """Decision L416: ``{"step_time_asymmetry_pct", "n_strides", "step_time_s_instrumented", "step_time_s_other"}``
    of one foot's initial contacts ``foot_ic_s`` and the lower back's contacts of both feet ``waist_ic_s`` (s, one
    clock up to a constant offset under a quarter step). With the median phase phi of the other foot's contact
    (:func:`other_foot_phases`) and the foot's median stride T: the step onto the other foot phi T, onto the
    instrumented foot (1 - phi) T, and their symmetry index (Robinson et al. 1987, L121). None values with fewer
    than ``min_strides`` strides (and at least 2, which a standard error needs: ``standard_error_points``, decision
    L490, always given; decision L677: it counts the lower back's lag, :func:`index_standard_error_pct`; decision
    L686: with an index, ``bias_allowance_points`` (:func:`bias_allowance_points`) added in quadrature). Decision
    W532: None values too, and ``short_step_s`` the foot's median step, when that step is under :data:`MIN_STEP_S`."""
    from pdrlearn.track.clinical import symmetry_index_pct

    phases, lags = _phases_and_lags(foot_ic_s, waist_ic_s, tolerance_steps=tolerance_steps)
    f = np.sort(np.asarray(foot_ic_s, dtype=float)[np.isfinite(np.asarray(foot_ic_s, dtype=float))])
    stride = float(np.median(np.diff(f))) if len(f) >= 2 else float("nan")
    out = {"step_time_asymmetry_pct": None, "n_strides": int(len(phases)), "step_time_s_instrumented": None,
           "step_time_s_other": None,
           "standard_error_points": index_standard_error_pct(phases, lags, stride)}  # decisions L490, L677
    if len(phases) < max(min_strides, 2):
        return out
    if stride / 2.0 < MIN_STEP_S:  # decision W532: too short a step for the lower back's contacts
        out["short_step_s"] = stride / 2.0
        return out
    phi = float(np.median(phases))
    onto_other, onto_own = phi * stride, (1.0 - phi) * stride
    index = symmetry_index_pct(onto_own, onto_other)
    allowance = bias_allowance_points(index, stride)  # decision L686
    out.update(step_time_asymmetry_pct=index, step_time_s_instrumented=onto_own, step_time_s_other=onto_other,
               bias_allowance_points=allowance,
               standard_error_points=float(np.hypot(out["standard_error_points"], allowance)))
    return out


def bias_allowance_points(index_pct: float, stride_s: float) -> float:
    """Decision L686: the points a slow walk's index ``index_pct`` may read high by - :data:`ASYMMETRY_BIAS_FRACTION`
    of it when the foot's median step (half its median stride ``stride_s``) is at least :data:`BIAS_STEP_S`, else 0
    (the lower back dates the contact ending the shorter step earlier, which one foot unit cannot measure)."""
    if not (np.isfinite(index_pct) and np.isfinite(stride_s)) or stride_s / 2.0 < BIAS_STEP_S:
        return 0.0
    return float(ASYMMETRY_BIAS_FRACTION * abs(index_pct))


def _waist_ic_key(session) -> str:
    """Decision L427: a digest of everything ``waist-ic``'s contacts of ``session`` are computed from: the lower-back
    accelerometer's and gyroscope's timestamps and values, the session's axis frames and whether it infers them."""
    import hashlib

    h = hashlib.blake2b(digest_size=20)
    for name in ("wAccelerometer", "wGyroscope"):
        s = session.streams[name]
        for a in (s.t, s.values):
            a = np.ascontiguousarray(a)
            h.update(repr((name, a.shape, a.dtype.str)).encode())
            h.update(a.tobytes())
    h.update(repr((sorted(session.frames.items()), bool(getattr(session, "infer_frames", False)))).encode())
    return h.hexdigest()


class _WarningCount(logging.Handler):
    """Counts the ``pdrlearn`` logger's warnings while attached (nothing else: the records go on as before)."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.n = 0

    def emit(self, record) -> None:
        self.n += 1


def waist_ic_contacts(session) -> np.ndarray:
    """Decision L427: the lower back's contacts of both feet (``event_s``, s) of ``session`` by the ``waist-ic``
    detector (:class:`~pdrlearn.steps.waist_ic.WaistICStepDetector`, defaults), detected once per session object
    and lower-back data: kept on the session with :func:`_waist_ic_key`'s digest of the detector's inputs and
    returned (a copy) while the digest is the same, so a summary made again (``TrackResult.summary``, then
    :func:`pdrlearn.write_track`) does not run the detector again. A detection that logged a warning is not kept
    (the next one logs it again, as before)."""
    from pdrlearn.steps.waist_ic import WaistICStepDetector

    key = _waist_ic_key(session)
    kept = getattr(session, "_waist_ic_contacts", None)
    if kept is not None and kept[0] == key:
        return kept[1].copy()
    counter = _WarningCount()
    logger = logging.getLogger("pdrlearn")
    logger.addHandler(counter)
    try:
        events = WaistICStepDetector().detect(session)["event_s"].to_numpy(float)
    finally:
        logger.removeHandler(counter)
    if not counter.n:
        session._waist_ic_contacts = (key, events.copy())
    return events


#: decision L447: the words of the warnings that say the two units' clocks are offset (L161) or could not be checked
#: (L446); the cross measures of the two units are then left empty
CLOCK_WARNINGS = ("decision L161", "decision L446")


def clock_warning(warnings) -> str | None:
    """Decision L447: the first of ``warnings`` that says the unit clocks are offset or unknown, None without one."""
    return next((w for w in warnings or () if any(k in str(w) for k in CLOCK_WARNINGS)), None)


def track_asymmetry(session, steps, warnings=(), alignment: dict | None = None) -> dict:
    """Decision L416: the summary keys (``step_time_asymmetry_pct``, ``n_step_time_asymmetry_steps``,
    ``step_time_asymmetry_reason``) a foot track (steps with ``event_s``, every row ``unit`` foot) of ``session``
    takes from :func:`labelled_step_asymmetry` when the session holds the lower-back unit too (adopted by L416's
    rule; W413: no module switch); ``{}`` otherwise (the foot's "not observable" stays). The lower back's contacts:
    the waist-pendulum pipeline's offline IC detector (``waist-ic``, once per session's data: :func:`waist_ic_contacts`,
    L427); a lower-back stream under
    :data:`LABELLED_MIN_RATE_HZ` gives the reason instead of an index, and so do ``warnings`` (the track's) holding
    a clock warning (decision L447: :func:`clock_warning`). ``alignment``: the track's ``info["unit_alignment"]``;
    an estimate it applied (``source`` "estimated", ``--align-units``) moves the lower back's contacts onto the foot
    clock as it moved the track's waist streams (L447; a given clock moved the session itself before tracking)."""
    if (not len(steps) or "event_s" not in steps or "unit" not in steps
            or not (steps["unit"] == "foot").all() or not session.has("wAccelerometer", "wGyroscope")
            or np.isfinite(steps["event_s"].to_numpy(float)).sum() < 2):  # a streamed table without --contacts
        return {}
    if clock_warning(warnings) is not None:  # decision L447: the other foot's steps are labelled by the clocks
        return {"step_time_asymmetry_pct": None, "n_step_time_asymmetry_steps": 0, "step_time_asymmetry_reason": (
            "not given: the foot and lower-back unit clocks are offset or could not be checked (see the clock "
            "warning, decisions L161, L446), so the lower back's contacts cannot be labelled by the foot's; align "
            "the clocks (--align-units, or --clock-offset / --clock-drift-ppm) for the index (decision L447)")}
    rate = float(session.streams["wAccelerometer"].rate_hz or 0.0)
    if rate < LABELLED_MIN_RATE_HZ:
        return {"step_time_asymmetry_reason": (
            f"not given: the lower-back unit records at {rate:g} Hz, under the {LABELLED_MIN_RATE_HZ:g} Hz its "
            "contacts need to label the other foot's steps (decision L416); a unit on each foot times them "
            "(pdrlearn gait LEFT_DIR RIGHT_DIR)")}
    waist = waist_ic_contacts(session)  # decision L427: detected once per session's lower-back data
    if alignment and alignment.get("source") == "estimated":  # decision L447: --align-units' clock, as the track's
        from pdrlearn.kernels.align import to_foot_clock

        waist = to_foot_clock(waist, float(alignment["offset_s"]), float(alignment["drift"]),
                              float(alignment.get("ref_s", 0.0)))
    res = labelled_step_asymmetry(steps["event_s"].to_numpy(float), waist)
    if res.get("short_step_s") is not None:  # decision W532
        reason = short_step_reason(res["short_step_s"])
    elif res["step_time_asymmetry_pct"] is None:
        reason = (f"not given: {res['n_strides']} of the foot's strides hold one lower-back contact of the other "
                  f"foot, {MIN_STRIDES} needed (decision L416)")
    else:
        reason = ("the lower back's contacts labelled by the foot unit's (the other foot's step in each stride, "
                  f"median over {res['n_strides']} strides, standard error {res['standard_error_points']:.1f} points "
                  "counting the lower back's lag; decisions L416, L490, L677)")
        if res.get("bias_allowance_points"):  # decision L686: a slow asymmetric walk's index may read high
            reason += (f"; at steps of {BIAS_STEP_S:g} s or longer the lower back dates the contact ending the "
                       "shorter step earlier than the other, which pushes the two step times apart and one foot unit "
                       f"cannot measure: the index may read up to ~{100 * ASYMMETRY_BIAS_FRACTION:.0f} % of its value "
                       f"high (simulated limping walkers at 0.6-0.8 s steps), so the standard error counts "
                       f"{res['bias_allowance_points']:.1f} points for it (decision L686)")
        if res["standard_error_points"] > UNCERTAIN_SE_POINTS:  # decision L490: say it is loose
            reason += ("; uncertain: over 3 points, the lower back's contacts scatter too much about the foot's (a "
                       "child's short fast steps, a slow walker's short slow ones: trial T1 read 5-21 % on symmetric "
                       "children, 12 % on a slow walker), so a unit on each foot (pdrlearn gait LEFT_DIR RIGHT_DIR) "
                       "times it better; a longer walk helps a child's, not a slow walker's (decision L677)")
    out = {"step_time_asymmetry_pct": res["step_time_asymmetry_pct"],
           "n_step_time_asymmetry_steps": 2 * res["n_strides"], "step_time_asymmetry_reason": reason}
    if res["step_time_asymmetry_pct"] is not None:
        out.update(side_keys(res, session))
    return out


#: decision W532: how :func:`short_step_reason` begins (:func:`short_step_withheld` reads it)
SHORT_STEP_PREFIX = "not given: the foot's median step "


def short_step_reason(step_s: float) -> str:
    """Decision W532: ``step_time_asymmetry_reason`` of an index withheld at a foot's median step ``step_s`` (s) under
    :data:`MIN_STEP_S`; clinical.md's line (C190) and the console's gait line quote it."""
    return (f"{SHORT_STEP_PREFIX}{step_s:.3f} s is under {MIN_STEP_S:g} s, where the lower back dates "
            "the contacts too loosely to time the other foot's step (symmetric children read 2.8-13 %, decisions "
            "W531, W532); a unit on each foot times it: pdrlearn gait LEFT_DIR RIGHT_DIR")


def short_step_withheld(summary: dict) -> str | None:
    """Decision W532: the reason of a summary whose foot + lower-back index was withheld at a short step, the words
    after "not given: " (None otherwise)."""
    reason = summary.get("step_time_asymmetry_reason")
    if summary.get("step_time_asymmetry_pct") is None and isinstance(reason, str) and reason.startswith(
            SHORT_STEP_PREFIX):
        return reason[len("not given: "):]
    return None


def asymmetry_uncertain(pct, se) -> bool | None:
    """Decision C271: True when a step-time asymmetry index ``pct`` (%) with standard error ``se`` (points) carries
    one of :func:`asymmetry_flags`' words - within noise (under 1.96 standard errors: the standard error is
    comparable to the index) or uncertain (a standard error over 3 points); None without both numbers."""
    try:
        pct, se = float(pct), float(se)
    except (TypeError, ValueError):
        return None
    if not (np.isfinite(pct) and np.isfinite(se)):
        return None
    return bool(asymmetry_flags(pct, se))


def side_keys(res: dict, session) -> dict:
    """Decision L671: :func:`labelled_step_asymmetry`'s result ``res`` (an index given) as the summary's
    ``step_time_asymmetry_se_points`` (L490's standard error), ``step_time_asymmetry_uncertain``
    (:func:`asymmetry_uncertain`, decision C271) and, when ``session``'s meta.json names the
    instrumented foot (L260's keys), ``step_time_s_left`` / ``_right`` (the step landing on that foot:
    ``step_time_s_instrumented``, on the other ``step_time_s_other``, as W250's) and ``step_time_s_ratio`` = left /
    right; without the side those stay empty (a foot unit does not know which foot it is on)."""
    from pdrlearn.track.bilateral import session_foot

    out = {"step_time_asymmetry_se_points": float(res["standard_error_points"]),
           "step_time_asymmetry_uncertain": asymmetry_uncertain(res["step_time_asymmetry_pct"],
                                                                res["standard_error_points"])}  # decision C271
    meta = getattr(session, "meta", None)
    side = session_foot(meta if isinstance(meta, dict) else {})
    if side is not None:
        other = "left" if side == "right" else "right"
        out[f"step_time_s_{side}"] = float(res["step_time_s_instrumented"])
        out[f"step_time_s_{other}"] = float(res["step_time_s_other"])
        out["step_time_s_ratio"] = out["step_time_s_left"] / out["step_time_s_right"]
    return out
