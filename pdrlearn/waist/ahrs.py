"""Attitude of the waist unit and its data cast to a gravity-aligned navigation frame.

Seed 000 sec. II-A and seed 001 sec. 2.2.1 cast the waist data to a global frame with an AHRS
(seed 001: a Madgwick filter) before any gait analysis. We use Madgwick's filter in its IMU form
(accelerometer + gyroscope) as the ``ahrs`` package writes it, run by the scalar kernel
:func:`pdrlearn.orient._kernels.madgwick_imu` (equal to ``ahrs`` to rounding, over 10x faster; decision W43):
the magnetometers of the recordings we have are uncalibrated (see ../shared/data/README.md), so the
heading is relative to the start, not to magnetic north (docs/decisions/waist.md W5).

Frames: the sensor axes are mapped to the body frame FLU with the session's declared
``frames["waist"]``; the navigation frame has z up and x along the unit's initial forward direction
(heading 0 = where the unit faced at the start, counter-clockwise positive).
"""

from __future__ import annotations

import logging
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io import Session
from pdrlearn.orient._kernels import madgwick_imu
from pdrlearn.signal import gravity_rotation, interp_rows

log = logging.getLogger(__name__)

ACC, GYR = "wAccelerometer", "wGyroscope"
#: bridged gaps longer than this (s) are filled as a rest (decision B11: reported, they end the walking
#: sequence; pdrlearn.track.gaps.MIN_GAP_S)
from pdrlearn.kernels.waist_stream import LONG_GAP_S, MADGWICK_GAIN  # noqa: E402,F401  (W92)


@dataclass
class WaistIMU:
    """Waist data in the navigation frame, one row per accelerometer sample.

    Attributes
    ----------
    t : (n,) s; fs : rate (Hz)
    acc_nav : (n, 3) specific force in the navigation frame (m/s^2; z up, includes gravity)
    gyr_nav : (n, 3) angular rate in the navigation frame (rad/s); ``[:, 2]`` is the vertical rate
    yaw : (n,) unit heading about the vertical (rad, unwrapped, 0 = initial facing direction)
    acc_v : (n,) vertical acceleration without gravity (m/s^2, up +)
    acc_h : (n, 2) horizontal acceleration in the navigation frame (m/s^2)
    acc_ap, acc_ml : (n,) horizontal acceleration along / across the unit's current heading
        (antero-posterior forward +, medio-lateral left +) (m/s^2)
    up_body : (n, 3) the AHRS's up direction (unit vector) in the body frame FLU, i.e. the attitude's tilt
        (decision W102's trunk-tilt gate); None when the data came without it
    bridged : (n,) bool, samples made up inside a gap of dropped samples (W34's line or B11's rest), which are no
        evidence that the unit stood still (decision W136); None when not known (all recorded)
    gyr_body : (n, 3) angular rate in the body frame FLU (rad/s), as the AHRS read it: the rate about the trunk's
        long axis while lying (decision W269); None when the data came without it

    :meth:`still` is the navigation-frame standstill mask, computed once per object (decision W354).
    """

    t: np.ndarray
    fs: float
    acc_nav: np.ndarray
    gyr_nav: np.ndarray
    yaw: np.ndarray
    acc_v: np.ndarray
    acc_h: np.ndarray
    acc_ap: np.ndarray
    acc_ml: np.ndarray
    up_body: np.ndarray | None = None
    bridged: np.ndarray | None = None
    gyr_body: np.ndarray | None = None
    _still: np.ndarray | None = field(default=None, init=False, repr=False, compare=False)

    @property
    def w_z(self) -> np.ndarray:
        return self.gyr_nav[:, 2]

    def still(self) -> np.ndarray:
        """Decision W354: :func:`~pdrlearn.signal.conditioning.standstill_mask` with its defaults on ``acc_nav``,
        ``gyr_nav`` at ``fs`` (L296's still samples, W122's standstills), computed on the first call and shared
        (read-only) by every later reader of this object."""
        if self._still is None:
            from pdrlearn.signal.conditioning import standstill_mask

            still = standstill_mask(self.acc_nav, self.gyr_nav, self.fs)
            still.setflags(write=False)
            self._still = still
        return self._still


def nav_still(signals) -> np.ndarray:
    """Decision W354: the standstill mask (``standstill_mask``, its defaults) of navigation-frame ``signals``
    (``acc_nav``, ``gyr_nav``, ``fs``): a :class:`WaistIMU`'s own :meth:`~WaistIMU.still`, else computed."""
    if isinstance(signals, WaistIMU):
        return signals.still()
    from pdrlearn.signal.conditioning import standstill_mask

    return standstill_mask(signals.acc_nav, signals.gyr_nav, signals.fs)


def _quat_wxyz_to_rotation(q: np.ndarray) -> Rotation:
    return Rotation.from_quat(np.column_stack([q[:, 1:], q[:, :1]]))


def _where(session: Session, stream: str) -> str:
    """The file of ``stream`` when the session was read from disk, else the session and stream names."""
    if session.folder is not None:
        return str(session.folder / f"{stream}.csv")
    return f"session '{session.name}': {stream}"


def no_gyroscope_message(session: Session, purpose: str) -> str:
    """Decisions W130, B189: the one line for a lower-back session with an accelerometer and no gyroscope - what needs
    it, and the accelerometer-only step detector that works (no distance, bouts or heading: W130 keeps refusing)."""
    folder = str(session.folder) if session.folder is not None else "DIR"
    return (f"{session.where}: no wGyroscope.csv, needed by {purpose}: the waist attitude (which way is up and "
            "forward) and the heading come from the gyroscope, in both lower-back pipelines (waist-pendulum, "
            "waist-pll; decision W130); with the accelerometer alone only the contacts can be found: "
            f"'pdrlearn steps {folder} "
            "--detector pll --out steps.csv' (no distance, bouts or heading); or record the gyroscope too")


def body_data(session: Session, *, purpose: str = "waist dead reckoning") -> tuple[np.ndarray, np.ndarray,
                                                                                      np.ndarray]:
    """Waist accelerometer and gyroscope on the accelerometer's timestamps, in the body frame FLU.

    The waist kernels count samples (windows, shortest/longest step), so the clock must be uniform: when
    the accelerometer has dropped samples (an interval over 1.5 nominal periods, :meth:`Stream.gaps`),
    both streams are interpolated linearly onto the uniform clock ``t0 + k / fs`` of the native rate
    (decision W34).
    A gap longer than :data:`LONG_GAP_S` (reported and ending the walking sequence, B11) is
    filled as a rest instead: the mean specific force of the second before it and zero rate, so the AHRS
    keeps its attitude across it (a straight line between two walking samples tilted it for the rest of the
    recording and moved the median gravity, hence contacts and lengths before and after the gap; W34).
    A gyroscope gap over :data:`LONG_GAP_S` (the accelerometer recording on) is zero rate, not a line.
    Uniform recordings are returned unchanged.

    Raises :class:`MissingSensorError` without them and :class:`DataError` for an undeclared frame,
    NaN values or a recording shorter than 2 s.
    """
    if session.has(ACC) and not session.has(GYR):  # decisions W130, B189: say what works without one
        raise MissingSensorError(no_gyroscope_message(session, purpose))
    session.require(ACC, GYR, purpose=purpose)
    session.require_cover(ACC, GYR)  # interpolated onto the accelerometer's clock: no made-up rates at the ends
    frame = session.require_frame("waist")
    acc_s, gyr_s = session[ACC], session[GYR]
    t = acc_s.t
    if len(acc_s) < 2 or acc_s.duration_s < 2.0:
        raise DataError(f"{_where(session, ACC)} covers {acc_s.duration_s:.2f} s; "
                        f"{purpose} needs at least 2 s of data: record a longer session")
    for s in (acc_s, gyr_s):
        if not np.all(np.isfinite(s.values)):
            raise DataError(f"{_where(session, s.name)} contains NaN or infinite values; "
                            "clean or interpolate the recording first")
    acc = acc_s.values
    gaps = acc_s.gaps()
    if gaps:  # decision W34: bridge dropped samples so that sample counts stay durations
        fs = acc_s.rate_hz
        t = acc_s.t[0] + np.arange(int(round(acc_s.duration_s * fs)) + 1) / fs
        acc = interp_rows(t, acc_s.t, acc_s.values)
        log.info("%s: %s has %d gap(s) (longest %.3f s), interpolated onto a uniform %.4g Hz clock",
                 session.name, ACC, len(gaps), max(g.duration_s for g in gaps), fs)
    gyr = gyr_s.values
    if len(gyr_s) != len(t) or not np.allclose(gyr_s.t, t, atol=1e-6):
        gyr = interp_rows(t, gyr_s.t, gyr_s.values)
    long = [g for g in gaps if g.duration_s > LONG_GAP_S]
    gyr_gaps = gyr_s.gaps()
    gyr_long = [g for g in gyr_gaps if g.duration_s > LONG_GAP_S]
    if long or gyr_long:  # a straight line between two walking samples would tilt the AHRS for the rest
        gyr = gyr.copy() if gyr is gyr_s.values else gyr  # of the recording
        half = 0.5 / acc_s.rate_hz
        for g in long:
            inside = (t > g.start_s + half) & (t < g.start_s + g.duration_s - half)  # not the edge samples
            before = (acc_s.t > g.start_s - LONG_GAP_S) & (acc_s.t <= g.start_s)
            acc[inside] = acc_s.values[before].mean(axis=0)  # at rest: the specific force of the last second
            gyr[inside] = 0.0
        for g in gyr_long:  # the gyroscope alone lost samples: no rotation is made up inside its gap
            gyr[(t > g.start_s + half) & (t < g.start_s + g.duration_s - half)] = 0.0
    r = frame.matrix()
    return t, acc @ r.T, gyr @ r.T


def waist_imu(session: Session, *, gain: float = MADGWICK_GAIN, init_s: float = 0.5) -> WaistIMU:
    """Run the AHRS on a session's waist unit and return its data in the navigation frame.

    Parameters
    ----------
    gain : Madgwick filter gain (-)
    init_s : the initial attitude is the gravity direction averaged over the first ``init_s`` seconds
    """
    t, acc, gyr = body_data(session)
    imu = imu_from_body(t, acc, gyr, gain=gain, init_s=init_s)
    imu.bridged = bridged_samples(session, t)
    kept = _KEPT.get()
    if kept is not None:  # decision W353: inside kept_imus(), for a later reader of the same session
        kept.append((session, float(gain), float(init_s), imu))
    return imu


#: decision W353: the list :func:`kept_imus` collects :func:`waist_imu`'s results in (None: outside it)
_KEPT: ContextVar[list | None] = ContextVar("pdrlearn_kept_waist_imus", default=None)


@contextmanager
def kept_imus():
    """Decision W353: inside the ``with`` block every :func:`waist_imu` result is kept with its session, gain and
    ``init_s`` in the yielded list, for :func:`kept_imu` to hand to a later reader (``track --gait-quality``'s W350
    reads the track's own AHRS instead of running it again). Nothing is kept outside the block."""
    kept: list = []
    token = _KEPT.set(kept)
    try:
        yield kept
    finally:
        _KEPT.reset(token)


def kept_imu(kept: list, session: Session, *, gain: float = MADGWICK_GAIN, init_s: float = 0.5) -> WaistIMU:
    """Decision W353: the :class:`WaistIMU` that :func:`waist_imu` computed inside :func:`kept_imus` for this very
    ``session`` object with these settings; else :func:`waist_imu` runs (the same numbers either way)."""
    for s, g, i, imu in kept:
        if s is session and g == float(gain) and i == float(init_s):
            return imu
    return waist_imu(session, gain=gain, init_s=init_s)


def bridged_samples(session: Session, t: np.ndarray) -> np.ndarray:
    """Samples of the clock ``t`` (as :func:`body_data` returns it) strictly inside an interval of dropped
    accelerometer or gyroscope samples (:meth:`Stream.gaps`; the recorded samples at its edges excluded): what
    :func:`body_data` made up there (decision W34's line, B11's rest) is no measurement (decision W136)."""
    out = np.zeros(len(t), dtype=bool)
    for name in (ACC, GYR):
        s = session[name]
        half = 0.5 / s.rate_hz
        for g in s.gaps():
            out |= (t > g.start_s + half) & (t < g.start_s + g.duration_s - half)
    return out


def imu_from_body(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, *, fs: float | None = None,
                  gain: float = MADGWICK_GAIN, init_s: float = 0.5) -> WaistIMU:
    """The AHRS and navigation-frame casting of :func:`waist_imu` on body-frame (FLU) arrays on a uniform
    clock, as :func:`body_data` returns them (``fs``: rate in Hz, default ``1 / median(diff(t))``)."""
    fs = float(1.0 / np.median(np.diff(t))) if fs is None else float(fs)
    n0 = max(1, int(round(init_s * fs)))
    r0 = Rotation.from_matrix(gravity_rotation(acc[:n0].mean(axis=0)))
    x, y, z, w = r0.as_quat()
    q0 = np.array([w, x, y, z])
    q0 /= np.linalg.norm(q0)  # as ahrs' Madgwick batch form: the first sample's attitude is q0 itself
    q = np.vstack([q0, madgwick_imu(q0, gyr[1:], acc[1:], 1.0 / fs, gain=gain)])
    rot = _quat_wxyz_to_rotation(q)
    acc_nav = rot.apply(acc)
    gyr_nav = rot.apply(gyr)
    fwd = rot.apply(np.tile([1.0, 0.0, 0.0], (len(t), 1)))
    yaw = np.unwrap(np.arctan2(fwd[:, 1], fwd[:, 0]))
    g = float(np.median(acc_nav[:, 2]))
    acc_v = acc_nav[:, 2] - g
    c, s = np.cos(yaw), np.sin(yaw)
    ap = c * acc_nav[:, 0] + s * acc_nav[:, 1]
    ml = -s * acc_nav[:, 0] + c * acc_nav[:, 1]
    log.info("AHRS: %d samples at %.1f Hz, local gravity %.3f m/s^2", len(t), fs, g)
    return WaistIMU(t=t, fs=fs, acc_nav=acc_nav, gyr_nav=gyr_nav, yaw=yaw, acc_v=acc_v,
                    acc_h=acc_nav[:, :2].copy(), acc_ap=ap, acc_ml=ml,
                    up_body=rot.inv().apply(np.tile([0.0, 0.0, 1.0], (len(t), 1))), gyr_body=gyr)
