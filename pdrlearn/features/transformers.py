"""Per-task, per-unit step feature transformers (thesis ch. 6), scikit-learn compatible.

Every transformer takes step windows - a :class:`~pdrlearn.features.windows.StepWindows` or its array
``X (n_steps, len(CHANNELS), n_samples)`` - and returns a 2-D feature matrix. ``fit`` is stateless
(it only records the input layout), so they drop into a ``Pipeline`` before a scaler and a classifier.

Signals (derived from :data:`~pdrlearn.features.windows.CHANNELS`, see docs/features.md):

============== ===================================== ==============================================
signal         definition                            thesis axis
============== ===================================== ==============================================
foot_acc_v     foot_acc_z (vertical, gravity removed) foot accelerometer y (terrain, ch. 6.1)
foot_pitch     -foot_gyr_y (+ = toes up)              foot gyroscope z (terrain, ch. 6.1)
foot_acc_fwd   foot_acc_x (forward horizontal)        foot accelerometer x (direction, length)
waist_acc_v    waist_acc_z (vertical, gravity removed) waist accelerometer x (terrain)
waist_acc_fwd  waist_acc_x                            waist accelerometer z (direction, eq. 31)
waist_yaw      waist_gyr_z (pelvic rotation)          waist gyroscope x (direction, length)
force          force_a + force_b                      foot force sensor (length, Table 29)
============== ===================================== ==============================================
"""

from __future__ import annotations

import functools

import numpy as np
from sklearn.base import BaseEstimator, TransformerMixin

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.features import _kernels as K
from pdrlearn.features.windows import CHANNEL_INDEX, CHANNELS, GROUP_STREAMS, GROUPS, StepWindows

#: Derived signals: name -> (channels summed, sign, sensor group).
SIGNALS: dict[str, tuple[tuple[str, ...], float, str]] = {
    "foot_acc_v": (("foot_acc_z",), 1.0, "foot_acc"),
    "foot_pitch": (("foot_gyr_y",), -1.0, "foot_gyr"),  # thesis foot z axis points right: + = toes up
    "foot_acc_fwd": (("foot_acc_x",), 1.0, "foot_acc"),
    "waist_acc_v": (("waist_acc_z",), 1.0, "waist_acc"),
    "waist_acc_fwd": (("waist_acc_x",), 1.0, "waist_acc"),
    "waist_yaw": (("waist_gyr_z",), 1.0, "waist_gyr"),
    "force": (("force_a", "force_b"), 1.0, "force"),
}
for _g, _cs in GROUPS.items():
    for _c in _cs:
        SIGNALS.setdefault(_c, ((_c,), 1.0, _g))

UNITS = ("foot", "waist", "both")


def as_windows(X) -> np.ndarray:
    """The window array of ``X`` (StepWindows or ndarray), validated against :data:`CHANNELS`."""
    arr = X.X if isinstance(X, StepWindows) else np.asarray(X, dtype=np.float64)
    if arr.ndim != 3 or arr.shape[1] != len(CHANNELS):
        raise DataError(f"step windows: expected an array (n_steps, {len(CHANNELS)}, n_samples) with the "
                        f"CHANNELS layout, got shape {arr.shape}; build it with "
                        "pdrlearn.features.step_windows")
    if arr.shape[0] == 0:
        raise DataError("step windows: no steps (empty array); detect or label steps first")
    return arr


def signal(X: np.ndarray, name: str) -> np.ndarray:
    """Derived signal ``name`` (see :data:`SIGNALS`) of every step, (n_steps, n_samples), a new array.

    Channels summed left to right, then times the sign; a sign of 1.0 skips the (exact) product and a
    single channel is one copy (per-step latency, issue 5).
    """
    chans, sign, _ = SIGNALS[name]
    first = X[:, CHANNEL_INDEX[chans[0]], :]
    if len(chans) == 1:
        return first.copy() if sign == 1.0 else sign * first
    out = first + X[:, CHANNEL_INDEX[chans[1]], :]
    for c in chans[2:]:
        out += X[:, CHANNEL_INDEX[c], :]
    return out if sign == 1.0 else sign * out


def times(X: np.ndarray) -> np.ndarray:
    return X[:, 0, :]


@functools.lru_cache(maxsize=64)
def _checked_channels(names: tuple[str, ...]) -> np.ndarray:
    """Window channels (``t_s`` first) that the signals ``names`` read."""
    return np.array([0] + [CHANNEL_INDEX[c] for nm in names for c in SIGNALS[nm][0]], dtype=np.intp)


def signals_unit(names, both: str = "both") -> str:
    """Decision B392: the unit whose sensors the :data:`SIGNALS` ``names`` read (``foot``: foot and force, ``waist``),
    ``both`` when they read both; the unit a missing-sensor line of a transformer without ``unit`` names."""
    units = {"waist" if SIGNALS[n][2].startswith("waist") else "foot" for n in names}
    return units.pop() if len(units) == 1 else both


def require_signals(X: np.ndarray, names, *, task: str, unit: str) -> None:
    """Raise :class:`MissingSensorError` if a needed sensor is absent, :class:`DataError` on NaN steps."""
    if np.isfinite(X[:, _checked_channels(tuple(names)), :]).all():  # the usual case, one check (latency)
        return
    for name in names:
        chans, _, group = SIGNALS[name]
        vals = X[:, [CHANNEL_INDEX[c] for c in chans], :]
        bad = ~np.isfinite(vals).all(axis=(1, 2))
        if bad.all():
            alt = " or unit='foot'" if group.startswith("waist") else " or unit='waist'"
            who = f"unit='{unit}'"
            if unit == "both":  # the combined vector of both units (training unit 'combined', decision C22)
                who, alt = "of both units, unit 'combined'", ", or use a model of the other unit"
            elif unit == "fused":  # decision B392: heuristic fusion's rules read both units
                who, alt = "of both units, heuristic fusion", ", or use a model of the other unit"
            raise MissingSensorError(
                f"{task} features ({who}) need the {group.replace('_', ' ')} "
                f"({', '.join(GROUP_STREAMS[group])}), which the step windows lack; record it{alt}"
            )
        if bad.any():
            raise DataError(f"{task} features: {int(bad.sum())} of {len(bad)} steps have NaN {group} "
                            "samples; drop those steps or repair the stream")
    if not np.isfinite(times(X)).all():
        raise DataError(f"{task} features: the t_s channel has NaN values; rebuild the windows")


class _StepFeatures(TransformerMixin, BaseEstimator):
    """Shared machinery: stateless fit, input validation, feature names."""

    task = "features"

    def _signals(self) -> tuple[str, ...]:
        raise NotImplementedError

    def _names(self) -> list[str]:
        raise NotImplementedError

    def _compute(self, X: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def _check_unit(self) -> None:
        unit = getattr(self, "unit", "both")
        if unit not in UNITS:
            raise DataError(f"{type(self).__name__}: unit must be one of {', '.join(UNITS)}, not {unit!r}")

    def fit(self, X, y=None):
        """Stateless: checks the window layout and records ``n_features_out_``."""
        self._check_unit()
        as_windows(X)
        self.n_features_out_ = len(self._names())
        return self

    def transform(self, X) -> np.ndarray:
        """Feature matrix (n_steps, n_features)."""
        self._check_unit()
        arr = as_windows(X)
        require_signals(arr, self._signals(), task=self.task, unit=self._unit_named())
        return self._compute(arr)

    def _unit_named(self) -> str:
        """The unit a missing-sensor line names (:func:`require_signals`)."""
        return getattr(self, "unit", "both")

    def get_feature_names_out(self, input_features=None) -> np.ndarray:
        self._check_unit()
        return np.asarray(self._names(), dtype=object)

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.requires_fit = False
        return tags


# -- terrain SVM features (thesis ch. 6.1.1.1) ------------------------------------------------------

#: (signal, statistic of :func:`pdrlearn.kernels.stats.peak_stats`) per sensor, thesis ch. 6.1.1.1.
TERRAIN_SVM_SPEC: dict[str, tuple[tuple[str, str], ...]] = {
    # foot accelerometer, 6 features: min, max, instant difference, peak difference, sum neg, sum pos
    "foot_acc": tuple(("foot_acc_v", s) for s in ("min", "max", "dt_peaks", "range", "sum_neg", "sum_pos")),
    # foot gyroscope, 5 features: min, max, instant difference, sum pos, sum neg
    "foot_gyr": tuple(("foot_pitch", s) for s in ("min", "max", "dt_peaks", "sum_pos", "sum_neg")),
    # waist accelerometer, 6 features: max, t_min, t_max, instant difference, sum neg, sum pos
    "waist_acc": tuple(("waist_acc_v", s)
                       for s in ("max", "t_min", "t_max", "dt_peaks", "sum_neg", "sum_pos")),
}
UNIT_SENSORS = {"foot": ("foot_acc", "foot_gyr"), "waist": ("waist_acc",),
                "both": ("foot_acc", "foot_gyr", "waist_acc")}


def peak_features(X: np.ndarray, spec) -> np.ndarray:
    """Columns ``peak_stats(signal)[stat]`` for each ``(signal, stat)`` of ``spec``.

    The signals are stacked as extra rows and go through one ``peak_stats`` call (its statistics are
    row by row, so the numbers are those of one call per signal, with fewer numpy calls per step).
    """
    sigs = list(dict.fromkeys(sig for sig, _ in spec))
    n = X.shape[0]
    t = times(X)
    rows = np.concatenate([signal(X, s) for s in sigs]) if len(sigs) > 1 else signal(X, sigs[0])
    stats = K.peak_stats(rows, np.concatenate([t] * len(sigs)) if len(sigs) > 1 else t)
    at = {s: i * n for i, s in enumerate(sigs)}
    out = np.empty((n, len(spec)))
    for j, (sig, stat) in enumerate(spec):
        out[:, j] = stats[stat][at[sig]:at[sig] + n]
    return out


class TerrainSVMFeatures(_StepFeatures):
    """The 17 terrain SVM features (thesis ch. 6.1.1.1): foot accelerometer 6, foot gyroscope 5,
    waist accelerometer 6, computed on the vertical accelerations and the foot pitch rate.

    Parameters
    ----------
    unit : ``"foot"`` (11 features), ``"waist"`` (6) or ``"both"`` (17)

    Units: accelerations m/s^2, rates rad/s, instants s (from the step start), sums = time integrals
    (m/s, rad) of the positive part / magnitude of the negative part.
    """

    task = "terrain"

    def __init__(self, *, unit: str = "both"):
        self.unit = unit

    def _spec(self):
        return [f for s in UNIT_SENSORS[self.unit] for f in TERRAIN_SVM_SPEC[s]]

    def _signals(self):
        return tuple(dict.fromkeys(sig for sig, _ in self._spec()))

    def _names(self):
        return [f"{sig}_{stat}" for sig, stat in self._spec()]

    def _compute(self, X):
        return peak_features(X, self._spec())


# -- segment features (thesis ch. 6.1.1.2, 6.2.1, 6.3.1) ------------------------------------------


class SegmentFeatures(_StepFeatures):
    """Per signal, ``n_segments`` equal parts x (max, min, mean, slope) (thesis ch. 6.1.1.2).

    Parameters
    ----------
    channels : derived signals (:data:`SIGNALS`) or raw channels of :data:`CHANNELS`
    n_segments : parts per signal (thesis: 6, ~5 samples per part of a 30-sample step)
    """

    task = "segment"

    def __init__(self, *, channels: tuple[str, ...] = ("foot_acc_v", "foot_pitch", "waist_acc_v"),
                 n_segments: int = 6):  # thesis ch. 6.1.1.2: 6 parts
        self.channels = channels
        self.n_segments = n_segments

    def _check_unit(self) -> None:
        unknown = [c for c in self.channels if c not in SIGNALS]
        if unknown or not len(self.channels):
            raise DataError(f"SegmentFeatures: unknown channels {unknown}; choose from {', '.join(SIGNALS)}")
        if not (isinstance(self.n_segments, int | np.integer) and self.n_segments >= 1):
            raise DataError(f"SegmentFeatures: n_segments must be a positive integer, "
                            f"not {self.n_segments!r}")

    def _signals(self):
        return tuple(self.channels)

    def _unit_named(self) -> str:  # decision B392: terrain nn/waist's line named "unit 'combined'"
        return signals_unit(self._signals())

    def _names(self):
        return [f"{c}_seg{j + 1}_{s}" for c in self.channels for j in range(self.n_segments)
                for s in ("max", "min", "mean", "slope")]

    def _compute(self, X):
        if self.n_segments > X.shape[2]:
            raise DataError(f"SegmentFeatures: {self.n_segments} segments need at least that many samples "
                            f"per step, the windows have {X.shape[2]}")
        return np.hstack([K.segment_stats(signal(X, c), times(X), self.n_segments) for c in self.channels])


def _segment_names(sig: str, n_segments: int = 6) -> list[str]:
    return SegmentFeatures(channels=(sig,), n_segments=n_segments)._names()


def waist_yaw_sign(X: np.ndarray) -> np.ndarray:
    """1 when the pelvis' net yaw rotation over the step is positive (left), else 0 (thesis ch. 6.2.1)."""
    return K.positive_net_rotation(signal(X, "waist_yaw"), times(X))


class DirectionFeatures(_StepFeatures):
    """Direction features (thesis ch. 6.2.1): 24 segment features of the forward foot acceleration
    plus the sign of the pelvic rotation (1 = positive, 0 = negative) = 25.

    Per unit (docs/decisions/features.md): ``foot`` = the 24 foot features; ``waist`` = 24 segment
    features of the waist's forward acceleration + the pelvic sign (25); ``both`` = thesis (25).
    """

    task = "direction"

    def __init__(self, *, unit: str = "both", n_segments: int = 6):  # thesis ch. 6.2.1: 6 parts
        self.unit = unit
        self.n_segments = n_segments

    def _acc(self) -> str:
        return "waist_acc_fwd" if self.unit == "waist" else "foot_acc_fwd"

    def _signals(self):
        return (self._acc(),) + (("waist_yaw",) if self.unit != "foot" else ())

    def _names(self):
        sign = ["waist_yaw_sign"] if self.unit != "foot" else []
        return _segment_names(self._acc(), self.n_segments) + sign

    def _compute(self, X):
        cols = [K.segment_stats(signal(X, self._acc()), times(X), self.n_segments)]
        if self.unit != "foot":
            cols.append(waist_yaw_sign(X)[:, None])
        return np.hstack(cols)


#: Force-sensor features of the learned length classifiers (thesis ch. 6.3.1).
LENGTH_FORCE_STATS = ("time_to_peak", "takeoff_force", "air_time")
#: Waist-gyroscope features of the learned length classifiers (thesis ch. 6.3.1).
LENGTH_WAIST_STATS = ("amplitude", "duration")


def waist_yaw_stats(X: np.ndarray) -> dict[str, np.ndarray]:
    """Pelvic-rotation statistics (thesis Table 31, ch. 6.3.1): ``amplitude`` (half peak-to-peak, rad/s),
    ``left`` (s from the step start to the max), ``right`` (s from the max to the end),
    ``left_minus_right`` (s), ``duration`` (s)."""
    return K.yaw_stats(K.peak_stats(signal(X, "waist_yaw"), times(X)))


def waist_yaw_amplitude_duration(X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``amplitude`` (rad/s) and ``duration`` (s) of :func:`waist_yaw_stats`, the two pelvic-rotation
    features of the learned length classifiers (thesis ch. 6.3.1), without the other ten peak statistics.

    Same arithmetic as ``K.yaw_stats(K.peak_stats(...))``: ``0.5 * (max - min)`` and
    ``(t_last - t_first)`` (bit-identical; tests/test_classify_length_fast.py).
    """
    yaw, t = signal(X, "waist_yaw"), times(X)
    return 0.5 * (yaw.max(axis=1) - yaw.min(axis=1)), t[:, -1] - t[:, 0]


class LengthFeatures(_StepFeatures):
    """Length features (thesis ch. 6.3.1): 24 segment features of the forward foot acceleration,
    3 force features (time from contact to peak force, take-off force, air time) and 2 pelvic-rotation
    features (amplitude, signal length) = 29.

    ``unit="foot"`` = 27 (acc + force), ``"waist"`` = 2, ``"both"`` = 29.
    """

    task = "length"

    def __init__(self, *, unit: str = "both", n_segments: int = 6,  # thesis ch. 6.3.1: 6 parts
                 zero_fraction: float = 0.05):
        self.unit = unit
        self.n_segments = n_segments
        self.zero_fraction = zero_fraction

    def _signals(self):
        foot = ("foot_acc_fwd", "force") if self.unit != "waist" else ()
        return foot + (("waist_yaw",) if self.unit != "foot" else ())

    def _names(self):
        names = []
        if self.unit != "waist":
            names += _segment_names("foot_acc_fwd", self.n_segments)
            names += [f"force_{s}" for s in LENGTH_FORCE_STATS]
        if self.unit != "foot":
            names += [f"waist_yaw_{s}" for s in LENGTH_WAIST_STATS]
        return names

    def _compute(self, X):
        # columns written into one array (no column_stack / hstack: per-step latency, issue 5)
        t = times(X)
        nseg = 4 * self.n_segments
        foot, waist = self.unit != "waist", self.unit != "foot"
        width = foot * (nseg + len(LENGTH_FORCE_STATS)) + waist * len(LENGTH_WAIST_STATS)
        out = np.empty((X.shape[0], width))
        j = 0
        if foot:
            out[:, :nseg] = K.segment_stats(signal(X, "foot_acc_fwd"), t, self.n_segments)
            fs = K.force_stats(signal(X, "force"), t, zero_fraction=self.zero_fraction)
            for j, s in enumerate(LENGTH_FORCE_STATS, start=nseg):
                out[:, j] = fs[s]
            j += 1
        if waist:
            out[:, j], out[:, j + 1] = waist_yaw_amplitude_duration(X)  # LENGTH_WAIST_STATS
        return out


def make_features(task: str, unit: str = "both", kind: str = "svm") -> _StepFeatures:
    """The thesis feature transformer of ``task`` for ``unit`` and classifier ``kind``.

    terrain: svm -> :class:`TerrainSVMFeatures` (17), nn -> 72 segment features (thesis ch. 6.1.1.2);
    direction: :class:`DirectionFeatures` (25, both kinds); length: :class:`LengthFeatures` (29, both kinds).
    """
    unit = "both" if unit == "combined" else unit  # decision C123: train's name of the combined unit
    if unit not in UNITS:
        raise DataError(f"make_features: unit must be one of {', '.join(UNITS)}, not {unit!r}")
    if kind not in ("svm", "nn"):
        raise DataError(f"make_features: kind must be 'svm' or 'nn', not {kind!r}")
    if task == "terrain":
        if kind == "svm":
            return TerrainSVMFeatures(unit=unit)
        chans = {"foot": ("foot_acc_v", "foot_pitch"), "waist": ("waist_acc_v",),
                 "both": ("foot_acc_v", "foot_pitch", "waist_acc_v")}[unit]
        return SegmentFeatures(channels=chans, n_segments=6)  # thesis ch. 6.1.1.2
    if task == "direction":
        return DirectionFeatures(unit=unit)
    if task == "length":
        return LengthFeatures(unit=unit)
    raise DataError(f"make_features: unknown task '{task}'; choose terrain, direction or length")
