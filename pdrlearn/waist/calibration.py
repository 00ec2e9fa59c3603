"""Per-user calibration of the waist pipelines from walks of known length (seed 000 sec. II-D,
seed 001 sec. 2.2.5, seed 003 sec. 3.2) and of the gyro bias from a 360-degree walk (seed 003 eq. 2)."""

from __future__ import annotations

import dataclasses
import logging
import re

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io import Session
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.evaluate import reference_bouts, steps_in_interval
from pdrlearn.waist.heading import TurnClassifier
from pdrlearn.waist.lengths import pause_scaled_message
from pdrlearn.waist.params import DEFAULT_K, TAU_K, WaistParams, resolve_params
from pdrlearn.waist.plausibility import (  # noqa: F401  (W99 moved to plausibility; its names stay importable here)
    GYRO_OVERCOUNT_CAUSE,
    MISSED_STEPS_CAUSE,
    STEP_COUNT_DISAGREE,
    STEP_COUNT_MARGIN_S,
    STEP_COUNT_MIN,
    calibration_gait,
    step_counts,
    steps_missed,
    turns_bias_message,
)
from pdrlearn.waist.pll_calibration import calibrated_here, recorded_options, without_recorded
from pdrlearn.waist.steplength import (
    CADENCE_LAW_STEADY,
    MIN_GAIN_STRIDES,
    PIVOT_FIT_ITERATIONS,
    CalibrationWalk,
    cadence_law_factor,
    fit_frequency,
    fit_pendulum,
    gain_standard_error,
    model_lengths,
    steady_steps,
    with_pivot_factors,
)

log = logging.getLogger(__name__)


def span_mask(session: Session, steps, span_s: tuple[float | None, float | None] | None) -> np.ndarray:
    """Decision W61: the steps (rows of ``steps``) whose both contacts lie inside ``span_s`` = ``(start, end)``
    seconds from the recording's start (either None = open; ``span_s`` None = every step)."""
    if span_s is None:
        return np.ones(len(steps), dtype=bool)
    t0 = session.t_start
    for name, v in zip(("--start", "--end"), span_s, strict=True):
        if v is not None and not np.isfinite(float(v)):
            raise DataError(f"calibrate: {name} {v}: give seconds from the start of {session.name} (a finite "
                            "number, e.g. --start 5 --end 11)")
    lo = -np.inf if span_s[0] is None else t0 + float(span_s[0])
    hi = np.inf if span_s[1] is None else t0 + float(span_s[1])
    if not lo < hi:
        raise DataError(f"calibrate: --start {span_s[0]} is not before --end {span_s[1]} (seconds from the "
                        f"start of {session.name})")
    return (steps["start_s"].to_numpy(float) >= lo) & (steps["end_s"].to_numpy(float) <= hi)


def calibration_walks(session: Session, pipeline: str, *, distance_m: float | None = None,
                      params=None, result=None, span_s: tuple[float | None, float | None] | None = None,
                      detector=None) -> list[CalibrationWalk]:
    """The walks of known length in ``session``.

    With ``distance_m`` the whole session is one walk (all detected steps, as ``track`` sums them: the
    distance from the first to the last detected contact, decision W21); otherwise each reference walking
    bout (``bouts.csv``) is one walk with the steps :func:`~pdrlearn.waist.evaluate.steps_in_interval`
    counts for it. ``result``: the session's :class:`~pdrlearn.track.base.TrackResult` if already computed.
    ``span_s`` (with ``distance_m``): ``(start, end)`` in seconds from the recording's start (either None =
    open): only the steps whose both contacts lie inside count (decision W61, ``calibrate --start/--end``).
    ``detector`` (decision W471): the contacts from this waist step detector (``track_waist``'s ``detector``).
    """
    from pdrlearn.track.waist import track_waist, without_heading_note

    p, _ = resolve_params(session, params)
    if result is None:
        with without_heading_note():  # W83's line is about a track's heading, which calibration does not use
            result = track_waist(session, pipeline=pipeline, params=p, detector=detector)
    res = result
    st = res.steps[res.steps["has_next"]]
    if "g_m" in st:  # the g the tracker multiplies by K, smoothed if it is (W56), so D = sum c (K g + F) (W21)
        g = st["g_m"].to_numpy(float)
    else:
        g = (K.pendulum_length(st["h_m"].to_numpy(float), p.leg_m, k=1.0, f=0.0) if "h_m" in st
             else np.zeros(len(st)))
    c = np.ones(len(st))
    if res.info.get("options", {}).get("turn_factor") and "dyaw_rad" in st:  # the same model as tracking (W19)
        c = K.turning_step_factor(st["dyaw_rad"].to_numpy(float))
    # W150: a pivot step keeps the chord of its turn; its factor depends on K, so the walk carries the rotations and
    # calibrate() refits with the factors of the fitted parameters (W21: the tracker's sum)
    dpsi = st["dyaw_rad"].to_numpy(float) if "pivot_factor" in st else None
    if "pause_factor" in st:  # W111: a pause keeps one period's length, in calibration as in tracking (W21)
        c = c * st["pause_factor"].to_numpy(float)
    if "merged" in st:  # W27: a fragment merged into its neighbour carries no length (nor an F term)
        c = np.where(st["merged"].to_numpy(bool), 0.0, c)
    f = st["frequency_hz"].to_numpy(float)
    steady = steady_steps(1.0 / res.steps["frequency_hz"].to_numpy(float), res.steps["has_next"].to_numpy(bool),
                          frequency_scale=p.frequency_scale())[res.steps["has_next"].to_numpy(bool)]  # W261
    paused = ((st["pause_factor"].to_numpy(float) < 1.0) if "pause_factor" in st else np.zeros(len(st), bool)) & (c > 0)
    return [CalibrationWalk(d, f[m], g[m], name, c[m], None if dpsi is None else dpsi[m], steady[m],
                            int((paused & m).sum()))  # W514
            for d, m, name in counted_walks(session, st, distance_m=distance_m, span_s=span_s)]


def counted_walks(session: Session, st, *, distance_m: float | None = None,
                  span_s: tuple[float | None, float | None] | None = None) -> list[tuple[float, np.ndarray, str]]:
    """The walks of known length among the steps ``st`` (a track's rows with a next contact) as ``(distance_m, mask
    over st, name)``: with ``distance_m`` one walk of every step (inside ``span_s``, decision W61: both contacts
    inside; W21: first to last detected contact), otherwise one per reference bout (``bouts.csv``) with the steps
    :func:`~pdrlearn.waist.evaluate.steps_in_interval` counts for it. The counting rules of both fits,
    :func:`calibration_walks` and a gain model's (:func:`fit_length_gain`, decision W460)."""
    if span_s is not None and distance_m is None:
        raise DataError("calibrate: --start/--end mark the stretch whose length --distance gives; pass --distance "
                        "METERS too (the reference bouts of bouts.csv carry their own times)")
    keep = np.ones(len(st), dtype=bool)
    if span_s is not None:  # W61: the measured stretch only
        keep = span_mask(session, st, span_s)
        if not keep.any():
            raise DataError(f"calibrate: no detected step of {session.name} lies inside --start/--end "
                            f"({span_s[0]}-{span_s[1]} s from its start; the recording covers "
                            f"{session.duration_s:.1f} s); widen the stretch")
    if distance_m is not None:
        if not (np.isfinite(distance_m) and distance_m > 0):
            raise DataError(f"calibrate: --distance {distance_m} must be a positive number of metres")
        # on the clock of --start/--end (s from the recording's start, W61), which a session's clock need not be
        t0, kept = session.t_start, st[keep]
        span = (f"{session.name}: contacts {kept['start_s'].min() - t0:.1f}-{kept['end_s'].max() - t0:.1f} s from "
                "the recording's start" if len(kept) else session.name)
        return [(float(distance_m), keep, span)]
    bouts = reference_bouts(session)
    if bouts is None:
        raise DataError(f"session '{session.name}' has no bouts.csv with reference lengths; "
                        "pass --distance METERS (the length walked in the recording)")
    walks = []
    for b in bouts.itertuples():
        m = steps_in_interval(st, b.start_s, b.end_s)
        if m.any():
            walks.append((float(b.length_m), m, f"{session.name}@{b.start_s:.1f}s"))
    return walks


def _cadence_factors(walk: CalibrationWalk, f_cal: float | None, p: WaistParams, law: bool | str) -> np.ndarray:
    """Decisions W240, W261: the tracker's ``cadence_law`` factor of each of ``walk``'s steps (W21: calibration sums
    what the tracker sums); with ``"steady"`` 1 on a step the tracker's :func:`steady_steps` did not call steady."""
    fac = cadence_law_factor(walk.f_hz, f_cal, p)
    if law == CADENCE_LAW_STEADY and walk.steady is not None:
        fac = np.where(walk.steady, fac, 1.0)
    return fac


def _fit_with_pivots(walks: list[CalibrationWalk], pipeline: str, base: WaistParams, out: WaistParams
                     ) -> tuple[list[CalibrationWalk], str]:
    """Fit ``out``'s step-length parameters (``K``, ``F`` or ``a``, ``b``) on ``walks`` and return the walks with the
    pivot factors of the fitted parameters and the fit's note. Without W150's ``dpsi`` one fit; with it, refit with
    the factors of the last fit until they no longer change (at most :data:`PIVOT_FIT_ITERATIONS`), so the tracker's
    sum over a calibration walk is its distance (W21)."""
    fit = fit_pendulum if pipeline == "waist-pendulum" else fit_frequency
    keys = ("k", "f_m") if pipeline == "waist-pendulum" else ("a_walk", "b_walk")
    cur = with_pivot_factors(walks, pipeline, base)
    prev = None
    for _ in range(PIVOT_FIT_ITERATIONS if any(w.dpsi is not None for w in walks) else 1):
        vals = fit(cur, base)
        for k, v in zip(keys, vals[:2], strict=True):
            setattr(out, k, v)
        cur = with_pivot_factors(walks, pipeline, out)
        # a capped step's factor follows the fitted gain, so the refits converge (geometrically) rather than repeat
        if prev is not None and np.allclose(vals[:2], prev, rtol=1e-13, atol=1e-13):
            break
        prev = vals[:2]
    return cur, vals[2]


MIN_STRIDES_GMM = 20  # strides needed to fit the straight/turning mixture (decision W14)
#: a gap this long (s) can hold a whole step: the IC detector's shortest step (decision W16); decision W34
GAP_NOTE_S = 0.3


#: decision W393: the note of a waist-pll calibration (trial T1 finding 5: calibrated on a 40 m walk, 57 steps, the
#: 50 m route read +11.3 % with 80 steps for 75, the pendulum +0.7 %)
PLL_EDGE_NOTE = ("waist-pll counts extra contacts at the edges of walking sequences (decision W345; pll_edge_lock "
                 "removes some, W372): this calibration counts them among its walk's steps and does not correct "
                 "them, so a walk with more starts, stops or turns than this one reads long (decision W393); "
                 "waist-pendulum has no such extras")


def gap_notes(session: Session, t0: float, t1: float) -> list[str]:
    """Notes on the accelerometer gaps of at least :data:`GAP_NOTE_S` inside ``[t0, t1]`` (s): the steps in
    them are interpolated (W34) and come out short, so a calibration on that walk overestimates K."""
    acc = session.streams.get("wAccelerometer")
    if acc is None:
        return []
    g = [x for x in acc.gaps() if x.duration_s >= GAP_NOTE_S and t0 <= x.start_s + x.duration_s and x.start_s <= t1]
    if not g:
        return []
    longest = max(g, key=lambda x: x.duration_s)
    return [f"{session.name}: {len(g)} gap(s) of dropped samples between its first and last step "
            f"({longest.duration_s:.2f} s at {longest.start_s:.1f} s); the steps there come out short and K high "
            "(decision W34): re-record the walk or calibrate on another one"]


#: decision W39: the plausible range of a walk's known distance over the distance the default (uncalibrated)
#: step-length model gives its steps -- for the pendulum with F = 0 that is K / DEFAULT_K (4.587/4 since W46;
#: K itself when W39 chose the range). Our calibrations span 0.83-1.22 as K (W39: the five mobgap Test5 walks
#: with bouts, both pipelines, and the simulated users), 0.72-1.06 as the ratio since W46; seed
#: 003 sec. 3.2's pendulum needs no gain at all (accuracy 100.96 %). Outside the range the walk's distance is
#: wrong (a --distance of a longer walk, a walk that was not all recorded) or the user unusual (a slow
#: shuffle, a walking aid); the warning names both (W78) and the calibration is kept.
PLAUSIBLE_GAIN = (0.6, 1.8)


def default_lengths(walk: CalibrationWalk, pipeline: str, base: WaistParams) -> float:
    """The distance the uncalibrated model ``base`` gives the steps of ``walk``, as the tracker sums it."""
    walk = with_pivot_factors([walk], pipeline, base)[0]  # W150
    return float(np.sum(walk.factors() * model_lengths(walk, pipeline, base)))


def check_gain(walks: list[CalibrationWalk], pipeline: str, base: WaistParams) -> list[str]:
    """Warnings for walks whose known distance is implausible for their steps (decision W39): the ratio of
    the distance to :func:`default_lengths` outside :data:`PLAUSIBLE_GAIN`. Raises :class:`DataError`
    when the calibration as a whole would need a gain <= 0 (no steps with length)."""
    tot_l = sum(default_lengths(w, pipeline, base) for w in walks)
    if not tot_l > 0:
        raise DataError(f"calibrate: the detected steps of {', '.join(w.name for w in walks)} carry no length "
                        "under the default model (no vertical motion / step frequency); check the recordings")
    lo, hi = PLAUSIBLE_GAIN
    out = []
    for w in walks:
        lw = default_lengths(w, pipeline, base)
        g = w.distance_m / lw if lw > 0 else float("inf")
        if not lo <= g <= hi:  # W78: a true slow shuffle / a damped trunk is as likely as a wrong --distance
            why = ("much shorter steps than the default model assumes for their trunk motion (a slow, shuffling "
                   "walker)" if g < lo else "a trunk that moves much less than the default model assumes for "
                   "their steps (a walking aid or rollator, a very smooth gait)")
            out.append(f"{w.name}: the known distance {w.distance_m:g} m is {g:.2f} x what the default model "
                       f"gives its {len(w.f_hz)} steps ({lw:.2f} m; usual {lo:g}-{hi:g}, decision W39). Either "
                       "--distance is wrong (give the length from the first to the last heel strike of this walk), "
                       f"or the walker takes {why}: then, if its step count is right (decision W99), this "
                       "calibration is what the walker needs (it is kept; decision W78)")
    return out


def step_count_check(session: Session, event_s: np.ndarray) -> str | None:
    """Decision W99: one warning when :func:`step_counts` disagree by more than :data:`STEP_COUNT_DISAGREE` of
    the pelvic-gyro count (the larger count at least :data:`STEP_COUNT_MIN`); None when they agree or cannot be
    compared."""
    counts = step_counts(session, event_s)
    if counts is None:
        return None
    n_w, n_g = counts
    if max(n_w, n_g) < STEP_COUNT_MIN or abs(n_w - n_g) <= STEP_COUNT_DISAGREE * n_g:
        return None
    why = (f"fewer contacts than pelvic-gyro steps: either {MISSED_STEPS_CAUSE}, {GYRO_OVERCOUNT_CAUSE}"  # W114, W554
           if steps_missed(counts)
           else "more contacts than steps: a very slow walker's phantom contacts, a walking aid's strikes")
    return (f"{session.name}: the waist step detector counted {n_w} contacts on this walk, the pelvic-gyro detector "
            f"{n_g} (more than {100 * STEP_COUNT_DISAGREE:.0f} % apart, decision W99): the step count is doubtful, and "
            f"with it K and the step count and cadence of every track calibrated with it ({why}); check with "
            "'pdrlearn steps DIR --detector pelvic-gyro' (and a foot unit if there is one) before relying on this "
            "calibration")


def fit_turn_classifier(mean_rates: np.ndarray) -> tuple[dict | None, str]:
    """Straight/turning GMM on |MRZ| of calibration strides (seed 003 sec. 3.3: fitted on one trial).

    Kept only when the walks contain turns the fit can see (decision W14): at least
    :data:`MIN_STRIDES_GMM` strides and a turning component with >= 5 % weight whose mean lies more than
    three straight standard deviations above the straight mean; otherwise the prior stays in force.
    """
    x = np.abs(np.asarray(mean_rates, dtype=float))
    if x.size < MIN_STRIDES_GMM:
        return None, f"turn classifier: prior kept ({x.size} strides < {MIN_STRIDES_GMM})"
    clf = TurnClassifier().fit(x)
    m, s, w = clf.means_, clf.sds_, clf.weights_
    if w[1] < 0.05 or m[1] - m[0] < 3 * s[0]:
        return None, "turn classifier: prior kept (the calibration walks show no separate turning strides)"
    return clf.to_dict(), (f"turn classifier fitted on {x.size} strides: straight {m[0]:.3f}+-{s[0]:.3f}, "
                           f"turning {m[1]:.3f}+-{s[1]:.3f} rad/s")


def _finite(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def shrink_pendulum_gain(walks: list[CalibrationWalk], k_cal: float, f_m: float, how: str, *, shrink: bool = False,
                         tau: float | None = None) -> tuple[float, dict, str]:
    """The calibrated gain ``k_cal`` and, with ``shrink``, the same shrunk toward the population gain
    :data:`~pdrlearn.waist.params.DEFAULT_K` by precision weighting (decision W48, measured and not the default):
    its standard error from the walks' own per-stride scatter
    (:func:`~pdrlearn.waist.steplength.gain_standard_error`), the between-subject spread ``tau`` (default
    :data:`~pdrlearn.waist.params.TAU_K`). Returns ``(K, record, note)``; ``record`` goes to
    ``WaistParams.k_shrinkage`` (``k_cal``, ``se``, ``n_strides``, ``k0``, ``tau``, ``k_shrunk`` = what shrinkage
    gives, ``k`` = the K kept, ``applied``). ``k_cal`` is kept when ``shrink`` is off, when K and F were fitted
    jointly or F is not 0 (the prior is on the F = 0 model's K), or when the walks have fewer than
    :data:`~pdrlearn.waist.steplength.MIN_GAIN_STRIDES` strides (no standard error); the note says which."""
    tau = TAU_K if tau is None else float(tau)
    se, n = gain_standard_error(walks, f_m)
    rec = {"k_cal": float(k_cal), "se": _finite(se), "n_strides": n, "k0": DEFAULT_K, "tau": _finite(tau),
           "k_shrunk": None, "k": float(k_cal), "applied": False}
    sd = f" +- {se:.4f} (se over {n} strides)" if np.isfinite(se) else ""
    if not how.startswith("K only") or f_m != 0:
        why = "K and F fitted (walks of several speeds); the prior is on K with F = 0"
    elif not np.isfinite(se):
        why = (f"{n} stride(s) < {MIN_GAIN_STRIDES}: no standard error of K from the walk; "
               "calibrate on a longer walk")
    elif not (np.isfinite(tau) and tau > 0):
        why = f"no between-subject spread tau ({tau})"
    else:
        ks = K.shrink_gain(k_cal, se, DEFAULT_K, tau)
        rec["k_shrunk"] = ks
        w = 100 * tau * tau / (tau * tau + se * se)
        if not shrink:
            return float(k_cal), rec, (f"K {k_cal:.4f}{sd} as calibrated; --shrink would give {ks:.4f} ({w:.0f} % "
                                       f"the walk's, {100 - w:.0f} % the population K0 = {DEFAULT_K:.4f}, tau "
                                       f"{tau:.4f}; decision W48: not the default)")
        rec.update(k=ks, applied=True)
        return ks, rec, (f"K shrunk toward the population K0 = {DEFAULT_K:.4f} (--shrink, decision W48): calibrated "
                         f"{k_cal:.4f}{sd}, tau {tau:.4f} -> K = {ks:.4f} ({w:.0f} % the walk's)")
    return float(k_cal), rec, f"K {k_cal:.4f}{sd} as calibrated, not shrunk toward K0 = {DEFAULT_K:.4f}: {why}"


#: decision W169: fewer calibration steps than this and ``calibrate`` warns that the gain varies from walk to walk
MIN_CALIBRATION_STEPS = 20

#: the note of :func:`~pdrlearn.waist.params.default_params` each pipeline's fit replaces (a regex from the start)
_FITTED_NOTE = {"waist-pendulum": r"K = ", "waist-pll": r"height \S+ m -> SL = "}


def belt_distance(session: Session, steps, span_s=None) -> tuple[float, str]:
    """Decision W378: a treadmill walk's calibration distance (m) - meta.json ``belt_speed_mps`` (L321) x the span of
    the lower back's counted contacts ``steps`` (rows with a next contact) inside ``span_s`` (W61), first to last,
    as ``--distance`` counts them (W21) - and its note. One line (B366) without the key or without a step."""
    from pdrlearn.track.belt import BELT_KEY, belt_value

    where = str(session.folder or session.name)
    v = belt_value(session.meta, where)
    if v is None:
        raise DataError(f"calibrate: --belt needs meta.json {BELT_KEY} in {where} (the treadmill's belt speed, m/s); "
                        "declare it, or give the walked length with --distance (decisions W378, B366)")
    st = steps[span_mask(session, steps, span_s)] if span_s is not None else steps
    if not len(st):
        raise DataError(f"calibrate: --belt: no detected step of {session.name} lies inside --start/--end; widen the "
                        "stretch (decisions W378, B366)")
    t0, t1 = float(st["start_s"].min()), float(st["end_s"].max())
    d = v * (t1 - t0)
    return d, (f"--belt: {session.name} {v:.2f} m/s x {t1 - t0:.1f} s of contacts ({t0 - session.t_start:.1f}-"
               f"{t1 - session.t_start:.1f} s) = {d:.2f} m of belt (decision W378)")


#: decision W460: a gain model's fit stops when a refit changes the gain by less than this fraction (one refit when
#: the tracked sum is linear in the gain; W150's pivot cap is not, and converges geometrically), at most
#: :data:`GAIN_FIT_ITERATIONS` tracks of every walk
GAIN_FIT_RTOL = 1e-9
GAIN_FIT_ITERATIONS = 8


def gain_model(spec: str):
    """Decision W460: the step-length model ``spec`` names (``"NAME"`` or ``"NAME:key=value,..."``) and its settings,
    checked for ``calibrate --length-model``: it declares a linear gain
    (:attr:`~pdrlearn.waist.lengths.StepLengthModel.gain_param`) and ``spec`` does not set it."""
    from pdrlearn.plugins import parse_spec
    from pdrlearn.waist.lengths import get_step_length

    model = get_step_length(spec)
    name, own = parse_spec(spec, "step-length model")
    if model.gain_param is None:
        own_model = name in ("pendulum", "frequency")
        raise DataError(f"calibrate: --length-model {name} " + (
            "is a pipeline's own model: calibrate fits it without --length-model (--pipeline waist-pendulum: "
            "pendulum, waist-pll: frequency)" if own_model else
            "declares no linear gain (gain_param) for calibrate to fit; set gain_param = 'SETTING' in its class when "
            "its lengths are proportional to that setting (docs/extending.md), or set its settings by hand") +
            " (decision W460)")
    if model.gain_param in own:
        raise DataError(f"calibrate: --length-model {spec} sets the gain {model.gain_param} that calibrate fits; "
                        f"drop {model.gain_param}= (decision W460)")
    return model, name, own


def calibration_detector(detector):
    """Decision W471 (``calibrate --detector``): the waist :class:`~pdrlearn.steps.StepDetector` ``detector`` names
    (a registered name, ``NAME:key=value,...`` or an instance; None: the pipeline's own), checked as ``track
    --detector`` checks it (:func:`pdrlearn.track.waist.waist_detector`); a foot detector is one line saying what
    calibrate fits."""
    if detector is None:
        return None
    from pdrlearn.steps import get_detector
    from pdrlearn.track.waist import waist_detector

    det = get_detector(detector) if isinstance(detector, str) else detector
    if getattr(det, "unit", None) == "foot":
        raise DataError(f"calibrate: --detector {getattr(det, 'name', detector)} detects the foot's strides; calibrate "
                        "fits the lower-back step length on a waist detector's contacts: choose one with unit 'waist' "
                        "(pelvic-gyro, pll, waist-ic or a plug-in) -- the foot pipeline (plasys) takes no calibrate "
                        "file (decisions L26, W471)")
    return waist_detector(det, False)


def fit_length_gain(sessions: list[Session], pipeline: str, spec: str, params: WaistParams,
                    distances: list[float | None], spans: list, detector=None) -> tuple[float, str]:
    """Decision W460: the gain of the gain model ``spec`` (:func:`gain_model`) that makes the tracker's sum over the
    walks of known length their distance (``D = k sum(l_1)``, the pendulum's K-only fit, seed 003 eq. 1 with F = 0:
    K = sum D / sum g): each session tracked (``track_waist`` on ``pipeline`` with ``params``) with the model at gain
    ``k``, its steps counted as :func:`counted_walks` counts them (``distances`` and ``spans``: one per session; W21,
    W61, bouts) and ``k`` refitted as ``k sum D / sum l_k`` until it changes by less than :data:`GAIN_FIT_RTOL`;
    ``detector`` (decision W471): on that waist detector's contacts. Returns ``(k, note)``."""
    from pdrlearn.plugins import spec_text
    from pdrlearn.track.waist import track_waist, without_heading_note

    model, name, own = gain_model(spec)
    gain, k = model.gain_param, 1.0
    for i in range(GAIN_FIT_ITERATIONS):
        total_d = total_l = 0.0
        n_walks = n_steps = 0
        for s, d, span in zip(sessions, distances, spans, strict=True):
            with without_heading_note():  # W83's line, the uncalibrated gain's own lines (W455)
                res = track_waist(s, pipeline=pipeline, params=params, length_model=spec_text(name, {**own, gain: k}),
                                  detector=detector)
            st = res.steps[res.steps["has_next"]]
            lengths = st["length_m"].to_numpy(float)
            for dist, m, _ in counted_walks(s, st, distance_m=d, span_s=span):
                total_d, total_l = total_d + dist, total_l + float(lengths[m].sum())
                n_walks, n_steps = n_walks + 1, n_steps + int(m.sum())
        if not total_l > 0:
            raise DataError(f"calibrate: the counted steps carry no length under {name} at {gain}={k:g}; check the "
                            "recordings and the model's settings (decision W460)")
        new = k * total_d / total_l
        if abs(new - k) <= GAIN_FIT_RTOL * new:
            return new, (f"{name} gain {gain} = {new:.4f} on {n_walks} walk(s), {n_steps} steps, {total_d:.2f} m: the "
                         f"tracked sum at this gain is the known distance (decision W460; {i + 1} track(s) of each "
                         "walk)")
        k = new
    return k, (f"{name} gain {gain} = {k:.4f}: the refits did not settle in {GAIN_FIT_ITERATIONS} tracks of each walk "
               "(decision W460); check the tracked sum")


def fast_gait_line(gait: dict | None, meta: dict | None, pipeline: str) -> str | None:
    """Decision W617: ``track``'s walking-range line (L95, leg-scaled by L148: :func:`pdrlearn.track.gait.
    gait_range_warning`) on the calibration walks' gait (:func:`calibration_gait`: their median cadence and the known
    distance over the counted steps' time), when it lies above the range (running, or short fast steps); None inside
    or below it (a slow walker's 10 m walk test is what calibrate is for)."""
    from pdrlearn.track.gait import gait_range_warning, leg_length, session_range_side

    if not gait:
        return None
    summary = {"median_cadence_spm": gait.get("median_cadence_spm"), "gait_speed_mps": gait.get("speed_mps"),
               **leg_length(meta), "pipeline": pipeline, "info": {"pipeline": pipeline, "params_source": "calibrated"}}
    if session_range_side(summary) != "fast":
        return None
    return "the calibration walks' " + gait_range_warning(summary, consequence=(
        "the step length is fitted on this gait, where the waist step-length models are not validated, and does not "
        "carry over to walking: calibrate on a walk of known length at the walker's walking pace (decision W617)"))


def calibrate(sessions: list[Session], pipeline: str, *, distances: list[float] | None = None,
              turns: float | None = None, fit_turns: bool = False, params=None, shrink: bool = False,
              tau_k: float | None = None, spans: list[tuple[float | None, float | None]] | None = None,
              belt: bool = False, length_model: str | None = None, detector=None) -> WaistParams:
    """Fit the step-length parameters of ``pipeline`` (with ``turns``, the gyro bias; with ``fit_turns``,
    the straight/turning mixture, decision W14).

    Parameters
    ----------
    sessions : calibration recordings of one user
    distances : known length (m) of each session; ``None`` -> the sessions' reference bouts
    turns : signed number of full turns (+ = left) walked in each session, for the bias (seed 003 eq. 2)
    shrink : waist-pendulum: shrink the calibrated K toward the population K by its standard error (decision
        W48: measured, not the default); ``tau_k`` the between-subject spread (default
        :data:`~pdrlearn.waist.params.TAU_K`). K's standard error is recorded in ``k_shrinkage`` either way.
    spans : with ``distances``: per session (or one for all) the ``(start, end)`` seconds from the recording's
        start whose steps the distance covers (decision W61); None = every detected step.
    belt : decision W378 (``calibrate --belt``): each session is a treadmill walk (meta.json ``belt_speed_mps``,
        L321) and its distance the belt speed x the span of its counted contacts (first to last, inside ``spans``),
        the belt distance the walker covered between them; not with ``distances``.
    length_model : decision W460 (``calibrate --length-model``): also fit this gain model's gain on the same walks
        (:func:`fit_length_gain`), kept in ``length_models``.
    detector : decision W471 (``calibrate --detector``): the walks' contacts from this waist step detector (a
        registered name, ``NAME:key=value,...`` or a :class:`~pdrlearn.steps.StepDetector` with unit "waist") instead
        of the pipeline's own, for both fits; recorded in ``detector`` (``track`` says when it tracks with another).
    """
    if not sessions:
        raise DataError("calibrate: give at least one session folder")
    if length_model is not None:
        gain_model(length_model)  # W460: one line before any session is tracked
    from pdrlearn.track.waist import detector_spec

    det = calibration_detector(detector)  # decision W471: one line before any session is tracked
    if (shrink or tau_k is not None) and pipeline != "waist-pendulum":  # W48: it would be ignored
        raise DataError(f"calibrate: --shrink shrinks the pendulum gain K (decision W48), which {pipeline} does not "
                        "have; calibrate --pipeline waist-pendulum, or drop --shrink")
    if distances is not None and len(distances) not in (1, len(sessions)):
        raise DataError(f"calibrate: {len(distances)} --distance values for {len(sessions)} sessions; "
                        "give one per session")
    if spans is not None and len(spans) not in (1, len(sessions)):
        raise DataError(f"calibrate: {len(spans)} --start/--end stretches for {len(sessions)} sessions; "
                        "give one per session or one for all")
    from pdrlearn.track.units import keep_units
    from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist, without_heading_note

    base, _ = resolve_params(sessions[0], params)
    if det is None and calibrated_here(base, pipeline) and (base.options or {}).get("pll_edge_lock") is None:
        # decision W369: re-calibrating from a PARAMS.json that records none counts with today's default, silently
        base = dataclasses.replace(base, options=recorded_options(base.options, pipeline,
                                                                  OPTION_DEFAULTS["pll_edge_lock"]))
    walks: list[CalibrationWalk] = []
    rates = []
    notes_gap: list[str] = []
    notes_count: list[str] = []
    cadence_law: bool | str = False  # decision W240: the tracks' option, read from the calibration walks' own tracks
    edge_lock = None  # decision W369: the pll_edge_lock the walks' waist-pll tracks counted their contacts with
    pause_steps: bool | str = OPTION_DEFAULTS["pause_steps"]  # W514: the value the walks' tracks shortened steps by
    if belt and distances is not None:
        raise DataError("calibrate: --belt takes each walk's distance from meta.json belt_speed_mps x its contact "
                        "span; give --belt or --distance, not both (decision W378)")
    belt_notes: list[str] = []
    walk_distances: list[float | None] = []  # W460: each session's distance (given or the belt's), for a gain fit
    for i, s in enumerate(sessions):
        d = None if distances is None else distances[i if len(distances) > 1 else 0]
        with without_heading_note():  # W83: calibration does not use the heading
            # decision C199: the lower back alone, as `track --units waist` (W547): a foot unit the waist pipelines do
            # not track changes no calibration step (T1 F2: W336's veto read a race walker's foot as at rest)
            waist = keep_units(s, ("waist",)) if s.placement_streams("foot") else s
            res = track_waist(waist, pipeline=pipeline, params=base, detector=det)
        cadence_law = cadence_law or res.info.get("options", {}).get("cadence_law") or False  # W261: its value
        edge_lock = res.info.get("options", {}).get("pll_edge_lock", edge_lock)  # W369: one value (base's options)
        pause_steps = res.info.get("options", {}).get("pause_steps", pause_steps)  # W514: one value (base's options)
        if not res.steps["has_next"].any():  # W61: a standing-only recording, not a model failure
            raise DataError(f"calibrate: 0 steps detected in {s.folder or s.name}; calibrate needs a walk of known "
                            "length (give a recording of walking, with --distance or bouts.csv)")
        span = None if spans is None else spans[i if len(spans) > 1 else 0]
        if belt:  # decision W378: the belt distance between the first and the last counted contact
            d, note = belt_distance(s, res.steps[res.steps["has_next"]], span)
            belt_notes.append(note)
        walk_distances.append(d)
        walks += calibration_walks(s, pipeline, distance_m=d, params=base, result=res, span_s=span, detector=det)
        if d is not None:  # decision W99: cross-check the walk's contact count with the pelvic gyro
            counted = res.steps[res.steps["has_next"]]
            counted = counted[span_mask(s, counted, span)]  # the steps the walk counts (W21, W61)
            note = step_count_check(s, np.unique(np.concatenate([counted["start_s"].to_numpy(float),
                                                                 counted["end_s"].to_numpy(float)])))
            if note:
                notes_count.append(note)
        st = res.steps
        if len(st):  # decision W34: say when a calibration walk lost samples
            notes_gap += gap_notes(s, float(st["start_s"].min()), float(st["end_s"].max()))
        r = res.steps["mean_rate_rps"].to_numpy(float)
        rates.append(r[np.isfinite(r)])
    out = WaistParams(**{k: v for k, v in base.to_dict().items() if k != "schema"})
    # the starting values' notes, less the default the fit replaces (a calibrated K is not the population K, a
    # fitted walking line not the height's)
    replaced_note = _FITTED_NOTE.get(pipeline)
    out.notes = [n for n in base.notes if not (replaced_note and re.match(replaced_note, n))]
    out.k_shrinkage = None
    # decision W87: the rate the step length is calibrated at (the calibrated factor depends on it)
    out.rate_hz = round(float(np.median([s["wAccelerometer"].rate_hz for s in sessions if s.has("wAccelerometer")]
                                        or [float("nan")])), 4)
    total = sum(w.distance_m for w in walks)
    n_steps = sum(len(w.f_hz) for w in walks)
    # decision W140: the gait the step length is calibrated on (a track of another cadence warns)
    out.gait = calibration_gait(np.concatenate([w.f_hz for w in walks]) if walks else np.zeros(0), total,
                                [w.f_hz for w in walks])  # decision W211: each walk's cadence, the range
    if cadence_law and pipeline == "waist-pendulum":  # W240: the tracker's cadence factor about these walks' cadence
        f_cal = (out.gait or {}).get("median_cadence_spm")
        f_cal = None if f_cal is None else float(f_cal) / 60.0  # as calibration_cadence_hz reads it back
        walks = [dataclasses.replace(w, c=w.factors() * _cadence_factors(w, f_cal, out, cadence_law)) for w in walks]
    if pipeline not in ("waist-pendulum", "waist-pll"):
        raise DataError(f"calibrate: unknown pipeline '{pipeline}'; choose waist-pll or waist-pendulum")
    implausible = check_gain(walks, pipeline, base)  # decision W39
    shrunk = None
    fitted, how = _fit_with_pivots(walks, pipeline, base, out)  # W150: the walks with the fitted pivot factors
    if pipeline == "waist-pendulum":
        out.k, out.k_shrinkage, shrunk = shrink_pendulum_gain(fitted, out.k, out.f_m, how, shrink=shrink, tau=tau_k)
    running = fast_gait_line(out.gait, sessions[0].meta, pipeline)  # decision W617: track's L95 line, the fast side
    for n in implausible + notes_count + ([running] if running else []):
        log.warning("calibrate: %s", n)
    out.notes += [running] if running else []
    out.notes += belt_notes  # decision W378
    if distances is not None:  # decision W21: the known length must span the counted steps
        out.notes += [f"--distance {w.distance_m:g} m counted over {len(w.f_hz)} steps, {w.name} (give the "
                      "length from the first to the last heel strike)" for w in walks]
    out.notes.append(f"{pipeline} step length calibrated on {len(walks)} walk(s), {n_steps} steps, "
                     f"{total:.2f} m: {how}")
    n_paused = sum(w.paused for w in walks)  # decision W514: the walk's steps the tracker shortened as stands
    if pipeline == "waist-pendulum":
        out.notes.append(f"{n_paused} of the {n_steps} steps shortened as pauses / stands (pause_factor < 1, "
                         "decisions W111, W134, W514); the fit sums them as the track does (W21)")
    pause_line = pause_scaled_message(n_paused, n_steps, pause_steps)  # W514: the option the tracks ran with
    if pause_line:
        log.warning("calibrate: %s", pause_line)
    if shrunk is not None:
        out.notes.append(shrunk)
    if n_steps < MIN_CALIBRATION_STEPS:  # decision W169: a short walk's gain varies from walk to walk
        short = (f"calibrated on {n_steps} steps (< {MIN_CALIBRATION_STEPS}): a gain from so short a walk varies "
                 "from walk to walk by more than the defaults' error on straight walks (decision W169: HA001's two "
                 "8-step Test5 walks give K 1.2194 and 1.1326); calibrate on 20 steps or more (several walks), or "
                 "use --shrink")
        log.warning("calibrate: %s", short)
        out.notes.append(short)
    for n in notes_gap:
        log.info("calibrate: %s", n)
    out.notes += notes_gap + implausible + notes_count
    if pipeline == "waist-pll":  # decision W393: the bout-edge extras are fitted into the length, not corrected
        out.notes.append(PLL_EDGE_NOTE)
    if length_model is not None:  # decision W460: the gain model's gain on the same walks, the same counted steps
        model, name, _ = gain_model(length_model)
        k, note = fit_length_gain(sessions, pipeline, length_model, base, walk_distances,
                                  [None if spans is None else spans[i if len(spans) > 1 else 0]
                                   for i in range(len(sessions))], detector=det)
        out.length_models = {**(out.length_models or {}), name: {model.gain_param: k}}
        out.notes.append(note)
    if turns is not None:
        from pdrlearn.waist.ahrs import waist_imu

        biases, walked = [], []
        for s in sessions:
            imu = waist_imu(s)
            biases.append(K.gyro_bias_360(imu.t, imu.w_z, turns=turns))
            walked.append(turns + biases[-1] * float(imu.t[-1] - imu.t[0]) / (2 * np.pi))  # int w dt / 2 pi
        out.gyro_bias_rps = float(np.mean(biases))
        out.notes.append(f"gyro bias {out.gyro_bias_rps:.5f} rad/s from {len(sessions)} walk(s) of "
                         f"{turns:+g} turn(s) (seed 003 eq. 2)")
        odd = turns_bias_message(walked, turns, out.gyro_bias_rps)  # decision C262
        if odd:
            log.warning("calibrate: %s", odd)
            out.notes.append(odd)
    if fit_turns:
        gmm, how = fit_turn_classifier(np.concatenate(rates) if rates else np.zeros(0))
        if gmm is not None:
            out.turn_gmm = gmm
        out.notes.append(how)
    out.source = "calibrated"
    out.pipeline = pipeline
    out.detector = detector_spec(det)  # decision W471: the contacts the step length was fitted on (None: its own)
    if det is not None:
        out.notes.append(f"the walks' contacts from --detector {out.detector} (decision W471: track with it)")
    # decision W484: the count's pll_edge_lock (W369) only when the contacts are the PLL's own; on another
    # detector's, none (not even the one an earlier waist-pll calibration of base recorded)
    out.options = (recorded_options(out.options, pipeline, edge_lock) if det is None
                   else without_recorded(out.options, base))
    log.info("calibrated %s: %s", pipeline, out.notes[-1])
    return out
