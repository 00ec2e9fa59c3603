"""A synthetic walk with a PDR drift model, used by the aiding tests and experiment when no simulated
session is at hand.

The walk is a random sequence of straights, turns and stops; PDR errors are a per-user step-length scale
error plus per-step noise, and a heading bias plus a gyro-like drift (random walk of the drift rate)
plus per-step noise. This is a model of PDR *errors*, not of sensor signals.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.base import TrackResult


def synthetic_walk(
    seed: int = 0, *, length_m: float = 1000.0, step_freq_hz: float | None = None, stop_every_m: float = 150.0
) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Ground truth of a random walk: ``(steps, trajectory)``.

    ``steps`` has ``start_s``, ``end_s``, ``event_s``, ``length_m``, ``heading_rad`` (true values);
    ``trajectory`` has ``t``, ``x``, ``y``, ``z`` (row 0 = start, one row per step end, plus the
    position held during stops).
    """
    rng = np.random.default_rng(seed)
    f0 = step_freq_hz if step_freq_hz is not None else rng.uniform(1.6, 2.0)
    a, b = rng.uniform(0.3, 0.4), rng.uniform(-0.1, 0.05)  # this user's a*f - b (seed 001 eq. 23)
    t, x, y, h = 0.0, 0.0, 0.0, rng.uniform(-np.pi, np.pi)
    steps, traj = [], [(0.0, 0.0, 0.0, 0.0)]
    dist, next_stop = 0.0, stop_every_m * rng.uniform(0.5, 1.5)
    while dist < length_m:
        seg = rng.uniform(15.0, 80.0)
        turn = rng.choice([-1, 1]) * rng.uniform(np.radians(30), np.radians(120))
        n_turn = int(rng.integers(3, 8))
        seg_f = f0 * rng.uniform(0.9, 1.1)
        s = 0.0
        i = 0
        while s < seg and dist < length_m:
            f = seg_f * (1 + 0.03 * rng.standard_normal())
            d = 1.0 / f
            sl = max(a * f - b + 0.02 * rng.standard_normal(), 0.3)
            if i < n_turn:
                h += turn / n_turn
            h += np.radians(1.0) * rng.standard_normal()  # natural sway of the walking direction
            steps.append((t, t + d, t + d, sl, float((h + np.pi) % (2 * np.pi) - np.pi)))
            t += d
            x += sl * np.cos(h)
            y += sl * np.sin(h)
            traj.append((t, x, y, 0.0))
            s += sl
            dist += sl
            i += 1
        if dist >= next_stop and dist < length_m:
            t += rng.uniform(5.0, 20.0)  # a stop: the walker stands still
            traj.append((t, x, y, 0.0))
            next_stop += stop_every_m * rng.uniform(0.5, 1.5)
    st = pd.DataFrame(steps, columns=["start_s", "end_s", "event_s", "length_m", "heading_rad"])
    tr = pd.DataFrame(traj, columns=["t", "x", "y", "z"])
    return st, tr


def pdr_with_drift(
    steps: pd.DataFrame,
    seed: int = 0,
    *,
    scale_sigma: float = 0.06,
    length_noise: float = 0.04,
    heading_bias_deg: float = 5.0,
    drift_deg_per_min: float = 0.5,
    heading_noise_deg: float = 3.0,
) -> TrackResult:
    """A PDR track with realistic errors from true steps (lengths m, headings rad).

    The per-user length scale is 1 + N(0, ``scale_sigma``); per-step length noise is relative; the heading
    error is a constant bias N(0, ``heading_bias_deg``) plus a drift whose rate starts at
    N(0, ``drift_deg_per_min``) and random-walks, plus white per-step noise.
    """
    rng = np.random.default_rng(10_000 + seed)
    n = len(steps)
    tt = steps["end_s"].to_numpy(float)
    scale = 1.0 + scale_sigma * rng.standard_normal()
    lengths = steps["length_m"].to_numpy(float) * scale * (1 + length_noise * rng.standard_normal(n))
    rate = np.radians(drift_deg_per_min) / 60.0 * rng.standard_normal()
    dt = np.diff(np.r_[0.0, tt])
    rates = rate + np.cumsum(np.radians(drift_deg_per_min) / 60.0 * 0.05 * rng.standard_normal(n))
    drift = np.cumsum(rates * dt)
    herr = np.radians(heading_bias_deg) * rng.standard_normal() + drift
    headings = steps["heading_rad"].to_numpy(float) + herr + np.radians(heading_noise_deg) * rng.standard_normal(n)
    out = steps[["start_s", "end_s", "event_s"]].copy()
    out["length_m"] = lengths
    out["heading_rad"] = (headings + np.pi) % (2 * np.pi) - np.pi
    out["dz_m"] = 0.0
    xs = np.r_[0.0, np.cumsum(lengths * np.cos(headings))]
    ys = np.r_[0.0, np.cumsum(lengths * np.sin(headings))]
    traj = pd.DataFrame(
        {
            "t": np.r_[float(steps["start_s"].iloc[0]) if n else 0.0, tt],
            "x": xs,
            "y": ys,
            "z": np.zeros(n + 1),
        }
    )
    return TrackResult(
        out.reset_index(drop=True), traj, {"pipeline": "synthetic-drift", "seed": seed, "length_scale": scale}
    )


def position_errors(
    trajectory: pd.DataFrame,
    truth: pd.DataFrame,
    *,
    xcol: str = "x",
    ycol: str = "y",
) -> np.ndarray:
    """Horizontal error (m) of each trajectory row against the truth interpolated at its time."""
    t = trajectory["t"].to_numpy(float)
    tx = np.interp(t, truth["t"].to_numpy(float), truth["x"].to_numpy(float))
    ty = np.interp(t, truth["t"].to_numpy(float), truth["y"].to_numpy(float))
    return np.hypot(trajectory[xcol].to_numpy(float) - tx, trajectory[ycol].to_numpy(float) - ty)


def synthetic_waist_session(
    seed: int = 0,
    *,
    duration_s: float = 60.0,
    rate_hz: float = 100.0,
    speed_ms: float = 1.2,
    step_freq_hz: float = 1.9,
    gyro_bias_rads: float = 0.003,
):
    """A level waist IMU (FLU axes) walking straights and turns with stops: ``(Session, truth)``.

    The forward speed oscillates by +-0.1 m/s at the step frequency (the alternate acceleration pattern
    of seed 004 Sec. III-C) and ramps up/down over about two steps (1 s) at the start/end of each bout.
    Sensor noise: accelerometer 0.05 m/s^2, gyroscope 0.005 rad/s plus a constant bias, magnetometer 0.5 uT.
    ``truth`` has ``t``, ``x``, ``y``, ``z``, ``v``, ``yaw`` per sample.
    """
    from pdrlearn.io.frames import AxisFrame
    from pdrlearn.io.session import Session, Stream

    rng = np.random.default_rng(seed)
    n = int(duration_s * rate_hz)
    t = np.arange(n) / rate_hz
    # bouts: walk 8-20 s, stop 2-5 s
    walking = np.zeros(n, bool)
    k = int(1.5 * rate_hz)
    while k < n:
        w = int(rng.uniform(8.0, 20.0) * rate_hz)
        walking[k : k + w] = True
        k += w + int(rng.uniform(2.0, 5.0) * rate_hz)
    ramp = np.convolve(walking.astype(float), np.ones(int(rate_hz)) / rate_hz, mode="same")
    v = ramp * (speed_ms + 0.1 * np.sin(2 * np.pi * step_freq_hz * t))
    a_fwd = np.gradient(v, 1.0 / rate_hz)
    yaw_rate = np.zeros(n)
    k = 0
    while k < n:  # turns of 45-120 deg at 0.6 rad/s while walking, every 5-10 s
        k += int(rng.uniform(5.0, 10.0) * rate_hz)
        ang = rng.choice([-1, 1]) * rng.uniform(np.radians(45), np.radians(120))
        m = int(abs(ang) / 0.6 * rate_hz)
        yaw_rate[k : k + m] = np.sign(ang) * 0.6 * walking[k : k + m]
        k += m
    yaw = rng.uniform(-np.pi, np.pi) + np.cumsum(yaw_rate) / rate_hz
    x = np.cumsum(v * np.cos(yaw)) / rate_hz
    y = np.cumsum(v * np.sin(yaw)) / rate_hz
    a_lat = v * yaw_rate  # centripetal, body left
    acc = np.column_stack([a_fwd, a_lat, np.full(n, 9.8)]) + 0.05 * rng.standard_normal((n, 3))
    gyr = np.column_stack([np.zeros(n), np.zeros(n), yaw_rate]) + gyro_bias_rads + 0.005 * rng.standard_normal((n, 3))
    m_w = np.array([0.0, 22.0, -40.0])  # ENU field (uT): north and downward dip
    mag = np.column_stack(
        [
            np.cos(yaw) * m_w[0] + np.sin(yaw) * m_w[1],
            -np.sin(yaw) * m_w[0] + np.cos(yaw) * m_w[1],
            np.full(n, m_w[2]),
        ]
    ) + 0.5 * rng.standard_normal((n, 3))
    ses = Session(
        f"synthetic-waist-{seed}",
        streams={
            "wAccelerometer": Stream("wAccelerometer", t, acc),
            "wGyroscope": Stream("wGyroscope", t, gyr),
            "wMagneticField": Stream("wMagneticField", t, mag),
        },
        frames={"waist": AxisFrame(x="forward", y="left", z="up")},
    )
    truth = pd.DataFrame({"t": t, "x": x, "y": y, "z": np.zeros(n), "v": v, "yaw": yaw})
    ses.trajectory = truth[["t", "x", "y", "z"]]
    return ses, truth
