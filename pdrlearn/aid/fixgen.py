"""Fix generators from a ground-truth trajectory: GNSS (noise matched to the reported accuracy, outages,
indoor multipath bias), beacon/landmark proximity fixes and a precise infrastructure (camera) stream;
plus an NMEA 0183 writer so generated fixes can go through the same reader as real logs.

All generators take a trajectory table (``t`` in s, or ``timestamp`` in ms as a session folder's trajectory.csv,
decision D40; ``x`` east / ``y`` north in m) and return a fix table
(``t``, ``x``, ``y``, ``accuracy_m`` and, when ``origin`` is given, ``lat``/``lon``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.aid.fixes import DEFAULT_UERE_M, RADIUS68_PER_SIGMA, nmea_checksum
from pdrlearn.aid.geo import enu_to_geodetic
from pdrlearn.errors import DataError


def _truth(trajectory: pd.DataFrame, what: str = "trajectory") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    if trajectory is not None and "t" not in trajectory.columns and "timestamp" in trajectory.columns:
        # decision D40: a session folder's trajectory.csv (pdrlearn.sim) has timestamp in ms
        trajectory = trajectory.assign(t=pd.to_numeric(trajectory["timestamp"], errors="coerce") / 1000.0)
    if trajectory is None or not {"t", "x", "y"} <= set(trajectory.columns) or len(trajectory) < 2:
        raise DataError(f"{what}: need a ground-truth table with columns t (s; or timestamp in ms, as a session "
                        "folder's trajectory.csv), x, y and at least 2 rows")
    t, x, y = (trajectory[c].to_numpy(float) for c in ("t", "x", "y"))
    if not (np.isfinite(t).all() and np.isfinite(x).all() and np.isfinite(y).all()):
        raise DataError(f"{what}: NaN in t/x/y; interpolate or drop those rows first")
    return t, x, y


def _in_intervals(t: np.ndarray, intervals) -> np.ndarray:
    m = np.zeros(t.shape, bool)
    for a, b in intervals or ():
        m |= (t >= a) & (t < b)
    return m


def _with_geo(df: pd.DataFrame, origin) -> pd.DataFrame:
    if origin is not None:
        df["lat"], df["lon"] = enu_to_geodetic(df["x"].to_numpy(), df["y"].to_numpy(), *origin)
    return df


def gnss_fixes(
    trajectory: pd.DataFrame,
    *,
    rate_hz: float = 1.0,
    accuracy_m: float = 5.0,
    accuracy_spread: float = 0.3,
    correlation_s: float = 10.0,
    outages=(),
    indoor=(),
    indoor_accuracy_factor: float = 3.0,
    multipath_bias_m: float = 10.0,
    outage_probability: float = 0.0,
    origin: tuple[float, float] | None = None,
    seed: int | None = 0,
) -> pd.DataFrame:
    """Simulated GNSS fixes along a ground-truth trajectory.

    Parameters
    ----------
    rate_hz : fix rate (Hz); default 1 Hz, our choice (a common phone fix rate; seed 001 Sec. 2.2.6 says
        only that GNSS updates at 4 Hz at most).
    accuracy_m : median reported accuracy (m, 68 % horizontal radius) in open sky.
    accuracy_spread : log-normal spread of the reported accuracy from fix to fix.
    correlation_s : correlation time (s) of the position error (first-order Gauss-Markov); 0 = white.
        The error's per-axis standard deviation equals the one implied by the reported accuracy.
    outages : ``[(t0, t1), ...]`` (s) without any fix.
    indoor : ``[(t0, t1), ...]`` (s) indoors: reported accuracy times ``indoor_accuracy_factor`` and a
        multipath bias of ``multipath_bias_m`` (m) in a random direction per interval, not covered by the
        reported accuracy.
    outage_probability : probability that a fix is missing (random dropouts).
    origin : (lat, lon) degrees of the local frame's origin; adds ``lat``/``lon`` columns.
    seed : random seed.
    """
    if rate_hz <= 0 or accuracy_m <= 0:
        raise DataError(f"gnss_fixes: rate_hz ({rate_hz}) and accuracy_m ({accuracy_m}) must be > 0")
    t, x, y = _truth(trajectory)
    rng = np.random.default_rng(seed)
    tf = np.arange(np.ceil(t[0] * rate_hz), np.floor(t[-1] * rate_hz) + 1) / rate_hz
    n = tf.size
    acc = accuracy_m * np.exp(accuracy_spread * rng.standard_normal(n))
    ind = _in_intervals(tf, indoor)
    acc[ind] *= indoor_accuracy_factor
    sigma = acc / RADIUS68_PER_SIGMA
    # unit-variance Gauss-Markov sequence, scaled by each fix's sigma
    phi = np.exp(-1.0 / (rate_hz * correlation_s)) if correlation_s > 0 else 0.0
    w = rng.standard_normal((n, 2))
    e = np.empty((n, 2))
    if n:
        e[0] = w[0]
    for i in range(1, n):
        e[i] = phi * e[i - 1] + np.sqrt(1.0 - phi * phi) * w[i]
    ex, ey = e[:, 0] * sigma, e[:, 1] * sigma
    for a, b in indoor or ():
        ang = rng.uniform(-np.pi, np.pi)
        m = (tf >= a) & (tf < b)
        ex[m] += multipath_bias_m * np.cos(ang)
        ey[m] += multipath_bias_m * np.sin(ang)
    keep = ~_in_intervals(tf, outages) & (rng.random(n) >= outage_probability)
    df = pd.DataFrame(
        {
            "t": tf,
            "x": np.interp(tf, t, x) + ex,
            "y": np.interp(tf, t, y) + ey,
            "accuracy_m": acc,
            "indoor": ind,
        }
    )[keep].reset_index(drop=True)
    return _with_geo(df, origin)


def infrastructure_fixes(
    trajectory: pd.DataFrame,
    *,
    rate_hz: float = 10.0,
    sigma_m: float = 0.05,
    seed: int | None = 0,
    origin: tuple[float, float] | None = None,
) -> pd.DataFrame:
    """A precise external positioning stream (e.g. ceiling cameras) that a tracker can query.

    ``sigma_m`` is the per-axis standard deviation; the default 0.05 m matches the second EKF's
    Q_c = diag(0.0025, 0.0025) m^2 (seed 004 Sec. V).
    """
    t, x, y = _truth(trajectory)
    rng = np.random.default_rng(seed)
    tf = np.arange(np.ceil(t[0] * rate_hz), np.floor(t[-1] * rate_hz) + 1) / rate_hz
    df = pd.DataFrame(
        {
            "t": tf,
            "x": np.interp(tf, t, x) + sigma_m * rng.standard_normal(tf.size),
            "y": np.interp(tf, t, y) + sigma_m * rng.standard_normal(tf.size),
            "accuracy_m": np.full(tf.size, sigma_m * RADIUS68_PER_SIGMA),
        }
    )
    return _with_geo(df, origin)


def landmark_fixes(
    trajectory: pd.DataFrame,
    landmarks,
    *,
    radius_m: float = 1.5,
    accuracy_m: float | None = None,
    min_interval_s: float = 10.0,
    origin: tuple[float, float] | None = None,
) -> pd.DataFrame:
    """Beacon/landmark fixes: when the walker passes within ``radius_m`` of a landmark, one fix at the
    landmark's position (at the closest approach), at most one per landmark every ``min_interval_s``.

    ``landmarks`` is an (n, 2) array of east/north positions (m). The reported accuracy defaults to the
    detection radius (the true position is anywhere within it).
    """
    t, x, y = _truth(trajectory)
    lm = np.asarray(landmarks, float).reshape(-1, 2)
    acc = radius_m if accuracy_m is None else accuracy_m
    rows = []
    for k, (lx, ly) in enumerate(lm):
        d = np.hypot(x - lx, y - ly)
        inside = d <= radius_m
        if not inside.any():
            continue
        # passes = runs of consecutive samples inside the radius; the fix at the closest sample of each pass
        edges = np.flatnonzero(np.diff(np.r_[0, inside.astype(int), 0]))
        last = -np.inf
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            i = a + int(np.argmin(d[a:b]))
            if t[i] - last >= min_interval_s:
                rows.append((t[i], lx, ly, acc, k))
                last = t[i]
    df = pd.DataFrame(rows, columns=["t", "x", "y", "accuracy_m", "landmark"]).sort_values("t")
    return _with_geo(df.reset_index(drop=True), origin)


def _nmea_deg(value: float, lat: bool) -> tuple[str, str]:
    hemi = ("N" if value >= 0 else "S") if lat else ("E" if value >= 0 else "W")
    v = abs(value)
    d = int(v)
    m = (v - d) * 60.0
    if round(m, 5) >= 60.0:
        d, m = d + 1, 0.0
    return (f"{d:02d}{m:08.5f}" if lat else f"{d:03d}{m:08.5f}"), hemi


def _sentence(body: str) -> str:
    return f"${body}*{nmea_checksum(body):02X}"


def write_nmea(
    fixes: pd.DataFrame,
    path,
    *,
    utc_start_s: float = 36000.0,
    uere_m: float = DEFAULT_UERE_M,
    date: str = "150326",
) -> Path:
    """Write fixes (``t``, ``lat``, ``lon``, ``accuracy_m``) as GGA + RMC sentences.

    ``t`` maps to UTC time of day ``utc_start_s + t - t[0]``; HDOP = accuracy / ``uere_m``.
    """
    if not {"t", "lat", "lon", "accuracy_m"} <= set(fixes.columns):
        raise DataError("write_nmea: the fix table needs t, lat, lon, accuracy_m (pass origin= to the generator)")
    path = Path(path)
    lines = []
    t0 = float(fixes["t"].iloc[0]) if len(fixes) else 0.0
    for r in fixes.itertuples():
        tod = (utc_start_s + r.t - t0) % 86400.0
        hh, mm = int(tod // 3600), int(tod % 3600 // 60)
        ts = f"{hh:02d}{mm:02d}{tod % 60:05.2f}"
        la, ns = _nmea_deg(r.lat, True)
        lo, ew = _nmea_deg(r.lon, False)
        hdop = max(r.accuracy_m / uere_m, 0.1)
        lines.append(_sentence(f"GPGGA,{ts},{la},{ns},{lo},{ew},1,08,{hdop:.2f},100.0,M,47.0,M,,"))
        lines.append(_sentence(f"GPRMC,{ts},A,{la},{ns},{lo},{ew},0.0,0.0,{date},,,A"))
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text("\r\n".join(lines) + "\r\n", encoding="ascii")
    tmp.replace(path)
    return path
