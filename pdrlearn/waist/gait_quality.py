"""Lower-back gait quality of each walking bout: the trunk's sway and stability measures (decision W350).

A vestibular clinic reads walking's stability from the lower back's acceleration (T3 finding F9): how smooth and
rhythmic the trunk moves stride after stride, how much it sways sideways. Per bouts.csv row of a lower-back track
with at least :data:`MIN_STRIDES` strides (contact k to contact k + 2), in the gravity-aligned, heading-following
frame of the waist pipelines (:func:`pdrlearn.waist.ahrs.waist_imu`: AP along the heading, ML across it, V up):

* harmonic ratios ``hr_ap``, ``hr_v``, ``hr_ml`` (Menz, Lord & Fitzpatrick 2003, Gait Posture 18:35-46, as
  recalled): the amplitude spectrum of each stride's acceleration at the first :data:`N_HARMONICS` harmonics of the
  stride frequency; AP and V (two peaks per stride) sum of even over sum of odd harmonics, ML (one sway per stride)
  odd over even; the mean over the bout's strides. A symmetric, smooth walk has high ratios.
* step and stride regularity and step symmetry, V and AP (Moe-Nilssen & Helbostad 2004, J Biomech 37:121-126, as
  recalled): the peaks of the unbiased autocorrelation near one step and one stride
  (:func:`pdrlearn.waist.rhythm.autocorrelation_peak`); symmetry = step regularity / stride regularity (1: the two
  steps alike; the ratio form of Tura et al. 2010, as recalled).
* RMS of the AP, ML and V acceleration (linearly detrended over the bout) and the ML RMS ratio, ML RMS over the
  RMS of the acceleration vector (Sekine et al. 2013, as recalled).

A bout under :data:`MIN_STRIDES` strides gets empty values; a foot track's bouts too (the foot has no trunk sway).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.waist.rhythm import autocorrelation_peak

#: decision W350: a bout of fewer strides gets no gait-quality values: 10 strides, the number from which the harmonic
#: ratio settles (Bellanca et al. 2013, Gait Posture 38:1004-1008, as recalled; Menz et al. 2003 read 10 strides)
MIN_STRIDES = 10
#: Menz, Lord & Fitzpatrick 2003 (as recalled): the first 20 harmonics of the stride frequency
N_HARMONICS = 20

#: decision W352: the one warning line of ``track --gait-quality`` (the measures are opt-in until understood)
NOT_VALIDATED = ("gait quality (--gait-quality) is not validated against real recordings: healthy mobgap walks read "
                 "below the published healthy ranges (W352); compare within a person at the same walking speed "
                 "(the same walker slowing down reads lower regularity and harmonic ratios, W360), not against "
                 "published norms")
#: decision W350: bouts.csv's gait-quality columns, in order
QUALITY_COLUMNS = ("hr_ap", "hr_v", "hr_ml", "step_regularity_v", "stride_regularity_v", "step_symmetry_v",
                   "step_regularity_ap", "stride_regularity_ap", "step_symmetry_ap", "rms_ap_mps2", "rms_ml_mps2",
                   "rms_v_mps2", "rms_ml_ratio")


def harmonic_ratio(stride: np.ndarray, *, odd_over_even: bool = False) -> float:
    """Harmonic ratio of one stride's acceleration (Menz et al. 2003, as recalled): the DFT of the stride (mean
    removed; bin k is the k-th harmonic of the stride frequency), amplitudes of harmonics 1..:data:`N_HARMONICS` (as
    many as the samples hold); sum of the even ones over the odd ones (AP, V), ``odd_over_even`` for ML. NaN when the
    denominator is (numerically) 0 or the stride holds fewer than 2 harmonics."""
    x = np.asarray(stride, dtype=np.float64)
    amp = np.abs(np.fft.rfft(x - x.mean()))[1:N_HARMONICS + 1]
    if amp.size < 2:
        return float("nan")
    odd, even = float(amp[0::2].sum()), float(amp[1::2].sum())  # amp[0] is harmonic 1 (odd)
    num, den = (odd, even) if odd_over_even else (even, odd)
    return num / den if den > 1e-9 * (num + den) else float("nan")  # a denominator of rounding noise: none


def _rms(x: np.ndarray) -> float:
    """RMS of ``x`` after removing its least-squares line (the bout's slow drift)."""
    n = np.arange(x.size, dtype=np.float64)
    resid = x - np.polyval(np.polyfit(n, x, 1), n)
    return float(np.sqrt(np.mean(resid ** 2)))


def bout_quality(t: np.ndarray, acc_ap: np.ndarray, acc_ml: np.ndarray, acc_v: np.ndarray, fs: float,
                 contacts_s: np.ndarray) -> dict:
    """:data:`QUALITY_COLUMNS` of one bout whose initial contacts are ``contacts_s`` (s, on the clock ``t``; the
    acceleration in the gravity-aligned frame, m/s^2, sampled at ``fs`` Hz); NaN each with fewer than
    :data:`MIN_STRIDES` strides (contacts - 2, as bouts.csv's ``n_strides``)."""
    out = dict.fromkeys(QUALITY_COLUMNS, float("nan"))
    c = np.sort(np.asarray(contacts_s, dtype=np.float64))
    c = c[np.isfinite(c)]
    if c.size - 2 < MIN_STRIDES:
        return out
    idx = np.searchsorted(t, c)
    a, b = int(idx[0]), int(idx[-1])
    if b - a < 2 * N_HARMONICS:
        return out
    axes = {"ap": np.asarray(acc_ap, float), "ml": np.asarray(acc_ml, float), "v": np.asarray(acc_v, float)}
    for name, x in axes.items():  # Menz et al. 2003: one ratio per stride (contact k to k + 2), their mean
        out[f"hr_{name}"] = float(np.nanmean([harmonic_ratio(x[i:j], odd_over_even=name == "ml")
                                              for i, j in zip(idx[:-2], idx[2:], strict=True)]))
    step_s = float(np.median(np.diff(c)))
    for name in ("v", "ap"):  # Moe-Nilssen & Helbostad 2004 (as recalled): unbiased autocorrelation, step / stride
        seg = axes[name][a:b]
        step = autocorrelation_peak(seg, fs, step_s, unbiased=True)
        stride = autocorrelation_peak(seg, fs, 2.0 * step_s, unbiased=True)
        out[f"step_regularity_{name}"], out[f"stride_regularity_{name}"] = step, stride
        out[f"step_symmetry_{name}"] = step / stride if stride > 0 else float("nan")  # Tura et al. 2010 (as recalled)
    rms = {name: _rms(x[a:b]) for name, x in axes.items()}
    out.update({f"rms_{name}_mps2": r for name, r in rms.items()})
    total = float(np.sqrt(sum(r ** 2 for r in rms.values())))
    out["rms_ml_ratio"] = rms["ml"] / total if total > 0 else float("nan")  # Sekine et al. 2013 (as recalled)
    return out


def add_bout_quality(bouts: pd.DataFrame, steps: pd.DataFrame, imu) -> pd.DataFrame:
    """Decision W350: ``bouts`` (a lower-back track's bouts.csv table) with :data:`QUALITY_COLUMNS` filled from the
    contacts (``steps.event_s``) between each row's ``start_s`` and ``end_s`` and ``imu``
    (:class:`~pdrlearn.waist.ahrs.WaistIMU`: ``t``, ``acc_ap``, ``acc_ml``, ``acc_v``, ``fs``)."""
    if not len(bouts) or not len(steps) or "event_s" not in steps:
        return bouts
    ev = steps["event_s"].to_numpy(float)
    rows = [bout_quality(imu.t, imu.acc_ap, imu.acc_ml, imu.acc_v, imu.fs, ev[(ev >= s) & (ev <= e)])
            for s, e in zip(bouts["start_s"].to_numpy(float), bouts["end_s"].to_numpy(float), strict=True)]
    for col in QUALITY_COLUMNS:
        bouts[col] = [r[col] for r in rows]
    return bouts


def quality_medians(bouts: pd.DataFrame) -> dict:
    """Decision W350: summary.json's ``gait_quality``: ``n_bouts``, the bouts with values (10+ strides), and the median
    of each of :data:`QUALITY_COLUMNS` over them (None without such a bout)."""
    have = bouts.dropna(subset=["hr_ap"]) if "hr_ap" in bouts else bouts.iloc[:0]
    return {"n_bouts": len(have), **{c: float(have[c].median()) if len(have) and have[c].notna().any() else None
                                      for c in QUALITY_COLUMNS}}
