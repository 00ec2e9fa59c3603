"""``waist-ic``: the waist-pendulum pipeline's initial-contact detector as a step detector.

A thin wrapper: the contacts are those of :class:`pdrlearn.waist.events.InitialContactDetector` (seed 003
sec. 3.1 offline zero-lag FIR with the sequence rules W18, W20, W23, W28, W32; docs/decisions/waist.md) on
the AHRS's navigation-frame data (:mod:`pdrlearn.waist.ahrs`), exactly as ``pdrlearn track --pipeline
waist-pendulum`` finds them (same defaults, same cut at long recording gaps, B11).

Online (decision 17, docs/decisions/steps.md): the offline rules use whole-recording statistics (the mean
vertical acceleration removed before the FIR, the median lateral velocity that decides step sides, the
forward-backward lateral band-pass), so no contact is final before the recording ends. The online
detector therefore holds every sample and decides all contacts at :meth:`OnlineStepDetector.flush`: its
result is identical to :meth:`WaistICStepDetector.detect` for any chunking, its memory grows with the
stream (6 floats per sample) and ``push`` returns no steps. ``WaistICStepDetector(delay_s=1.75)`` is the
bounded-delay variant: the realtime IC detector of decision W31 (the same rules on the last 12 s, each
contact decided once, 1.75 to < 2 s after it happens) with a streaming AHRS; its state is bounded, its
``detect`` is its own online detector on one chunk (identical for any chunking), and its contacts are
those of ``pdrlearn track --pipeline waist-pendulum --realtime`` (decision 17).
"""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io.session import Session
from pdrlearn.steps.base import StepDetector

log = logging.getLogger(__name__)

#: the lower-back streams the detector reads (accelerometer + gyroscope for the AHRS, seed 001 sec. 2.2.1)
_STREAMS = ("wAccelerometer", "wGyroscope")


class _Bridge:
    """Decision W59: the dropped samples of a pushed stream bridged as the offline detector's input is
    (:func:`pdrlearn.waist.ahrs.body_data`, decision W34), so that ``online`` equals ``detect``: an interval
    over 1.5 periods gets its missing samples at the nominal period, linearly interpolated; one over
    ``LONG_GAP_S`` is filled as a rest (the mean of the raw samples of the second before it, zero rate); one over
    :data:`pdrlearn.track.gaps.MIN_GAP_S` ends the walking sequence (B11), added to ``gaps``."""

    def __init__(self, fs: float, gaps: dict):
        self.fs = fs
        self.gaps = gaps
        self.t_last: float | None = None
        self.v_last: np.ndarray | None = None
        self.tail_t = np.zeros(0)
        self.tail_v = np.zeros((0, 6))

    def __call__(self, t: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        from pdrlearn.track.gaps import MIN_GAP_S
        from pdrlearn.waist.ahrs import LONG_GAP_S

        p = 1.0 / self.fs
        prev = self.t_last is not None
        tt = np.concatenate([[self.t_last], t]) if prev else t
        vv = np.vstack([self.v_last, v]) if prev else v
        raw_t, raw_v = np.concatenate([self.tail_t, t]), np.vstack([self.tail_v, v])
        self.t_last, self.v_last = float(t[-1]), v[-1].copy()
        keep = raw_t > raw_t[-1] - LONG_GAP_S - p
        self.tail_t, self.tail_v = raw_t[keep], raw_v[keep]
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
            if d[i] > MIN_GAP_S:  # decision B11: the walking sequence ends at it
                self.gaps.setdefault("online stream", []).append((float(tt[i]), float(tt[i + 1])))
            a = i + 1
        ts.append(tt[a:])
        vs.append(vv[a:])
        out_t, out_v = np.concatenate(ts), np.vstack(vs)
        return (out_t[1:], out_v[1:]) if prev else (out_t, out_v)


class _WaistICProcessor:
    """Holds the body-frame samples; :meth:`flush` runs the offline IC detector on all of them."""

    def __init__(self, det: WaistICStepDetector, fs: float, rotation=None, gaps=None):
        self.det = det
        self.fs = fs
        self.rotation = None if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
        self.gaps = dict(gaps or {})
        self.bridge = _Bridge(fs, self.gaps)
        self.t: list[np.ndarray] = []
        self.v: list[np.ndarray] = []

    def process(self, t: np.ndarray, v: np.ndarray) -> list:
        t, v = self.bridge(t, v)  # W59: dropped samples bridged as detect's input (W34)
        self.t.append(t.copy())
        self.v.append(v.copy())
        return []  # decision 17: no contact is final before the end of the recording

    def flush(self) -> list:
        if not self.t:
            return []
        t, v = np.concatenate(self.t), np.concatenate(self.v)
        self.t, self.v = [], []
        if t.size < 2:
            return []
        acc, gyr = v[:, :3], v[:, 3:6]
        if self.rotation is not None:  # sensor frame -> body frame FLU (as pdrlearn.waist.ahrs.body_data)
            acc, gyr = acc @ self.rotation.T, gyr @ self.rotation.T
        from pdrlearn.track.gaps import cut_steps_at_gaps  # lazy: pdrlearn.track imports pdrlearn.steps
        from pdrlearn.track.waist import no_steps_message
        from pdrlearn.waist.ahrs import imu_from_body
        from pdrlearn.waist.events import gate_threshold

        imu = imu_from_body(t, acc, gyr, fs=self.fs, gain=self.det.ahrs_gain)
        # decision steps 35: the motion gate of `track`'s lower-back pipelines (W76's relative gate by default)
        thr, sigma, source = gate_threshold(imu, self.det.walk_threshold)
        steps = cut_steps_at_gaps(self.det.ic_detector(thr).detect(imu).steps_, self.gaps)
        if not len(steps):  # decision W76, as track: never 0 steps without a word
            log.warning("waist-ic: %s", no_steps_message(thr, sigma, source))
        return [(float(r.event_s), float(r.start_s), float(r.end_s), float(r.confidence), {"fc_s": float(r.fc_s)})
                for r in steps.itertuples()]


class _RealtimeProcessor:
    """Decision W31 on a stream: a streaming Madgwick AHRS, then every ``hop_s`` the offline IC detector on
    the last ``history_s + delay_s + hop_s`` seconds decides the contacts ``delay_s`` to ``delay_s + hop_s``
    old, once (:class:`pdrlearn.waist._kernels.DelayedDecider`, the state of ``track --realtime``'s
    :func:`~pdrlearn.waist._kernels.delayed_decisions`, fed as the samples arrive).
    A contact is reported once the next one is decided or no next one can follow within ``max_step_s``."""

    def __init__(self, det: WaistICStepDetector, fs: float, rotation=None, gaps=None):
        from pdrlearn.waist import _kernels as K

        self.det, self.fs = det, fs
        self.rotation = None if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
        self.gaps = dict(gaps or {})
        self.bridge = _Bridge(fs, self.gaps)
        self.ic_det = det.ic_detector()  # realtime: W4's fixed gate unless given (W76 needs the whole session)
        self.decider = K.DelayedDecider(fs, delay_s=det.delay_s, hop_s=det.hop_s, history_s=det.history_s)
        self.max_gap = K._max_gap(det.max_step_s, fs)
        self.n0 = max(1, int(round(INIT_S * fs)))  # the AHRS's initial attitude (pdrlearn.waist.ahrs.waist_imu)
        self.raw: list[np.ndarray] = []  # samples before the initial attitude is known
        self.q: np.ndarray | None = None  # the AHRS attitude (w, x, y, z) after the last sample
        self.g = 0.0
        self.prev_raw_yaw = 0.0
        self.wrap = 0
        self.b0 = 0  # absolute index of the first buffered sample
        self.buf: dict[str, np.ndarray] = {}
        self.n = 0
        self.decided: list[tuple[int, float, float]] = []  # (ic index, ic time, fc time) not yet reported

    # -- AHRS ------------------------------------------------------------------------------------
    def _nav(self, t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, first: bool) -> None:
        from scipy.spatial.transform import Rotation

        from pdrlearn.orient._kernels import madgwick_imu

        dt, gain = 1.0 / self.fs, self.det.ahrs_gain
        if first:  # as Madgwick's batch form: the first sample is the initial attitude itself
            q0 = self.q / np.linalg.norm(self.q)
            q = np.vstack([q0, madgwick_imu(q0, gyr[1:], acc[1:], dt, gain=gain)])
        else:
            q = madgwick_imu(self.q, gyr, acc, dt, gain=gain)
        self.q = q[-1]
        rot = Rotation.from_quat(np.column_stack([q[:, 1:], q[:, :1]]))
        acc_nav, gyr_nav = rot.apply(acc), rot.apply(gyr)
        fwd = rot.apply(np.tile([1.0, 0.0, 0.0], (len(t), 1)))
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

    # -- decisions -------------------------------------------------------------------------------
    def _detect(self, lo: int, hi: int):
        """The offline IC detector on the buffered samples ``[lo, hi)`` (absolute indices)."""
        from pdrlearn.waist.ahrs import WaistIMU

        a, b = lo - self.b0, hi - self.b0
        w = {k: v[a:b] for k, v in self.buf.items()}
        imu = WaistIMU(t=w["t"], fs=self.fs, acc_nav=w["acc_nav"], gyr_nav=w["gyr_nav"], yaw=w["yaw"],
                       acc_v=w["acc_v"], acc_h=w["acc_nav"][:, :2], acc_ap=w["acc_ap"], acc_ml=w["acc_ml"])
        return self.ic_det._offline(imu)

    def _decide(self, end: bool) -> None:
        t = self.buf["t"]
        for i, f, _, _ in self.decider.decide_until(self.n, self._detect, end=end):
            self.decided.append((i, float(t[i - self.b0]), float(t[f - self.b0])))

    def _report(self, final: bool) -> list:
        from pdrlearn.track.gaps import cut_steps_at_gaps
        from pdrlearn.waist.events import steps_from_events

        out = []
        done = self.decider.done
        t_done = self.buf["t"][done - self.b0] if self.buf and done >= self.b0 else -np.inf
        while self.decided:
            i, ti, tf = self.decided[0]
            if len(self.decided) < 2 and not final and not t_done - ti > self.det.max_step_s:
                break  # a next contact within max_step_s may still be decided
            pair = self.decided[:2]
            st = steps_from_events(np.array([p[1] for p in pair]), np.arange(len(pair)),
                                   max_step_s=self.det.max_step_s)
            st["fc_s"] = tf
            st = cut_steps_at_gaps(st.iloc[:1] if len(pair) == 1 else st, self.gaps)
            if len(st) and st["start_s"].iloc[0] == ti:  # (a contact inside a recording gap is dropped, B11)
                r = st.iloc[0]
                out.append((ti, ti, float(r.end_s), float(r.confidence), {"fc_s": tf}))
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
        t, v = self.bridge(t, v)  # W59: dropped samples bridged as detect's input (W34)
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
        from scipy.spatial.transform import Rotation

        from pdrlearn.signal import gravity_rotation

        r0 = Rotation.from_matrix(gravity_rotation(v[:self.n0, :3].mean(axis=0)))  # as waist_imu
        x, y, z, w = r0.as_quat()
        self.q = np.array([w, x, y, z])

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


INIT_S = 0.5  # pdrlearn.waist.ahrs.waist_imu's init_s: initial attitude from the first 0.5 s


class WaistICStepDetector(StepDetector):
    """Every step (both feet) at its initial contact, from the lower-back accelerometer and gyroscope.

    The waist-pendulum pipeline's offline IC detector (:class:`pdrlearn.waist.events.InitialContactDetector`,
    seed 003 sec. 3.1; rules W18 rhythm, W20 left/right alternation, W23 weight shift, W28 end steps,
    W32) on the Madgwick AHRS's navigation-frame data (seed 001 sec. 2.2.1, decision W5): the same contacts
    as ``pdrlearn track --pipeline waist-pendulum``. The event is the IC; ``end_s`` is the next IC of the
    walking sequence (``end_s == start_s`` and confidence 0.5 for a contact that closes a sequence, as
    :func:`pdrlearn.waist.events.steps_from_events`); ``fc_s`` the final contact after it.

    Parameters (keyword-only; defaults = the pipeline's)
    ----------
    walk_threshold : motion-gate threshold on the std of vertical acceleration over 2 s (m/s^2); None (default):
        ``track``'s gate (decision steps 35): W4's 0.5, lowered for a session whose trunk moves little by W76's
        session-relative gate (offline; the realtime variant keeps 0.5, as ``track --realtime``)
    max_step_s : contacts further apart end a walking sequence (s; the pipeline's 1.5)
    rhythm, alternate, weight_shift, end_steps : the sequence rules W18, W20, W23, W28 (default on)
    learned : the W33 learned second stage (off by default; ``True`` = the shipped model, or a path)
    ahrs_gain : Madgwick gain (decision W5: 0.033, the `ahrs` package's IMU default from Madgwick 2010;
        seed 001 sec. 2.2.1 uses a Madgwick filter but gives no gain)
    delay_s : ``None`` (default): the offline detector, every contact reported at the end (decision 17);
        a number: the realtime IC detector of decision W31 on a stream, each contact decided ``delay_s`` to
        ``delay_s + hop_s`` after it (W31: 1.75 s, the thesis' < 2 s) from the last ``history_s`` seconds
        (W31: 10 s) and reported when the next one is decided (at most ``max_step_s`` later); bounded state
    hop_s, history_s : decision interval and history of the realtime variant (s; W31: 0.25, 10)

    Online (decision 17): input columns are the waist accelerometer (m/s^2) and gyroscope (rad/s) in the
    body frame FLU at ``fs`` Hz (``online(fs, rotation=R)`` maps sensor-frame samples with the session's
    ``frames["waist"]`` matrix); dropped samples (an interval over 1.5 periods) are bridged as :meth:`detect`
    bridges them (decision W59, W34), so a stream with dropped samples gives ``detect``'s contacts; every
    contact is reported by ``flush()`` (``delay_s``: once decided).
    """

    name = "waist-ic"
    unit = "waist"
    input_columns = ("acc_x", "acc_y", "acc_z", "gyr_x", "gyr_y", "gyr_z")
    extra_columns = ("fc_s",)

    def __init__(self, *, walk_threshold: float | None = None,  # steps 35: None = track's gate (W4 0.5, W76)
                 max_step_s: float = 1.5,  # the pipeline's MAX_STEP_S (pdrlearn.track.waist)
                 rhythm: bool = True, alternate: bool = True, weight_shift: bool = True, end_steps: bool = True,
                 learned: bool | str = False,
                 ahrs_gain: float = 0.033,  # W5: Madgwick 2010 / `ahrs` IMU default (waist.ahrs.MADGWICK_GAIN)
                 delay_s: float | None = None, hop_s: float = 0.25, history_s: float = 10.0):  # W31
        self._store(locals())

    def ic_detector(self, walk_threshold: float | None = None):
        """The :class:`InitialContactDetector` (offline) with this detector's settings; its gate ``walk_threshold``
        (m/s^2), else this detector's, else W4's fixed 0.5."""
        from pdrlearn.waist.events import WALK_THRESHOLD_MPS2, InitialContactDetector

        thr = next((x for x in (walk_threshold, self.walk_threshold) if x is not None), WALK_THRESHOLD_MPS2)
        return InitialContactDetector(walk_threshold=thr, max_step_s=self.max_step_s,
                                      rhythm=self.rhythm, alternate=self.alternate, weight_shift=self.weight_shift,
                                      end_steps=self.end_steps, learned=self.learned)

    def _inputs(self, session: Session):
        from pdrlearn.track.gaps import long_gaps
        from pdrlearn.waist.ahrs import body_data

        missing = [n for n in _STREAMS if not session.has(n)]
        if missing:
            where = str(session.folder) if session.folder is not None else f"session '{session.name}'"
            raise MissingSensorError(
                f"{where}: no {' or '.join(missing)} (lower-back unit) for the waist-ic step detector, which "
                f"reads the lower-back accelerometer and gyroscope (it has: {', '.join(session.streams) or 'none'}); "
                "use --detector accel for a foot unit")
        t, acc, gyr = body_data(session, purpose="the waist-ic step detector")
        gaps = long_gaps(session, _STREAMS)  # decision B11: contacts inside a gap dropped, as track
        return t, np.column_stack([acc, gyr]), {"gaps": gaps}

    def _make_processor(self, fs: float, rotation=None, gaps=None, **context):
        if self.delay_s is not None:
            if not (self.delay_s >= 0 and self.hop_s > 0 and self.history_s >= 0):
                raise DataError(f"waist-ic: delay_s={self.delay_s!r}, hop_s={self.hop_s!r}, "
                                f"history_s={self.history_s!r} must be >= 0, > 0, >= 0 seconds (W31: 1.75, 0.25, 10)")
            return _RealtimeProcessor(self, fs, rotation=rotation, gaps=gaps)
        return _WaistICProcessor(self, fs, rotation=rotation, gaps=gaps)
