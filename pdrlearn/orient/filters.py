"""Orientation estimators (thesis ch.7.1 and 7.2.1): waist heading and foot attitude.

Both hold their settings (keyword-only) and results (ending in ``_``); the numerics live in
:mod:`pdrlearn.orient._kernels`.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io.session import Session
from pdrlearn.orient import _kernels as K
from pdrlearn.signal import interp_rows, lowpass, runs, standstill_mask

log = logging.getLogger(__name__)

_UNIT = {
    "foot": ("fAccelerometer", "fGyroscope", None),
    "waist": ("wAccelerometer", "wGyroscope", "wMagneticField"),
}


@dataclass
class UnitData:
    """One unit's streams in the body frame FLU, on the accelerometer's timestamps.

    Attributes
    ----------
    t : (n,) s;  acc : (n, 3) m/s^2;  gyr : (n, 3) rad/s;  mag : (n, 3) uT or None;  fs : Hz
    """

    placement: str
    t: np.ndarray
    acc: np.ndarray
    gyr: np.ndarray
    mag: np.ndarray | None
    fs: float


def unit_data(session: Session, placement: str, *, purpose: str = "localization",
              sensor_axes: bool = False) -> UnitData:
    """Accelerometer, gyroscope (and magnetometer) of a unit rotated into FLU via its declared frame;
    ``sensor_axes`` True: in the sensor's own axes, without a frame (none required, none checked: decision C142,
    for callers that read magnitudes only, e.g. the foot's rests).

    Raises
    ------
    MissingSensorError when the accelerometer or gyroscope is missing; DataError when the unit's axis
    frame is not declared, a stream is too short, or values are not finite.
    """
    acc_n, gyr_n, mag_n = _UNIT[placement]
    acc_s = session.require(acc_n, gyr_n, purpose=purpose)
    session.require_cover(acc_n, gyr_n)  # the gyroscope is interpolated onto the accelerometer's clock
    gyr_s = session.streams[gyr_n]
    R = np.eye(3) if sensor_axes else session.require_frame(placement).matrix()
    if len(acc_s) < 4 or len(gyr_s) < 4:
        raise DataError(f"session '{session.name}': {placement} streams have fewer than 4 samples")
    t = acc_s.t
    for s in (acc_s, gyr_s):
        if not np.all(np.isfinite(s.values)):
            raise DataError(f"session '{session.name}': {s.name} contains NaN/inf; clean or interpolate it")
    acc = acc_s.values @ R.T
    gyr = interp_rows(t, gyr_s.t, gyr_s.values) @ R.T
    mag = None
    if mag_n and mag_n in session.streams and len(session.streams[mag_n]) >= 2:
        session.require_cover(acc_n, mag_n)  # B21: a stopped compass would hold its last field (the heading)
        m = session.streams[mag_n]
        mag = interp_rows(t, m.t, m.values) @ R.T
    return UnitData(placement, t, acc, gyr, mag, float(acc_s.rate_hz))


class WaistHeading:
    """Waist heading: tilt-compensated compass + gyroscope through a complementary filter (thesis ch.7.1).

    Parameters
    ----------
    phi : filter coefficient at ``phi_rate_hz`` (thesis: 0.92 at 20 Hz); the time constant (thesis eq. 37)
        is kept at other rates.
    threshold : heading changes smaller than this (rad) are ignored (thesis ch.7.1: 0.035 rad)
    gravity_cutoff_hz : low-pass cutoff (Hz) of the accelerometer used as the gravity direction
    use_magnetometer : ``False`` -> gyroscope-only heading relative to ``initial_heading``
    initial_heading : ENU heading (rad) at the start when there is no magnetometer
    hard_iron_ut : (3,) offset (uT, body FLU) subtracted from the magnetometer before the compass, e.g. the
        fit of :func:`pdrlearn.track.plasys.fit_waist_hard_iron` (decision L84); None = none
    yaw_bias : (k, 2) (time s, vertical-rate bias rad/s) subtracted from the vertical rate, linearly interpolated
        in time and held beyond its ends (decision W126: read at rest); None = none

    Attributes
    ----------
    t_ : (n,) s;  heading_ : (n,) unwrapped ENU heading (rad, 0 = east, CCW);  compass_ : (n,) raw
    compass heading (rad) or None;  warnings_ : list of str
    """

    def __init__(self, *, phi: float = 0.92, phi_rate_hz: float = 20.0, threshold: float = 0.035,
                 gravity_cutoff_hz: float = 1.0, use_magnetometer: bool = True, initial_heading: float = 0.0,
                 hard_iron_ut=None, yaw_bias=None):
        self.phi = phi  # thesis ch.7.1
        self.phi_rate_hz = phi_rate_hz  # thesis ch.7.1: 20 Hz samples
        self.threshold = threshold  # thesis ch.7.1: 0.035 rad
        self.gravity_cutoff_hz = gravity_cutoff_hz
        self.use_magnetometer = use_magnetometer
        self.initial_heading = initial_heading
        self.hard_iron_ut = hard_iron_ut
        self.yaw_bias = yaw_bias

    def estimate(self, t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, mag: np.ndarray | None = None,
                 *, fs: float | None = None) -> WaistHeading:
        """Estimate the heading from FLU accelerometer (m/s^2), gyroscope (rad/s), magnetometer (uT)."""
        t = np.asarray(t, dtype=float)
        if t.size < 2:
            raise DataError("waist heading: need at least 2 samples")
        fs = fs or 1.0 / float(np.median(np.diff(t)))
        dt = 1.0 / fs
        cutoff = min(self.gravity_cutoff_hz, 0.4 * fs)
        grav = lowpass(acc, cutoff, fs)
        rate = K.yaw_rate(grav, gyr)
        if self.yaw_bias is not None and len(self.yaw_bias):  # decision W126
            b = np.asarray(self.yaw_bias, dtype=float)
            rate = rate - np.interp(t, b[:, 0], b[:, 1])
        self.warnings_: list[str] = []
        if mag is not None and self.use_magnetometer:
            if self.hard_iron_ut is not None:  # decision L84
                mag = np.asarray(mag, dtype=float) - np.asarray(self.hard_iron_ut, dtype=float)
            self.compass_ = K.tilt_compensated_heading(grav, mag)
            phi = K.phi_for_rate(dt, phi=self.phi, rate_hz=self.phi_rate_hz)
            theta = K.complementary_filter(self.compass_, rate, dt, phi=phi)
        else:
            self.compass_ = None
            self.warnings_.append("no magnetometer: waist heading from the gyroscope only, relative to the "
                                  f"initial heading {self.initial_heading:.3f} rad")
            steps = np.cumsum(0.5 * (rate[1:] + rate[:-1]) * dt)
            theta = self.initial_heading + np.concatenate([[0.0], steps])
        self.t_ = t
        self.heading_ = K.deadband(theta, self.threshold)
        return self

    def fit_session(self, session: Session) -> WaistHeading:
        """Estimate from a session's waist unit (raises MissingSensorError without one)."""
        u = unit_data(session, "waist", purpose="waist heading")
        if u.mag is None and self.use_magnetometer:
            log.info("%s: no magnetometer; gyroscope-only heading", session.name)
        return self.estimate(u.t, u.acc, u.gyr, u.mag, fs=u.fs)

    def heading_at(self, times: np.ndarray) -> np.ndarray:
        """Unwrapped heading (rad) interpolated at ``times`` (s)."""
        if not hasattr(self, "heading_"):
            raise DataError("WaistHeading: call estimate() first")
        return np.interp(np.asarray(times, dtype=float), self.t_, self.heading_)


def noise_from_standstill(acc: np.ndarray, gyr: np.ndarray) -> dict[str, float]:
    """Q/R of the foot angle Kalman filter from a standstill segment (thesis eq. 42/43).

    ``q_angle`` = variance of the gyroscope rate (rad^2/s^2), ``q_bias`` = a small fraction of it per
    sample (a bias random walk is not observable in a short standstill), ``r`` = variance of the
    accelerometer angles (rad^2). Floors keep the filter well-posed with noise-free data.
    """
    roll, pitch = K.tilt_from_accel(acc)
    gv = float(np.mean(np.var(gyr[:, :2], axis=0)))
    av = float(np.mean([np.var(roll), np.var(pitch)]))
    return {"q_angle": max(gv, 1e-6), "q_bias": max(gv * 1e-3, 1e-9), "r": max(av, 1e-5)}


class FootAttitude:
    """Foot roll/pitch from the accelerometer fused with the gyroscope by the 2-state Kalman filter.

    Thesis ch.7.2.1 (eq. 38-43): the accelerometer angles are measurements while the foot is in stance;
    in swing only the gyroscope propagates the angle. Q/R come from the first standstill (thesis: "the
    measurements are obtained with the BSU stationary") or the given values.

    Parameters
    ----------
    q_angle, q_bias, r : filter noise (see :func:`noise_from_standstill`); ``None`` = from standstill
    standstill_s : minimum standstill length (s) used to estimate Q/R

    Attributes
    ----------
    roll_, pitch_ : (n,) rad;  bias_ : (n, 2) gyroscope bias of x and y (rad/s);  noise_ : dict
    """

    def __init__(self, *, q_angle: float | None = None, q_bias: float | None = None, r: float | None = None,
                 standstill_s: float = 1.0):
        self.q_angle = q_angle
        self.q_bias = q_bias
        self.r = r
        self.standstill_s = standstill_s

    def _noise(self, acc: np.ndarray, gyr: np.ndarray, fs: float) -> dict[str, float]:
        noise = {"q_angle": 1e-4, "q_bias": 1e-7, "r": 1e-3}
        still = standstill_mask(acc, gyr, fs)
        for a, b in runs(still):
            if (b - a) / fs >= self.standstill_s:
                noise = noise_from_standstill(acc[a:b], gyr[a:b])
                break
        for k in noise:
            if getattr(self, k) is not None:
                noise[k] = float(getattr(self, k))
        return noise

    def estimate(self, acc: np.ndarray, gyr: np.ndarray, fs: float, stance: np.ndarray) -> FootAttitude:
        """Run the filter on FLU accelerometer (m/s^2) and gyroscope (rad/s); ``stance`` (n,) bool."""
        if acc.shape[0] == 0:
            raise MissingSensorError("foot attitude: empty foot streams")
        self.noise_ = self._noise(acc, gyr, fs)
        roll_m, pitch_m = K.tilt_from_accel(acc)
        dt = 1.0 / fs
        i0 = int(np.argmax(stance)) if stance.any() else 0
        self.roll_, bx = K.angle_kalman(roll_m, gyr[:, 0], dt, use_meas=stance, x0=(roll_m[i0], 0.0),
                                        **self.noise_)
        self.pitch_, by = K.angle_kalman(pitch_m, gyr[:, 1], dt, use_meas=stance, x0=(pitch_m[i0], 0.0),
                                         **self.noise_)
        self.bias_ = np.column_stack([bx, by])
        return self
