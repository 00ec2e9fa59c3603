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
from pdrlearn.kernels import stats as K
from pdrlearn.kernels.window import available_groups, fill_step_window


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
    X = np.full((len(channels), n_samples), np.nan)
    fill_step_window(X, streams, t0, t1, channel_index={c: i for i, c in enumerate(channels)},
                     available=available_groups(streams), forward=forward, rest_search_s=rest_search_s,
                     heading=heading)
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
            cols.append(K.positive_net_rotation(sig("waist_yaw"), t)[:, None])
        elif op == "yaw":
            cols.append(K.yaw_stats(peaks("waist_yaw"))[item[1]][:, None])
        elif op == "rule":
            cols.append(rule_feature(W, item[1], sig, peaks)[:, None])
        elif op == "signals":  # DTW step signals (steps, len(names), samples)
            return np.stack([sig(n) for n in item[1]], axis=1)
        else:
            raise DataError(f"bundle feature recipe: unknown operation {op!r}; re-export with this version")
    F = np.hstack(cols)
    if not np.isfinite(F).all():
        raise DataError("step features are NaN: the stream lacks a sensor the model needs"
                        + _empty_channels(W, recipe, signals, channel_index))
    return F


#: heuristic rule statistics computed on the force signal's shape (``rule_feature``)
_FORCE_STATS = ("air_time", "time_to_peak", "peak_mean_4", "contact_force_2", "takeoff_force")


def recipe_channels(recipe: list, signals: dict) -> list[str]:
    """The window channels a feature recipe reads (its signals' channels, in a fixed order)."""
    names = {item[1] for item in recipe if item[0] in ("peak", "segments") and isinstance(item[1], str)}
    names |= {"force" for item in recipe if item[0] == "force"}
    names |= {"waist_yaw" for item in recipe if item[0] in ("yaw", "yaw_sign")}
    names |= {n for item in recipe if item[0] == "signals" for n in item[1]}
    for item in recipe:  # heuristic rule features "<signal>:<statistic>"
        if item[0] == "rule":
            s, _, stat = str(item[1]).partition(":")
            names.add(s)
            if stat == "range_x_air_time":  # thesis Table 30 #3: times the force's air time
                names.add("force")
    return list(dict.fromkeys(c for n in sorted(names) if n in signals for c in signals[n][0]))


def _empty_channels(W: np.ndarray, recipe: list, signals: dict, channel_index: dict) -> str:
    """The message tail naming the window channels that the recipe's signals read and that hold NaN (as the
    step graph's error says them, ``runtime.classify.StepGraph.predict``); empty when none can be named."""
    chans = recipe_channels([it for it in recipe if it[0] != "rule"], signals)
    missing = [c for c in chans if c in channel_index and not np.isfinite(W[:, channel_index[c], :]).all()]
    if not missing:
        return ""
    return (f" (window channels {', '.join(missing)} are empty); push those sensors, or export a model trained "
            "without them")


def rule_feature(W: np.ndarray, name: str, sig, peaks) -> np.ndarray:
    """Named heuristic rule feature ``"<signal>:<statistic>"`` (thesis Tables 22-24, 29-31, eq. 31-32)."""
    t = W[:, 0, :]
    if name == "foot_acc_fwd:range_x_air_time":  # thesis Table 30 #3
        return peaks("foot_acc_fwd")["range"] * K.force_stats(sig("force"), t)["air_time"]
    s, _, stat = name.partition(":")
    if stat == "abs_peak_asym":
        return np.abs(peaks(s)["peak_asym"])
    if stat == "half_balance":  # thesis eq. 31
        return K.half_balance(sig(s))
    if stat == "step_probability":  # thesis eq. 32
        return K.step_probability(sig(s))
    if stat in _FORCE_STATS:
        return K.force_stats(sig(s), t)[stat]
    ps = peaks(s)
    if stat in ps:
        return ps[stat]
    yaw = K.yaw_stats(ps)
    if stat in yaw:
        return yaw[stat]
    raise DataError(f"bundle rule feature {name!r} is unknown to this runtime; re-export the bundle")
