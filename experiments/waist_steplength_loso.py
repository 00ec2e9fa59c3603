"""Step-length model variants of `waist-pendulum` on the mobgap subjects, leave-one-subject-out (decision W25).

Per subject (HA001, HA002, MS001 of `pdrlearn fetch mobgap --out datasets/external`): the detected steps of
the `waist-pendulum` pipeline (offline IC detector, meta.json leg length; every model below is a change of
the pipeline without W27, `merge_fragments=False`, which the "pendulum" row reproduces) and per step a
length feature;
K calibrated on the subject's Test5 walk(s) (total reference length / total feature, as `pdrlearn calibrate`
fits K alone on walks of one speed, W8), tested on its Test11 (daily activities) bouts. Errors against
both references: the INDIP bout `Length` and the bout's own strides (steps x half the mean stride,
`pdrlearn.waist.evaluate.bout_stride_length`). Test5 LOO = Trial1 -> Trial2 / Trial2 -> Trial1.

Features (all x the W19 turning factor of the net step rotation unless said otherwise):
- pendulum: 2 sqrt(2 L h - h^2) (seed 003 eq. 1, the pipeline's model)
- pendulum, total rotation: W19's factor of the integral of |yaw rate| over the step instead of the net rotation
- Weinberg: (max - min of the vertical acceleration in the step)^(1/4) (Weinberg 2002, Analog Devices AN-602)
- (h f^2)^(1/4): Weinberg's law written with the pendulum's excursion h and step frequency f
- pendulum x (f / f_cal)^beta: K varies with step frequency; beta is a population parameter, chosen on the
  two other subjects (minimum of their mean median |error vs strides|) and applied to the held-out one
- pendulum + phi: an offset in the feature (K (g + phi), a negative F, W22), phi chosen the same way
- pendulum without fragments: steps shorter than half the median step of their walking sequence get no
  length (a spurious contact splitting one step)

Per-step h estimators and calibration variants of decision W27 (the pendulum with another h, both in the
calibration and in the test; K from the subject's Test5 as above):
- h stride mean: mean of the step's h and the next step's (the previous one's for the last step of a
  sequence) -- one h per stride, the left/right pair averaged
- h median of 3: median of the previous, this and the next step's h within the walking sequence
- h stride window: the displacement integrated over the stride IC_k -> IC_k+2 (the last step of a sequence:
  IC_k-1 -> IC_k+1), zero mean acceleration and velocity drift removed over the stride, h = peak-to-peak
  inside the step's part
- h band-pass: zero-lag 0.5-5 Hz band-pass of the vertical acceleration over the walking sequence (+- 2 s),
  integrated twice with a 0.5 Hz high-pass after each integration, h = peak-to-peak between the contacts
- h raw up axis: the whole-step h of the sensor's up axis (body frame z, gravity removed by the per-step
  mean) instead of the AHRS's gravity-aligned vertical
- h fragments merged (W27): the pipeline's default since W27, steps under half their sequence's median
  step merged with a neighbour (`pdrlearn.waist.steplength.fragment_windows`)
- h outliers -> sequence median: a step whose h lies outside [0.5, 2] x (or above 2 x) the median h of its
  walking sequence gets that median (a robust per-sequence length for implausible excursions)
- K shrunk to the population: K = (1 - w) K_own + w K_others, K_others calibrated on the other two
  subjects' Test5 walks (leave-one-subject-out), w = 0.25, 0.5
- pendulum (W27) x cos(turn)^p (decision W36): the W19 turning factor raised to p (p = 1: the pipeline's
  default model), p chosen on the two other subjects as beta and phi; pooled rows for every p
and a per-trial diagnostic of the straight walks (--diagnose): step frequency, h, reference step length,
K against the reference steps with and without the first / last step(s), correlation of the per-step
reference / pendulum ratio with step frequency, tilt of the sensor's up axis at rest; and (--turns) the
per-step reference / pendulum ratio of the Test11 steps by their pelvis rotation (W36).

Run: .venv/bin/python experiments/waist_steplength_loso.py [--external datasets/external]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import signal as sig

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.waist import _sequences
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import body_data, waist_imu
from pdrlearn.waist.evaluate import bout_stride_length, reference_bouts, steps_in_interval
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = {"HA001": ["Test5_Trial1", "Test5_Trial2"], "HA002": ["Test5_Trial2"],
            "MS001": ["Test5_Trial1", "Test5_Trial2"]}  # HA002 Test5 Trial1 has no reference (E3)
BETAS = np.round(np.arange(-1.0, 1.01, 0.25), 2)
PHIS = np.round(np.arange(-0.3, 0.21, 0.05), 2)
TURN_POWERS = np.array([0.0, 0.5, 1.0, 1.5, 2.0, 3.0])  # W36: exponents of the W19 factor cos(turn)
FRAGMENT_FRAC = 0.5


def _fragments(st: pd.DataFrame) -> np.ndarray:
    dur = (st["end_s"] - st["start_s"]).to_numpy(float)
    hn = st["has_next"].to_numpy(bool)
    out = np.zeros(len(st), dtype=bool)
    for seq in _sequences(st):
        q = seq[hn[seq]]
        if len(q) >= 3:
            out[q] = dur[q] < FRAGMENT_FRAC * np.median(dur[q])
    return out


BAND_HZ = (0.5, 5.0)  # W27 band-pass variant: the step band of slow to fast walking (0.8-2.5 Hz) and harmonics
OUTLIER_BAND = (0.5, 2.0)  # W27: h outside this x the sequence median is "implausible"
SHRINK = (0.25, 0.5)


def _displacement(a: np.ndarray, fs: float) -> np.ndarray:
    """Vertical displacement (m) of a window with zero mean acceleration, zero velocity drift and equal
    height at both ends (the integration of :func:`pdrlearn.waist._kernels.vertical_excursion`)."""
    a = np.asarray(a, dtype=np.float64) - np.mean(a)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) / fs)])
    v -= np.linspace(v[0], v[-1], v.size)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) / fs)])
    return x - np.linspace(x[0], x[-1], x.size)


def h_variants(st: pd.DataFrame, acc_v: np.ndarray, acc_up_raw: np.ndarray, fs: float, idx: np.ndarray
               ) -> dict[str, np.ndarray]:
    """Per-step h (m) of the W27 estimators (module docstring) for the rows of ``st`` (0 without a next
    contact)."""
    hn = st["has_next"].to_numpy(bool)
    h = st["h_m"].to_numpy(float)
    n = len(st)
    out = {k: np.zeros(n) for k in ("stride mean", "median of 3", "stride window", "band-pass", "raw up axis",
                                    "outliers -> sequence median", "high outliers -> sequence median")}
    for i in np.flatnonzero(hn):
        out["raw up axis"][i] = K.vertical_excursion(acc_up_raw, fs, idx[i], idx[i + 1])
    sos = sig.butter(2, BAND_HZ, btype="bandpass", fs=fs, output="sos")
    hp = sig.butter(2, BAND_HZ[0], btype="highpass", fs=fs, output="sos")
    pad = int(round(2.0 * fs))
    for seq in _sequences(st):
        w = seq[hn[seq]]
        if not len(w):
            continue
        hw = h[w]
        m = len(w)
        out["stride mean"][w] = [0.5 * (hw[j] + hw[j + 1]) if j + 1 < m else 0.5 * (hw[j] + hw[j - 1]) if m > 1
                                 else hw[j] for j in range(m)]
        out["median of 3"][w] = [np.median(hw[max(0, j - 1):j + 2]) for j in range(m)]
        for j, i in enumerate(w):
            i0, i2 = ((idx[i], idx[w[j + 1] + 1]) if j + 1 < m else (idx[w[j - 1]], idx[i + 1]) if j > 0
                      else (idx[i], idx[i + 1]))
            x = _displacement(acc_v[i0:i2 + 1], fs)[idx[i] - i0: idx[i + 1] - i0 + 1]
            out["stride window"][i] = float(np.ptp(x)) if x.size else 0.0
        a0, a1 = max(idx[w[0]] - pad, 0), min(idx[w[-1] + 1] + pad + 1, len(acc_v))
        if a1 - a0 > 32:
            x = np.cumsum(sig.sosfiltfilt(sos, acc_v[a0:a1])) / fs
            x = np.cumsum(sig.sosfiltfilt(hp, x)) / fs
            x = sig.sosfiltfilt(hp, x)
            for i in w:
                out["band-pass"][i] = float(np.ptp(x[idx[i] - a0: idx[i + 1] - a0 + 1]))
        med = float(np.median(hw))
        lo, hi = OUTLIER_BAND
        out["outliers -> sequence median"][w] = np.where((hw < lo * med) | (hw > hi * med), med, hw)
        out["high outliers -> sequence median"][w] = np.where(hw > hi * med, med, hw)
    return out


def step_features(session) -> tuple[pd.DataFrame, dict[str, np.ndarray]]:
    """Walking steps (with a next contact) and per step the raw features (before K)."""
    p, _ = resolve_params(session, None)
    st = get_pipeline("waist-pendulum")(session, params=p, merge_fragments=False).steps
    sm = get_pipeline("waist-pendulum")(session, params=p).steps  # W27 (default): fragments merged
    imu = waist_imu(session)
    fs = imu.fs
    idx = np.clip(np.round((st["event_s"].to_numpy(float) - imu.t[0]) * fs).astype(int), 0, len(imu.t) - 1)
    hn = st["has_next"].to_numpy(bool)
    rng = np.zeros(len(st))
    for i in np.flatnonzero(hn):
        a = imu.acc_v[idx[i]:idx[i + 1] + 1]
        rng[i] = a.max() - a.min()
    ev, end = st["event_s"].to_numpy(float), st["end_s"].to_numpy(float)
    rot = K.integrate_rate(imu.t, np.abs(imu.w_z - p.gyro_bias_rps), ev, end)
    h = st["h_m"].to_numpy(float)
    g = K.pendulum_length(h, p.leg_m)
    c = K.turning_step_factor(st["dyaw_rad"].to_numpy(float))
    f = np.nan_to_num(st["frequency_hz"].to_numpy(float), nan=0.0)
    feats = {"g": g, "c": c, "c_total": K.turning_step_factor(rot), "f": f, "weinberg": rng ** 0.25,
             "hf": (np.clip(h, 0, None) * f ** 2) ** 0.25, "fragment": _fragments(st).astype(float), "h": h}
    _, acc_b, _ = body_data(session)
    for name, hv in h_variants(st, imu.acc_v, acc_b[:, 2], fs, idx).items():
        feats["g:" + name] = K.pendulum_length(hv, p.leg_m)
    feats["g:fragments merged (W27)"] = K.pendulum_length(sm["h_m"].to_numpy(float), p.leg_m)
    feats["c:fragments merged (W27)"] = np.where(sm["merged"].to_numpy(bool), 0.0,
                                                 K.turning_step_factor(sm["dyaw_rad"].to_numpy(float)))
    return st[hn], {k: v[hn] for k, v in feats.items()}


def collect(ext: Path) -> dict[str, list[dict]]:
    """Per subject: one row per reference bout (Test5 and Test11) with the step features inside it."""
    data = {}
    for subj, cal in SUBJECTS.items():
        rows = []
        for t in [*cal, "Test11_Trial1"]:
            s = read_session(ext / f"mobgap_{subj}_{t}")
            st, x = step_features(s)
            for b in reference_bouts(s).itertuples():
                m = steps_in_interval(st, b.start_s, b.end_s)
                rows.append({"test": t, "L": float(b.length_m), "LS": bout_stride_length(s, b.start_s, b.end_s)[0],
                             **{k: v[m] for k, v in x.items()}})
        data[subj] = rows
    return data


def model_sum(r: dict, model: str, par: float = 0.0, f_cal: float = 1.0) -> float:
    if model == "pendulum":
        return float(np.sum(r["c"] * r["g"]))
    if model == "pendulum, total rotation":
        return float(np.sum(r["c_total"] * r["g"]))
    if model == "Weinberg":
        return float(np.sum(r["c"] * r["weinberg"]))
    if model == "(h f^2)^(1/4)":
        return float(np.sum(r["c"] * r["hf"]))
    if model == "pendulum x (f/f_cal)^beta":
        return float(np.sum(r["c"] * r["g"] * (r["f"] / f_cal) ** par))
    if model == "pendulum + phi":
        return float(np.sum(r["c"] * np.maximum(r["g"] + par, 0.0)))
    if model == "pendulum without fragments":
        return float(np.sum(r["c"] * r["g"] * (1.0 - r["fragment"])))
    if model == "pendulum (W27) x cos(turn)^p":  # W36: the W19 factor's exponent, p = 1 is the default
        c = r["c:fragments merged (W27)"]
        return float(np.sum(np.where(c > 0, np.clip(c, 1e-12, None) ** par, 0.0) * r["g:fragments merged (W27)"]))
    if model.startswith("pendulum, h "):
        v = model.removeprefix("pendulum, h ")
        return float(np.sum(r.get("c:" + v, r["c"]) * r["g:" + v]))
    raise ValueError(model)


def k_of(rows: list[dict], model: str = "pendulum", par: float = 0.0, f_cal: float = 1.0) -> float:
    """K of ``model`` calibrated on the Test5 bouts of ``rows`` (total length / total feature, W8)."""
    cal = [r for r in rows if r["test"].startswith("Test5")]
    return sum(r["L"] for r in cal) / sum(model_sum(r, model, par, f_cal) for r in cal)


def errors(rows: list[dict], model: str, par: float = 0.0, shrink: tuple[float, float] | None = None) -> dict:
    """Test11 median |per-bout error| vs ``Length`` and vs strides, and the Test5 trial -> trial errors;
    ``shrink = (w, K_others)``: K = (1 - w) K_own + w K_others (W27)."""
    cal = [r for r in rows if r["test"].startswith("Test5")]
    f_cal = float(np.median(np.concatenate([r["f"] for r in cal])))
    w, k_pop = shrink if shrink is not None else (0.0, 0.0)
    k = (1 - w) * k_of(rows, model, par, f_cal) + w * k_pop
    t11 = [r for r in rows if r["test"].startswith("Test11")]
    est = np.array([k * model_sum(r, model, par, f_cal) for r in t11])
    eL = 100 * (est - np.array([r["L"] for r in t11])) / np.array([r["L"] for r in t11])
    eS = 100 * (est - np.array([r["LS"] for r in t11])) / np.array([r["LS"] for r in t11])
    loo = []
    if len(cal) == 2:
        for a, b in ((0, 1), (1, 0)):
            k2 = (1 - w) * cal[a]["L"] / model_sum(cal[a], model, par, f_cal) + w * k_pop
            loo.append(100 * (k2 * model_sum(cal[b], model, par, f_cal) - cal[b]["L"]) / cal[b]["L"])
    return {"test11_median_vs_length_pct": float(np.median(np.abs(eL))),
            "test11_median_vs_strides_pct": float(np.median(np.abs(eS))),
            "test5_loo_pct": " / ".join(f"{x:+.1f}" for x in loo) or "-"}


H_MODELS = ["pendulum, h " + k for k in ("stride mean", "median of 3", "stride window", "band-pass", "raw up axis",
                                           "outliers -> sequence median", "high outliers -> sequence median",
                                           "fragments merged (W27)")]


def _reference_steps(session, st: pd.DataFrame) -> np.ndarray:
    """Per detected step the reference step length: half the mean of the reference strides containing
    its midpoint (NaN if none)."""
    rs = session.steps.dropna(subset=["length_m"])
    mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
    out = np.full(mid.size, np.nan)
    for i, m in enumerate(mid):
        x = rs[(rs["start_s"] <= m) & (rs["end_s"] >= m)]
        if len(x):
            out[i] = x["length_m"].mean() / 2.0
    return out


def diagnose(ext: Path) -> pd.DataFrame:
    """W27 angle 1: per straight-walk trial the gait and the pendulum's ratio to the reference steps."""
    rows = []
    for subj, cal in SUBJECTS.items():
        for t in cal:
            s = read_session(ext / f"mobgap_{subj}_{t}")
            st, x = step_features(s)
            b = reference_bouts(s).iloc[0]
            m = steps_in_interval(st, b.start_s, b.end_s)
            st, x = st[m], {k: v[m] for k, v in x.items()}
            ref, g = _reference_steps(s, st), x["g"]
            ratio = ref / g
            _, acc_b, _ = body_data(s)
            up = acc_b[: int(round(0.5 * 100))].mean(axis=0)
            rows.append({"trial": f"{subj} {t}", "steps": int(m.sum()), "f_hz": float(np.mean(x["f"])),
                         "h_cm": 100 * float(np.mean(x["h"])), "ref_step_m": float(np.nanmean(ref)),
                         "K_bout": float(b.length_m / np.sum(x["c"] * g)),
                         "K_ref_steps": float(np.nansum(ref) / np.sum(g[np.isfinite(ref)])),
                         "K_no_first_last": float(np.nansum(ref[1:-1]) / np.sum(g[1:-1][np.isfinite(ref[1:-1])])),
                         "K_no_first_last2": float(np.nansum(ref[1:-2]) / np.sum(g[1:-2][np.isfinite(ref[1:-2])])),
                         "ratio_cv_pct": 100 * float(np.nanstd(ratio) / np.nanmean(ratio)),
                         "corr_ratio_f": float(pd.Series(ratio).corr(pd.Series(x["f"]))),
                         "first_ratio": float(ratio[0]), "last_ratio": float(ratio[-1]),
                         "K_raw_up_axis": float(b.length_m / np.sum(x["c"] * x["g:raw up axis"])),
                         "tilt_at_rest_deg": float(np.degrees(np.arccos(abs(up[2]) / np.linalg.norm(up))))})
    return pd.DataFrame(rows)


def collect_errors(rows: list[dict], model: str, par: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Signed Test11 per-bout errors (%) vs ``Length`` and vs strides, K from the subject's Test5."""
    cal = [r for r in rows if r["test"].startswith("Test5")]
    f_cal = float(np.median(np.concatenate([r["f"] for r in cal])))
    k = k_of(rows, model, par, f_cal)
    t11 = [r for r in rows if r["test"].startswith("Test11")]
    est = np.array([k * model_sum(r, model, par, f_cal) for r in t11])
    L, LS = np.array([r["L"] for r in t11]), np.array([r["LS"] for r in t11])
    return 100 * (est - L) / L, 100 * (est - LS) / LS


def turn_per_step(ext: Path) -> pd.DataFrame:
    """W36: per Test11 walking step inside the bouts (default pipeline, merged fragments left out, a reference
    step length = half the mean reference stride containing its midpoint), the reference / pendulum chord
    ratio (K = 1, no turn factor) by the step's net pelvis rotation, and the slope b of
    log(ratio) = a + b log cos(rotation) (W19 assumes b = 1; rotation capped at 89 deg)."""
    rows = []
    for subj in SUBJECTS:
        s = read_session(ext / f"mobgap_{subj}_Test11_Trial1")
        p, _ = resolve_params(s, None)
        st = get_pipeline("waist-pendulum")(s, params=p).steps
        ref = _reference_steps(s, st)
        inside = np.zeros(len(st), dtype=bool)
        for b in reference_bouts(s).itertuples():
            inside |= steps_in_interval(st, b.start_s, b.end_s)
        g = K.pendulum_length(st["h_m"].to_numpy(float), p.leg_m)
        ok = inside & st["has_next"].to_numpy(bool) & ~st["merged"].to_numpy(bool) & np.isfinite(ref) & (g > 0.02)
        turn = np.degrees(np.abs(st["dyaw_rad"].to_numpy(float)))
        for r, gg, t in zip(ref[ok], g[ok], turn[ok], strict=True):
            rows.append({"subject": subj, "ratio": r / gg, "turn_deg": t})
    df = pd.DataFrame(rows)
    df["turn"] = pd.cut(df["turn_deg"], [0, 10, 20, 35, 50, 70, 180])
    out = df.groupby(["turn", "subject"], observed=True)["ratio"].agg(["size", "median"]).unstack("subject")
    slopes = {}
    for subj, g in df.groupby("subject"):
        x = np.log(np.cos(np.radians(np.minimum(g["turn_deg"].to_numpy(float), 89.0))))
        slopes[subj] = float(np.polyfit(x, np.log(g["ratio"].to_numpy(float)), 1)[0])
    out.loc["slope b of log(ratio) on log cos(turn)", :] = [slopes.get(sj, np.nan) if c == "median" else np.nan
                                                          for c, sj in out.columns]
    return out


def turn_power_sim(powers=(1.0, 1.5), users=(1, 2, 3)) -> pd.DataFrame:
    """W36: the simulator (`experiments/waist.py`'s protocol: users x scenarios A-D, calibrated on a measured
    60 m walk) with the W19 factor raised to each power, offline and realtime `waist-pendulum`."""
    from unittest import mock

    import waist as W

    base = K.turning_step_factor
    out = []
    for pw in powers:
        cfg = [c for c in W.CONFIGS if c[0] in ("waist-pendulum", "waist-pendulum realtime")]
        with mock.patch.object(W, "CONFIGS", cfg), \
                mock.patch.object(K, "turning_step_factor", lambda d, pw=pw: base(d) ** pw):
            out.append(W.summarize_sim(W.simulated(list(users))).assign(p=pw))
    return pd.concat(out, ignore_index=True)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--diagnose", action="store_true", help="also print the per-trial straight-walk diagnostic (W27)")
    ap.add_argument("--turns", action="store_true", help="also print the per-step turn diagnostic (W36)")
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 220)
    data = collect(args.external)
    rows = []
    fixed = ["pendulum", "pendulum, total rotation", "Weinberg", "(h f^2)^(1/4)", "pendulum without fragments",
             *H_MODELS]
    for subj, r in data.items():
        for m in fixed:
            rows.append({"subject": subj, "model": m, "parameter": "-", **errors(r, m)})
        others = [o for o in data if o != subj]
        k_pop = k_of([x for o in others for x in data[o]])
        for w in SHRINK:
            rows.append({"subject": subj, "model": f"pendulum, K shrunk {w:.2f} to the others' K",
                         "parameter": f"K_others {k_pop:.3f}", **errors(r, "pendulum", shrink=(w, k_pop))})
    grids = {}
    for m, grid in (("pendulum x (f/f_cal)^beta", BETAS), ("pendulum + phi", PHIS),
                    ("pendulum (W27) x cos(turn)^p", TURN_POWERS)):
        g = pd.DataFrame({s: [errors(r, m, x)["test11_median_vs_strides_pct"] for x in grid]
                          for s, r in data.items()}, index=grid)
        grids[m] = g
        for held in data:
            others = [s for s in data if s != held]
            best = float(g[others].mean(axis=1).idxmin())
            rows.append({"subject": held, "model": m + " (LOSO)", "parameter": f"{best:+.2f} (from {'+'.join(others)})",
                         **errors(data[held], m, best)})
    out = pd.DataFrame(rows).sort_values(["subject", "model"], kind="stable")
    print("Test11 bouts, K calibrated on the subject's Test5 (median |per-bout error|, %):")
    print(out.round(1).to_string(index=False))
    for m, g in grids.items():
        print(f"\n{m}: median |error vs strides| on Test11 per parameter value (%):")
        print(g.round(1).to_string())
    pooled = []
    for m in out["model"].unique():
        e = [collect_errors(data[sj], m) for sj in data] if "(LOSO)" not in m and "shrunk" not in m else None
        if e:
            eL, eS = (np.abs(np.concatenate([x[j] for x in e])) for j in (0, 1))
            pooled.append({"model": m, "test11_pooled_median_vs_length_pct": float(np.median(eL)),
                           "test11_pooled_median_vs_strides_pct": float(np.median(eS))})
    for x in TURN_POWERS:  # W36: pooled per exponent (fixed, no LOSO choice)
        m = "pendulum (W27) x cos(turn)^p"
        e = [collect_errors(data[sj], m, x) for sj in data]
        eL, eS = (np.abs(np.concatenate([y[j] for y in e])) for j in (0, 1))
        pooled.append({"model": f"{m}, p = {x:g}", "test11_pooled_median_vs_length_pct": float(np.median(eL)),
                       "test11_pooled_median_vs_strides_pct": float(np.median(eS))})
    print("\nTest11, all 15 bouts pooled (median |per-bout error|, %):")
    print(pd.DataFrame(pooled).round(1).to_string(index=False))
    if args.diagnose:
        print("\nStraight walks (Test5) per trial, W27 angle 1 (K_* = reference / pendulum over the bout's steps):")
        print(diagnose(args.external).round(3).to_string(index=False))
    if args.turns:
        print("\nTest11 steps: reference / pendulum chord (K = 1, no turn factor) by net pelvis rotation (W36):")
        print(turn_per_step(args.external).round(2).to_string())
        print("\nSimulator, W19 factor cos(turn)^p (W36):")
        print(turn_power_sim().round(2).to_string(index=False))
    res = ROOT / "experiments" / "results"
    out.to_csv(res / "waist_steplength_loso.csv", index=False, float_format="%.4g")
    print(f"wrote {res / 'waist_steplength_loso.csv'}")


if __name__ == "__main__":
    main()
