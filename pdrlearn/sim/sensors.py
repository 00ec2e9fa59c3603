"""Sensor error models of the PLASYS units (thesis ch.4) applied to the ideal 100 Hz readings.

Noise standard deviations are the thesis' stationary statistics. Those were measured on the 20 Hz
outputs, which the foot firmware obtains by averaging five 100 Hz samples (thesis ch.4.2.3); the 100 Hz
white noise is therefore ``sd * sqrt(5)`` so that the 20 Hz output reproduces the tables. Constant biases
are drawn per session with the tables' mean offsets as standard deviations.

Accelerometer scale factors are a property of the DEVICE (decision S22 in docs/decisions/simulator.md):
the unit's own scale error is drawn once per unit (``device_rng``, the user's unit in
:func:`pdrlearn.sim.simulate`) and each session adds a small turn-on/temperature term
(``scale_session_sd``). Without ``device_rng`` the whole scale error is drawn per session (the model
before S22, kept for A/B comparisons with the knob ``device_errors=False``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pdrlearn.sim.kernels import STANDARD_GRAVITY, quantize

FIRMWARE_AVERAGE = 5  # 100 Hz samples averaged per 20 Hz output (thesis ch.4.2.3)


@dataclass(frozen=True)
class ImuErrorModel:
    """Noise (sd of the 20 Hz output), bias scale, range and resolution of one accelerometer/gyroscope."""

    noise_sd: tuple[float, float, float]
    bias_sd: tuple[float, float, float]
    full_scale: float
    lsb: float | None = None
    scale_sd: float = 0.0  # per-DEVICE scale-factor error (fraction, sd), decision S22
    bias_walk: float = 0.0  # bias random walk (unit / sqrt(s)): slow drift during a session
    scale_session_sd: float = 0.0  # per-SESSION change of the scale factor (fraction, sd), decision S22


# thesis Table 4: foot accelerometer deviation (m/s^2) and mean offsets from (0, g, 0)
FOOT_ACC = ImuErrorModel(
    noise_sd=(0.0191, 0.0193, 0.0223),
    bias_sd=(0.0414, 9.8224 - STANDARD_GRAVITY, 0.4475),
    full_scale=16 * 9.81,  # +-16 g (thesis ch.4.2.1.1)
    lsb=9.81 / 256,  # thesis eq. 24: 256 counts per g
    scale_sd=0.003,  # total-acceleration mean 9.83 vs 9.807 m/s^2 (thesis Table 4): ~0.3 %
    # ADXL345 data sheet (thesis ref. [32]): sensitivity change due to temperature +-0.01 %/degC; a unit
    # 5 degC warmer or colder than in its last session (sd) -> 0.05 % (decision S22)
    scale_session_sd=0.0005,
)
# thesis Table 6: foot gyroscope deviation and mean (rad/s); 2000 dps range (thesis ch.4.2.1.2)
FOOT_GYR = ImuErrorModel(
    noise_sd=(0.0100, 0.0101, 0.0107),
    bias_sd=(0.0018, 0.0024, 0.0071),
    full_scale=np.radians(2000.0),
    lsb=np.radians(0.070),  # L3G4200D at 2000 dps: 70 mdps/digit (data sheet, thesis ref. [111])
    # the thesis notes a small drift over time (ch.4.2.1.2); no figure is given: docs/decisions S12
    bias_walk=2e-4,
)
# thesis Table 12: waist accelerometer deviation and mean offsets (gravity on the x axis in that test)
WAIST_ACC = ImuErrorModel(
    noise_sd=(0.0175, 0.0209, 0.0323),
    bias_sd=(9.8869 - STANDARD_GRAVITY, 0.2201, 0.1675),
    full_scale=16 * 9.81,
    scale_sd=0.003,
    # MPU-6500 family data sheet (thesis ref. [55]): sensitivity change vs temperature +-0.026 %/degC;
    # 5 degC sd between sessions -> 0.13 % (decision S22)
    scale_session_sd=0.0013,
)
# thesis Table 14: waist gyroscope deviation and mean (rad/s)
WAIST_GYR = ImuErrorModel(
    noise_sd=(0.0011, 0.0009, 0.0008),
    bias_sd=(0.0014, 0.0005, 0.0004),
    full_scale=np.radians(2000.0),
    bias_walk=5e-5,  # smaller drift than the foot gyroscope (thesis ch.4.3.1.2); docs/decisions S12
)
MAG_NOISE_SD = (0.6835, 0.7389, 0.7351)  # uT, thesis Table 16
MAG_LSB = 0.15  # uT, AK8963 sensitivity (thesis Table 15)
MAG_RANGE = 4900.0  # uT (thesis Table 15)
BARO_NOISE_SD = 0.0157  # hPa, thesis Table 18 (deviation)
BARO_P0_RANGE = (996.5423, 1028.9545)  # hPa, thesis Table 18 (30-day minimum and maximum)
BARO_LSB = 0.0018  # hPa = 0.18 Pa resolution (thesis Table 17)
BUILDING_ALTITUDE_M = 75.0  # the thesis' test building is 75 m above sea level (thesis ch.4.3.1.4)
FORCE_RANGE_N = 440.0  # Tekscan A201 force range (thesis Table 7)


def device_scale(model: ImuErrorModel, device_rng: np.random.Generator) -> np.ndarray:
    """The unit's own per-axis scale factors (1 + error), drawn once per device (decision S22)."""
    return 1.0 + device_rng.normal(0.0, 1.0, 3) * model.scale_sd


def imu_readout(
    ideal: np.ndarray,
    model: ImuErrorModel,
    rng: np.random.Generator,
    *,
    noise: bool,
    device_rng: np.random.Generator | None = None,
    bias_tau_s: float | None = None,
) -> tuple[np.ndarray, dict]:
    """Apply scale error, bias, white noise, saturation and quantisation to 100 Hz ideal readings (n, 3).

    Parameters
    ----------
    rng : the session's randomness (biases, noise, the per-session scale term)
    device_rng : the unit's own randomness: its scale factors (``model.scale_sd``) are drawn from it and
        the session adds ``model.scale_session_sd`` (decision S22). None: the whole scale error
        (``model.scale_sd``) is drawn per session (the model before S22).
    bias_tau_s : decision S110: the bias drift is a first-order Gauss-Markov process of this correlation time (s)
        driven by the same increments (``model.bias_walk``), bounded at a stationary sd of ``bias_walk *
        sqrt(tau / 2)``; None (default): S12's unbounded random walk

    Returns the readings and a dict of the drawn errors (for the session metadata).
    """
    if not noise:
        return ideal.copy(), {"bias": [0.0, 0.0, 0.0], "scale": [1.0, 1.0, 1.0]}
    bias = rng.normal(0.0, 1.0, 3) * np.asarray(model.bias_sd)
    z = rng.normal(0.0, 1.0, 3)  # the same draws as before S22, so the other session errors are unchanged
    if device_rng is None:
        scale = 1.0 + z * model.scale_sd
    else:
        scale = device_scale(model, device_rng) * (1.0 + z * model.scale_session_sd)
    sd = np.asarray(model.noise_sd) * np.sqrt(FIRMWARE_AVERAGE)
    out = ideal * scale + bias + rng.normal(0.0, 1.0, ideal.shape) * sd
    if model.bias_walk > 0:  # 100 Hz samples: increments of sd bias_walk * sqrt(0.01 s)
        steps = rng.normal(0.0, model.bias_walk * 0.1, ideal.shape)
        out += np.cumsum(steps, axis=0) if bias_tau_s is None else gauss_markov(steps, 0.01, bias_tau_s)
    out = np.clip(out, -model.full_scale, model.full_scale)
    if model.lsb:
        out = quantize(out, model.lsb)
    return out, {"bias": [float(b) for b in bias], "scale": [float(s) for s in scale]}


def gauss_markov(steps: np.ndarray, dt: float, tau_s: float) -> np.ndarray:
    """Decision S110: the first-order Gauss-Markov process ``b_k = exp(-dt / tau) b_(k-1) + steps_k`` (from 0) along
    axis 0: S12's random walk (``np.cumsum(steps)``) pulled back to 0 with correlation time ``tau_s``; with
    increments of sd ``q sqrt(dt)`` its stationary sd is ``q sqrt(tau / 2)`` (the walk's sd at t = tau / 2)."""
    from scipy.signal import lfilter

    return lfilter([1.0], [1.0, -float(np.exp(-dt / tau_s))], steps, axis=0)


def magnetometer_readout(
    b_sensor: np.ndarray, rng: np.random.Generator, *, noise: bool, hard_iron_sd: float = 2.0
) -> tuple[np.ndarray, dict]:
    """Add a hard-iron offset, Table 16 noise and Table 15 resolution to the field in the sensor frame (uT)."""
    if not noise:
        return b_sensor.copy(), {"hard_iron_ut": [0.0, 0.0, 0.0]}
    offset = rng.normal(0.0, hard_iron_sd, 3)
    out = (
        b_sensor + offset + rng.normal(0.0, 1.0, b_sensor.shape) * np.asarray(MAG_NOISE_SD) * np.sqrt(FIRMWARE_AVERAGE)
    )
    return quantize(np.clip(out, -MAG_RANGE, MAG_RANGE), MAG_LSB), {"hard_iron_ut": [float(v) for v in offset]}


def field_disturbance(
    pos: np.ndarray, rng: np.random.Generator, amplitude_ut: float, spacing_m: float = 4.0, width_m: float = 1.0
) -> np.ndarray:
    """Smooth indoor field disturbances (uT, ENU) along the walked positions ``pos`` (n, 3).

    Gaussian blobs of random vector amplitude (sd ``amplitude_ut``) every ``spacing_m`` metres of path.
    """
    out = np.zeros_like(pos)
    if amplitude_ut <= 0 or len(pos) < 2:
        return out
    seg = np.linalg.norm(np.diff(pos[:, :2], axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n_blobs = int(s[-1] // spacing_m) + 1
    at = np.searchsorted(s, (np.arange(n_blobs) + rng.random(n_blobs)) * spacing_m).clip(0, len(pos) - 1)
    centres = pos[at] + np.column_stack([rng.normal(0.0, 1.0, (n_blobs, 2)), np.zeros(n_blobs)])
    amps = rng.normal(0.0, amplitude_ut, (n_blobs, 3))
    from scipy.spatial import cKDTree

    # decision S126: each blob's candidates from a k-d tree (radius 4 w, a superset), then the same exact test on them;
    # one blob's at a time (all blobs' lists at once held 1.0 GB for a 4 h shift walking one corridor)
    tree = cKDTree(pos)
    for c, a in zip(centres, amps, strict=True):
        rows = np.asarray(tree.query_ball_point(c, 4 * width_m * (1 + 1e-9) + 1e-12, return_sorted=True), dtype=np.intp)
        d2 = np.sum((pos[rows] - c) ** 2, axis=1)
        near = rows[d2 < (4 * width_m) ** 2]
        out[near] += np.exp(-0.5 * d2[d2 < (4 * width_m) ** 2] / width_m**2)[:, None] * a
    return out


def barometer_readout(
    pressure: np.ndarray, t: np.ndarray, rng: np.random.Generator, *, noise: bool, drift_hpa_per_h: float
) -> tuple[np.ndarray, dict]:
    """Add a linear weather drift, Table 18 noise and Table 17 resolution to the pressure (hPa)."""
    if not noise:
        return pressure.copy(), {"drift_hpa_per_h": 0.0}
    slope = rng.normal(0.0, drift_hpa_per_h)
    out = pressure + slope * (t - t[0]) / 3600.0
    out = out + rng.normal(0.0, BARO_NOISE_SD * np.sqrt(FIRMWARE_AVERAGE), pressure.shape)
    return quantize(out, BARO_LSB), {"drift_hpa_per_h": float(slope)}


def force_readout(load_n: np.ndarray, rng: np.random.Generator, *, noise: bool) -> np.ndarray:
    """Force-sensor reading (N): relative noise from thesis Table 8, 0 when unloaded, clipped to Table 7 range.

    Table 8: the deviation is 3 % of the mean at 3 kg (29.4 N) and 10 % at 0.5 kg (4.9 N); the relative
    deviation is interpolated in log-force between those two points.
    """
    out = np.clip(load_n, 0.0, FORCE_RANGE_N)
    if not noise:
        return out
    f = np.maximum(out, 1e-9)
    rel = np.clip(0.10 - (0.10 - 0.031) * np.log(f / 4.9) / np.log(29.4 / 4.9), 0.03, 0.10)
    noisy = out * (1.0 + rel * np.sqrt(FIRMWARE_AVERAGE) * rng.normal(0.0, 1.0, out.shape))
    return np.where(out > 0, np.clip(noisy, 0.0, FORCE_RANGE_N), 0.0)
