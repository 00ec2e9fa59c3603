"""The lean runtime's waist-only tracker: a belt phone or lower-back IMU, numpy only (decisions W92-W95).

:class:`WaistTracker` runs a **waist bundle** (``pdrlearn export CAL.json --out BUNDLE``: the calibrated
``waist-pendulum`` parameters (W87's rate included), the options and the unit's axis frame): ``push(t, acc, gyr)``
returns the steps that became final, as :class:`pdrlearn.waist.WaistTracker` does with the PARAMS.json. Both are
:class:`WaistStream` -- one implementation (W64's reporting rules, the kernels ``track_waist`` calls, W31's
contacts from :mod:`pdrlearn.kernels.waist_stream`) -- so their steps are equal; this module imports numpy and
:mod:`pdrlearn.kernels` only (``tests/test_runtime_imports.py``).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.order import first_out_of_order, repeated, repeats_dropped_line
from pdrlearn.runtime.detector_line import live_detector_line
from pdrlearn.runtime.fixes import FixInput
from pdrlearn.runtime.replay import refuse_pushed_out_of_range
from pdrlearn.runtime.threads import OwnGuard, new_guard, one_call_at_a_time
from pdrlearn.textfile import read_json

log = logging.getLogger(__name__)

#: W64: the fragment test (W27) reads at most this many steps of the open walking sequence (about a minute of
#: walking; the recordings we have walk at most ~40 steps between stops, so it equals the replay's whole sequence)
FRAGMENT_CONTEXT_STEPS = 100
#: W64: a step is reported once this many later contacts of its walking sequence are decided (or it ended)
LOOKAHEAD_ROWS = 2
#: decision W165: with W134's ``pause_steps="standing"`` a step is reported once one more contact is decided: W18's
#: local period (``kernels.waist.local_medians``) reads up to three steps on each side of the step
PAUSE_LOOKAHEAD_ROWS = LOOKAHEAD_ROWS + 1
#: rows before the reported one that its heading window reads: W82's slow-turn window reads 3 strides back, and the
#: window's first step has no step before it for its stride rate (W24), so one more
HEADING_LOOKBACK_ROWS = 4
#: W65: without a declared frame, inference is tried on the held samples every INFER_EVERY_S of new data, from
#: frame_inference.MIN_WALK_S on; at most the last INFER_MAX_S seconds are held meanwhile
#: the straight / turning prior of the gyro heading (decision W7; ``pdrlearn.waist.heading.DEFAULT_TURN_GMM``)
DEFAULT_TURN_GMM = {"means": [0.03, 0.45], "sds": [0.04, 0.25], "weights": [0.7, 0.3]}


@dataclass(frozen=True)
class LiveStep:
    """One reported contact, as a row of ``track_waist(...).steps`` with its trajectory point.

    ``t`` the initial contact (s, the pushed clock); ``end_s`` the next contact of the walking sequence
    (``== t`` for a contact that closes one: ``length_m`` 0); ``length_m`` (m) and ``heading_rad`` (ENU, rad,
    start heading added) of the step; ``x``, ``y`` (m) the position at ``end_s``; ``side``: None, or with the option
    ``sides=True`` of :class:`pdrlearn.waist.WaistTracker` the foot of the contact, ``"left"`` / ``"right"`` / ``""``
    (undecided), from W20's lateral velocity on the samples the contact was decided on (decision W138: an option,
    not adopted as the default; 93 % the simulated foot where decided, the offline side 98 %); ``merged``: a W27
    fragment whose length its neighbour carries; ``turning``: the stride's straight (0) / turning (1) class (seed 003
    sec. 3.3); ``lat``, ``lon`` (degrees): the position at ``end_s`` when the tracker was given a geodetic start
    (decision W137), else None; ``z`` (m): the barometric altitude at ``end_s`` relative to the track's first sample
    (less the drift W231 left out of the pauses before it, decision E146) and ``dz_m`` its change over the step,
    ``pause_dz_m`` the change while standing before it (a pause over 30 s: its ride only, W231 / E146; W89's,
    ``track_waist``'s ``z`` / ``dz_m`` / ``pause_dz_m``; decisions E106, W158) when barometer samples were pushed
    (:meth:`WaistStream.push_barometer`), else None; ``stairs``: W91's rate test on that altitude
    (``track_waist``'s ``stairs`` column without ``stairs_climb``; with the option ``stairs_length`` such a step is at
    most the 0.30 m tread, decision E107), None without a barometer; ``pos_sigma_m`` (m): the modelled 1-sigma radius of
    the position after the step, `pdrlearn run`'s trajectory.csv ``pos_sigma_m`` at ``end_s`` (decisions L128, E352;
    "within about 2 x pos_sigma_m"), None once a fix has been used (an aided track is outside the model, as run's)."""

    t: float
    end_s: float
    length_m: float
    heading_rad: float
    x: float
    y: float
    has_next: bool
    merged: bool = False
    turning: int = 0
    side: str | None = None
    lat: float | None = None
    lon: float | None = None
    z: float | None = None
    dz_m: float | None = None
    stairs: bool | None = None
    pause_dz_m: float | None = None
    pos_sigma_m: float | None = None


class WaistStream(OwnGuard, FixInput):
    """The live waist-pendulum tracker's stream processing (decisions W31, W64, W92): shared by
    :class:`WaistTracker` (a waist bundle) and :class:`pdrlearn.waist.WaistTracker` (a PARAMS.json), which differ
    only in where the parameters and the axis frame come from.

    ``params``: an object with ``leg_m``, ``k``, ``f_m``, ``gyro_bias_rps``, ``turn_gmm`` (the resolved
    :class:`~pdrlearn.waist.params.WaistParams`, or the bundle's); ``options``: the resolved pipeline options
    (``integrate_stops``, ``turn_factor``, ``rhythm``, ``merge_fragments``, ``slow_turn_rps``, ``initial_heading``,
    ``pivot_steps``: W150; ``pause_ride``: W231 / E146 and ``rest_bias``: L296 / L308, decided at the contact after the
    pause or rest, absent = off);
    ``rotation``: the sensor -> body FLU matrix (None: the subclass's ``_frame`` finds one); ``start``: ``(x0, y0,
    h0)`` (m, m, rad ENU); ``latlon``: the start's ``(lat, lon)`` in degrees, checked (decision W137: each step's
    ``lat``/``lon``), or None; ``sides``: W138's causal side of each contact (an option); ``warnings``: the lines so
    far (logged here)."""

    _name = "WaistTracker"
    _one_at_a_time = "push/push_barometer/flush/add_fix"  # decisions E241, E256: the calls one_call_at_a_time guards

    def __init__(self, fs: float, *, params, options: dict, walk_threshold: float, rotation, start: tuple,
                 warnings: list[str], keep_steps: int | None = None, check_input: bool = True,
                 latlon: tuple[float, float] | None = None, sides: bool = False,
                 drop_duplicate_timestamps: bool = False, not_applied_live: str | None = None,
                 uniform_clock: bool | str = False):
        from collections import deque

        from pdrlearn.kernels.waist import TurnPrior
        from pdrlearn.kernels.waist_stream import MAX_STEP_S
        from pdrlearn.runtime.guard import FrozenWatch, UnitGuard

        self._busy = new_guard()  # decision E241: E231's guard, one thread at a time
        from pdrlearn.kernels.waist_stream import clock_option

        # decisions E366 / E371's options (kernels.waist_stream.Bridge)
        self._uniform_clock = clock_option(uniform_clock)
        self.fs = float(fs)
        self.params = params
        self.options = options
        x0, y0, self._h0 = (float(v) for v in start)
        self._xy0 = (x0, y0)
        self._sx = self._sy = 0.0  # running sums of the displacements (as track_waist's cumsum)
        self.position = (x0, y0)
        self.heading = float(self._h0)
        # decision W137: the geodetic position (rad) of the last reported (x, y), moved step by step (eq. 56/57)
        self._ll = None if latlon is None else (math.radians(latlon[0]), math.radians(latlon[1]))
        self._xy_reported = (x0, y0)
        # decision W138: |lateral velocity| at the last decided contacts, the scale a side is decided against
        self._side_scale: deque[float] = deque(maxlen=FRAGMENT_CONTEXT_STEPS)
        self._sides = bool(sides)
        self._init_fixes((x0, y0))  # decisions D19-D21: add_fix
        #: decision B119: the units of the first seconds (None: checked, or ``check_input=False``); B120: frozen
        self._guard = UnitGuard(WAIST_SENSORS, self._name) if check_input else None
        self._frozen = FrozenWatch()
        self._reclip = None
        if options.get("reclip", True):  # decision W623: a unit re-clipped on the belt, said and its radius grown
            from pdrlearn.kernels.reclip import LiveReclipWatch

            self._reclip = LiveReclipWatch(self.fs)
        self.warnings: list[str] = list(warnings)
        for w in warnings:
            log.warning("live waist tracker: %s", w)
        #: decision E368: E107's line for the offline-only options left at their offline defaults (None: none), which
        #: the live tracker does without: nothing the caller set or can act on, so logged at DEBUG, not warned
        self.not_applied_live = not_applied_live
        if not_applied_live:
            log.debug("live waist tracker: %s", not_applied_live)
        self.steps: deque[LiveStep] = deque(maxlen=keep_steps)
        self._thr = float(walk_threshold)
        self._max_step_s = MAX_STEP_S
        gmm = params.turn_gmm or {}  # as TurnClassifier(**turn_gmm) before a fit: the W7 prior where unset
        self._clf = TurnPrior(*(gmm.get(k) if gmm.get(k) is not None else DEFAULT_TURN_GMM[k]
                                for k in ("means", "sds", "weights")))
        self._rot = None if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
        self._proc = None
        self._last_t = -np.inf
        #: decision E203: drop a sample whose timestamp repeats the one before (keep the first), counted here
        self._drop_dups = bool(drop_duplicate_timestamps)
        self.n_dropped_duplicates = 0
        self._dts: list[float] | None = []  # the first sample intervals, until the unit check (E29)
        # samples of the navigation frame (absolute index b0 + i) since the oldest one a pending step needs
        self._b0 = 0
        self._bt = np.zeros(0)
        self._bv = np.zeros(0)  # vertical acceleration (gravity removed)
        self._bw = np.zeros(0)  # vertical rate (rad/s)
        self._bc = np.zeros(0)  # its running integral, minus the gyro bias (rad)
        self._cum_last = 0.0
        self._w_last: float | None = None
        self._t_prev: float | None = None
        # contacts reported by the detector (rows of track_waist's steps table): id -> row
        self._rows: dict[int, dict] = {}
        self._n_rows = 0
        self._next = 0  # id of the next row to report
        self._absorbed: set[int] = set()  # W27 fragments merged into the row before them
        self._span_start: dict[int, int] = {}  # row -> first row of its merged step (a fragment before it)
        self._h_seq: float | None = None  # heading of the last step of the open sequence (before the start rotation)
        self._cur_gyro = 0.0  # track_waist's ``current`` of the gyro headings (with integrate_stops)
        self._cur_out = 0.0  # and of the reported headings
        self._stop_cum: float | None = None  # running integral at the last sequence's closing contact
        self._rest_a = 0.0  # and its time (L308)
        self._seen_seq = False
        self._n_gaps = 0
        self._cum_first: float | None = None  # running integral at the first contact (W74)
        self._untracked_warned = False
        # decision W165: W134's stand steps (the option's value "standing"; a bundle exported before has none: off)
        self._pause = options.get("pause_steps") == "standing"
        self._wait = PAUSE_LOOKAHEAD_ROWS if self._pause else LOOKAHEAD_ROWS
        self._seq_steps = self._seq_stands = 0  # W529: the open sequence's steps and W134 stands so far
        self._ba = np.zeros((0, 3))  # with it: navigation-frame specific force (m/s^2) and rate (rad/s)
        self._bg = np.zeros((0, 3))
        self._alt = None  # decision E106: the barometric altitude (kernels.barometer.LiveAltitude), once pushed
        self._z_prev = 0.0  # the altitude at the last reported step's end (0 at the track's first sample)
        self._baro_last = -np.inf
        # decision E358: under stairs_length "climbs" with live_climbs "hold", the open run of W91's proposals whose
        # steps wait until it is a climb (W108's, read causally) or has ended (None: off, E107 names "climbs")
        self._climbs = None
        if options.get("stairs_length") == "climbs" and options.get("live_climbs") == "hold":
            from pdrlearn.kernels.barometer import LiveClimbHold

            self._climbs = LiveClimbHold()
        # decision E146: W231's ride of a pause over RIDE_WINDOW_S, decided at its step's contact (a bundle exported
        # before E146 has no such option: off); the drift left out: (pause start, pause end, m) and its sum
        self._ride = bool(options.get("pause_ride", False))
        self._pause_a: float | None = None  # the last reported row's end (the next pause's start)
        self.pause_drifts: list[tuple[float, float, float]] = []
        self._drift_said = False  # decision E150: W231's line once per stream, however often flush() is called
        self._drift = 0.0
        # decision L308: L296's rest bias, decided at the contact that ends the rest (the whole rest is held: the
        # buffer keeps the samples from HEADING_LOOKBACK_ROWS rows back); the magnitudes its still test reads
        self._rest_bias = bool(options.get("rest_bias", False)) and bool(options["integrate_stops"])
        self._bam = np.zeros(0)
        self._bgm = np.zeros(0)
        self._rest_removed = 0.0  # the bias left out so far (W74 compares with the integrated yaw, as offline)
        #: decision L309: the (start, end) of each rest L296 corrected (``track_waist``'s ``info["rest_bias_rests"]``,
        #: L306), None when L296 is not in force
        self.rest_bias_rests: list[tuple[float, float]] | None = [] if self._rest_bias else None
        self._radius = None  # decision E355: the position radius' carried sums (E352), made at the first report

    # -- the axis frame (hooks: pdrlearn.waist.WaistTracker infers or checks it, W65 / B108) -------------
    def _frame_pending(self) -> bool:
        """Whether pushed samples still go through :meth:`_frame` (a frame inference or check pending)."""
        return False

    def _frame(self, t: np.ndarray, v: np.ndarray):
        """Samples to feed once a frame is known (None while it is not): here the frame is given."""
        self._start_proc()
        return t, v

    def _held_size(self) -> int:
        return 0

    def _no_frame_at_end(self) -> None:
        """:meth:`flush` before any frame was known."""

    def state_size(self) -> int:
        """Numbers the tracker holds to process what comes (not :attr:`steps`): its sample buffer and pending rows,
        the held samples of W65 and the W31 detector's window; bounded over any stream length (decision W64)."""
        n = 4 * self._bt.size + 6 * len(self._rows) + len(self._absorbed) + len(self._span_start)
        n += self._ba.size + self._bg.size  # W165
        n += self._bam.size + self._bgm.size  # L308
        n += len(self._side_scale)  # W138: at most FRAGMENT_CONTEXT_STEPS
        n += self._held_size()
        n += 0 if self._alt is None else self._alt.size()  # E106: the barometer samples a pending step reads
        n += 0 if self._climbs is None else 16 * self._climbs.size()  # E358: the held steps (a run of proposals)
        p = self._proc
        if p is not None:
            n += sum(np.size(v) for v in p.buf.values()) + 4 * len(p.decided) + sum(np.size(r[1]) for r in p.raw)
            n += p.bridge.tail_v.size + p.bridge.tail_t.size + 2 * sum(len(g) for g in p.gaps.values())
            n += 2 * len(p.bridge.filled)
        return int(n)

    # -- input -------------------------------------------------------------------------------------------
    @one_call_at_a_time  # decision E241
    def push(self, t, acc, gyr) -> list[LiveStep]:
        """Add samples: ``t`` (n,) s increasing, ``acc`` (n, 3) m/s^2 with gravity, ``gyr`` (n, 3) rad/s, in the
        unit's sensor frame. Returns the steps reported by this push (decision W64: once final); a push without
        samples (``push([], [], [])``) returns none and changes nothing (decision E40)."""
        t = np.asarray(t, dtype=np.float64).reshape(-1)
        acc, gyr = np.asarray(acc, dtype=np.float64), np.asarray(gyr, dtype=np.float64)
        if not t.size and not acc.size and not gyr.size:  # decision E40: an empty push is a no-op
            return []
        if acc.ndim == 1 and acc.size == 3 and t.size == 1:
            acc, gyr = acc.reshape(1, 3), gyr.reshape(1, 3)
        if acc.shape != (t.size, 3) or gyr.shape != (t.size, 3):
            raise DataError(f"{self._name}.push: expected acc and gyr of shape ({t.size}, 3) for {t.size} "
                            f"timestamps, got {acc.shape} and {gyr.shape}")
        if not t.size:
            return []
        if not (np.isfinite(t).all() and np.isfinite(acc).all() and np.isfinite(gyr).all()):
            raise DataError(f"{self._name}.push: NaN or inf in the pushed samples; drop those samples")
        keep = np.ones(t.size, dtype=bool)
        if self._drop_dups:  # decision E203: a phone's repeated sample, dropped (the first kept)
            keep = ~repeated(t, [self._last_t])  # the kernel the foot Tracker shares (E225)
        self._check_order(t[keep], np.flatnonzero(keep))  # E203: named by their index in the pushed arrays
        if not keep.all():
            t, acc, gyr = t[keep], acc[keep], gyr[keep]
            if not t.size:
                self._count_repeats(int((~keep).sum()))
                return []
        guard, pushed = self._guard, dict(zip(WAIST_SENSORS, ((t, acc), (t, gyr)), strict=True))
        if guard is not None:  # decision B119, before any state changes (a refused push changes nothing)
            arrays = {n: pushed[n] for n in guard.wanted() if n in pushed}
            judged = guard.check(arrays)
        # decision B442: B435's range check (the foot Tracker's), after the guard's verdict, before any change
        refuse_pushed_out_of_range(self._name, pushed, guard)
        if self._dts is not None:
            self._unit_check(t)
        if not keep.all():  # E203 (amended): counted only once every check has passed
            self._count_repeats(int((~keep).sum()))
        if guard is not None:
            guard.take(arrays, judged)
        if self._fixes.t_start is None:  # aid_track's t_start: the track's first sample (decision D19, amended)
            self._fixes.t_start = float(t[0])
        if self._alt is not None:  # E106: the altitude is relative to the track's first sample (track_waist's)
            self._alt.set_origin(self._fixes.t_start)
        self._last_t = float(t[-1])
        for msg in self._frozen.push(pushed):  # decision B120: a frozen sensor, one warning per run
            self.warnings.append(msg)
            log.warning("live waist tracker: %s", msg)
        line = None if self._reclip is None else self._reclip.push(t, acc)  # decision W623
        if line:
            self.warnings.append(line)
            log.warning("live waist tracker: %s", line)
        v = np.column_stack([acc, gyr])
        if self._proc is None or self._frame_pending():
            v_t = self._frame(t, v)
            if v_t is None:
                return []
            t, v = v_t
        return self._feed(self._proc.process(t, v), final=False)

    def _count_repeats(self, n: int) -> None:
        """Decision E203: ``n`` dropped repeated samples counted; the first drop of a run adds one warning line (called
        only for a push every check accepted: a refused push changes nothing, B119)."""
        if not self.n_dropped_duplicates:
            msg = repeats_dropped_line(f"{self._name}.push", "n_dropped_duplicates")
            self.warnings.append(msg)
            log.warning("live waist tracker: %s", msg)
        self.n_dropped_duplicates += n

    def _check_order(self, t: np.ndarray, index: np.ndarray, *, where: str = "push", last: float | None = None) -> None:
        """Decision E203: one line naming the first sample of the push that does not increase strictly - from the
        previous push's last sample, or from the sample before it in this push - and the fix. ``t`` the kept samples'
        times, ``index`` their indices in the pushed array (the line names those: a dropped repeat shifts no index).
        ``where`` / ``last``: the method and its stream's last time (decision E349: ``push_barometer``'s own)."""
        last = self._last_t if last is None else last
        k = first_out_of_order(t, last)
        if k is None:
            return
        i, now = int(index[k]), float(t[k])
        before = float(t[k - 1]) if k else float(last)  # a dropped repeat before it has prev's time
        fix = ("pass drop_duplicate_timestamps=True to drop repeated samples (the first kept, as 'pdrlearn import "
               "--drop-duplicate-timestamps')" if now == before else "sort the samples by time before pushing")
        what = "repeats" if now == before else "goes back from"
        if k == 0:
            raise DataError(f"{self._name}.{where}: timestamps must increase strictly across pushes (seconds): this "
                            f"push's {'first sample' if i == 0 else f'sample {i}'} (t={now:.6f} s) {what} the previous "
                            f"push's last (t={last:.6f} s); {fix}")
        raise DataError(f"{self._name}.{where}: timestamps must increase strictly (seconds): sample {i} of this push "
                        f"(t={now:.6f} s) {what} sample {i - 1} (t={before:.6f} s); {fix}")

    @one_call_at_a_time  # decision E241
    def push_barometer(self, t, p_hpa) -> None:
        """Add waist barometer samples (decision E106): ``t`` (n,) s on the clock of :meth:`push`, increasing strictly
        across pushes, ``p_hpa`` (n,) pressure in hPa (a non-finite sample is skipped, as offline). Each step then has
        the barometric altitude ``track_waist`` gives it (W89: ``LiveStep.z`` / ``dz_m``), read on the samples pushed
        before the step is reported: push each slice of the barometer before the motion samples of the same time
        for the offline numbers. A barometer whose altitude changes faster than anyone travels (decision B188) is
        warned about once and read no further. Returns nothing; steps come from :meth:`push` / :meth:`flush`."""
        from pdrlearn.kernels.barometer import WAIST_EFFECT, LiveAltitude, implausible_barometer_message

        t = np.asarray(t, dtype=np.float64).reshape(-1)
        p = np.asarray(p_hpa, dtype=np.float64).reshape(-1)
        if p.shape != t.shape:
            raise DataError(f"{self._name}.push_barometer: expected {t.size} pressures (hPa) for {t.size} timestamps, "
                            f"got shape {p.shape}")
        if not t.size:
            return
        if not np.isfinite(t).all():
            raise DataError(f"{self._name}.push_barometer: NaN or inf timestamps; drop those samples")
        keep = ~repeated(t, [self._baro_last]) if self._drop_dups else np.ones(t.size, dtype=bool)  # E203 (E349)
        self._check_order(t[keep], np.flatnonzero(keep), where="push_barometer", last=self._baro_last)  # E349
        if not keep.all():
            t, p = t[keep], p[keep]
            self._count_repeats(int((~keep).sum()))
            if not t.size:
                return
        self._baro_last = float(t[-1])
        if self._alt is None:
            self._alt = LiveAltitude()
            if self._fixes.t_start is not None:
                self._alt.set_origin(self._fixes.t_start)
        found = self._alt.push(t, p)
        if found is not None:  # decision B188, as the offline track: one line, the barometer read no further
            msg = implausible_barometer_message(found, WAIST_EFFECT.replace("stays 0", "stays where it was"))
            self.warnings.append(msg)
            log.warning("live waist tracker: %s", msg)

    def _pos_sigma(self, t: float, end: float, length: float, heading: float) -> float:
        """Decision E352: the 1-sigma radius (m) of the position after this step, as `pdrlearn run`'s trajectory.csv
        ``pos_sigma_m`` (decision L128's ``"waist"`` model, L297 / L306's clock over the rests L296 corrected live,
        L309) after the steps reported so far and this one (the radius after a step reads no later step). Decision
        E355: the kernel's :class:`~pdrlearn.kernels.position_sigma.RadiusState` carries those steps' sums, so a
        report costs the same at any length of walk (E352 recomputed the whole track: 11.38 ms at 5000 steps); the
        one mechanism of :func:`~pdrlearn.kernels.position_sigma.stride_radius`, the offline tracks' kernel."""
        if self._radius is None:
            from pdrlearn.kernels.position_sigma import SIGMA_PARAMS, RadiusState
            from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S

            # decision L128: the waist model; L297 / L306: the rests over REST_BIAS_MIN_S L296 corrected
            self._radius = RadiusState(float(self._fixes.t_start), SIGMA_PARAMS["waist"], rest_s=REST_BIAS_MIN_S)
        state = self._radius
        clock = [end] if self.rest_bias_rests is None else state.clock([t], [end], self.rest_bias_rests)
        r, _ = state.extend([length], [heading], clock)
        return float(r[0])

    def _stairs_rise(self, row: dict) -> float | None:
        """What decision W91's test (``track_waist``'s ``_stairs_steps`` without ``stairs_climb``) reads on the live
        altitude: its change (m) over STAIRS_RATE_WINDOW_S centred on the step's middle (``stairs_rate_test``); None
        without a (usable) barometer."""
        from pdrlearn.kernels.barometer import STAIRS_RATE_WINDOW_S

        if self._alt is None:
            return None
        mid, half = 0.5 * (row["t"] + row["end"]), 0.5 * STAIRS_RATE_WINDOW_S
        last = float(self._alt.times[-1]) if self._alt.times.size else mid + half  # (none: at() is None)
        # decision W622: both ends' windows (W621's, long at a low rate) cut alike on their right by the samples not
        # yet pushed, so the rise lags a flight alike at both ends instead of shrinking it
        a, b = self._alt.at(mid - half, upto=last - 2.0 * half), self._alt.at(mid + half)
        return None if a is None or b is None else float(b - a)

    def _unit_check(self, t: np.ndarray) -> None:
        """Decision E29 as the runtime's: the first RATE_PROBE_MIN sample intervals give a rate more than
        RATE_UNIT_FACTOR away from ``fs``: the timestamps are not in seconds (in ms the W31 detector re-ran its
        window on every sample, for minutes, and gave no step). One line, before anything is fed."""
        from pdrlearn.runtime.resample import RATE_PROBE_MIN, check_rate_unit

        d = np.diff(t, prepend=self._last_t) if np.isfinite(self._last_t) else np.diff(t)
        dts = self._dts + d[:RATE_PROBE_MIN].tolist()
        if len(dts) < RATE_PROBE_MIN:
            self._dts = dts
            return
        check_rate_unit(f"{self._name}.push", 1.0 / float(np.median(dts[:RATE_PROBE_MIN])), self.fs, "fs=")
        self._dts = None  # judged once

    @one_call_at_a_time  # decision E241
    def flush(self) -> list[LiveStep]:
        """End of the stream: decide the last contacts and report every step left."""
        guard, self._guard = self._guard, None
        if guard is not None:  # decision B119: a stream shorter than GUARD_S, checked on what it has
            guard.finish()
        if self._proc is None:
            self._no_frame_at_end()
            return []
        out = self._feed(self._proc.flush(), final=True)
        self._warn_unused_fixes()  # decision D21
        if self.pause_drifts and not self._drift_said:  # decision E146: W231's line, once the stream has ended
            from pdrlearn.kernels.pause_ride import drift_line  # (its total); E150: once per stream

            self._drift_said = True
            a, b, d = (np.array(v) for v in zip(*self.pause_drifts, strict=True))
            line = drift_line(d, a, b)
            if line:
                self.warnings.append(line)
                log.warning("live waist tracker: %s", line)
        return out

    def _start_proc(self) -> None:
        if self._proc is not None:
            return
        from pdrlearn.kernels.waist_stream import RealtimeContacts, rule_contacts

        # the waist-ic detector's defaults (W31), as ``track --pipeline waist-pendulum --realtime`` runs it
        rules = rule_contacts({"walk_threshold": self._thr, "max_step_s": self._max_step_s,
                               "rhythm": bool(self.options["rhythm"]),  # W166: W131 inside W31's window
                               "contact_shift": bool(self.options.get("contact_shift", True))  # E130: as replay
                               and bool(self.options.get("realtime_contact_shift", False))})
        self._proc = RealtimeContacts(self.fs, rules, rotation=self._rot, max_step_s=self._max_step_s,
                                      on_nav=self._add, uniform_clock=getattr(self, "_uniform_clock", False))

    # -- the navigation-frame samples -------------------------------------------------------------------
    def _add(self, t: np.ndarray, acc_v: np.ndarray, w_z: np.ndarray, acc_nav: np.ndarray,
             gyr_nav: np.ndarray) -> None:
        w = w_z - self.params.gyro_bias_rps
        if self._w_last is None:  # rate_integral: 0 at the first sample, trapezoids in order (as one cumsum)
            inc = 0.5 * (w[1:] + w[:-1]) * np.diff(t)
            c = np.cumsum(np.concatenate([[0.0], inc]))
        else:
            inc = 0.5 * (w + np.concatenate([[self._w_last], w[:-1]])) * np.diff(np.concatenate([[self._t_prev], t]))
            c = np.cumsum(np.concatenate([[self._cum_last], inc]))[1:]
        self._w_last, self._t_prev, self._cum_last = float(w[-1]), float(t[-1]), float(c[-1])
        self._bt = np.concatenate([self._bt, t])
        self._bv = np.concatenate([self._bv, acc_v])
        self._bw = np.concatenate([self._bw, w_z])
        self._bc = np.concatenate([self._bc, c])
        if self._pause:  # W165: what W134's still test and the trunk's travel read
            self._ba = np.concatenate([self._ba, acc_nav])
            self._bg = np.concatenate([self._bg, gyr_nav])
        if self._rest_bias:  # L308: what L296's still test reads (standstill_mask: magnitudes only)
            self._bam = np.concatenate([self._bam, np.linalg.norm(acc_nav, axis=1)])
            self._bgm = np.concatenate([self._bgm, np.linalg.norm(gyr_nav, axis=1)])

    def _idx(self, ts: float) -> int:
        """Buffer index of the sample at time ``ts`` (a contact is a sample)."""
        i = min(int(np.searchsorted(self._bt, ts - 0.25 / self.fs)), self._bt.size - 1)
        if not abs(self._bt[i] - ts) < 0.5 / self.fs:  # an internal error, not the caller's: say so
            raise RuntimeError(f"{self._name}: the sample at {ts:.3f} s left the buffer "
                               f"({self._bt[0]:.3f}-{self._bt[-1]:.3f} s); please report this")
        return i

    def _trim(self) -> None:
        """Drop the samples no future report reads: contacts still to come have their IC after the detector's
        ``done``; the pending ones (the detector's and ours, from HEADING_LOOKBACK_ROWS rows before the next) are
        kept."""
        lows = [self._proc.decider.done + 1 - self._b0]
        lows += [i - self._b0 for i, *_ in self._proc.decided]
        k = max(self._next - HEADING_LOOKBACK_ROWS, 0)
        if k in self._rows:
            lows.append(self._idx(self._rows[k]["t"]))
        drop = max(0, min(lows) - 2)
        if drop:
            self._bt, self._bv, self._bw, self._bc = (a[drop:] for a in (self._bt, self._bv, self._bw, self._bc))
            if self._pause:
                self._ba, self._bg = self._ba[drop:], self._bg[drop:]
            if self._rest_bias:
                self._bam, self._bgm = self._bam[drop:], self._bgm[drop:]
            self._b0 += drop
        filled = self._proc.bridge.filled
        while filled and self._bt.size and filled[0][1] < self._bt[0]:  # W165: gaps before the buffer
            filled.pop(0)
        if self._alt is not None and self._bt.size:  # E106: a pending step ends after the oldest sample held
            held = float(self._bt[0])
            if self._ride:  # E146: W231 reads the whole open pause (before the first step too)
                a = self._fixes.t_start if self._pause_a is None else self._pause_a
                held = held if a is None else min(held, float(a))
            self._alt.trim(held)

    # -- contacts -> steps ------------------------------------------------------------------------------
    def _feed(self, contacts: list, *, final: bool) -> list[LiveStep]:
        for ev, _start_s, end, _conf, extra in contacts:
            k = self._n_rows
            prev = self._rows.get(k - 1)
            seq = k if prev is None or not prev["has_next"] else prev["seq"]
            self._rows[k] = {"t": float(ev), "end": float(end), "has_next": bool(end > ev), "seq": seq,
                             "fc": float(extra.get("fc_s", np.nan)), "side": self._side(extra.get("v_ml_mps"))}
            self._n_rows += 1
        if self._proc is not None and len(self._proc.gaps.get("online stream", ())) > self._n_gaps:
            self._gap_warnings()
        out = []
        while self._next < self._n_rows and self._ready(self._next, final):
            out.extend(self._report(self._next))
            self._next += 1
            old = self._next - LOOKAHEAD_ROWS - FRAGMENT_CONTEXT_STEPS - 1
            if old in self._rows:
                del self._rows[old]
        if final and self._climbs is not None:  # decision E358: the stream's end ends the open run
            out.extend(self._emit(q, bound) for q, bound in self._climbs.flush())
        if self._proc is not None:
            self._trim()
        return out

    def _side(self, v: float | None) -> str | None:
        """Decision W138: a decided contact's side from W20's lateral velocity ``v`` (m/s) at it, read on the samples it
        was decided on (:class:`~pdrlearn.kernels.waist_stream.RealtimeContacts`), against the median |v| of the
        contacts decided so far (this one included; the last FRAGMENT_CONTEXT_STEPS): W129's labels."""
        from pdrlearn.kernels.waist import SIDE_LABELS, step_sides

        if v is None or not self._sides:
            return None
        self._side_scale.append(abs(float(v)))
        scale = np.asarray(self._side_scale)
        side = step_sides(np.concatenate([[float(v)], scale]), np.r_[False, np.ones(scale.size, dtype=bool)])[0]
        return SIDE_LABELS[int(side)]

    def _gap_warnings(self) -> None:
        from pdrlearn.kernels.gaps import gap_warnings
        from pdrlearn.kernels.waist_stream import live_gap_fix

        gaps = self._proc.gaps.get("online stream", [])
        new = gaps[self._n_gaps:]
        self._n_gaps = len(gaps)
        for w in gap_warnings({"wAccelerometer, wGyroscope": new}, fix=live_gap_fix()):  # decision E349
            self.warnings.append(w)
            log.warning("live waist tracker: %s", w)

    def _check_untracked(self, row: dict, h: float) -> None:
        """Decision W74, as ``track_waist``: one warning when a step's heading ``h`` (rad, before the start rotation)
        misses :data:`pdrlearn.waist.heading.UNTRACKED_TURN_WARN_DEG` of the yaw turned since the first contact."""
        from pdrlearn.kernels.waist import UNTRACKED_TURN_WARN_DEG, turn_gap, untracked_turn_message

        if self._untracked_warned or self._cum_first is None:
            return
        h = h + self._rest_removed  # decision L296 / L308: the long rests' bias left out is the yaw's, not a turn
        diff = np.degrees(float(turn_gap(float(np.interp(row["end"], self._bt, self._bc)) - self._cum_first, h)))
        if abs(diff) >= UNTRACKED_TURN_WARN_DEG:
            self._untracked_warned = True
            msg = untracked_turn_message(float(diff), float(row["end"]), bool(self.options["integrate_stops"]))
            self.warnings.append(msg)
            log.warning("live waist tracker: %s", msg)

    @staticmethod
    def _horizon(k: int) -> int:
        """W64: the last row row ``k``'s report reads."""
        return k + LOOKAHEAD_ROWS

    def _ready(self, k: int, final: bool) -> bool:
        """W64: row ``k`` is final once its walking sequence has ended or the rows to its horizon are known."""
        if final:
            return True
        hz = k + self._wait  # W64's horizon; one row more with W134's stand steps (W165)
        for j in range(k, min(hz, self._n_rows - 1) + 1):
            if not self._rows[j]["has_next"]:
                return True  # the sequence is complete
        return self._n_rows - 1 >= hz

    def _seq_rows(self, k: int) -> list[int]:
        """The rows of ``k``'s walking sequence from at most FRAGMENT_CONTEXT_STEPS before it to LOOKAHEAD_ROWS
        after it (or its end): the same rows whatever was pushed when (W64)."""
        s = self._rows[k]["seq"]
        lo = max(s, k - FRAGMENT_CONTEXT_STEPS, min(self._rows))
        ids = []
        for j in range(lo, min(self._horizon(k) + 1, self._n_rows)):
            ids.append(j)
            if not self._rows[j]["has_next"]:
                break
        return ids

    def _stand_factor(self, k: int, a: int, b: int, length: float) -> float:
        """Decision W165: W134's factor of row ``k`` (its step from row ``a``'s contact to row ``b``'s end, W27) as the
        offline pendulum model computes it (``PendulumLength(pause_steps="standing")``: the kernels
        ``still_samples``, ``step_still_travel``, ``standing_step_mask``, ``progression_factor``), on the rows of its
        walking sequence known now (up to PAUSE_LOOKAHEAD_ROWS after it, or the sequence's end: the three steps
        W18's local period reads) and the buffered samples of the step; 1 where the step holds no stand. Called once
        per step of a sequence in order (W516 / W529 count the sequence's steps and stands so far)."""
        from pdrlearn.kernels import waist as K

        s = self._rows[k]["seq"]
        ids = []
        for j in range(max(s, k - FRAGMENT_CONTEXT_STEPS, min(self._rows)), min(k + self._wait + 1, self._n_rows)):
            ids.append(j)
            if not self._rows[j]["has_next"]:
                break
        t0 = np.array([self._rows[j]["t"] for j in ids])
        t1 = np.array([self._rows[j]["end"] for j in ids])
        hn = np.array([self._rows[j]["has_next"] for j in ids])
        win = K.fragment_windows(t0, t1, hn) if self.options["merge_fragments"] else {}
        use, span = hn.copy(), t1 - t0
        for ow, (x, y) in win.items():  # as the model's fragment_mask and _spans
            use[x:y + 1] = False
            use[ow], span[ow] = True, t1[y] - t0[x]
        jk = k - ids[0]
        use[jk], span[jk] = True, self._rows[b]["end"] - self._rows[a]["t"]  # this step, as reported (W64)
        i0, i1 = self._idx(self._rows[a]["t"]), self._idx(self._rows[b]["end"])
        w = max(1, int(round(0.25 * self.fs)))  # standstill_mask's window, whole on both sides of the step
        lo, hi = max(i0 - w, 0), min(i1 + w + 1, self._bt.size)
        still = K.still_samples(self._ba[lo:hi], self._bg[lo:hi], self.fs)
        half = 0.5 / self.fs
        for ga, gb in self._proc.bridge.filled:  # W136: samples made up inside a gap are no standstill
            still &= ~((self._bt[lo:hi] > ga + half) & (self._bt[lo:hi] < gb - half))
        disp, run_s = K.step_still_travel(self._ba[lo:hi, :2], still, self.fs, i0 - lo, i1 - lo)
        runs = np.full(len(ids), np.nan)
        runs[jk] = run_s
        stand = bool(K.standing_candidates(runs, span, use, ~hn)[jk])
        self._seq_steps += 1  # W516 / W529: the sequence's steps and W134 stands so far, as the model counts them
        self._seq_stands += stand
        if not (stand and K.stands_within_share(self._seq_stands, self._seq_steps)) or not length > 0:
            return 1.0
        return float(K.progression_factor(np.array([disp]), np.array([length]))[0])

    def _rest_turn(self, t_b: float) -> float:
        """W72's rotation from the last sequence's closing contact to ``t_b`` (the next one's first contact); with
        ``rest_bias`` (decision L308) L296's :func:`~pdrlearn.kernels.rest_heading.rest_rotation` on the held samples
        of the rest, as ``track_waist``'s ``_step_headings``."""
        whole = float(np.interp(t_b, self._bt, self._bc)) - self._stop_cum
        if not self._rest_bias:
            return whole
        from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S, rest_rotation
        from pdrlearn.kernels.waist import still_from_magnitudes

        t_a = self._rest_a
        if t_b - t_a <= REST_BIAS_MIN_S:  # W72, as offline (no still test needed)
            return whole
        still = still_from_magnitudes(self._bam, self._bgm, self.fs)  # standstill_mask's test (L296)
        turned = rest_rotation(self._bt, self._bw - self.params.gyro_bias_rps, still, t_a, t_b, cum=self._bc)
        if turned != whole:
            self._rest_removed += whole - turned
            self.rest_bias_rests.append((float(t_a), float(t_b)))  # decision L309: L306's spans
        return turned

    def _pause_drift(self, t_b: float, pause_dz: float) -> float:
        """Decision E146: the drift (m) of the pause before the step starting at ``t_b`` whose whole change is
        ``pause_dz`` (W158): that change less W231's ride when the pause lasts over RIDE_WINDOW_S, else 0."""
        from pdrlearn.kernels.pause_ride import RIDE_WINDOW_S

        t_a = self._fixes.t_start if self._pause_a is None else self._pause_a
        if not self._ride or t_a is None or not t_b - t_a > RIDE_WINDOW_S:  # a short pause counts whole (W158)
            return 0.0
        ride = self._alt.ride(t_a, t_b)
        if ride is None:
            return 0.0
        drop = pause_dz - ride
        if drop:
            self.pause_drifts.append((float(t_a), float(t_b), float(drop)))
        return drop

    def _report(self, k: int) -> list[LiveStep]:
        """The steps reported once row ``k`` is final: its own, or (decision E358's hold) none or the held ones."""
        from pdrlearn.kernels import waist as K
        from pdrlearn.kernels.barometer import stairs_rate_test

        p, o = self.params, self.options
        row = self._rows[k]
        s = row["seq"]
        if self._cum_first is None:
            self._cum_first = float(np.interp(row["t"], self._bt, self._bc))
        if k == s:  # a walking sequence starts: track_waist's ``current`` (and the turn made standing, W: opt)
            self._seq_steps = self._seq_stands = 0  # W516 / W529's counts
            if self._seen_seq and o["integrate_stops"] and self._stop_cum is not None:
                self._cur_gyro += self._rest_turn(row["t"])
            self._seen_seq = True
            self._h_seq = None
        ids = self._seq_rows(k)
        merged, length, turning = False, 0.0, 0
        if row["has_next"]:
            # -- heading (seed 003 sec. 3.3 via gyro_headings on the sequence from two steps before) -------
            lw = max(s, k - HEADING_LOOKBACK_ROWS, ids[0])
            ev = [self._rows[j]["t"] for j in ids if j >= lw]
            if self._rows[ids[-1]]["has_next"]:  # the open sequence's next contact is decided (its end)
                ev.append(self._rows[ids[-1]]["end"])
            i0 = max(self._idx(ev[0]) - 1, 0)
            i1 = self._idx(ev[-1]) + 2
            win = SimpleNamespace(t=self._bt[i0:i1], w_z=self._bw[i0:i1])
            hd, tr = K.gyro_headings(win.t, win.w_z, np.asarray(ev), predict=self._clf.predict,
                                     bias_rps=p.gyro_bias_rps, heading0=0.0, cum=self._bc[i0:i1],
                                     slow_turn_rps=float(o["slow_turn_rps"] or 0.0),
                                     gentle_curves=bool(o.get("gentle_curves",  # W543
                                                              K.GENTLE_DEFAULTS["gentle_curves"])))
            j = k - lw
            turning = int(tr[j])
            if k == s:
                h = self._cur_gyro + hd[0]
            else:
                h = self._h_seq + (hd[j] - hd[j - 1])
            self._h_seq = h
            # -- length (W10 whole-step pendulum, W27 fragments, W19 turn factor) -------------------------
            a, b = self._span_start.pop(k, k), k
            if k in self._absorbed:  # a fragment the step before carries (W27)
                merged = True
                self._absorbed.discard(k)
            elif o["merge_fragments"]:  # W27 on the sequence so far (W64): merges are never undone
                rel = [j for j in ids if j >= ids[0]]
                hn = np.array([self._rows[j]["has_next"] for j in rel])
                wins = K.fragment_windows(np.array([self._rows[j]["t"] for j in rel]),
                                        np.array([self._rows[j]["end"] for j in rel]), hn)
                owner = {f: ow for ow, (x, y) in wins.items() for f in range(x, y + 1) if f != ow}
                jk, nb = k - ids[0], k - ids[0] + 1
                if a == k and jk in owner:  # k is a fragment (one with a fragment merged into it is an owner)
                    ow = owner[jk]
                    if ow != nb and not (nb < len(rel) and hn[nb] and nb not in owner):
                        ow = None  # its owner, the step before, is reported already and the next is no step
                    if ow is not None:
                        merged = True
                        self._span_start[k + 1] = a
                elif jk in wins and wins[jk][1] == nb:  # the fragment after k merges into k
                    self._absorbed.add(k + 1)
                    b = k + 1
            if not merged:
                end_b = self._rows[b]["end"]
                h_m = K.vertical_excursion(self._bv, self.fs, self._idx(self._rows[a]["t"]), self._idx(end_b))
                dyaw = sum(float(np.interp(self._rows[j]["end"], self._bt, self._bc)
                                 - np.interp(self._rows[j]["t"], self._bt, self._bc)) for j in range(a, b + 1))
                length = max(float(K.pendulum_length(np.array([h_m]), p.leg_m, k=p.k, f=p.f_m)[0]), 0.0)
                if self._pause:  # W134 / W165: a stand inside a walk keeps the trunk's travel (the model's factor)
                    length *= self._stand_factor(k, a, b, length)
                if o["turn_factor"]:
                    length *= float(K.turning_step_factor(np.array([dyaw]))[0])
                if o.get("pivot_steps"):  # W150 (a bundle exported before it has no such option: off)
                    length *= float(K.pivot_step_factor(np.array([length]), np.array([dyaw]))[0])
            head = h
            self._check_untracked(row, h)
        else:  # a contact closing its sequence: no displacement, the sequence's last heading
            head = self._h_seq if self._h_seq is not None else self._cur_out
            if self._h_seq is not None:
                self._cur_gyro = self._cur_out = self._h_seq
            self._stop_cum = float(np.interp(row["t"], self._bt, self._bc))
            self._rest_a = row["t"]  # L308: the rest starts at the closing contact (offline's t_a)
        rise = self._stairs_rise(row)
        stairs = None if rise is None else bool(stairs_rate_test(rise))
        # W91's option, as track_waist: at most the tread on stairs (E107); W156's "climbs" needs the whole
        # recording's climbs: named as not applied live (unapplied_options_line) unless E358's hold reads them
        if stairs and o.get("stairs_length") and o.get("stairs_length") != "climbs":
            from pdrlearn.kernels.barometer import STAIR_TREAD_M

            length = min(length, STAIR_TREAD_M)
        enu = float(np.angle(np.exp(1j * (head + self._h0))))
        z = dz = pause_dz = None
        if self._alt is not None:  # decision E106: W89's altitude at the step's end, as track_waist's z / dz_m
            z = self._alt.at(row["end"])
            if z is not None:
                # decision W158, as track_waist: dz_m from the step's start, pause_dz_m the standstill before it
                zs = self._alt.at(row["t"])
                zs = z if zs is None else zs
                dz, pause_dz, self._z_prev = z - zs, zs - self._z_prev, z
                drop = self._pause_drift(row["t"], pause_dz)
                pause_dz -= drop  # decision E146: W231's ride only; the drift leaves this and every later z
                self._drift += drop
                z -= self._drift
        self._pause_a = row["end"]
        part = dict(t=row["t"], end_s=row["end"], length_m=length, heading_rad=enu, has_next=row["has_next"],
                    merged=merged, turning=turning, side=row["side"], z=z, dz_m=dz, pause_dz_m=pause_dz, stairs=stairs)
        if self._climbs is None:
            return [self._emit(part)]
        # decision E358: the steps of an open run of W91's proposals wait until it is a climb or has ended
        a, b = (None, None) if self._alt is None else (self._alt.at(row["t"]), self._alt.at(row["end"]))
        return [self._emit(q, bound) for q, bound in self._climbs.push(part, int(np.sign(rise)) if stairs else 0, a, b)]

    def _emit(self, part: dict, bound: float | None = None) -> LiveStep:
        """The reported step of ``part`` (its length at most ``bound``, m, E358's climb) on the track: its position,
        fix (D19-D21), lat/lon (W137) and radius (E352), in the order the steps are reported."""
        if bound is not None:
            part = {**part, "length_m": min(part["length_m"], bound)}
        length, enu = part["length_m"], part["heading_rad"]
        self._sx += length * np.cos(enu)
        self._sy += length * np.sin(enu)
        x, y = self._xy0[0] + self._sx, self._xy0[1] + self._sy
        self.position, self.heading = (float(x), float(y)), enu
        fused = self._fuse_step(part["t"], part["end_s"], length, enu)  # decisions D19-D21
        if fused is not None:
            x, y = fused
        lat = lon = None
        if self._ll is not None:  # decision W137: the reported displacement, thesis eq. 56/57
            from pdrlearn.kernels.geodetic import step_destination

            dx, dy = float(x) - self._xy_reported[0], float(y) - self._xy_reported[1]
            self._ll = step_destination(*self._ll, math.hypot(dx, dy), math.atan2(dy, dx))
            lat, lon = math.degrees(self._ll[0]), math.degrees(self._ll[1])
        self._xy_reported = (float(x), float(y))
        sigma = None if fused is not None else self._pos_sigma(part["t"], part["end_s"], length, enu)
        if self._reclip is not None and self._reclip.found:  # decision W623: a re-clip's heading error grows it
            extra = self._reclip.extra_sigma_m(length)
            sigma = None if sigma is None else sigma + extra
        step = LiveStep(**part, x=float(x), y=float(y), lat=lat, lon=lon, pos_sigma_m=sigma)
        self.steps.append(step)
        return step


# -- the waist bundle (decisions E57, E58) --------------------------------------------------------------
#: the waist unit's streams a waist bundle tracks (the AHRS reads both, seed 001 sec. 2.2.1)
WAIST_SENSORS = ("wAccelerometer", "wGyroscope")
#: the parameter fields a waist bundle's params file must hold (``WaistParams``, resolved at export)
PARAM_KEYS = ("leg_m", "k", "f_m", "gyro_bias_rps")


@dataclass(frozen=True)
class WaistBundle:
    """A verified waist-only bundle: ``manifest`` (manifest.json), ``params`` (the resolved waist-pendulum
    parameters: ``leg_m``, ``k``, ``f_m``, ``gyro_bias_rps``, ``turn_gmm``, ``walk_threshold_mps2``, ``rate_hz``,
    ``source``, ``pipeline``, the calibration's ``gait``, its ``detector`` (W471, W483) and its PARAMS.json options
    ``gait_check`` (W141) and ``speed_check`` (E142, true unless set false)), ``options`` (the live pipeline
    options) and ``rotation`` (the sensor -> body FLU matrix of the waist unit, None when the export was given no
    frame)."""

    path: Path
    manifest: dict
    params: SimpleNamespace
    options: dict
    rotation: np.ndarray | None

    @property
    def rate_hz(self) -> float:
        """The rate (Hz) the step length was calibrated at (W87), NaN when not recorded."""
        r = self.manifest["sampling"].get("rate_hz")
        return float(r) if r is not None else math.nan


def defaults_only_line(line: str) -> bool:
    """Decision E368: whether ``line`` is E107's line naming only options at their offline default (``... (the offline
    default)`` each), as a waist bundle exported before E368 holds it among its warnings."""
    import re

    m = re.match(r"the options? (.+?) (?:is|are) not applied by the live waist tracker \(decision E107\)", line)
    if m is None:
        return False
    named = m.group(1)
    return 0 < len(re.findall(r"\b[a-z_]+=", named)) == named.count("(the offline default)")


def load_waist_bundle(path: str | Path, *, verify: bool = True) -> WaistBundle:
    """Open a waist-only bundle (``pdrlearn export CAL.json --out PATH``), checking its schema, version and
    checksums first (as :func:`pdrlearn.runtime.load_bundle`); a foot-unit bundle or another schema version is one
    line (decision E58)."""
    from pdrlearn.runtime.bundle import WAIST_SCHEMA_NAME, _fail, read_manifest, verify_files, version_warning

    path = Path(path)
    m = read_manifest(path, schema=WAIST_SCHEMA_NAME)
    verify_files(path, m, checksums=verify)  # decision E270: the safety checks run whatever verify says
    line = version_warning(path, m)
    if line:  # decision B211: B137's line, for the waist bundle too (it had loaded another version silently)
        log.warning(line)
    rel = m["params"]
    if rel not in m["files"]:
        raise _fail(path, f"manifest.json names params '{rel}', which it does not list; re-export the bundle")
    try:
        p = read_json(path / rel)
    except (OSError, ValueError) as exc:
        raise _fail(path, f"{rel} is not valid JSON ({exc}); re-export the bundle") from None
    bad = [k for k in PARAM_KEYS if not isinstance(p.get(k), int | float) or not math.isfinite(p[k])]
    if bad:
        raise _fail(path, f"{rel} has no finite {', '.join(bad)}; re-export the bundle")
    frame = (m.get("frames") or {}).get("waist_matrix")
    rot = None if frame is None else np.asarray(frame, dtype=float).reshape(3, 3)
    params = SimpleNamespace(**{k: p.get(k) for k in (*PARAM_KEYS, "turn_gmm", "walk_threshold_mps2", "rate_hz",
                                                      "source", "pipeline", "gait",  # gait: W140
                                                      "detector")},  # detector: W471's record (W483)
                             gait_check=bool((p.get("options") or {}).get("gait_check", False)),  # W141
                             speed_check=bool((p.get("options") or {}).get("speed_check", True)))  # W211, E142
    return WaistBundle(path, m, params, dict(m["options"]), rot)


class WaistTracker(WaistStream):
    """Live waist-only tracking from a waist bundle, numpy only (decisions E57, W92-W94; docs/deploying.md).

    ``WaistTracker(load_waist_bundle(PATH), start=(x, y), heading_rad=h)`` then ``push(t, acc, gyr)`` (t (n,) s,
    acc (n, 3) m/s^2 with gravity, gyr (n, 3) rad/s, in the unit's sensor frame) returns the steps that became final
    (:class:`LiveStep`: length, heading, position), ``flush()`` the rest; ``add_fix(t, x, y, sigma_m)`` gives it a
    position fix (decision D19). The steps equal :class:`pdrlearn.waist.WaistTracker` with the calibration file
    the bundle was exported from (one implementation, :class:`WaistStream`).

    Parameters
    ----------
    bundle : a :class:`WaistBundle` (or its folder)
    fs : the pushed samples' rate (Hz); None: the bundle's calibration rate. Another rate than the calibration's
        by more than 10 % warns (decision W87)
    start : ``(x, y)`` or ``(x, y, z)`` (m, ENU; z is not read: a step's ``z`` is the barometric altitude relative
        to the first sample, with :meth:`push_barometer`, E106); heading_rad : the direction set off in (rad, ENU,
        0 = east; W81: a value over 2 pi, degrees, is refused)
    start_latlon : the geodetic start ``(lat, lon)`` / ``(lat, lon, alt)`` / ``"LAT,LON[,ALT]"`` in degrees (alt in
        m), checked as ``pdrlearn run --start`` and :class:`pdrlearn.waist.WaistTracker`'s ``start`` (decisions L157,
        W147): each step then has ``lat``, ``lon`` (W137's eq. 56/57 step; alt kept as :attr:`start_altitude_m`, not
        tracked); None: no lat/lon. A keyword of its own: ``start=(x, y)`` stays ENU metres (as L159's ``Tracker``)
    frame : the unit's axes, ``"x=up,y=right,z=forward"`` (as ``export --frame``) or a 3x3 sensor -> body FLU
        rotation (decision W95: orthonormal; mirrored: warned), when the bundle has none (or to override it)
    keep_steps : how many reported steps :attr:`steps` keeps (None: all)
    check_input : check the units of the first seconds (decision B119: acceleration in g or mg, a gyroscope in
        deg/s is one line) -- False only for data already checked
    sides : give each step its foot (``LiveStep.side``: ``"left"`` / ``"right"`` / ``""`` undecided), W138's causal
        side, as :class:`pdrlearn.waist.WaistTracker` ``(sides=True)`` gives it (decision E103). An option, not the
        default, as there (W138: the simulated foot for 93.3 % of the decided contacts, short of its 97 % rule). Not
        the offline track's ``side`` by construction (W129 reads a zero-phase filter of the whole recording and the
        median over all its contacts; this reads the samples the contact was decided on and the contacts so far):
        on the bundled HA001 Test11 recording the two agree on 79 of the 80 contacts both decide (E103)
    drop_duplicate_timestamps : drop a pushed sample whose timestamp equals the one before it (in the same push or the
        previous push's last), keeping the first, as ``pdrlearn import --drop-duplicate-timestamps`` does for a file
        (decision E203: a phone app repeats samples routinely; the barometer's ``push_barometer`` too, decision
        E349); counted in ``n_dropped_duplicates``, one warning line. Off (the default): such a push is refused
        with one line naming the sample and this option

    uniform_clock : decision E366's option (not adopted: its rule failed at 100 Hz): put the pushed samples on the
        uniform clock ``t0 + k / fs`` as they arrive, as offline ``track`` puts a jittered recording (B33), instead of
        W59's fill of each interval over 1.5 periods; a belt phone's 4 ms stamp jitter at 50 Hz had made the live
        distance +3.5 % long with the default (-0.35 % with the option; docs/decisions/export.md E366); ``"nearest"``
        (E371) / ``"nearest-phase"`` (E372): each pushed sample on its nearest clock instant, values unchanged (options,
        not adopted)

    Attribute ``not_applied_live``: E107's line for the offline-only options the calibration leaves at their offline
    defaults, which the live tracker does without (None: none); logged at DEBUG only (decision E368: nothing to act
    on; an option the calibration sets and the live tracker does not apply is still a warning)
    """

    def __init__(self, bundle, *, fs: float | None = None, start=(0.0, 0.0), heading_rad: float = 0.0,
                 frame=None, keep_steps: int | None = None, check_input: bool = True, start_latlon=None,
                 sides: bool = False, drop_duplicate_timestamps: bool = False, uniform_clock: bool | str = False):
        from pdrlearn.kernels.frames import frame_rotation, mirrored_line
        from pdrlearn.kernels.geodetic import start_coordinate
        from pdrlearn.kernels.waist import rate_mismatch_line

        b = bundle if isinstance(bundle, WaistBundle) else load_waist_bundle(bundle)
        self.bundle = b
        if fs is None:
            fs = b.rate_hz
        if not (isinstance(fs, int | float) and math.isfinite(fs) and fs > 0):
            raise DataError(f"WaistTracker: fs={fs!r} must be the sampling rate in Hz (the bundle {b.path} records "
                            "no calibration rate)")
        rot = frame_rotation(frame, "WaistTracker: frame=") if frame is not None else b.rotation
        if rot is None:
            raise DataError(f"WaistTracker: bundle {b.path} has no waist axis frame; pass frame= (3x3 sensor -> "
                            "body FLU) or re-export with 'pdrlearn export CAL.json --frame x=up,y=right,z=forward'")
        try:
            x0, y0 = float(start[0]), float(start[1])
            h0 = float(heading_rad)
        except (TypeError, ValueError, IndexError):
            raise DataError(f"WaistTracker: start={start!r} must be (x, y) in m and heading_rad a number") from None
        if not abs(h0) <= 2 * math.pi:  # decision W81
            raise DataError(f"WaistTracker: heading_rad={h0!r} is not radians (|value| <= 2 pi); convert degrees "
                            "with math.radians")
        if not isinstance(sides, bool | np.bool_):  # decision E103: a flag (a string "false" would switch it on)
            raise DataError(f"WaistTracker: sides={sides!r} must be True or False")
        try:  # decision W147: L157's one check, as the live tracker's start and run --start
            latlon, self.start_altitude_m = start_coordinate(start_latlon, "start_latlon")
        except DataError as exc:
            raise DataError(f"WaistTracker: {exc}") from None
        warnings = list(b.manifest.get("warnings") or [])
        quiet = b.manifest.get("not_applied_live")  # decision E368 (a bundle exported before it: in its warnings)
        old = [w for w in warnings if defaults_only_line(w)]
        warnings = [w for w in warnings if w not in old]
        quiet = quiet or (old[0] if old else None)
        if b.params.source == "calibrated":  # decision W483: W479's line from the bundle's own record, so that a
            # bundle exported before W479 (no such manifest line) says it too; one exported since holds it once
            line = live_detector_line(b.params.detector)
            if line and line not in warnings:
                warnings.append(line)
        line = mirrored_line(rot, "WaistTracker: frame=" if frame is not None else f"waist bundle {b.path}")
        if line:
            warnings.append(line)
        line = rate_mismatch_line(b.rate_hz if b.params.source == "calibrated" else math.nan, float(fs),
                                  f"waist bundle {b.path}")
        if line:
            warnings.append(line)
        thr = b.params.walk_threshold_mps2
        super().__init__(fs, params=b.params, options=b.options, rotation=rot, start=(x0, y0, h0),
                         warnings=warnings, walk_threshold=thr if thr is not None else b.manifest["walk_threshold"],
                         keep_steps=keep_steps, check_input=check_input, latlon=latlon, sides=bool(sides),
                         drop_duplicate_timestamps=bool(drop_duplicate_timestamps), not_applied_live=quiet,
                         uniform_clock=uniform_clock)
