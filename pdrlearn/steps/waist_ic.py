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
stream (6 floats per sample) and ``push`` returns no steps. For a bounded delay use the realtime variant
of the IC detector (decision W31: contacts decided 1.75 to < 2 s after they happen;
``pdrlearn track --pipeline waist-pendulum --realtime``).
"""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.errors import MissingSensorError
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
        self.gaps = gaps or {}
        self.t: list[np.ndarray] = []
        self.v: list[np.ndarray] = []

    def process(self, t: np.ndarray, v: np.ndarray) -> list:
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
        from pdrlearn.waist.ahrs import imu_from_body

        imu = imu_from_body(t, acc, gyr, fs=self.fs, gain=self.det.ahrs_gain)
        steps = cut_steps_at_gaps(self.det.ic_detector().detect(imu).steps_, self.gaps)
        return [(float(r.event_s), float(r.start_s), float(r.end_s), float(r.confidence), {"fc_s": float(r.fc_s)})
                for r in steps.itertuples()]


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
    walk_threshold : motion-gate threshold on the std of vertical acceleration over 2 s (m/s^2; W4: 0.5)
    max_step_s : contacts further apart end a walking sequence (s; the pipeline's 1.5)
    rhythm, alternate, weight_shift, end_steps : the sequence rules W18, W20, W23, W28 (default on)
    learned : the W33 learned second stage (off by default; ``True`` = the shipped model, or a path)
    ahrs_gain : Madgwick gain (Madgwick 2010 / seed 001 sec. 2.2.1: 0.033)

    Online (decision 17): input columns are the waist accelerometer (m/s^2) and gyroscope (rad/s) in the
    body frame FLU on a uniform clock (``online(fs, rotation=R)`` maps sensor-frame samples with the
    session's ``frames["waist"]`` matrix); every contact is reported by ``flush()``.
    """

    name = "waist-ic"
    unit = "waist"
    input_columns = ("acc_x", "acc_y", "acc_z", "gyr_x", "gyr_y", "gyr_z")
    extra_columns = ("fc_s",)

    def __init__(self, *, walk_threshold: float = 0.5,  # W4 (= pdrlearn.waist.events.WALK_THRESHOLD_MPS2)
                 max_step_s: float = 1.5,  # the pipeline's MAX_STEP_S (pdrlearn.track.waist)
                 rhythm: bool = True, alternate: bool = True, weight_shift: bool = True, end_steps: bool = True,
                 learned: bool | str = False,
                 ahrs_gain: float = 0.033):  # Madgwick 2010 IMU gain, seed 001 sec. 2.2.1 (ahrs.MADGWICK_GAIN)
        self._store(locals())

    def ic_detector(self):
        """The :class:`InitialContactDetector` (offline) with this detector's settings."""
        from pdrlearn.waist.events import InitialContactDetector

        return InitialContactDetector(walk_threshold=self.walk_threshold, max_step_s=self.max_step_s,
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
        return _WaistICProcessor(self, fs, rotation=rotation, gaps=gaps)
