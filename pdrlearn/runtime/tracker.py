"""Streaming tracker: ``Tracker(bundle).push(samples) -> new steps`` with bounded state.

Samples arrive per sensor (``{"fAccelerometer": (t, values), ...}``) or as Bluetooth-protocol
measurements (objects with ``t``, ``sensor``, ``values``). The tracker keeps at most
``buffer_s`` seconds per sensor, detects foot stances online, and for every stance-to-stance step:
builds the step window, classifies it with each task's model, estimates its displacement with the
PLASYS rules and updates heading and position.

Displacement, heading and position (decision E6, docs/decisions/export.md) come from the stride kernel
:mod:`pdrlearn.kernels.stride`, the same one ``pdrlearn track --streaming`` (plasys pipeline) runs: the
stride's levelled, gravity-removed foot acceleration at the unit's own rate integrated twice with a
zero-velocity update at both stances (thesis ch.7.2), the M3 rules (thesis eq. 61, ch.7.2.2), heading
= previous heading + the integral of the levelled vertical rate over the stride (``heading_source``).
"""

from __future__ import annotations

import functools
import logging
import math
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError, InternalError, ModelError, VerticalAxisError
from pdrlearn.kernels import carried_yaw as _carried_yaw
from pdrlearn.kernels import distance as _distance
from pdrlearn.kernels import first_walk as _first_walk
from pdrlearn.kernels import lull as _lull
from pdrlearn.kernels import pedal as _pedal
from pdrlearn.kernels import relative_length as _relative_length
from pdrlearn.kernels import sideways as _sideways
from pdrlearn.kernels import spin as _spin
from pdrlearn.kernels import stop_bias as _stop_bias
from pdrlearn.kernels import turn_length as _turn_length
from pdrlearn.kernels.align import MAX_CLOCK_DRIFT
from pdrlearn.kernels.altitude_check import judged_terrain
from pdrlearn.kernels.backward import signed_chord
from pdrlearn.kernels.bayes import DEFAULT_MIN_CONFIDENCE, SIGMA_REL, check_rules, confident_one
from pdrlearn.kernels.clipping import clipped_axes
from pdrlearn.kernels.contact import force_at, stride_contact, stride_times
from pdrlearn.kernels.counter_wrap import live_wrap
from pdrlearn.kernels.distance import (
    applicable_calibration,
    apply_level_gain_one,
    calibrated_stride_sd,
    summed_level_step,
    unclassed_level_dz_one,
)
from pdrlearn.kernels.fixes import wrap_angle
from pdrlearn.kernels.frames import DIRECTIONS
from pdrlearn.kernels.gait_range import running_stride, streamed_slow_line
from pdrlearn.kernels.gait_values import cadence_speed
from pdrlearn.kernels.gap_compass import GapCompass
from pdrlearn.kernels.gaps import MIN_GAP_S, drop_stride_disp, streamed_drops_line, waist_gap_turn
from pdrlearn.kernels.order import first_out_of_order, reorder_hint, repeated, repeats_dropped_line
from pdrlearn.kernels.stride import (
    DEFAULT_DOWN_MODE,
    DOWN_MODES,
    FINE_AHEAD_S,
    FINE_PAD_S,
    GAP_YAW_MAX_S,
    HEADING_SOURCES,
    CycleGapLine,
    CyclePhase,
    StanceSegmenter,
    advance_xyz,
    fine_spec,
    headed_by_foot,
    impossible_stride_one,
    impossible_stride_warning,
    long_stop_span,
    long_stop_turn,
    no_length_bounds_warning,
    placement_offset,
    pre_l59_fallback,
    reversed_by_rules,
    stride_gap_yaw,
    stride_motion,
    stride_rules_one,
    travel_sign_one,
    waist_bridge_yaw,
    waist_end_phase_yaw,
    waist_forward_flip,
    waist_gap_from,
    waist_gap_max_s,
)
from pdrlearn.kernels.toeoff import LiveToeOff
from pdrlearn.kernels.window import (
    BOUNDARIES,
    BRIDGE_GAP_S,
    GAP_TOL_S,
    GROUP_STREAMS,
    GROUPS,
    TASK_COLUMNS,
    WINDOW_HEADINGS,
    PitchReference,
    _fill_channels,
    _unit_grid,
    available_groups,
    fill_step_window,
    hole_stride_dz,
    levelled_units,
    posture_warning,
    rest_boundaries,
    segment,
    stride_hole,
    stride_hole_line,
)
from pdrlearn.runtime.baro_check import BaroCheck
from pdrlearn.runtime.baro_fusion import FusedRows
from pdrlearn.runtime.bundle import Bundle, load_bundle, waist_only_hint
from pdrlearn.runtime.classify import StepGraph, TaskClassifier
from pdrlearn.runtime.clip_watch import ClipWatch, full_scales
from pdrlearn.runtime.clocks import SENSORS as CLOCK_SENSORS
from pdrlearn.runtime.clocks import ClockCheck, offset_remedy, waist_on_foot_clock
from pdrlearn.runtime.domain import DomainLog
from pdrlearn.runtime.fixes import FixInput
from pdrlearn.runtime.gait import StrideGait, gait_summary
from pdrlearn.runtime.guard import LIVE_STRIDES, FrozenFootWatch, FrozenWatch, MirrorWatch, UnitGuard
from pdrlearn.runtime.links import RepeatedLines, StartClocks, order_error, unit_of
from pdrlearn.runtime.rate_watch import DROP_FACTOR, RateWatch
from pdrlearn.runtime.replay import refuse_pushed_out_of_range
from pdrlearn.runtime.resample import InputStage, stopped_message
from pdrlearn.runtime.restart import drop_measured, restart_state
from pdrlearn.runtime.restart import resume as resume_state
from pdrlearn.runtime.samples import SENSOR_WIDTH, checked_samples
from pdrlearn.runtime.stream import FootLevelling, HeightLog, Ring, fill_resampled, foot_levelled, waist_entry
from pdrlearn.runtime.threads import OwnGuard, new_guard, one_call_at_a_time

log = logging.getLogger(__name__)
#: float64 in native byte order. Arrays made here share this dtype object (``is`` is the cheap test), but
#: unpickled arrays (multiprocessing queues, pickled sessions) carry an equal copy of it (``==``, decision E21)
_F64 = np.dtype(np.float64)
_ONE = (1,)
#: the window channels of the waist's levelled acceleration (computed only when one of them is needed, E17)
_WAIST_ACC = frozenset(("waist_acc_x", "waist_acc_y", "waist_acc_z"))
#: samples kept before a step's start: the window margin (1 s) and L31's gap-yaw look-back
_LOOK_BACK_S = max(1.0, GAP_YAW_MAX_S)
#: decisions E285 / E305: the rings :func:`~pdrlearn.kernels.carried_yaw.carried_yaw` reads, kept from CARRY_BACK_S
#: before the next stride's start; the other rings keep the foot's bound
_CARRIED_RINGS = ("wAccelerometer", "wGyroscope")
#: decision E30: an interval between two pushed samples of a stream longer than this (s) is a gap the tracker
#: warns about (once per gap); longer than B11's 1 s (``pdrlearn.track.gaps.MIN_GAP_S``) in a foot stream, the
#: stride across it moves 0 m, as offline ``pdrlearn track`` (plasys) does
GAP_WARN_S = BRIDGE_GAP_S  # 0.25 s; decision E36: a stride over such a gap is measured on the gap clock
GAP_LONG_S = 1.0
#: decision B141: a push whose timestamps jump further ahead of the stream's last sample than this (s) is refused
#: as a clock glitch (``Tracker(max_gap_s=...)``; ``math.inf`` accepts any gap, as ``pdrlearn run`` on a recording)
MAX_GAP_S = 60.0
#: decision E39: a stream's last value counts as held (E31's warning) when it is older than ``max_wait_s`` and than
#: this many of the stream's own sample intervals: one missed sample plus up to one interval of delivery delay
#: (E23's grace is one delivery interval; E30 calls 1.5 intervals a gap)
HELD_INTERVALS = 2.0
#: the foot streams whose long gaps zero the stride across them (offline plasys' ``foot_gaps``, B11)
_FOOT_GAP_STREAMS = frozenset(("fAccelerometer", "fGyroscope", "fForceA", "fForceB"))
#: the foot streams whose shorter gaps (over GAP_WARN_S) leave the stride across them without classes: B11 takes
#: the foot unit from a step overlapping a gap of its accelerometer or gyroscope
_FOOT_IMU = frozenset(("fAccelerometer", "fGyroscope"))

#: Default displacement parameters written into bundles. ``length_bounds_m``: the user's per foot-unit *stride*
#: class bounds, set by the export from the model (or --length-bounds); none by default (decision L59: a bundle
#: of a model without measured bounds skips the length rule, as ``pdrlearn track --model``, instead of the
#: thesis step bounds x 2 that an export before L59 wrote here, which clamp typical strides: L50).
DEFAULT_DISPLACEMENT = {
    "unit": "foot stride",
    "length_bounds_m": None,
    # decision L178: the thesis' eq. 61 norm is a down stride's path length, its horizontal part moves x/y ("norm3":
    # the norm itself, the thesis' placement)
    "down_mode": DEFAULT_DOWN_MODE,
    "stance_gyro_rad_s": 0.8,  # decision E7: stance = foot rate below this for >= min_stance_s
    "min_stance_s": 0.1,
    "stance_half_s": 0.3,
    "min_step_s": 0.3,
    "max_step_s": 3.0,
    "initial_heading_rad": 0.0,
    "heading_source": "auto",  # decision E6: "auto" (waist gyro when present, else foot), "foot", "waist-gyro"
    "max_wait_s": 2.0,  # longest wait for a late sensor before a step is processed (thesis: < 2 s delay)
    # decision L40 / E25: the class rules the runtime applies; since L41 offline M3's, "bayes" (L14) with the
    # 0.95 gate (L18), with the stride kernel's own gain (held-out users 11-20, mean |distance error| A-D
    # 0.65/0.99/1.50/1.24 -> 0.20/0.18/0.19/0.18 %, altitude on D 9.77 -> 2.21 %). "thesis" stays selectable;
    # a bundle without these keys (exported before E25) keeps "thesis" and no gate (LEGACY_RULES).
    "rules": "bayes",
    "min_confidence": 0.95,
}
#: the class rules of a bundle without ``rules`` / ``min_confidence`` (exported before decision E25)
LEGACY_RULES, LEGACY_MIN_CONFIDENCE = "thesis", 0.0


#: what the streamed stride rules do for a task without a class (decision C17, ``pdrlearn.track.plasys``)
_NO_CLASS_RULE = {"terrain": "the stride's raw height change", "direction": "the estimate's own sign",
                  "length": "no length clamp"}


def check_tasks(bundle: Bundle, tasks, methods) -> tuple[list[str], dict[str, str] | None]:
    """Decisions B137, B139: ``tasks`` (None: all the bundle's) and ``methods`` (task -> ``"method/unit"``, or a
    method alone as ``run --method`` takes it: :meth:`Bundle.method_unit`) as the bundle has them, else a
    one-line error naming the valid values: an unknown task (a typo, ``"terrian"``) was a raw KeyError in
    ``tasks`` and silently ignored in ``methods``, a method without its unit a raw unpacking error. Returns
    the task list - None resolved to the bundle's tasks here, once; an empty list stays empty: no task is
    classified, ``track --streaming``'s M2 (decision E291: ``tasks or all`` classified every task) - and the
    methods resolved to ``"method/unit"``."""
    have = list(bundle.tasks)
    if tasks is not None:
        tasks = [tasks] if isinstance(tasks, str) else list(tasks)
        bad = [t for t in tasks if t not in have]
        if bad:
            raise DataError(f"tasks={tasks}: bundle {bundle.path} has no {', '.join(map(str, bad))} classifier; "
                            f"its tasks: {', '.join(have)}")
    resolved = have if tasks is None else tasks  # decision E291: [] is no task, not every task
    if methods is None:
        return resolved, None
    out = {}
    for task, mu in methods.items():
        what = f"methods={{{task!r}: {mu!r}}}"
        if task not in have:
            raise DataError(f"{what}: bundle {bundle.path} has no {task} classifier; its tasks: {', '.join(have)}")
        if tasks is not None and task not in tasks:
            raise DataError(f"{what}: tasks={tasks} leaves {task} out; add it to tasks or drop it from methods")
        if not isinstance(mu, str) or not mu.strip():
            raise DataError(f"{what}: give \"method/unit\" or a method, e.g. {bundle.exported(task)[0]!r}")
        out[task] = bundle.method_unit(task, mu, what=what)
    return resolved, out


def check_units(bundle: Bundle, units) -> tuple[str, ...]:
    """The body units a tracker follows (decision E26), in the bundle's order: a subset of the bundle's units
    that holds the foot (the runtime detects steps on the foot gyroscope, decision E7); else a one-line error."""
    asked = tuple(dict.fromkeys(str(u).strip() for u in ([units] if isinstance(units, str) else units)))
    have = bundle.body_units
    missing = [u for u in asked if u not in have]
    if missing or not asked:
        raise DataError(f"units {','.join(asked) or '(none)'}: bundle {bundle.path} has no "
                        f"{', '.join(missing) or 'unit given'} models (its units: {', '.join(have) or 'none'}); "
                        f"give {' or '.join(have) if have == ('foot',) else 'foot or foot,waist'}")
    if "foot" not in asked:
        raise DataError(f"units {','.join(asked)}: the runtime detects steps on the foot unit's gyroscope, so it "
                        f"needs the foot unit (give foot or foot,waist); {waist_only_hint()}")
    return tuple(u for u in have if u in asked)


def tracked_units(bundle: Bundle, units, sensors) -> tuple[str, ...]:
    """The body units a :class:`Tracker` follows (decision E26): ``units`` checked (:func:`check_units`); without them
    the bundle's, or the foot unit alone when the declared ``sensors`` lack a sensor the waist unit needs (decision
    E32). Public for the lean replay, which needs them before its tracker (decision E357's ``--altitude``)."""
    if units is None and sensors is not None and "foot" in bundle.body_units and not set(
            bundle.sensors_of(("waist",))[0]) <= set(sensors):  # decision E32: the declared streams
        units = ("foot",)  # lack a sensor the waist unit needs: tracked as a foot-only session (E26)
        log.info("bundle %s: sensors %s lack the waist unit's: tracking the foot unit only (units=('foot',))",
                 bundle.path, ", ".join(sensors))
    return bundle.body_units if units is None else check_units(bundle, units)


def forward_vector(frame: dict) -> np.ndarray:
    """Sensor-frame vector pointing body-forward for a declared frame ``{"x": "forward", ...}``."""
    try:
        R = np.array([DIRECTIONS[frame["x"]], DIRECTIONS[frame["y"]], DIRECTIONS[frame["z"]]], float).T
    except KeyError as exc:
        raise DataError(
            f"axis frame {frame!r}: unknown or missing axis {exc}; use forward/backward/left/"
            "right/up/down for x, y and z"
        ) from None
    return R.T @ np.array([1.0, 0.0, 0.0])


@dataclass
class Step:
    """One step emitted by :meth:`Tracker.push` (times s, lengths m, angles rad, ENU position m)."""

    start_s: float
    end_s: float
    classes: dict[str, str] = field(default_factory=dict)
    proba: dict[str, dict[str, float]] = field(default_factory=dict)
    length_m: float = 0.0
    dz_m: float = 0.0
    heading_rad: float = 0.0
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    #: decision E30: the longest foot-stream gap (s, > 1 s) inside the stride; such a stride moves 0 m, keeps
    #: the heading and has no classes (0.0 = none)
    gap_s: float = 0.0
    #: decisions E49 / E50: the stride's initial contact (s; the force sensors' stance onset, else the foot
    #: accelerometer's impact, offline's rules; NaN: none, or ``Tracker(contacts=False)``, the default)
    event_s: float = math.nan
    #: decision E51: initial contact to the previous emitted stride's (s, L66/L80's rule; NaN: none) and the
    #: stride's own turn (rad: its heading unit's yaw over the stride, without the pivot before it)
    stride_time_s: float = math.nan
    turn_angle_rad: float = math.nan
    #: decision L106: the heading unit's turn between the previous stride and this one (rad: the pivot L31 / L61
    #: / L90 adds to the heading before the stride; ``turn_angle_rad`` + ``pivot_rad`` = the heading's change)
    pivot_rad: float = math.nan
    #: decision L97: the last-line guard (L94) moved this stride 0 m; it is no stride for the gait parameters
    #: (no stride time, cadence, speed or walking time, as a gap row)
    impossible: bool = False
    #: decision L243 (L228's column for the streamed tracks): the stride is the third or a later consecutive
    #: sideways stride of L219's rule (60-120 deg from the foot's facing, over 0.15 m), decided when it ends; no
    #: steady forward stride for the CVs and the straight speed (the run's first two strides stay False)
    sideways: bool = False
    #: decision E319: the stride's displacement to the left of the foot's facing at its start (m; negative to the
    #: right; NaN on a gap or posture row): a side step's side (steps.csv travel left / right)
    lateral_m: float = math.nan
    #: decision E325: why the stride is not reliable, decided when it is emitted: ``"clipped"`` (a foot IMU sample
    #: inside it is clipped, B77 / B311 / B456's kernel), ``"running"`` (L95 / W144's "looks like running" on the
    #: stride's own cadence and speed); () for a reliable stride, a gap row or a zeroed (L94) stride
    flags: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        """The step as one row of a steps table: the classes under their steps.csv columns (``terrain``,
        ``direction``, ``length_class``; decision B142: ``length`` before), ``p_<task>_<class>``, the numbers;
        ``heading_rad`` wrapped to [-pi, pi) as steps.csv has it (decision E87; the attribute
        :attr:`heading_rad` stays unwrapped, the heading the track integrates)."""
        return {
            "start_s": self.start_s,
            "end_s": self.end_s,
            "event_s": self.event_s,  # decision E49
            **{TASK_COLUMNS.get(t, t): c for t, c in self.classes.items()},  # B142: length -> length_class
            **{f"p_{t}_{c}": v for t, p in self.proba.items() for c, v in p.items()},
            "length_m": self.length_m,
            "dz_m": self.dz_m,
            "heading_rad": float(wrap_angle(self.heading_rad)),  # decision E87: as steps.csv (E43)
            "x": self.x,
            "y": self.y,
            "z": self.z,
            "stride_time_s": self.stride_time_s,  # decision E51
            "turn_angle_rad": self.turn_angle_rad,
            "pivot_rad": self.pivot_rad,  # decision L106
            "impossible": self.impossible,  # decision L97
            "gap_s": self.gap_s,  # decision E37: pdrlearn run's steps.csv
            "sideways": self.sideways,  # decision L243
            "lateral_m": self.lateral_m,  # decision E319
        }


def enu_start(start, start_enu_m) -> np.ndarray:
    """Decision L159: the tracker's start position, ``start_enu_m=(x, y, z)`` in ENU metres (the keyword named for
    its meaning; ``start=`` is the older name of the same, kept). Both, or not three numbers, is one
    :class:`DataError` line: a geodetic ``(lat, lon)`` is not a position here (``pdrlearn run --start`` and the
    pipelines' ``start=`` take it)."""
    if start is not None and start_enu_m is not None:
        raise DataError("Tracker: give start_enu_m=(x, y, z) (ENU metres) once; start= is its older name")
    given, name = (start_enu_m, "start_enu_m") if start_enu_m is not None else (start, "start")
    if given is None:
        return np.zeros(3)
    try:
        xyz = np.array([float(v) for v in given])
    except (TypeError, ValueError):
        xyz = np.zeros(0)
    if xyz.shape != (3,) or not np.isfinite(xyz).all():
        raise DataError(f"Tracker: {name}={given!r} is the start position (x, y, z) in ENU metres (east, north, up "
                        "from your origin), three finite numbers, e.g. start_enu_m=(0.0, 0.0, 12.5); a (lat, lon) "
                        "start is for pdrlearn run --start and the pipelines' start=")
    return xyz


def calibration_record(displacement: dict) -> dict | None:
    """The distance-calibration record (``gain``, ``rate_hz``, ``stride_sd``) of a bundle's ``displacement``
    parameters (decision E14), or None when the bundle carries none (uncalibrated model, older bundle).
    Decision L41: the streamed stride kernel's own gain and sd when the bundle has them, else (bundles
    exported before L41) the offline engine's, as before."""
    if displacement.get("streaming_distance_gain") is not None:
        return {"gain": float(displacement["streaming_distance_gain"]),
                "rate_hz": displacement.get("distance_gain_rate_hz"),
                "stride_sd": displacement.get("streaming_stride_sigma_rel"), "reason": None}
    if displacement.get("distance_gain") is None:
        return None
    return {"gain": float(displacement["distance_gain"]), "rate_hz": displacement.get("distance_gain_rate_hz"),
            "stride_sd": displacement.get("stride_sigma_rel"), "reason": None}


#: decision L91's clause of a long foot gap's line (the waist heads the strides), and E299's when the waist gyroscope
#: has its own gap there (a later wGyroscope gap rewrites the first into the second: review R3 F5)
_L91_TURN = "turns with the waist gyroscope (L91)"


def _e299_turn(cycle: bool = True) -> str:
    """Decision E299 (E365, review s53r1: one wording with ``track --streaming``'s,
    :func:`~pdrlearn.kernels.gaps.waist_gap_turn`): what a foot gap's line says of the turn when the waist gyroscope
    was silent too (``cycle``: E354's ``bridge_cycle``)."""
    return (f"turns with the waist gyroscope where it recorded, across its own gap by {waist_gap_turn(cycle)}: "
            "every later stride's heading may be off by that turn (decision E299)")


def heading_gap_line(a: float, b: float, cycle: bool = False) -> str:
    """Decision E299: the line for a gap of ``a``-``b`` s (over B11's 1 s) in the waist gyroscope that heads the
    strides: the turn inside it is not measured. ``cycle`` (decision E365): the gap lies inside a foot gap that E354's
    line bridges (:func:`~pdrlearn.kernels.gaps.waist_gap_turn`)."""
    how = ("carried across it by " + waist_gap_turn(True) if cycle else
           "carried across it on a straight line between its samples around it, so a turn inside the gap is not "
           "measured")
    return (f"wGyroscope: no samples for {b - a:.2f} s ({a:.2f}-{b:.2f} s) while it heads the strides: the heading "
            f"is {how} and every later stride's heading may be off by that turn (trial T2: 18-60 deg after 1.6-4 s "
            "gaps in a turn; decision E299)")


def _no_samples(tv) -> bool:
    """Whether a sensor's ``(t, values)`` of a push holds no timestamp (decision E40)."""
    try:
        return len(tv[0]) == 0
    except (TypeError, IndexError, KeyError):
        return False


@functools.lru_cache(maxsize=8)
def _nan_template(n_channels: int, n_samples: int) -> np.ndarray:
    """A read-only all-NaN window; ``.copy()`` of it is ``np.full`` without its Python wrapper (E17)."""
    W = np.full((n_channels, n_samples), np.nan)
    W.flags.writeable = False
    return W


class _Views(dict):
    """Sensor name -> ``(t, values)`` views of the tracker's buffers, each made on first access (a step
    reads 4-6 of the buffered sensors; decision E16). Membership and iteration are the buffers'."""

    __slots__ = ("_buf", "rings")

    def __init__(self, buf: dict[str, Ring]):
        super().__init__()
        self._buf = buf
        self.rings = buf  # the buffers themselves: runtime.stream cuts segments from them directly (E17)

    def __missing__(self, name: str):
        v = self[name] = self._buf[name].view()
        return v

    def __contains__(self, name) -> bool:
        return name in self._buf

    def __iter__(self):
        return iter(self._buf)

    def __len__(self) -> int:
        return len(self._buf)

    def get(self, name, default=None):  # dict.get bypasses __missing__: it would say a buffered sensor is absent
        return self[name] if name in self._buf else default


class Tracker(OwnGuard, FixInput):
    """Classify and track steps as samples stream in (numpy + onnxruntime only).

    Parameters
    ----------
    bundle : a :class:`Bundle` or the path of a bundle folder (verified on load).
    frames : placement -> declared axis frame of the incoming data (default: the bundle's).
    tasks : tasks to classify (default: every task in the bundle; an empty list: none, the strides tracked as
        ``track --streaming --method M2`` tracks them, decision E291).
    methods : task -> ``"method/unit"`` to use instead of the bundle's chosen one.
    start_enu_m : initial position ``(x, y, z)`` in ENU metres (east, north, up; default the origin), and
        ``heading_rad`` the initial heading override. ``start`` is its older name (decision L159: a geodetic
        (lat, lon) is not taken here; a wrong length or both keywords is one error line).
    buffer_s : seconds of samples kept per sensor (bounded state).
    heading_source : "auto" | "foot" | "waist-gyro" (default: the bundle's ``displacement``).
    rules, min_confidence : the class rules, "bayes" or "thesis", and the probability a class needs before
        its rule applies (0 = every class); default: the bundle's ``displacement`` (``pdrlearn export`` writes
        "bayes" and 0.95, offline M3's rule and ``pdrlearn track --streaming``'s default since decision L41;
        bundles exported under E25 before it say "thesis" and 0; a bundle exported before decision E25 has
        neither and keeps "thesis" without a gate). ``rules`` given without ``min_confidence``: that rule's
        own gate (thesis 0, bayes 0.95), as ``pdrlearn track``.
    step_graph : classify with the bundle's step graph when it has one (one onnxruntime run per step,
        decision E10); False = one run per model (the same numbers, slower).
    incremental : level the foot samples as they are pushed (decision E15; the same windows to rounding,
        less work at the step event); False = all of it at the step event (the shared kernel alone).
    units : the body units to track with, ``("foot",)`` or ``("foot", "waist")`` (default: the bundle's).
        ``("foot",)`` with a two-unit bundle (decision E26): a session without the waist unit, or whose
        waist failed: waist samples are ignored, no waist sensor is required, every task classifies with
        the foot model ``pdrlearn track`` picks for such a session, the heading is the foot's (``auto``).
        Steps are detected on the foot, so a unit list without it is an error. Decision E32: without
        ``units``, a ``sensors`` list that lacks a sensor the bundle's waist unit requires means ``("foot",)``.
    sensors : the sensor streams the data will have (default: unknown, every model's sensors expected).
        Decision E26 amended: a task whose model reads an absent sensor (e.g. a length model on force
        sensors) classifies with the bundle's best-ranked model that reads none, else is left unclassified
        (``unclassified``; one warning line), as ``pdrlearn track`` does.
    speculative : compute the step that the next push is likely to complete at the end of the push before
        (decision E24): the window, classification and stride of the stride the stance in progress closes
        (:meth:`StanceSegmenter.closing_stride`), used when that push completes exactly that step from the
        same data, else recomputed. The same numbers bit for bit; the step-completing push then does only
        the step's heading and position, and the push before it the rest. False = all at the step event.
    waist_gap_yaw : a stride headed by the waist gyroscope adds the waist's turn between two strides that do not
        touch (decision L61; ``pdrlearn track --streaming``'s ``waist_gap_yaw``); the foot's pivot is always
        added to a stride headed by the foot (L31).
    waist_bridge : the stride across a foot accelerometer / gyroscope gap over 1 s turns by the waist gyroscope's
        turn from the previous stride's end (the foot's rest before the gap) to its own end (the rest after it)
        when the waist heads the strides (decision L99, the default; L91's mechanism; ``pdrlearn track
        --streaming``'s ``waist_bridge``); False: it keeps the heading (E30, L90).
    bridge_cycle : across the waist gyroscope's own gap inside that bridge (both units silent) the turn is the line
        between the gait-cycle mean rates of the stride before and the stride after (decision E354, ``pdrlearn track
        --streaming``'s ``bridge_cycle``; added to the stride after); False: L91's line between the two rates at the
        gap's edges (W389).
    gap_compass : after such a gap the heading is also re-anchored to the waist compass, weighed against that line
        (decision E361, :class:`~pdrlearn.kernels.gap_compass.GapCompass`; ``pdrlearn track --streaming``'s
        ``gap_compass``); False: the line alone (E354).
    drop_neighbour : a stride across dropped foot samples over 0.25 s (under 1 s) takes the length (scaled by the
        durations) and height change of the clean stride before it (decision L167, an option; E101: a keyword, as
        ``track_plasys(streaming=True, drop_neighbour=...)``); False (default): its own (decision L549: no module
        switch).
    cycle_yaw : a stride headed by the waist gyroscope is placed along its gait cycle's mean yaw, the heading after
        it less the pelvic rotation's yaw at the stride's ends (decision E336, the default; ``track_streaming``'s
        ``cycle_yaw``); False: along the heading after it (the pelvis' yaw at the foot's rest, before E336).
    max_gap_s : a push whose timestamps jump further ahead than this (s; default 60) of a stream's last sample is
        refused in one line, the tracker unchanged (decision B141: a clock glitch accepted as a gap would refuse
        every later sample); ``math.inf`` accepts any gap.
    resume : a :meth:`restart_state` of another tracker (decision L134): go on where it stood (its position and
        heading, the stride in progress measured whole from the samples it buffered); ``start`` and
        ``heading_rad`` are then not used. The steps those samples complete come out with the first push.
    clock_check : with the foot and the waist unit, estimate their clock offset from the pushed samples as ``pdrlearn
        track`` / ``run`` do (decisions L161, L170, L177: the same detectors and estimate, numpy only) and warn once
        when it is over 0.2 s, at every 20th foot stride and at :meth:`flush`; :attr:`clock_offset` holds the last
        estimate (at ``flush``: the offline check's on the same samples). False: no check.
    waist_clock_offset_s : a known offset of the waist clock (s, ``t_waist = t_foot + offset``, the sign L161's line
        and ``track --align-units`` give): every pushed waist sample is moved to ``t - offset`` before anything
        else (decision L177: the live form of ``--align-units``; 0: none). Settable between pushes (decision E227),
        as :meth:`rebase_clock` sets it: a waist pod that reconnected with its clock restarted goes on.
    drop_duplicate_timestamps : drop a pushed sample whose timestamp repeats one already taken of its stream (the
        sample before it in the push, or one the tracker still buffers; a resampled stream's last 5 s of input
        times and a stream's rate probe count too, decision E239: a Bluetooth packet sent again), keeping the
        first, as ``WaistTracker(drop_duplicate_timestamps=True)`` (decision E225, E203's kernel); counted per
        sensor in :attr:`dropped_duplicates` (total :attr:`n_dropped_duplicates`), one warning line. Off: such a
        push is refused, the line says "duplicates one already taken".
    waist_clock_drift_ppm : a known drift of the waist clock (ppm, ``t_waist = t_foot x (1 + ppm/1e6) + offset``,
        ``pdrlearn run --clock-drift-ppm``'s model and mechanism, ``to_foot_clock``): every pushed waist sample is
        moved to ``(t - offset) / (1 + ppm/1e6)`` (decision E229; 0: none).
    stream_checks : say at :meth:`flush` the lines ``pdrlearn run`` says of a session: the intervals of dropped
        samples (over 1.5 sample intervals, up to 1 s) the pushed streams had, in run's line (L77, decision E230;
        :meth:`drop_stats` counts them either way), and, for a foot track pushed a barometer, L145's line when the
        foot's altitude change disagrees with the barometer's (decision E232); ``pdrlearn run`` turns it off: it says
        them itself.
    check_domain : score each classified stride against the training ranges the bundle's models carry (decision
        E105; ``pdrlearn export`` stores them since): :meth:`domain_report` is ``pdrlearn track --model``'s report
        (C16), and :meth:`flush` warns C61's one line when more than half a task's strides lie outside. Off by
        default (the per-model features cost time at each step); ``pdrlearn run`` turns it on. A bundle without
        ranges checks nothing (no line, no error). ``warn_out_of_domain`` (a fraction, as ``track``'s option,
        turns the check on): C16's detailed line from that fraction instead.
    length_reference : ``"model"`` (default: the classifier's length class) or ``"session"`` (decision C117, opt-in:
        a flat, forward, straight stride's reported class is its length against 0.8 / 1.2 x the median of the
        session's such strides so far, after 10 of them; the distance is computed as before). A restarted tracker
        (``resume``) starts a new median.
    innovation_gate : decision D31 (an option, off by default as ``track --fixes``' gate, D33): ``add_fix`` rejects
        a fix more than 3 sigma from the filter's estimate (the chi-square 0.997 gate, never two fixes in a row),
        names it in one warning as it is rejected and counts it in ``fix_stats()["fixes_rejected"]`` (decision D35).
    first_walk : a foot-headed track's heading is turned once, at the end of its first walk (the 4th stride over 0.2
        m), by that walk's direction less the start heading (L494's reference made causal; decision E215: measured,
        a unit yawed on the shoe ended 15.0 -> 2.0 m off on average, not adopted as the default: unyawed feet got
        worse in two of five walks; decision E222: this keyword, as ``track_plasys(streaming=True, first_walk=...)``).
        False (default): the heading's 0 stays the foot unit's facing and one line says how far the walk heads.
    gated_level_dz : an M3 stride whose terrain class the confidence gate dropped gets L39's level rule, per stride
        (True, decision L189: offline's L184 function) or on the summed dz of its run of such strides (``"summed"``,
        L206); both measured and not adopted (L189, L207). False (default): raw heights. Decision L550: this keyword,
        as ``track_plasys(streaming=True, gated_level_dz=...)``; only with a bundle that classifies terrain.
    cycling : True (default): L611's pedalling check (E280): a stride is held until its verdict is final (up to three
        later strides: a short turning stride in a spin waits 1.7-3.8 s) and a pedalling one is removed. False
        (decision E304, ``pdrlearn run --no-cycling``, ``track_plasys(cycling=False)``): for an activity without
        bicycles (dance, a clinic), no stride is judged pedalling and none is held.
    full_scale : decision B456: the sensors' declared ranges, stream name -> ``"4 g"`` / ``"500 deg/s"`` (meta.json's
        ``full_scale``): clipping is judged at them (samples within 5 % of the range). Decision E303: with
        ``check_input`` and ``stream_checks``, each IMU stream's 10 s blocks are checked for clipping (B77 / B311, or
        at the declared range) and stuck axes (B455): one line per stream, and per stream and axis, in ``warnings``.
    altitude : ``"foot"`` (default: the strides' own height, as ``pdrlearn track``'s default) or ``"fused"``
        (decision E339: L154's fusion with the pushed waist barometer, ``track --altitude fused``'s filter,
        :class:`~pdrlearn.kernels.barometer.AltitudeFusion`; ``pdrlearn run --altitude fused``): a row is returned
        once the barometer was pushed about a second past its end (W89's window; or its declared end, or the other
        streams 2 s further, or :meth:`flush`), with its fused ``dz_m`` and ``z``. Needs wBarometer among the
        tracked units' sensors (refused otherwise); declared ``sensors`` without it keep the foot's height with
        L154's line. Carried over by ``restart_state`` (decision E356: the held barometer, the filter and the rows
        not returned yet; a resumed tracker's ``altitude`` must be the saved one's).
    gait : decision E320: keep every returned stride's gait values (:class:`pdrlearn.runtime.gait.StrideGait`,
        numpy only; needs ``contacts=True``: a stride time is initial contact to initial contact):
        :meth:`gait_strides` per stride, :meth:`gait_summary` the session's (with the other foot's tracker, the
        symmetry indices). Not carried over by ``restart_state`` / ``resume``. Decision E326: each stride's toe-off
        (L73's kernel on its buffered foot gyroscope, :class:`~pdrlearn.kernels.toeoff.LiveToeOff`), so the strides
        have stance / swing times; decision E327: with the other foot, double support and their symmetry indices.
    """

    _one_at_a_time = "push/flush/add_fix"  # decisions E231, E256: the calls one_call_at_a_time guards

    _foot_q: list | tuple = ()  # set per tracker in __init__ (a bare Tracker.__new__ has no queued feeds)
    _spec: tuple | None = None  # likewise: no step computed ahead (decision E24)
    _trims = 0
    speculative = False
    _pushed_gaps: list | None = None  # decision E30 (a bare Tracker.__new__ has none)
    _pushed_drops: list | None = None  # decision E230 (likewise)
    _baro = None  # decision E232 (likewise: no barometer check)
    _first_walk = None  # decision E215 (a bare Tracker.__new__ has none)
    bridge_cycle = False  # decision E354 (a bare Tracker.__new__: L91's line)
    _compass: GapCompass | None = None  # decision E361 (a bare Tracker.__new__: none)
    _stop_bias = None  # decision E272 (a bare Tracker.__new__ has none)
    _drop_at_w = math.inf  # decision E285 (as _stop_bias)
    _pitch_ref: PitchReference | None = None  # decisions B474 / B475 (a bare Tracker.__new__ makes one at its first)
    _pedal_line: list | None = None  # decision E280: [spans, index in warnings]
    _foot_gaps: list | tuple = ()
    _heading_gaps: list | tuple = ()  # decision E299: the waist gyroscope's gaps over 1 s, the latest 16
    _range_rows: deque | tuple = ()  # decision E350: the latest strides' cadence, speed and straightness
    _slow_said = False  # decision E350: flush's L95 line said
    _l91_lines: list | tuple = ()  # E299 amended (R3 F5): (start, end, index in warnings) of foot lines saying L91
    _drop_ref: tuple | None = None  # decision L167 (a bare Tracker.__new__ has no clean stride yet)
    _session_length = None  # decision C117 (a bare Tracker.__new__: the model's length class)
    _side: _sideways.SideRun | None = None  # decision E124 (a bare Tracker.__new__ makes one at its first stride)
    _side_rows: _sideways.SideRun | None = None  # decision L243 (the same)
    _drop_warned = False
    n_turns_in_place = 0  # decision L742: foot windows left out as turns on the spot
    _spun: tuple[float, float] | None = None  # decision L742: (their foot turn, the last one's end) since a stride
    _hole_warned = False  # decision L674's one line
    drop_neighbour = False  # decisions E101, L549 (a bare Tracker.__new__: L167 off)
    cycle_yaw = True  # decision E336 (a bare Tracker.__new__: on, as the keyword's default)
    _cycle_phase = None  # decision E338 (a bare Tracker.__new__ makes one at its first stride)
    gated_level_dz: bool | str = False  # decision L550 (a bare Tracker.__new__: raw heights)
    #: decision E46: the long foot gaps (start, end) not yet behind the last emitted stride, the pending gap row
    #: ([start, gap_s] or None), the end / reported heading / position of the last emitted stride
    _row_gaps: list | tuple = ()
    _gap_row: list | None = None
    _kept: tuple | None = None
    #: decision E47: (terrain class or None, integrated dz before gain and rules, final dz) per processed stride
    #: (a :class:`HeightLog`, decision E75)
    _heights: HeightLog | tuple = ()
    _held_s = math.inf  # decision E31: set per tracker in __init__
    _checked: dict = {}  # noqa: RUF012 - replaced per push, never mutated in place
    _guard = None  # decision B119 (a bare Tracker.__new__ checks nothing)
    _domain: DomainLog | None = None  # decision E105 (a bare Tracker.__new__ scores nothing)
    _frozen_foot: FrozenFootWatch | None = None  # decision B213 (a bare Tracker.__new__ watches nothing)
    _clip: ClipWatch | None = None  # decision E303 (likewise)
    _flag_scales: dict | None = None  # decision E325 (likewise: no clipped flag)
    _rates: RateWatch | None = None  # decision E309 (likewise)
    _rate_log: list | tuple = ()  # decision E309: the rate changes found (a bare Tracker.__new__ has none)
    _warn_ood: float | None = None
    _domain_said = False
    #: decision C227: the bundle's one user when the replayed session is that user's (``pdrlearn run`` sets it); the
    #: out-of-range line then sends such strides to the calibration instead of advising a per-user model
    domain_user: str | None = None
    #: decision L134: a resumed tracker's last measured stride end (s; strides found again up to it are dropped)
    _resume_end: float | None = None
    _carry: list | tuple = ()
    #: decisions E223-E227 (a bare Tracker.__new__: no offset, no repeat dropped, every line written)
    foot_clock_offset_s = 0.0
    _drop_dups = False
    _starts: StartClocks | None = None
    _repeats: RepeatedLines | None = None
    _gait_log: StrideGait | None = None  # decision E320 (a bare Tracker.__new__: none kept)
    _toe_off: LiveToeOff | None = None  # decision E326 (likewise)
    _fused: FusedRows | None = None  # decision E339 (likewise: the foot's own altitude)

    def __init__(
        self,
        bundle: Bundle | str | Path,
        *,
        frames: dict | None = None,
        tasks=None,
        methods: dict[str, str] | None = None,
        start=None,
        heading_rad: float | None = None,
        buffer_s: float = 8.0,
        heading_source: str | None = None,
        step_graph: bool = True,
        incremental: bool = True,
        resample: bool | str = "native",
        max_lag_s: float | None = None,
        input_rates_hz: dict[str, float] | None = None,
        stream_ends_s: dict[str, float] | None = None,
        speculative: bool = True,
        rules: str | None = None,
        min_confidence: float | None = None,
        units=None,
        sensors=None,
        waist_gap_yaw: bool = True,
        waist_bridge: bool = True,
        bridge_cycle: bool = True,
        gap_compass: bool = True,
        contacts: bool = False,
        check_input: bool = True,
        drop_neighbour: bool = False,
        cycle_yaw: bool = True,
        resume: dict | None = None,
        max_gap_s: float = MAX_GAP_S,
        start_enu_m=None,
        clock_check: bool = True,
        waist_clock_offset_s: float = 0.0,
        waist_clock_drift_ppm: float = 0.0,
        stream_checks: bool = True,
        check_domain: bool = False,
        warn_out_of_domain: float | None = None,
        length_reference: str = "model",
        innovation_gate: bool = False,
        first_walk: bool = False,
        drop_duplicate_timestamps: bool = False,
        gated_level_dz: bool | str = False,
        cycling: bool = True,
        full_scale: dict | None = None,
        gait: bool = False,
        altitude: str = "foot",
    ):
        self._busy = new_guard()  # decision E231: push / flush one thread at a time
        start_xyz = enu_start(start, start_enu_m)  # decision L159
        self.stream_checks = bool(stream_checks)  # decisions E230, E232 (checked below)
        self.gated_level_dz = _distance.check_gated_level_dz(gated_level_dz)  # decisions L189, L206, L550
        #: decision C117: "session" reports a flat forward stride's length class against the session's median stride
        self._session_length = (_relative_length.SessionLength()
                                if _relative_length.check_length_reference(length_reference) == "session" else None)
        for key, flag in (("clock_check", clock_check), ("stream_checks", stream_checks),  # L177, E230: flags
                          ("cycling", cycling)):  # decision E304
            if not isinstance(flag, bool | np.bool_):
                raise DataError(f"{key}={flag!r} must be True or False")
        if (isinstance(waist_clock_offset_s, bool) or not isinstance(waist_clock_offset_s, int | float | np.number)
                or not math.isfinite(waist_clock_offset_s)):
            raise DataError(f"waist_clock_offset_s={waist_clock_offset_s!r} must be the waist clock's offset in "
                            "seconds (a finite number; 0 for none)")
        if (isinstance(waist_clock_drift_ppm, bool) or not isinstance(waist_clock_drift_ppm, int | float | np.number)
                or not abs(waist_clock_drift_ppm) <= MAX_CLOCK_DRIFT * 1e6):  # decision E229, as run's B265
            raise DataError(f"waist_clock_drift_ppm={waist_clock_drift_ppm!r} must be the waist clock's drift in ppm "
                            f"(a finite number within +-{MAX_CLOCK_DRIFT * 1e6:.0f}, t_waist = t_foot x (1 + "
                            "ppm/1e6) + offset; 0 for none)")
        from pdrlearn.classify.domain import check_warn_at

        check_warn_at(warn_out_of_domain)  # decision C16's option, as track's
        #: decision E105: the strides' out-of-domain scores (None: not checked, the default)
        self._domain = DomainLog() if check_domain or warn_out_of_domain is not None else None
        self._warn_ood = warn_out_of_domain
        self._domain_said = False
        self.bundle = bundle if isinstance(bundle, Bundle) else load_bundle(bundle)
        m = self.bundle.manifest
        sensors = None if sensors is None else [str(n) for n in sensors]
        self._unchecked = sensors is None  # decision B140: the first step checks the pushed streams
        #: the body units tracked (decision E26), their required and used sensors
        self.units = tracked_units(self.bundle, units, sensors)
        self.required, optional = self.bundle.sensors_of(self.units)
        if sensors is not None:  # decision E55: a declared stream set that lacks a required sensor, refused now
            self.bundle.check_streams(dict.fromkeys(sensors, math.nan), where=f"sensors={sensors}", units=self.units)
        self.used_sensors = [*self.required, *optional]
        fm = m["features"]
        self.channels = list(fm["channels"])
        self.ci = {c: i for i, c in enumerate(self.channels)}
        self.n_samples = int(fm["n_samples"])
        self.heading_mode = fm.get("heading", "pca")
        if self.heading_mode not in WINDOW_HEADINGS:  # decision B138: any other value ran as "declared"
            raise ModelError(f"bundle {self.bundle.path}: features.heading {self.heading_mode!r} is not one of "
                             f"{', '.join(WINDOW_HEADINGS)}; re-export it with this version")
        self.rest_search_s = float(fm.get("rest_search_s", 0.3))
        #: where classification windows are cut (decisions 13 / C13): "given" = the segmenter's stance
        #: boundaries, "rest" = each moved to the middle of the foot's rest by the training side's own
        #: kernel (bundles exported before the setting existed read as "given")
        self.boundaries = str(fm.get("boundaries", "given"))
        if self.boundaries not in BOUNDARIES:
            raise ModelError(f"bundle {self.bundle.path}: features.boundaries {self.boundaries!r} is not one "
                             f"of {', '.join(BOUNDARIES)}; re-export it with this version")
        # a rest boundary is searched up to rest_search_s after the step's end (+ the 50 ms smoothing box)
        self._lookahead_s = self.rest_search_s + 0.05 if self.boundaries == "rest" else 0.0
        frames = frames or m["frames"]
        self.forward = {p: forward_vector(f) for p, f in frames.items()}
        self.warnings: list[str] = []
        from pdrlearn.runtime.rides import BAROMETERS, RideWatch

        baro = next((n for n in BAROMETERS if n in self.used_sensors), None)
        self._rides = RideWatch(baro) if baro is not None else None  # decision E211: each ride not counted, named
        #: decision E232: L145's foot-vs-barometer check (a foot track pushed a barometer, run's line at flush)
        self._baro = (BaroCheck(baro) if baro is not None and "foot" in self.units and self.stream_checks
                      else None)
        self._fused = self._fusion(altitude, sensors, stream_ends_s)  # decision E339
        if self._fused is not None:  # E339: L145's live check reads the foot's z; a fused track's is run's summary's
            self._baro = None
        #: decision B131: [first s, last s, steps, index in warnings, the line last logged (B473)]
        self._posture: list | None = None
        self._turn_tally: list | None = None  # decisions C89 / C94: [TurnTally, index of its line in warnings]
        self._model_args = (*check_tasks(self.bundle, tasks, methods), units, step_graph)  # decisions B137, B139
        if self._session_length is not None:  # decision C131: the classes C117's median needs, or one line
            _relative_length.check_session_tasks(self._model_args[0], self.bundle.path,  # E291 amended (R3 F6):
                                                 None if tasks is None else list(self.bundle.tasks))  # the caller's
        self._choose_models(sensors)
        self.params = dict(m["displacement"])
        self.heading_source = heading_source or str(self.params.get("heading_source", "auto"))
        if self.heading_source not in HEADING_SOURCES:
            raise DataError(f"heading_source {self.heading_source!r} is not one of {', '.join(HEADING_SOURCES)}")
        if self.heading_source == "waist-gyro" and "waist" not in self.units:  # decision E26
            raise DataError(f"heading_source waist-gyro needs the waist unit, and the tracker follows "
                            f"{'+'.join(self.units)} only; use heading_source auto or foot")
        b = self.params.get("length_bounds_m")
        #: decision L59: a bundle exported before it from a model without bounds stored the thesis step bounds
        #: x 2 as if they were the user's (its length_bounds_source says so): read as no bounds, as since L59
        self._fallback_bounds = pre_l59_fallback(self.params)
        self.bounds = (None if b is None or self._fallback_bounds
                       else {str(k): (float(v[0]), float(v[1])) for k, v in b.items()})
        self._down_mode = str(self.params.get("down_mode", DEFAULT_DOWN_MODE))
        if self._down_mode not in DOWN_MODES:  # decision L51: "projected" is an option
            raise DataError(f"bundle {self.bundle.path}: displacement down_mode {self._down_mode!r} is not one of "
                            f"{', '.join(DOWN_MODES)}; fix the \"displacement\" entry of its manifest.json")
        #: decision L40 / E25: the class rules and their confidence gate (absent from older bundles: thesis, 0)
        self.rules = str(self.params.get("rules", LEGACY_RULES) if rules is None else rules)
        if min_confidence is None and rules is not None:  # L41: a rule asked for brings its own gate, as track's
            min_confidence = 0.0 if self.rules == "thesis" else DEFAULT_MIN_CONFIDENCE
        self.min_confidence = float(self.params.get("min_confidence", LEGACY_MIN_CONFIDENCE)
                                    if min_confidence is None else min_confidence)
        check_rules(self.rules, self.min_confidence, f"bundle {self.bundle.path}")
        self._sigma_rel = SIGMA_REL  # the bayes rule's relative stride sd: the calibrated one once resolved (L26)
        self.segmenter = StanceSegmenter.from_params(self.params)
        #: decision L141: the stride kernel's displacement on the histospline below 50 Hz (None: the unit's rate),
        #: from the ring buffers; a step then waits for FINE_PAD_S of samples past its end (the spline's padding)
        self._fine = fine_spec(self.params, self._stream, self.forward, rest_search_s=self.rest_search_s,
                               heading=self.heading_mode,
                               where=f"bundle {self.bundle.path} (the \"displacement\" entry of its manifest.json)")
        if self._fine is not None:  # decision E83: one sample more, so the push before computes the step ahead
            self._lookahead_s = max(self._lookahead_s, FINE_PAD_S + FINE_AHEAD_S)
        #: the user's distance calibration carried by the bundle (decision E14; absent = gain 1), resolved
        #: against the pushed foot rate at the first step (the rate check of ``pdrlearn track``, L26)
        self._calibration = calibration_record(self.params)
        #: applied gain on the level strides (None until the foot rate is known), calibrated stride sd
        self.distance_gain: float | None = None
        self.stride_sd: float | None = None
        if self.bounds is None and "length" in self.classifiers:  # decision L59: offline track's line, once
            self._warn(no_length_bounds_warning(
                "the bundle (exported before decision L59: its length_bounds_m are the thesis step bounds x 2, "
                "not the user's, and are ignored)" if self._fallback_bounds else "the bundle"))
        notes = [c.note for c in self.classifiers.values() if c.note]
        if notes:  # decision E26: a bundle exported before it records no foot-only models; one line
            self._warn(f"{'+'.join(self.units)} only: no {'+'.join(self.units)}-only models recorded (exported "
                       f"before decision E26): {'; '.join(notes)}, which `pdrlearn track` may not pick; re-export "
                       "the model (pdrlearn export) for track's choice")
        if not {"fAccelerometer", "fGyroscope"} <= set(self.bundle.used_sensors):
            raise ModelError(
                f"bundle {self.bundle.path}: the streaming tracker detects steps on the foot "
                "unit's gyroscope, and this bundle has no foot unit; train with foot data "
                "(waist-only tracking: pdrlearn track --pipeline waist-pll)"
            )
        self.rate_hz = self.bundle.rate_hz
        self.buffer_s = float(buffer_s)
        self._buf: dict[str, Ring] = {}
        self._oldest = math.inf  # time of the oldest buffered sample (s)
        # a lower bound of the earliest cut that drops a sample (a ring keeps the last sample before the cut,
        # so its second sample; a ring of one sample, that sample): a cheap _trim between two steps
        self._drop_at = math.inf
        self._drop_at_w = math.inf  # decision E285: the waist rings' (see _trim)
        self._latest = -math.inf  # time of the newest buffered sample (s)
        #: the foot levelling's per-sample part, done at push time (decision E15); None = the shared
        #: kernel at the step event only (``incremental=False``, or no declared foot frame)
        self._foot = FootLevelling(self.forward["foot"]) if incremental and "foot" in self.forward else None
        #: one-sample foot feeds of the current push, ``(name, t, values)``: fed to ``_foot`` at the end of a
        #: push that completes no step, else at the next push (decision E21), or before a step needs them
        self._foot_q: list[tuple[str, float, list[float]]] = []
        self.position = start_xyz
        self._init_fixes(self.position[:2], innovation_gate=innovation_gate)  # decisions D19-D21, D35: add_fix
        self.heading = float(self.params.get("initial_heading_rad", 0.0) if heading_rad is None else heading_rad)
        self._first_walk = _first_walk.FirstWalk(self.heading, enabled=first_walk)  # decisions E215, E222
        self._pending: list[tuple[float, float]] = []  # detected steps waiting for every sensor's data
        self._det_t = -np.inf
        self._groups: tuple[tuple[str, ...], tuple[str, ...]] = ((), ())  # (buffered sensors, their groups)
        self.n_steps = 0
        self._prev_end: float | None = None  # end (s) of the last measured stride (decision L31)
        self._contacts: list[tuple[float, float]] = []  # steps decision 87: the last strides' (start, contact) (s)
        self._gated_run_dz = 0.0  # decision L206: the summed dz of the current run of gated level strides (m)
        self._row_gaps, self._heights = [], HeightLog()  # decisions E46, E47 (E75: typed arrays)
        self.waist_gap_yaw = bool(waist_gap_yaw)  # decision L61
        #: decision E272: the waist gyroscope's bias read at the last stop (None without the waist unit)
        self._stop_bias = _stop_bias.StopBias() if "waist" in self.units else None
        #: decision E280: L611's verdicts stride by stride, the foot's rest reading (L621) and the warning line
        self._loops, self._foot_rest, self._pedal_line = _pedal.LiveLoops(cycling), _pedal.LiveRest(), None
        #: decision E280: no stride starting within L611's CHAIN_PAUSE_S of the last one's end can still be detected
        #: this long (s) after that end: the longest stride, its closing stance and the wait before a step is measured
        self._chain_quiet_s = _pedal.CHAIN_PAUSE_S + self.segmenter.max_step_s + 2.0 + self._lookahead_s
        self.waist_bridge = bool(waist_bridge)  # decisions L91 / L99 (the default)
        self.bridge_cycle = bool(bridge_cycle)  # decision E354
        self._cycle = CycleGapLine()  # decision E354: a waist gap's turn held for the stride after it
        self._compass = GapCompass() if gap_compass else None  # decision E361
        #: the input side (decision E22): streams at another rate than the bundle's are tracked at their own
        #: rate (``resample="native"``, the default, as ``pdrlearn track --streaming``), resampled to the
        #: bundle's (``True``) or refused (``False``); ``inputs.input_rates_hz`` / ``resampled_hz`` tell which
        self.inputs = InputStage(self.bundle, resample=resample, rates_hz=input_rates_hz, used=self.used_sensors)
        #: a stream further behind the newest one than this (s) plus its own delivery interval stopped
        #: (decision E23; default: max_wait_s, 2 s, the thesis' delay requirement)
        self.max_lag_s = float(self.params.get("max_wait_s", 2.0) if max_lag_s is None else max_lag_s)
        #: a step waits at most this long (s of newer data) for a lagging stream before it is processed with
        #: that stream's last value held (E9); with the lag check on, a step waits until the stream catches up
        #: or the check gives it up (E23 amended): never made of held values
        self._wait_s = float(self.params.get("max_wait_s", 2.0)) if self.max_lag_s == math.inf else math.inf
        #: a recording's streams' last times (s): a stream behind the others before its end is in a gap,
        #: and the steps wait for it rather than the lag check stopping the replay (E23 amended)
        self._ends = {str(n): float(t) for n, t in (stream_ends_s or {}).items()}
        self._lag_next = -math.inf  # data time (s) of the next lag tick (delivery intervals measured)
        self._first_t = math.inf  # the first pushed sample's time (s)
        self._unseen = frozenset(self.required)  # not pushed yet
        self._tick_last: dict[str, float] = {}  # each stream's newest input time at the last lag tick
        self._batch: dict[str, float] = {}  # each stream's latest advance between two lag ticks (s)
        self._note_resampled()  # declared rates: the resampling is known (and announced) before any push
        #: decision E24: the step computed ahead, ``((t0, t1), stamp, core)``, or None; ``_trims`` counts the
        #: trims that dropped samples (part of the stamp: the data a step reads is final once every stream
        #: has a sample past it, and changes only by a trim or a re-anchored foot state)
        self.speculative = bool(speculative)
        #: decisions E49-E51: give each stride its initial contact and stride time (an option: E50's rule not met)
        self.contacts = bool(contacts)
        if not isinstance(gait, bool | np.bool_) or (gait and not self.contacts):  # decision E320
            raise DataError(f"gait={gait!r}: give True (with contacts=True: a stride time is initial contact to "
                            "initial contact, decisions E49, L66) or False")
        self._gait_log = StrideGait() if gait else None
        self._toe_off = LiveToeOff() if gait else None  # decision E326: each stride's toe-off (L73)
        self._toe_offs: dict[tuple[float, float], float] = {}
        self._spec: tuple | None = None
        self._trims = 0
        #: decisions E30, E31: the gaps the current push opens ``(sensor, last sample before, first after)`` (s), the
        #: gaps announced ``[start, end, long]`` (the latest few), the foot gaps over GAP_LONG_S not yet behind
        #: the processed strides, and the streams announced as held (``max_lag_s = inf``)
        self._pushed_gaps: list | None = None
        #: decision E230: the push's intervals of dropped samples (committed after its checks), the count per stream
        #: ``(intervals, longest s)``, each stream's limit (s) and whether flush said them
        self._pushed_drops: list | None = None
        self._drops: dict[str, tuple[int, float]] = {}
        self._drop_lim: dict[str, float] = {}
        self._drops_said = False
        self._gap_marks: list[list] = []
        self._foot_gaps: list[tuple[float, float, bool, bool]] = []  # (start, end, long, a foot IMU stream's)
        self._drop_ref: tuple | None = None  # decision L167: (displacement, duration) of the last clean stride
        self._side = _sideways.SideRun()  # decision E124: the side-stepping stretch the strides are in
        self._side_rows = _sideways.SideRun()  # decision L243: the same test on every stride, for Step.sideways
        self._drop_warned = False
        self._hole_warned = False
        self.drop_neighbour = bool(drop_neighbour)  # decisions E101, L549
        self.cycle_yaw = bool(cycle_yaw)  # decision E336
        self._cycle_phase = CyclePhase()  # decision E338
        self._held: set[str] = set()
        #: decision E115: the required waist streams that stopped while the foot strides went on (name -> the
        #: time of its newest sample then); their samples are taken again when they return
        self._paused: dict[str, float] = {}
        self._held_s = float(self.params.get("max_wait_s", 2.0))  # a held value older than this is warned about
        #: decision B141: a push whose timestamps jump further ahead than this (s) is refused (a clock glitch)
        self.max_gap_s = float(max_gap_s)
        if not self.max_gap_s > GAP_LONG_S:
            raise DataError(f"max_gap_s {max_gap_s!r}: give a number of seconds above {GAP_LONG_S:g} (a foot gap of "
                            "that length is a gap row, E30), or math.inf to accept any gap (decision B141)")
        #: decision B119: the units of the first GUARD_S seconds of each IMU stream, checked as offline's (None:
        #: checked, or ``check_input=False``); decision B120: frozen sensors
        self._guard = UnitGuard(self.used_sensors) if check_input else None
        self._frozen = FrozenWatch()
        #: decision E303: B77 / B311 clipping (B456: at the ``full_scale`` declared, stream -> "4 g" / "500 deg/s") and
        #: B455's stuck axes on each IMU stream's 10 s blocks (None: ``check_input=False``, or ``stream_checks=False``:
        #: ``pdrlearn run`` said them when it read the session)
        self._clip = (ClipWatch(self.used_sensors, full_scale, waist="waist" in self.units)
                      if check_input and self.stream_checks else None)
        #: decision E325: the declared full scales each stride's clipped flag is judged at (None: ``check_input=False``)
        self._flag_scales = full_scales(full_scale) if check_input else None
        #: decision E309: B457's sustained sample-rate change of each IMU stream, said once per change (the kernel of
        #: read_session, B460); None as ``_clip``
        self._rates = (RateWatch(self.used_sensors, limit=self._drop_limit) if check_input and self.stream_checks
                       else None)
        self._rate_log = [] if self._rates is None else self._rates.changes
        #: decision B213: B203's frozen foot IMU beside stepping force sensors, judged live (None: decided, no foot IMU
        #: or force sensor, or ``check_input=False``)
        self._frozen_foot = (FrozenFootWatch() if check_input and {"fAccelerometer", "fGyroscope"} <= set(
            self.used_sensors) and {"fForceA", "fForceB"} & set(self.used_sensors) else None)
        #: decision B129: D11's mirrored-pair test on the first foot strides (None: decided, no foot IMU, or
        #: ``check_input=False``)
        self._mirror = (MirrorWatch() if check_input and {"fAccelerometer", "fGyroscope"} <= set(self.used_sensors)
                        else None)
        #: decision L177: the live two-unit clock check (None: off, or the waist unit not followed) and the known
        #: waist clock offset moved off every pushed waist sample
        for key, given in (("waist_clock_offset_s", waist_clock_offset_s),
                           ("waist_clock_drift_ppm", waist_clock_drift_ppm)):
            if given and "waist" not in self.units:
                raise DataError(f"{key}={given!r}: the tracker follows {'+'.join(self.units)} only, so there is no "
                                "waist clock to move; drop it")
        self.waist_clock_offset_s = float(waist_clock_offset_s)
        self.waist_clock_drift_ppm = float(waist_clock_drift_ppm)  # decision E229
        #: decision E227: the foot clock's offset from the tracker's (its samples moved to ``t - offset``; 0 until
        #: :meth:`rebase_clock` moves a foot pod that reconnected with its clock restarted)
        self.foot_clock_offset_s = 0.0
        # the check reads the moved samples: the offset to name is the one given (or rebased, E227) plus the one seen
        self._clock = (ClockCheck(lambda off: offset_remedy(self.waist_clock_offset_s + off))
                       if clock_check and "waist" in self.units else None)
        #: decision E225: drop a pushed sample whose timestamp repeats one taken, counted per sensor here
        self._drop_dups = bool(drop_duplicate_timestamps)
        self.dropped_duplicates: dict[str, int] = {}
        #: decision E223: the two units' clocks at the start; E224: repeated lines counted (kind -> occurrences)
        self._starts = StartClocks(self.max_lag_s) if {"foot", "waist"} <= set(self.units) else None
        self._repeats = RepeatedLines()
        self.warning_counts = self._repeats.counts
        #: decision L134: a restart state's position, heading and samples (the steps they complete come out with
        #: the next push's or flush's)
        self._carry = resume_state(self, resume) if resume is not None else []


    @property
    def clock_offset(self) -> dict | None:
        """Decision L177: the last estimate of the foot-to-waist clock offset (``align_events``' dict: ``offset_s``,
        ``drift``, ``ref_s``, ``matched``, ``foot_events``, ``residual_sd_s``), None before one (or without the check).
        ``offset_s`` is the offset at foot-clock time ``ref_s``, inside the recording (decision L198): the constant
        ``waist_clock_offset_s`` that aligns it, whatever the clocks' origin. Decision E244: once an estimate has
        locked, ``offset_s`` is followed across step periods (``raw_offset_s``: L161's candidate closest to 0,
        ``periods_followed``: the whole step periods between them), so a drifting clock is not read as its twin."""
        return None if self._clock is None else self._clock.estimate

    @property
    def n_dropped_duplicates(self) -> int:
        """Decision E225: the pushed samples dropped as repeats (``drop_duplicate_timestamps=True``), every sensor."""
        return sum(self.dropped_duplicates.values())

    def rebase_clock(self, unit: str, offset_s: float) -> None:
        """Decision E227: from now on every pushed sample of ``unit`` (``"foot"`` or ``"waist"``) is moved to ``t -
        offset_s`` (its clock reads the tracker's time plus ``offset_s``; the waist's is ``waist_clock_offset_s``).
        A pod that reconnected with its clock restarted goes on in the same tracker: its buffered samples stay on
        the tracker's clock, its new ones join them. The refusal of its first new push is a
        :class:`~pdrlearn.errors.ClockWentBack` whose ``offset_s`` puts them beside the other unit's newest."""
        if unit not in self.units:
            raise DataError(f"rebase_clock({unit!r}, ...): the tracker follows {'+'.join(self.units)}; give one of "
                            f"{', '.join(map(repr, self.units))}")
        if isinstance(offset_s, bool) or not isinstance(offset_s, int | float | np.number) or not math.isfinite(
                offset_s):
            raise DataError(f"rebase_clock({unit!r}, {offset_s!r}): give the unit clock's offset in seconds (a finite "
                            "number: its clock reads the tracker's time plus it)")
        setattr(self, f"{unit}_clock_offset_s", float(offset_s))

    def _without_repeats(self, samples: dict) -> tuple[dict, dict[str, int]]:
        """Decision E225: ``samples`` without the samples whose timestamp repeats one taken (the kernel E203's
        ``WaistTracker`` uses: the sample before it, or one this tracker still buffers), and sensor -> how many were
        dropped (counted by :meth:`push` once the push is taken). Anything not a (t, values) pair of matching length
        is passed on for the push's checks to name."""
        out, dropped = None, {}
        for name, tv in samples.items():
            if not (isinstance(tv, tuple | list) and len(tv) == 2):
                continue
            try:
                t = np.asarray(tv[0], dtype=np.float64).reshape(-1)
            except (TypeError, ValueError):
                continue
            ring, raw = self._buf.get(name), self.inputs.last_in(name)
            last = max(-math.inf if ring is None else ring.last, -math.inf if raw is None else raw)
            if not t.size or (t[0] > last and not (t[1:] == t[:-1]).any()):
                continue  # the usual push: nothing repeated
            rep = repeated(t, self._taken_times(name))
            if rep.any():
                try:
                    v = np.asarray(tv[1], dtype=np.float64)
                except (TypeError, ValueError):
                    continue
                if v.ndim == 0 or len(v) != len(t):
                    continue
                out = out if out is not None else dict(samples)
                out[name] = (t[~rep], v[~rep])
                dropped[name] = int(rep.sum())
        return (samples if out is None else out), dropped

    def _taken_times(self, name: str) -> np.ndarray:
        """Decision E225: the input times of ``name`` the tracker still knows, sorted: its buffered samples', or
        (decision E239) a resampled stream's last input times and a stream still probed for its rate its probe's
        (the buffer of a resampled stream holds the output grid)."""
        ring = self._buf.get(name)
        own = np.empty(0) if ring is None or name in self.inputs.resamplers else ring.view()[0]
        return np.unique(np.concatenate([own, self.inputs.raw_times(name)]))

    def _count_repeats(self, dropped: dict[str, int]) -> None:
        """Decision E225 (E203's amended count): a taken push's dropped repeats counted; the first adds one line."""
        if not self.dropped_duplicates:
            self._warn(repeats_dropped_line("Tracker.push", "n_dropped_duplicates (per sensor: dropped_duplicates)"))
        for n, k in dropped.items():
            self.dropped_duplicates[n] = self.dropped_duplicates.get(n, 0) + k

    def _clocks_note(self, name: str, t: float | None) -> str:
        """Decision E223: the clause naming the units' start-up clock offset when the lagging stream ``name`` (newest
        sample ``t``, None: never taken) is of the unit whose clock reads behind, or was refused all along, else ''."""
        return "" if self._starts is None else self._starts.note(name, self.waist_clock_offset_s, t is not None)

    def _check_clocks(self, checked: dict, fast: dict | None) -> None:
        """Decision L177: the check's sensors' pushed samples to :class:`ClockCheck`, and its line once."""
        clock = self._clock
        for name in CLOCK_SENSORS:
            if name in checked:
                clock.feed(name, *checked[name])
            elif fast and name in fast:
                clock.feed(name, np.array([fast[name][0]]), np.array([fast[name][1]]))
        line = clock.check()
        if line:
            self._warn(line)

    def _fusion(self, altitude: str, sensors, ends) -> FusedRows | None:
        """Decision E339: the barometric altitude's holder for ``altitude="fused"`` (None for ``"foot"``)."""
        from pdrlearn.kernels.barometer import ALTITUDES, fused_without_barometer

        if altitude not in ALTITUDES:
            raise DataError(f"altitude={altitude!r} is not one of {', '.join(ALTITUDES)} (foot: the strides' own "
                            "height; fused: with the waist barometer, decisions L154, E339)")
        if altitude == "foot":
            return None
        if "wBarometer" not in self.used_sensors:  # as `track --units foot --altitude fused`
            raise DataError(f"altitude='fused' reads the waist barometer (wBarometer), which the tracked units "
                            f"({'+'.join(self.units)}) of bundle {self.bundle.path} do not use: track the foot and "
                            "the waist unit, or altitude='foot' (decision E339)")
        if sensors is not None and "wBarometer" not in sensors:  # decision L154's line: the foot's own height
            # decision E363: the pushed streams lack it (`run` names its session's folder before it gets here)
            self._warn(fused_without_barometer(f"the declared streams (sensors={', '.join(sensors)}) lack"))
            return None
        return FusedRows("wBarometer", end_s=(ends or {}).get("wBarometer"),
                         wait_s=float(self.bundle.manifest["displacement"].get("max_wait_s", 2.0)))

    @property
    def foot_altitude_change_m(self) -> float | None:
        """Decision E339: with ``altitude="fused"``, the foot's own altitude change (m) over the rows returned, of
        which at least one was fused (``track``'s ``info["foot_altitude_change_m"]``, L154); else None."""
        f = self._fused
        return None if f is None or not f.n_fused else float(f.foot_change_m)

    def restart_state(self) -> dict:
        """What a new tracker needs to go on where this one stands (decision L134): ``Tracker(bundle,
        resume=tracker.restart_state())`` measures the stride in progress whole, as this tracker would have; a
        new tracker given only ``start=`` and ``heading_rad=`` loses that stride's turn. Plain numbers and lists
        (:func:`pdrlearn.runtime.restart.restart_state`): ``json.dumps`` saves it."""
        return restart_state(self)

    def _choose_models(self, sensors) -> None:
        """Each task's model for a stream of ``sensors`` (None: unknown, every model's expected), the step graph
        and the window channels it fills (decision E26 amended), with the one warning line for the tasks left
        unclassified; run by ``__init__`` and when an optional stream stops (decision B121: the steps go on as
        a session without it would)."""
        tasks, methods, units, step_graph = self._model_args
        was = set(getattr(self, "unclassified", ()))  # B121: a task left unclassified before is not told again
        fm = self.bundle.manifest["features"]
        ctx = {"signals": fm["signals"], "channel_index": self.ci}
        self.classifiers: dict[str, TaskClassifier] = {}
        for task in tasks:  # check_tasks' list (decision E291: [] classifies no task)
            mu = (methods or {}).get(task)
            meth, unit = mu.split("/") if mu else (None, None)  # checked by check_tasks (B139)
            self.classifiers[task] = TaskClassifier(self.bundle, task, ctx, method=meth, unit=unit, lazy=True,
                                                    units=None if units is None else self.units, sensors=sensors)
        #: decision E26 amended: tasks whose models all read a sensor the stream will not have -> those sensors;
        #: left unclassified (no class: the stride rules act as without a model for them, as ``pdrlearn track``)
        self.unclassified = {t: c.missing for t, c in self.classifiers.items() if c.missing}
        for task in self.unclassified:
            del self.classifiers[task]
        #: one onnxruntime run per step for the chosen models (decision E10); None = per-model path
        self.step_graph = StepGraph.open(self.bundle, self.classifiers) if step_graph else None
        if self.step_graph is not None and sensors is not None and not {  # the graph reads every chosen model's
                s for g, cs in GROUPS.items() if set(cs) & set(self.step_graph.channel_names)  # channels: an
                for s in GROUP_STREAMS[g]} <= set(sensors):  # absent one is NaN -> the per-model path (same numbers)
            self.step_graph = None
        for task, clf in self.classifiers.items():  # per-model sessions: only where the graph does not
            if self.step_graph is None or task not in self.step_graph.tasks:  # classify (errors show here)
                clf.model.open()
        #: the window channels process_step resamples: those the step graph reads when it classifies every
        #: task, else all (None); the other rows stay NaN (decision E13)
        g = self.step_graph
        self._all_channels = frozenset(self.channels)
        self._step_channels = (None if g is None or set(g.tasks) != set(self.classifiers)
                               else frozenset({"t_s"} | {self.channels[j] for j in g.channels.tolist()}))
        new = {t: v for t, v in self.unclassified.items() if t not in was}
        if new:  # one line (decision E26 amended; the no-class rules: C17's streamed ones)
            miss = sorted({s for v in new.values() for s in v})
            it = "it" if len(new) == 1 else "them"
            rules = "; ".join(f"{t}: {_NO_CLASS_RULE.get(t, 'no class')}" for t in new)
            self._warn(f"{', '.join(new)} left unclassified: the stream has no {', '.join(miss)}, "
                       f"which every {'/'.join(self.units)} model of the bundle for {it} reads; "
                       f"the stride rules act as without a model ({rules}), as `pdrlearn track` does "
                       "(push those sensors, or export a model trained without them)")

    @property
    def resampled_hz(self) -> dict[str, float]:
        """Sensor -> its input rate (Hz), for the streams this tracker resamples to ``rate_hz`` (E22)."""
        return {n: r.rate_in for n, r in self.inputs.resamplers.items()}

    # -- classification of given windows (also used by the parity tests) ----------------------------
    def classify(self, W: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """Task -> (classes (n,), probabilities (n, n_classes)) for windows ``W (n, channels, samples)``."""
        cache: dict = {}  # signals and statistics shared by every model of this step
        g = self.step_graph
        probas = g.predict(W) if g is not None else {}
        out = {}
        for task, clf in self.classifiers.items():
            if task in probas:
                p = probas[task]
                out[task] = (clf.class_array[np.argmax(p, axis=1)], p)
            else:
                out[task] = clf.predict(W, cache)
        return out

    def window(self, t0: float, t1: float) -> np.ndarray:
        """The step window of ``[t0, t1]`` from the buffered samples (every channel), built by the shared
        kernel alone (:func:`pdrlearn.kernels.window.fill_step_window`, the training side's)."""
        streams = {k: self._stream(k) for k in self._buf}
        W = np.full((len(self.channels), self.n_samples), np.nan)
        w0, w1 = self.window_bounds(t0, t1, streams)
        short = [(k, float(t[0]), float(t[-1])) for k, (t, _) in streams.items()
                 if len(t) and (t[0] > w0 or t[-1] < w1)]
        if short or not streams:  # decision E63: samples trimmed (or not pushed yet) are not made up
            k, a, b = short[0] if short else ("any sensor", math.nan, math.nan)
            held = f"{k} from {a:.3f} to {b:.3f} s" if short else "no samples"
            raise DataError(f"window({t0:.3f}, {t1:.3f}): the tracker holds {held} only (it drops the samples "
                            "behind the last step boundary less 1 s, and keeps at most buffer_s = "
                            f"{self.buffer_s:g} s); take a step's window in the push that returns the step, before the "
                            "next push (decision E63)")
        fill_step_window(W, streams, w0, w1, channel_index=self.ci, available=available_groups(streams),
                         forward=self.forward, rest_search_s=self.rest_search_s, heading=self.heading_mode)
        return W

    def _window(self, t0: float, t1: float, channels=False):
        """Window (channels x samples) and levelled units of the step; ``channels``: the channels to fill
        (default: those process_step needs, ``self._step_channels``; None = all). The foot unit is
        levelled from the push-time state when it covers the step (decision E15), else by the shared
        kernel; resampling is the shared kernel's (``fill_step_window``'s per-channel path)."""
        channels = self._step_channels if channels is False else channels
        streams = _Views(self._buf)  # a sensor's buffer view is made when a kernel reads it (E16)
        W = _nan_template(len(self.channels), self.n_samples).copy()  # = np.full(..., nan) in one call (E17)
        if self._groups[0] != tuple(self._buf):  # the sensor groups change only when a new sensor arrives
            self._groups = (tuple(streams), available_groups(streams))
        avail = self._groups[1]
        w0, w1 = self.window_bounds(t0, t1, streams)
        need = self._all_channels if channels is None else channels
        waist_acc = not _WAIST_ACC.isdisjoint(need)  # else the waist's levelled acceleration is not computed
        lev = self._levelled(streams, w0, w1, avail, waist_acc)
        tg = w0 + (w1 - w0) * _unit_grid(self.n_samples)
        W[self.ci["t_s"]] = tg - w0
        if not fill_resampled(W, streams, w0, w1, tg, lev, self.ci, avail, need):
            _fill_channels(W, streams, w0, w1, tg, lev, self.ci, avail, need)
        if (w0, w1) != (t0, t1):  # displacement stays stance to stance, like pdrlearn track --streaming
            lev = self._levelled(streams, t0, t1, avail, waist_acc)
        return W, lev

    def _levelled(self, streams, t0: float, t1: float, avail: tuple[str, ...], waist_acc: bool = True):
        """:func:`pdrlearn.kernels.window.levelled_units` of ``[t0, t1]``, the foot from the push-time state
        (:func:`pdrlearn.runtime.stream.foot_levelled`) when it holds the step."""
        kw = {"forward": self.forward, "rest_search_s": self.rest_search_s, "heading": self.heading_mode}
        foot = None
        if self._foot is not None and "foot_acc" in avail and "foot_gyr" in avail:
            foot = foot_levelled(self._foot_state(t1), t0, t1, rest_search_s=self.rest_search_s,
                                 heading=self.heading_mode)
        if foot is None:
            return levelled_units(streams, t0, t1, available=avail, **kw)
        lev = {"foot": foot}
        if "waist_acc" in avail and "waist" in self.forward:  # the waist levelling on Python floats (E16)
            lev["waist"] = waist_entry(streams, t0, t1, self.forward["waist"], "waist_gyr" in avail, waist_acc)
        return lev

    def window_bounds(self, t0: float, t1: float, streams=None) -> tuple[float, float]:
        """Times (s) the classification window of the step ``[t0, t1]`` is cut at: the step itself, or
        with ``features.boundaries == "rest"`` each end moved to the middle of the foot's rest nearby
        (:func:`pdrlearn.kernels.window.rest_boundaries`, the function ``step_windows`` calls)."""
        streams = streams if streams is not None else {k: self._stream(k) for k in self._buf}
        if self.boundaries != "rest" or "fGyroscope" not in streams:
            return t0, t1
        pad = self.rest_search_s + 0.1  # the search span plus the smoothing box's reach
        tg, g = segment(*streams["fGyroscope"], t0 - pad, t1 + pad)
        a, b = rest_boundaries(tg, g, np.array([t0]), np.array([t1]), search_s=self.rest_search_s)
        return float(a[0]), float(b[0])

    # -- streaming ------------------------------------------------------------------------------------
    def _stream(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        return self._buf[name].view()

    def _append(self, name: str, t, v) -> None:
        if (type(t) is np.ndarray and type(v) is np.ndarray and t.shape == (1,) and v.ndim == 2 and v.shape[0] == 1
                and (t.dtype is _F64 or t.dtype == _F64) and (v.dtype is _F64 or v.dtype == _F64)):  # one float64
            # sample: no conversions (decision E16)
            n, t0, vals = 1, t.item(), v.tolist()[0]
        else:
            t = np.asarray(t, dtype=np.float64).reshape(-1)
            n = len(t)
            if n == 0:
                return
            v = np.asarray(v, dtype=np.float64).reshape(n, -1)
            t0 = float(t[0])
            vals = v[0].tolist() if n == 1 else None
        ring = self._buf.get(name)
        if n == 1:  # one sample (streaming sample by sample): the checks on Python floats
            ok = math.isfinite(t0) and all(map(math.isfinite, vals))
        else:  # finite iff the sum is (a sum of finite values overflows only beyond 1e308); else exactly
            ok = math.isfinite(float(np.add.reduce(t))) and math.isfinite(float(np.add.reduce(v, axis=None)))
            ok = ok or bool(np.isfinite(t).all() and np.isfinite(v).all())
        if not ok:
            raise DataError(f"{name}: pushed samples contain NaN/inf; clean the stream before tracking")
        if (ring is not None and t0 <= ring.last) or (n > 1 and not (t[1:] > t[:-1]).all()):
            prev = f" after {ring.last:.3f} s" if ring is not None else ""
            raise DataError(
                f"{name}: pushed timestamps are not increasing (at {t0:.3f} s{prev}); push samples in time order, "
                f"{reorder_hint()}")  # decision E349
        if ring is None:
            ring = self._buf[name] = Ring(v.shape[1])
            self._oldest = min(self._oldest, t0)
            if name in _CARRIED_RINGS:  # decisions E285 / E305: carried_yaw's rings keep their own bound
                self._drop_at_w = min(self._drop_at_w, t0)
            else:
                self._drop_at = min(self._drop_at, t0)
        elif v.shape[1] != ring.v.shape[1]:
            raise DataError(f"{name}: pushed {v.shape[1]} values per sample after {ring.v.shape[1]}; push every "
                            "sample of a sensor with the same number of values")
        if n == 1:
            ring.append1(t0, vals)
            if self._foot is not None and (name == "fAccelerometer" or name == "fGyroscope"):
                self._foot_q.append((name, t0, vals))
        else:
            ring.append(t, v)
            if self._foot is not None and (name == "fAccelerometer" or name == "fGyroscope"):
                self._feed_foot()  # the queued samples first: the state is fed in time order
                self._foot.feed(name, t, v)
        if ring.last > self._latest:
            self._latest = ring.last

    @one_call_at_a_time  # decision E231
    def push(self, samples) -> list[Step]:
        """Add samples; returns the steps completed by them (possibly none).

        ``samples`` : mapping sensor name -> ``(t (n,) s, values (n, k))``, or an iterable of
        measurements with ``t``, ``sensor`` and ``values`` attributes (the Bluetooth parser's output).
        A push without any sample (``{}``, ``[]``, ``{sensor: ([], [])}``) returns no step and changes nothing
        (decision E40).
        """
        if not isinstance(samples, dict):  # Bluetooth measurements: grouped per sensor
            grouped: dict[str, tuple[list, list]] = {}
            for mm in samples:
                ts, vs = grouped.setdefault(mm.sensor, ([], []))
                ts.append(mm.t)
                vs.append(mm.values)
            samples = grouped
        if self.waist_clock_offset_s or self.waist_clock_drift_ppm:  # decisions L177, E229: the waist samples on
            samples = waist_on_foot_clock(samples, self.waist_clock_offset_s,  # the foot clock, before anything else
                                          self.waist_clock_drift_ppm * 1e-6)
        if self.foot_clock_offset_s:  # decision E227: a foot pod rebased after a reconnect, likewise
            samples = waist_on_foot_clock(samples, self.foot_clock_offset_s, prefix="f")
        dropped = None
        if self._drop_dups:  # decision E225: repeated samples dropped before the checks, counted once taken
            samples, dropped = self._without_repeats(samples)
        fast = self._check_push(samples)  # decision E29: every sensor checked before any state changes
        if fast is None:  # decision E40: no sample at all, nothing to do
            if dropped:
                self._count_repeats(dropped)
            return []
        checked, self._checked = self._checked, {}
        spans = {**{n: (f[0], f[0]) for n, f in fast.items()},
                 **{n: (float(t[0]), float(t[-1])) for n, (t, _) in checked.items()}}
        if self._starts is not None and self._starts.contact is None:  # decision E223: the units' clocks at the start
            self._starts.seen(spans)
        self._check_stopped(spans)  # decision B122: E23 before any change
        guard = self._guard
        if guard is not None:  # decision B119: the units of the accelerometers' first seconds, the gyroscopes' windows
            arrays = {n: checked[n] if n in checked else (np.array([fast[n][0]]), np.array([fast[n][1]]))
                      for n in guard.wanted() if n in checked or n in fast}
            ready = guard.check(arrays)
        self._refuse_out_of_range(checked, fast)  # decision B435: after the unit guard's verdict, before any change
        if guard is not None:
            guard.take(arrays, ready)
        if dropped:  # decision E225: counted once every check has passed (E203 amended)
            self._count_repeats(dropped)
        if self._clock is not None:  # decision L177: the raw pushed samples, as the offline check reads a recording
            self._check_clocks(checked, fast)
        if self._foot_q:  # the foot samples of a push that completed a step (decision E21)
            self._feed_foot()
        samples = self.inputs.push(samples)  # the same dict when every stream is at the bundle's rate (E22)
        if samples:
            self._note_resampled()
            buf, foot = self._buf, self._foot_q if self._foot is not None else None
            for name, (t, v) in samples.items():
                # one float64 sample of a buffered sensor, finite, newer than its buffer and of its width (checked
                # by _check_push): appended here without _append's frame (decision E17); anything else (a new
                # sensor, chunks, other dtypes) goes through _append
                f = fast.get(name) if fast else None
                if f is not None:
                    ring = buf[name]
                    i = ring.i1
                    if i < len(ring.t):
                        t0, vals = f
                        ring.t[i] = t0  # Ring.append1
                        ring.v[i] = vals
                        ring.i1 = i + 1
                        ring.last = t0
                        if foot is not None and (name == "fAccelerometer" or name == "fGyroscope"):
                            foot.append((name, t0, vals))  # fed after the step (decision E21)
                        if t0 > self._latest:
                            self._latest = t0
                        continue
                self._append(name, t, v)
            if self._rides is not None and self._rides.name in samples:  # decision E211
                self._rides.push(*samples[self._rides.name])
            if self._baro is not None and self._baro.name in samples:  # decision E232
                self._baro.push(*samples[self._baro.name])
            if self._fused is not None and self._fused.name in samples:  # decision E339
                found = self._fused.push(*samples[self._fused.name])
                if found is not None:  # decision B188, as the offline track: one line, not fused from then on
                    from pdrlearn.kernels.barometer import FUSED_EFFECT, implausible_barometer_message

                    self._warn(implausible_barometer_message(found, FUSED_EFFECT.replace("own,", "own from then on,")))
        for msg in self._frozen.push(checked, fast):  # decision B120: a frozen sensor, one warning per run
            self._warn(msg)
        if self._frozen_foot is not None:  # decision B213: B203's frozen foot IMU, live
            self._frozen_foot_said(self._frozen_foot.push(checked, fast))
        if self._clip is not None:  # decision E303: clipping and stuck axes, live
            for msg in self._clip.push(checked, fast):
                self._warn(msg)
        if self._paused:  # decision E115: a paused waist stream that came back
            self._unpause()
        if self._pushed_gaps:
            self._note_gaps()
        if self._pushed_drops:  # decision E230
            self._count_drops()
        if self._rates is not None:  # decision E309: a rate change, once (after E230's count: B461 corrects it)
            for msg in self._rates.push(checked, fast):
                self._warn(msg)
            if self._rates.new:
                self._rate_changed(self._rates)
        self._detect()
        if self._pending or self._latest >= self._lag_next:  # E23: before a waiting step could go stale
            self._check_lag()
        if self._paused and self._repeats is not None:  # decision E236: a waist paused and not back is said
            line = self._repeats.overdue("waist paused", self._latest)
            if line is not None:
                self._warn(line)
        steps = self._process_ready()
        if self._fused is not None:  # decision E339: the rows whose barometric altitude is known, fused
            steps = self._fused.rows(steps, self._latest)
        # a push that completes steps returns them first, and the next push feeds its foot samples to the
        # push-time levelling (decision E21) and trims (decision E15); pushes in chunks of a stride or more
        # complete a step nearly every time, so trim anyway once the buffers hold twice buffer_s (bounded
        # state, issue 7)
        if not steps:
            if self._foot_q:
                self._feed_foot()
            self._trim()
            if self.speculative:
                self._speculate()
        elif self._latest - self._oldest > 2.0 * self.buffer_s:
            # the lead's merge of E280 with E63: a stride held for L611's verdict may be older than buffer_s when
            # it is returned; its window stays readable in the push that returns it (E63's documented use)
            self._trim(min(st.start_s for st in steps) - _LOOK_BACK_S)
        if self._carry:  # decision L134: the steps the restart state's samples completed come first
            steps, self._carry = [*self._carry, *steps], []
        if self._gait_log is not None:  # decision E320
            self._log_gait(steps)
        return steps

    def _refuse_out_of_range(self, checked: dict, fast: dict) -> None:
        """Decision B435: B425's range check on a push (:func:`~pdrlearn.runtime.replay.refuse_pushed_out_of_range`,
        shared with the lean WaistTracker, B442); ``check_input=False`` (no guard) still refuses the range, as
        B433's opt-out does."""
        refuse_pushed_out_of_range("Tracker", checked, self._guard, fast)

    def _check_push(self, samples: dict) -> dict[str, tuple[float, list[float]]] | None:
        """Decision E29: the input errors of every sensor of a push before any state changes (a push is all or
        nothing: a refused push can be retried without its bad sensor), each one line naming the sensor and
        the fix; and the gaps the push opens (an interval over :data:`GAP_WARN_S`), noted once per gap.
        A one-sample float64 push of a buffered sensor is checked on Python floats (decision E17's path) and
        returned, sensor -> ``(t, values)``, for :meth:`push` to append without checking it again; None for a
        push without any sample (decision E40)."""
        buf, gaps, drops, fast, some = self._buf, None, None, {}, False
        self._checked = {}  # sensor -> its checked (t, values) arrays (not the one-sample path's)
        resampled, isfinite = self.inputs.resamplers, math.isfinite
        for name, tv in samples.items():
            ring = buf.get(name)
            if ring is not None and type(tv) is tuple and len(tv) == 2:  # the one-sample path on Python floats
                t, v = tv
                if (type(t) is np.ndarray and type(v) is np.ndarray and t.shape == _ONE
                        and v.shape == (1, ring.v.shape[1]) and (t.dtype is _F64 or t.dtype == _F64)
                        and (v.dtype is _F64 or v.dtype == _F64) and name not in resampled):
                    t0, vals = t.item(), v.tolist()[0]
                    last = ring.last
                    # finite iff the sum is (finite values overflow only beyond 1e308: the general path then)
                    if t0 > last and isfinite(sum(vals, t0)):
                        fast[name] = (t0, vals)
                        if t0 - last > self._drop_limit(name):  # decision E230 (R2 1: on this path too)
                            drops = drops or []
                            drops.append((name, np.array([t0 - last])))
                        if t0 - last > GAP_WARN_S and t0 - last > self._gap_limit(name):
                            if t0 - last > self.max_gap_s and not self._resumes(name, t0):  # decision B141
                                raise self._jump_error(name, last, t0)
                            gaps = gaps or []
                            gaps.append((name, last, t0))
                        continue
            if name not in self.inputs.used or name in self.inputs.ignored:
                some = some or not _no_samples(tv)
                continue  # ignored by the input stage, whatever it holds
            try:
                t, v = tv
            except (TypeError, ValueError):
                raise DataError(f"{name}: push (t, values) per sensor, got {type(tv).__name__}") from None
            t, v = self._checked_arrays(name, t, v)
            if not len(t):
                continue
            some = True
            self._checked[name] = (t, v)
            raw = self.inputs.last_in(name)
            last = raw if raw is not None else (ring.last if ring is not None else None)
            if last is not None and not t[0] > last:
                raise self._order_error(name, float(t[0]), last, samples)
            self.inputs.check_rate(name, t)  # decision B452: timestamps in ms are named before B141's jump
            tt = t if last is None else np.concatenate(([last], t))
            if len(tt) > 1 and float(tt[-1] - tt[0]) > GAP_WARN_S:
                d = np.diff(tt)
                i = int(np.argmax(d))
                if d[i] > self.max_gap_s and not (i == 0 and self._resumes(name, float(tt[1]))):  # decision B141:
                    raise self._jump_error(name, float(tt[i]), float(tt[i + 1]))  # before any state change
            lim = self._drop_limit(name)
            if len(tt) > 1 and float(tt[-1] - tt[0]) > lim:  # decision E230: intervals of dropped samples
                dd = np.diff(tt)
                drops = drops or []
                drops.append((name, dd[dd > lim]))
            if len(tt) > 1 and float(tt[-1] - tt[0]) > GAP_WARN_S:
                for i in np.flatnonzero(d > self._gap_limit(name, d)).tolist():
                    gaps = gaps or []
                    gaps.append((name, float(tt[i]), float(tt[i + 1])))
        self._pushed_gaps, self._pushed_drops = gaps, drops
        return fast if some or fast else None

    def _drop_limit(self, name: str) -> float:
        """Decision E230: the interval (s) over which two samples of ``name`` enclose dropped samples, 1.5 of its sample
        intervals as ``pdrlearn run``'s read counts them (``Stream.gaps``, B64; not its jitter allowance, B33/B182),
        once its rate is known (declared or probed, E22); ``math.inf`` before."""
        lim = self._drop_lim.get(name)
        if lim is None:
            rate = self.inputs.input_rates_hz.get(name)
            if not rate:
                return math.inf
            lim = self._drop_lim[name] = DROP_FACTOR / rate
        return lim

    def _count_drops(self) -> None:
        """Decision E230: the push's intervals of dropped samples up to B11's 1 s (longer ones are E30's gaps),
        counted per stream for :meth:`drop_stats` and ``flush``'s line."""
        drops, self._pushed_drops = self._pushed_drops, None
        for name, d in drops:
            d = d[d <= MIN_GAP_S]
            if d.size:
                n, longest = self._drops.get(name, (0, 0.0))
                self._drops[name] = (n + int(d.size), max(longest, float(d.max())))

    def _rate_changed(self, rates: RateWatch) -> None:
        """Decision B461: a stream whose rate changed (B457, found by ``rates`` in this push) drops samples when an
        interval is over 1.5 of its NEW period from the change on (E230's limit follows it), and the intervals E230
        counted that lie within 1.5 of their own stretch's period (the watch's count since the last change: a slower
        stretch read at the faster rate, before or after the change) are taken back out of the count (the longest
        stays as counted)."""
        for name, _, period, excess in rates.new:
            self._drop_lim[name] = DROP_FACTOR * period
            if name not in self._drops or not excess:
                continue
            n, longest = self._drops[name]
            if n > excess:
                self._drops[name] = (n - excess, longest)
            else:
                del self._drops[name]

    def gait_strides(self) -> dict[str, np.ndarray]:
        """Decision E320: the gait values of every stride returned so far (``Tracker(gait=True)``), one (B,) array per
        :data:`pdrlearn.runtime.gait.STRIDE_COLUMNS` name (:meth:`pdrlearn.runtime.gait.StrideGait.strides`)."""
        return self._gait().strides()

    def gait_summary(self, other: Tracker | StrideGait | None = None) -> dict:
        """Decision E320: the session's gait summary of the strides returned so far
        (:func:`pdrlearn.runtime.gait.gait_summary`); ``other``: the other foot's ``Tracker(gait=True)`` (or its
        :class:`~pdrlearn.runtime.gait.StrideGait`) of the same walk, this tracker's foot the ``left`` one of the
        result, adding each side's means and the symmetry indices."""
        if isinstance(other, Tracker):
            other = other._gait()
        return gait_summary(self._gait(), other)

    def _log_gait(self, steps: list[Step]) -> None:
        """Decisions E320 / E326: the returned ``steps`` to the gait log with the toe-offs :meth:`_measure` read."""
        self._gait_log.add(steps, [self._toe_offs.pop((st.start_s, st.end_s), math.nan) for st in steps])
        if steps:  # a stride measured and not returned (L611's pedal stroke) is no longer wanted
            last = max(st.end_s for st in steps)
            self._toe_offs = {k: v for k, v in self._toe_offs.items() if k[1] > last}

    def _stride_toe_off(self, t0: float, t1: float, event_s: float) -> float:
        """Decision E326: the toe-off (s) of the stride ``[t0, t1]`` with contact ``event_s`` by L73's kernel on the
        buffered foot gyroscope from the toe-off tracker's ``pad_s`` before ``t0`` (NaN without the gyroscope)."""
        ring = self._buf.get("fGyroscope")
        if ring is None or not event_s == event_s:
            return math.nan
        t, v = ring.view()
        i0 = int(t.searchsorted(t0 - self._toe_off.pad_s, side="left"))
        i1 = int(t.searchsorted(t1, side="right"))
        return float(self._toe_off.stride(t[i0:i1], v[i0:i1, :3], t0, t1, event_s))

    def _gait(self) -> StrideGait:
        if self._gait_log is None:
            raise DataError("Tracker: no gait values kept - create it with Tracker(..., contacts=True, gait=True) "
                            "(decision E320)")
        return self._gait_log

    def drop_stats(self) -> dict[str, dict]:
        """Decision E230: per pushed stream with dropped samples, ``{"intervals": n, "longest_s": s}``: the intervals
        over 1.5 of its sample intervals and up to 1 s (``pdrlearn run``'s count, L77; longer ones are gaps, E30),
        so far. ``flush`` says them in ``run``'s line unless ``stream_checks=False``."""
        return {n: {"intervals": k, "longest_s": m} for n, (k, m) in self._drops.items()}

    def _resumes(self, name: str, t: float) -> bool:
        """Decision E115: a paused waist stream (:attr:`_paused`) whose samples return at ``t`` s in step with the
        others (no further ahead of the newest data than ``max_lag_s``) resumes: its jump is the gap it was silent
        for, not B141's clock glitch."""
        return name in self._paused and t <= self._latest + self.max_lag_s

    def _pausable(self, name: str) -> bool:
        """Decision E115: a required stream of the waist unit, in a Tracker of the foot strides whose heading auto
        takes a stride without waist samples from the foot (E114), does not stop the tracker when it stops."""
        return name.startswith("w") and "foot" in self.units and self.heading_source == "auto"

    def _pause(self, names: list[str], t: float | None) -> None:
        """Decision E115: the required waist streams ``names`` stopped (E23): the strides go on without them, one
        warning line (``t``: the earliest of their last samples); E31's held-value line is not added for them. Each
        stream is taken back when it passes its OWN last sample (a stream that stopped a little later than the others
        is not "back" at the earliest of their times)."""
        for n in names:
            last = self._buf[n].last if n in self._buf else None
            self._paused[n] = -math.inf if last is None or not math.isfinite(last) else float(last)
        self._held.update(names)
        since = "none received" if t is None else f"no samples since {t:.2f} s"
        clocks = self._clocks_note(names[0], t)  # decision E223: two clocks, named first
        self._warn_every("waist paused", (
            f"{', '.join(names)}: {since} while the other sensors are at {self._latest:.2f} s (more than max_lag_s = "
            f"{self.max_lag_s:g} s behind){': ' + clocks + '; meanwhile' if clocks else ':'} the foot's strides go on "
            "without the waist unit, their turn from the foot's gyroscope (decision E114) and their classes from the "
            "waist's last values held (unreliable); its samples are taken again when they return, in step with the "
            "foot's (decision E115); a waist unit that is gone: track the foot alone, units=('foot',) (pdrlearn run "
            "--units foot, decision E26)"))

    def _held_waist(self, lev: dict, t1: float) -> dict:
        """Decision E115: a stride whose end a paused waist stream did not reach is headed by the foot (E114), as a
        replay of the recording heads it (there the gap's far sample shows the gap): ``lev`` with the waist's
        gyroscope left out of the heading (its classes were read before)."""
        if self._paused and "waist" in lev and any(self._buf[n].last < t1 for n in self._paused if n in self._buf):
            w = lev["waist"]
            return {**lev, "waist": (w[0], w[1], None, *w[3:])}
        return lev

    def _unpause(self) -> None:
        """Decision E115: each paused stream whose samples came back resumes (one line per return)."""
        back = [n for n, t in self._paused.items() if n in self._buf and self._buf[n].last > t]
        if back:
            gone = min(self._paused[n] for n in back)
            for n in back:
                del self._paused[n]
            self._warn_every("waist resumed", f"{', '.join(back)}: samples again by {self._latest:.2f} s (none since "
                             f"{gone:.2f} s); the waist unit heads the strides again, from the heading the foot's "
                             "strides carried across the gap (decision E115)")

    def _jump_error(self, name: str, a: float, b: float) -> DataError:
        """Decision B141: the line refusing a push whose ``name`` samples jump from ``a`` to ``b`` s, more than
        ``max_gap_s`` ahead (a clock glitch accepted as a gap would refuse every later sample of the true clock)."""
        return DataError(
            f"{name}: pushed timestamps jump {b - a:+.2f} s ahead ({a:.3f} -> {b:.3f} s), more than max_gap_s = "
            f"{self.max_gap_s:g} s: a clock glitch? The push is refused and the tracker is unchanged (decision B141); "
            "push those samples with their right times, or, if the sensors really were silent that long, go on with "
            "old.flush() (the steps it still holds) and a new Tracker(bundle, start=tuple(old.position), "
            "heading_rad=old.heading), or give Tracker(max_gap_s=...)")

    def _order_error(self, name: str, t0: float, last: float, samples: dict | None = None) -> DataError:
        """Decisions E225 / E227: the refusal of a push whose first ``name`` sample (``t0`` s) is not after the
        stream's newest (``last``): a duplicate, a clock that went back (a reconnected pod) or a late sample;
        decision E243: with the push's other units whose clocks went back too (``samples``: the push)."""
        unit, raw = unit_of(name), self.inputs.last_in
        # the other unit's newest input sample (decision E249: a resampled stream's ring holds the output grid,
        # behind its input by the low-pass delay), as the order check itself reads its own stream's
        other = [r.last if raw(n) is None else raw(n) for n, r in self._buf.items() if unit_of(n) not in (None, unit)]
        return order_error(name, t0, last, duplicate=bool(repeated([t0], self._taken_times(name))[0]),
                           max_lag_s=self.max_lag_s, offset_s=self._clock_offset(unit),
                           other_newest=max(other) if other else None, note=self._jumped_note(t0),
                           also_back=self._also_back(unit, samples) if samples is not None else None,
                           drift={"waist": self.waist_clock_drift_ppm * 1e-6})  # decision E248

    def _clock_offset(self, unit: str | None) -> float:
        """The offset (s) ``rebase_clock`` last gave ``unit``'s clock (the waist's ``waist_clock_offset_s``)."""
        return float(getattr(self, f"{unit}_clock_offset_s", 0.0)) if unit else 0.0

    def _also_back(self, unit: str, samples: dict) -> dict:
        """Decision E243: the units of the push ``samples`` (the tracker's clock) other than ``unit`` whose clock went
        back too (a stream's first sample more than ``max_lag_s`` before its newest, no repeat of a taken sample, not
        inside a B141 jump): unit -> (their first sample, their streams' newest, the unit's offset now)."""
        out: dict[str, tuple[float, float, float]] = {}
        for name, tv in samples.items():
            u = unit_of(name)
            if u in (None, unit) or name not in self.inputs.used or name in self.inputs.ignored:
                continue
            try:
                t = np.asarray(tv[0], dtype=np.float64).reshape(-1)
            except (TypeError, ValueError, IndexError):
                continue
            raw, ring = self.inputs.last_in(name), self._buf.get(name)
            last = raw if raw is not None else (ring.last if ring is not None else None)
            if (not t.size or last is None or not last - t[0] > self.max_lag_s or self._jumped_note(float(t[0]))
                    or repeated(t[:1], self._taken_times(name))[0]):
                continue
            a, b, _ = out.get(u, (math.inf, -math.inf, 0.0))
            out[u] = (min(a, float(t[0])), max(b, float(last)), self._clock_offset(u))
        return out

    def _jumped_note(self, t: float) -> str:
        """Decision B141: for a refused sample at ``t`` s inside a gap the tracker accepted (a forward jump of its
        clock), what that means and the one way on; else ''."""
        for a, b, *_ in reversed(self._gap_marks):
            if a < t < b:
                return (f"; the tracker accepted a jump of its clock from {a:.3f} to {b:.3f} s as a gap (warned), so "
                        f"every sample before {b:.3f} s is refused from now on: if that jump was a clock glitch, only "
                        "old.flush() and a new Tracker(bundle, start=tuple(old.position), heading_rad=old.heading) "
                        "go on (decision "
                        f"B141; max_gap_s = {self.max_gap_s:g} s refuses longer jumps)")
        return ""

    def _gap_limit(self, name: str, d: np.ndarray | None = None) -> float:
        """Decision E30: the interval (s) beyond which two samples of ``name`` enclose a gap: GAP_WARN_S, or 1.5
        of its sample intervals for a slow stream (B11's gap; a 1 Hz barometer has no gap every second). The
        interval is the stream's known rate's, else the median of its intervals so far (those being probed, E22,
        and ``d``, the push's); with fewer than 3 of them, none is a gap yet."""
        rate = self.inputs.input_rates_hz.get(name)
        if rate:
            return max(GAP_WARN_S + GAP_TOL_S, 1.5 / rate)  # decision E230: not by float rounding
        p = self.inputs._probe.get(name)
        seen = [np.diff(np.concatenate(p[0]))] if p and p[0] else []
        d = np.concatenate([*seen, d]) if d is not None else (seen[0] if seen else np.empty(0))
        return max(GAP_WARN_S + GAP_TOL_S, 1.5 * float(np.median(d))) if len(d) >= 3 else math.inf

    def _note_gaps(self) -> None:
        """Decision E30: one warning per gap the push opened (the streams that show it, its length and where),
        the foot gaps over :data:`GAP_LONG_S` kept for :meth:`process_step` (the stride across one moves 0 m)."""
        gaps, self._pushed_gaps = self._pushed_gaps, None
        new: list[list] = []  # [start, end, long, names]
        for name, a, b in gaps:
            if name == "wGyroscope" and b - a > GAP_LONG_S:  # decision E299: the heading's own gaps
                self._heading_gaps = [*self._heading_gaps[-15:], (a, b)]
            long = name in _FOOT_GAP_STREAMS and b - a > GAP_LONG_S
            if long or name in _FOOT_IMU:
                self._foot_gaps.append((a, b, long, name in _FOOT_IMU))
            if long:  # decision E46: the stretch it lies in becomes one gap row
                self._row_gaps.append((a, b))
            for g in [*new, *self._gap_marks]:
                if a < g[1] and b > g[0]:  # the same gap, seen in another stream
                    if len(g) > 3:
                        g[3].append(name)
                        g[2] = g[2] or long
                    elif long and not g[2]:  # a gap announced as bridged turns out to be a long foot gap
                        g[2] = True
                        new.append([a, b, True, [name]])
                    elif name == "wGyroscope" and b - a > GAP_LONG_S and self._bridged():  # decision E299: the
                        self._heading_gap_after(a, b)  # heading's own gap, after a foot gap's line
                    break
            else:
                new.append([a, b, long, [name]])
        for a, b, long, names in new:
            self._gap_marks.append([a, b, long])
            turn = ((_L91_TURN if not any(x < b and y > a for x, y in self._heading_gaps)
                     else _e299_turn(self.bridge_cycle))
                    if self._bridged() else
                    "keeps the heading: the turn inside the gap is unknown, the heading after it is uncertain (L90)"
                    ) if _FOOT_IMU.intersection(names) else "keeps the heading"  # decision L92
            what = (f"a gap longer than {GAP_LONG_S:g} s (B11): the stride across it moves 0 m, {turn} and "
                    "has no classes; no step is counted inside it, as `pdrlearn track` counts no displacement there"
                    if long else
                    f"longer than {GAP_LONG_S:g} s in a stream whose gaps do not stop the strides (B11 zeroes only a "
                    "foot stream's; E64): the strides go on with it interpolated across the gap, as `pdrlearn track` "
                    "does, " + ("so a stride across it turns with the foot's gyroscope (E114) and its classes are "
                                "unreliable" if self._waist_gap_foot_heads(names) else
                                "so the heading and classes of the strides across it are unreliable")
                    if b - a > GAP_LONG_S else
                    f"bridged (interpolated) as `pdrlearn track` does up to {GAP_LONG_S:g} s (B11): the stride across "
                    "it has an unreliable length, height change and heading, and no classes when the gap is the "
                    "foot's")
            if long and turn == _L91_TURN:  # E299 amended (R3 F5): a waist gyroscope gap pushed later rewrites it
                self._l91_lines = [*self._l91_lines[-15:], (a, b, len(self.warnings))]
            self._warn(f"{', '.join(names)}: no samples for {b - a:.2f} s ({a:.2f}-{b:.2f} s); {what} (decision E30)")
        del self._gap_marks[:-16]  # the latest few: a gap is seen by every stream within a few pushes

    def _heading_gap_after(self, a: float, b: float) -> None:
        """Decision E299 (amended, session 45, FM, review R3 F5): the waist gyroscope's own gap ``a``-``b`` s pushed
        after a foot gap's line: a foot line that promised the waist's turn (L91) is rewritten in place to E299's
        clause (the foot's gap pushed first, the usual order when the waist's packets lag); else E299's line."""
        for x, y, at in self._l91_lines:
            if x < b and y > a and _L91_TURN in self.warnings[at]:
                self.warnings[at] = self.warnings[at].replace(_L91_TURN, _e299_turn(self.bridge_cycle))
                log.warning("bundle %s: %s", self.bundle.path, self.warnings[at])
                return
        self._warn(heading_gap_line(a, b, self.bridge_cycle and any(  # decision E365: inside E354's bridge
            long and imu and x < b and y > a for x, y, long, imu in self._foot_gaps)))

    def _waist_gap_foot_heads(self, names) -> bool:
        """Decision B231: whether the gap of the streams ``names`` (waist streams only) holds a waist accelerometer /
        gyroscope gap, whose strides the foot heads (E114: heading auto, the foot unit tracked)."""
        return (self.heading_source == "auto" and "foot" in self.units and all(n.startswith("w") for n in names)
                and bool({"wAccelerometer", "wGyroscope"}.intersection(names)))

    def _compassed(self) -> bool:
        """Decision E361: the waist compass re-anchors the heading after a waist gap (E354's line bridges it and the
        waist unit has a magnetometer)."""
        return self._compass is not None and self.bridge_cycle and "wMagneticField" in self._buf and self._bridged()

    def _bridged(self) -> bool:
        """Decision L91: a stride across a foot IMU gap turns by the waist gyroscope (the waist heads the
        strides: heading_source auto / waist-gyro with the waist unit's accelerometer and gyroscope)."""
        return (self.waist_bridge and self.heading_source in ("auto", "waist-gyro") and "waist" in self.units
                and "waist" in self.forward and "wGyroscope" in self._buf and "wAccelerometer" in self._buf)

    def _checked_arrays(self, name: str, t, v) -> tuple[np.ndarray, np.ndarray]:
        """``(t (n,), values (n, k))`` as float64 with k the sensor's width, finite and increasing; else a
        one-line :class:`DataError` naming the sensor and the expected shape (decision E29)."""
        t, v = checked_samples(name, t, v, SENSOR_WIDTH.get(name))
        if (i := first_out_of_order(t)) is not None:
            dup = ("; that sample repeats the one before it, a duplicate: Tracker(drop_duplicate_timestamps=True) "
                   "drops such samples (decision E225)" if t[i] == t[i - 1] else "")
            if (w := live_wrap(float(t[i - 1]), float(t[i]))) is not None:  # decision E297: a counter wrap in a push
                dup = (f"; the step back is a {w[0]}-bit counter of {w[1]:g} s ticks wrapping, not samples out of "
                       f"order: unwrap each pod's counter before pushing, pdrlearn.runtime.CounterUnwrapper(bits="
                       f"{w[0]}, tick_s={w[1]:g}) (decision E297)")
            raise DataError(f"{name}: pushed timestamps are not increasing (at {t[i]:.3f} s after {t[i - 1]:.3f} s); "
                            f"push samples in time order{dup or ', ' + reorder_hint()}")  # decision E349
        return t, v

    def _feed_foot(self) -> None:
        """Feed the queued one-sample foot pushes to the push-time levelling, in push order."""
        q, feed1 = self._foot_q, self._foot.feed1
        for name, t, vals in q:
            feed1(name, t, vals)
        q.clear()  # in place: push holds the list while it appends

    def _foot_state(self, t1: float) -> FootLevelling:
        """The push-time levelling state for a step ending at ``t1`` (s), with the queued foot samples fed
        when the step could read them (decision E21): a step reads the foot samples up to the first at or
        after ``t1``, and the queue holds the newest. The usual queue (one accelerometer and one gyroscope
        sample of one time, no sample waiting for its partner, room in the state's arrays) with a state
        already past ``t1`` changes neither the step's samples, nor the state's clock check, nor its anchor
        (a reallocation re-anchors the running product), so it waits for the next push: the step's numbers
        are those of the state fed first, bit for bit."""
        f, q = self._foot, self._foot_q
        if q and not (f.last > t1 and len(q) == 2 and q[0][1] == q[1][1] and q[0][0] != q[1][0]
                      and f._pa is None and f._pg is None and f.i1 < len(f.a["t"])):  # no re-anchoring
            self._feed_foot()
        return f

    @one_call_at_a_time  # decision E231
    def flush(self) -> list[Step]:
        """Process the detected steps still waiting for other sensors' samples (end of a recording); the
        resampled streams' last samples (their filter's delay, decision E22) are buffered first."""
        if self._foot_q:
            self._feed_foot()
        guard, self._guard = self._guard, None  # checked once: a refusal here does not repeat on every flush
        if guard is not None:  # decision B119: a stream shorter than GUARD_S, checked on what it has
            guard.finish()
        if self._clock is not None:  # decision L177: all the events, as the offline check on the recording
            line = self._clock.check(final=True)
            if line:
                self._warn(line)
        for name, (t, v) in self.inputs.flush().items():
            self._append(name, t, v)
        if self._frozen_foot is not None:  # decision B213: the last block, on what it holds
            self._frozen_foot_said(self._frozen_foot.flush())
        clip, self._clip = self._clip, None  # decision E303: the last blocks, once
        for msg in clip.flush() if clip is not None else ():
            self._warn(msg)
        rates, self._rates = self._rates, None  # decision E309: the last blocks, once
        for msg in rates.flush() if rates is not None else ():
            self._warn(msg)
        if rates is not None:
            self._rate_changed(rates)
        self._detect()
        steps = self._process_ready(force=True)
        steps += self._release(self._loops.flush())  # decision E280: the last strides, judged on what is known
        if self._fused is not None:  # decision E339: every held row, on the barometer pushed
            steps = self._fused.rows(steps, self._latest, final=True)
        self._log_pedal()
        self._trim()
        self.height_checks()  # decision E47: the end of a recording
        if self._repeats is not None:  # decision E236: the repeated lines held back since their last, summed up
            for line in self._repeats.summary(self._latest):
                self._warn(line)
        if self._drops and self.stream_checks and not self._drops_said:  # decision E230: run's line (L77), once
            self._drops_said = True
            self._warn(streamed_drops_line([(n, k, m) for n, (k, m) in self._drops.items()]))
        if self._baro is not None:  # decision E232: run's L145 line on the whole stream
            line = self._baro.line(final=True)
            if line and line not in self.warnings:
                self._warn(line)
        self._warn_unused_fixes()  # decision D21
        self._warn_out_of_domain()  # decision E105
        self._warn_turning_lengths()  # decisions C89 / C94
        self._slow_line()  # decision E350
        if self._carry:  # decision L134
            steps, self._carry = [*self._carry, *steps], []
        if self._gait_log is not None:  # decision E320
            self._log_gait(steps)
        return steps

    def _process_ready(self, force: bool = False) -> list[Step]:
        """Process pending steps once every buffered sensor has samples past the step's end (sensors
        stream with different delays; a window cut before the waist data arrives would be wrong)."""
        if not self._pending and not self._loops.held:
            return []
        paused = self._paused  # decision E115: not waited for
        ends = [r.last for n, r in self._buf.items() if n not in paused]
        required = self.required
        latest = min(ends + [-np.inf for n in required if n not in self._buf])
        # a sensor that stopped must not hold the steps forever: the thesis asks for < 2 s delay
        stale = max(ends) - self._wait_s
        out = []
        if not self._pending:  # decision E280: held strides whose chain can no longer go on are judged
            return self._release(self._loops.expire(max(latest, stale), self._chain_quiet_s))
        while self._pending and (force or self._pending[0][1] + self._lookahead_s < max(latest, stale)):
            if self._lull_wait(max(latest, stale), force):  # decision E345: its end may be a swing's lull
                break
            if self._unchecked:  # decision B140: before the first step's window is cut
                self._check_unpushed(*self._pending[0])
            t1 = self._pending[0][1]
            if latest < t1 - self._held_s:  # decision E31: a stream's last value held for this step
                self._note_held(t1, force)
            t0, t1 = self._pending.pop(0)
            if self._turn_in_place(t0, t1):  # decision L742: no stride; the next one's gap yaw keeps the turn
                continue
            snap = self._before()  # decision E280: what a restart state holds while the stride is held
            try:
                if self._pitched(t0, t1):  # decision B474: a foot pitched from its first rest is B131's posture
                    raise VerticalAxisError("foot pitched at rest")
                rec = self._measure(t0, t1)
            except VerticalAxisError:
                if not (self.n_steps or self._loops.seen):  # decision B131: the session starts so: the frame
                    raise  # cannot be judged
                rec = ("posture", t0, t1, _pedal.unjudged_row(t0, t1))  # E280: in its chain, not judged
            except DataError as exc:  # decision B123: the kernel's zero gravity, named by sensor and time
                if not str(exc).startswith("gravity_rotation:"):
                    raise
                raise DataError(self._no_gravity(t0, t1)) from None
            out += self._release(self._loops.add(rec[3], (rec, snap)))
        return out

    def _lull_wait(self, now: float, force: bool) -> bool:
        """Decision E345 (:mod:`pdrlearn.kernels.lull`): True while the first pending stride must wait (its end's rest
        is not readable yet, or its end is a lull and the stride after it is not known yet); a stride ending at a lull
        is joined with the next (``track --streaming``'s :func:`~pdrlearn.kernels.lull.join_lulls`, pair by pair).
        ``now``: the data's time (s) every stream has reached; ``force``: the end of the recording."""
        seg = self.segmenter
        if not seg.lull_join or "fAccelerometer" not in self._buf:
            return False
        a, b = self._pending[0]
        reach = _pedal.REST_WINDOW_S  # L611's rest test reads the samples within this of the instant
        if not force and now < b + reach:
            return True
        if not self._moving(b) or self._moving(a):
            return False
        if len(self._pending) < 2:  # the stride after it: still to come while the segmenter may return it
            return not force and seg.may_open_at(b) and seg.last_t - b <= seg.max_step_s + 2 * seg.half + 1.0
        nxt = self._pending[1]
        if nxt[0] != b:
            return False
        if not force and now < nxt[1] + reach:
            return True
        if _lull.joins((a, b), nxt, False, True, self._moving(nxt[1]), seg.max_step_s):
            self._pending[0:2] = [(a, nxt[1])]
        return False

    def _moving(self, at_s: float) -> bool:
        """Decision E345: L611's rest test at one instant on the buffered foot accelerometer (L621's live reading)."""
        t, acc = self._stream("fAccelerometer")
        i, j = np.searchsorted(t, (at_s - 2 * _pedal.REST_WINDOW_S, at_s + 2 * _pedal.REST_WINDOW_S))  # the test's
        return bool(_lull.moving_at(t[i:j], acc[i:j], at_s, self._foot_rest.g_rest)[0])  # samples and a margin

    def _pitched(self, t0: float, t1: float) -> bool:
        """Decision B474: whether the foot rests at the window's start pitched more than 45 deg further from level than
        at the most level rest of the strides so far (:func:`~pdrlearn.kernels.window.pitched_from`, ``track
        --streaming``'s test); the first stride (B131 judges its frame) starts that reference."""
        if "foot" not in self.forward or not all(n in self._buf for n in ("fAccelerometer", "fGyroscope")):
            return False
        if self._pitch_ref is None:
            self._pitch_ref = PitchReference()
        return self._pitch_ref.pitched(self._stream, self.forward["foot"], t0, t1, rest_search_s=self.rest_search_s)

    def _turn_in_place(self, t0: float, t1: float) -> bool:
        """Decision L742: whether the foot window ``[t0, t1]`` is a turn on the spot (:func:`~pdrlearn.kernels.spin.
        turn_in_place`, offline's rule); the first one warns one line."""
        if not all(n in self._buf for n in ("fAccelerometer", "fGyroscope")):
            return False
        if not _spin.turn_in_place(*self._stream("fAccelerometer"), *self._stream("fGyroscope"), t0, t1):
            return False
        self.n_turns_in_place += 1
        turn = _spin.spin_turn(self._stream, t0, t1)  # its turn goes to the next foot-headed stride
        self._spun = (turn + (self._spun[0] if self._spun is not None else 0.0), t1)
        if self.n_turns_in_place == 1:
            self._warn(_spin.spin_line())
        return True

    def _before(self) -> tuple:
        """Decision E280: the measuring state before a stride (the last stride's end, E272's bias): a restart state
        taken while strides are held (L611's verdict pending) restarts from the first held one's. Review R1 F3: and
        L621's live foot rest reading (its readings and still-sample count), which measuring the stride adds to.
        Decision E356: and E354's held waist gap (its seconds and the mean rate before it), which measuring a bridged
        stride holds and the stride after it takes; decision E365: and the last measured stride's mean rate."""
        stop, rest, cycle = self._stop_bias, self._foot_rest, self._cycle
        return (self._prev_end, None if stop is None else (stop.rps, stop.n_stops), (list(rest.readings), rest.n_still),
                (cycle.gap_s, cycle.before, cycle.last),  # decision E356: E354's waist gap held (E365: the last rate)
                None if self._compass is None else self._compass.state())  # decision E370: E361's compass

    @property
    def _restart_from(self) -> tuple:
        """Decision E280: :meth:`_before` the first held stride, or the state now when none is held."""
        return self._loops.held[0][1][1] if self._loops.held else self._before()

    def _release(self, judged: list) -> list[Step]:
        """Decision E280: the measured strides whose L611 verdict is final (:class:`~pdrlearn.kernels.pedal.
        LiveLoops`), placed in order: a posture noted (B131), a pedalling stride's turn kept and its span warned, the
        rest emitted."""
        out = []
        for (rec, _), pedal in judged:
            if rec[0] == "posture":
                self._note_posture(rec[1], rec[2])
                continue
            step = self._apply(rec, pedal)
            if step is None:
                self._note_pedal(rec[1], rec[2])
            else:
                out += self._emit(step)
        return out

    def _note_pedal(self, t0: float, t1: float) -> None:
        """Decision E280: L611's one warning line, as ``track --streaming``'s, widened in place in ``warnings`` as
        strides are removed; logged by :meth:`_log_pedal`."""
        if self._pedal_line is None:
            self._pedal_line = [[], len(self.warnings), None]
            self.warnings.append("")
        spans, at, _ = self._pedal_line
        _pedal.add_span(spans, t0, t1)
        self.warnings[at] = _pedal.REMOVED + _pedal.loop_part(spans)

    def _log_pedal(self) -> None:
        """Decision E280: at a flush (the end of a recording) L611's line is logged as it stands, once (again when a
        later flush changed it), so the log has ``track --streaming``'s whole line, not its first stride's."""
        self._log_widened(self._pedal_line, 1, 2)
        self._log_widened(self._posture, 3, 4)  # decision B473: B131's line as it stands (the whole posture)

    def _log_widened(self, p: list | None, at: int, logged: int) -> None:
        """Decisions E280 / B473: log the warning ``self.warnings[p[at]]`` of a line widened in place unless it is
        ``p[logged]``, the one last logged (then noted there)."""
        if p is not None and self.warnings[p[at]] != p[logged]:
            p[logged] = self.warnings[p[at]]
            log.warning("bundle %s: %s", self.bundle.path, p[logged])

    def _check_unpushed(self, t0: float, t1: float) -> None:
        """Decision B140: with no ``sensors=`` declared, a sensor a task's model reads that nothing has pushed by
        the time the first step is classified is a one-line :class:`DataError` (raised by that push, before the
        step is cut) naming the ``sensors=[...]`` that tracks such a stream (those tasks left to another model
        or unclassified, as ``pdrlearn track`` does); it was "step features are NaN" from inside the step."""
        pushed = set(self._buf) | set(self.inputs.ignored) | {n for n in self.used_sensors
                                                              if self.inputs.last_in(n) is not None}
        need = {t: sorted(c.reads - pushed) for t, c in self.classifiers.items() if c.reads - pushed}
        if not need:
            self._unchecked = False
            return
        gone = sorted({s for v in need.values() for s in v})
        have = [n for n in self.used_sensors if n in pushed]
        models = ", ".join(f"{t} ({self.classifiers[t].method}/{self.classifiers[t].unit})" for t in need)
        units = "" if self.units == self.bundle.body_units else f"units={self.units}, "
        it = "it" if len(gone) == 1 else "them"
        raise DataError(f"bundle {self.bundle.path}: nothing pushed {', '.join(gone)} by the first step "
                        f"({t0:.3f}-{t1:.3f} s), and the model of {models} reads {it}; for a stream without {it} "
                        f"declare its sensors, Tracker(bundle, {units}sensors={have}) (then classified as `pdrlearn "
                        f"track` does without {it}), else push {it} from the first samples")

    def _note_posture(self, t0: float, t1: float) -> None:
        """Decision B131: a step whose foot rests with the declared forward axis (nearly) vertical after steps whose
        frame was fine is a posture (kneeling, crawling), not a wrong meta.json: the step is skipped (the position
        holds) and one warning says when; later such steps widen its span and count."""
        if self._posture is None:
            self._posture = [t0, t1, 0, len(self.warnings), None]
            self.warnings.append("")
        p = self._posture
        p[1], p[2] = max(p[1], t1), p[2] + 1
        self.warnings[p[3]] = posture_warning(p[2], p[0], p[1])
        if p[2] == 1:  # the first at once; decision B473: the whole span again at a flush (_log_pedal)
            self._log_widened(p, 3, 4)

    def _note_turn_tally(self, label, length_m: float, turn_rad: float) -> None:
        """Decisions C89 / C94: the classifier's length class (before C88) against the stride's measured length."""
        if self._turn_tally is None:
            self._turn_tally = [_turn_length.TurnTally(), None]
        self._turn_tally[0].add(label, length_m, turn_rad, self.bounds)

    def _warn_turning_lengths(self) -> None:
        """Decisions C89 / C94: at a flush (the end of a recording), the one line on the strides counted so far, as
        track --streaming's at its end; a later flush with a changed count replaces it in place (and logs it)."""
        tally = self._turn_tally
        line = None if tally is None else tally[0].line(replaced=_turn_length.TURN_LENGTH_RULE)
        if line is None or (tally[1] is not None and self.warnings[tally[1]] == line):
            return
        if tally[1] is None:
            tally[1] = len(self.warnings)
            self._warn(line)
        else:
            self.warnings[tally[1]] = line
            log.warning("bundle %s: %s", self.bundle.path, line)

    def _no_gravity(self, t0: float, t1: float) -> str:
        """Decision B123: the line for a step whose accelerometer gives no gravity to level it by (the stride
        kernel's ``gravity_rotation``): the accelerometers reading ~0 over the step and its look-back, and when."""
        dead = []
        for name in ("fAccelerometer", "wAccelerometer"):
            if name in self._buf:
                t, v = self._stream(name)
                k = (t >= t0 - _LOOK_BACK_S) & (t <= t1)
                zero = np.linalg.norm(v[k], axis=1) < 1e-6
                if zero.any():
                    dead.append(f"{name} reads 0 in {int(zero.sum())} of its {int(k.sum())} samples of "
                                f"{float(t[k][zero][0]):.2f}-{float(t[k][zero][-1]):.2f} s")
        what = "; ".join(dead) or "fAccelerometer / wAccelerometer give a zero or non-finite mean at rest"
        return (f"{what}: the step {t0:.2f}-{t1:.2f} s has no gravity to level the unit by (an accelerometer that "
                "stopped or sends zeros); reconnect it and start a new Tracker (decision B123)")

    def _emit(self, step: Step) -> list[Step]:
        """Decision E46 (L67's rule on the streamed strides): a stride that touches a foot gap is not emitted; the
        stretch from the last emitted stride's end to the next stride that touches none, when a foot gap over
        :data:`GAP_LONG_S` lies in it, is emitted as one 0 m row just before that stride (``gap_s``: the longest
        such gap; ``heading_rad``: the previous row's, decision L76). None before the first emitted stride."""
        if step.gap_s > 0:
            if self._kept is not None and self._gap_row is None:
                self._gap_row = [self._kept[0], step.gap_s]
            elif self._gap_row is not None:
                self._gap_row[1] = max(self._gap_row[1], step.gap_s)
            return []
        out = []
        if self._kept is not None:
            a, b = self._kept[0], step.start_s
            longest = max([g1 - g0 for g0, g1 in self._row_gaps if g0 < b and g1 > a], default=0.0)
            if self._gap_row is not None:
                longest = max(longest, self._gap_row[1])
            if longest > 0 and b > a:
                x, y, z = self._kept[2]
                out.append(Step(a, b, {}, {}, 0.0, 0.0, self._kept[1], x, y, z, gap_s=longest))
                self.n_steps += 1
        self._gap_row = None
        # decision E51: IC to IC with the row emitted before (a gap row between: none), L66/L80's rule
        prev = self._kept[3] if self._kept is not None and not out else None
        if prev is not None and step.event_s == step.event_s and not step.impossible:  # L97: no stride time
            d = float(stride_times((prev[0], step.start_s), (prev[1], step.end_s), (prev[2], step.event_s))[1])
            if d == d:  # a missing value stays the one math.nan (steps compare equal as dicts, E21/E24's tests)
                step.stride_time_s = d
        if prev is not None and not step.impossible and self._running(step, prev):  # decision E325
            step.flags = (*step.flags, "running")
        if prev is not None and not step.impossible:  # decision E350: L95's figures of the stream, judged at flush
            self._note_range(step, prev)
        self._kept = (step.end_s, step.heading_rad, (step.x, step.y, step.z),  # L97: a zeroed stride ends none
                      (step.start_s, step.end_s, math.nan if step.impossible else step.event_s))
        self._row_gaps = [g for g in self._row_gaps if g[1] > step.end_s]
        if self._rides is not None:  # decision E211: a ride in the standstill before it (none after a gap row)
            ride = self._rides.line(step.start_s if prev is None else prev[1], step.start_s)
            if ride is not None:
                self._warn(ride)
        out.append(step)
        for st in out:  # decisions D19-D21: the fixes added so far, used at the step their time falls in
            fused = self._fuse_step(st.start_s, st.end_s, st.length_m, st.heading_rad)
            if fused is not None:
                st.x, st.y = fused
            if self._baro is not None:  # decision E232: the barometer's altitude at each row's end
                self._baro.row(st.start_s, st.end_s, st.z, st.dz_m)
        return out

    def height_checks(self) -> dict:
        """Decisions L69 / C28 (E47) over the strides processed so far, with ``pdrlearn track --streaming``'s
        arguments and the one implementation (:mod:`pdrlearn.kernels.altitude_check`): without a terrain
        classifier, whether the altitude is the foot's integrated height (the streamed rules keep each stride's
        height, no L39); with one, whether its classes contradict the integrated heights. Each warning is logged
        and added to ``warnings`` once. Returns ``{"altitude_check": ..., "terrain_dz_check": ...}`` (the one
        that does not apply is None), as ``track``'s ``info``."""
        from pdrlearn.kernels.altitude_check import integrated_altitude_check, terrain_dz_check

        out = {"altitude_check": None, "terrain_dz_check": None}
        if not self._heights:
            return out
        terrain, raw, dz = self._heights.columns()
        if "terrain" in self.classifiers:
            msg, out["terrain_dz_check"] = terrain_dz_check(terrain, raw, dz)
        else:
            msg, out["altitude_check"] = integrated_altitude_check(dz, levelled=False)
        if msg and msg not in self.warnings:
            self._warn(msg)
        return out

    def _note_held(self, t1: float, force: bool = False) -> None:
        """Decision E31: one warning per stream whose last sample is more than ``max_wait_s`` before the end of
        a step processed without it (E9's held values: ``max_lag_s = inf``, or the end of a recording); E39: and
        more than :data:`HELD_INTERVALS` of its own sample intervals (a 0.2 Hz barometer is not held after 2 s)."""
        held = [n for n, r in self._buf.items() if r.last < t1 - self._held_limit(n) and n not in self._held]
        if held:
            self._held.update(held)
            last = min(self._buf[n].last for n in held)
            why = ("max_lag_s = inf, decision E9" if self.max_lag_s == math.inf else  # decision E65: the reason
                   "flush() at the end of the stream" if force else f"up to max_wait_s = {self._wait_s:g} s")
            self._warn(f"{', '.join(held)}: no samples since {last:.2f} s; the step ending at {t1:.2f} s and those "
                       f"after it are measured with their last values held ({why}): heading and "
                       "classes that read them are unreliable; when its samples return the same Tracker goes on (a "
                       "pod that reconnected with its clock restarted: rebase_clock, decision E227), a sensor that is "
                       "gone: track without it (units=('foot',) for the waist; decision E31)")

    def _held_limit(self, name: str) -> float:
        """Decision E39: how long (s) a stream may have sent nothing before the end of a step before its last value
        counts as held: ``max_wait_s``, or :data:`HELD_INTERVALS` of its own sample intervals when longer (its
        known rate, E22, else the median interval of its buffer; none yet: ``max_wait_s``)."""
        rate = self.inputs.input_rates_hz.get(name)
        if rate:
            return max(self._held_s, HELD_INTERVALS / rate)
        t = self._buf[name].view()[0]
        return max(self._held_s, HELD_INTERVALS * float(np.median(np.diff(t)))) if len(t) > 2 else self._held_s

    def _note_resampled(self) -> None:
        """The input stage's lines (decision E22) once each: the resampling in ``warnings`` and logged at
        warning level (``pdrlearn run`` prints it as its one line); an ignored unused stream logged at debug
        level only (``inputs.ignored`` names it)."""
        msgs = self.inputs.messages
        while msgs:
            level, m = msgs.pop(0)
            if level >= logging.WARNING:
                self.warnings.append(m)
            log.log(level, "bundle %s: %s", self.bundle.path, m)

    def _check_lag(self) -> None:
        """Decision E23 (amended): a stream the bundle uses that has sent nothing while the newest data moved
        on by more than ``max_lag_s`` plus its own delivery interval (its latest advance between two lag
        ticks: the batch it arrives in, or its sample interval when slower) has stopped: a required one is a
        one-line :class:`DataError` naming it, an optional one is ignored from then on with one warning.
        A stream behind before its known end (``stream_ends_s``, a recording) is in a gap: the steps wait."""
        if self._latest >= self._lag_next:  # a lag tick (every 0.25 s of data): the delivery intervals
            self._lag_next = self._latest + 0.25 - 1e-9  # (0.25 s pushes tick each time, whatever the rounding)
            self._first_t = min(self._first_t, self._oldest)
            for n, r in self._buf.items():
                raw = self.inputs.last_in(n)
                last = r.last if raw is None else max(r.last, raw)
                adv = last - self._tick_last.get(n, self._first_t)
                if adv > 0.0:  # its latest delivery: a batch, or one sample interval of a slow stream
                    self._batch[n] = adv
                self._tick_last[n] = last
        if self._unseen:  # required sensors not pushed yet (a required sensor is never dropped)
            self._unseen = self._unseen.difference(self._buf)
        if not self._unseen and self._latest - min([r.last for r in self._buf.values()]) <= self.max_lag_s:
            return  # the common case
        required = self.required
        paused: dict[str, float] = {}
        for n, t, grace in self._stopped(self._latest, self._first_t, self._last_times(), self._batch):
            if n in required and t is not None and self._pausable(n):  # decision E115
                paused[n] = t  # its newest input time (a stream still probed for its rate is not buffered yet)
                continue
            msg = stopped_message(n, t, self._first_t, self._latest, self.max_lag_s, grace, n in required,
                                  cause=self._clocks_note(n, t))  # decision E223: two clocks, not a stopped sensor
            if n in required:
                raise DataError(msg)
            self.inputs.ignore(n, "it stopped")
            self._buf.pop(n, None)
            self.warnings.append(msg)
            log.warning("bundle %s: %s", self.bundle.path, msg)
            self._without(n)
        if paused:  # decision E223's session: the earliest newest input time, not only the buffered streams'
            self._pause(list(paused), min(paused.values()))

    def _last_times(self, pushed: dict[str, float] | None = None) -> dict[str, float | None]:
        """Each buffered or not yet seen required stream's newest input time (s; None: never pushed), with the
        newest times of a push not taken yet (``pushed``)."""
        last: dict[str, float | None] = {}
        for n in dict.fromkeys([*self._buf, *self._unseen, *(pushed or ())]):
            if n not in self.required and n not in self._buf:
                continue  # a new optional stream starts now; it can not lag yet
            raw = self.inputs.last_in(n)
            r = self._buf.get(n)
            ts = [x for x in (raw, None if r is None else r.last, (pushed or {}).get(n)) if x is not None]
            last[n] = max(ts) if ts else None
        return last

    def _stopped(self, latest: float, first_t: float, last: dict, batch: dict) -> list[tuple[str, float | None, float]]:
        """Decision E23's rule: ``(stream, its newest time, its grace)`` of each stream further behind ``latest``
        than ``max_lag_s`` plus its own delivery interval, outside a known gap (``stream_ends_s``)."""
        any_batch = max(batch.values(), default=0.0)  # the caller's batches, for a stream not seen yet
        out = []
        for n, t in last.items():
            if n in self._paused or latest - (first_t if t is None else t) <= self.max_lag_s:
                continue  # decision E115: a paused stream is not waited for
            if n in self._ends and (t is None or t < self._ends[n]):
                continue  # a gap in a recording (or a later start): the stream resumes, the steps wait
            rate = self.inputs.input_rates_hz.get(n)
            grace = any_batch if t is None else max(batch.get(n, 0.0), 1.0 / rate if rate else 0.0)
            if latest - (first_t if t is None else t) <= self.max_lag_s + grace:
                continue  # within its own delivery interval: it can not have sent more yet
            out.append((n, t, grace))
        return out

    def _check_stopped(self, pushed: dict[str, tuple[float, float]]) -> None:
        """Decision B122 (E29's all or nothing for E23): a push after which a required stream would be found
        stopped is refused before any of it is taken, with E23's line; ``pushed``: stream -> (first, last time)
        of the push's samples. The lag tick's delivery intervals are computed as :meth:`_check_lag` would, on
        copies."""
        if not pushed or self.max_lag_s == math.inf:
            return
        latest = max(self._latest, max(b for _, b in pushed.values()))
        if not (self._pending or latest >= self._lag_next):
            return  # no lag check in this push (as _check_lag)
        first_t = min(self._first_t, self._oldest, min(a for a, _ in pushed.values()))
        last = self._last_times({n: b for n, (_, b) in pushed.items()})
        batch = dict(self._batch)
        if latest >= self._lag_next:  # the tick's delivery intervals, of every stream buffered after the push
            for n in dict.fromkeys([*self._buf, *pushed]):
                r, raw = self._buf.get(n), self.inputs.last_in(n)
                ts = [x for x in (raw, None if r is None else r.last, pushed.get(n, (None, None))[1]) if x is not None]
                adv = max(ts) - self._tick_last.get(n, first_t)
                if adv > 0.0:
                    batch[n] = adv
        for n, t, grace in self._stopped(latest, first_t, last, batch):
            if n in self.required and not (t is not None and self._pausable(n)):  # decision E115: paused after it
                raise DataError(stopped_message(n, t, first_t, latest, self.max_lag_s, grace, True,
                                                cause=self._clocks_note(n, t)))  # decision E223

    def _without(self, name: str) -> None:
        """Decision B121: an optional stream that stopped: each task's model re-chosen as for a stream without it
        (the best-ranked model that reads none of the streams gone, else the task left unclassified; one warning
        line), so that the steps go on as in a session without that sensor."""
        gone = set(self.inputs.ignored)
        before = {t: (c.method, c.unit) for t, c in self.classifiers.items()}
        self._choose_models([n for n in self.used_sensors if n not in gone])
        self._spec, self._groups = None, ((), ())
        changed = [f"{t} {c.method}/{c.unit}" for t, c in self.classifiers.items()
                   if (c.method, c.unit) != before.get(t)]
        if changed:
            self._warn(f"{name} stopped: classified from now on as a stream without it would be, with "
                       f"{', '.join(changed)} (decision B121)")

    def _detect(self) -> None:
        """Online stance detection on the foot gyroscope (:class:`pdrlearn.kernels.stride.StanceSegmenter`,
        decision E7); a step runs from one stance to the next."""
        if "fGyroscope" not in self._buf or "fAccelerometer" not in self._buf:
            return
        ring = self._buf["fGyroscope"]
        if ring.last <= self._det_t:  # no new gyroscope sample
            return
        i1 = ring.i1
        if i1 - ring.i0 >= 2 and ring.t[i1 - 2] <= self._det_t and ring.v.shape[1] == 3:  # one new sample (E16)
            gx, gy, gz = ring.v[i1 - 1].tolist()  # |w| on Python floats: update's arithmetic (decision E17)
            self._pending += self.segmenter.update_norms([ring.last], [math.sqrt(gx * gx + gy * gy + gz * gz)])
        else:
            t, g = ring.view()
            i = int(t.searchsorted(self._det_t, side="right"))
            self._pending += self.segmenter.update(t[i:], g[i:])
        self._det_t = ring.last
        if self._resume_end is not None and self._pending:  # decision L134: the old tracker measured these
            self._pending = drop_measured(self._pending, self._resume_end)
            if self._pending:
                self._resume_end = None

    def _stamp(self) -> tuple:
        """What a computed-ahead step's data depends on besides its times (decision E24): the buffered
        sensors, the trims that dropped samples and the push-time foot state's anchor (a reallocation
        re-anchors its running product, ``FootLevelling.gen``) and on/off switch."""
        f = self._foot
        return tuple(self._buf), self._trims, (None if f is None else (f.gen, f.ok))

    def _speculate(self) -> None:
        """Decision E24: at the end of a push that completed no step, compute the step the next push is
        likely to complete (:meth:`StanceSegmenter.closing_stride`), when every stream already has a sample
        past what that step reads (then the next push reads the same samples), unless it is computed already.
        Decision E83: a detected step still waiting (the fine kernel's padding, L141) comes first: the next push
        can complete no other, and its samples are all in one push before it is due (``FINE_AHEAD_S``)."""
        cand = self._pending[0] if self._pending and self._fine is not None else self.segmenter.closing_stride()
        if cand is None:
            self._spec = None
            return
        stamp = self._stamp()
        if self._spec is not None and self._spec[0] == cand and self._spec[1] == stamp:
            return
        self._spec = None
        t0, t1 = cand
        # the samples a step reads end at the first one at or after its end (window_bounds: its search pad)
        need = t1 + max(self.rest_search_s + 0.1 if self.boundaries == "rest" else 0.0,
                        FINE_PAD_S if self._fine is not None else 0.0)  # decision L141: the spline's padding
        required = self.required
        if (any(n not in self._buf for n in required) or min(r.last for r in self._buf.values()) <= need
                or (self._foot is not None and self._foot.ok and self._foot.last <= need)):
            return
        try:
            core = self._step_core(t0, t1)
        except Exception:  # noqa: BLE001 - the step's own push recomputes it and raises there
            return
        self._spec = (cand, stamp, core)

    def _step_core(self, t0: float, t1: float) -> tuple:
        """The part of :meth:`process_step` that reads only the step's samples: levelled units, classes,
        probabilities, displacement (step frame) and heading change."""
        W, lev = self._window(t0, t1)
        classes, proba = self._classify_step(W)
        ood = DomainLog.score(self.classifiers, W) if self._domain is not None else None  # decision E105
        lev = self._held_waist(lev, t1)  # decision E115
        disp, dyaw = stride_motion(lev, self.heading_source, t0=t0, t1=t1, fine=self._fine)
        return lev, classes, proba, disp, dyaw, ood

    def process_step(self, t0: float, t1: float) -> Step:
        """Classify, measure and place the step ``[t0, t1]`` (s) from the buffered samples (no L611 verdict: the
        tracker's own pushes judge each stride first, decision E280)."""
        return self._apply(self._measure(t0, t1))

    def _measure(self, t0: float, t1: float) -> tuple:
        """Decision E280: what :meth:`process_step` reads from the samples and the strides before (classes,
        displacement, turns, E272's bias, the contact), with L611's row (:class:`~pdrlearn.kernels.pedal.LiveLoops`);
        :meth:`_apply` places it once its verdict is known. ``("gap", t0, t1, row, gap_s, bridge_yaw)`` for a stride
        across a foot gap (E30), else ``("stride", t0, t1, row, lev, classes, proba, disp, dyaw, turn, event_s,
        clipped)`` (``clipped``: decision E325's flag)."""
        spec = self._spec
        if spec is not None and spec[0] == (t0, t1):  # computed ahead (decision E24): from the same data?
            self._spec = None
            if self._foot is not None and self._foot_q:
                self._foot_state(t1)  # feeds the queue when the step could read it (E21), as _window would
            if spec[1] != self._stamp():
                spec = None
        else:
            spec = None
        bridged = False
        prev = self._prev_end
        before = [c for c in self._contacts if c[0] < t0]  # steps decision 87: a stride measured again, the same
        prev_ic = before[-1][1] if before else math.nan
        pause_gap = False  # decision L90: the pause before this stride overlaps a foot IMU gap over 1 s
        if self._foot_gaps:  # decision E30 / B11: a stride across a foot gap over 1 s moves 0 m
            pause_gap = prev is not None and prev < t0 and any(
                long and imu and a < t0 and b > prev for a, b, long, imu in self._foot_gaps)
            over = [(b - a, long, imu) for a, b, long, imu in self._foot_gaps if a < t1 and b > t0]
            self._foot_gaps = [g for g in self._foot_gaps if g[1] > t0]
            gap = max([d for d, long, _ in over if long], default=0.0)
            if gap:
                bridge = 0.0
                if self._bridged() and any(long and imu for _, long, imu in over):  # decision L91
                    lo = min(t0, t0 if prev is None else prev)
                    bridge = waist_bridge_yaw(self._stream, lo, t1, gap_line=not self.bridge_cycle)
                    if self.bridge_cycle:  # decision E354: the waist gap's turn waits for the stride after it
                        self._cycle.hold(self._stream, lo, t1)
                self._prev_end = t1  # no L31 pivot across it either: the foot's turn inside the gap is unknown
                if self._compassed():  # decision E361: the row's turn in the compass's heading
                    self._compass.row(bridge)
                self._contacts = (before + [(t0, math.nan)])[-2:]  # steps decision 87: no contact
                return ("gap", t0, t1, _pedal.unjudged_row(t0, t1), gap, bridge)  # E280: in its chain, not judged
            bridged = bool(over)  # a shorter gap in the foot accelerometer / gyroscope: no classes (B11)
        if bridged:  # no classes, as UserModel.predict_steps leaves a step without the foot unit (offline, track
            # --streaming); decision E36: levelled and integrated with the gap counted as one sample interval, as
            # offline and track --streaming (by the shared kernel: the push-time state has the real clock)
            classes, proba = {}, {}
            streams = _Views(self._buf)
            lev = levelled_units(streams, t0, t1, available=available_groups(streams), forward=self.forward,
                                 rest_search_s=self.rest_search_s, heading=self.heading_mode, bridge_gaps=True)
            lev = self._held_waist(lev, t1)  # decision E115
            disp, dyaw = stride_motion(lev, self.heading_source, t0=t0, t1=t1, fine=self._fine)
        else:
            lev, classes, proba, disp, dyaw, ood = spec[2] if spec is not None else self._step_core(t0, t1)
            if self._domain is not None:  # decision E105: a classified stride's scores
                self._domain.add(ood, self.classifiers)
            if self._mirror is not None:
                self._mirror_stride(t0, t1)
        if bridged:  # decision L167 (an option; track --streaming's): the length and height of the clean stride before
            on = self.drop_neighbour  # decisions E101, L549 (a bare Tracker.__new__: False)
            disp = np.array(drop_stride_disp(disp, t1 - t0, self._drop_ref, on))
            if on and self._drop_ref is not None and not self._drop_warned:
                self._drop_warned = True
                self._warn("strides across dropped foot samples over 0.25 s take the length and height change of the "
                           "stride before each (decision L167)")
        hole = 0.0 if bridged and self.drop_neighbour else self._swing_hole(t0, t1)  # L167's option: its neighbour's
        if hole:  # decision L674: a hole in the foot's samples: no classes, the height change of the clean stride
            classes, proba = {}, {}  # before it (R3 F1; the length kept)
            disp = np.array((float(disp[0]), float(disp[1]), hole_stride_dz(self._drop_ref)))
            if not self._hole_warned:
                self._hole_warned = True
                self._warn(stride_hole_line(hole, t0, t1))
        elif not bridged:
            self._drop_ref = (disp.copy(), t1 - t0)
        turn = dyaw  # decision E51: the stride's own turn, before the pivot between strides
        if pause_gap:  # decisions L90 / L91 (track --streaming's): no foot pivot over a foot gap; the waist's turn
            if self._bridged():
                dyaw += waist_bridge_yaw(self._stream, prev, t0, gap_line=not self.bridge_cycle)
                if self.bridge_cycle:  # decision E354 (taken below by this stride)
                    self._cycle.hold(self._stream, prev, t0)
            elif not headed_by_foot(lev, self.heading_source):  # L61's waist look-back is measured, kept
                dyaw += stride_gap_yaw(lev, self.heading_source, self._stream, prev, t0, foot=False,
                                       waist=self.waist_gap_yaw)
        else:  # decisions L31 / L61: the heading unit's turn between strides (track --streaming's call)
            stop = (long_stop_turn(self._stream, prev, t0) if self.waist_gap_yaw  # decision E335: E324's turn, read
                    and not headed_by_foot(lev, self.heading_source) else None)  # once for both calls below
            if self._spun is not None and headed_by_foot(lev, self.heading_source):  # decision L742: the foot's
                dyaw += self._spun[0]  # turn in place before it, and its pivot after that (track --streaming's)
                dyaw += stride_gap_yaw(lev, self.heading_source, self._stream, _spin.foot_gap_start(prev, self._spun),
                                       t0)
            else:
                dyaw += stride_gap_yaw(lev, self.heading_source, self._stream, prev, t0, waist=self.waist_gap_yaw,
                                       stop_turn=stop)
            started = _carried_yaw.carried_turn(self._stream, lev, self.heading_source, prev, t0, t1,
                                                 self.waist_gap_yaw, stop_turn=stop)  # E285 (track --streaming's)
            if started is not None:
                turn, dyaw = started
        if self._stop_bias is not None and not headed_by_foot(lev, self.heading_source):  # decision E272
            # decision L742: a stop is still: the one after a turn in place starts at its end (no bias from the turn)
            self._stop_bias.update(self._stream, _spin.foot_gap_start(prev, self._spun), t0)
            lo = prev if pause_gap and self._bridged() else waist_gap_from(prev, t0, self.waist_gap_yaw)
            turn -= self._stop_bias.turn(t0, t1)
            dyaw -= self._stop_bias.turn(lo, t1)
        turn = _sideways.own_turn(lev, self.heading_source, turn)  # decision L699: the foot's own turn, as offline's
        if self.bridge_cycle:  # decision E354: a held waist gap's turn (0 without one)
            dyaw += self._cycle.take(self._stream, t0, t1)
            if self._bridged():  # decision E365: the rate before a next gap, recorded as the stride is measured
                self._cycle.note(self._stream, t0, t1)
        if self._compassed():  # decision E361 (track --streaming's call)
            if headed_by_foot(lev, self.heading_source):
                self._compass.row(dyaw)
            else:
                dyaw += self._compass.stride(self._stream, t0, t1, dyaw, self._cycle.spread)
        self._spun = None  # decision L742: taken by this stride (or by the waist's gap, or lost over a foot gap)
        self._prev_end = t1
        if bridged:  # decision E280: a stride across bridged samples (L167's) is in its chain, not judged
            row = _pedal.unjudged_row(t0, t1)
        else:  # decision L621: the foot's own rest reading, causally (E280)
            row = (t0, t1, float(disp[2]), self._foot_rest.unrested(self._stream, t0, t1), float(np.hypot(*disp[:2])),
                   True)
        event_s = self._contact(t0, t1, prev_ic) if self.contacts else math.nan
        self._contacts = (before + [(t0, event_s)])[-2:]
        if self._toe_off is not None and (t0, t1) not in self._toe_offs:  # decision E326 (once per stride)
            self._toe_offs[(t0, t1)] = self._stride_toe_off(t0, t1, event_s)
        return ("stride", t0, t1, row, lev, classes, proba, disp, dyaw, turn, event_s, self._clipped(t0, t1))

    def _apply(self, rec: tuple, pedal: bool = False) -> Step | None:
        """Decision E280: place a measured stride (:meth:`_measure`): the rules, heading, position and the Step. A
        pedalling one (L611) is no step: its turn still turns the heading (as ``track --streaming``'s), it moves 0 m,
        and its height counts as a 0 m stride without class in E47's checks; None."""
        if rec[0] == "gap":
            _, t0, t1, _, gap, bridge = rec
            self.heading += bridge  # decision L91
            self._heights.append(None, 0.0, 0.0)  # decision E47: no class, 0 m (as --streaming's)
            x, y, z = self.position.tolist()
            return Step(t0, t1, {}, {}, 0.0, 0.0, self.heading, x, y, z, gap_s=gap)
        _, t0, t1, _, lev, classes, proba, disp, dyaw, turn, event_s, clipped = rec
        if pedal:  # decision L611, as track --streaming: no row, 0 m, no class; the turn kept
            self.heading += dyaw
            self._heights.append(None, float(disp[2]), 0.0)
            return None
        if self.distance_gain is None:
            self._resolve_calibration()
        # the one-stride kernels on Python floats: the same arithmetic as apply_level_gain, apply_stride_rules
        # and advance (decision E17)
        dx, dy, dz = disp.tolist()
        raw_dz = dz
        if self.distance_gain != 1.0:  # decision L26 / E14, as pdrlearn track
            dx, dy, dz = apply_level_gain_one(dx, dy, dz, self.distance_gain)
        if self.bounds is not None and "length" in classes:  # decision C94: C89's count, track --streaming's
            self._note_turn_tally(classes["length"], math.hypot(dx, dy), _sideways.foot_turn(lev))
        if _turn_length.TURN_LENGTH_RULE and self.bounds is not None and "length" in classes:  # decisions C88 /
            # C91: a turning stride's length class from its measured length, track's and track --streaming's call
            label, lp = _turn_length.turn_length_class_one(classes["length"], proba.get("length"), math.hypot(dx, dy),
                                                           _sideways.foot_turn(lev), self.bounds)
            classes, proba = {**classes, "length": label}, {**proba, "length": lp}
        if self.rules == "thesis" and self.min_confidence <= 0:
            terrain = classes.get("terrain")
            length, dz = stride_rules_one(dx, dy, dz, terrain, classes.get("direction"),
                                          classes.get("length"), bounds=self.bounds, down_mode=self._down_mode)
        else:  # decision L40: the gate (L18) and the bayes rule (L14) of pdrlearn track, one stride at a time
            g, get, pget = self.min_confidence, classes.get, proba.get
            terrain = confident_one(get("terrain"), pget("terrain"), g)
            length, dz = stride_rules_one(
                dx, dy, dz, terrain,
                confident_one(get("direction"), pget("direction"), g), confident_one(get("length"), pget("length"), g),
                bounds=self.bounds, down_mode=self._down_mode, rules=self.rules, length_proba=pget("length"),
                sigma_rel=self._sigma_rel)
        if self.gated_level_dz == "summed" and "terrain" in self.classifiers:  # decision L550: the keyword
            # decision L206: L39's rule on the summed dz of the run of gated strides (one kernel with streamed)
            dz, self._gated_run_dz = summed_level_step(dz, terrain is not None, self._gated_run_dz)
        elif terrain is None and self.gated_level_dz is True and "terrain" in self.classifiers:
            dz = unclassed_level_dz_one(dz, False)  # decision L189 (offline's L184): no terrain class, L39's rule
        impossible = impossible_stride_one(length, dz, t1 - t0)
        if impossible:  # decision L94: never summed, as pdrlearn track
            self._warn(impossible_stride_warning(1, t0, t1, length, dz))
            length, dz = 0.0, 0.0
        heading = self.heading + dyaw
        foot_headed = headed_by_foot(lev, self.heading_source)
        direction = (heading + placement_offset(lev, self.heading_source, disp)  # decision L34
                     + reversed_by_rules(foot_headed, dx, length))  # L37
        side = 0.0
        if not foot_headed:  # decisions E124, E234 (track --streaming's call; adopted, no module switch)
            if self._side is None:
                self._side = _sideways.SideRun()
            side = self._side.stride(dx, dy, length, _sideways.step_frame(lev), _sideways.foot_turn(lev))  # L400
        direction += side + waist_forward_flip(foot_headed, classes.get("direction"), length, side)  # E216
        if self.cycle_yaw and not foot_headed:  # decision E336: along the cycle's mean yaw (track --streaming's)
            if self._cycle_phase is None:  # a bare Tracker.__new__
                self._cycle_phase = CyclePhase()
            direction -= waist_end_phase_yaw(lev, t0, t1, self._cycle_phase)  # E338: held over turning strides
        if self._first_walk is not None:  # decision E215: L494's first-walk direction, said once (applied: opt-in)
            if self._fixes.used:  # a used fix set the frame (D24's yaw feedback learnt in it)
                self._first_walk.stop()
            ref = self._first_walk.stride(foot_headed, direction, math.hypot(dx, dy))
            if ref is not None:  # the end of the first walk: said once (turned only as an opt-in, 0.0 otherwise)
                heading, direction = heading - ref, direction - ref
                line = self._first_walk.line(t1)
                if line:
                    self._warn(line)
        if self._side_rows is None:
            self._side_rows = _sideways.SideRun()
        judged = self._side_rows.started  # decisions L505, E318: the stream's first measured stride is not judged
        self._side_rows.stride(dx, dy, length, _sideways.step_frame(lev),  # decision L243: whatever the heading
                               _sideways.foot_turn(lev))  # L400: a turning stride is no side step
        x, y, z = advance_xyz(*self.position.tolist(), direction, length, dz)
        if not math.isfinite(direction + x + y + z):  # decision E38: NaN / inf fail (also inf - inf)
            self._non_finite(t0, t1, heading, direction, (x, y, z), (length, dz))
        self.heading = heading
        self.position = np.array((x, y, z))
        self.n_steps += 1
        self._heights.append(judged_terrain(classes.get("terrain"), impossible), raw_dz, dz)  # decisions E47, C240
        turn = float(turn)  # decision E51: the stride's own turn (L690: not wrapped, a spin of 180-360 deg is itself)
        chord = float(signed_chord(dx, dy, _sideways.foot_turn(lev),  # decision L692: the measured travel
                                   _sideways.step_frame(lev)))  # against the foot's own mid-stride facing
        length, direction = travel_sign_one(length, direction, chord if judged else abs(chord),  # L654, E318: the
                                            # measured travel (a first stride's: not backward), after the position
                                            self._side_rows.decided,  # decision C137: a side step is no backward
                                            turn)  # decisions L578, L692: nor a turn on the spot
        if self._session_length is not None and "length" in classes:  # decision C117: the reported class only
            label, lp = self._session_length.stride(classes["length"], proba.get("length"), abs(length),
                                                    terrain=classes.get("terrain"),
                                                    direction=classes.get("direction"), turn_rad=turn)
            classes, proba = {**classes, "length": label}, {**proba, "length": lp}
        return Step(t0, t1, classes, proba, length, dz, direction, x, y, z, event_s=event_s,
                    turn_angle_rad=turn, impossible=impossible,
                    pivot_rad=float(np.angle(np.exp(1j * (dyaw - turn)))),  # decision L106
                    sideways=self._side_rows.decided,  # decision L243
                    lateral_m=self._side_rows.lateral,  # decision E319
                    flags=("clipped",) if clipped and not impossible else ())  # decision E325

    def _clipped(self, t0: float, t1: float) -> bool:
        """Decision E325: a foot accelerometer or gyroscope sample of the stride ``[t0, t1]`` is clipped
        (:func:`~pdrlearn.kernels.clipping.clipped_axes` on the stride's buffered samples: B77 / B311, or B456 at the
        declared full scale); False with ``check_input=False``."""
        if self._flag_scales is None:
            return False
        for name, kind in (("fAccelerometer", "accelerometer"), ("fGyroscope", "gyroscope")):
            ring = self._buf.get(name)
            if ring is None:
                continue
            t, v = ring.view()
            i0, i1 = int(t.searchsorted(t0, side="left")), int(t.searchsorted(t1, side="right"))
            hit, _ = clipped_axes(v[i0:i1, :3], kind, self._flag_scales.get(name))
            if hit.any():
                return True
        return False

    @staticmethod
    def _stride_s(step: Step, prev: tuple) -> float:
        """Decision E325: the emitted ``step``'s IC-to-IC stride time (E51), else the time from the previous emitted
        stride's start (``prev``: its start, end, IC) to its own (L66 / L80's kernel with the starts as the events)."""
        d = step.stride_time_s
        if d != d:
            d = float(stride_times((prev[0], step.start_s), (prev[1], step.end_s), (prev[0], step.start_s))[1])
        return d

    @staticmethod
    def _running(step: Step, prev: tuple) -> bool:
        """Decision E325: L95 / W144's running rule (:func:`~pdrlearn.kernels.gait_range.running_stride`) on the
        stride time :meth:`_stride_s`."""
        return running_stride(step.length_m, Tracker._stride_s(step, prev))

    def _note_range(self, step: Step, prev: tuple) -> None:
        """Decision E350: the emitted ``step``'s cadence, speed (L66, :meth:`_stride_s`) and whether it is straight
        (L79: level, its own turn under 15 deg), the latest 4096 strides (over an hour of walking), for
        :meth:`flush`'s L95 line (:func:`~pdrlearn.kernels.gait_range.streamed_slow_line`)."""
        if not isinstance(self._range_rows, deque):  # a bare Tracker.__new__ or a restart state: from here on
            self._range_rows = deque(maxlen=4096)
        cad, speed = cadence_speed(np.array([step.length_m]), np.array([self._stride_s(step, prev)]))
        turn = step.turn_angle_rad
        self._range_rows.append((float(cad[0]), float(speed[0]), bool(
            turn == turn and abs(turn) < _turn_length.STRAIGHT_MAX_RAD and abs(step.dz_m) < _distance.LEVEL_DZ_M)))

    def _slow_line(self) -> None:
        """Decision E350: offline ``track``'s L95 line for a walk below the range, on the strides :meth:`_note_range`
        kept (said once, at :meth:`flush`)."""
        if self._slow_said or not self._range_rows:
            return
        cad, speed, straight = zip(*self._range_rows, strict=True)
        line = streamed_slow_line(cad, speed, straight)
        if line:
            self._slow_said = True
            self._warn(f"{line} ({decision_ref('L95', 'E350')})")

    def _swing_hole(self, t0: float, t1: float) -> float:
        """Decision L674: the longest hole (s) in the foot accelerometer / gyroscope input times of the stride
        ``[t0, t1]`` (:func:`~pdrlearn.kernels.window.stride_hole`), 0.0 without one. The input times, not the
        buffer's (:meth:`_taken_times`, E239's): with ``resample=True`` the buffer holds the resampler's grid, in
        which a hole under 1 s is interpolated away (review R3 F3, session 45, FM)."""
        return max([stride_hole(self._taken_times(name), t0, t1) for name in sorted(_FOOT_IMU) if name in self._buf],
                   default=0.0)

    def _contact(self, t0: float, t1: float, prev_ic_s: float = math.nan) -> float:
        """Decisions E49 / E50: the initial contact (s) of the stride ``[t0, t1]`` from its buffered samples
        (:func:`pdrlearn.kernels.contact.stride_contact`: the force sensors' stance onset when they are buffered,
        else the foot accelerometer's impact; offline's sources), NaN when it has none. ``prev_ic_s``: the previous
        stride's contact (steps decision 87)."""
        ring = self._buf.get("fAccelerometer")
        if ring is None:
            return math.nan
        t, v = ring.view()
        i0, i1 = int(t.searchsorted(t0, side="left")), int(t.searchsorted(t1, side="right"))
        t, v = t[i0:i1], v[i0:i1, :3]
        fa, fb = self._buf.get("fForceA"), self._buf.get("fForceB")
        force = None if fa is None or fb is None else force_at(t, (fa.view(), fb.view()))
        return stride_contact(t, v, force, prev_ic_s)

    def _non_finite(self, t0: float, t1: float, heading: float, direction: float, xyz: tuple, motion: tuple) -> None:
        """Decision E38: a stride of data that passed every input check left a non-finite heading or position:
        pdrlearn's fault (:class:`InternalError`, as E27's levelling check), raised before the tracker takes it
        (its heading and position stay those of the previous step)."""
        what = "heading" if not math.isfinite(direction) else "position"
        raise InternalError(
            f"internal error in pdrlearn.runtime: the stride {t0:.3f}-{t1:.3f} s gave a non-finite {what} (heading "
            f"{heading:.6g} rad, direction {direction:.6g} rad, position ({xyz[0]:.6g}, {xyz[1]:.6g}, {xyz[2]:.6g}) "
            f"m, length {motion[0]:.6g} m, dz {motion[1]:.6g} m) from finite samples; this is a bug, not bad data - "
            "please report it; the tracker keeps the previous step's heading and position")

    def _mirror_stride(self, t0: float, t1: float) -> None:
        """Decision B129: the stride ``[t0, t1]``'s foot samples to :class:`MirrorWatch` (stance to stance, as
        offline's rest-to-rest strides); once it has decided, the test is dropped."""
        ta, a = segment(*self._stream("fAccelerometer"), t0, t1)
        inside = (ta >= t0) & (ta <= t1)
        msg = self._mirror.stride(ta[inside], a[inside], *segment(*self._stream("fGyroscope"), t0, t1))
        if len(self._mirror.ratios) >= LIVE_STRIDES:
            self._mirror = None
        if msg:
            self._warn(msg)

    def domain_report(self) -> dict | None:
        """Decision E105: the out-of-domain report of the strides classified so far (``pdrlearn track --model``'s,
        C16: ``out_of_domain_fraction``, per task the strides outside the training range, ``warn`` at
        ``warn_out_of_domain``); None when the tracker does not check (``check_domain`` off), the bundle holds no
        training ranges (exported before E105) or no stride was checked."""
        return None if self._domain is None else self._domain.report(self._warn_ood)

    def quiet_clipping(self) -> None:
        """Decision E303: no live clipping / stuck-axis lines (a caller that read the session with ``read_session``
        said B77 / B455 already: ``pdrlearn evaluate BUNDLE``); decision E309: nor B457's rate-change line."""
        self._clip = None
        self._rates = None

    @property
    def rate_changes(self) -> list[dict]:
        """Decision E309: the sustained sample-rate changes of the pushed streams said so
        far (B457's detection, B460's kernel), each ``{"streams": [...], "t_s", "before_hz", "after_hz"}``; empty
        for steady streams or without ``check_input`` / ``stream_checks``."""
        return [{k: v for k, v in c.items() if k != "key"} for c in self._rate_log]

    def quiet_domain(self) -> None:
        """Decision E198: keep checking the strides against the training ranges (:meth:`domain_report`) but never
        say E105's line (``pdrlearn evaluate BUNDLE`` pools the sessions and warns only with its option)."""
        self._domain_said = True

    def _warn_out_of_domain(self) -> None:
        """Decision E105: C61's one line (C16's with ``warn_out_of_domain``) at the end of a recording, once."""
        if self._domain is None or self._domain_said:
            return
        from pdrlearn.classify.domain import session_warning_line

        line = session_warning_line(self.domain_report(), what="strides", user=self.domain_user)  # decision C227
        if line:
            self._domain_said = True
            self._warn(line)

    def _frozen_foot_said(self, msg: str | None) -> None:
        """Decision B213: the watch's one line, after which it is dropped (bounded memory)."""
        if msg:
            self._frozen_foot = None
            self._warn(msg)

    def _warn(self, msg: str) -> None:
        """One warning line: kept in ``warnings`` and logged."""
        self.warnings.append(msg)
        log.warning("bundle %s: %s", self.bundle.path, msg)

    def _warn_every(self, kind: str, msg: str) -> None:
        """Decision E224: a line that can repeat while its cause lasts, written at most once per
        :data:`~pdrlearn.runtime.links.REPEAT_WARN_S` of stream time; every one counted in ``warning_counts``."""
        if self._repeats is None:  # a bare Tracker.__new__: every line
            self._repeats = RepeatedLines()
        line = self._repeats.line(kind, msg, self._latest)
        if line is not None:
            self._warn(line)

    def _resolve_calibration(self) -> None:
        """The distance gain and stride sd that apply at the pushed foot accelerometer's rate (median
        sample interval, as ``Stream.rate_hz``); a rate mismatch warns once and applies neither."""
        t = self._stream("fAccelerometer")[0]
        fs = 1.0 / float(np.median(np.diff(t))) if len(t) > 1 else float(self.rate_hz)
        fs = self.resampled_hz.get("fAccelerometer", fs)  # resampled (E22): the data's own rate, as track
        # E22: resampled, the warning says why resampling does not make the calibration apply
        rec, warning = applicable_calibration(self._calibration, fs, resampled_hz=(
            float(self.rate_hz) if "fAccelerometer" in self.resampled_hz else None))
        if warning:
            self.warnings.append(warning)
            log.warning("bundle %s: %s", self.bundle.path, warning)
        self.distance_gain = float(rec.get("gain", 1.0)) if rec is not None else 1.0
        self.stride_sd = calibrated_stride_sd(rec)
        self._sigma_rel = float(self.stride_sd) if self.stride_sd else SIGMA_REL  # L26, as pdrlearn track

    def _classify_step(self, W: np.ndarray) -> tuple[dict[str, str], dict[str, dict[str, float]]]:
        """Classes and probabilities (task -> class -> p) of one step window, as :meth:`classify` with
        Python floats: the argmax of a few probabilities on a list costs less than ``np.argmax`` (E13)."""
        g = self.step_graph
        probas = g.predict(W[None]) if g is not None else {}
        classes: dict[str, str] = {}
        proba: dict[str, dict[str, float]] = {}
        cache: dict = {}
        for task, clf in self.classifiers.items():
            p = probas[task] if task in probas else clf.predict(W[None], cache)[1]
            row = p[0].tolist()
            best = max(row)
            k = row.index(best) if sum(row) == sum(row) else int(np.argmax(p[0]))  # NaN: np.argmax's rule
            classes[task] = clf.classes[k]
            proba[task] = dict(zip(clf.classes, row, strict=True))
        return classes, proba

    def _foot_silent_keep(self) -> float:
        """Decision E113: while a foot IMU stream has sent nothing for over :data:`GAP_LONG_S` (a foot gap in
        progress, B11, not yet seen: the gap is known when the foot's samples return), the samples from the last
        stride's end (and the last boundary) less the look-back are kept, so the waist's turn over the whole gap
        (L91's bridge) and the stride before it are computed from the samples ``track --streaming`` reads; before,
        ``buffer_s`` (8 s) trimmed the waist during the gap and a 30 s gap across a 180 + -90 deg turn bridged
        only the last 8 s (-90.6 deg for +92.8). Bounded by ``max_gap_s`` (a longer jump is refused, B141) and by
        the recording (``pdrlearn run``); ``inf`` when the foot streams (no limit from here)."""
        foot = [self._buf[n].last for n in _FOOT_IMU if n in self._buf]
        if not foot or not self._latest - min(foot) > GAP_LONG_S:
            return math.inf
        marks = [x for x in (self._prev_end, self.segmenter.last_boundary) if x is not None]
        keep = min([*marks, min(foot)]) - _LOOK_BACK_S
        return max(keep, self._latest - self.max_gap_s - _LOOK_BACK_S) if math.isfinite(self.max_gap_s) else keep

    def _trim(self, keep_before: float = math.inf) -> None:
        """Drop samples older than both the last step boundary (minus a margin) and ``buffer_s``, and than
        ``keep_before`` (s: the steps this push returns, whose windows E63 lets the caller read)."""
        if not self._buf:
            return
        keep_from = self._latest - self.buffer_s
        if self.segmenter.last_boundary is not None:  # the next step starts at the last boundary
            keep_from = max(keep_from, self.segmenter.last_boundary - _LOOK_BACK_S)
        keep_from = min(keep_from, keep_before)
        if self._pending:  # keep what the waiting steps need
            keep_from = min(keep_from, self._pending[0][0] - _LOOK_BACK_S)
        prev_end = self._restart_from[0]  # decision E280: a restart state re-measures the held strides from there
        if self._loops.held:
            keep_from = min(keep_from, self._loops.held[0][0][0] - _LOOK_BACK_S)
        # decision E285: a waist-headed stride reads the waist's samples from CARRY_BACK_S before its start (the next,
        # a waiting and a held one's); the foot's samples and state keep their own bound. Decision E305: the next
        # stride starts after the latest sample less buffer_s whatever the last boundary (a stand or sit ends at a
        # stance a rest-to-rest stride starts at most max_rest_s into), so a long stop no longer holds its samples
        last = self.segmenter.last_boundary
        last = None if last is None else max(last, self._latest - self.buffer_s)
        starts = [x for x in (last, self._pending[0][0] if self._pending else None,
                              self._loops.held[0][0][0] if self._loops.held else None) if x is not None]
        carry = "waist" in self.units and self.heading_source != "foot" and starts
        waist_from = min(keep_from, min(starts) - _carried_yaw.CARRY_BACK_S - _LOOK_BACK_S) if carry else keep_from
        if prev_end is not None and any(g[2] and g[3] for g in self._foot_gaps):  # decision L91: the waist's
            keep_from = min(keep_from, prev_end - _LOOK_BACK_S)  # turn from the last stride's end is bridged
        elif prev_end is not None and self.waist_gap_yaw and "waist" in self.units \
                and waist_gap_max_s(prev_end, self._latest) > GAP_YAW_MAX_S:  # decision L498: a stop up to 60 s
            keep_from = min(keep_from, prev_end - _LOOK_BACK_S)  # keeps its samples for the waist's gap yaw
        if prev_end is not None and carry and self.waist_gap_yaw:  # decision E324: a stop over 60 s keeps the waist's
            span = long_stop_span(prev_end, self._latest)  # samples (up to 600 s of them) for L296's rest rotation
            if span is not None:
                waist_from = min(waist_from, span[0] - _LOOK_BACK_S)
        if self._stop_bias is not None and (prev_end is not None or "wAccelerometer" in self._buf):  # decision E272:
            # a stop's last KEEP_S seconds (E286: also the waist's rest before the first stride)
            start = -math.inf if prev_end is None else prev_end
            keep_from = min(keep_from, max(start, self._latest - _stop_bias.KEEP_S) - _LOOK_BACK_S)
        keep_from = min(keep_from, self._foot_silent_keep())  # decision E113
        waist_from = min(waist_from, keep_from)
        if keep_from <= self._drop_at and waist_from <= self._drop_at_w:  # nothing to drop (the common case between
            return  # two steps)
        self._trims += 1  # a computed-ahead step is recomputed (decision E24)
        for name, ring in self._buf.items():  # E305: carried_yaw reads the waist's accelerometer and gyroscope only
            ring.drop_before(waist_from if name in _CARRIED_RINGS else keep_from)
        if self._foot is not None:
            if self._foot_q:
                self._feed_foot()
            self._foot.drop_before(keep_from)
        self._oldest = min(float(r.t[r.i0]) for r in self._buf.values())
        at = {n: float(r.t[r.i0 + 1] if r.i1 - r.i0 > 1 else r.t[r.i0]) for n, r in self._buf.items()}
        self._drop_at = min((v for n, v in at.items() if n not in _CARRIED_RINGS), default=math.inf)
        self._drop_at_w = min((v for n, v in at.items() if n in _CARRIED_RINGS), default=math.inf)  # E285, E305
