"""Realtime (causal) waist IC detector vs the offline one (decision W31).

Step F1 per Test11 recording of HA001, HA002, MS001 (`pdrlearn fetch mobgap --out datasets/external`),
the five Test5 walks and simulated A-D x 3 speeds x users 1-3, scored as `experiments/waist_ic_errors.py`
scores them (inside the reference bouts, untimed INDIP contacts unscored, 0.25 s), with the IC timing
error; and the decision delay (decision time - IC; simulator, the contacts a live stream would have decided,
the contacts decided by the end of the data left out).

Run: .venv/bin/python experiments/waist_realtime_ic.py [--external datasets/external] [--variants a,b]
Writes experiments/results/waist_realtime_ic.md (all variants only).
"""

from __future__ import annotations

import argparse
import contextlib
import logging
from pathlib import Path
from unittest import mock

import numpy as np
from scipy import signal as sg

from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.steps.evaluate import match_events, score_events
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import InitialContactDetector
from waist_ic_errors import SUBJECTS, TEST5, TOL, f1, scored  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
VARIANTS = {
    "offline": {"realtime": False},
    "realtime seed 003 (zero crossings, W17)": {"realtime": True, "delay_s": None},
    "realtime W31 (delay 1.75 s, hop 0.25 s)": {"realtime": True},
    "realtime W31 delay 1.25 s": {"realtime": True, "delay_s": 1.25},
    "realtime W31 delay 0.75 s": {"realtime": True, "delay_s": 0.75},
    "realtime W31 delay 1.9 s, hop 0.1 s": {"realtime": True, "delay_s": 1.9, "hop_s": 0.1},
    "realtime W31 history 20 s": {"realtime": True, "history_s": 20.0},
    # not adopted (W31): the lateral velocity's zero-phase filters padded with 2 s (odd / even reflection)
    # instead of scipy's default few samples, against the window-end transient of the side cue (W20)
    "realtime W31, side cue odd-padded 2 s": {"realtime": True, "pad": ("odd", 2.0)},
    "realtime W31, side cue even-padded 2 s": {"realtime": True, "pad": ("even", 2.0)},
}


def _padded_lateral_velocity(padtype: str, pad_s: float):
    def lv(acc_ml, fs, *, band_hz=K.SIDE_BAND_HZ):
        a = np.asarray(acc_ml, dtype=np.float64)
        if a.shape[0] < 32:
            return np.zeros_like(a)
        kw = {"padtype": padtype, "padlen": min(a.shape[0] - 1, int(pad_s * fs))}
        lo, hi = band_hz[0], min(band_hz[1], 0.45 * fs)
        bp = sg.butter(2, [lo, hi], btype="bandpass", fs=fs, output="sos")
        v = np.cumsum(sg.sosfiltfilt(bp, a, **kw)) / fs
        return sg.sosfiltfilt(sg.butter(2, lo, btype="highpass", fs=fs, output="sos"), v, **kw)
    return lv


def run(name: str, imu):
    kw = dict(VARIANTS[name])
    pad = kw.pop("pad", None)
    with contextlib.ExitStack() as stack:
        if pad is not None:
            stack.enter_context(mock.patch.object(K, "lateral_velocity", _padded_lateral_velocity(*pad)))
        return InitialContactDetector(**kw).detect(imu)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=Path("datasets/external"))
    ap.add_argument("--variants", default="")
    ap.add_argument("--sim", type=int, default=1)
    a = ap.parse_args()
    logging.basicConfig(level=logging.WARNING)
    names = [n for n in VARIANTS if not a.variants or any(v in n for v in a.variants.split(","))]
    sessions = {f"{s} Test11": [read_session(a.external / f"mobgap_{s}_Test11_Trial1")] for s in SUBJECTS}
    sessions["Test5 (5 walks)"] = [read_session(a.external / f"mobgap_{n}") for n in TEST5]
    imus = {k: [waist_imu(s) for s in v] for k, v in sessions.items()}
    sims = ([simulate(sc, u, speed=sp, rate_hz=100.0) for sc in "ABCD" for sp in ("slow", "normal", "fast")
             for u in (1, 2, 3)] if a.sim else [])
    sim_imus = [waist_imu(s) for s in sims]
    lines: list[str] = []
    out = print if a.variants else (lambda x, **_: (print(x, flush=True), lines.append(x)))
    out("| detector | " + " | ".join([*sessions, "Test11 pooled", "simulated A-D x 3 x users 1-3",
                                  "decision delay min / median / max (s, simulator)"]) + " |")
    out("|---" * (len(sessions) + 4) + "|")
    for n in names:
        cells, pool = [], [0, 0, 0]
        for k in sessions:
            tp = det = nref = 0
            dt: list[float] = []
            for s, imu in zip(sessions[k], imus[k], strict=True):
                ev, ref, i_d, i_r = scored(s, imu, run(n, imu))
                tp, det, nref = tp + i_d.size, det + ev.size, nref + ref.size
                dt += list(ev[i_d] - ref[i_r])
            if "Test11" in k:
                pool = [pool[0] + tp, pool[1] + det, pool[2] + nref]
            ms = 1e3 * np.asarray(dt)
            cells.append(f"{f1(tp, det, nref):.3f} (TP {tp}, det {det}, ref {nref}; "
                         f"IC {ms.mean():+.1f} ± {ms.std():.1f} ms)")
        cells.append(f"{f1(*pool):.3f}")
        tp = det = nref = 0
        dt, delays = [], []
        for s, imu in zip(sims, sim_imus, strict=True):
            d = run(n, imu)
            ev, ref = imu.t[d.ic_], s.extras["ics"]["ic_s"].to_numpy(float)
            live = d.decided_ < len(imu.t)  # the end-of-data flush decides the rest earlier
            delays += list((d.decided_ - d.ic_)[live] / imu.fs)
            sc = score_events(ev, ref)
            tp, det, nref = tp + sc["true_positives"], det + sc["count"], nref + sc["reference_count"]
            i_d, i_r = match_events(ev, ref, np.full(ref.size, TOL))
            dt += list(ev[i_d] - ref[i_r])
        ms = 1e3 * np.asarray(dt)
        cells.append(f"{f1(tp, det, nref):.4f} (TP {tp}, det {det}; IC {ms.mean():+.1f} ± {ms.std():.1f} ms)"
                     if sims else "-")
        dl = np.asarray(delays) if delays else np.full(1, np.nan)
        cells.append(f"{dl.min():.2f} / {np.median(dl):.2f} / {dl.max():.2f}" if "offline" not in n else "-")
        out(f"| {n} | " + " | ".join(cells) + " |", flush=True)
    if lines:
        (ROOT / "experiments" / "results" / "waist_realtime_ic.md").write_text(
            "# Realtime waist IC detector (decision W31)\n\n" + "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
