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
(``merge_fragments=False``: always). State is bounded: the samples since the oldest step still pending, the rows of
the open walking sequence (at most :data:`FRAGMENT_CONTEXT_STEPS`) and the W31 detector's 12 s window.

Decision W65: the axis frame is given (``frame`` or ``meta`` as meta.json would declare it); without one it is
inferred (:func:`pdrlearn.track.frame_inference.infer_waist_frame`, decision D8) from the first samples that fix it
-- tried every :data:`INFER_EVERY_S` seconds of buffered data, at most the last :data:`INFER_MAX_S` seconds
held -- and the track starts at the first held sample (the replay infers it from the whole recording).
"""

from __future__ import annotations

import json
import logging
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from pdrlearn.errors import DataError

log = logging.getLogger(__name__)

#: W64: the fragment test (W27) reads at most this many steps of the open walking sequence (about a minute of
#: walking; the recordings we have walk at most ~40 steps between stops, so it equals the replay's whole sequence)
FRAGMENT_CONTEXT_STEPS = 100
#: W64: a step is reported once this many later contacts of its walking sequence are decided (or it ended)
LOOKAHEAD_ROWS = 2
#: rows before the reported one that its heading window reads: W82's slow-turn window reads 3 strides back, and the
#: window's first step has no step before it for its stride rate (W24), so one more
HEADING_LOOKBACK_ROWS = 4
#: W65: without a declared frame, inference is tried on the held samples every INFER_EVERY_S of new data, from
#: frame_inference.MIN_WALK_S on; at most the last INFER_MAX_S seconds are held meanwhile
INFER_EVERY_S = 2.0
INFER_MAX_S = 120.0


@dataclass(frozen=True)
class LiveStep:
    """One reported contact, as a row of ``track_waist(...).steps`` with its trajectory point.

    ``t`` the initial contact (s, the pushed clock); ``end_s`` the next contact of the walking sequence
    (``== t`` for a contact that closes one: ``length_m`` 0); ``length_m`` (m) and ``heading_rad`` (ENU, rad,
    start heading added) of the step; ``x``, ``y`` (m) the position at ``end_s``; ``side`` is ``None`` (the
    detector's left/right guess, W20, is internal); ``merged``: a W27 fragment whose length its neighbour carries;
    ``turning``: the stride's straight (0) / turning (1) class (seed 003 sec. 3.3)."""

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
    if isinstance(frame, dict):
        f = AxisFrame.from_dict(frame)
        return f.matrix(), f, "given as frame="
    if isinstance(frame, str):
        try:
            d = dict(part.split("=") for part in frame.replace(" ", "").split(","))
        except ValueError:
            raise DataError(f"frame {frame!r}: write it as 'x=up,y=right,z=forward' (each sensor axis = a body "
                            "direction)") from None
        f = AxisFrame.from_dict(d)
        return f.matrix(), f, "given as frame="
    r = np.asarray(frame, dtype=float)
    if r.shape != (3, 3) or not np.all(np.isfinite(r)) or abs(abs(np.linalg.det(r)) - 1.0) > 1e-6:
        raise DataError(f"frame: a 3x3 rotation (sensor -> body forward/left/up) was expected, got shape {r.shape}; "
                        "or pass {'x': 'up', 'y': 'right', 'z': 'forward'}")
    return r, None, "given as frame="


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


class WaistTracker:
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
    start : ``{"x": m, "y": m, "heading_rad": rad}`` (ENU) or None (origin); ``(lat, lon)`` is not supported live
    initial_heading : the direction the walker sets off in, radians ENU (counter-clockwise from east; 0 = east, the
        default); a magnitude above 2 pi (degrees, as the CLI's ``--initial-heading``) is refused (decision W81)
    integrate_stops, turn_factor, rhythm, merge_fragments, slow_turn_rps : as :func:`pdrlearn.track.waist.
        track_waist` (None: ``params.options``, else its defaults)
    keep_steps : how many reported steps :attr:`steps` keeps (None: all)

    Attributes
    ----------
    position : (x, y) m after the last reported step; heading : its heading (rad, ENU); steps : reported
    :class:`LiveStep` s; warnings : what ``track`` would warn about (defaults, gaps, an inferred frame);
    params : the resolved :class:`~pdrlearn.waist.params.WaistParams`; options : the resolved options
    """

    def __init__(self, fs: float, *, params=None, meta: dict | None = None, sensor_height_m: float | None = None,
                 height_m: float | None = None, frame=None, start=None, initial_heading: float | None = None,
                 integrate_stops: bool | None = None, turn_factor: bool | None = None, rhythm: bool | None = None,
                 merge_fragments: bool | None = None, slow_turn_rps: float | None = None,
                 keep_steps: int | None = None):
        from collections import deque

        from pdrlearn.io.session import Session
        from pdrlearn.track.waist import MAX_STEP_S, _start, resolve_options
        from pdrlearn.waist.events import WALK_THRESHOLD_MPS2
        from pdrlearn.waist.heading import TurnClassifier
        from pdrlearn.waist.params import resolve_params

        if not (isinstance(fs, int | float) and np.isfinite(fs) and fs > 0):
            raise DataError(f"WaistTracker: fs={fs!r} must be the sampling rate in Hz (a positive number)")
        self.fs = float(fs)
        meta = dict(meta or {})
        sub = dict(meta.get("subject") or {})
        for key, v in (("sensor_height_m", sensor_height_m), ("height_m", height_m)):
            if v is not None:
                sub[key] = float(v)
        meta["subject"] = sub
        self.params, warnings = resolve_params(Session(name="live", meta=meta), params)
        p = self.params
        given = {"realtime": True, "heading": "gyro", "refine_ic": None, "initial_heading": initial_heading,
                 "resolve_signs": None, "integrate_stops": integrate_stops, "turn_factor": turn_factor,
                 "rhythm": rhythm, "merge_fragments": merge_fragments, "length_smoothing": None,
                 "slow_turn_rps": slow_turn_rps}
        o = resolve_options(p, given)
        if o["length_smoothing"] != "none":
            raise DataError(f"length_smoothing '{o['length_smoothing']}' looks up to 1 s ahead and the live tracker "
                            "does not (decision W56); set the PARAMS.json option length_smoothing to none")
        if p.source == "calibrated" and p.pipeline not in (None, "waist-pendulum"):
            warnings.append(f"the parameters were calibrated for {p.pipeline}: the waist-pendulum step length "
                            "keeps its defaults (run 'pdrlearn calibrate --pipeline waist-pendulum')")
        asked = (p.options or {}).get("heading")
        if asked not in (None, "gyro"):  # decision W82: no silent override of the PARAMS.json heading
            warnings.append(f"the PARAMS.json option heading '{asked}' is not available live: the live tracker uses "
                            "the gyro heading, which drops gentle curves unless the option slow_turn_rps is set "
                            "(0.035, decision W82)")
        self.options = o
        if isinstance(start, list | tuple):
            raise DataError("WaistTracker: start=(lat, lon) is not supported live; pass {'x': m, 'y': m, "
                            "'heading_rad': rad} and convert the positions yourself")
        x0, y0, self._h0, _ = _start(start, float(o["initial_heading"]))
        self._xy0 = (x0, y0)
        self._sx = self._sy = 0.0  # running sums of the displacements (as track_waist's cumsum)
        self.position = (x0, y0)
        self.heading = float(self._h0)
        self.warnings: list[str] = list(warnings)
        for w in warnings:
            log.warning("live waist tracker: %s", w)
        self.steps: deque[LiveStep] = deque(maxlen=keep_steps)
        self._thr = p.walk_threshold_mps2 if p.walk_threshold_mps2 is not None else WALK_THRESHOLD_MPS2
        self._max_step_s = MAX_STEP_S
        self._clf = TurnClassifier(**(p.turn_gmm or {}))
        self._rot, self._declared, self._declared_origin = _declared_frame(frame, meta)
        self._chk = _HeldSamples(trim=False)  # B108: raw samples held until the declared frame is checked
        self._proc = None
        self._held = _HeldSamples(trim=True)  # W65: raw samples held until the frame is inferred
        self._last_t = -np.inf
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
        self._seen_seq = False
        self._n_gaps = 0
        self._cum_first: float | None = None  # running integral at the first contact (W74)
        self._untracked_warned = False

    def state_size(self) -> int:
        """Numbers the tracker holds to process what comes (not :attr:`steps`): its sample buffer and pending rows,
        the held samples of W65 and the W31 detector's window; bounded over any stream length (decision W64)."""
        n = 4 * self._bt.size + 5 * len(self._rows) + len(self._absorbed) + len(self._span_start)
        n += self._held.size() + self._chk.size()
        p = self._proc
        if p is not None:
            n += sum(np.size(v) for v in p.buf.values()) + 3 * len(p.decided) + sum(np.size(r[1]) for r in p.raw)
            n += p.bridge.tail_v.size + p.bridge.tail_t.size + 2 * sum(len(g) for g in p.gaps.values())
        return int(n)

    # -- input -------------------------------------------------------------------------------------------
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
            raise DataError(f"WaistTracker.push: expected acc and gyr of shape ({t.size}, 3) for {t.size} "
                            f"timestamps, got {acc.shape} and {gyr.shape}")
        if not t.size:
            return []
        if not (np.isfinite(t).all() and np.isfinite(acc).all() and np.isfinite(gyr).all()):
            raise DataError("WaistTracker.push: NaN or inf in the pushed samples; drop those samples")
        if t[0] <= self._last_t or (t.size > 1 and np.any(np.diff(t) <= 0)):
            raise DataError("WaistTracker.push: timestamps must increase strictly across pushes (seconds)")
        if self._dts is not None:
            self._unit_check(t)
        self._last_t = float(t[-1])
        v = np.column_stack([acc, gyr])
        if self._declared is not None:
            self._check_declared(t, v)
        if self._proc is None:
            v_t = self._hold(t, v)
            if v_t is None:
                return []
            t, v = v_t
        return self._feed(self._proc.process(t, v), final=False)

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
        check_rate_unit("WaistTracker.push", 1.0 / float(np.median(dts[:RATE_PROBE_MIN])), self.fs, "fs=")
        self._dts = None  # judged once

    def flush(self) -> list[LiveStep]:
        """End of the stream: decide the last contacts and report every step left."""
        if self._proc is None:
            if self._held.t:
                tt = np.concatenate(self._held.t)
                msg = (f"no walking to track: no axis frame given and the {tt[-1] - tt[0]:.0f} s pushed do not fix "
                       "one (decision W65): 0 steps, 0 m; pass frame= if the unit did walk")
                self.warnings.append(msg)
                log.warning("live waist tracker: %s", msg)
                self._held.clear()
            return []
        return self._feed(self._proc.flush(), final=True)

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

    def _start_proc(self) -> None:
        if self._proc is not None:
            return
        from pdrlearn.steps.waist_ic import WaistICStepDetector, _RealtimeProcessor
        from pdrlearn.waist._kernels import DECISION_DELAY_S

        tracker = self

        class _Proc(_RealtimeProcessor):
            def _nav(self, t, acc, gyr, first):  # the navigation-frame samples, as they are made
                super()._nav(t, acc, gyr, first)
                m = len(t)
                tracker._add(self.buf["t"][-m:], self.buf["acc_v"][-m:], self.buf["gyr_nav"][-m:, 2])

        det = WaistICStepDetector(walk_threshold=self._thr, max_step_s=self._max_step_s,
                                  rhythm=bool(self.options["rhythm"]), delay_s=DECISION_DELAY_S)
        self._proc = _Proc(det, self.fs, rotation=self._rot)

    # -- the navigation-frame samples -------------------------------------------------------------------
    def _add(self, t: np.ndarray, acc_v: np.ndarray, w_z: np.ndarray) -> None:
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

    def _idx(self, ts: float) -> int:
        """Buffer index of the sample at time ``ts`` (a contact is a sample)."""
        i = min(int(np.searchsorted(self._bt, ts - 0.25 / self.fs)), self._bt.size - 1)
        if not abs(self._bt[i] - ts) < 0.5 / self.fs:  # an internal error, not the caller's: say so
            raise RuntimeError(f"WaistTracker: the sample at {ts:.3f} s left the buffer "
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
            self._b0 += drop

    # -- contacts -> steps ------------------------------------------------------------------------------
    def _feed(self, contacts: list, *, final: bool) -> list[LiveStep]:
        for ev, _start_s, end, _conf, extra in contacts:
            k = self._n_rows
            prev = self._rows.get(k - 1)
            seq = k if prev is None or not prev["has_next"] else prev["seq"]
            self._rows[k] = {"t": float(ev), "end": float(end), "has_next": bool(end > ev), "seq": seq,
                             "fc": float(extra.get("fc_s", np.nan))}
            self._n_rows += 1
        if self._proc is not None and len(self._proc.gaps.get("online stream", ())) > self._n_gaps:
            self._gap_warnings()
        out = []
        while self._next < self._n_rows and self._ready(self._next, final):
            out.append(self._report(self._next))
            self._next += 1
            old = self._next - LOOKAHEAD_ROWS - FRAGMENT_CONTEXT_STEPS - 1
            if old in self._rows:
                del self._rows[old]
        if self._proc is not None:
            self._trim()
        return out

    def _gap_warnings(self) -> None:
        from pdrlearn.track.gaps import gap_warnings

        gaps = self._proc.gaps.get("online stream", [])
        new = gaps[self._n_gaps:]
        self._n_gaps = len(gaps)
        for w in gap_warnings({"wAccelerometer, wGyroscope": new}):
            self.warnings.append(w)
            log.warning("live waist tracker: %s", w)

    def _check_untracked(self, row: dict, h: float) -> None:
        """Decision W74, as ``track_waist``: one warning when a step's heading ``h`` (rad, before the start rotation)
        misses :data:`pdrlearn.waist.heading.UNTRACKED_TURN_WARN_DEG` of the yaw turned since the first contact."""
        from pdrlearn.waist.heading import UNTRACKED_TURN_WARN_DEG, turn_gap, untracked_turn_message

        if self._untracked_warned or self._cum_first is None:
            return
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
        hz = self._horizon(k)
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

    def _report(self, k: int) -> LiveStep:
        from pdrlearn.waist import _kernels as K
        from pdrlearn.waist.heading import gyro_headings
        from pdrlearn.waist.steplength import fragment_windows

        p, o = self.params, self.options
        row = self._rows[k]
        s = row["seq"]
        if self._cum_first is None:
            self._cum_first = float(np.interp(row["t"], self._bt, self._bc))
        if k == s:  # a walking sequence starts: track_waist's ``current`` (and the turn made standing, W: opt)
            if self._seen_seq and o["integrate_stops"] and self._stop_cum is not None:
                self._cur_gyro += float(np.interp(row["t"], self._bt, self._bc)) - self._stop_cum
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
            hd, tr = gyro_headings(win, np.asarray(ev), classifier=self._clf, bias_rps=p.gyro_bias_rps,
                                   heading0=0.0, cum=self._bc[i0:i1], slow_turn_rps=float(o["slow_turn_rps"] or 0.0))
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
                wins = fragment_windows(np.array([self._rows[j]["t"] for j in rel]),
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
                if o["turn_factor"]:
                    length *= float(K.turning_step_factor(np.array([dyaw]))[0])
            head = h
            self._check_untracked(row, h)
        else:  # a contact closing its sequence: no displacement, the sequence's last heading
            head = self._h_seq if self._h_seq is not None else self._cur_out
            if self._h_seq is not None:
                self._cur_gyro = self._cur_out = self._h_seq
            self._stop_cum = float(np.interp(row["t"], self._bt, self._bc))
        enu = float(np.angle(np.exp(1j * (head + self._h0))))
        self._sx += length * np.cos(enu)
        self._sy += length * np.sin(enu)
        x, y = self._xy0[0] + self._sx, self._xy0[1] + self._sy
        self.position, self.heading = (float(x), float(y)), enu
        step = LiveStep(t=row["t"], end_s=row["end"], length_m=length, heading_rad=enu, x=float(x), y=float(y),
                        has_next=row["has_next"], merged=merged, turning=turning)
        self.steps.append(step)
        return step


__all__ = ["WaistTracker", "LiveStep", "FRAGMENT_CONTEXT_STEPS", "LOOKAHEAD_ROWS"]
