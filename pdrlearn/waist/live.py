"""Live waist-only tracking: :class:`WaistTracker` (docs/waist.md "Live tracking", decisions W64-W65).

``pdrlearn track DIR --pipeline waist-pendulum --realtime`` replays a recording through the causal contact
detector of decision W31; :class:`WaistTracker` is the same pipeline fed sample by sample from a live lower-back
unit (a belt phone, a lower-back IMU): ``push(t, acc, gyr)`` with the raw sensor-frame accelerometer (m/s^2,
including gravity) and gyroscope (rad/s) returns the steps that became final, with their length, heading and
position. Nothing is re-implemented: the contacts are those of the ``waist-ic`` detector's streaming form
(:class:`pdrlearn.steps.waist_ic._RealtimeProcessor`: the AHRS, the bridge of dropped samples W59 and the W31
decisions), the step length and heading are the kernels :func:`pdrlearn.track.waist.track_waist` calls
(:func:`~pdrlearn.waist._kernels.vertical_excursion`, :func:`~pdrlearn.waist._kernels.pendulum_length`,
:func:`~pdrlearn.waist._kernels.turning_step_factor`, :func:`~pdrlearn.waist.steplength.fragment_windows`,
:func:`~pdrlearn.waist.heading.gyro_headings`), and the parameters and options resolve as ``track_waist``'s.

Decision W64: a step is reported once two more contacts of its walking sequence are decided (or the sequence has
ended): its heading needs the turning class of the next stride (seed 003 sec. 3.3 integrates the straight step
after a turning one), and its fragment merge (W27) the next step's duration. The W27 fragment test uses the median
step of the walking sequence so far (the steps known then, at most :data:`FRAGMENT_CONTEXT_STEPS`), not of the
whole sequence, and a merge is never undone. Everything else is the replay's computation, so the steps and positions
equal ``track_waist(session, pipeline="waist-pendulum", realtime=True)`` to rounding unless a W27 decision differs
(``merge_fragments=False``: always) or an option of :data:`LIVE_UNAPPLIED_OPTIONS` is in force. L296's ``rest_bias``
is applied live since decision L308, and W231's ``pause_ride`` where the PARAMS.json gives it true (E146): both are
decided at the contact that ends the rest or pause (the step is reported after it anyway, W64), on the samples the
tracker holds across it. State is bounded: the samples since the oldest step still pending, the rows of
the open walking sequence (at most :data:`FRAGMENT_CONTEXT_STEPS`) and the W31 detector's 12 s window.

Decision W65: the axis frame is given (``frame`` or ``meta`` as meta.json would declare it); without one it is
inferred (:func:`pdrlearn.track.frame_inference.infer_waist_frame`, decision D8) from the first samples that fix it
-- tried every :data:`INFER_EVERY_S` seconds of buffered data, at most the last :data:`INFER_MAX_S` seconds
held -- and the track starts at the first held sample (the replay infers it from the whole recording).
"""

from __future__ import annotations

import json
import logging

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError
from pdrlearn.runtime.waist import FRAGMENT_CONTEXT_STEPS, LOOKAHEAD_ROWS, LiveStep, WaistStream

log = logging.getLogger(__name__)

#: W65: without a declared frame, inference is tried on the held samples every INFER_EVERY_S of new data, from
#: frame_inference.MIN_WALK_S on; at most the last INFER_MAX_S seconds are held meanwhile
INFER_EVERY_S = 2.0
INFER_MAX_S = 120.0


def _declared_frame(frame, meta: dict | None):
    """``(rotation, AxisFrame or None, origin)``: the sensor -> body FLU rotation from ``frame`` (AxisFrame, dict
    ``{"x": "up", ...}``, ``"x=up,y=right,z=forward"`` or a 3x3 matrix) or, without one, from ``meta`` as a
    session's meta.json declares it; the AxisFrame (None for a matrix) and where it came from, for the data check
    (decision B108). ``(None, None, "")`` without a frame."""
    from pdrlearn.io.frames import AxisFrame, frames_from_meta

    if frame is None:
        f = frames_from_meta(meta or {}).get("waist")
        return (None, None, "") if f is None else (f.matrix(), f, 'declared in meta "frames"')
    if isinstance(frame, AxisFrame):
        return frame.matrix(), frame, "given as frame="
    from pdrlearn.kernels.frames import axes_dict, check_rotation

    if isinstance(frame, dict | str):
        f = AxisFrame.from_dict(axes_dict(frame, "WaistTracker: frame="))
        return f.matrix(), f, "given as frame="

    return check_rotation(frame, "WaistTracker: frame="), None, "given as frame="


def live_options(p, warnings: list[str], quiet: list[str] | None = None, **given) -> dict:
    """The live waist-pendulum options from the parameters ``p`` and the caller's ``given`` (None = the PARAMS.json's,
    else the pipeline defaults: ``track_waist``'s :func:`~pdrlearn.track.waist.resolve_options`), with the lines
    about what the live tracker cannot do added to ``warnings``; shared by :class:`WaistTracker` and ``pdrlearn
    export CAL.json`` (the waist bundle's options, decision E57). ``quiet``: a list, to take E107's line for the
    options left at their offline defaults (nothing the caller set or can act on; decision E368), ``warnings`` keeping
    the line for the options the PARAMS.json sets; None: one line for both in ``warnings``."""
    from pdrlearn.track.waist import CAUSAL_PAUSE_STEPS, CHOICE_OPTIONS, resolve_options

    given = {"realtime": True, "heading": "gyro", "refine_ic": None, "initial_heading": None, "resolve_signs": None,
             "integrate_stops": None, "turn_factor": None, "rhythm": None, "merge_fragments": None,
             "length_smoothing": None, "slow_turn_rps": None, "gentle_curves": None, "pivot_steps": None,
             "stairs_length": None,
             "pause_steps": None, "realtime_contact_shift": None,
             "freeze_index": None,  # W216: `run` computes the lower back's freeze index after the track, opt-in
             "pause_ride": None, "rest_bias": None,  # decisions E146, L308: a bundle's options
             "live_climbs": None,  # decision E358: stairs_length "climbs" held live
             **given}
    o = resolve_options(p, given)
    if given["pause_ride"] is None:  # decision E146: only as the PARAMS.json (or the caller) gives it
        o["pause_ride"] = live_value("pause_ride", p.options)
    values, codes = CHOICE_OPTIONS["live_climbs"]
    if o["live_climbs"] not in values:  # decision E358: a misspelt value would track silently without it
        raise DataError(f"live_climbs {o['live_climbs']!r} is not one of {', '.join(json.dumps(v) for v in values)} "
                        f"(decision {codes}); fix the PARAMS.json \"options\"")
    if o["pause_steps"] != CAUSAL_PAUSE_STEPS:  # W165: the live trackers apply W134's value, or none
        o["pause_steps"] = False
    if o["length_smoothing"] != "none":
        raise DataError(f"length_smoothing '{o['length_smoothing']}' looks up to 1 s ahead and the live tracker "
                        "does not (decision W56); set the PARAMS.json option length_smoothing to none")
    if p.source == "calibrated" and p.pipeline not in (None, "waist-pendulum"):
        warnings.append(f"the parameters were calibrated for {p.pipeline}: the waist-pendulum step length "
                        "keeps its defaults (run 'pdrlearn calibrate --pipeline waist-pendulum')")
    if quiet is None:
        line = unapplied_options_line(p)  # decision E107: no option of the PARAMS.json dropped without a word
        if line:
            warnings.append(line)
    else:  # decision E368: the options the PARAMS.json sets warned, the offline defaults' line kept aside
        for which, into in (("given", warnings), ("defaults", quiet)):
            line = unapplied_options_line(p, which=which)
            if line:
                into.append(line)
    if p.source == "calibrated" and p.pipeline in (None, "waist-pendulum"):  # decision W479: W471's line live too
        from pdrlearn.track.waist import calibrated_detector_line

        line = calibrated_detector_line(p.detector, None, "waist-pendulum", live=True)  # the pipeline's own
        if line:
            warnings.append(line)
    asked = (p.options or {}).get("heading")
    if asked not in (None, "gyro"):  # decision W82: no silent override of the PARAMS.json heading
        warnings.append(f"the PARAMS.json option heading '{asked}' is not available live: the live tracker uses "
                        "the gyro heading, which keeps gentle curves only as runs of strides over 1.5 deg/s; the "
                        f"option slow_turn_rps 0.035 adds slower ones ({decision_ref('W543', 'W82')})")
    return o


#: decision E107: the PARAMS.json options the live waist-pendulum tracker does not apply (the offline detector's
#: W119/W127, W131, W151, W152 look ahead -- W131 runs inside W31's window with ``realtime_contact_shift``, W166;
#: ``pause_steps`` W111 / W122 too, but W134's "standing" is applied, W165; W102/W104's trunk posture, W108's climbs
#: read the whole recording); ``heading`` has W82's own line and ``length_smoothing`` is refused (W56). The rest are
#: applied (``stairs_length`` since E107) or do not concern the live tracker (``realtime``; ``refine_ic``,
#: ``pll_edge_lock`` (W356) and ``resolve_signs`` are waist-pll / harmonic-heading options; ``relative_gate`` off is
#: the live fixed gate).
LIVE_UNAPPLIED_OPTIONS = ("stairs_climb", "max_tilt_deg", "sit_veto", "vault_veto", "contact_shift", "weak_fill",
                          "step_bound",  # W230: the runtime does not bound a step's barometric change
                          "parity_fill", "integrate_end",  # W187: the final stop is known only offline
                          "stand_veto",  # W189: the recording's median bounce is known only offline
                          "contact_model",  # W203: its features read the recording's medians
                          "freeze_veto",  # W214: the freeze index's 4 s window looks 2 s ahead
                          "pelvic_rhythm_veto",  # W440: the pelvic rhythm's window looks 3 s ahead
                          "slow_min_step",  # W591: the pelvic gyro's median step over the whole recording
                          "foot_rest_veto",  # W336: a foot rest is judged over its whole run of contacts
                          "rhythm_warning",  # W338: a chunk of 16 contacts is judged after its last one
                          "trunk_rhythm_veto",  # W550: a run is judged after its last contact
                          "mount_drift",  # W565 / W571: the bouts' uprights are read over the whole recording
                          "side_at_contact",  # W235: the offline detector's sequence rules only
                          "fast_fill",  # W242: the offline detector's sequence rules only
                          "ap_above_mean",  # W265: W29's IC of the offline detector only
                          "turn_bridge",  # W374: the offline gate reads the walk after the turn
                          "climb_veto",  # L330: W108's climbs read the whole recording (L314's veto, opt-in)
                          "ride_vibration",  # L402 / L403: the live tracker tells no ride's kind (no rides.csv)
                          "walked_ride",  # W609: the live tracker tells no ride's kind (no rides.csv)
                          "gap_bridge",  # W625 (not adopted, opt-in): offline only
                          "lying_heading",  # W269: W222's lying is labelled on the whole recording
                          "gentle_rest_bias",  # W544: W105's first standstill may come after the step
                          # E146: W231's ride is applied live only where the PARAMS.json gives pause_ride true (E146's
                          # rule was not met for the default); L308 applies rest_bias live (E147: no longer named)
                          "pause_ride",
                          "cadence_law")  # W240, W261 ("steady"): measured, not adopted; `pdrlearn track` only


#: decisions W271, E151: options E107's line names only where the PARAMS.json gives them, not at their offline
#: default: ``lying_heading`` (true offline since W271) would otherwise be named on every live track, most with no
#: lying; ``foot_rest_veto`` (true offline since W337) acts only with a foot unit, never read live
NAMED_WHEN_GIVEN = ("lying_heading", "foot_rest_veto", "gentle_rest_bias")  # W544: as lying_heading


def unapplied_options_line(p, *, which: str = "all") -> str | None:
    """Decision E107 (E126): the line naming the options of :data:`LIVE_UNAPPLIED_OPTIONS` whose offline value (the
    PARAMS.json ``"options"`` of ``p``, else the offline default) differs from what the live tracker does
    (:func:`live_value`), else None: ``sit_veto`` ``"opposite"``, the offline default (W185), is named whether given or
    not, ``false`` (what the live tracker does) is not. ``which`` (decision E368): ``"given"`` names only the options
    the PARAMS.json sets, ``"defaults"`` only those at their offline default, ``"all"`` both."""
    from pdrlearn.track.waist import OPTION_DEFAULTS

    given = p.options or {}
    offline = {k: given[k] if given.get(k) is not None else OPTION_DEFAULTS[k] for k in LIVE_UNAPPLIED_OPTIONS}
    live = {k: live_value(k, given) for k in LIVE_UNAPPLIED_OPTIONS}
    unapplied = [k for k in LIVE_UNAPPLIED_OPTIONS if offline[k] != live[k]
                 and (k not in NAMED_WHEN_GIVEN or given.get(k) is not None)]
    held = (given.get("live_climbs") if given.get("live_climbs") is not None
            else OPTION_DEFAULTS["live_climbs"]) == "hold"  # decision E358: W108's climbs read live, held
    if given.get("stairs_length") == "climbs" and not held:  # W156 reads the whole recording's climbs (W108)
        unapplied.append("stairs_length")
        offline["stairs_length"], live["stairs_length"] = "climbs", False
    if given.get("pause_steps") in (True, "progression"):  # W165: live applies "standing" (W134) and false only
        unapplied.append("pause_steps")  # live_options turns these into false
        offline["pause_steps"], live["pause_steps"] = given["pause_steps"], False
    if which != "all":  # decision E368: the options the PARAMS.json sets, or those at their offline default
        unapplied = [k for k in unapplied if (given.get(k) is not None) == (which == "given")]
    if not unapplied:
        return None
    named = ", ".join(f"{k}={json.dumps(offline[k])}{'' if given.get(k) is not None else ' (the offline default)'}"
                      for k in unapplied)
    as_live = ", ".join(f"{k}={json.dumps(live[k])}" for k in unapplied)
    many = len(unapplied) > 1
    hint = (" (contact_shift applies live with the option realtime_contact_shift true, decision W166)"
            if "contact_shift" in unapplied and offline["contact_shift"] else "")  # E130
    return (f"the option{'s' if many else ''} {named} {'are' if many else 'is'} not applied by the live waist tracker "
            f"(decision E107): it tracks as with {as_live}; offline `pdrlearn track` applies "
            f"{'them' if many else 'it'}{hint}")


def live_value(option: str, given: dict | None = None):
    """Decisions E126, E130: the value of the option ``option`` of :data:`LIVE_UNAPPLIED_OPTIONS` that the live tracker
    tracks as, under the PARAMS.json ``"options"`` ``given``: no sit veto (``False``, W185's realtime value, as
    :func:`pdrlearn.track.waist.track_waist` gives a ``realtime`` track that does not set it; W472), where the offline
    default is ``"opposite"``); no stand veto (``False``, where the offline default is ``"walking"``
    since W219; the walking stretches' bounce is known only offline, W189 / W218); ``contact_shift`` only with
    ``realtime_contact_shift`` (W166, off by default: ``False``); no ``parity_fill`` (``False``: W152 / W159's fill is
    the offline detector's only, where the default is ``"within"``); no ``turn_bridge`` (``False``: W374's bridge reads
    the walk after the turn, where the offline default is ``"side"`` since W385); ``pause_ride`` only as the PARAMS.json
    gives it (E146: W231's ride is applied live when given true; not given: ``False``, W158's whole pause, where the
    offline default is true); ``lying_heading`` ``False`` (W271, E151: the live tracker labels no lying; E107's line
    names its offline default only where the PARAMS.json gives it, :data:`NAMED_WHEN_GIVEN`); else the option's offline
    default (E107)."""
    from pdrlearn.track.waist import OPTION_DEFAULTS

    given = given or {}

    def value(k):
        return given[k] if given.get(k) is not None else OPTION_DEFAULTS[k]

    if option == "sit_veto":  # decision W185: the whole-recording veto is the offline default only
        return False
    if option == "stand_veto":
        return False
    if option == "contact_shift":  # W166: W131 inside W31's window only with realtime_contact_shift
        return bool(value("contact_shift")) and bool(value("realtime_contact_shift"))
    if option in ("parity_fill", "turn_bridge"):  # W159, W374 / W385: InitialContactDetector.rule_settings keeps
        return False  # them offline only
    if option == "pause_ride":  # E146: applied live when the PARAMS.json gives it true, else W158's whole pause
        return bool(given["pause_ride"]) if given.get("pause_ride") is not None else False
    if option in ("lying_heading", "foot_rest_veto", "gentle_rest_bias"):  # W271, E151, W337, W544: never applied
        return False  # live (named only where given, NAMED_WHEN_GIVEN)
    return OPTION_DEFAULTS[option]


class _HeldSamples:
    """Raw samples held while a frame inference waits (W65's inference, B108's check of a declared frame): the
    pushed chunks are joined only when an attempt is due, every INFER_EVERY_S s of pushed time from
    ``frame_inference.MIN_WALK_S`` on (no quadratic cost for 1-sample pushes); ``trim`` keeps at most the last
    INFER_MAX_S s."""

    def __init__(self, trim: bool):
        self.trim = trim
        self.t: list[np.ndarray] = []
        self.v: list[np.ndarray] = []
        self.next_try = -np.inf

    def push(self, t: np.ndarray, v: np.ndarray, min_s: float):
        """Hold ``(t, v)``; the held ``(tt, vv)`` when an attempt is due, else None."""
        self.t.append(t)
        self.v.append(v)
        if t[-1] - self.t[0][0] < min_s or t[-1] < self.next_try:
            return None
        tt, vv = np.concatenate(self.t), np.concatenate(self.v)
        if self.trim and tt[-1] - tt[0] > INFER_MAX_S:  # hold at most INFER_MAX_S s
            keep = tt >= tt[-1] - INFER_MAX_S
            tt, vv = tt[keep], vv[keep]
        self.t, self.v = [tt], [vv]
        self.next_try = tt[-1] + INFER_EVERY_S  # (a time on the pushed clock)
        return tt, vv

    def clear(self) -> None:
        self.t, self.v = [], []

    def size(self) -> int:
        return sum(a.size for a in self.t) + sum(a.size for a in self.v)


class WaistTracker(WaistStream):
    """Live waist-pendulum tracking of a lower-back unit (decisions W31, W64, W65; docs/waist.md "Live tracking").

    Parameters
    ----------
    fs : nominal sampling rate (Hz) of the pushed samples
    params : PARAMS.json path, dict or :class:`~pdrlearn.waist.params.WaistParams` from ``pdrlearn calibrate``
        (None: defaults from ``meta`` / ``sensor_height_m`` / ``height_m``, with the warnings ``track`` gives)
    meta : a session's meta.json contents (its ``subject`` heights and ``frames`` are read as ``track`` reads them)
    sensor_height_m, height_m : shorthand for meta.json's ``sensor_height_m`` / ``height_m`` (m)
    frame : the unit's axes (an :class:`~pdrlearn.io.frames.AxisFrame`, ``{"x": "up", "y": "right", "z":
        "forward"}``, ``"x=up,y=right,z=forward"`` or a 3x3 sensor -> body FLU matrix); None: ``meta``'s, else
        inferred from the first walking (W65)
    start : ``{"x": m, "y": m, "heading_rad": rad}`` (ENU), or the pipelines' ``(lat, lon)`` / ``(lat, lon, alt)`` in
        degrees (alt in m; ``"LAT,LON[,ALT]"`` too; checked as ``--start``, decision L157): each step then has ``lat``,
        ``lon`` (decision W137; the altitude is kept as :attr:`start_altitude_m`, not tracked), or None (origin)
    initial_heading : the direction the walker sets off in, radians ENU (counter-clockwise from east; 0 = east, the
        default); a magnitude above 2 pi (degrees, as the CLI's ``--initial-heading``) is refused (decision W81)
    integrate_stops, turn_factor, rhythm, merge_fragments, slow_turn_rps, gentle_curves, pivot_steps : as
        :func:`pdrlearn.track.waist.track_waist` (None: ``params.options``, else its defaults; ``pivot_steps``: W150)
    pause_steps : W134's ``"standing"`` (a step holding a stand of half its local period inside a walk keeps the
        trunk's travel; decision W165: decided once the third contact after the step is, at most
        :data:`~pdrlearn.runtime.waist.PAUSE_LOOKAHEAD_ROWS` rows, one contact later than without it) or False (None:
        ``params.options``, else the pipeline's default); the look-ahead values True / "progression" are not applied
    keep_steps : how many reported steps :attr:`steps` keeps (None: all)
    uniform_clock : decisions E366 / E371 / E372's options (not adopted), as :class:`pdrlearn.runtime.WaistTracker`'s
    check_input : check the units of the first seconds (decision B119) -- False only for data already checked
    sides : give each step its foot (``LiveStep.side``: "left" / "right" / "" undecided) from W20's lateral velocity
        on the samples the contact was decided on (decision W138, causal). An option, not the default: on simulated
        users 2270-2289 it is the simulated foot for 93.3 % of the decided contacts where the offline track's
        ``side`` is 98.2 %, short of the 97 % W138 set before measuring (False: ``side`` is None)

    Attributes
    ----------
    position : (x, y) m after the last reported step; heading : its heading (rad, ENU); start_altitude_m : the
    geodetic start's altitude (m; 0.0 without one); steps : reported
    :class:`LiveStep` s; warnings : what ``track`` would warn about (defaults, gaps, an inferred frame);
    not_applied_live : E107's line for the offline-only options left at their offline defaults, which the live
    tracker does without (None: none; decision E368: logged at DEBUG, not warned: nothing to act on);
    params : the resolved :class:`~pdrlearn.waist.params.WaistParams`; options : the resolved options
    """

    def __init__(self, fs: float, *, params=None, meta: dict | None = None, sensor_height_m: float | None = None,
                 height_m: float | None = None, frame=None, start=None, initial_heading: float | None = None,
                 integrate_stops: bool | None = None, turn_factor: bool | None = None, rhythm: bool | None = None,
                 merge_fragments: bool | None = None, slow_turn_rps: float | None = None,
                 gentle_curves: bool | None = None, keep_steps: int | None = None, check_input: bool = True,
                 sides: bool = False,
                 pivot_steps: bool | None = None, pause_steps: bool | str | None = None,
                 uniform_clock: bool | str = False):
        from pdrlearn.io.session import Session
        from pdrlearn.track.waist import _start
        from pdrlearn.waist.events import WALK_THRESHOLD_MPS2
        from pdrlearn.waist.params import resolve_params

        if not (isinstance(fs, int | float) and np.isfinite(fs) and fs > 0):
            raise DataError(f"WaistTracker: fs={fs!r} must be the sampling rate in Hz (a positive number)")
        meta = dict(meta or {})
        sub = dict(meta.get("subject") or {})
        for key, v in (("sensor_height_m", sensor_height_m), ("height_m", height_m)):
            if v is not None:
                sub[key] = float(v)
        meta["subject"] = sub
        p, warnings = resolve_params(Session(name="live", meta=meta), params)
        quiet: list[str] = []  # decision E368: E107's line for the offline defaults, not a warning
        o = live_options(p, warnings, quiet, initial_heading=initial_heading, integrate_stops=integrate_stops,
                         turn_factor=turn_factor, rhythm=rhythm, merge_fragments=merge_fragments,
                         slow_turn_rps=slow_turn_rps, gentle_curves=gentle_curves, pivot_steps=pivot_steps,
                         pause_steps=pause_steps)
        x0, y0, h0, latlon, self.start_altitude_m = _start(start, float(o["initial_heading"]))  # W137, L157
        rot, self._declared, self._declared_origin = _declared_frame(frame, meta)
        if rot is not None and self._declared is None:  # a matrix (an AxisFrame gets B108's check)
            from pdrlearn.kernels.frames import mirrored_line

            line = mirrored_line(rot, "WaistTracker: frame=")
            if line:
                warnings.append(line)
        self._chk = _HeldSamples(trim=False)  # B108: raw samples held until the declared frame is checked
        self._held = _HeldSamples(trim=True)  # W65: raw samples held until the frame is inferred
        super().__init__(fs, params=p, options=o, rotation=rot, start=(x0, y0, h0), warnings=warnings,
                         walk_threshold=p.walk_threshold_mps2 if p.walk_threshold_mps2 is not None
                         else WALK_THRESHOLD_MPS2, keep_steps=keep_steps, check_input=check_input, latlon=latlon,
                         sides=sides, not_applied_live=quiet[0] if quiet else None,
                         uniform_clock=uniform_clock)  # decisions E366 / E371's options

    # -- W65: the frame ---------------------------------------------------------------------------------
    def _hold(self, t: np.ndarray, v: np.ndarray):
        """Samples to feed once a frame is known (the held ones first), or None while it is not."""
        from pdrlearn.track.frame_inference import MIN_WALK_S, FrameInferenceError, infer_waist_frame

        if self._rot is not None:
            self._start_proc()
            return t, v
        held = self._held.push(t, v, MIN_WALK_S)
        if held is None:
            return None
        tt, vv = held
        try:
            found = infer_waist_frame(vv[:, :3], vv[:, 3:], self.fs)
        except FrameInferenceError:
            return None
        self._rot = found.frame.matrix()
        msg = (f"no axis frame given: inferred from the first {tt[-1] - tt[0]:.0f} s: \"frames\": "
               f"{json.dumps({'waist': found.frame.to_dict()})} ({found.describe()}); pass frame= if that is wrong "
               "(decision W65, B108: valid JSON for meta.json)")
        self.warnings.append(msg)
        log.warning("live waist tracker: %s", msg)
        self._held.clear()
        self._start_proc()
        return tt, vv

    def _check_declared(self, t: np.ndarray, v: np.ndarray) -> None:
        """Decision B108: once the held samples fix the unit's frame (as W65's inference, tried every
        INFER_EVERY_S s, on at most INFER_MAX_S s), the declared frame is checked against it once, with offline's
        check (:func:`~pdrlearn.track.frame_inference.declared_frame_warning`); nothing is held after that."""
        from pdrlearn.track.frame_inference import (
            MIN_WALK_S,
            FrameInferenceError,
            declared_frame_warning,
            infer_waist_frame,
        )

        held = self._chk.push(t, v, MIN_WALK_S)
        if held is None:
            return
        tt, vv = held
        try:
            found = infer_waist_frame(vv[:, :3], vv[:, 3:], self.fs)
        except FrameInferenceError:
            if tt[-1] - tt[0] < INFER_MAX_S:
                return
            found = None  # the data do not fix the axes: the declared frame stays unquestioned (as offline)
        declared, self._declared = self._declared, None
        self._chk.clear()
        msg = declared_frame_warning("waist", declared, found, self._declared_origin, used="the declared frame")
        if msg is not None:
            self.warnings.append(msg)
            log.warning("live waist tracker: %s", msg)

    def _frame_pending(self) -> bool:
        return self._declared is not None  # B108: the declared frame's check is pending

    def _frame(self, t: np.ndarray, v: np.ndarray):
        if self._declared is not None:
            self._check_declared(t, v)
        if self._proc is None:
            return self._hold(t, v)
        return t, v

    def _held_size(self) -> int:
        return self._held.size() + self._chk.size()

    def _no_frame_at_end(self) -> None:
        if self._held.t:
            tt = np.concatenate(self._held.t)
            msg = (f"no walking to track: no axis frame given and the {tt[-1] - tt[0]:.0f} s pushed do not fix "
                   "one (decision W65): 0 steps, 0 m; pass frame= if the unit did walk")
            self.warnings.append(msg)
            log.warning("live waist tracker: %s", msg)
            self._held.clear()


__all__ = ["WaistTracker", "LiveStep", "FRAGMENT_CONTEXT_STEPS", "LOOKAHEAD_ROWS"]
