"""Decision 25 of docs/decisions/steps.md: a period-scaled IC search for slow steps, measured against its
adoption rule (written in the decision before this script was run).

Candidate: the offline IC detector's kept vertical maxima (`InitialContactDetector().detect(imu).anchor_`:
its sequence rules decide on the maxima, not on the ICs, so the candidate only re-locates each IC); for a
maximum whose local step period (W18's `_kernels._period_around`) exceeds 0.5 s, the IC is the largest local
AP maximum within 0.5 x that period before it (seed 003 sec. 3.1 / Fig. 1: the higher AP peak is the IC);
otherwise W3's IC unchanged.

Scored: Test11 and Test5 of the mobgap subjects as `pdrlearn steps` scores them (`score_steps`: inside the
bouts, untimed contacts and one detection per same-foot gap unscored, 0.25 s); the simulator (A-D x
slow/normal/fast x users 1-3, 100 Hz; the model pelvis and S27's realistic pelvis) against every contact
(`score_events`, as W41). The baseline is checked equal to `pdrlearn steps --detector waist-ic`'s contacts.

Run: PYTHONPATH=$PWD python experiments/waist_ic_period.py [--external datasets/external] [--sim-users 3]
Writes experiments/results/waist_ic_period.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import itertools
import logging
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.signal import lowpass
from pdrlearn.sim import simulate
from pdrlearn.steps.detectors import get_detector
from pdrlearn.steps.evaluate import score_events, score_steps
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.events import InitialContactDetector

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = ("HA001", "HA002", "MS001")
TEST5 = ("HA001_Test5_Trial1", "HA001_Test5_Trial2", "HA002_Test5_Trial2", "MS001_Test5_Trial1",
         "MS001_Test5_Trial2")
NORMAL_STEP_S = 0.5  # decision 7: a normal step; W16's 0.25 s IC search is half of it
SEARCH_FRAC = 0.25 / NORMAL_STEP_S  # W16 / decision 7 (no fitted constant)
MAX_STEP_S = 1.5  # W16


def contacts(imu, candidate: bool) -> np.ndarray:
    """IC times of the default offline detector; with ``candidate`` the period-scaled search (decision 25)."""
    det = InitialContactDetector().detect(imu)
    ic, anchor = det.ic_.copy(), det.anchor_
    if candidate and anchor.size:
        fs = imu.fs
        ap = lowpass(imu.acc_ap, min(20.0, 0.4 * fs), fs, causal=False)  # the detector's AP (ap_cutoff_hz)
        order = np.argsort(anchor, kind="stable")
        a = anchor[order].astype(float)
        max_gap = K._max_gap(MAX_STEP_S, fs)
        for k, i in enumerate(order):
            period = K._period_around(a, k, max_gap) / fs
            if not np.isfinite(period) or period <= NORMAL_STEP_S:
                continue
            p = int(anchor[i])
            lo = max(0, p - int(round(SEARCH_FRAC * period * fs)))
            seg = ap[lo:p + 1]
            if seg.size < 3:
                continue
            inner = np.flatnonzero((seg[1:-1] >= seg[:-2]) & (seg[1:-1] > seg[2:])) + 1
            if inner.size:  # seed 003 Fig. 1: the higher AP peak is the IC
                ic[i] = lo + int(inner[np.argmax(seg[inner])])
    return np.sort(imu.t[ic])


def real_counts(session, ev: np.ndarray) -> tuple[int, int, int]:
    s = score_steps(pd.DataFrame({"event_s": ev, "unit": "waist"}), session)
    return s["true_positives"], s["scored_count"], s["reference_count"]


def f1(c) -> float:
    tp, det, ref = (sum(x) for x in zip(*c, strict=True))
    return 2 * tp / (det + ref) if det + ref else float("nan")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.basicConfig(level=logging.ERROR)
    cli = get_detector("waist-ic")
    rows = {}
    print("| recording | default F1 (TP/det/ref) | candidate F1 (TP/det/ref) |\n|---|---|---|")
    for name in [f"{s}_Test11_Trial1" for s in SUBJECTS] + list(TEST5):
        s = read_session(args.external / f"mobgap_{name}")
        imu = waist_imu(s)
        base = contacts(imu, False)
        ref_cli = np.sort(cli.detect(s)["event_s"].to_numpy(float))
        assert np.allclose(base, ref_cli), f"baseline differs from `pdrlearn steps --detector waist-ic` on {name}"
        rows[name] = (real_counts(s, base), real_counts(s, contacts(imu, True)))
        b, c = rows[name]
        print(f"| {name} | {f1([b]):.3f} ({b[0]}/{b[1]}/{b[2]}) | {f1([c]):.3f} ({c[0]}/{c[1]}/{c[2]}) |")
    t11 = [rows[f"{s}_Test11_Trial1"] for s in SUBJECTS]
    print(f"| Test11 pooled | {f1([r[0] for r in t11]):.3f} | {f1([r[1] for r in t11]):.3f} |")
    print("\nNot part of the rule: Test11 against INDIP (matched contacts) and against the lab's Stereophoto contacts "
          "(docs/external-data.md X4; every detection, recall and timing as `step_metrics` reports them)")
    for sub in SUBJECTS:
        s = read_session(args.external / f"mobgap_{sub}_Test11_Trial1")
        imu = waist_imu(s)
        cells = []
        for cand in (False, True):
            m = step_metrics(pd.DataFrame({"event_s": contacts(imu, cand)}), s)
            cells.append(f"INDIP IC {m['ic_timing_mean_ms']:+.1f} +- {m['ic_timing_sd_ms']:.1f} ms; Stereophoto "
                         f"recall {m['stereo_recall']:.3f} ({m['n_stereo_matched']}), IC "
                         f"{m['ic_timing_stereo_mean_ms']:+.1f} +- {m['ic_timing_stereo_sd_ms']:.1f} ms")
        print(f"- {sub}: default {cells[0]} -> candidate {cells[1]}")
    sim = {}
    for pelvis in ("model", "realistic"):
        acc = ([], [])
        moved = []
        for scenario, speed in itertools.product("ABCD", ("slow", "normal", "fast")):
            for user in range(1, args.sim_users + 1):
                s = simulate(scenario, user, speed=speed, rate_hz=100.0, pelvis=pelvis)
                imu = waist_imu(s)
                ref = s.extras["ics"]["ic_s"].to_numpy(float)
                for j, cand in enumerate((False, True)):
                    ev = contacts(imu, cand)
                    sc = score_events(ev, ref)
                    acc[j].append((sc["true_positives"], sc["count"], sc["reference_count"]))
                if acc[0][-1] != acc[1][-1]:
                    moved.append(f"u{user} {scenario} {speed}: {acc[0][-1]} -> {acc[1][-1]}")
        sim[pelvis] = acc
        tot = [[sum(x) for x in zip(*a, strict=True)] for a in acc]
        print(f"\nsimulator ({pelvis} pelvis) F1 default {f1(acc[0]):.4f} (TP {tot[0][0]}, det {tot[0][1]}, ref "
              f"{tot[0][2]}) -> candidate {f1(acc[1]):.4f} (TP {tot[1][0]}, det {tot[1][1]}, ref {tot[1][2]})")
        for m in moved:
            print("  changed:", m)
    # the adoption rule of decision 25
    d = {s: f1([r[1]]) - f1([r[0]]) for s, r in zip(SUBJECTS, t11, strict=True)}
    a_ok = all(v >= -0.005 for v in d.values())
    b_ok = f1([r[1] for r in t11]) - f1([r[0] for r in t11]) >= 0.01
    c_ok = all(abs(f1([rows[n][1]]) - 1.0) < 1e-12 for n in TEST5)
    d_ok = True
    for acc in sim.values():
        t0, t1 = ([sum(x) for x in zip(*a, strict=True)] for a in acc)
        d_ok &= t1[0] >= t0[0] and abs(t1[1] - t1[2]) <= abs(t0[1] - t0[2])
    print(f"\nadoption rule: (a) no subject down > 0.005: {a_ok} ({', '.join(f'{k} {v:+.3f}' for k, v in d.items())}); "
          f"(b) pooled +0.01: {b_ok}; (c) Test5 all 1.000: {c_ok}; (d) simulator: {d_ok}. "
          f"Verdict: {'adopt' if a_ok and b_ok and c_ok and d_ok else 'option' if a_ok and c_ok and d_ok else 'drop'}")


if __name__ == "__main__":
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main()
    (ROOT / "experiments" / "results" / "waist_ic_period.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
