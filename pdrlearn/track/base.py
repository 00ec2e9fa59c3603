"""The common result type of every tracking pipeline and the pipeline registry."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

import pandas as pd

from pdrlearn.errors import DataError, check_keyword_names
from pdrlearn.io.session import session_entry
from pdrlearn.plugins import Registry

#: Per-step table columns every pipeline fills (others may be added).
STEP_TABLE_COLUMNS = ("start_s", "end_s", "event_s", "length_m", "heading_rad", "dz_m")
#: Trajectory columns: local ENU metres (x east, y north, z up); lat/lon when a start coordinate is given.
TRAJECTORY_COLUMNS = ("t", "x", "y", "z")


@dataclass
class TrackResult:
    """Output of a tracking pipeline.

    Attributes
    ----------
    steps : one row per detected step: ``start_s``, ``end_s``, ``event_s`` (s), ``length_m`` (m, signed
        horizontal displacement along the heading; negative only with a ``backward`` direction class, decision
        L65), ``heading_rad`` (ENU, 0 = east, counter-clockwise), ``dz_m`` (altitude change), and where known
        ``terrain``, ``direction``, ``length_class``, ``confidence``; the foot pipeline adds the gait columns
        ``stride_time_s``, ``cadence_spm``, ``speed_mps``, ``turn_angle_rad`` (decision L66) and ``gap_s``
        (L67; docs/localization.md "steps.csv columns").
    trajectory : ``t``, ``x``, ``y``, ``z`` (+ ``lat``, ``lon``) — position after each step (first row = start);
        every registered pipeline adds ``pos_sigma_m``, the 1-sigma radius of the horizontal position (m,
        decision L128, :mod:`pdrlearn.track.position_sigma`).
    info : pipeline name, method, parameters used, warnings (e.g. "no model: M3 unavailable").
    tracked : ``(name, folder)`` of the session a registered pipeline tracked (decision B181; None: not known),
        which :meth:`summary` checks.
    """

    steps: pd.DataFrame
    trajectory: pd.DataFrame
    info: dict = field(default_factory=dict)
    tracked: tuple[str, str | None] | None = field(default=None, repr=False, compare=False)

    @property
    def distance_m(self) -> float:
        from pdrlearn.kernels.travel import walked_distance

        # decision E316: the one sum of the walked distance (|length_m|), the lean runtime's too
        return walked_distance(self.steps["length_m"].to_numpy(float)) if len(self.steps) else 0.0

    def turns(self, bouts: pd.DataFrame | None = None) -> pd.DataFrame:
        """Decision W330: this track's turns.csv (:func:`pdrlearn.track.clinical.turn_table`) as ``pdrlearn track``
        writes it: a lower-back track's turns timed, split and angled by its yaw-rate turns (``info["yaw_turns"]``,
        L210, W328), which ``turn_table(result.steps)`` alone does not see; ``bout`` numbered by ``bouts`` (None: the
        track's detected bouts, :func:`pdrlearn.track.bouts.detected_bouts`)."""
        from pdrlearn.track.bouts import detected_bouts
        from pdrlearn.track.clinical import turn_table

        return turn_table(self.steps, detected_bouts(self.steps) if bouts is None else bouts,
                          yaw_turns=self.info.get("yaw_turns"), gap_turns=self.info.get("waist_gap_turns"))  # L701

    def summary(self, session, *, pipeline: str | None = None) -> dict:
        """The dict ``pdrlearn track`` writes as ``summary.json`` for this track of ``session``: distance,
        errors against the session's ground truth (``distance_error_pct``, ...), gait speed and cadence
        (``gait_speed_mps``, ``median_cadence_spm``), ``session``, ``input_dir``, ``pipeline``, ``info``
        (:func:`pdrlearn.track.evaluate.track_summary`; decision C14). A ``session`` other than the one tracked
        (another name or folder) is one :class:`DataError` line (decision B181: it was scored silently)."""
        from pdrlearn.track.evaluate import track_summary

        given = session_identity(session)
        if self.tracked is not None and given is not None and given != self.tracked:
            raise DataError(f"summary: this track is of session {self.tracked[0]!r} ({self.tracked[1] or 'in memory'})"
                            f", not of {given[0]!r} ({given[1] or 'in memory'}); pass the session you tracked")
        import dataclasses

        # the caller's track untouched (as write_track): the summary records the declared incline in its info (L442)
        return track_summary(dataclasses.replace(self, info=dict(self.info)), session, pipeline=pipeline)

    def plot(self, session=None, *, out=None, title: str = "", dpi: float | None = None):
        """Decision E89: the plan view of this track (``path.png`` of ``pdrlearn track``; with ``session``, its
        ground truth too), a ``matplotlib.figure.Figure`` (shown by a notebook cell; the matplotlib backend left
        as it was, E88); ``out``: also saved there (.png / .pdf / .svg, ``dpi``). Several tracks in one
        figure: :func:`pdrlearn.track.plot_paths` / :func:`pdrlearn.track.path_figure`."""
        from pdrlearn.plots import save_atomic
        from pdrlearn.track.plots import path_figure

        label = f"{self.info.get('pipeline', 'track')} {self.info.get('method', '') or ''}".strip()
        _, fig = path_figure({label: self}, session=session, title=title)
        if out is not None:
            save_atomic(fig, out, dpi=dpi)
        return fig


def session_identity(session) -> tuple[str, str | None] | None:
    """``(name, resolved folder or None)`` of a session (decision B181), None for anything else."""
    import os

    name = getattr(session, "name", None)
    if not isinstance(name, str):
        return None
    folder = getattr(session, "folder", None)
    return name, (os.path.realpath(folder) if folder is not None else None)


Pipeline = Callable[..., TrackResult]


def _load_builtin_pipelines() -> None:
    import pdrlearn.track.pipelines  # noqa: F401  (each module registers its pipelines)


def _wrap(name: str, fn: Pipeline) -> Pipeline:
    """``fn`` as every pipeline runs: the session checked once at the entry point (decisions B49/B51), the
    track's ``pos_sigma_m`` added (decision L128) and every warning of the session's reading and of the tracking
    in ``info["warnings"]`` (decision E154: most were logged only)."""
    @functools.wraps(fn)
    def with_sigma(session, *args, **kwargs) -> TrackResult:
        from pdrlearn.track.position_sigma import add_position_sigma
        from pdrlearn.warning_lines import captured_warnings, merged_warnings

        with captured_warnings(echo=True) as logged:
            result = fn(session, *args, **kwargs)
        if isinstance(getattr(result, "info", None), dict):  # decision E154
            result.info["warnings"] = merged_warnings(result.info.get("warnings") or [],
                                                      [*getattr(session, "_read_warnings", []), *logged],
                                                      getattr(session, "wheres", None))  # B359 (R1)
            from pdrlearn.io.plasys import clipped_shares

            result.info["clipped_share"] = clipped_shares(session)  # decision B456: summary.json's clip figures
        add_position_sigma(result, session)  # decision L128: every pipeline's track gets pos_sigma_m
        result.tracked = session_identity(session)  # decision B181: summary() checks the session it is given
        return result

    return session_entry(with_sigma, caller=f"pipeline '{name}'")


def _adapt_pipeline(name: str, fn) -> Pipeline:
    if not callable(fn):
        raise DataError(f"pipeline '{name}': {fn!r} is not a function fn(session, **options) -> TrackResult")
    return fn if getattr(fn, "_pdrlearn_pipeline", False) else _wrap(name, fn)


#: Pipeline name -> function (a dict to read). Reading it first imports every module that registers a
#: built-in pipeline (:mod:`pdrlearn.track.pipelines`) and the installed plug-ins (entry point group
#: ``pdrlearn.pipelines``, decision E82), so ``list(PIPELINES)`` names them all from the first access; a built-in
#: name is not replaced silently (decision E81).
PIPELINES = Registry("pipeline", "pdrlearn.pipelines", load_builtins=_load_builtin_pipelines,
                     adapt=_adapt_pipeline, helper="register_pipeline")


def register_pipeline(name: str, *, replace: bool = False) -> Callable[[Pipeline], Pipeline]:
    """Decorator: ``@register_pipeline("waist-pll")`` on ``fn(session, **options) -> TrackResult``. A built-in
    name (``plasys``, ``waist-pendulum``, ``waist-pll``) is refused unless ``replace=True`` (decision E81); an
    installed package can declare its pipeline as an entry point of group ``pdrlearn.pipelines`` instead
    (docs/extending.md)."""

    def deco(fn: Pipeline) -> Pipeline:
        wrapped = _wrap(name, fn)
        wrapped._pdrlearn_pipeline = True
        PIPELINES.register(name, wrapped, replace=replace)
        return wrapped

    return deco


def keyword_names(fn: Callable, *, exclude: Iterable[str] = ()) -> list[str]:
    """The keyword arguments of ``fn`` (its keyword-only and positional-or-keyword parameters after the first,
    the session), without ``**`` catch-alls and the names in ``exclude``."""
    params = list(inspect.signature(fn).parameters.values())[1:]
    kinds = (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    return [p.name for p in params if p.kind in kinds and p.name not in set(exclude)]


def check_keywords(pipeline: str, given: Mapping | Iterable[str], valid: Iterable[str]) -> None:
    """Raise ``TypeError`` (as Python does for an unknown keyword) when ``given`` holds a name that is not in
    ``valid``, naming it, the closest valid name (``difflib``) and every valid one (decision L43;
    :func:`pdrlearn.errors.check_keyword_names`, shared with the step detectors)."""
    check_keyword_names(f"{pipeline} pipeline", given, valid)


def resolve_pipeline(name: str, session, params=None) -> str:
    """``"auto"`` (the CLI default, decision L36): ``plasys`` for a session with a foot unit, else
    ``waist-pendulum`` (the lower-back pipeline with the best step F1 and distance on the real recordings,
    docs/waist.md); on a session with a waist unit, a lower-back parameters file ``params`` (W474,
    :func:`lower_back_params`) chooses the lower back (:func:`lower_back_choice`, the CLI's own rule, W478); any
    other name is returned as given."""
    if name != "auto":
        return name
    if lower_back_params(session, params):  # decision W474 (W478: the API makes the CLI's choice)
        return lower_back_choice(session, params, "params")
    if session.has("fAccelerometer") or not session.has("wAccelerometer"):
        return "plasys"
    warn_foot_unit_ignored(session, "tracking the waist")  # decision B204
    return "waist-pendulum"


def waist_params_file(par) -> tuple[bool, str | None]:
    """Whether ``par`` (``--params``' parsed JSON, or a :class:`~pdrlearn.waist.params.WaistParams`) is a lower-back
    parameters file (``pdrlearn calibrate``'s schema or a WaistParams key), and the lower-back pipeline it names (None
    when it names none): what the CLI's ``_refuse_waist_params`` refuses for plasys and what chooses the lower back
    under --pipeline auto (W474)."""
    from dataclasses import fields

    from pdrlearn.waist.params import SCHEMA, WaistParams

    if isinstance(par, WaistParams):
        return True, par.pipeline if par.pipeline in WAIST_PIPELINES else None
    if not isinstance(par, dict):
        return False, None
    # W471's "detector" is too common a word to call a file a waist one
    waist_keys = {f.name for f in fields(WaistParams)} - {"notes", "source", "options", "detector"}
    if par.get("schema") != SCHEMA and not waist_keys & set(par):
        return False, None
    return True, par.get("pipeline") if par.get("pipeline") in WAIST_PIPELINES else None


def lower_back_params(session, params) -> bool:
    """Decision W474: ``params`` is a lower-back parameters file and ``session`` has a waist unit, so ``--pipeline
    auto`` (and ``get_pipeline("auto")``, W478) tracks the lower back with it."""
    return bool(session.has("wAccelerometer") and waist_params_file(params)[0])


def lower_back_choice(session, params, chosen_by: str) -> str:
    """Decisions W474 / W407: the lower-back pipeline ``--pipeline auto`` takes when ``chosen_by`` (a lower-back
    option: ``--params FILE``, ``--length-model``, a waist ``--detector``) asks for the lower back - the pipeline
    ``params`` was calibrated for, else waist-pendulum - with one warning when the foot unit is left untracked."""
    from pdrlearn.waist.params import WaistParams

    if isinstance(params, WaistParams):
        params = {"source": params.source, "pipeline": params.pipeline}
    pipeline = calibrated_pipeline("waist-pendulum", params)
    if session.has("fAccelerometer"):  # decision W474: the foot unit left untracked is said, in one line
        import logging

        logging.getLogger("pdrlearn.cli").warning(
            "%s: %s chose the lower-back pipeline %s (--pipeline auto): the foot unit is not tracked; give "
            "--pipeline plasys to track the foot, or --pipeline %s to choose the lower back yourself (decision "
            "W474)", session.where, chosen_by, pipeline, pipeline)
    return pipeline


#: decision W407: the lower-back pipelines `--pipeline auto` may take from a calibration file's "pipeline"
WAIST_PIPELINES = ("waist-pendulum", "waist-pll")


def calibrated_pipeline(chosen: str, params) -> str:
    """Decision W407: ``--pipeline auto``'s lower-back choice ``chosen`` (:func:`resolve_pipeline`) replaced by the
    lower-back pipeline the parameters (``--params``' parsed JSON) were calibrated for (``"source": "calibrated"``,
    ``"pipeline"`` one of :data:`WAIST_PIPELINES`), so a waist-pll calibration tracks with waist-pll instead of
    leaving waist-pendulum at its defaults; ``chosen`` otherwise (a foot pipeline, or no such file)."""
    if chosen not in WAIST_PIPELINES or not isinstance(params, dict) or params.get("source") != "calibrated":
        return chosen
    named = params.get("pipeline")
    return named if named in WAIST_PIPELINES else chosen


def foot_unit_ignored(session, doing: str) -> str | None:
    """Decision B204: the line when a session has foot files but no fAccelerometer.csv, so that the choice
    between the units (``auto``) leaves the foot unit out and does ``doing`` with the waist; None otherwise."""
    if session.has("fAccelerometer") or not session.has("wAccelerometer"):
        return None
    foot = [n for n, st in session.streams.items() if n.startswith("f") and len(st)]
    if not foot:
        return None
    from pdrlearn.io.sensors import SENSORS

    files = ", ".join(SENSORS[n].filename for n in foot)
    return (f"fAccelerometer.csv missing: foot unit ignored, {doing} (the foot unit's {files} are not used "
            "without it; restore fAccelerometer.csv to track the foot, or remove the foot files; decision B204)")


def warn_foot_unit_ignored(session, doing: str) -> None:
    """Decision B204: log :func:`foot_unit_ignored`'s line (a warning: ``track-all`` lists it with the session)."""
    line = foot_unit_ignored(session, doing)
    if line:
        import logging

        logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, line)


def get_pipeline(name: str) -> Pipeline:
    """The tracking pipeline ``name``: a function ``fn(session, **options) -> TrackResult``.

    Pipelines (``list(PIPELINES)``; ``help(get_pipeline("plasys"))`` documents each option):

    - ``"plasys"`` (foot unit, + waist): PLASYS M1/M2/M3 (thesis ch.7). Keyword arguments: ``method``
      (``"auto"`` default as ``pdrlearn track``: M3 with ``model``, else the M3 engine without class rules;
      ``"M1"``, ``"M2"``, ``"M3"``), ``model`` (model directory, loaded model or ``"oracle"``), ``start``
      ((lat, lon[, alt]), as ``--start``: decision L157), ``params`` (FootDisplacement settings), ``steps`` (a
      string: ``"detector"``, ``"stance"`` or
      ``"labels"``, the session's steps table), ``heading``, ``initial_heading``,
      ``bounds``, ``bounds_scale``, ``down_mode``, ``min_confidence``, ``align``, ``rules`` (``"bayes"`` /
      ``"thesis"``), ``fused_tau_s``, ``streaming``, ``distance_gain``, ``calibration``, ``gap_yaw``, ``waist_gap_yaw``,
      ``waist_bridge`` (decisions L91 / L99: streamed on by default), ``warn_out_of_domain``, ``toe_off``
      (decision L73: the toe-off / stance / swing columns, offline), ``hard_iron_fit`` (decision L84),
      ``compass_sinusoid`` (decision L770: the waist compass's direction sinusoid off before the fused window),
      ``forward_yaw`` (decision L796: the waist compass turned by D10's measured mount yaw; default on),
      ``forward_yaw_gate`` (decision L801: not when W435's power ratio or W434's force_frame distrusts it; off),
      ``cycling``
      (decision E304: False judges no stride pedalling, as ``--no-cycling``),
      ``contacts`` (decisions E49-E51: with ``streaming``, each stride's initial contact and stride time),
      ``drop_neighbour`` (decisions L167, E101: with ``streaming``, a stride across dropped foot samples takes the
      length and height change of the stride before it; off by default), ``ignore_force`` (decision L366: offline,
      the foot IMU alone, the force sensors left out; without it L365 checks them against the IMU),
      ``altitude`` (decision L154: ``"foot"``, the default, or ``"fused"`` with the waist barometer; an option),
      ``waist_bias`` (decision W126: remove the waist gyroscope bias read at rest when W105 fires; on by default, W423),
      ``compass_fallback`` (decision L226: with heading ``"fused"``, follow the waist gyroscope turned to the compass
      by one constant offset when L182's compass check warns; on by default, L227), ``fallback_drift`` (decision L266:
      that offset drifts linearly in time, the waist gyroscope's rate bias; on by default, L265), ``first_walk``
      (decisions E215, E222: with ``streaming``, a foot-headed heading turned once by the first walk's direction at
      its end; off by default), ``transfers`` (decisions W418, W439: offline, time the chair transfers and TUG from
      the waist unit; on by default, the distance calibration turns it off), ``gated_level_dz`` (decisions L189,
      L206, L550: with ``streaming``, True / ``"summed"`` give M3 strides whose terrain class the gate dropped L39's
      level rule; off by default), ``fused_climb`` (decisions L564, L565, L586: with ``altitude="fused"`` and
      without a terrain model, a stride inside a barometric climb is fused with the foot's own height; off by
      default), ``fused_straight`` (decisions L589, L609: with heading ``"fused"``, the waist-to-foot offset fitted on
      straight strides only, so turns on the spot do not pull it; on by default since L609, False = L17's offset
      over every stride), ``ride_vibration`` (decisions L615, L616: offline, with a waist barometer, a ride or a long
      standstill whose foot unit vibrates is a vehicle; on by default, ``{"options": {"ride_vibration": false}}``),
      ``foot_ramps`` (decision L717: without ``altitude="fused"`` and without terrain classes, ramps.csv and the ramp
      strides from the foot's own L39 heights; off by default, its rule was not met).
    - ``"waist-pendulum"`` (lower back): initial contacts from the waist acceleration, inverted-pendulum
      step length; ``"waist-pll"``: PLL steps, step length linear in the step frequency. Keyword arguments:
      ``params`` (``pdrlearn calibrate``'s PARAMS.json path / dict), ``start``, ``realtime``
      (waist-pendulum's causal variant), ``heading``, ``refine_ic``, ``initial_heading``, ``resolve_signs``,
      ``integrate_stops``, ``turn_factor``, ``rhythm``, ``merge_fragments``, ``length_smoothing``, ``relative_gate``,
      ``stairs_length`` (decision W91, off; ``"climbs"``: W108's climbs only, W156), ``stairs_climb`` (decision
      W108, off: stairs only inside a climb above the barometer's still noise, z only on stairs), ``slow_turn_rps``
      (decision W82, off), ``gentle_curves`` (decision W543: runs of same-sign strides kept),
      ``gentle_rest_bias`` (decision W544: W543's test less W105's rate at rest, offline),
      ``pelvic_rhythm_veto`` (decision W440, off; ``"slow"``: only below 70 steps/min -- a
      contact sooner than 0.6 of the pelvic gyroscope's local step period is dropped),
      ``slow_min_step`` (decisions W591-W593, off; ``"slow"``: below 70 steps/min the offline waist-pendulum's
      shortest step is 0.75 of the pelvic gyroscope's median step),
      ``max_tilt_deg`` (decision W102, off: a trunk-tilt gate on the contacts), ``sit_veto`` (decision W104:
      no contact around a sit-to-stand's trunk-flexion peak; ``"rhythm"``: W109, sparing left/right step pairs;
      ``"alternation"``: W180, also an undecided contact between two same-side contacts of its sequence;
      ``"opposite"``, the offline default since W185 (off with ``realtime``): W184, instead an undecided contact
      between two opposite-side contacts of its sequence),
      ``pause_steps`` (decision W111, off: a step over 1.5 local periods keeps one period's length;
      ``"progression"``: W122, a step with a standstill in it keeps at most the trunk's travel over it;
      ``"standing"``, the offline default since W134: W122 only for a still run of half a local step period, not a
      walk's first or last step),
      ``vault_veto`` (decision W119, off: no contact whose step vaults the pelvis under a quarter of its neighbours';
      ``"turns"``: W127, sparing a step that turns the pelvis by more than 15 deg),
      ``contact_shift`` (decision W131, on: every kept contact judged once more by W23's weight-shift test with the
      side read at the contact, turns spared; offline only),
      ``realtime_contact_shift`` (decision W166, off: W131's test inside each realtime decision window, for
      ``realtime`` and the live trackers; measured and not adopted),
      ``weak_fill`` (decision W148, off: a weak step on the decided alternating side where the alternation and the
      local rhythm ask for one; offline only),
      ``parity_fill`` (decision W152, off: a contact without a vertical maximum between two kept contacts of one
      decided side about two local periods apart, at the opposite side's lateral-sway extreme; ``"within"``: only
      inside one walking sequence of the other contacts, decision W159; offline only),
      ``side_at_contact`` (decision W235, off: the offline detector's sequence rules read each candidate's W20 side at
      its initial contact instead of at its vertical maximum; offline only),
      ``fast_fill`` (decision W242, off: one contact where a gap between two kept contacts has room for exactly one
      step and the vertical acceleration low-passed at twice the cut-off has a maximum of its own there;
      ``"outside_freeze"``: none inside an episode of the freeze index, W213, decision W255; offline only),
      ``ap_above_mean`` (decisions W29 / W265, off: the IC is the last local AP maximum in W3's 0.25 s window above the
      AP acceleration's 2 s mean, if there is one; offline only),
      ``turn_bridge`` (decisions W374 / W375 / W384 / W385, ``"side"``: the motion gate is also open over a yaw-rate
      turn with walking within 1.5 s before and after it, so a turn on the spot's weak steps are candidates, and of the
      contacts that adds only those whose side is decided and alternates are kept; ``true``: all of them; offline
      only),
      ``gait_check`` (decision W140, off: with calibrated params, warn when the walk's median cadence is outside
      x0.75-x1.33 of the calibration walks'),
      ``speed_check`` (decision W211, on: with calibrated params, warn when the walk's median cadence is more than 10 %
      outside the calibration walks' cadence range, i.e. another walking speed),
      ``pll_check`` (decision W186, off: an uncalibrated offline waist-pll track warns when it reads over 1.5 x the
      pendulum model's distance on the same session),
      ``pll_slow_check`` (decisions W289 / W290, off: the same at over 1.25 x while the pendulum reading is under
      1.0 m/s, a slow walker's),
      ``pll_slow_cadence_check`` (decisions W313 / W314, on: the same at over 1.25 x while the pendulum reading's
      median cadence is under 100 steps/min),
      ``short_step_check`` (decision W207, off: an uncalibrated offline waist-pendulum track warns when its median
      step is under half the comfortable step of the stature, a shuffle the pendulum reads long),
      ``integrate_end`` (decision W187, off: the last step's heading takes the yaw turned on the spot after it, to
      the recording's end; offline only),
      ``stand_veto`` (decisions W218 / W219, ``"walking"``: a run of contacts whose median vertical bounce is under
      1/3 of the walking stretches' (at least 4 regular strides on alternating sides) is no walking unless walking
      strides lie within 3 s before and after it, W198, and a stretch's walk is never dropped; offline
      ``waist-pendulum`` only; ``"adjacent"`` W198 (W199's default, withdrawn by W217), ``true`` W190 without the
      sparing, ``"turns"`` W191, ``"alternation"`` W196, false off),
      ``contact_model`` (decision W204, off: ``"learned"`` keeps only the contacts a learned, calibrated re-scorer
      gives p >= 0.5, W203; offline ``waist-pendulum`` only),
      ``freeze_veto`` (decision W215, off: the offline lower-back contacts inside a freeze episode of the freeze
      index, freezes.csv, W213, are dropped, W214; implies ``freeze_index``),
      ``rhythm_warning`` (decisions W338 / W339, off: without a foot unit, one warning line per stretch of lower-back
      contacts whose vertical stride regularity is under 0.4, a vehicle's bounce; W339's rule was not met),
      ``trunk_rhythm_veto`` (decision W550, off: offline, a run of lower-back contacts with no 4 consecutive step
      intervals within +-50 % of its median is left out - trunk jerks of involuntary movements, S114; its rule was
      not met; the runs are named in a warning line either way from 4 contacts on),
      ``foot_rest_veto`` (decisions W336 / W337, on: with a foot unit, a run of 4 or more lower-back contacts none
      within 1 s of a foot stride that swings the foot is dropped, a standing passenger's bounce in a vehicle; the
      runs are named in a warning line either way; decision W547: a foot unit `--units` left out is not read),
      ``pll_edge_lock`` (decisions W356 / W357: true makes waist-pll keep a gated run's first and last PLL peak only
      when the loop is locked at it, phase error within 45 deg; a free-running peak at a bout's edge is no step, W345;
      ``"trailing"`` judges only the run's last peak, decision W358; ``"walk-end"`` (W368) only a
      last peak where the walk ends, W367; ``"walk-edges"``, the default since W373, also a first peak where the walk
      starts after it, W372; false keeps every gated peak),
      ``freeze_index`` (decision W216, off: the lower back's freeze index, W213: freezes.csv and ``n_freezes`` /
      ``freeze_time_s``, null when off; foot tracks always compute theirs),
      ``realtime_sit_veto`` (decision W201, off: a realtime track applies the sit veto causally, each contact
      decided 3.25 s after it with the upright of the walking contacts seen so far, W200),
      ``pause_ride`` (decision W231, on: a lower-back pause longer than 30 s keeps its barometric change only where
      it changes 1.5 m or more within 30 s, a lift or escalator ride; drift across a rest is left out and warned),
      ``rest_bias`` (decision L296, on: across a rest over 60 s the waist gyroscope's bias is taken from the rest's
      own still samples, which add no heading),
      ``lying_heading`` (decisions W269 / W271, on: while lying in bed (W222's lying, 10 s or more) the gyro heading
      turns by the yaw of the trunk's long axis about gravity only, not by the vertical rate of rolling over;
      offline ``integrate_stops`` gyro heading only),
      ``rest_frame`` (decisions W285 / W287, off: each harmonic step direction less the AHRS frame's turn about the
      vertical over the rests over 60 s before it, the bias integral L296's still samples give; harmonic headings
      only; measured, not adopted: W286's rule failed on the last step's own heading error),
      ``pivot_steps`` (decision W150, off: a step whose pelvis turns 45 deg or more keeps at most the chord of its
      turn on a 0.2 m radius; both pipelines),
      ``cadence_law`` (decision W240, off: a calibrated waist-pendulum step times sqrt(SL(f) / SL(f_cal)) of seed
      000's walking line, the calibration walks' median cadence ``f_cal``; ``"steady"``, decision W261: only on steady
      walking steps; not in the live trackers),
      ``detector`` (decision E85: a waist step detector's contacts), ``gate`` (decision W473: W4's walking gate on
      those contacts), ``length_model`` (decision E84: a registered
      step-length model, docs/extending.md) (:func:`pdrlearn.track.waist.track_waist`); ``model`` is accepted and
      unused. With ``wBarometer`` the track's altitude is the barometer's (W89); without, one warning (W90).

    ``"auto"`` (decision E182): the one ``pdrlearn track --pipeline auto`` chooses for each session
    (:func:`resolve_pipeline`); its options are those of the pipeline chosen.

    An unknown keyword raises ``TypeError`` naming the closest valid one (decision L43); an unknown
    ``name`` raises :class:`~pdrlearn.errors.DataError` listing the pipelines. Warnings (e.g. "no model")
    are ``logging`` records of the ``pdrlearn`` logger (also in ``result.info["warnings"]``), not Python
    ``warnings``: ``logging.getLogger("pdrlearn").setLevel(logging.ERROR)`` silences them. They print on stderr
    only through a handler you configure (``logging.basicConfig()``): with none, Python's last-resort printer does
    not print a pipeline's warnings (decisions B350, E179 amended), read ``result.info["warnings"]``.
    """
    if name == "auto":  # decision E182: the CLI's --pipeline auto, chosen per session by resolve_pipeline
        return track_auto
    try:
        return PIPELINES[name]
    except KeyError:
        raise PIPELINES.unknown(name) from None


def track_auto(session, **options) -> TrackResult:
    """Decision E182: ``get_pipeline("auto")``: the pipeline ``pdrlearn track --pipeline auto`` chooses for
    ``session`` (:func:`resolve_pipeline`, the CLI's own choice: ``plasys`` with a foot unit, else
    ``waist-pendulum``), called with ``options``; ``result.info["pipeline"]`` names the one chosen, and the choice's
    warning (B204: foot files without fAccelerometer.csv) is in ``result.info["warnings"]``."""
    from pdrlearn.warning_lines import captured_warnings, merged_warnings

    with captured_warnings(echo=True) as logged:
        name = resolve_pipeline("auto", session, options.get("params"))  # W478: W474's rule, the CLI's own
    result = get_pipeline(name)(session, **options)
    if logged and isinstance(getattr(result, "info", None), dict):
        result.info["warnings"] = merged_warnings(result.info.get("warnings") or [], logged,
                                                  getattr(session, "where", None))
    return result
