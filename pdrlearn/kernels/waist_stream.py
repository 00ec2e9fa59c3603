"""The waist unit's contacts on a stream, numpy only (decisions W31, W59, W92).

:class:`Bridge` fills dropped samples as the offline detector's input is filled (W59, W34);
:class:`RealtimeContacts` is decision W31's realtime IC detector: a streaming Madgwick AHRS, then every ``hop_s``
the offline detector on the last seconds decides the contacts ``delay_s`` old, once. ``pdrlearn track --pipeline
waist-pendulum --realtime`` (through ``WaistICStepDetector(delay_s=...).online``), the live waist tracker of
:mod:`pdrlearn.waist` and the lean runtime's :class:`pdrlearn.runtime.WaistTracker` all run this code.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels import waist as K
from pdrlearn.kernels.ahrs import madgwick_imu, quat_from_matrix, quat_matrices
from pdrlearn.kernels.gaps import MIN_GAP_S, cut_contacts_at_gaps
from pdrlearn.kernels.rotation import gravity_rotation

#: bridged gaps longer than this (s) are filled as a rest (decision B11: reported, they end the walking sequence;
#: MIN_GAP_S); ``pdrlearn.waist.ahrs.LONG_GAP_S``
LONG_GAP_S = 1.0
#: Madgwick 2010 IMU gain (the ``ahrs`` package's default, W5); seed 001 sec. 2.2.1 uses the filter, gives no gain
MADGWICK_GAIN = 0.033
#: contacts further apart end a walking sequence (s): the waist-pendulum pipeline's (``pdrlearn.track.waist``)
MAX_STEP_S = 1.5
INIT_S = 0.5  # pdrlearn.waist.ahrs.waist_imu's init_s: initial attitude from the first 0.5 s


def rule_contacts(settings: dict | None = None):
    """The ``offline`` detector of :class:`RealtimeContacts` from :func:`pdrlearn.kernels.waist.contacts_offline`
    with ``settings`` (its keywords; ``walk_threshold`` at least), without the W33 learned stage."""
    kw = dict(settings or {})

    def offline(w: dict, fs: float):
        return K.contacts_offline(w["acc_v"], w["acc_ap"], w["acc_ml"], w["gyr_nav"][:, 2], fs, with_ap=False,
                                  **kw)[:3]

    return offline


def live_gap_fix() -> str:
    """Decision E349: what a live waist tracker does at a gap over B11's 1 s (:class:`Bridge`), the end of its gap
    line in place of the offline "re-record or trim the session" (a live stream cannot be either)."""
    return ("the live tracker goes on: each gap is filled as a rest (no turn counted inside it: the heading is kept "
            "across it, a turn inside it is missed), the walking sequence ends at it and the steps resume with the "
            "first contact after it (decisions W59, B11); check the heading after the longest one")


def clock_option(value) -> bool | str:
    """The live ``Bridge``'s clock keyword: False (W59's fill), True (E366's interpolation onto ``t0 + k / fs``) or
    ``"nearest"`` (E371: each sample on its nearest clock instant) or ``"nearest-phase"`` (E372: the same on a clock
    whose phase follows the stamps)."""
    if value in ("nearest", "nearest-phase"):
        return value
    if value in (False, True, None, 0, 1):
        return bool(value)
    raise ValueError(f"uniform_clock must be False, True, 'nearest' or 'nearest-phase', not {value!r}")


class Bridge:
    """Decision W59 and, with ``uniform_clock=True``, E366's option (not adopted: its rule failed at 100 Hz): the
    pushed samples put on the uniform clock ``t0 + k / fs`` from the first sample,
    as the offline detector's input is (W34's and B33's clock: :func:`pdrlearn.waist.ahrs.body_data`,
    :meth:`pdrlearn.io.session.Stream.on_uniform_clock`), causally: each clock instant gets the linear interpolation
    of the two pushed samples either side of it (a pushed sample within ``snap_s`` of it is taken as it is, time
    and values, so a uniform stream passes unchanged), once the later one is pushed; the same whatever the chunking.
    The waist kernels count samples (``dt = 1 / fs``): a phone's jittered stamps, whose intervals over 1.5 periods
    had each been filled with a made-up sample (no sample missing), had stretched every step by ~4 % at 4 ms jitter
    (trial s53t2 F3). An interval over ``LONG_GAP_S`` is filled as a rest instead (the mean of the raw samples of
    the second before it, zero rate); an interval over 1.5 periods is recorded in :attr:`filled` (W136's made-up
    samples), one over :data:`pdrlearn.track.gaps.MIN_GAP_S` ends the walking sequence (B11), added to ``gaps``.
    ``uniform_clock="nearest"`` (E371) puts each pushed sample, values as they are, on its nearest clock instant and
    fills only the instants left without one; ``"nearest-phase"`` (E372) does so on a clock whose phase follows the
    stamps. Both options, not adopted (docs/decisions/export.md: ~1 % long at 100 Hz with 4 ms jitter)."""

    def __init__(self, fs: float, gaps: dict, *, snap_s: float = 1e-6, uniform_clock: bool | str = False):
        self.fs = fs
        self.gaps = gaps
        self.snap_s = float(snap_s)
        #: decision E366: the clock above (an option: not adopted, its rule failed at 100 Hz); False: W59's fill of
        #: each interval over 1.5 periods with ``round(interval x fs) - 1`` samples
        #: decision E371's option ``"nearest"``: each pushed sample on its nearest clock instant, no interpolation
        self.uniform_clock = clock_option(uniform_clock)
        self.k_last = -1  # E371: the last clock instant a pushed sample was put on
        self.phase = 0.0  # E372: the clock's phase (s) the stamps show, a running mean of their offsets
        self.t_last: float | None = None
        self.v_last: np.ndarray | None = None
        self.t0: float | None = None  # the clock's origin: the first pushed sample (E366)
        self.k = 0  # the next clock instant's index
        self.tail_t = np.zeros(0)
        self.tail_v = np.zeros((0, 6))
        #: the intervals ``(t_a, t_b)`` whose samples were made up (W136 / W165: no standstill); a reader trims it
        self.filled: list[tuple[float, float]] = []

    def __call__(self, t: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if not self.uniform_clock:
            return self._fill(t, v)
        if self.uniform_clock in ("nearest", "nearest-phase"):
            t, v = self._snap(t, v)
            if not t.size:
                return t, v
        p, prev, tt, vv, raw_t, raw_v = self._take(t, v)
        if self.t0 is None:
            self.t0 = float(tt[0])
        d = np.diff(tt)
        for i in np.flatnonzero(d > 1.5 * p):  # W136 / B11: the intervals with made-up samples
            self.filled.append((float(tt[i]), float(tt[i + 1])))
            if d[i] > MIN_GAP_S:  # decision B11: the walking sequence ends at it
                self.gaps.setdefault("online stream", []).append((float(tt[i]), float(tt[i + 1])))
        # E366: the clock instants up to the newest pushed sample (within snap_s), each once
        k1 = int(np.floor((tt[-1] + self.snap_s - self.t0) * self.fs)) + 1
        ks = np.arange(self.k, max(k1, self.k))
        g = self.t0 + ks / self.fs
        g = g[g <= tt[-1] + self.snap_s]
        self.k += g.size
        if not g.size:
            return t[:0], v[:0]
        i = np.clip(np.searchsorted(tt, g, side="right") - 1, 0, tt.size - 1)
        j = np.minimum(i + 1, tt.size - 1)
        span = tt[j] - tt[i]
        w = np.where(span > 0, (g - tt[i]) / np.where(span > 0, span, 1.0), 0.0)
        out_v = (1.0 - w)[:, None] * vv[i] + w[:, None] * vv[j]
        out_t = g.copy()
        at_i = np.abs(g - tt[i]) <= self.snap_s  # a pushed sample on the clock passes as it is (E366)
        at_j = ~at_i & (np.abs(tt[j] - g) <= self.snap_s)
        out_t[at_i], out_v[at_i] = tt[i[at_i]], vv[i[at_i]]
        out_t[at_j], out_v[at_j] = tt[j[at_j]], vv[j[at_j]]
        rest = ~at_i & ~at_j & (span > LONG_GAP_S)
        for a in np.unique(i[rest]):  # as body_data: at rest, the specific force of the last second, zero rate
            before = (raw_t > tt[a] - LONG_GAP_S) & (raw_t <= tt[a])
            out_v[rest & (i == a)] = np.concatenate([raw_v[before, :3].mean(axis=0), np.zeros(3)])
        return out_t, out_v

    def _snap(self, t: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """E371: each pushed sample put on its nearest clock instant ``t0 + k / fs`` (within half a period), values
        as they are; one whose instant is already taken (or earlier) is dropped, the first wins. The instants
        without a sample are then filled by :meth:`__call__`'s interpolation between its neighbours (W59's fill)."""
        if self.t0 is None and t.size:
            self.t0 = float(t[0])
        if self.uniform_clock == "nearest-phase":
            k = self._phase_snap(t)
        else:
            k = np.rint((t - self.t0) * self.fs).astype(np.int64)
        keep = k > np.maximum.accumulate(np.concatenate([[self.k_last], k]))[:-1]
        k = k[keep]
        if k.size:
            self.k_last = int(k[-1])
        # a sample already on its instant keeps its stamp (a uniform stream passes bit-identical)
        g = self.t0 + k / self.fs
        tk = t[keep]
        return np.where(np.abs(tk - g) <= self.snap_s, tk, g), v[keep]

    def _phase_snap(self, t: np.ndarray, alpha: float = 0.02) -> np.ndarray:
        """E372: the instants of E371 on a clock whose phase is the running mean (weight ``alpha`` per sample: ~1 s at
        50 Hz, 4 ms jitter averaged to ~0.4 ms) of the stamps' offsets from it, so the first stamp's own error no
        longer shifts every instant; a sample whose nearest instant is taken goes to the next one if its stamp is
        within a period of it (a phone takes one sample per period: the pair was one early, one late), else -1
        (dropped)."""
        k = np.empty(t.size, dtype=np.int64)
        last, ph = self.k_last, self.phase
        for n, x in enumerate((t - self.t0) * self.fs):
            kn = int(np.rint(x - ph))
            if kn <= last:
                kn = last + 1 if last + 1 - (x - ph) < 1.0 else -1
            if kn >= 0:
                ph += alpha * ((x - kn) - ph)
                last = kn
            k[n] = kn
        self.phase = ph
        return k

    def _take(self, t: np.ndarray, v: np.ndarray) -> tuple:
        """The pushed samples with the previous push's last before them (``tt``, ``vv``) and with the raw samples of
        the last ``LONG_GAP_S`` (``raw_t``, ``raw_v``: a long gap's rest), the state moved on past them."""
        p = 1.0 / self.fs
        prev = self.t_last is not None
        tt = np.concatenate([[self.t_last], t]) if prev else t
        vv = np.vstack([self.v_last, v]) if prev else v
        raw_t, raw_v = np.concatenate([self.tail_t, t]), np.vstack([self.tail_v, v])
        self.t_last, self.v_last = float(t[-1]), v[-1].copy()
        keep = raw_t > raw_t[-1] - LONG_GAP_S - p
        self.tail_t, self.tail_v = raw_t[keep], raw_v[keep]
        return p, prev, tt, vv, raw_t, raw_v

    def _fill(self, t: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """W59 (the default): an interval over 1.5 periods gets ``round(interval x fs) - 1`` samples at the nominal
        period, linearly interpolated (over ``LONG_GAP_S``: a rest); the other samples pass as they are."""
        p, prev, tt, vv, raw_t, raw_v = self._take(t, v)
        d = np.diff(tt)
        big = np.flatnonzero(d > 1.5 * p)
        if not big.size:
            return t, v
        ts, vs, a = [], [], 0
        for i in big:
            ts.append(tt[a:i + 1])
            vs.append(vv[a:i + 1])
            n = int(round(d[i] * self.fs)) - 1
            ti = tt[i] + p * np.arange(1, n + 1)
            if d[i] > LONG_GAP_S:  # as body_data: at rest, the specific force of the last second, zero rate
                before = (raw_t > tt[i] - LONG_GAP_S) & (raw_t <= tt[i])
                fill = np.tile(np.concatenate([raw_v[before, :3].mean(axis=0), np.zeros(3)]), (n, 1))
            else:
                w = ((ti - tt[i]) / d[i])[:, None]
                fill = (1.0 - w) * vv[i] + w * vv[i + 1]
            ts.append(ti)
            vs.append(fill)
            self.filled.append((float(tt[i]), float(tt[i + 1])))
            if d[i] > MIN_GAP_S:  # decision B11: the walking sequence ends at it
                self.gaps.setdefault("online stream", []).append((float(tt[i]), float(tt[i + 1])))
            a = i + 1
        ts.append(tt[a:])
        vs.append(vv[a:])
        out_t, out_v = np.concatenate(ts), np.vstack(vs)
        return (out_t[1:], out_v[1:]) if prev else (out_t, out_v)


class RealtimeContacts:
    """Decision W31 on a stream: a streaming Madgwick AHRS, then every ``hop_s`` the offline IC detector on
    the last ``history_s + delay_s + hop_s`` seconds decides the contacts ``delay_s`` to ``delay_s + hop_s``
    old, once (:class:`pdrlearn.waist._kernels.DelayedDecider`, the state of ``track --realtime``'s
    :func:`~pdrlearn.waist._kernels.delayed_decisions`, fed as the samples arrive).
    A contact is reported once the next one is decided or no next one can follow within ``max_step_s``.

    ``offline(window, fs)``: the offline detector on a window of navigation-frame arrays (``t``, ``acc_nav``,
    ``gyr_nav``, ``yaw``, ``acc_v``, ``acc_ap``, ``acc_ml``) -> ``(ic, fc, anchor)`` window indices
    (:func:`rule_contacts` with the pipeline's defaults, or the ``waist-ic`` detector's); ``on_nav(t, acc_v,
    w_z, acc_nav, gyr_nav)``: called with each stretch of navigation-frame samples as the AHRS makes them (the live
    trackers)."""

    def __init__(self, fs: float, offline, *, rotation=None, gaps=None, gain: float = MADGWICK_GAIN,
                 delay_s: float = K.DECISION_DELAY_S, hop_s: float = K.DECISION_HOP_S,
                 history_s: float = K.DECISION_HISTORY_S, max_step_s: float = MAX_STEP_S, on_nav=None,
                 min_step_s: float | None = K.DECISION_MIN_STEP_S, uniform_clock: bool | str = False):
        self.fs, self.offline, self.gain, self.max_step_s, self.on_nav = fs, offline, gain, max_step_s, on_nav
        self.rotation = None if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
        self.gaps = dict(gaps or {})
        self.bridge = Bridge(fs, self.gaps, uniform_clock=uniform_clock)  # E366: an option
        self.decider = K.DelayedDecider(fs, delay_s=delay_s, hop_s=hop_s, history_s=history_s, min_step_s=min_step_s)
        self.max_gap = K._max_gap(max_step_s, fs)
        self.n0 = max(1, int(round(INIT_S * fs)))  # the AHRS's initial attitude (pdrlearn.waist.ahrs.waist_imu)
        self.raw: list[np.ndarray] = []  # samples before the initial attitude is known
        self.q: np.ndarray | None = None  # the AHRS attitude (w, x, y, z) after the last sample
        self.g = 0.0
        self.prev_raw_yaw = 0.0
        self.wrap = 0
        self.b0 = 0  # absolute index of the first buffered sample
        self.buf: dict[str, np.ndarray] = {}
        self.n = 0
        #: (ic index, ic time, fc time, W138's lateral velocity at the ic) not yet reported
        self.decided: list[tuple[int, float, float, float]] = []

    # -- AHRS ------------------------------------------------------------------------------------
    def _nav(self, t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, first: bool) -> None:
        dt, gain = 1.0 / self.fs, self.gain
        if first:  # as Madgwick's batch form: the first sample is the initial attitude itself
            q0 = self.q / np.linalg.norm(self.q)
            q = np.vstack([q0, madgwick_imu(q0, gyr[1:], acc[1:], dt, gain=gain)])
        else:
            q = madgwick_imu(self.q, gyr, acc, dt, gain=gain)
        self.q = q[-1]
        rot = quat_matrices(q)
        acc_nav, gyr_nav = np.einsum("nij,nj->ni", rot, acc), np.einsum("nij,nj->ni", rot, gyr)
        fwd = rot[:, :, 0]  # the body's forward axis in the navigation frame
        raw = np.arctan2(fwd[:, 1], fwd[:, 0])
        if first:
            self.prev_raw_yaw = raw[0]
            self.g = float(np.median(acc_nav[:self.n0, 2]))  # causal: gravity of the first INIT_S
        # unwrap with whole turns counted as integers: the same yaw whatever the chunking
        dd = np.diff(np.concatenate([[self.prev_raw_yaw], raw]))
        turns = self.wrap + np.cumsum(np.where(dd > np.pi, -1, np.where(dd < -np.pi, 1, 0)))
        self.wrap, self.prev_raw_yaw = int(turns[-1]), raw[-1]
        yaw = raw + 2 * np.pi * turns
        c, s = np.cos(yaw), np.sin(yaw)
        new = {"t": t, "acc_nav": acc_nav, "gyr_nav": gyr_nav, "yaw": yaw, "acc_v": acc_nav[:, 2] - self.g,
               "acc_ap": c * acc_nav[:, 0] + s * acc_nav[:, 1], "acc_ml": -s * acc_nav[:, 0] + c * acc_nav[:, 1]}
        self.buf = {k: np.concatenate([self.buf[k], v]) if self.buf else v for k, v in new.items()}
        self.n += len(t)
        if self.on_nav is not None:
            self.on_nav(t, new["acc_v"], gyr_nav[:, 2], acc_nav, gyr_nav)

    # -- decisions -------------------------------------------------------------------------------
    def _detect(self, lo: int, hi: int):
        """The offline IC detector on the buffered samples ``[lo, hi)`` (absolute indices)."""
        a, b = lo - self.b0, hi - self.b0
        return self.offline({k: v[a:b] for k, v in self.buf.items()}, self.fs)

    def _decide(self, end: bool) -> None:
        t = self.buf["t"]
        v_ml: dict[int, np.ndarray] = {}  # decision time -> W20's lateral velocity of that decision's window
        for i, f, _, tt in self.decider.decide_until(self.n, self._detect, end=end):
            lo = max(self.b0, tt - self.decider.span)
            if tt not in v_ml:  # decision W138: on the samples the contact was decided on only ([T - span, T))
                v_ml[tt] = K.lateral_velocity_cached(self.buf["acc_ml"][lo - self.b0:tt - self.b0], self.fs)
            self.decided.append((i, float(t[i - self.b0]), float(t[f - self.b0]), float(v_ml[tt][i - lo])))

    def _report(self, final: bool) -> list:
        out = []
        done = self.decider.done
        t_done = self.buf["t"][done - self.b0] if self.buf and done >= self.b0 else -np.inf
        while self.decided:
            i, ti, tf, v_ml = self.decided[0]
            if len(self.decided) < 2 and not final and not t_done - ti > self.max_step_s:
                break  # a next contact within max_step_s may still be decided
            ts = np.array([p[1] for p in self.decided[:2]])
            end, has_next, conf = K.contact_rows(ts, self.max_step_s)  # as steps_from_events
            keep, spans = (np.ones(ts.size, bool), np.zeros(ts.size, bool)) if not self.gaps else \
                cut_contacts_at_gaps(ts, end, has_next, self.gaps)  # as cut_steps_at_gaps
            if keep[0]:  # (a contact inside a recording gap is dropped, B11)
                end0 = ti if spans[0] else float(end[0])
                out.append((ti, ti, end0, float(conf[0]), {"fc_s": tf, "v_ml_mps": v_ml}))
            self.decided.pop(0)
        return out

    def _trim(self) -> None:
        # keep the next decision's window, the final one's (flush at n >= next_t - hop) and t[done]
        d = self.decider
        drop = max(0, min(d.next_t - d.hop - d.span, d.done) - self.b0)
        if drop > 0:
            self.buf = {k: v[drop:] for k, v in self.buf.items()}
            self.b0 += drop

    # -- stream ----------------------------------------------------------------------------------
    def process(self, t: np.ndarray, v: np.ndarray) -> list:
        t, v = self.bridge(t, v)  # W59 / E366: on detect's uniform clock (W34, B33)
        if not t.size:  # E366: no clock instant reached yet
            return []
        if self.rotation is not None:
            v = np.column_stack([v[:, :3] @ self.rotation.T, v[:, 3:6] @ self.rotation.T])
        first = False
        if self.q is None:
            self.raw.append((t, v))
            tt = np.concatenate([r[0] for r in self.raw])
            if tt.size < self.n0:
                return []
            vv = np.concatenate([r[1] for r in self.raw])
            self.raw = []
            t, v, first = tt, vv, True
            self._start(v)
        self._nav(t, v[:, :3], v[:, 3:6], first)
        self._decide(end=False)
        out = self._report(final=False)
        self._trim()
        return out

    def _start(self, v: np.ndarray) -> None:
        self.q = quat_from_matrix(gravity_rotation(v[:self.n0, :3].mean(axis=0)))  # as waist_imu

    def flush(self) -> list:
        if self.q is None and self.raw:  # shorter than the initial attitude window: start anyway
            tt = np.concatenate([r[0] for r in self.raw])
            vv = np.concatenate([r[1] for r in self.raw])
            self.raw = []
            self.n0 = min(self.n0, tt.size)
            self._start(vv)
            self._nav(tt, vv[:, :3], vv[:, 3:6], True)
        if self.n == 0:
            return []
        self._decide(end=True)
        return self._report(final=True)
