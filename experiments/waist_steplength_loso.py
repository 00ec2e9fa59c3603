"""Step-length model variants of `waist-pendulum` on the mobgap subjects, leave-one-subject-out (decision W25).

Per subject (HA001, HA002, MS001 of `pdrlearn fetch mobgap --out datasets/external`): the detected steps of
the `waist-pendulum` pipeline (offline IC detector, meta.json leg length) and per step a length feature;
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

Run: .venv/bin/python experiments/waist_steplength_loso.py [--external datasets/external]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.waist import _sequences
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import bout_stride_length, reference_bouts, steps_in_interval
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = {"HA001": ["Test5_Trial1", "Test5_Trial2"], "HA002": ["Test5_Trial2"],
            "MS001": ["Test5_Trial1", "Test5_Trial2"]}  # HA002 Test5 Trial1 has no reference (E3)
BETAS = np.round(np.arange(-1.0, 1.01, 0.25), 2)
PHIS = np.round(np.arange(-0.3, 0.21, 0.05), 2)
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


def step_features(session) -> tuple[pd.DataFrame, dict[str, np.ndarray]]:
    """Walking steps (with a next contact) and per step the raw features (before K)."""
    p, _ = resolve_params(session, None)
    st = get_pipeline("waist-pendulum")(session, params=p).steps
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
             "hf": (np.clip(h, 0, None) * f ** 2) ** 0.25, "fragment": _fragments(st).astype(float)}
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
    raise ValueError(model)


def errors(rows: list[dict], model: str, par: float = 0.0) -> dict:
    cal = [r for r in rows if r["test"].startswith("Test5")]
    f_cal = float(np.median(np.concatenate([r["f"] for r in cal])))
    k = sum(r["L"] for r in cal) / sum(model_sum(r, model, par, f_cal) for r in cal)
    t11 = [r for r in rows if r["test"].startswith("Test11")]
    est = np.array([k * model_sum(r, model, par, f_cal) for r in t11])
    eL = 100 * (est - np.array([r["L"] for r in t11])) / np.array([r["L"] for r in t11])
    eS = 100 * (est - np.array([r["LS"] for r in t11])) / np.array([r["LS"] for r in t11])
    loo = []
    if len(cal) == 2:
        for a, b in ((0, 1), (1, 0)):
            k2 = cal[a]["L"] / model_sum(cal[a], model, par, f_cal)
            loo.append(100 * (k2 * model_sum(cal[b], model, par, f_cal) - cal[b]["L"]) / cal[b]["L"])
    return {"test11_median_vs_length_pct": float(np.median(np.abs(eL))),
            "test11_median_vs_strides_pct": float(np.median(np.abs(eS))),
            "test5_loo_pct": " / ".join(f"{x:+.1f}" for x in loo) or "-"}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 220)
    data = collect(args.external)
    rows = []
    fixed = ["pendulum", "pendulum, total rotation", "Weinberg", "(h f^2)^(1/4)", "pendulum without fragments"]
    for subj, r in data.items():
        for m in fixed:
            rows.append({"subject": subj, "model": m, "parameter": "-", **errors(r, m)})
    grids = {}
    for m, grid in (("pendulum x (f/f_cal)^beta", BETAS), ("pendulum + phi", PHIS)):
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
    res = ROOT / "experiments" / "results"
    out.to_csv(res / "waist_steplength_loso.csv", index=False, float_format="%.4g")
    print(f"wrote {res / 'waist_steplength_loso.csv'}")


if __name__ == "__main__":
    main()
