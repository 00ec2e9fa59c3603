"""Decisions L259-L263: bilateral gait (``pdrlearn gait``) against the references it can be checked on.

Run: ``PYTHONPATH=$PWD python experiments/bilateral_gait.py [--sim]`` (datasets/external linked for walk4x10).

Part 1, real pairs: gaitmap_level_left + _right (mocap IC and TC per stride: step time, double / single support)
and external gaitmap_walk4x10_left + _right (mocap IC only: step time). Both feet's folders are one recording
(same sample count, t = 0 at the same first sample). Printed: the walk measures of the tracks and of the labels,
and per matched step / cycle (same foot, its IC within 0.15 s of the label's, as L66 / L73 match strides) the
error tracked - reference.

Part 2 (``--sim``), simulated users 5100-5129: the simulator instruments the right foot only (S1), so no
two-foot simulated pair exists. What is checked: (a) the kernel on the simulator's both-feet contacts
(``ics.csv``) reads the step-time ratio the simulator was given (1 + ``--step-time-asymmetry``, S35), and
(b) the tracked right foot's IC timing against the true ICs (a lag common to both tracked feet cancels in
a step time; what does not cancel is the difference of the two feet's errors), and (c) a half-tracked pair, the
tracked right foot's ICs with the true left ICs: what mixing one tracked foot with contacts from elsewhere does.
"""

from __future__ import annotations

import logging
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.track.bilateral import bilateral_gait, pair_sessions
from pdrlearn.track.plasys import track_plasys

logging.disable(logging.WARNING)
ROOT = Path(__file__).resolve().parents[1] / "datasets"
PAIRS = [("real/gaitmap_level_left", "real/gaitmap_level_right"),
         ("external/gaitmap_walk4x10_left", "external/gaitmap_walk4x10_right")]
SIM_USERS = range(5100, 5130)
SIM_ASYM = (0.0, 0.1, 0.2, 0.3, 0.39)  # S35's example 0.39; user u gets SIM_ASYM[u % 5]


def matched(a: pd.DataFrame, b: pd.DataFrame, key: str, cols: list[str], tol: float = 0.15) -> pd.DataFrame:
    """Rows of ``a`` (tracked) matched to ``b`` (reference): same ``side``, ``key`` within ``tol`` s; errors a - b."""
    rows = []
    for _, r in a.iterrows():
        c = b[(b["side"] == r["side"]) & ((b[key] - r[key]).abs() < tol)]
        if len(c) == 1:
            rows.append({"side": r["side"], **{k: r[k] - c.iloc[0][k] for k in cols}})
    return pd.DataFrame(rows, columns=["side", *cols])


def stat(x, scale: float = 1.0, unit: str = "") -> str:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)] * scale
    if not len(x):
        return "none"
    return f"n={len(x)} median {np.median(x):+.1f}{unit}, SD {x.std(ddof=1) if len(x) > 1 else 0:.1f}{unit}"


def walk_line(name: str, w: dict) -> str:
    def f(v, spec):
        return "-" if v is None else format(v, spec)

    return (f"  {name}: steps {w['n_steps_left']}/{w['n_steps_right']}, step time {f(w['step_time_s_left'], '.3f')}"
            f"/{f(w['step_time_s_right'], '.3f')} s SI {f(w['step_time_s_si_pct'], '.2f')} % ratio "
            f"{f(w['step_time_s_ratio'], '.3f')}; stride length SI {f(w['stride_length_m_si_pct'], '.2f')} %; DS "
            f"{f(w['double_support_pct'], '.1f')} %, SS L/R {f(w['single_support_pct_left'], '.1f')}/"
            f"{f(w['single_support_pct_right'], '.1f')} % ({w['n_support_cycles']} cycles)")


def real() -> None:
    for left, right in PAIRS:
        ld, rd = ROOT / left, ROOT / right
        if not ld.is_dir():
            print(f"{left}: not found, skipped")
            continue
        res = pair_sessions(ld, rd)
        ref = res["reference"]
        print(f"{Path(left).name} + {Path(right).name}: bouts tracked {len(res['bouts'])}, reference "
              f"{len(ref['bouts'])}")
        print(walk_line("tracked  ", res["walk"]))
        print(walk_line("reference", ref["walk"]))
        st = matched(res["steps"], ref["steps"], "ic_s", ["step_time_s"])
        print(f"  matched steps, step time error: {stat(st['step_time_s'], 1000, ' ms')}")
        for s in ("left", "right"):
            print(f"    {s}: {stat(st.loc[st['side'] == s, 'step_time_s'], 1000, ' ms')}")
        cy = matched(res["cycles"], ref["cycles"], "start_s", ["double_support_pct", "single_support_pct"])
        print(f"  matched cycles, double support error: {stat(cy['double_support_pct'], 1, ' pp')}; single "
              f"support error: {stat(cy['single_support_pct'], 1, ' pp')}")


def sim() -> None:
    py = sys.executable
    rows, ic_err = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for u in SIM_USERS:
            a = SIM_ASYM[u % len(SIM_ASYM)]
            d = Path(tmp) / f"s{u}"
            subprocess.run([py, "-m", "pdrlearn", "simulate", "--route", "stand:3, straight:25, stand:3",
                            "--step-time-asymmetry", str(a), "--user-seed", str(u), "--rate", "100", "--out",
                            str(d)], check=True, capture_output=True)
            s = read_session(d)
            ics = s.extras["ics"]
            truth = {f: pd.DataFrame({"ic_s": ics.loc[ics["foot"] == f, "ic_s"].to_numpy(float)})
                     for f in ("left", "right")}
            t = bilateral_gait(truth["left"], truth["right"])["walk"]
            tr = track_plasys(s).steps
            half = bilateral_gait(truth["left"], tr)["walk"]
            ic = tr["event_s"].dropna().to_numpy(float)
            true_r = truth["right"]["ic_s"].to_numpy(float)
            near = np.abs(ic[:, None] - true_r[None, :]).min(axis=1)
            k = np.abs(ic[:, None] - true_r[None, :]).argmin(axis=1)
            ic_err.extend((ic - true_r[k])[near < 0.15])
            rows.append((u, a, t["step_time_s_ratio"], t["step_time_s_si_pct"], half["step_time_s_ratio"],
                         half["step_time_s_si_pct"], half["n_steps_left"] + half["n_steps_right"],
                         t["n_steps_left"] + t["n_steps_right"]))
            print(f"user {u} a={a}: truth contacts ratio {rows[-1][2]:.4f} SI {rows[-1][3]:.2f} %; half-tracked "
                  f"ratio {rows[-1][4]:.4f} SI {rows[-1][5]:.2f} % ({rows[-1][6]} of {rows[-1][7]} steps)",
                  flush=True)
    df = pd.DataFrame(rows, columns=["user", "a", "ratio", "si", "half_ratio", "half_si", "n_half", "n_truth"])
    e_ic = np.asarray(ic_err) * 1000.0
    print(f"tracked right-foot IC - true IC: n={len(e_ic)} median {np.median(e_ic):+.1f} ms, SD "
          f"{e_ic.std(ddof=1):.1f} ms")
    print(f"truth contacts: |ratio - (1 + a)| max {np.abs(df['ratio'] - 1 - df['a']).max():.4f}")
    e = df["half_si"] - df["si"]
    print(f"half-tracked SI - truth-contacts SI: median {e.median():+.2f} pp, max |.| {e.abs().max():.2f} pp; "
          f"ratio error median {(df['half_ratio'] - df['ratio']).median():+.4f}, max |.| "
          f"{(df['half_ratio'] - df['ratio']).abs().max():.4f}")


if __name__ == "__main__":
    real()
    if "--sim" in sys.argv:
        sim()
