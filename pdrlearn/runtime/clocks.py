"""The live two-unit clock check (decision L177): L161's estimate of the foot-to-waist clock offset, as ``pdrlearn
track`` and ``pdrlearn run`` (L170) compute it on a recording, from the samples pushed to a
:class:`~pdrlearn.runtime.Tracker`, numpy only.

The same detectors (the foot accelerometer detector, thesis ch.5.1, or with both force sensors the accelerometer +
force detector, ch.5.2; the waist PLL, seed 000 Sec. II-C) run on the pushed samples through their shared online
processors (:mod:`pdrlearn.kernels.step_events`, with the numpy low-pass), and the same estimate
(:func:`pdrlearn.kernels.align.align_events`) reads their events: at every :data:`CHECK_EVERY_STRIDES`-th foot
stride on the events so far and at ``flush`` on all of them, where it is the offline check's on the same samples.
Decision E120: "the events so far" are the last :data:`WINDOW_FOOT_EVENTS` foot events (and the waist events from
:data:`WINDOW_PAD_S` before the first of them, at most :data:`WINDOW_WAIST_EVENTS`): up to that many the estimate is
the one over every event, as before; a longer stream reads the offset over its last window (``ref_s`` inside it,
L198), so the work per check and the state stay bounded however long the stream runs.
Differences from the offline check, by construction: the detectors' rate is the median interval of a stream's
first :data:`RATE_PROBE_SAMPLES` samples (offline: of the whole recording; equal for regular sampling), the PLL
keeps its adult range (offline, W117 reads the whole recording's rhythm and widens it above 2.4 steps/s), and the
force sensors are used when both were pushed by the push that brought the foot accelerometer's first
:data:`RATE_PROBE_SAMPLES` samples.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.align import (
    UNIT_OFFSET_WARN_S,
    align_events,
    offset_locked,
    to_foot_clock,
    unit_offset_message,
)
from pdrlearn.kernels.contact import (
    EVENT_CUTOFF_HZ,
    FAST_EVENT_CUTOFF_HZ,
    FAST_PERIOD_S,
    FORCE_AMP,
    FORCE_MIN_SWING_S,
    FORCE_OFF_FRAC,
    FORCE_ON_FRAC,
    FORCE_REF_STANCES,
    IMPACT_CLUSTER_S,
    PEAK_FRAC,
    PEAK_PROMINENCE,
    SHORT_MAX_AMP,
    SHORT_MIN_RATE_HZ,
    SHORT_PERIOD_S,
)
from pdrlearn.kernels.step_events import MIN_STRIDE_S, AccelProcessor, ForceProcessor, PLLProcessor
from pdrlearn.kernels.waist import PLL_F0_HZ

#: the default settings of ``pdrlearn.steps``' AccelStepDetector, AccelForceStepDetector and PLLStepDetector,
#: which ``align_units`` runs (thesis ch.5.1 / 5.2, seeds 000/001; steps decisions 6, 14, 16, 18, 37, W117;
#: ``tests/test_runtime_clocks.py`` pins them to the detectors' own defaults)
ACCEL = {"cutoff_hz": 3.0, "order": 3, "threshold": 1.7, "still_window_s": 0.08, "still_std": 0.6,
         "still_level_tol": 1.2, "min_quiet_s": 0.1, "max_quiet_s": 0.2, "quiet_frac": 0.5, "quiet_rank": 2,
         "rests_only": True, "min_swing_s": 0.2, "max_swing_s": 2.5, "min_stride_s": MIN_STRIDE_S,
         "peak_frac": PEAK_FRAC, "peak_prominence": PEAK_PROMINENCE, "event_cutoff_hz": EVENT_CUTOFF_HZ,
         "gravity": 9.80665, "subsample": None,  # steps decision 89: peak_prominence
         "short_period_s": SHORT_PERIOD_S, "fast_period_s": FAST_PERIOD_S,  # steps decisions 87, 88
         "fast_event_cutoff_hz": FAST_EVENT_CUTOFF_HZ, "impact_cluster_s": IMPACT_CLUSTER_S,  # steps decision 91
         "short_min_rate_hz": SHORT_MIN_RATE_HZ, "short_max_amp": SHORT_MAX_AMP,  # steps decisions 93, 94
         "event_power": False}  # steps decision 97 (an option, not adopted)
FORCE = {"cutoff_hz": 3.0, "order": 3, "threshold": FORCE_AMP, "force_on_frac": FORCE_ON_FRAC,
         "force_off_frac": FORCE_OFF_FRAC, "min_swing_s": FORCE_MIN_SWING_S, "subsample": None,
         "ref_stances": FORCE_REF_STANCES, "confirm": True}  # steps decision 54
PLL = {"f0_hz": PLL_F0_HZ, "loop_hz": 0.5, "damping": 0.707, "f_min_hz": 0.8, "f_max_hz": None, "cutoff_hz": 5.0,
       "agc_tau_s": 1.0, "gravity_cutoff_hz": 0.3, "gate_window_s": 2.0, "gate_var": 0.25, "refine_frac": 0.25,
       "placement": "waist", "relative_gate": None,  # steps 48/49: offline detect's only; a stream keeps gate_var
       "edge_lock": False,  # W356: the detector's default
       "slow_band": True}  # W475: offline detect's only (the session's pelvic-gyro rhythm); a stream keeps W117's
#: a stream's detector rate is the median interval of its first this many samples (offline: of the whole stream)
RATE_PROBE_SAMPLES = 64
#: decision L177 (L170's sketch): the offset is estimated again every this many foot strides (about 30 s of walking
#: at the first, enough for L161's median offset) and at ``flush``
CHECK_EVERY_STRIDES = 20
#: decision E120: the estimate reads at most this many foot events, the latest (about 4.8 min of walking at a 1.1 s
#: stride; L177's and L198's measured sessions fit in it, so their estimates are unchanged); one estimate then costs
#: at most ~8 ms (``align_events``' grid of 801 offsets x 256 events) instead of growing with the stream
WINDOW_FOOT_EVENTS = 256
#: ... and the waist events from this long before the first kept foot event (s): ``align_events``' largest offset
#: (2 s) plus its tolerance (0.12 s) and a margin for the drift term, so no match inside the window is lost ...
WINDOW_PAD_S = 3.0
#: ... at most this many, the latest (the waist sees both feet: about 2 per foot stride; a waist walking while the
#: foot unit detects nothing cannot grow the list)
WINDOW_WAIST_EVENTS = 4 * WINDOW_FOOT_EVENTS
#: decision E229: after its line the check goes on estimating and warns again when the estimate has moved this far (s)
#: from the offset it last warned of (a drifting clock, T4's 150 ppm hour: 0.1 s in about 11 min); a priori: half
#: L161's 0.2 s threshold, a quarter of the slowest validated walk's 0.43 s step period (L95)
REWARN_MOVE_S = 0.1
#: decision E244: a followed estimate whose nearest candidate (a whole number of step periods from L161's) still lies
#: more than this fraction of the step period from the offset predicted is not followed (a priori: halfway between
#: the prediction and the half period at which a candidate of the other branch is nearer)
LOST_FRACTION = 0.25
#: decision E258: the drift (ppm) up to which the live check keeps its lock (simulated 400 m walks, every check locked)
FOLLOWED_PPM = 3000.0
#: decision E271: a lock lost after a locked estimate is said once when the offsets moved at more than this drift
#: (ppm) since the first locked estimate followed; a priori half :data:`FOLLOWED_PPM` (the unlocked estimate lags the
#: clock; below it, before E258, the lock held: a lost lock there is a rest or a window of few steps, E244's matter)
DRIFT_LOST_PPM = FOLLOWED_PPM / 2
#: samples of a stream held before they are run through its detector (one call per block, not per sample)
BLOCK_SAMPLES = 64
FORCE_SENSORS = ("fForceA", "fForceB")
SENSORS = ("fAccelerometer", *FORCE_SENSORS, "wAccelerometer")


class _Held:
    """Pushed samples of one stream not yet run through its detector."""

    def __init__(self):
        self.t: list[np.ndarray] = []
        self.v: list[np.ndarray] = []
        self.n = 0

    def add(self, t: np.ndarray, v: np.ndarray) -> None:
        self.t.append(np.asarray(t, dtype=np.float64).reshape(-1))
        self.v.append(np.asarray(v, dtype=np.float64).reshape(len(self.t[-1]), -1))
        self.n += len(self.t[-1])

    def take(self) -> tuple[np.ndarray, np.ndarray]:
        t, v = np.concatenate(self.t), np.concatenate(self.v)
        self.t, self.v, self.n = [], [], 0
        return t, v


class ClockCheck:
    """L161's clock offset of the foot and waist units from pushed samples (decision L177).

    ``feed(name, t, values)`` with the raw pushed samples of ``fAccelerometer``, ``fForceA``, ``fForceB`` and
    ``wAccelerometer`` (others ignored), then ``check()`` once per push: it runs the foot detector and returns L161's
    warning line the first time the estimate is over :data:`UNIT_OFFSET_WARN_S`, and again each time a later one over
    it has moved more than :data:`REWARN_MOVE_S` from the last warned offset (decision E229; None otherwise;
    ``final=True`` at the end of the stream: all events of the window, as the offline check up to it).
    :attr:`estimate` is ``align_events``' last dict (``offset_s``, ``drift``, ``matched``, ...), or None before there
    are 3 events of each unit; it is renewed every :data:`CHECK_EVERY_STRIDES` foot strides, after a line too (E229),
    and once one has locked its ``offset_s`` is followed across step periods (decision E244, :meth:`_follow`).
    ``remedy``: the fix the line names, a callable of an offset (E228: the estimate's and its twin's). State: the
    detectors' (bounded) and the
    event times of the window (decision E120: at most :data:`WINDOW_FOOT_EVENTS` foot and
    :data:`WINDOW_WAIST_EVENTS` waist events, plus those of one push)."""

    def __init__(self, remedy=None):
        self.remedy = remedy
        self._held = {n: _Held() for n in SENSORS}
        self._force_t: dict[str, np.ndarray] = {}
        self._force_v: dict[str, np.ndarray] = {}
        self._foot = self._waist = None
        self._with_force: bool | None = None
        self._foot_events: list[float] = []
        self._waist_events: list[float] = []
        self._foot_seen = 0  # foot events detected so far (the window keeps the latest, E120)
        self._checked_at = 0
        self._windowed = False  # the foot window was full once: the waist events before it are dropped too
        self.estimate: dict | None = None
        self.warned = False
        self.warned_offset: float | None = None  # decision E229: the offset of the last line
        self._followed: tuple[float, float, float] | None = None  # decision E244: (offset, drift, ref_s) followed
        self._chain: tuple[float, float] | None = None  # decision E271: (offset, ref_s) of the first locked followed
        self.drift_said = False  # decision E271: the lost drift is said once

    def feed(self, name: str, t, v) -> None:
        held = self._held.get(name)
        if held is None:
            return
        held.add(t, v)
        if name == "wAccelerometer" and held.n >= BLOCK_SAMPLES:
            self._run_waist(held.take())

    def check(self, final: bool = False) -> str | None:
        """The warning line when a new estimate (every CHECK_EVERY_STRIDES foot strides, and at the end) is over the
        threshold: the first time, then when it has moved over REWARN_MOVE_S from the last line's (decision E229)."""
        if final:
            for name in ("wAccelerometer",):
                if self._held[name].n:
                    self._run_waist(self._held[name].take(), final=True)
                elif self._waist is not None:
                    self._waist_events += [e[0] for e in self._waist.flush()]
            self._run_foot(final=True)
        else:  # the foot samples after the whole push was fed (its force samples too: the detector is chosen once)
            self._run_foot(final=False)  # after the line too: the held samples stay one block (the state bounded)
            self._trim()
            if self._foot_seen < self._checked_at + CHECK_EVERY_STRIDES:  # E229: after a line too
                return None
        if final:
            self._trim()
        self._checked_at = self._foot_seen
        try:
            self.estimate = self._estimate()
        except DataError:  # fewer than 3 events of a unit: no estimate yet
            return None
        lost = self._follow(self.estimate)  # decision E244
        lost = self._drift_lost(self.estimate) or lost  # decision E271 (an estimate that did not lock: lost is None)
        off = self.estimate["offset_s"]
        line = unit_offset_message(off, self.estimate["drift"], remedy=self.remedy, estimate=self.estimate)  # L183
        if line is None or (self.warned_offset is not None and abs(off - self.warned_offset) <= REWARN_MOVE_S):
            return lost
        k = self.estimate.get("periods_followed", 0)
        if k:
            line += (f" [followed across {k:+d} step period(s) from the previous estimates: the steps alone read "
                     f"{self.estimate['raw_offset_s']:+.2f} s, the candidate closest to 0 (decision E244)]")
        self.warned, self.warned_offset = True, off
        return line if lost is None else f"{lost}; {line}"

    def _drift_lost(self, est: dict) -> str | None:
        """Decision E271: the one line when ``est`` did not lock (L183) after a locked estimate the check follows and
        the offsets moved at more than :data:`DRIFT_LOST_PPM` since the first locked one of the chain (``est``'s
        offset moved by whole step periods to the one nearest the followed prediction, as E244 reads it): a waist
        clock drifting beyond what the check follows (E258), after which it goes quiet. None otherwise."""
        fol, chain = self._followed, self._chain
        if self.drift_said or fol is None or chain is None or offset_locked(est):
            return None
        ref, x, period = float(est["ref_s"]), float(est["offset_s"]), float(est.get("step_period_s", math.nan))
        if not ref - chain[1] > 0:
            return None
        p = fol[0] + fol[1] * (ref - fol[2])
        if math.isfinite(period) and period > 0:
            x += round((p - x) / period) * period
        ppm = (x - chain[0]) / (ref - chain[1]) * 1e6
        if not abs(ppm) > DRIFT_LOST_PPM:
            return None
        self.drift_said = True
        return (f"the live clock check lost its lock on the waist clock: the waist's steps read {x:+.3f} s from "
                f"the foot's at {ref:.0f} s where it locked on {chain[0]:+.3f} s at {chain[1]:.0f} s, a drift of "
                f"{ppm:+.0f} ppm, beyond the {FOLLOWED_PPM:.0f} ppm it follows (decision E258); until it locks again "
                f"it says nothing of this clock: give the drift, Tracker(..., waist_clock_drift_ppm={ppm:.0f}) (added "
                "to any drift already given; `pdrlearn run --clock-drift-ppm`), or align the recording offline "
                "(`pdrlearn track --align-units`) (decision E271)")

    def _estimate(self) -> dict:
        """``align_events`` on the window's events; decision E258: once a locked estimate with a fitted drift ``d``
        (at ``ref_s`` r) is followed, on the foot events moved by it, ``t + d (t - r)``, and the result read back on
        the foot clock (:func:`_with_drift`)."""
        fol = self._followed
        if fol is None or not fol[1]:
            return align_events(self._foot_events, self._waist_events)
        _, d, r = fol
        f = np.asarray(self._foot_events, dtype=float)
        return _with_drift(align_events(f + d * (f - r), self._waist_events), d, r)

    def _follow(self, est: dict) -> str | None:
        """Decision E244: ``est`` (``align_events``' dict) moved by whole step periods to the candidate nearest the
        offset the previous locked estimates predict (their offset and drift), so a clock that drifts past half a step
        period is followed, not read as its twin; ``raw_offset_s`` keeps L161's candidate, ``periods_followed`` the
        periods moved. The line saying it lost the followed offset (and follows again from L161's), else None."""
        x, period = float(est["offset_s"]), float(est.get("step_period_s", math.nan))
        est["raw_offset_s"], est["periods_followed"] = x, 0
        if not offset_locked(est):  # L183: an estimate that did not lock tells no offset to follow
            return None
        prev, self._followed = self._followed, None
        lost = None
        if prev is not None:
            p = prev[0] + prev[1] * (float(est["ref_s"]) - prev[2])
            k = round((p - x) / period) if math.isfinite(period) and period > 0 else 0
            if math.isfinite(period) and period > 0 and abs(x + k * period - p) <= LOST_FRACTION * period:
                est["offset_s"] = x + k * period
                est["periods_followed"] = int(k)
            else:
                near = "no step period" if not math.isfinite(period) else f"nor a {period:.2f} s step period from it"
                lost = (f"the live clock check lost the waist clock's offset it followed: it read {x:+.2f} s "
                        f"({near}) where {p:+.2f} s was expected from the previous estimates (a long rest, or a "
                        "window of few steps); it follows again from this estimate, the candidate closest to 0; a "
                        "waist clock that drifts: give Tracker(..., waist_clock_drift_ppm=) the drift its lines"
                        " measure (decision E244)")
        self._followed = (float(est["offset_s"]), float(est["drift"]), float(est["ref_s"]))
        if prev is None or lost is not None:  # decision E271: a chain of followed estimates starts here
            self._chain = (self._followed[0], self._followed[2])
        return lost

    def _trim(self) -> None:
        """Decision E120: keep the last WINDOW_FOOT_EVENTS foot events and, once that window was full, the waist
        events from WINDOW_PAD_S before its first one; at most WINDOW_WAIST_EVENTS waist events in any case."""
        foot, waist = self._foot_events, self._waist_events
        if len(foot) > WINDOW_FOOT_EVENTS:
            del foot[:len(foot) - WINDOW_FOOT_EVENTS]
            self._windowed = True
        if self._windowed and foot and waist and waist[0] < foot[0] - WINDOW_PAD_S:
            k = int(np.searchsorted(np.asarray(waist), foot[0] - WINDOW_PAD_S, side="left"))
            del waist[:k]
        if len(waist) > WINDOW_WAIST_EVENTS:
            del waist[:len(waist) - WINDOW_WAIST_EVENTS]

    def _add_foot(self, events) -> None:
        times = [e[0] for e in events]
        self._foot_events += times
        self._foot_seen += len(times)

    # -- the detectors --------------------------------------------------------------------------------------
    @staticmethod
    def _rate(t: np.ndarray) -> float:
        return 1.0 / float(np.median(np.diff(t[:RATE_PROBE_SAMPLES])))

    def _run_waist(self, tv: tuple[np.ndarray, np.ndarray], final: bool = False) -> None:
        t, v = tv
        if self._waist is None:
            if t.size < 2:
                if not final:  # too few to read a rate: held for the next push
                    self._held["wAccelerometer"].add(t, v)
                return
            self._waist = PLLProcessor(SimpleNamespace(**PLL), self._rate(t))
        self._waist_events += [e[0] for e in self._waist.process(t, v)]
        if final:
            self._waist_events += [e[0] for e in self._waist.flush()]

    def _run_foot(self, final: bool) -> None:
        acc = self._held["fAccelerometer"]
        if self._foot is None:
            if acc.n < min(RATE_PROBE_SAMPLES, BLOCK_SAMPLES) and not final:
                return
            if acc.n < 2:
                return
            self._with_force = all(self._held[n].n or n in self._force_t for n in FORCE_SENSORS)
        if acc.n < BLOCK_SAMPLES and not final:
            return
        for n in FORCE_SENSORS:  # the force samples so far, held as one array (np.interp reads them at acc times)
            h = self._held[n]
            if h.n:
                t, v = h.take()
                self._force_t[n] = np.concatenate([self._force_t[n], t]) if n in self._force_t else t
                self._force_v[n] = np.concatenate([self._force_v[n], v[:, 0]]) if n in self._force_v else v[:, 0]
        t, v = acc.take() if acc.n else (np.zeros(0), np.zeros((0, 3)))
        if self._with_force and t.size:
            if not final:  # acc samples past the forces' last one wait for them (interpolated as offline)
                cut = min(float(self._force_t[n][-1]) for n in FORCE_SENSORS)
                k = int(np.searchsorted(t, cut, side="right"))
                if k < t.size:
                    self._held["fAccelerometer"].add(t[k:], v[k:])
                t, v = t[:k], v[:k]
            f = [np.interp(t, self._force_t[n], self._force_v[n]) for n in FORCE_SENSORS]
            v = np.column_stack([v[:, :3], *f])
            for n in FORCE_SENSORS:  # keep the force samples from the last one at or before the last acc time
                if t.size:
                    j = max(int(np.searchsorted(self._force_t[n], t[-1], side="right")) - 1, 0)
                    self._force_t[n], self._force_v[n] = self._force_t[n][j:], self._force_v[n][j:]
        if self._foot is None and t.size >= 2:
            det = ForceProcessor(SimpleNamespace(**FORCE), self._rate(t)) if self._with_force else \
                AccelProcessor(SimpleNamespace(**ACCEL), self._rate(t))
            self._foot = det
        if self._foot is None:
            return
        if t.size:
            self._add_foot(self._foot.process(t, v))
        if final:
            self._add_foot(self._foot.flush())


def _with_drift(est: dict, d: float, r: float) -> dict:
    """Decision E258: ``align_events``' ``est`` on foot events moved by ``t + d (t - r)`` read on the foot clock. Its
    line ``w - f' = o' + d' (f' - r')`` is, with ``f' - r' = (1 + d)(f - r'')`` and ``r'' = r + (r' - r) / (1 + d)``
    (the matched foot events' mean on the foot clock), ``w - f = o' + d (r'' - r) + (d + d' (1 + d)) (f - r'')``."""
    o, d2, r2 = float(est["offset_s"]), float(est["drift"]), float(est["ref_s"])
    ref = r + (r2 - r) / (1.0 + d)
    drift = d + d2 * (1.0 + d)
    out = dict(est, offset_s=o + d * (ref - r), drift=drift, ref_s=ref)
    if est.get("drift_span_s"):  # L457: how far the whole drift moves the clock over the matched events
        out["drift_span_s"] = abs(drift) * float(est["drift_span_s"]) / abs(d2) / (1.0 + d) if d2 else 0.0
    if est.get("window_line") is not None:
        wo, wd, wr = est["window_line"]
        wref = r + (wr - r) / (1.0 + d)
        out["window_line"] = [wo + d * (wref - r), d + wd * (1.0 + d), wref]
    return out


def replay_check(streams: dict, chunk_s: float = 1.0) -> ClockCheck:
    """The live check on a recording's ``{sensor: (t, values)}`` replayed in ``chunk_s`` pushes (E28's cut), fed as
    :class:`~pdrlearn.runtime.Tracker` feeds it, then ``check(final=True)``: for measurements and tests of the check
    alone (decision E120)."""
    from pdrlearn.runtime.replay import replay_chunks

    cc = ClockCheck()
    for push in replay_chunks({n: streams[n] for n in SENSORS if n in streams}, chunk_s):
        for n, (t, v) in push.items():
            if len(t):
                cc.feed(n, t, v)
        cc.check()
    cc.check(final=True)
    return cc


def waist_on_foot_clock(samples: dict, offset_s: float, drift: float = 0.0, prefix: str = "w") -> dict:
    """Decision L177: ``samples`` (sensor -> ``(t, values)``) with the waist sensors' times moved to ``t - offset_s``
    (L161's model), and with ``drift`` (s/s, decision E229) to ``(t - offset_s) / (1 + drift)``: ``to_foot_clock``
    at ``ref_s`` 0, the mechanism of ``run --clock-offset`` / ``--clock-drift-ppm`` (B265; bit for bit ``t -
    offset_s`` without drift); anything that is no (t, values) pair is passed on for the push's checks to name.
    ``prefix="f"``: the foot sensors' instead (decision E227: a foot pod rebased after a reconnect)."""
    out = dict(samples)
    for name, tv in samples.items():
        if str(name).startswith(prefix) and isinstance(tv, tuple | list) and len(tv) == 2:
            try:
                t = to_foot_clock(np.asarray(tv[0], dtype=np.float64), offset_s, drift)
            except (TypeError, ValueError):
                continue
            out[name] = (t, tv[1])
    return out


def offset_remedy(offset_s: float) -> str:
    """What L177's line tells a live tracker to do: a new tracker with the waist clock moved by the estimate."""
    return f"a new Tracker(..., waist_clock_offset_s={offset_s:.3f})" if math.isfinite(offset_s) else "Tracker(...)"


__all__ = ["ClockCheck", "UNIT_OFFSET_WARN_S", "offset_remedy", "replay_check", "waist_on_foot_clock"]
