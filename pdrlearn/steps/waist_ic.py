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


class _WaistICProcessor:
    """Holds the body-frame samples; :meth:`flush` runs the offline IC detector on all of them."""

    def __init__(self, det: WaistICStepDetector, fs: float, rotation=None, gaps=None):
        self.det = det
        self.fs = fs
        self.rotation = None if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
        self.gaps = dict(gaps or {})
        from pdrlearn.kernels.waist_stream import Bridge

        self.bridge = Bridge(fs, self.gaps)
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


def _RealtimeProcessor(det: WaistICStepDetector, fs: float, rotation=None, gaps=None, on_nav=None):
    """Decision W31 on a stream (:class:`pdrlearn.kernels.waist_stream.RealtimeContacts`, numpy only, W92) with
    this detector's settings; its window detector is the offline :class:`InitialContactDetector` (the W33 learned
    stage included when set)."""
    from pdrlearn.kernels.waist_stream import RealtimeContacts
    from pdrlearn.waist.ahrs import WaistIMU

    ic_det = det.ic_detector()

    def offline(w: dict, fs_: float):
        imu = WaistIMU(t=w["t"], fs=fs_, acc_nav=w["acc_nav"], gyr_nav=w["gyr_nav"], yaw=w["yaw"], acc_v=w["acc_v"],
                       acc_h=w["acc_nav"][:, :2], acc_ap=w["acc_ap"], acc_ml=w["acc_ml"])
        return ic_det._offline(imu)

    return RealtimeContacts(fs, offline, rotation=rotation, gaps=gaps, gain=det.ahrs_gain, delay_s=det.delay_s,
                            hop_s=det.hop_s, history_s=det.history_s, max_step_s=det.max_step_s, on_nav=on_nav,
                            min_step_s=det.min_step_s)




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
    min_step_s : the shortest step (s; W16's 0.3); ``None`` (default, decision W113): relative to the session's own
        step rhythm, 0.75 of its step period and at most 0.3 s (a child's 3-4 Hz steps)
    contact_shift : offline (``delay_s=None``): every kept contact judged once more by W23's weight-shift test with the
        side read at the contact, turns spared (decision W131, default on; ignored with ``delay_s``, W133)

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
                 delay_s: float | None = None, hop_s: float = 0.25, history_s: float = 10.0,  # W31
                 min_step_s: float | None = None,  # W16 / W113: None = relative to the session's step rhythm
                 contact_shift: bool = True,  # W131 (offline only, W133)
                 parity_fill: bool | str = "within"):  # W152 / W159 (offline only), as the track's
        self._store(locals())

    def ic_detector(self, walk_threshold: float | None = None):
        """The :class:`InitialContactDetector` (offline) with this detector's settings; its gate ``walk_threshold``
        (m/s^2), else this detector's, else W4's fixed 0.5."""
        from pdrlearn.waist.events import WALK_THRESHOLD_MPS2, InitialContactDetector

        thr = next((x for x in (walk_threshold, self.walk_threshold) if x is not None), WALK_THRESHOLD_MPS2)
        return InitialContactDetector(walk_threshold=thr, max_step_s=self.max_step_s,
                                      rhythm=self.rhythm, alternate=self.alternate, weight_shift=self.weight_shift,
                                      end_steps=self.end_steps, learned=self.learned, min_step_s=self.min_step_s,
                                      contact_shift=self.contact_shift and self.delay_s is None,  # W131, W133
                                      parity_fill=self.parity_fill if self.delay_s is None else False)  # W159

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
