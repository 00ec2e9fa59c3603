"""Where the PLL's daily-activity errors come from (docs/decisions/steps.md decision 18, waist.md W42).

Per-event breakdown of `PLLStepDetector` (``--gate-var``, default the detector's) and of the `waist-pll`
pipeline on the mobgap Test11 recordings against ``ics.csv`` (tolerance 0.25 s): in-bout false positives and
misses by cause, detections outside the reference bouts by activity; then the calibrated `waist-pll` bout
distance split into count and step length (calibration on Test5 as experiments/waist.py).

Run: .venv/bin/python experiments/pll_breakdown.py [--external datasets/external] [--gate-var 0.5]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
from scipy.signal import butter, filtfilt

from pdrlearn.io import read_session
from pdrlearn.steps import PLLStepDetector
from pdrlearn.steps.evaluate import match_events, untimed_mask
from pdrlearn.track import get_pipeline
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.evaluate import steps_in_interval, waist_metrics
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = {"HA001": ["Test5_Trial1", "Test5_Trial2"], "HA002": ["Test5_Trial2"],
            "MS001": ["Test5_Trial1", "Test5_Trial2"]}  # calibration walks as experiments/waist.py


def _gravity_dirs(s) -> np.ndarray:
    """Unit gravity direction in the sensor frame (0.5 Hz zero-phase low-pass): the trunk's posture."""
    acc = s["wAccelerometer"]
    b, a = butter(2, 0.5 / (0.5 * acc.rate_hz))
    g = filtfilt(b, a, acc.values, axis=0)
    return g / np.linalg.norm(g, axis=1)[:, None]


def breakdown(s, ev: np.ndarray, gate_std: float) -> dict[str, int]:
    imu = waist_imu(s)
    up = _gravity_dirs(s)
    sig = K.rolling_std(imu.acc_v, imu.fs, causal=False)
    ics = np.sort(s.extras["ics"]["ic_s"].dropna().to_numpy(float))
    b = s.extras["bouts"]
    b = b[b.level == "wb"]
    inb = np.zeros(len(ev), bool)
    for r in b.itertuples():
        inb |= (ev >= r.start_s - 0.25) & (ev <= r.end_s + 0.25)
    evb = ev[inb]
    un = untimed_mask(evb, s)
    evs = evb[~un]
    i_d, i_r = match_events(evs, ics, 0.25)
    md = np.zeros(len(evs), bool)
    md[i_d] = True
    mr = np.zeros(len(ics), bool)
    mr[i_r] = True
    c: dict[str, int] = {"in-bout scored": len(evs), "in-bout at untimed contacts": int(un.sum()),
                         "matched": int(md.sum()), "reference": len(ics)}

    def add(k: str) -> None:
        c[k] = c.get(k, 0) + 1

    dif = np.diff(ics)
    period = float(np.median(dif[dif < 1.5]))
    for k in np.flatnonzero(~md):
        t = evs[k]
        nb = [abs(t - evs[j]) for j in (k - 1, k + 1) if 0 <= j < len(evs)]
        if nb and min(nb) < 0.6 * period:
            add("FP second peak inside a step (< 0.6 step period from a neighbour)")
        elif np.any(np.abs(ics[~mr] - t) < 0.6):
            add("FP misplaced (a missed contact within 0.6 s)")
        else:
            add("FP other")
    for j in np.flatnonzero(~mr):
        t = ics[j]
        if sig[min(np.searchsorted(imu.t, t), len(sig) - 1)] < gate_std:
            add("FN gated (2 s std of vertical acc under the gate)")
        elif np.any(np.abs(evs[~md] - t) < 0.6):
            add("FN misplaced (an unmatched detection within 0.6 s)")
        elif not np.any(np.abs(evs - t) < 1.0):
            add("FN in a detection gap (none within 1 s)")
        else:
            add("FN other")
    edges = np.concatenate([b.start_s.to_numpy(), b.end_s.to_numpy()])
    for t in ev[~inb]:
        i0, i1 = np.searchsorted(imu.t, [t - 1.5, t + 1.5])
        w = up[i0:i1]
        m = w.mean(0) / np.linalg.norm(w.mean(0))
        tilt = np.degrees(np.arccos(np.clip(w @ m, -1, 1)))
        dyaw = np.degrees(abs(imu.yaw[min(i1, len(imu.t) - 1)] - imu.yaw[i0]))
        if np.min(np.abs(edges - t)) < 1.5:
            add("OUT within 1.5 s of a bout end")
        elif tilt.max() > 10:
            add("OUT posture change (trunk > 10 deg from its 3 s mean posture)")
        elif dyaw > 45:
            add("OUT turning (> 45 deg in 3 s)")
        elif sig[np.searchsorted(imu.t, t)] < 0.7:
            add("OUT weak motion (std < 0.7 m/s^2)")
        else:
            add("OUT walking-like, unlabelled")
    return c


def decomposition(ext: Path, subj: str) -> tuple[float, float, float, float, int, int]:
    """Calibrated waist-pll (no W19 factor) bout distance: tracked, detected steps x SL(reference cadence),
    reference steps x SL(reference cadence), reference (W25 strides), detected and reference step counts."""
    cal = [read_session(ext / f"mobgap_{subj}_{c}") for c in SUBJECTS[subj]]
    base, _ = resolve_params(cal[0], None)
    base.options = {"turn_factor": False}
    p = calibrate(cal, "waist-pll", params=base)
    s = read_session(ext / f"mobgap_{subj}_Test11_Trial1")
    res = get_pipeline("waist-pll")(s, params=p, turn_factor=False)
    m = waist_metrics(res.steps, s)
    ics = np.sort(s.extras["ics"]["ic_s"].dropna().to_numpy(float))
    out = np.zeros(6)
    for b in m["bouts"]:
        st = res.steps[steps_in_interval(res.steps, b["start_s"], b["end_s"]) & res.steps.has_next.to_numpy()]
        ic = ics[(ics >= b["start_s"] - 1e-6) & (ics <= b["end_s"] + 1e-6)]
        f_ref = (len(ic) - 1) / (ic[-1] - ic[0])
        sl = p.a_walk * min(f_ref, 2.2) - p.b_walk  # W37 cap
        out += [b["tracked_m"], len(st) * sl, b["n_reference_steps"] * sl, b["reference_strides_m"], len(st),
                b["n_reference_steps"]]
    return tuple(out)


def main() -> None:
    logging.disable(logging.WARNING)
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--gate-var", type=float, default=None, help="PLL gate (m^2/s^4); default the detector's")
    args = ap.parse_args()
    kw = {} if args.gate_var is None else {"gate_var": args.gate_var}
    gate_std = float(np.sqrt(PLLStepDetector(**kw).gate_var))
    for label in ("pll detector", "waist-pll pipeline"):
        total: dict[str, int] = {}
        for subj in SUBJECTS:
            s = read_session(args.external / f"mobgap_{subj}_Test11_Trial1")
            if label == "pll detector":
                ev, g = PLLStepDetector(**kw).detect(s)["event_s"].to_numpy(float), gate_std
            else:
                ev, g = get_pipeline("waist-pll")(s).steps["event_s"].to_numpy(float), 0.5
            c = breakdown(s, np.sort(ev), g)
            print(f"{label} {subj} Test11: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
            for k, v in c.items():
                total[k] = total.get(k, 0) + v
        print(f"{label}, all three:")
        for k in sorted(total):
            print(f"  {total[k]:4d}  {k}")
    print("calibrated waist-pll bout distance (m): tracked | detected steps x SL(ref cadence) | "
          "reference steps x SL(ref cadence) | reference (W25) | steps detected / reference")
    for subj in SUBJECTS:
        r = decomposition(args.external, subj)
        print(f"  {subj}: {r[0]:.2f} | {r[1]:.2f} | {r[2]:.2f} | {r[3]:.2f} | {r[4]:.0f} / {r[5]:.0f}")


if __name__ == "__main__":
    main()
