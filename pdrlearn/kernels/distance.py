"""The per-user distance calibration rule (docs/decisions/localization.md L26), shared by ``pdrlearn track``
(:func:`pdrlearn.track.plasys.track_plasys`, offline and ``streaming=True``) and the streaming runtime
(:class:`pdrlearn.runtime.tracker.Tracker`, decision E14 of docs/decisions/export.md).

A calibration record (``gain``, ``rate_hz``, ``stride_sd``, ``reason``: the dict of
:func:`pdrlearn.displace.calibrate_distance`, stored in the user model; a bundle carries it in its
``displacement`` parameters) applies only at the foot rate it was estimated at, and its gain multiplies
the horizontal displacement of the level strides only. numpy + standard library only (runtime boundary).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from pdrlearn.errors import DataError

#: A stride is "level" when its estimated height change is below this (m): half a stair rise, as the
#: simulator's terrain label (decisions S3: 0.08 m) - a stair stride climbs 2 x 0.15-0.18 m (L26).
LEVEL_DZ_M = 0.10
#: Relative foot-rate difference beyond which a calibration does not apply: the 20 Hz averaging bias the
#: gain corrects is rate specific (L26).
RATE_TOLERANCE = 0.01
#: decision B465: a rate difference matters for a calibration (the foot gain here, W87's waist K) only when the lower
#: of the two rates is under this (Hz): simulated users 15100-15102 resampled to 25-1000 Hz moved the waist K at most
#: 0.72 % and the foot distance at most 0.09 % among 50-1000 Hz, K 3.21-5.05 % from 25 Hz to 50-1000 Hz
RATE_MATTERS_HZ = 50.0


def rate_matters(a_hz: float, b_hz: float) -> bool:
    """Decision B465: whether a calibration made at ``a_hz`` can differ at ``b_hz`` (Hz): the lower rate is under
    :data:`RATE_MATTERS_HZ` (whether the two differ at all is the caller's tolerance)."""
    return min(float(a_hz), float(b_hz)) < RATE_MATTERS_HZ
#: Decision L144 (candidate, measured; see docs/decisions/localization.md): a "sustained slope" is a run of at
#: least SLOPE_RUN_STRIDES consecutive strides whose height changes share a sign and are each >= SLOPE_DZ_M (m):
#: 0.04 m is 3 % of a 1.3 m stride, 6 strides ~8 m of walking. None = off (L39 alone).
SLOPE_DZ_M = 0.04
SLOPE_RUN_STRIDES = 6
#: Decision L144: whether L39's level rule and L127's floor count keep a sustained slope (the measured candidate)
SUSTAINED_SLOPE = False
#: Decision L304 (candidate, measured in L305): L39's threshold applied to the mean |dz| of a run of at least
#: RUN_MEAN_STRIDES consecutive strides whose height changes share a sign and are each >= RUN_MEMBER_DZ_M (m), so a
#: slope's strides are kept or levelled together whichever way the foot's integration bias pushes them (L291).
#: 0.05 m = half L39's 0.10 m (as L39 is half a stair stride's rise); 3 strides: the shortest run that is more than
#: a stride and its two neighbours, within one 9 m run of a 1:12 ramp (6-7 strides). None of them fitted.
RUN_MEMBER_DZ_M = 0.05
RUN_MEAN_STRIDES = 3
#: Decision L304: whether L39's level rule keeps the strides of such a run whose mean |dz| >= LEVEL_DZ_M
RUN_MEAN_LEVEL = False
#: Decisions L189 / L206 (options, measured and not adopted): the values of the ``gated_level_dz`` keyword of
#: ``track_plasys(streaming=True)`` / ``track_streaming`` and the runtime ``Tracker`` (decision L550: a keyword, no
#: module switch). True (L189; not adopted by its rule (d): one real level walk ended 0.061 m higher): an M3 stride
#: whose terrain class the confidence gate (L18) dropped gets L184's level rule (:func:`unclassed_level_dz`), as
#: offline M3 does (``plasys.GATED_LEVEL_DZ``). ``"summed"`` (L206; measured in L207, not adopted: a real level walk
#: ends higher and two real stair climbs read lower): L39's threshold on the summed dz of a run of such strides
#: (:func:`summed_level_step`) instead of each stride's own dz. False (the default): raw heights.
GATED_LEVEL_MODES = (False, True, "summed")


def check_gated_level_dz(value):
    """``gated_level_dz`` (decision L550) checked: False, True (np.bool_ too) or ``"summed"``, else one DataError
    line naming the values (1 / 0 are not taken for True / False)."""
    if isinstance(value, bool | np.bool_):
        return bool(value)
    if isinstance(value, str) and value == "summed":
        return value
    raise DataError(f"gated_level_dz={value!r} is not one of False, True, 'summed' (decisions L189, L206: the level "
                    "rule for streamed M3 strides whose terrain class the gate dropped; False, the default, keeps "
                    "their raw heights)")


def rate_differs(trained_hz: float, fs_hz: float, *, tolerance: float = RATE_TOLERANCE) -> bool:
    """Whether a rate ``fs_hz`` (Hz) differs from the rate something was trained or calibrated at by more
    than ``tolerance`` of the latter: the distance calibration's check (decision E14), shared by the step
    classifiers' rate warning (decision C18)."""
    return abs(float(trained_hz) - float(fs_hz)) > tolerance * float(trained_hz)


def classifier_rate_warning(off: Mapping, *, resample_hint: bool = False) -> str:
    """Decision C18's one line for the units of ``off`` (unit -> ``{"trained_hz", "session_hz"}``) whose
    step classifiers run at another rate than they were trained at; shared by ``pdrlearn track``
    (``track.plasys.rate_check``) and ``pdrlearn run`` (``runtime.resample.InputStage``, whose own line names
    ``--resample``). ``resample_hint``: name ``--resample`` of ``track`` / ``evaluate`` (decision B113)."""
    units = " and ".join(off)
    trained = " / ".join(f"{v['trained_hz']:g}" for v in off.values())
    now = " / ".join(f"{v['session_hz']:.4g}" for v in off.values())
    return (f"the model's step classifiers were trained at {trained} Hz, the session's {units} unit"
            f"{'s run' if len(off) > 1 else ' runs'} at {now} Hz: its step classes may be unreliable; "
            "train on the user's own data at this rate (`pdrlearn train`)"
            + (", or pass --resample to resample the session to the model's rate (decision B113)"
               if resample_hint else ""))


def applicable_calibration(rec: Mapping | None, fs_hz: float, *, tolerance: float = RATE_TOLERANCE,
                           resampled_hz: float | None = None) -> tuple[Mapping | None, str | None]:
    """The calibration record if it applies at the foot rate ``fs_hz`` (Hz), else None and the warning.

    A record without ``rate_hz`` applies at any rate (as before the rate was stored). ``resampled_hz``: the
    data was recorded at ``fs_hz`` and resampled to this rate (the runtime's ``--resample``, E22: the
    calibration is judged at the recording's rate), which the warning says."""
    if rec is None:
        return None, None
    rate = rec.get("rate_hz")
    if rate and rate_differs(float(rate), fs_hz, tolerance=tolerance) and rate_matters(float(rate), fs_hz):  # B465
        if resampled_hz is None:
            at = f"runs at {float(fs_hz):g} Hz"
        elif float(fs_hz) < float(resampled_hz):
            at = (f"was recorded at {float(fs_hz):g} Hz (resampled to {float(resampled_hz):g} Hz, which does not "
                  "restore what the recording rate lost)")
        else:  # decision B135: a higher recording rate lost nothing; the gain is judged at it (B113)
            at = (f"was recorded at {float(fs_hz):g} Hz (resampled to {float(resampled_hz):g} Hz; the gain is "
                  "judged at the recording's rate, decision B113)")
        return None, (f"the model's distance calibration was made at {float(rate):g} Hz, the foot unit {at}: "
                      f"not applied: the bias it corrects depends on the rate under {RATE_MATTERS_HZ:g} Hz (above it "
                      "the foot distance moved at most 0.09 % between rates, decision B465); recalibrate on a walk "
                      f"recorded at {float(fs_hz):g} Hz")
    return rec, None


def calibrated_stride_sd(rec: Mapping | None) -> float | None:
    """The user's relative sd of one stride's length estimate from an applicable record (None: none, or
    the calibration was refused - ``reason`` set)."""
    if rec is None or rec.get("reason") is not None or not rec.get("stride_sd"):
        return None
    return float(rec["stride_sd"])


def sustained_slope(dz: np.ndarray, *, slope_dz_m: float = SLOPE_DZ_M, run: int = SLOPE_RUN_STRIDES) -> np.ndarray:
    """Decision L144: boolean mask of the strides (``dz`` m, walking order) inside a run of at least ``run``
    consecutive strides whose height changes share a sign and are each at least ``slope_dz_m`` in size - a
    slope climbed or descended stride after stride, which L39's per-stride threshold alone calls level."""
    dz = np.nan_to_num(np.asarray(dz, dtype=np.float64).ravel(), nan=0.0, posinf=0.0, neginf=0.0)
    sign = np.where(dz >= slope_dz_m, 1, np.where(dz <= -slope_dz_m, -1, 0))
    mask = np.zeros(len(dz), dtype=bool)
    edges = np.flatnonzero(np.diff(sign)) + 1
    for a, b in zip(np.r_[0, edges], np.r_[edges, len(dz)], strict=True):
        if sign[a] != 0 and b - a >= run:
            mask[a:b] = True
    return mask


def run_mean_kept(dz: np.ndarray, *, level_dz_m: float = LEVEL_DZ_M, member_dz_m: float = RUN_MEMBER_DZ_M,
                  run: int = RUN_MEAN_STRIDES) -> np.ndarray:
    """Decision L304: boolean mask of the strides (``dz`` m, walking order) inside a run of at least ``run``
    consecutive strides whose height changes share a sign, are each at least ``member_dz_m`` in size, and whose mean
    |dz| reaches L39's ``level_dz_m``: L39's threshold judged on the run, not on each stride (L291)."""
    dz = np.nan_to_num(np.asarray(dz, dtype=np.float64).ravel(), nan=0.0, posinf=0.0, neginf=0.0)
    sign = np.where(dz >= member_dz_m, 1, np.where(dz <= -member_dz_m, -1, 0))
    mask = np.zeros(len(dz), dtype=bool)
    edges = np.flatnonzero(np.diff(sign)) + 1
    for a, b in zip(np.r_[0, edges], np.r_[edges, len(dz)], strict=True):
        if sign[a] != 0 and b - a >= run and np.abs(dz[a:b]).mean() >= level_dz_m:
            mask[a:b] = True
    return mask


def level_dz(dz: np.ndarray, *, level_dz_m: float = LEVEL_DZ_M, slope: bool | None = None,
             run_mean: bool | None = None) -> np.ndarray:
    """Height changes ``dz`` (m) with the level strides' (|dz| < ``level_dz_m``, half a stair rise) set to 0:
    the altitude rule of the thesis (ch. 7.2.2: a flat step keeps its altitude) decided by the stride's own
    height change where there are no terrain classes (decision L39). ``slope`` (default
    :data:`SUSTAINED_SLOPE`, decision L144): a stride of a :func:`sustained_slope` keeps its height. ``run_mean``
    (default :data:`RUN_MEAN_LEVEL`, decision L304): a stride of a :func:`run_mean_kept` run keeps its height. A new
    array."""
    dz = np.asarray(dz, dtype=np.float64)
    level = np.abs(dz) < level_dz_m
    if SUSTAINED_SLOPE if slope is None else slope:
        level &= ~sustained_slope(dz)
    if RUN_MEAN_LEVEL if run_mean is None else run_mean:
        level &= ~run_mean_kept(dz, level_dz_m=level_dz_m)
    return np.where(level, 0.0, dz)


def unclassed_level_dz(dz: np.ndarray, classed: np.ndarray) -> np.ndarray:
    """Decision L184: :func:`level_dz` (L39) on the strides without a terrain class (``classed`` False, e.g. the
    confidence gate of L18 dropped it); the classed strides keep the height their class rule gave. A new array."""
    dz = np.asarray(dz, dtype=np.float64)
    return np.where(np.asarray(classed, dtype=bool), dz, level_dz(dz))


def unclassed_level_dz_one(dz: float, classed: bool) -> float:
    """Decision L189: :func:`unclassed_level_dz` of one stride (the runtime's call, one stride at a time): the
    same function on a 1-element array, so the same threshold; L144's sustained slope (off by default) needs a run of
    strides, which one stride never is."""
    return float(unclassed_level_dz(np.array([dz], dtype=np.float64), np.array([classed]))[0])


def summed_level_step(dz: float, classed: bool, run_dz: float) -> tuple[float, float]:
    """Decision L206, one stride: a stride without a terrain class (``classed`` False) whose own |dz| is under
    L39's :data:`LEVEL_DZ_M` extends the run of such strides, whose summed raw dz so far is ``run_dz`` (m); it is
    levelled (0) iff the run's summed dz including it stays under :data:`LEVEL_DZ_M` in absolute value (L39's
    threshold on the run's sum; thesis ch. 7.2.2: a flat step keeps its altitude). Any other stride keeps ``dz`` and
    ends the run. Returns (the stride's dz, the run's summed dz after it: 0.0 when the run ended)."""
    if classed or not abs(dz) < LEVEL_DZ_M:
        return dz, 0.0
    run_dz += dz
    return (0.0 if abs(run_dz) < LEVEL_DZ_M else dz), run_dz


def streamed_gated_level_dz(dz: np.ndarray, classed: np.ndarray, mode=False) -> np.ndarray:
    """The streamed paths' level rule for strides without a terrain class, by ``mode`` (the callers'
    ``gated_level_dz`` keyword, decision L550): True = :func:`unclassed_level_dz` per stride (decision L189),
    ``"summed"`` = :func:`summed_level_step` along the strides in order (decision L206), False = the heights unchanged
    (:func:`check_gated_level_dz`'s line for any other value). A new array."""
    mode = check_gated_level_dz(mode)
    dz = np.asarray(dz, dtype=np.float64)
    if mode is True:
        return unclassed_level_dz(dz, classed)
    if mode == "summed":
        out, run = dz.copy(), 0.0
        for i, (d, c) in enumerate(zip(dz.tolist(), np.asarray(classed, dtype=bool).tolist(), strict=True)):
            out[i], run = summed_level_step(d, c, run)
        return out
    return dz.copy()


def terrain_from_dz(dz, valid=None, *, level_dz_m: float = LEVEL_DZ_M) -> np.ndarray:
    """Decision L424: (n,) object ``"up"`` / ``"down"`` / ``"flat"`` from each stride's height change ``dz`` (m) by
    L39's level threshold (``level_dz_m``: half a stair stride's rise), None where ``valid`` (n,) bool is False."""
    dz = np.asarray(dz, dtype=float)
    out = np.where(dz >= level_dz_m, "up", np.where(dz <= -level_dz_m, "down", "flat")).astype(object)
    if valid is not None:
        out[~np.asarray(valid, dtype=bool)] = None
    return out


def apply_level_gain(disp: np.ndarray, gain: float, *, level_dz_m: float = LEVEL_DZ_M) -> np.ndarray:
    """Displacements ``disp (B, 3)`` (or one ``(3,)``) m with the horizontal part of the level strides
    (|dz| < ``level_dz_m``) multiplied by ``gain``; stair strides keep theirs (L26). A new array."""
    d = np.array(disp, dtype=np.float64)
    if gain == 1.0:
        return d
    rows = d.reshape(-1, 3)
    level = np.abs(rows[:, 2]) < level_dz_m
    rows[level, :2] *= gain
    return d


def apply_level_gain_one(dx: float, dy: float, dz: float, gain: float, *, level_dz_m: float = LEVEL_DZ_M
                         ) -> tuple[float, float, float]:
    """:func:`apply_level_gain` of one stride's displacement on Python floats (the same products; the
    runtime's call, decision E17 in docs/decisions/export.md)."""
    if abs(dz) < level_dz_m:
        return dx * gain, dy * gain, dz
    return dx, dy, dz
