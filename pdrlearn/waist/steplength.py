"""Step length of waist steps and its per-user calibration (seed 000 sec. II-D, seed 001 eq. 23,
seed 003 sec. 3.2)."""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.waist import _kernels as K
from pdrlearn.waist._kernels import FRAGMENT_FRAC, MIN_FRAGMENT_SEQ, fragment_windows  # noqa: F401  (W92)
from pdrlearn.waist.params import WaistParams

log = logging.getLogger(__name__)

#: seed 000 sec. II-D: linear ranges 1.5-2.2 Hz walking, 2.7-4.2 Hz running; the split between them
RUN_SPLIT_HZ = 2.45
#: decision W37: the upper ends of those linear ranges (seed 000 sec. II-D); a step faster than its line's
#: range keeps the length the line gives at the end (no extrapolation to 2 m steps at 5 Hz)
WALK_MAX_HZ = 2.2
RUN_MAX_HZ = 4.2
#: decision W240: the lower end of seed 000 sec. II-D's linear walking range (1.5-2.2 Hz); below it the seed gives no
#: line, so ``cadence_law`` holds a slower step at this frequency
WALK_MIN_HZ = 1.5
MIN_SPREAD_HZ = 0.15  # fit a slope only when the calibration walks span this much frequency (decision W8)
# decision W27: a step shorter than this fraction of its walking sequence's median step is a fragment of a step
# split by a spurious contact (step-time variability within a walking sequence is a few per cent, Hausdorff
# 2005 J NeuroEng Rehabil 2:19, so half the period is no step at that cadence; the same limit as W25/W26)


def pendulum_h(acc_v: np.ndarray, fs: float, i_ic: int, i_fc: int, i_next: int, *,
               single_stance: bool = False) -> float:
    """Vertical excursion (m) of a step, IC to next IC (decision W10: the whole step, as Zijlstra & Hof,
    because the waist FC estimate is too noisy); with ``single_stance`` from the FC after the IC to the
    next IC as seed 003 sec. 3.2 describes (the whole step when the FC is not inside it)."""
    i0 = i_fc if single_stance and i_ic < i_fc < i_next - 2 else i_ic
    return K.vertical_excursion(acc_v, fs, i0, i_next)


def fragment_mask(n: int, windows: dict[int, tuple[int, int]]) -> np.ndarray:
    """Rows merged into another step by :func:`fragment_windows` (they carry no length, W27)."""
    m = np.zeros(n, dtype=bool)
    for k, (a, b) in windows.items():
        m[a:b + 1] = True
        m[k] = False
    return m


def frequency_lengths(f_hz: np.ndarray, p: WaistParams, *, running: np.ndarray | None = None) -> np.ndarray:
    """Piecewise-linear step length (m) from step frequency (seed 000 sec. II-D): the walking line
    below :data:`RUN_SPLIT_HZ` (or where ``running`` is False), the running line above. Each line is
    evaluated at most at the upper end of its linear range, :data:`WALK_MAX_HZ` / :data:`RUN_MAX_HZ`
    (decision W37). The frequency is first scaled by :meth:`WaistParams.frequency_scale` (decision W118: a child's
    step at the same dimensionless frequency as an adult's reads as the adult's)."""
    f = np.asarray(f_hz, dtype=np.float64) * p.frequency_scale()  # decision W118: the dimensionless frequency
    run = f >= RUN_SPLIT_HZ if running is None else np.asarray(running, dtype=bool)
    sl = np.where(run, K.frequency_length(np.minimum(f, RUN_MAX_HZ), p.a_run, p.b_run),
                  K.frequency_length(np.minimum(f, WALK_MAX_HZ), p.a_walk, p.b_walk))
    return np.clip(sl, 0.0, None)


def cadence_law_factor(f_hz: np.ndarray, f_cal_hz: float | None, p: WaistParams) -> np.ndarray:
    """Decision W240 (option ``cadence_law``): each pendulum step's factor ``sqrt(SL(f) / SL(f_cal))``, ``SL`` seed
    000 sec. II-D's walking line of ``p`` (:func:`frequency_lengths`, W118's dimensionless frequency) with both
    frequencies held inside the linear walking range :data:`WALK_MIN_HZ`-:data:`WALK_MAX_HZ` -- the geometric mean
    of the pendulum's length and the cadence law, both calibrated at ``f_cal_hz`` (the calibration walks' median
    step frequency). Ones without ``f_cal_hz``, and where a line length is not positive or a frequency not finite."""
    f = np.asarray(f_hz, dtype=np.float64)
    ones = np.ones(f.shape)
    if f_cal_hz is None or not np.isfinite(f_cal_hz) or not f_cal_hz > 0:
        return ones
    lo = WALK_MIN_HZ / p.frequency_scale()  # the range is the line's own (dimensionless, W118) frequency
    walking = np.zeros(f.shape, dtype=bool)
    sl = frequency_lengths(np.maximum(np.nan_to_num(f, nan=lo), lo), p, running=walking)
    sl_cal = float(frequency_lengths(np.array([max(float(f_cal_hz), lo)]), p, running=np.zeros(1, dtype=bool))[0])
    ok = np.isfinite(f) & (sl > 0) & (sl_cal > 0)
    return np.where(ok, np.sqrt(np.where(ok, sl, 1.0) / (sl_cal if sl_cal > 0 else 1.0)), 1.0)


#: decision W261: the value of option ``cadence_law`` that applies W240's factor only to steady walking steps
CADENCE_LAW_STEADY = "steady"
#: decision W261: a step is steady when it and the steps before it in its walking sequence make this many steps (two
#: strides: each foot twice); the first three steps of a sequence are never steady, so neither are seed 004 sec.
#: III-C's two steps before "the velocity of the user ... usually reaches a steady state"
STEADY_WINDOW_STEPS = 4
#: decision W261: the highest coefficient of variation of the window's stride times (contact to the same foot's next
#: contact, the sum of two consecutive steps) for a steady window: steady walking's stride time varies a few per cent
#: (Hausdorff 2005, J NeuroEng Rehabil 2:19), and a waist contact's timing adds about 60 ms SD (W29's HA001 IC vs
#: INDIP, +-59 ms), ~0.08 of a 1.1 s stride for two contacts; chosen a priori, nothing fitted
STEADY_MAX_CV = 0.10


def steady_steps(step_s: np.ndarray, has_next: np.ndarray, *, frequency_scale: float = 1.0,
                 window: int = STEADY_WINDOW_STEPS, max_cv: float = STEADY_MAX_CV) -> np.ndarray:
    """Decision W261: which rows are steady walking steps -- the row and the ``window - 1`` rows before it all have a
    next contact (one walking sequence: a sequence closes at its row without one), the coefficient of variation
    (sample SD / mean) of their stride times (each two consecutive step times, s) is at most ``max_cv``, and their
    median step frequency (1 / the median step time, times ``frequency_scale``: W118's dimensionless frequency) lies
    in seed 000 sec. II-D's linear walking range :data:`WALK_MIN_HZ`-:data:`WALK_MAX_HZ`. Trailing (causal): a row is
    decided by its own and earlier step times only, so offline and realtime tracks decide it alike."""
    t = np.asarray(step_s, dtype=np.float64)
    ok = np.asarray(has_next, dtype=bool) & np.isfinite(t) & (t > 0)
    n = len(t)
    out = np.zeros(n, dtype=bool)
    if window < 2 or n < window:
        return out
    from numpy.lib.stride_tricks import sliding_window_view

    wt = sliding_window_view(np.where(ok, t, np.nan), window)  # row i + window - 1 and the window - 1 before it
    full = sliding_window_view(ok, window).all(axis=1)
    strides = wt[:, 1:] + wt[:, :-1]
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = strides.mean(axis=1)
        cv = strides.std(axis=1, ddof=1) / mean
        f = frequency_scale / np.median(wt, axis=1)
    steady = full & (cv <= max_cv) & (f >= WALK_MIN_HZ) & (f <= WALK_MAX_HZ)
    out[window - 1:] = np.where(full, steady, False)
    return out


def calibration_cadence_hz(p: WaistParams) -> float | None:
    """Decision W240: the calibration walks' median step frequency (Hz) from W140's ``gait`` record of calibrated
    parameters, else None (defaults: no calibration cadence)."""
    cad = (p.gait or {}).get("median_cadence_spm") if p.source == "calibrated" else None
    return float(cad) / 60.0 if cad is not None and float(cad) > 0 else None


@dataclass
class CalibrationWalk:
    """One calibration walk: per-step features of the detected steps and the known distance (m).

    ``f_hz`` step frequencies (frequency model); ``g`` = ``2 sqrt(2 L h - h^2)`` per step (pendulum);
    ``c`` = the factor the tracker multiplies each step's length by (the turning-step factor of W19; ones
    when ``None``); ``steady`` (decision W261): which steps ``cadence_law="steady"`` scales (None: not known). The
    fits below solve the walk's distance as the tracker sums it (decision W21):
    ``D = sum(c (a f - b))`` and ``D = sum(c (K g + F))``. ``dpsi`` (decision W150, option ``pivot_steps``): each
    step's net rotation (rad); its pivot factor depends on the fitted length, so :func:`with_pivot_factors` gives
    the walk whose ``c`` includes it for given parameters (None: the option is off).
    """

    distance_m: float
    f_hz: np.ndarray
    g: np.ndarray
    name: str = ""
    c: np.ndarray | None = None
    dpsi: np.ndarray | None = None
    #: decision W261: each step's :func:`steady_steps` verdict in the tracker's steps (None: not known)
    steady: np.ndarray | None = None
    #: decision W514: how many of the walk's steps the tracker shortened as pauses / stands (``pause_factor`` < 1)
    paused: int = 0

    def factors(self) -> np.ndarray:
        n = len(self.f_hz)
        return np.ones(n) if self.c is None else np.asarray(self.c, dtype=np.float64)


def model_lengths(walk: CalibrationWalk, pipeline: str, p: WaistParams) -> np.ndarray:
    """Each step's length under the parameters ``p`` before the tracker's factors ``c`` (``K g + F`` >= 0 for the
    pendulum, non-finite ``g`` as 0; the walking line for the frequency model, as the tracker's walking steps)."""
    if pipeline == "waist-pendulum":
        return np.maximum(p.k * np.nan_to_num(np.asarray(walk.g, dtype=float), nan=0.0)
                          + (p.f_m if np.isfinite(p.f_m) else 0.0), 0.0)
    return frequency_lengths(np.nan_to_num(np.asarray(walk.f_hz, dtype=float), nan=0.0), p,
                             running=np.zeros(len(walk.f_hz), dtype=bool))


def with_pivot_factors(walks: list[CalibrationWalk], pipeline: str, p: WaistParams) -> list[CalibrationWalk]:
    """Decision W150: the walks with each ``c`` times the pivot factor its steps get under the parameters ``p``
    (:func:`~pdrlearn.waist._kernels.pivot_step_factor` of the ``c``-scaled lengths, as the tracker applies it after
    W19); walks without ``dpsi`` as they are."""
    from dataclasses import replace

    out = []
    for w in walks:
        if w.dpsi is None:
            out.append(w)
            continue
        c = w.factors()
        out.append(replace(w, c=c * K.pivot_step_factor(c * model_lengths(w, pipeline, p), w.dpsi), dpsi=None))
    return out


#: decision W150: the most refits of the pivot factors (each fit moves fewer steps across their chord; a
#: calibration walk with pivot steps converges in a few)
PIVOT_FIT_ITERATIONS = 50


def _walk_sums(walks: list[CalibrationWalk], x: str, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per walk with steps: ``sum(c x)``, ``sum(c)`` and the distance, for ``x`` = ``"f_hz"`` or ``"g"``
    (non-finite features count as 0, as the tracker's lengths do); the frequencies times ``scale`` (W118)."""
    rows = []
    for w in walks:
        if not len(w.f_hz):
            continue
        c = w.factors()
        v = np.nan_to_num(np.asarray(getattr(w, x), dtype=np.float64), nan=0.0)
        if x == "f_hz":  # the walking line is evaluated at most at WALK_MAX_HZ by the tracker (W37), at W118's f
            v = np.minimum(v * scale, WALK_MAX_HZ)
        rows.append((float(np.sum(c * v)), float(np.sum(c)), float(w.distance_m)))
    if not rows:
        raise DataError("calibration: no steps detected in the calibration walks; check the recordings")
    a = np.array(rows)
    return a[:, 0], a[:, 1], a[:, 2]


def fit_frequency(walks: list[CalibrationWalk], p: WaistParams) -> tuple[float, float, str]:
    """``(a, b)`` of ``SL = a f - b`` from walks of known length (seed 000 sec. II-D + least squares).

    Each walk gives one point (its steps' mean frequency, distance / steps), both weighted by the
    turning-step factors so that tracking the walk with the fitted line sums to its distance (decision
    W21; seed 000 eq. 1's harmonic mean would not: the tracker sums per-step ``a f_k - b``). With points
    spanning at least :data:`MIN_SPREAD_HZ` the line is the least-squares fit; otherwise the slope ``a``
    is kept and only the offset ``b`` is fitted (decision W8), exactly reproducing the walks' total.
    """
    sf, sc, d = _walk_sums(walks, "f_hz", p.frequency_scale())  # W118: the line's own (dimensionless) frequency
    ok = sc > 0
    sf, sc, d = sf[ok], sc[ok], d[ok]
    if not sc.size:
        raise DataError("calibration: every calibration step is a quarter turn or more; walk straight")
    f, sl = sf / sc, d / sc
    if f.max() - f.min() >= MIN_SPREAD_HZ and f.size >= 2:
        a, c = np.polyfit(f, sl, 1, w=np.sqrt(sc))
        return float(a), float(-c), f"least squares over {f.size} walks ({f.min():.2f}-{f.max():.2f} Hz)"
    a = p.a_walk
    b = float((a * sf.sum() - d.sum()) / sc.sum())
    span = f.max() - f.min()
    return float(a), b, f"offset only (walks span {span:.2f} Hz < {MIN_SPREAD_HZ} Hz; slope kept)"


def fit_pendulum(walks: list[CalibrationWalk], p: WaistParams) -> tuple[float, float, str]:
    """``(K, F)`` of seed 003 eq. 1 from walks of known length.

    Each walk gives ``D = K sum(c g) + F sum(c)`` (``c`` the turning-step factors, decision W21). With
    walks whose mean ``g`` differ by more than 10 % both are fitted by least squares, ``F`` of either sign
    as long as every walk's mean step comes out positive (decision W22); otherwise ``F`` is kept at its
    default and ``K`` fitted (decision W8).
    """
    sg, nn, d = _walk_sums(walks, "g")
    mean_g = sg / np.where(nn > 0, nn, 1.0)
    if len(d) >= 2 and (mean_g.max() - mean_g.min()) > 0.1 * mean_g.mean():
        (k, f), *_ = np.linalg.lstsq(np.column_stack([sg, nn]), d, rcond=None)
        if k > 0 and np.all(k * mean_g + f > 0):
            return float(k), float(f), f"K and F by least squares over {len(d)} walks"
    f = p.f_m
    k = float(np.sum(d - f * nn) / np.sum(sg)) if np.sum(sg) > 0 else float("nan")
    if not k > 0:
        raise DataError("calibration: the known distance is shorter than the foot-length term of the "
                        f"{int(round(nn.sum()))} detected steps (or no step shows vertical motion); "
                        "check --distance")
    return k, float(f), f"K only (F kept at {f:.3f} m; walks too similar to separate K and F)"


#: decision W48: a standard error of the calibrated gain needs at least this many strides (an sd of one value
#: is undefined)
MIN_GAIN_STRIDES = 2


def gain_standard_error(walks: list[CalibrationWalk], f_m: float = 0.0) -> tuple[float, int]:
    """``(se, n_strides)`` of the pendulum gain the walks calibrate (decision W48): the per-stride implied gains
    of :func:`~pdrlearn.waist._kernels.stride_gains` of every walk pooled, ``se = sd / sqrt(n_strides)``;
    ``se`` is NaN with fewer than :data:`MIN_GAIN_STRIDES` strides."""
    kj = [K.stride_gains(w.distance_m, w.g, w.factors(), f_m) for w in walks]
    x = np.concatenate(kj) if kj else np.zeros(0)
    x = x[np.isfinite(x)]
    if x.size < MIN_GAIN_STRIDES:
        return float("nan"), int(x.size)
    return float(np.std(x, ddof=1) / np.sqrt(x.size)), int(x.size)
