"""The "bayes" class rule's stride length and the confidence gate, numpy only (decisions L14, L18, L40).

The integrated stride length is a measurement ``N(L, sigma^2)`` of the true length L, sigma =
max(``sigma_rel`` L, ``sigma_min``); the length classifier gives the prior ``sum_c p_c U(L; lo_c, hi_c)``;
the rule's length is the posterior mean (closed form, truncated normals; docs/decisions/localization.md
L14). One formula, :func:`_posterior`, written with arithmetic operators only, serves both callers:
:func:`bayes_length_one` on Python floats (the streaming runtime's step, decision E17: no numpy call) and
:func:`bayes_length` on arrays (the offline :class:`pdrlearn.displace.StepRules`). Both evaluate the normal
cdf / pdf with :mod:`math` (``erfc``, ``exp``), element by element in the array version, so a stride gets
the same bits from either (decision L40).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from pdrlearn.errors import DataError

#: Class rules with a model's classes (decision L18): "bayes" (L14) was better than "thesis" in every run.
DEFAULT_MODEL_RULES = "bayes"
#: Probability a model's class needs before its rule applies (decision L18): a wrong length class costs
#: ~15-20 % of a stride, a right one gains ~0 when the estimate is good.
DEFAULT_MIN_CONFIDENCE = 0.95
#: The estimate's sd: max(``SIGMA_REL`` x length, ``SIGMA_MIN``) (decision L14; the user's calibrated stride
#: sd replaces ``SIGMA_REL`` when the model carries one, L26) and the height change above which the
#: estimate's vertical keeps its sign whatever the terrain class (L14: 0.1 m, half a stair rise, sim S3).
SIGMA_REL, SIGMA_MIN, DZ_MIN = 0.03, 0.02, 0.1
RULES = ("thesis", "bayes")

_INV_SQRT2 = 1.0 / math.sqrt(2.0)
_INV_SQRT2PI = 1.0 / math.sqrt(2.0 * math.pi)


def _normal(x: float) -> tuple[float, float, float]:
    """Standard normal cdf, 0.5 erfc(-x / sqrt 2), survival function 0.5 erfc(x / sqrt 2) (each accurate in
    its small tail) and density at ``x``."""
    return (0.5 * math.erfc(-x * _INV_SQRT2), 0.5 * math.erfc(x * _INV_SQRT2),
            _INV_SQRT2PI * math.exp(-0.5 * x * x))


_normal_ufunc = np.frompyfunc(_normal, 1, 3)  # the same math calls element by element (object arrays out)


def _normal_array(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    c, s, d = _normal_ufunc(x)
    return c.astype(float), s.astype(float), d.astype(float)


def _posterior(d, sg, proba: Sequence, bounds: Sequence[tuple[float, float]], normal):
    """(z, num): the posterior mass and first moment of L given the estimate ``d`` (m) with sd ``sg`` and
    the class prior (``proba[c]`` on ``bounds[c]``); ``d``, ``sg``, ``proba[c]`` are floats or arrays of one
    shape (operators only, so one formula serves both; ``normal(x)`` = (cdf, survival, pdf)). Per class: the mass
    P(L in class | d) = Phi(b) - Phi(a) and the integral of L N(d; L, sg) over the class, d mass + sg (phi(a)
    - phi(b)), with a, b = (lo - d) / sg, (hi - d) / sg (truncated normal moments), weighed by p_c / width_c.
    A class above the estimate (a > 0) takes its mass from the upper tail, Q(a) - Q(b) (Q = 1 - Phi): there
    Phi(b) - Phi(a) is a difference of two numbers next to 1 and cancels to 0 (a = 9.3: exactly 0 while
    phi(a) is still 1e-19), which made the ratio num / z of a stride 9 sd below the class 1e30 m (decision
    L93)."""
    z = num = 0.0
    for p, (lo, hi) in zip(proba, bounds, strict=True):
        a, b = (lo - d) / sg, (hi - d) / sg
        (ca, sa, pa), (cb, sb, pb) = normal(a), normal(b)
        upper = a > 0  # bool or bool array: operators only, so one formula serves floats and arrays
        mass = upper * (sa - sb) + (1 - upper) * (cb - ca)
        w = p / max(hi - lo, 1e-9)
        z = z + w * mass
        num = num + w * (d * mass + sg * (pa - pb))
    return z, num


def bayes_length_one(distance: float, proba: Sequence[float], bounds: Sequence[tuple[float, float]],
                     sigma: float) -> float:
    """Posterior-mean |length| (m) of one stride: |estimate| ``distance`` (m), class probabilities ``proba``
    (summing to 1) on class ``bounds`` ((lo, hi) m), estimate sd ``sigma`` (m). Python floats."""
    d = abs(distance)
    z, num = _posterior(d, sigma, proba, bounds, _normal)
    return num / z if z > 1e-300 else d


def bayes_length(distance: np.ndarray, proba: np.ndarray, bounds: Sequence[tuple[float, float]],
                 sigma: np.ndarray) -> np.ndarray:
    """:func:`bayes_length_one` of B strides: ``distance (B,)``, ``proba (B, C)``, ``sigma (B,)`` -> (B,)."""
    d = np.abs(np.asarray(distance, dtype=float))
    sg = np.broadcast_to(np.asarray(sigma, dtype=float), d.shape)
    p = np.asarray(proba, dtype=float).reshape(len(d), len(bounds))
    z, num = _posterior(d, sg, list(p.T), bounds, _normal_array)
    z = np.broadcast_to(np.asarray(z, dtype=float), d.shape)
    return np.where(z > 1e-300, np.asarray(num, dtype=float) / np.where(z > 1e-300, z, 1.0), d)


def class_proba_one(proba: Mapping[str, float] | None, names: Iterable[str], label) -> list[float]:
    """The probabilities of ``names`` from one stride's ``proba`` (class -> p): non-finite as 0, normalised
    (all 0: uniform); one-hot of ``label`` when ``proba`` lacks a name (labels without probabilities, as
    :func:`pdrlearn.displace.rules._class_proba`)."""
    try:
        p = [float(proba[n]) for n in names]
    except (KeyError, TypeError):  # no probabilities (None) or not for every class
        return [1.0 if n == label else 0.0 for n in names]
    s = sum(p)
    if 0.0 < s < math.inf:  # all finite (a NaN or inf makes the sum fail this test): the common case
        return [v / s for v in p]
    p = [v if math.isfinite(v) else 0.0 for v in p]
    s = sum(p)
    return [v / s for v in p] if s > 0 else [1.0 / len(p)] * len(p)


def confident_one(label, proba: Mapping[str, float] | None, min_confidence: float):
    """Decision L18's gate on one stride's class: ``label`` when its task's highest probability reaches
    ``min_confidence`` (or there are no probabilities, or the gate is 0), else None (no rule). NaN
    probabilities are skipped (pandas' row max, as the offline ``_confident``)."""
    if min_confidence <= 0 or not proba:
        return label
    if max(proba.values()) >= min_confidence:  # a finite value reaches the gate (NaN compares False): kept
        return label
    finite = [v for v in proba.values() if v == v]  # else the NaN-free maximum decides (pandas skipna)
    return None if finite and max(finite) < min_confidence else label


def check_rules(rules: str, min_confidence: float, where: str) -> None:
    """One-line error for an unknown rule or a gate outside 0..1."""
    if rules not in RULES:
        raise DataError(f"{where}: rules {rules!r} is not one of {', '.join(RULES)}")
    if not 0.0 <= float(min_confidence) <= 1.0:
        raise DataError(f"{where}: min_confidence {min_confidence!r} must be between 0 and 1 (0 = every class)")
