"""Named scalar step features used by the heuristic rule tables (thesis Tables 22-24, 29-31, eq. 31-32).

A rule feature is named ``"<signal>:<statistic>"`` (signals: :data:`pdrlearn.features.SIGNALS`).
:class:`RuleFeatures` turns step windows into the matrix of the named features a rule table needs.
Units: accelerations m/s^2, rates rad/s, forces in the sensor's unit, times s, integrals unit x s.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.features import _kernels as K
from pdrlearn.features.transformers import _StepFeatures, signal, signals_unit, times
from pdrlearn.kernels.stats import half_balance, step_probability, yaw_stats

_PEAK_STATS = ("min", "max", "t_min", "t_max", "dt_peaks", "abs_dt_peaks", "range", "peak_asym",
               "sum_pos", "sum_neg", "pos_minus_neg", "duration")


_FORCE_STATS = ("air_time", "time_to_peak", "peak_mean_4", "contact_force_2", "takeoff_force")
_YAW_STATS = ("amplitude", "left", "right", "left_minus_right")


class _Stats:
    """Per-call cache of the statistics of each signal of windows ``X``."""

    def __init__(self, X: np.ndarray):
        self.X = X
        self._peak: dict[str, dict[str, np.ndarray]] = {}
        self._force: dict[str, dict[str, np.ndarray]] = {}

    def peak(self, sig: str) -> dict[str, np.ndarray]:
        if sig not in self._peak:
            self._peak[sig] = K.peak_stats(signal(self.X, sig), times(self.X))
        return self._peak[sig]

    def force(self, sig: str) -> dict[str, np.ndarray]:
        if sig not in self._force:
            self._force[sig] = K.force_stats(signal(self.X, sig), times(self.X))
        return self._force[sig]


def _stat(name: str) -> Callable[[_Stats, str], np.ndarray]:
    if name in _PEAK_STATS:
        return lambda S, sig: S.peak(sig)[name]
    if name == "abs_peak_asym":
        return lambda S, sig: np.abs(S.peak(sig)["peak_asym"])
    if name == "half_balance":
        return lambda S, sig: half_balance(signal(S.X, sig))
    if name == "step_probability":
        return lambda S, sig: step_probability(signal(S.X, sig))
    if name in _FORCE_STATS:
        return lambda S, sig: S.force(sig)[name]
    if name in _YAW_STATS:
        return lambda S, sig: yaw_stats(S.peak(sig))[name]
    raise DataError(f"unknown rule statistic '{name}'")


def _range_x_air_time(S: _Stats) -> np.ndarray:
    """Thesis Table 30 #3: foot acceleration peak difference x time without force (m/s^2 x s)."""
    return S.peak("foot_acc_fwd")["range"] * S.force("force")["air_time"]


#: Features that combine two signals: name -> (signals, function).
COMBINED: dict[str, tuple[tuple[str, ...], Callable[[_Stats], np.ndarray]]] = {
    "foot_acc_fwd:range_x_air_time": (("foot_acc_fwd", "force"), _range_x_air_time),
}


def feature_signals(name: str) -> tuple[str, ...]:
    """Signals a rule feature needs."""
    if name in COMBINED:
        return COMBINED[name][0]
    sig, _, stat = name.partition(":")
    if not stat:
        raise DataError(f"rule feature '{name}' is not of the form '<signal>:<statistic>'")
    return (sig,)


def rule_features(X: np.ndarray, names) -> np.ndarray:
    """Matrix (n_steps, len(names)) of the named rule features of windows ``X``."""
    S = _Stats(X)
    cols = []
    for name in names:
        if name in COMBINED:
            cols.append(COMBINED[name][1](S))
        else:
            sig, _, stat = name.partition(":")
            cols.append(_stat(stat)(S, sig))
    return np.column_stack(cols)


class RuleFeatures(_StepFeatures):
    """Windows -> the named scalar features of a rule table (``names``, e.g. ``("foot_acc_v:min",)``)."""

    task = "heuristic"

    def __init__(self, *, names: tuple[str, ...] = ("foot_acc_v:min",), task: str = "heuristic"):
        self.names = names
        self.task = task

    def _check_unit(self) -> None:
        for n in self.names:
            feature_signals(n)

    def _signals(self):
        return tuple(dict.fromkeys(s for n in self.names for s in feature_signals(n)))

    def _names(self):
        return list(self.names)

    def _unit_named(self) -> str:
        """Decision B392: the unit whose sensors the rules read (``foot`` / ``waist``, ``fused`` for both), which a
        missing-sensor line names; it named ``unit 'combined'`` for a heuristic/waist model (trial T4)."""
        return signals_unit(self._signals(), "fused")

    def _compute(self, X):
        return rule_features(X, self.names)
