"""Step windows and feature recipes, numpy only.

:func:`step_window` builds one step's window ``(len(channels), n_samples)`` in the channel layout that
the bundle's manifest records (``features.channels``), the same construction as
:func:`pdrlearn.features.step_windows` (levelled, heading-aligned, gravity removed, resampled).
:func:`compute_features` evaluates a feature *recipe* written by the exporter: a list of
``["peak", signal, stat]``, ``["segments", signal, n_segments]``, ``["force", stat, zero_fraction]``,
``["yaw_sign"]``, ``["yaw", stat]`` items whose columns are concatenated in order.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.runtime import _kernels as K

#: source streams of each channel group (the PLASYS file names, thesis ch. 4.3.3)
GROUP_STREAMS = {
    "foot_acc": ("fAccelerometer",),
    "foot_gyr": ("fGyroscope",),
    "force": ("fForceA", "fForceB"),
    "waist_acc": ("wAccelerometer",),
    "waist_gyr": ("wGyroscope",),
    "waist_baro": ("wBarometer",),
}


def _segment(t: np.ndarray, v: np.ndarray, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
    i0 = max(int(np.searchsorted(t, t0, side="right")) - 1, 0)
    i1 = min(int(np.searchsorted(t, t1, side="left")) + 1, len(t))
    return t[i0:i1], v[i0:i1]


def box_filter(v: np.ndarray, width: int) -> np.ndarray:
    """Centred moving mean of odd ``width`` along axis 0, edges repeated (``uniform_filter1d`` with
    ``mode="nearest"``)."""
    h = width // 2
    p = np.concatenate([np.repeat(v[:1], h, axis=0), v, np.repeat(v[-1:], h, axis=0)], axis=0)
    c = np.concatenate([np.zeros((1,) + v.shape[1:]), np.cumsum(p, axis=0)], axis=0)
    return (c[width:] - c[:-width]) / width


def _interp(tq: np.ndarray, t: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Resample the columns of ``v`` at ``tq``; when downsampling, a box anti-alias filter over one output
    interval first (as the PLASYS firmware's 5-sample mean, thesis ch. 4.3.2)."""
    if len(tq) > 1 and len(t) > 2:
        width = int(round((tq[1] - tq[0]) * (len(t) - 1) / float(t[-1] - t[0])))  # mean spacing
        width = 2 * (width // 2) + 1
        if width > 1:
            v = box_filter(v, width)
    return np.stack([np.interp(tq, t, v[:, j]) for j in range(v.shape[1])], axis=0)


def foot_levelled(t, acc, gyr, forward_s, *, rest_search_s: float, heading: str):
    """Foot acceleration (gravity removed) and rate in the step frame, and |acc| (see features/windows)."""
    n = acc.shape[0]
    fs = (n - 1) / float(t[-1] - t[0]) if n > 1 else 1.0  # mean rate over the step
    m = max(2, min(int(round(rest_search_s * fs)), n // 4 + 1))
    k0 = K.rest_index(acc, gyr, 0, m)
    k1 = K.rest_index(acc, gyr, n - m, n)
    h = max(0, int(round(0.02 * fs)))
    g0 = acc[max(k0 - h, 0) : k0 + h + 1].mean(axis=0)
    g1 = acc[max(k1 - h, 0) : k1 + h + 1].mean(axis=0)
    r0 = K.gravity_rotation(g0)
    if gyr is not None:
        rot = K.correct_tilt_drift(K.propagate_attitude(gyr, np.diff(t), k0, r0), g1, k0, k1)
    else:
        rot = np.broadcast_to(r0, (n, 3, 3))
    a_lev = np.einsum("kij,kj->ki", rot, acc)
    a_lev[:, 2] -= float(np.linalg.norm(g0))
    ref = (rot[k0] @ forward_s)[:2]
    if np.linalg.norm(ref) < 0.1:
        raise DataError(
            "foot unit: the declared forward axis points (nearly) vertically at rest; "
            "check the foot frame of the bundle"
        )
    ref = ref / np.linalg.norm(ref)
    yaw = K.heading_rotation(K.principal_horizontal_axis(a_lev, ref) if heading == "pca" else ref)
    g_out = None if gyr is None else np.einsum("kij,kj->ki", rot, gyr) @ yaw.T
    return a_lev @ yaw.T, g_out, np.linalg.norm(acc, axis=1)


def waist_levelled(acc, gyr, forward_s):
    g = acc.mean(axis=0)
    r = K.gravity_rotation(g)
    ref = (r @ forward_s)[:2]
    if np.linalg.norm(ref) < 0.1:
        raise DataError("waist unit: the declared forward axis points (nearly) vertically; check the frame")
    rr = K.heading_rotation(ref / np.linalg.norm(ref)) @ r
    a = acc @ rr.T
    a[:, 2] -= float(np.linalg.norm(g))
    return a, (None if gyr is None else gyr @ rr.T)


def step_window(
    streams: dict[str, tuple[np.ndarray, np.ndarray]],
    t0: float,
    t1: float,
    *,
    channels: list[str],
    forward: dict[str, np.ndarray],
    n_samples: int = 40,
    heading: str = "pca",
    rest_search_s: float = 0.3,
) -> np.ndarray:
    """One step's window ``(len(channels), n_samples)``; channels of absent sensors are NaN.

    Parameters
    ----------
    streams : sensor name -> ``(t (n,) s, values (n, k))`` covering ``[t0, t1]``.
    t0, t1 : step start and end (s).
    channels : channel layout (manifest ``features.channels``; first is ``t_s``).
    forward : placement -> sensor-frame vector pointing body-forward (from the declared frame).
    """
    ci = {c: i for i, c in enumerate(channels)}
    X = np.full((len(channels), n_samples), np.nan)
    tg = t0 + (t1 - t0) * np.linspace(0.0, 1.0, n_samples)
    X[0] = tg - t0
    has = {g for g, names in GROUP_STREAMS.items() if all(nm in streams for nm in names)}
    if "foot_acc" in has and "foot" in forward:
        ta, acc = _segment(*streams["fAccelerometer"], t0, t1)
        gyr = _interp(ta, *_segment(*streams["fGyroscope"], t0, t1)).T if "foot_gyr" in has else None
        a, g, an = foot_levelled(ta, acc, gyr, forward["foot"], rest_search_s=rest_search_s, heading=heading)
        c = ci["foot_acc_x"]
        X[c : c + 3] = _interp(tg, ta, a)
        X[ci["foot_acc_norm"]] = _interp(tg, ta, an[:, None])[0]
        if g is not None:
            c = ci["foot_gyr_x"]
            X[c : c + 3] = _interp(tg, ta, g)
    if "force" in has:
        for j, name in enumerate(("fForceA", "fForceB")):
            tf, f = _segment(*streams[name], t0, t1)
            X[ci["force_a"] + j] = _interp(tg, tf, f)[0]
    if "waist_acc" in has and "waist" in forward:
        tw, wacc = _segment(*streams["wAccelerometer"], t0, t1)
        wgyr = _interp(tw, *_segment(*streams["wGyroscope"], t0, t1)).T if "waist_gyr" in has else None
        a, g = waist_levelled(wacc, wgyr, forward["waist"])
        c = ci["waist_acc_x"]
        X[c : c + 3] = _interp(tg, tw, a)
        if g is not None:
            c = ci["waist_gyr_x"]
            X[c : c + 3] = _interp(tg, tw, g)
    if "waist_baro" in has:
        tb, b = _segment(*streams["wBarometer"], t0, t1)
        X[ci["waist_baro"]] = np.interp(tg, tb, b[:, 0]) - np.interp(t0, tb, b[:, 0])
    return X


def signal(W: np.ndarray, name: str, signals: dict, channel_index: dict) -> np.ndarray:
    """Derived signal (rows = steps) from the manifest's signal table ``name -> [[channels], sign]``."""
    chans, sign = signals[name][0], float(signals[name][1])
    out = W[:, channel_index[chans[0]], :].copy()
    for c in chans[1:]:
        out += W[:, channel_index[c], :]
    return sign * out


def compute_features(
    W: np.ndarray, recipe: list, *, signals: dict, channel_index: dict, cache: dict | None = None
) -> np.ndarray:
    """Feature matrix ``(n_steps, n_features)`` of windows ``W (n_steps, channels, samples)``.

    ``cache`` (optional, one dict per ``W``) shares signals and statistics between the recipes of the
    several models that classify the same step.
    """
    t = W[:, 0, :]
    cols: list[np.ndarray] = []
    c = {} if cache is None else cache

    def sig(name):
        key = ("sig", name)
        if key not in c:
            c[key] = signal(W, name, signals, channel_index)
        return c[key]

    def peaks(name):
        key = ("peak", name)
        if key not in c:
            c[key] = K.peak_stats(sig(name), t)
        return c[key]

    def segments(name, n):
        key = ("seg", name, n)
        if key not in c:
            c[key] = K.segment_stats(sig(name), t, n)
        return c[key]

    def force(zero_fraction):
        key = ("force", zero_fraction)
        if key not in c:
            c[key] = K.force_stats(sig("force"), t, zero_fraction=zero_fraction)
        return c[key]

    for item in recipe:
        op = item[0]
        if op == "peak":
            cols.append(peaks(item[1])[item[2]][:, None])
        elif op == "segments":
            cols.append(segments(item[1], int(item[2])))
        elif op == "force":
            cols.append(force(float(item[2]))[item[1]][:, None])
        elif op == "yaw_sign":
            dt = K._gradient(t)
            cols.append((np.sum(sig("waist_yaw") * dt, axis=1) > 0).astype(float)[:, None])
        elif op == "yaw":
            ps = peaks("waist_yaw")
            val = {
                "amplitude": 0.5 * ps["range"],
                "duration": ps["duration"],
                "left": ps["t_max"],
                "right": ps["duration"] - ps["t_max"],
            }[item[1]]
            cols.append(val[:, None])
        elif op == "rule":
            cols.append(rule_feature(W, item[1], sig, peaks)[:, None])
        elif op == "signals":  # DTW step signals (steps, len(names), samples)
            return np.stack([sig(n) for n in item[1]], axis=1)
        else:
            raise DataError(f"bundle feature recipe: unknown operation {op!r}; re-export with this version")
    F = np.hstack(cols)
    if not np.isfinite(F).all():
        raise DataError("step features are NaN: the stream lacks a sensor the model needs")
    return F


def rule_feature(W: np.ndarray, name: str, sig, peaks) -> np.ndarray:
    """Named heuristic rule feature ``"<signal>:<statistic>"`` (thesis Tables 22-24, 29-31, eq. 31-32)."""
    t = W[:, 0, :]
    if name == "foot_acc_fwd:range_x_air_time":  # thesis Table 30 #3
        return peaks("foot_acc_fwd")["range"] * K.force_stats(sig("force"), t)["air_time"]
    s, _, stat = name.partition(":")
    if stat == "abs_peak_asym":
        return np.abs(peaks(s)["peak_asym"])
    if stat == "half_balance":  # thesis eq. 31: halves of the step's motion (cumulative |x| at half)
        x = sig(s)
        cum = np.cumsum(np.abs(x), axis=1)
        total = cum[:, -1]
        split = np.argmax(cum >= 0.5 * total[:, None], axis=1)
        first_mask = np.arange(x.shape[1])[None, :] <= split[:, None]
        first = np.sum(np.where(first_mask, x, 0.0), axis=1)
        second = np.sum(np.where(first_mask, 0.0, x), axis=1)
        return np.where(total > 0, (first - second) / np.where(total > 0, total, 1.0), 0.0)
    if stat == "step_probability":  # thesis eq. 32, acceleration read in g
        x = sig(s)
        return np.clip((100.0 - np.abs(x.max(1) + x.min(1)) / 9.80665 * 20.0) / 100.0, 0.0, 1.0)
    if stat in ("air_time", "time_to_peak", "peak_mean_4", "contact_force_2", "takeoff_force"):
        return K.force_stats(sig(s), t)[stat]
    ps = peaks(s)
    if stat in ps:
        return ps[stat]
    yaw = {
        "amplitude": 0.5 * ps["range"],
        "left": ps["t_max"],
        "right": ps["duration"] - ps["t_max"],
        "left_minus_right": 2 * ps["t_max"] - ps["duration"],
    }
    if stat in yaw:
        return yaw[stat]
    raise DataError(f"bundle rule feature {name!r} is unknown to this runtime; re-export the bundle")
