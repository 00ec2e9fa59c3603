"""Pendulum h estimators of `waist-pendulum` through the whole pipeline, leave-one-recording-out (decision W40).

Each variant replaces :func:`pdrlearn.waist._kernels.vertical_excursion` (the h of one step, used by the
tracker and by `pdrlearn calibrate` alike) and runs `experiments/waist.py`'s protocols for the calibrated
offline `waist-pendulum` (W18/W19/W27 on): the mobgap subjects (`--external`, from `pdrlearn fetch mobgap`):
each Test5 trial -> the other (HA001, MS001), the subject's Test5 -> its Test11 (daily activities; median
|per-bout error| vs INDIP `Length` / vs the bouts' own strides, W25); pooled medians over the 4 Test5 and 15
Test11 bouts; and the simulator (users 1-3 calibrated on a measured "60 m" walk, scenarios A-D, median
|distance error| vs the strides).

Variants (none published; each addresses one source of the per-stride scatter, W40):
- base: IC -> IC, mean acceleration and linear velocity / position drift removed, h = peak-to-peak
  (W10, seed 003 sec. 3.2)
- rms: the same displacement, h = 2 sqrt(2) x its standard deviation (the peak-to-peak of a sinusoid of
  that power): less sensitive to a single sample's extreme than the peak-to-peak
- ext25: integrated over the step extended by a quarter of its duration on both sides (drift removal
  over a longer window), h = peak-to-peak inside IC -> IC
- local period: the window is the local step period (autocorrelation peak of the vertical acceleration
  within 0.75-1.25 x the IC-to-IC time, +- 1 s around the step, peak >= 0.5) centred on the step's
  midpoint, instead of the detected contacts (IC jitter moves the window's length)

Run: .venv/bin/python experiments/waist_h_variants.py [--external datasets/external] [--variants base rms]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.waist._kernels as KK
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.evaluate import waist_metrics
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
from waist import external_runs, walked_between_contacts  # noqa: E402

BASE = KK.vertical_excursion
EXTEND = 0.25  # ext25: the window grows by this fraction of the step on both sides
PERIOD_RANGE = (0.75, 1.25)  # local period: lags searched, x the IC-to-IC time
PERIOD_MIN_CORR = 0.5  # local period: weaker autocorrelation peaks keep the contacts' window


def _displacement(a: np.ndarray, fs: float) -> np.ndarray:
    """The base estimator's displacement (zero mean acceleration, linear velocity / position drift removed)."""
    a = np.asarray(a, dtype=np.float64) - np.mean(a)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) / fs)])
    v -= np.linspace(v[0], v[-1], v.size)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) / fs)])
    return x - np.linspace(x[0], x[-1], x.size)


def h_rms(acc_v: np.ndarray, fs: float, i0: int, i1: int) -> float:
    a = acc_v[i0:i1 + 1]
    return 0.0 if a.size < 3 else float(2.0 * np.sqrt(2.0) * np.std(_displacement(a, fs)))


def h_extended(acc_v: np.ndarray, fs: float, i0: int, i1: int) -> float:
    e = int(round(EXTEND * (i1 - i0)))
    j0, j1 = max(i0 - e, 0), min(i1 + e, len(acc_v) - 1)
    if j1 - j0 < 3:
        return 0.0
    return float(np.ptp(_displacement(acc_v[j0:j1 + 1], fs)[i0 - j0:i1 - j0 + 1]))


def h_local_period(acc_v: np.ndarray, fs: float, i0: int, i1: int) -> float:
    n = i1 - i0
    if n < 10:
        return BASE(acc_v, fs, i0, i1)
    mid, half = (i0 + i1) // 2, int(round(1.0 * fs))
    x = np.asarray(acc_v[max(mid - half - n, 0):min(mid + half + n, len(acc_v) - 1) + 1], dtype=np.float64)
    x = x - x.mean()
    lags = np.arange(int(PERIOD_RANGE[0] * n), int(PERIOD_RANGE[1] * n) + 1)
    lags = lags[lags < x.size - 10]
    if not lags.size:
        return BASE(acc_v, fs, i0, i1)
    c = np.array([np.dot(x[:-q], x[q:]) / np.sqrt(np.dot(x[:-q], x[:-q]) * np.dot(x[q:], x[q:])) for q in lags])
    j = int(np.argmax(c))
    if c[j] < PERIOD_MIN_CORR or j in (0, len(c) - 1):
        return BASE(acc_v, fs, i0, i1)
    j0 = max(mid - int(lags[j]) // 2, 0)
    return BASE(acc_v, fs, j0, min(j0 + int(lags[j]), len(acc_v) - 1))


VARIANTS = {"base": BASE, "rms": h_rms, "ext25": h_extended, "local period": h_local_period}


def evaluate(ext: Path, sim_users: int = 3) -> dict:
    """The protocols of the module docstring with the current ``vertical_excursion``."""
    rows, bouts = [], []
    for cal_names, test_name in external_runs(ext):
        cal = [read_session(ext / n) for n in cal_names]
        test = read_session(ext / test_name)
        base, _ = resolve_params(cal[0], None)
        p = calibrate(cal, "waist-pendulum", params=base)
        m = waist_metrics(get_pipeline("waist-pendulum")(test, params=p).steps, test)
        subj, t = test_name.split("_")[1], "_".join(test_name.split("_")[2:])
        rows.append({"subject": subj, "test": t, "err": m["distance_error_pct"],
                     "med": m["bout_distance_error_median_pct"], "med_s": m["bout_distance_error_strides_median_pct"]})
        bouts += [{"test": t, **b} for b in m["bouts"]]
    df, b = pd.DataFrame(rows), pd.DataFrame(bouts)
    t5, t11 = b[b.test.str.startswith("Test5")], b[b.test.str.startswith("Test11")]
    out = {"Test5 trial -> trial (%)": " ".join(f"{r.subject} {r.err:+.1f}" for r in df[df.test.str.startswith("Test5")]
                                                .itertuples()),
           "Test11 median vs Length / strides (%)": ", ".join(
               f"{r.subject} {r.med:.1f} / {r.med_s:.1f}" for r in df[df.test.str.startswith("Test11")].itertuples()),
           "Test5 pooled median (%)": float(t5.error_pct.abs().median()),
           "Test11 pooled median vs Length (%)": float(t11.error_pct.abs().median()),
           "Test11 pooled median vs strides (%)": float(t11.error_strides_pct.abs().median())}
    if sim_users:
        from pdrlearn.sim import simulate
        from pdrlearn.track.evaluate import evaluate_track

        e = []
        for u in range(1, sim_users + 1):
            c = simulate("walk", u, "normal", rate_hz=100.0, seed=1, length_m=60.0)
            base, _ = resolve_params(c, None)
            p = calibrate([c], "waist-pendulum", distances=[walked_between_contacts(c)], params=base)
            for sc in "ABCD":
                s = simulate(sc, u, "normal", rate_hz=100.0)
                e.append(abs(evaluate_track(get_pipeline("waist-pendulum")(s, params=p), s)["distance_error_pct"]))
        out["simulator |distance error| median (%)"] = float(np.median(e))
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--variants", nargs="*", default=list(VARIANTS), choices=list(VARIANTS))
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 250)
    pd.set_option("display.max_colwidth", 80)
    rows = []
    for v in args.variants:
        KK.vertical_excursion = VARIANTS[v]
        try:
            rows.append({"h": v, **evaluate(args.external, args.sim_users)})
        finally:
            KK.vertical_excursion = BASE
        print(pd.DataFrame(rows[-1:]).round(3).to_string(index=False), flush=True)
    out = pd.DataFrame(rows)
    print("\nwaist-pendulum, calibrated, per h estimator:")
    print(out.round(3).T.to_string(header=False))
    res = ROOT / "experiments" / "results"
    out.to_csv(res / "waist_h_variants.csv", index=False, float_format="%.4g")
    print(f"wrote {res / 'waist_h_variants.csv'}")


if __name__ == "__main__":
    main()
