"""Standstill detection, standstill calibration (thesis ch.4.4) and resampling of streams."""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io.sensors import UNIT_IMU
from pdrlearn.io.session import Session, Stream
from pdrlearn.signal.filters import interp_rows, uniform_grid

log = logging.getLogger(__name__)

G = 9.80665  # standard gravity, m/s^2 (thesis ch.4.3.1)

#: accelerometer / gyroscope stream names of each unit
UNIT_STREAMS = UNIT_IMU


def resample_stream(stream: Stream, rate_hz: float) -> Stream:
    """Resample a stream on a uniform grid ``t[0] + k / rate_hz`` by linear interpolation.

    Gaps (dropped samples) are bridged linearly. Raises :class:`DataError` on an empty stream.
    """
    if len(stream) == 0:
        raise DataError(f"{stream.name}: cannot resample an empty stream")
    if len(stream) == 1:
        return stream.copy()
    t_new = uniform_grid(float(stream.t[0]), float(stream.t[-1]), rate_hz)
    return Stream(stream.name, t_new, interp_rows(t_new, stream.t, stream.values))


def _check_finite(a: np.ndarray, what: str) -> None:
    if not np.all(np.isfinite(a)):
        raise DataError(f"{what}: contains NaN or infinite values; clean or interpolate the data first")


def standstill_mask(acc: np.ndarray, gyr: np.ndarray, fs: float, *, window_s: float = 0.25,
                    acc_tol: float = 0.3, gyr_tol: float = 0.25) -> np.ndarray:
    """Samples where the unit is still.

    A sample is still when, over a centred window of ``window_s`` seconds, the standard deviation of the
    acceleration magnitude is below ``acc_tol`` (m/s^2) and the mean gyroscope magnitude is below
    ``gyr_tol`` (rad/s); the three conditions of the stance detectors reviewed in thesis ch.3
    (acceleration magnitude, its local variance, gyroscope magnitude) reduced to two because the
    magnitude level depends on the sensor's scale error (real units rest at 9.5-9.85 m/s^2).

    Parameters
    ----------
    acc : (n, 3) specific force (m/s^2); gyr : (n, 3) angular rate (rad/s), same timestamps.
    fs : sampling rate (Hz).
    """
    acc = np.asarray(acc, dtype=np.float64)
    gyr = np.asarray(gyr, dtype=np.float64)
    if acc.shape[0] != gyr.shape[0]:
        raise DataError(f"standstill_mask: {acc.shape[0]} accelerometer but {gyr.shape[0]} gyroscope "
                        "samples; resample both on the same timestamps")
    if acc.shape[0] == 0:
        return np.zeros(0, dtype=bool)
    _check_finite(acc, "standstill_mask accelerometer")
    _check_finite(gyr, "standstill_mask gyroscope")
    from pdrlearn.kernels.waist import still_samples

    return still_samples(acc, gyr, fs, window_s=window_s, acc_tol=acc_tol, gyr_tol=gyr_tol)  # numpy (W165)


def runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Contiguous ``True`` runs of a boolean mask as ``(start, stop)`` index pairs (stop exclusive)."""
    m = np.asarray(mask, dtype=bool)
    if m.size == 0:
        return []
    d = np.diff(np.concatenate([[0], m.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(d == 1).tolist(), np.flatnonzero(d == -1).tolist(), strict=True))


@dataclass
class UnitCalibration:
    """Offsets of one unit estimated from a standstill period.

    Attributes
    ----------
    gyro_bias : (3,) mean gyroscope output at rest (rad/s)
    acc_mean : (3,) mean specific force at rest (m/s^2), i.e. the gravity vector in the sensor frame
    gravity_norm : |acc_mean| (m/s^2)
    acc_noise_std, gyro_noise_std : (3,) per-axis standard deviation at rest (m/s^2, rad/s)
    t0, t1 : standstill interval used (s)
    """

    gyro_bias: np.ndarray
    acc_mean: np.ndarray
    gravity_norm: float
    acc_noise_std: np.ndarray
    gyro_noise_std: np.ndarray
    t0: float
    t1: float

    @property
    def gravity(self) -> np.ndarray:
        return self.acc_mean

    def to_dict(self) -> dict:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in self.__dict__.items()}


@dataclass
class StandstillCalibration:
    """Per-unit calibration (``units["foot"]``, ``units["waist"]``) from the initial standstill."""

    units: dict[str, UnitCalibration] = field(default_factory=dict)

    def __getitem__(self, unit: str) -> UnitCalibration:
        return self.units[unit]

    def __contains__(self, unit: str) -> bool:
        return unit in self.units

    def to_dict(self) -> dict:
        return {u: c.to_dict() for u, c in self.units.items()}


def _unit_calibration(session: Session, unit: str, *, min_s: float, max_s: float,
                      mask_kw: dict) -> UnitCalibration:
    acc_name, gyr_name = UNIT_STREAMS[unit]
    acc_s = session.require(acc_name, purpose=f"{unit} standstill calibration")
    gyr_s = session.require(gyr_name, purpose=f"{unit} standstill calibration")
    if len(acc_s) < 2 or len(gyr_s) < 2:
        raise DataError(f"session '{session.name}': {unit} streams are empty; nothing to calibrate")
    session.require_cover(acc_name, gyr_name)  # B21: interpolated onto the accelerometer's clock below
    t = acc_s.t
    gyr = interp_rows(t, gyr_s.t, gyr_s.values)
    fs = acc_s.rate_hz
    still = standstill_mask(acc_s.values, gyr, fs, **mask_kw)
    for a, b in runs(still):
        if t[b - 1] - t[a] >= min_s - 1.5 / fs:
            stop = a + int(np.searchsorted(t[a:b], t[a] + max_s, side="right"))
            sl = slice(a, stop)
            acc_mean = acc_s.values[sl].mean(axis=0)
            return UnitCalibration(
                gyro_bias=gyr[sl].mean(axis=0), acc_mean=acc_mean,
                gravity_norm=float(np.linalg.norm(acc_mean)),
                acc_noise_std=acc_s.values[sl].std(axis=0), gyro_noise_std=gyr[sl].std(axis=0),
                t0=float(t[a]), t1=float(t[stop - 1]))
    raise DataError(
        f"session '{session.name}': no {unit} standstill of at least {min_s:g} s found; record the thesis' "
        "5 s standstill at the start (ch.4.4) or lower min_s"
    )


def calibrate_standstill(session: Session, *,
                         min_s: float = 2.0,  # thesis ch.7.2: two-second setup standstill
                         max_s: float = 5.0,  # thesis ch.4.4: five seconds still at the start
                         units: tuple[str, ...] | None = None, **mask_kw) -> StandstillCalibration:
    """Estimate gyro bias, gravity vector and noise of each unit from its first standstill.

    Thesis ch.4.4: the user stands still for five seconds at the start; ch.7.2 uses two seconds. The
    first still run (see :func:`standstill_mask`; ``mask_kw`` passes its settings) lasting at least
    ``min_s`` seconds is used, truncated to its first ``max_s`` seconds.

    Parameters
    ----------
    units : units to calibrate; default every unit whose accelerometer and gyroscope are present.

    Raises
    ------
    MissingSensorError when no unit (or a requested unit) has accelerometer and gyroscope;
    DataError when a unit has no standstill of ``min_s`` seconds.
    """
    if units is None:
        units = tuple(u for u, names in UNIT_STREAMS.items() if session.has(*names))
        if not units:
            raise MissingSensorError(
                f"session '{session.name}' has no unit with both accelerometer and gyroscope; "
                "standstill calibration needs fAccelerometer+fGyroscope or wAccelerometer+wGyroscope"
            )
    cal = StandstillCalibration()
    for u in units:
        if u not in UNIT_STREAMS:
            raise DataError(f"calibrate_standstill: unknown unit '{u}'; use 'foot' or 'waist'")
        cal.units[u] = _unit_calibration(session, u, min_s=min_s, max_s=max_s, mask_kw=mask_kw)
        log.info("%s %s calibration: %s", session.name, u, cal.units[u].to_dict())
    return cal


def apply_calibration(session: Session, cal: StandstillCalibration, *, acc_scale: bool = False) -> Session:
    """Return a copy of ``session`` with each calibrated unit's gyroscope bias subtracted.

    The accelerometer keeps gravity (its rest mean is the gravity vector, not an offset: the unit's
    tilt is unknown, see docs/decisions/steps.md); with ``acc_scale=True`` it is rescaled so that the
    rest magnitude equals standard gravity (corrects a scale error such as 9.5 m/s^2 at rest).
    """
    out = session.copy()
    for unit, c in cal.units.items():
        acc_name, gyr_name = UNIT_STREAMS[unit]
        if gyr_name in out.streams:
            out.streams[gyr_name].values = out.streams[gyr_name].values - c.gyro_bias
        if acc_scale and acc_name in out.streams and c.gravity_norm > 0:
            out.streams[acc_name].values = out.streams[acc_name].values * (G / c.gravity_norm)
    return out
