"""Per-stride horizontal position uncertainty of a track: ``pos_sigma_m`` (decision L128).

The error model is :func:`pdrlearn.kernels.position_sigma.position_covariance`; this module picks its parameters
for the pipeline and heading that made the track and writes the 1-sigma radius into the trajectory. The
parameters were fitted (maximum likelihood) on the true position errors of simulated users 900-905, a 4-loop
route of ~530 m with turns both ways, 2 storeys up and down a loop, backward strides and stops
(``experiments/position_sigma.py fit``, decision L128). Checked on fresh users 660-679 (L129): ``plasys-fused``
calibrated (98.2 % of the strides, 17/20 final positions within 2 sigma); ``waist`` calibrated (98.3 %, 20/20;
waist-pendulum). ``plasys-streaming`` and ``plasys-foot`` were too large (99.2 % and 100 %) and were refitted
on users 1160-1179 (L150), then tested on users 1180-1199 (L151): calibrated (94.8 % and 96.5 %, 20/20 each).
``plasys-foot-streaming`` (streamed foot-only): the refit failed (89.5 %); it keeps L128's ``plasys-foot``
constants, uncalibrated, too large (100 %, 20/20). It is no guarantee: magnetic disturbances,
map constraints, real sensors worse than the simulator's and a walker other than the simulator's are outside it.
A row whose position was held across a foot dropout (``gap_s`` > 0, no length) adds the displacement it missed,
radius^2 + (speed x gap)^2, kept by every later row (decision E127), for every regime. Decision L335: a
``plasys-fused`` track adds its own compass check's median angle as the extent heading error (marches of 0.8-4 km).
Decision L333: every radius is cut so its 2-sigma circle never exceeds s + |D| + l, the one that holds the true
position when the track's distance walked s is not under the true one (decision L342).
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.kernels.position_sigma import (  # noqa: F401 (SIGMA_PARAMS, reach_bound, missed_walk: E352 moved
    SIGMA_PARAMS,  # them to the kernel for the live tracker; their names stay here)
    missed_walk,
    reach_bound,
    rest_clock,
    stride_radius,
)
from pdrlearn.kernels.rests import between_rows

log = logging.getLogger(__name__)

#: decision L237: the candidate's per-axis variance per metre walked (m^2/m), derived, not fitted, from the
#: simulator's documented field disturbance (S33: sd 3 uT per component, one blob per 4 m of path, 1 m wide, centres
#: N(0, 1 m) off the path) over its horizontal Earth field 45 uT cos 55 deg: (1/4) 3^2 2 pi 1^2 / sqrt(3) / 25.81^2 / 2
PLACE_DIFFUSION_M2 = 0.25 * 3.0 ** 2 * 2 * np.pi / np.sqrt(3.0) / (45.0 * np.cos(np.radians(55.0))) ** 2 / 2
#: decision L239: the candidate's bounded heading error (rad, sd) on the route's extent, derived, not fitted: the waist
#: compass's heading error at a place, from the simulator's documented magnetometer - its hard-iron offset (sd 2 uT per
#: axis, ``sim.sensors.magnetometer_readout``) and its field disturbance at a point of the path (S33: blobs of sd 3 uT
#: per component, one per 4 m, 1 m wide, centres N(0, 1 m) off the path: variance 3^2 (1 sqrt(pi) / 4) / sqrt(3) =
#: 2.30 uT^2 per component) - across the horizontal Earth field 45 uT cos 55 deg = 25.81 uT:
#: sqrt(2^2 + 2.30) / 25.81 = 0.0973 rad (5.6 deg). L17's +-60 s window passes the compass's error on as a mean over
#: the window, whose rms cannot exceed the rms of what it averages: the window bounds the heading error (it does not
#: grow with the walk) at most at this size
EXTENT_HEADING_RAD = float(np.sqrt(2.0 ** 2 + 3.0 ** 2 * np.sqrt(np.pi) / 4.0 / np.sqrt(3.0))
                           / (45.0 * np.cos(np.radians(55.0))))
#: decision E128: the speed (m/s) E127 takes for a held gap when the track has no walking stride of its own: a
#: typical adult walking speed, inside L95's range (0.5-2.5 m/s); stated, not fitted
GAP_FALLBACK_SPEED_MPS = 1.4


def held_gap_variance(steps, *, bridge_error: float = 0.15) -> np.ndarray | None:
    """Decision E127: per stride, the per-axis variance (m^2) its held position adds: a row with ``gap_s`` > 0 and no
    length (the position held across a foot dropout) misses the displacement walked in the gap, up to the speed times
    the gap in any direction: radius^2 + (v g)^2, i.e. (v g)^2 / 2 per axis. v: the median |length| / duration of the
    track's strides without a gap (E128's speed without any). None when no row is a held gap. Decision W625: a row
    a waist gap was bridged on (``gap_bridged_m`` > 0) misses ``bridge_error`` (W625's 15 % rule) of those metres."""
    if "gap_bridged_m" in steps and len(steps):  # decision W625
        bridged = pd.to_numeric(steps["gap_bridged_m"], errors="coerce").fillna(0.0).to_numpy(float)
        if (bridged > 0).any():
            return 0.5 * (bridge_error * bridged) ** 2
    if "gap_s" not in steps or not len(steps):
        return None
    gap = pd.to_numeric(steps["gap_s"], errors="coerce").fillna(0.0).to_numpy(float)
    length = np.abs(steps["length_m"].to_numpy(float))
    held = (gap > 0) & ~(length > 0)
    if not held.any():
        return None
    dur = steps["end_s"].to_numpy(float) - steps["start_s"].to_numpy(float)
    walk = ~held & (gap <= 0) & np.isfinite(length) & (length > 0) & np.isfinite(dur) & (dur > 0)
    v = float(np.median(length[walk] / dur[walk])) if walk.any() else GAP_FALLBACK_SPEED_MPS
    return np.where(held, 0.5 * (v * gap) ** 2, 0.0)


#: decision E205 (adopted by its rule; docs/decisions/export.md): the regimes whose bias clock skips the rests longer
#: than L296's minute that the streamed heading does not integrate (L31's gap yaw looks back 1 s)
STREAMED_REGIMES = ("plasys-streaming", "plasys-foot-streaming")


def streamed_rests(steps, min_s: float) -> list[tuple[float, float]]:
    """Decision E205: the (end, start) spans between two consecutive strides of a streamed track longer than
    ``min_s`` (s), without those next to a held foot-gap row (``gap_s`` > 0, whose turn L99 bridges by the waist's
    whole turn): over them the streamed heading adds only :func:`~pdrlearn.kernels.stride.gap_yaw`'s last second."""
    if not len(steps) or not {"start_s", "end_s"} <= set(steps):
        return []
    start, end = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    held = steps["gap_s"].fillna(0.0).to_numpy(float) > 0 if "gap_s" in steps else np.zeros(len(steps), bool)
    lo, hi = between_rows(start, end)
    keep = (hi - lo > min_s) & ~held[1:] & ~held[:-1]
    return [(float(a), float(b)) for a, b in zip(lo[keep], hi[keep], strict=True)]


def sigma_regime(info: dict, session) -> str:
    """The :data:`SIGMA_PARAMS` key for a track of ``session`` with ``info`` (its pipeline, heading source,
    streaming)."""
    if str(info.get("pipeline", "")).startswith("waist"):
        return "waist"
    if info.get("streaming"):  # the streamed heading is the waist gyroscope's when there is one (L99)
        return "plasys-streaming" if session.has("wGyroscope") else "plasys-foot-streaming"
    if (info.get("compass_check") or {}).get("gyro_fallback"):  # decision L267: the heading is the waist gyroscope's
        return "plasys-gyro-fallback"
    return "plasys-fused" if info.get("heading_source") in ("fused", "waist") else "plasys-foot"


def bias_clock(steps, end: np.ndarray, t0: float, rest_s: float, rests=None) -> np.ndarray:
    """Decision L297: the steps' end times with every rest longer than ``rest_s`` taken out (between two steps: from a
    step's ``end_s`` to the next one's ``start_s``; before the first step: from the track's start ``t0``): the clock
    of the model's residual heading rate when the heading takes the bias of such a rest from the rest itself (L296;
    before the first step the heading has not started), so it does not turn by ``b t`` across it. ``rests``
    (decision L306): the (start, end) spans L296 took the bias out of; when given, a rest between two steps is taken
    out only if it overlaps one of them (a rest whose heading still integrates the bias keeps its clock)."""
    if "start_s" not in steps or not len(end):
        return end
    return rest_clock(steps["start_s"].to_numpy(float), end, t0, rest_s, rests)


def sigma_per_row(steps, t, params: dict[str, float], rest_s: float | None = None, rests=None,
                  bounded: dict | None = None) -> np.ndarray:
    """The 1-sigma radius (m) at each time ``t`` (a track's trajectory times, the first its start) of a track
    with ``steps`` (steps.csv columns ``length_m``, ``heading_rad``, ``end_s``) under the model ``params``: the
    covariance after the last stride that ended at or before the time, 0 at the start, never decreasing, and
    (decision L333) never over half :func:`reach_bound`, so the 2-sigma circle is never wider than the circle that
    holds the true position for certain when the track's distance is not under the walker's (L342); ``bounded`` (a
    dict, when given) gets ``"bounded"``: whether the last stride's radius was cut to that bound.
    ``rest_s`` (decision L297): the bias term's clock skips the rests longer than this (:func:`bias_clock`); with
    ``rests`` (decision L306) only those of them that overlap these (start, end) spans."""
    t = np.asarray(t, float)
    sigma = np.zeros(len(t))
    if len(steps) and len(t):
        t0 = float(t[0])
        length, heading, end = (steps[c].to_numpy(float) for c in ("length_m", "heading_rad", "end_s"))
        raw = length
        # decision L143: a stride of unknown length, heading or end has no known displacement: its rows get NaN,
        # the later strides are modelled without it (its length taken as 0; an unknown end as the stride before's)
        bad = ~(np.isfinite(length) & np.isfinite(heading) & np.isfinite(end))
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            log.warning("pos_sigma_m: %d stride(s) with a non-finite length, heading or end time (the first: stride "
                        "%d, starting %.2f s): their rows get NaN and the later strides are modelled without them, "
                        "a slightly smaller radius than the walk's (decision L143)", int(bad.sum()), k + 1,
                        float(steps["start_s"].iloc[k]) if "start_s" in steps else float("nan"))
            length, heading = np.where(bad, 0.0, length), np.where(bad, 0.0, heading)
            end = pd.Series(np.where(np.isfinite(end), end, np.nan)).ffill().fillna(t0).to_numpy(float)
        clock = end if rest_s is None else bias_clock(steps, end, t0, rest_s, rests)  # L297, L306
        r, cut = stride_radius(length, heading, clock, t0, params, raw=raw, bad=bad,
                               held_var_m2=held_gap_variance(steps))
        if bounded is not None:
            bounded["bounded"] = cut
        i = np.searchsorted(end, t + 1e-9, side="right") - 1
        sigma = np.where(i >= 0, r[np.clip(i, 0, len(r) - 1)], 0.0)
        sigma[0] = 0.0  # the start is where the track is put
    return sigma


def compass_extent_rad(compass_check: dict | None) -> float:
    """Decision L334: the heading error (rad) of a ``plasys-fused`` track's extent term: L182's judged median |angle|
    between the waist compass and the foot's gyroscope heading (``info.compass_check.median_deg``); 0 without a
    check (no waist magnetometer, too few straight strides) or a non-finite median."""
    med = (compass_check or {}).get("median_deg")
    return float(np.radians(med)) if med is not None and np.isfinite(med) and med > 0 else 0.0


def sigma_params(regime: str, info: dict | None = None, *, extent_heading: bool = False, extent_return: bool = False,
                 compass_extent: bool = False, boundary_offset_rad: float = 0.047) -> dict[str, float]:
    """The error model of ``regime``: its :data:`SIGMA_PARAMS`. Decision E342: a ``plasys-streaming`` track whose
    ``info["cycle_yaw"]`` is False (E336 off: its strides go along the pelvis' yaw at the foot's rest, E331's offset)
    takes ``heading_offset_rad`` = ``boundary_offset_rad``, E331's measured RMS offset of that heading (E337's term is
    the offset left after E336 + E338). Three options, off by default (decision L595: keywords, no module switches;
    each changes ``plasys-fused`` only):

    - ``extent_heading`` (decision L240: L239's candidate not adopted, its rule failed on the short routes only: 100 %
      of their strides within 2 sigma against the rule's 99.5 %; 27/29 R1 finals within 2 sigma against 18/29
      without, users 5040-5079) adds ``extent_heading_rad`` = :data:`EXTENT_HEADING_RAD`;
    - ``extent_return`` (decision L242: L241's candidate not adopted, 20/25 long-route finals within 2 sigma against
      the rule's 90-99 %, users 5130-5169) adds ``extent_return_rad`` = :data:`EXTENT_HEADING_RAD`: L239's heading
      error on the part of the extent the track has come back from, per axis e^2 (R_k^2 - |D_k|^2) (the two are
      alternatives: both set add both);
    - ``compass_extent`` (decision L334, adopted by L335, not kept by L341: the pooled 94.0 % held 3 fallback marches
      the term does not touch, and the check's angle holds the foot's own yaw drift, L336): the extent term's heading
      error is the track's own compass check (``info["compass_check"]``, :func:`compass_extent_rad`) in place of
      L239's."""
    params = dict(SIGMA_PARAMS[regime])
    if regime == "plasys-streaming" and (info or {}).get("cycle_yaw") is False:  # decision E342 (E331's delta)
        params["heading_offset_rad"] = float(boundary_offset_rad)
    if regime == "plasys-fused":
        for flag, term in ((extent_heading, "extent_heading_rad"), (extent_return, "extent_return_rad")):
            if flag:
                params[term] = EXTENT_HEADING_RAD
        compass = compass_extent_rad((info or {}).get("compass_check")) if compass_extent else 0.0
        if compass:  # decisions L334 / L335: the track's own compass check, in place of L239's derived value
            params["extent_heading_rad"] = compass
    return params


def add_position_sigma(result, session, regime: str | None = None, *, params: dict[str, float] | None = None) -> None:
    """Write ``pos_sigma_m`` (m, the 1-sigma radius ``sqrt(trace P)`` of the horizontal position, 0 at the start)
    into ``result.trajectory`` and the model used into ``result.info["position_sigma"]``. A trajectory row gets
    the covariance after the last stride that ended at or before its time. ``regime``: a :data:`SIGMA_PARAMS`
    key (default :func:`sigma_regime`; ``pdrlearn run`` names its own). ``params``: the regime's error model with
    :func:`sigma_params`' options (default: ``sigma_params(regime, result.info)``, none of them)."""
    traj = result.trajectory
    if not len(traj):
        return
    regime = regime or sigma_regime(result.info, session)
    params = sigma_params(regime, result.info) if params is None else params
    rest_s, rests = None, result.info.get("rest_bias_rests")
    if rests is not None:  # decision L306: L296 was in force on this heading (gyro; `run`'s live one: L309)
        from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S

        rest_s = REST_BIAS_MIN_S  # decision L297: L296's rests turn the heading by their moving samples only
    elif regime in STREAMED_REGIMES:  # decision E205 (adopted; L595: no switch): rests the streamed heading skips
        from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S

        rest_s, rests = REST_BIAS_MIN_S, streamed_rests(result.steps, REST_BIAS_MIN_S)
    bounded: dict = {}
    traj["pos_sigma_m"] = sigma_per_row(result.steps, traj["t"].to_numpy(float), params, rest_s, rests, bounded)
    # decision L333: whether the end's radius is the distance bound (the model's own was wider)
    result.info["position_sigma"] = {"model": regime, **params, "bounded": bounded.get("bounded", False)}


def drop_position_sigma(result) -> None:
    """An aided track (GNSS, fixes) is outside the model: no ``pos_sigma_m``."""
    result.trajectory = result.trajectory.drop(columns=["pos_sigma_m"], errors="ignore")
    result.info.pop("position_sigma", None)


#: decision L175: a track warns when its final 2-sigma radius exceeds this share of the distance walked. Fixed a
#: priori, not fitted: foot-mounted PDR is judged in % of the distance travelled, and a working foot track ends
#: within a few % of it (this project's offline plasys: 124 m after 5 km, 2.5 %, trial "longhaul"); a 2-sigma
#: circle a quarter of the walk wide says the end could be anywhere across a quarter of the route - ten times
#: a working track's error, a position no longer fit to be read off a map
SIGMA_SHARE_WARN = 0.25
#: decision L175: regimes whose radius is known to be too large (L150/L151: uncalibrated, 100 % of the strides within
#: 2 sigma), on which the warning would be false
SIGMA_TOO_LARGE = frozenset({"plasys-foot-streaming"})
#: decision L175 (amended by the lead, twenty-fifth session): the line speaks of heading drift over a long walk; on
#: a short walk the radius is the models' constant point term (3.1 m for the lower back, L128), not drift, and a
#: 10 m walk test (a clinician's trial) would be told its position is unusable. 100 m: about 80 s of walking, ten
#: times a 10 m walk test and three times the distance below which that point term alone exceeds the share
SIGMA_WARN_MIN_DISTANCE_M = 100.0
#: decision L341: the models were fitted and checked on L129's routes of about 530 m (L128-L151); a track that walked
#: farther than this says once that its radius is not calibrated there (a load-carriage trial: a 3.7 km march ended
#: 387 m off with a 235 m radius, 7.9 % of its strides within 2 sigma). 600 m: the longest such route, rounded up
SIGMA_CALIBRATED_ROUTE_M = 600.0


def position_sigma_range_warning(summary: dict) -> str | None:
    """Decision L341: one line when the track walked over :data:`SIGMA_CALIBRATED_ROUTE_M` and L175's line does not
    already call the position unusable; None otherwise (no sigma, a short walk, or a model of
    :data:`SIGMA_TOO_LARGE`, whose radius is known to be too large)."""
    sigma, dist = summary.get("final_position_sigma_m"), summary.get("distance_m")
    if sigma is None or dist is None or not (np.isfinite(sigma) and np.isfinite(dist)):
        return None
    model = (summary.get("info") or {}).get("position_sigma", {}).get("model", "?")
    if float(dist) <= SIGMA_CALIBRATED_ROUTE_M or model in SIGMA_TOO_LARGE or position_sigma_warning(summary):
        return None
    return (f"the position radius (pos_sigma_m, model {model}) was calibrated on routes of about 530 m (L129); on this "
            f"{float(dist):.0f} m walk it is not calibrated and can be several times too small (a 3.7 km march: "
            "387 m off with a 235 m radius); read the 2-sigma circle as a lower bound (decision L341)")


def position_sigma_warning(summary: dict) -> str | None:
    """Decision L175: one line when twice ``final_position_sigma_m`` (path.png's circle) exceeds
    :data:`SIGMA_SHARE_WARN` of ``distance_m``; None otherwise (no sigma, no distance, a walk under
    :data:`SIGMA_WARN_MIN_DISTANCE_M`, within, or a model of :data:`SIGMA_TOO_LARGE`)."""
    sigma, dist = summary.get("final_position_sigma_m"), summary.get("distance_m")
    if sigma is None or dist is None or not (np.isfinite(sigma) and np.isfinite(dist) and dist > 0):
        return None
    if float(dist) < SIGMA_WARN_MIN_DISTANCE_M or not 2.0 * float(sigma) > SIGMA_SHARE_WARN * float(dist):
        return None
    model = (summary.get("info") or {}).get("position_sigma", {}).get("model", "?")
    if model in SIGMA_TOO_LARGE:
        return None
    fix = ("track offline with a foot and a waist unit (the waist compass, `plasys-fused`) or give position fixes "
           "(`track --fixes` / `--gnss`)")
    why = "a gyroscope-only heading drifts over a long walk"
    if model == "plasys-gyro-fallback":  # decision L267: the compass was judged disturbed (L182), the track
        fix = ("this offline track left the waist compass (L182, L226) for the waist gyroscope; give position "
               "fixes (`track --fixes` / `--gnss`)")
    elif model == "plasys-fused":  # decision L335: the track already reads the compass; its check's angle
        ext = ((summary.get("info") or {}).get("position_sigma") or {}).get("extent_heading_rad")
        if ext:
            why = (f"the waist compass and the foot's gyroscope heading disagree by a median {np.degrees(ext):.1f} "
                   "deg on this walk (L182's check), a heading error this radius carries over the route's extent, "
                   "decision L335")
        fix = "give position fixes (`track --fixes` / `--gnss`)"
    return (f"the end position's 2-sigma radius {2 * float(sigma):.0f} m is {200 * float(sigma) / float(dist):.0f} % "
            f"of the {float(dist):.0f} m walked (model {model}; over {100 * SIGMA_SHARE_WARN:.0f} % warns, decision "
            f"L175): the position is not usable ({why}; distance, steps and gait are not affected); for a position, "
            f"{fix}")
