"""Per-user distance calibration of the foot displacement (docs/decisions/localization.md L26).

The foot engine (ZUPT/ZARU strapdown + white-noise-jerk Kalman filter, methods M2/M3) measures level
strides with a small systematic error: the accelerometer's own scale factors (a property of the unit,
ADXL345 sensitivity tolerance up to +-10 %, thesis Table 4 suggests ~0.3 %) and, at the PLASYS 20 Hz
rate, the information the five-sample averaging removes (-0.17 %, L25). Neither is observable in a
session (the foot is flat at every rest), but both are in the user's calibration exercises (thesis
ch.6/7.2.2), whose strides have known lengths: the ratio reference / estimate over the level, forward,
straight strides is the user's distance gain. It is estimated robustly (MAD outlier rejection, ratio of
sums), shrunk towards 1 by its standard error, stored in the user's model by ``pdrlearn train``
(``training_data.distance_calibration`` in the manifest) and applied by M3 to the level strides.

``distance_gain`` is the pure kernel; :func:`calibrate_distance` runs the tracker's own engine on
labelled sessions and returns the record stored in the model. The streamed tracker (``track --streaming``,
the runtime) measures each stride with its own stride-local kernel, whose bias differs from the offline
engine's (+0.8 % on the simulator, L40), so the record also holds the gain of that kernel
(``record["streaming"]``, decision L41), which streamed tracking applies instead.
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError, PdrlearnError

# the level-stride threshold and the rate check are shared with the streaming runtime (decision E14)
from pdrlearn.kernels.distance import LEVEL_DZ_M, RATE_TOLERANCE  # noqa: F401
from pdrlearn.warning_lines import isolated_warnings

log = logging.getLogger(__name__)

#: Prior sd of the gain (fraction): a MEMS scale-factor + non-linearity budget of 1 % (the same budget as
#: ``FootDisplacement(accel_scale_error=0.01)``, decision L21).
PRIOR_SD = 0.01
#: Largest |gain - 1| accepted (fraction): the ADXL345 sensitivity tolerance (230..282 LSB/g around 256 at
#: +-16 g full resolution, data sheet of thesis ref. [32]) is ~+-10 %; beyond it the labels are suspect.
MAX_DEVIATION = 0.10
#: A stride is "straight" when the heading changes less than this to both neighbours (deg).
STRAIGHT_TURN_DEG = 15.0
MIN_STRIDES = 10


def distance_gain(raw_m, ref_m, *, prior_sd: float = PRIOR_SD, outlier_mad: float = 3.5,
                  min_strides: int = MIN_STRIDES, max_deviation: float = MAX_DEVIATION) -> dict:
    """Robust distance gain ``reference / estimate`` of a set of strides.

    Parameters
    ----------
    raw_m, ref_m : estimated and reference stride lengths (m), positive, same length
    prior_sd : sd of the prior N(1, prior_sd^2) of the gain (fraction)
    outlier_mad : strides whose log ratio is further than this many robust sd (1.4826 MAD) from the
        median are left out
    min_strides : fewer usable strides -> gain 1 (with ``reason``)
    max_deviation : a ratio further than this from 1 -> gain 1 (with ``reason``): the labels are suspect

    Returns
    -------
    dict with ``gain`` (shrunk, applied), ``ratio`` (ratio of sums of the kept strides), ``se`` (its
    standard error), ``stride_sd`` (robust relative sd of one stride's estimate, 1.4826 MAD),
    ``weight`` (shrinkage weight prior^2 / (prior^2 + se^2)), ``n_strides`` (kept),
    ``n_outliers`` and ``reason`` (None when the gain was estimated).
    """
    raw = np.asarray(raw_m, float)
    ref = np.asarray(ref_m, float)
    if raw.shape != ref.shape:
        raise DataError(f"distance_gain: {raw.shape[0]} estimates for {ref.shape[0]} references")
    ok = np.isfinite(raw) & np.isfinite(ref) & (raw > 0) & (ref > 0)
    raw, ref = raw[ok], ref[ok]
    out = {"gain": 1.0, "ratio": None, "se": None, "stride_sd": None, "weight": 0.0, "n_strides": int(len(raw)),
           "n_outliers": 0, "reason": None}
    if len(raw) < min_strides:
        out["reason"] = f"{len(raw)} usable strides (< {min_strides})"
        return out
    lr = np.log(ref / raw)
    med = np.median(lr)
    mad = 1.4826 * np.median(np.abs(lr - med))
    keep = np.abs(lr - med) <= outlier_mad * mad if mad > 0 else np.ones(len(lr), bool)
    raw, ref = raw[keep], ref[keep]
    out["n_outliers"], out["n_strides"] = int((~keep).sum()), int(keep.sum())
    if len(raw) < min_strides:
        out["reason"] = f"{len(raw)} strides left after outlier rejection (< {min_strides})"
        return out
    ratio = float(ref.sum() / raw.sum())
    # ratio of sums = raw-weighted mean of the per-stride ratios; its standard error
    w = raw / raw.sum()
    r = ref / raw
    se = float(np.sqrt(np.sum(w**2 * (r - ratio) ** 2) * len(r) / max(len(r) - 1, 1)))
    out.update(ratio=ratio, se=se, stride_sd=float(1.4826 * np.median(np.abs(r / np.median(r) - 1.0))))
    if abs(ratio - 1.0) > max_deviation:
        out["reason"] = (f"ratio {ratio:.4f} is further than {max_deviation:.0%} from 1: check the labelled "
                         "stride lengths")
        return out
    weight = prior_sd**2 / (prior_sd**2 + se**2)
    out.update(gain=float(1.0 + weight * (ratio - 1.0)), weight=float(weight))
    return out


def straight_level_forward(steps: pd.DataFrame, *, level_dz_m: float = LEVEL_DZ_M,
                           turn_deg: float = STRAIGHT_TURN_DEG) -> np.ndarray:
    """Mask of the consecutive tracked strides (``steps``: ``raw_length_m`` m, ``dz_m`` m,
    ``heading_rad`` rad) that are level (|dz| < ``level_dz_m``), forward (positive length) and straight
    (heading change to both neighbours < ``turn_deg`` deg; the first and last stride are not)."""
    raw = steps["raw_length_m"].to_numpy(float)
    dz = steps["dz_m"].to_numpy(float)
    dh = np.degrees(np.abs(np.diff(np.unwrap(steps["heading_rad"].to_numpy(float)))))
    straight = (np.concatenate([[np.inf], dh]) < turn_deg) & (np.concatenate([dh, [np.inf]]) < turn_deg)
    return (raw > 0) & (np.abs(dz) < level_dz_m) & straight


def _labelled_flat_forward(labels: pd.DataFrame) -> np.ndarray:
    """Labels that are flat and forward where the table says so (columns ``terrain``/``direction``)."""
    mask = np.ones(len(labels), bool)
    for col, value in (("terrain", "flat"), ("direction", "forward")):
        if col in labels:
            mask &= labels[col].astype(str).to_numpy() == value
    return mask


def _offline_track(s, params):
    """The offline engine on the session's labelled strides (force stance where the session has force
    sensors; M3 with the labels' classes otherwise), gain 1."""
    from pdrlearn.track.plasys import track_plasys

    method = "M2" if s.has("fForceA") or s.has("fForceB") else "M3"
    return track_plasys(s, method=method, model=None if method == "M2" else "oracle", steps="labels",
                        heading="foot", params=params, distance_gain=1.0,
                        transfers=False)  # decision W439: a calibration reads no TUG


def _streaming_track(s, params):
    """The streamed tracker's stride kernel (``track --streaming``, the runtime) on the stance segmenter's
    strides, foot heading, gain 1; M2: each stride's measured displacement and height change."""
    from pdrlearn.track.plasys import track_plasys

    return track_plasys(s, method="M2", streaming=True, heading="foot", params=params, distance_gain=1.0)


def _estimate(sessions, track, params, kernel_kw) -> dict:
    """Track each labelled session with ``track``, keep the level, forward, straight strides matched to a
    flat forward label (IoU >= 0.5) and apply :func:`distance_gain` to all of them together."""
    from pdrlearn.io.resample import recorded_rate
    from pdrlearn.track import speed_domain
    from pdrlearn.track.evaluate import match_by_overlap

    raw_all, ref_all, used, skipped, rates, speeds, times = [], [], [], [], [], [], []
    for s in sessions:
        lab = s.steps
        if lab is None or "length_m" not in lab or not s.has("fAccelerometer", "fGyroscope"):
            skipped.append(f"{s.name}: no labelled stride lengths or no foot unit")
            continue
        try:
            # the tracker's notes (e.g. default length bounds) are not the user's; kept per thread (E179)
            with isolated_warnings("pdrlearn.track"):
                res = track(s, params)
        except PdrlearnError as exc:
            skipped.append(f"{s.name}: {exc}")
            continue
        lab = lab.reset_index(drop=True)
        if "speed_mps" in res.steps:  # decision L474: the tracked strides' speeds (L480: the cruise strides')
            v = pd.to_numeric(res.steps["speed_mps"], errors="coerce").to_numpy(float)
            speeds.append(v[speed_domain.cruise_strides(res.steps)])  # L480 / L481 adopted (W413: no switch)
        if "stride_time_s" in res.steps:  # decision C191: the same strides' stride times
            t = pd.to_numeric(res.steps["stride_time_s"], errors="coerce").to_numpy(float)
            times.append(t[speed_domain.cruise_strides(res.steps)])
        pairs = match_by_overlap(res.steps, lab, min_iou=0.5)
        if not pairs:
            skipped.append(f"{s.name}: no tracked stride matches a label")
            continue
        ei, ri = (np.array(v) for v in zip(*pairs, strict=True))
        st = res.steps.iloc[ei].reset_index(drop=True)
        mask = straight_level_forward(res.steps)[ei] & _labelled_flat_forward(lab.iloc[ri])
        raw_all.append(st["raw_length_m"].to_numpy(float)[mask])
        ref_all.append(lab["length_m"].to_numpy(float)[ri][mask])
        used.append(s.name)
        rates.append(recorded_rate(s, "fAccelerometer"))  # decision C56: judged at the recording's rate (E22)
    raw = np.concatenate(raw_all) if raw_all else np.zeros(0)
    ref = np.concatenate(ref_all) if ref_all else np.zeros(0)
    out = distance_gain(raw, ref, **kernel_kw)
    rec = [r for r, _ in rates]
    rate_hz = float(np.median([to or r for r, to in rates])) if rates else None
    if rec and (max(rec) - min(rec)) > RATE_TOLERANCE * max(rec):
        # decision C56: no rate of its own (not the median of the sessions' rates, a rate none was recorded at)
        out.update(gain=1.0, weight=0.0, reason="calibration sessions recorded at different foot rates "
                   f"{' / '.join(f'{r:g}' for r in sorted({round(r, 3) for r in rec}))} Hz")
        rate_hz = None
    out.update(rate_hz=rate_hz, sessions_used=used, sessions_skipped=skipped)
    speeds = np.concatenate(speeds) if speeds else np.zeros(0)
    out["speed_range_mps"] = speed_domain.training_speed_range(speeds)  # decision L474
    out["speed_range_strides"] = "cruise"  # decision L480: the strides the range was taken over
    out["stride_time_range_s"] = speed_domain.training_stride_time_range(  # decision C191
        np.concatenate(times) if times else np.zeros(0))
    return out


def calibrate_distance(sessions, *, params: dict | None = None, streaming: bool = True, **kernel_kw) -> dict:
    """The user's distance gain from labelled calibration sessions (strides with ``length_m``).

    Each session is tracked on its labelled strides with the M2/M3 foot engine (force stance where the
    session has force sensors; M3 with the labels' classes otherwise), the level, forward, straight
    strides are matched to their labels and :func:`distance_gain` is applied to all of them together.

    Returns the record stored in the user model: the :func:`distance_gain` dict plus ``rate_hz`` (foot
    accelerometer rate of the sessions, Hz), ``engine`` and ``sessions`` (names used / skipped and why).
    With ``streaming`` (default), ``record["streaming"]`` is the same estimate made with the streamed
    tracker's stride kernel (:func:`calibrate_streaming`, decision L41); the offline fields do not change.
    """
    sessions = list(sessions)
    out = _estimate(sessions, _offline_track, params, kernel_kw)
    out.update(engine="plasys M2/M3 foot engine", params=dict(params or {}))
    # key order as before L41 (rate_hz, engine, params, sessions_used, sessions_skipped)
    out = {**{k: v for k, v in out.items() if not k.startswith("sessions_")},
           "sessions_used": out["sessions_used"], "sessions_skipped": out["sessions_skipped"]}
    log.info("distance calibration: gain %.4f (ratio %s, se %s, %d strides)", out["gain"], out["ratio"],
             out["se"], out["n_strides"])
    if streaming:
        out["streaming"] = calibrate_streaming(sessions, **kernel_kw)
    return out


def calibrate_streaming(sessions, *, params: dict | None = None, **kernel_kw) -> dict:
    """The distance gain of the streamed tracker's stride kernel (decision L41): as
    :func:`calibrate_distance`, but each session is tracked as ``track --streaming`` and the runtime track it
    (the stance segmenter's strides, ``params`` = its settings, default the runtime's; each stride measured
    by :func:`~pdrlearn.kernels.stride.stride_motion` from its own samples; foot heading; gain 1); the same
    selection (level, forward, straight, labelled flat and forward) and kernel (:func:`distance_gain`).

    Returns the :func:`distance_gain` dict plus ``rate_hz``, ``engine`` and ``sessions_used`` /
    ``sessions_skipped``."""
    out = _estimate(list(sessions), _streaming_track, params, kernel_kw)
    out["engine"] = "streaming stride kernel (track --streaming, runtime)"
    log.info("distance calibration (streaming kernel): gain %.4f (ratio %s, se %s, %d strides)", out["gain"],
             out["ratio"], out["se"], out["n_strides"])
    return out


def streaming_calibration(rec: dict | None) -> dict | None:
    """The calibration record streamed tracking applies (decision L41): the streaming kernel's estimate
    (``rec["streaming"]``: gain, stride sd, refusal reason), or ``rec`` itself for a record made before L41
    (the offline engine's gain, as before). The foot rate it applies at is the record's ``rate_hz`` (the same
    sessions; the one rate a bundle carries, ``distance_gain_rate_hz``)."""
    if not isinstance(rec, dict) or not isinstance(rec.get("streaming"), dict):
        return rec
    return {**{k: v for k, v in rec.items() if k != "streaming"}, **rec["streaming"], "rate_hz": rec.get("rate_hz")}


#: decision L41: why a model calibrated before L41 keeps the thesis rule when streamed
PRE_L41_CALIBRATION = ("the model's distance calibration predates decision L41 (offline engine only; the streamed "
                       "stride kernel measures ~0.8 % longer strides): streamed with the thesis rule on every class, "
                       "as before; retrain (pdrlearn train) for the streamed gain and offline's rule (bayes, 0.95)")


def predates_streaming_calibration(rec: dict | None) -> bool:
    """True for a calibration record made before decision L41 (no ``streaming`` part): streamed tracking then
    has only the offline engine's gain, with which the bayes rule was measured worse than the thesis rule on
    scenarios C and D (L41, users 4-10), so the streamed default stays the thesis rule for such a model."""
    return isinstance(rec, dict) and not isinstance(rec.get("streaming"), dict)


def model_distance_calibration(model) -> dict | None:
    """The distance-calibration record of a trained user model (``data_summary`` / manifest
    ``training_data``), or None for models trained before L26."""
    summary = getattr(model, "data_summary", None) or {}
    rec = summary.get("distance_calibration")
    return rec if isinstance(rec, dict) else None
