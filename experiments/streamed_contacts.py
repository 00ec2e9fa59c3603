"""Decisions E49-E51: the streamed paths' initial contacts (IC) and stride times against the reference.

Run: ``PYTHONPATH=$PWD python experiments/streamed_contacts.py`` (datasets/external linked for the 4x10 m walks).
For simulated scenarios A-D (``simulate(X, user_seed=42)``, the instrumented foot's true ``ic_s``) and the real foot
recordings with mocap ICs (gaitmap level walks; the 4x10 m walks when linked), three paths: offline ``track``
(default: M3 engine, no model), ``track --streaming --contacts`` and ``pdrlearn run --contacts`` (the shipped bundle
``models/plasys-sim-default``, foot unit, 1 s replay chunks). Reference stride time: IC to the same foot's previous
IC (real: ``ic - pre_ic``; a row spanning two strides, over 1.5 x the median, left out, as L66). Each reference
stride is matched to the tracked stride whose window holds its IC (not L66's 0.15 s event match: a streamed IC error
must not unmatch it). Prints, per session and path, the stride time error (mean, SD, max |err| ms), the IC error
(ms) and the strides with a stride time; then E51's latency: each streamed stride's IC is known when its stride is
returned; with pushes of one sample interval, the newest pushed sample time minus the IC (median, max).
"""

from __future__ import annotations

import logging
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main as cli
from pdrlearn.io import read_session, write_session
from pdrlearn.track import get_pipeline

logging.disable(logging.WARNING)
ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"
REAL = ["real/gaitmap_level_left", "real/gaitmap_level_right", "external/gaitmap_walk4x10_left",
        "external/gaitmap_walk4x10_right"]


def reference(session) -> tuple[np.ndarray, np.ndarray]:
    """(IC s, reference stride time s) per reference stride (NaN where none)."""
    ref = session.steps
    ic = ref["ic_s"].to_numpy(float)
    if "pre_ic_s" in ref:
        st = ic - ref["pre_ic_s"].to_numpy(float)
    else:
        st = np.concatenate([[np.nan], np.diff(ic)])
    with np.errstate(invalid="ignore"):
        st = np.where(st <= 1.5 * np.nanmedian(st), st, np.nan)
    return ic, st


def errors(steps: pd.DataFrame, ic: np.ndarray, ref_st: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Stride time error and IC error (s) per reference stride (NaN: no tracked stride or no value)."""
    s0, s1 = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    ev, st = steps["event_s"].to_numpy(float), steps["stride_time_s"].to_numpy(float)
    e_st, e_ic = np.full(len(ic), np.nan), np.full(len(ic), np.nan)
    for k, x in enumerate(ic):
        j = np.flatnonzero((s0 <= x) & (x <= s1))
        if len(j):
            e_st[k] = st[j[0]] - ref_st[k]
            e_ic[k] = ev[j[0]] - x
    return e_st, e_ic


def fmt(e: np.ndarray) -> str:
    e = e[np.isfinite(e)] * 1000.0
    if not len(e):
        return "none"
    sd = e.std(ddof=1) if len(e) > 1 else 0.0
    return f"n={len(e)} mean {e.mean():+.1f}, SD {sd:.1f}, max {np.abs(e).max():.1f} ms"


def run_steps(session_dir: Path, out: Path) -> pd.DataFrame:
    assert cli(["run", str(BUNDLE), str(session_dir), "--units", "foot", "--contacts", "--out", str(out),
                "--force"]) == 0
    return pd.read_csv(out / "steps.csv")


def latency(session) -> tuple[float, float, float]:
    """E51: median and max (newest pushed sample - IC) and max (newest pushed sample - stride end), s, with
    pushes of one sample interval."""
    from pdrlearn.runtime.replay import replay_chunks
    from pdrlearn.runtime.tracker import Tracker

    feet = {n: (st.t, st.values) for n, st in session.streams.items() if n[0] == "f"}
    tr = Tracker(BUNDLE, units=("foot",), frames={"foot": session.frames["foot"].to_dict()}, sensors=list(feet),
                 input_rates_hz={n: session.streams[n].rate_hz for n in feet}, contacts=True)
    dt = 1.0 / session.streams["fAccelerometer"].rate_hz
    lag_ic, lag_end = [], []
    for chunk in replay_chunks(feet, dt):
        newest = max(float(t[-1]) for t, _ in chunk.values() if len(t)) if any(len(t) for t, _ in chunk.values()) \
            else None
        for st in tr.push(chunk):
            if np.isfinite(st.event_s):
                lag_ic.append(newest - st.event_s)
            lag_end.append(newest - st.end_s)
    return float(np.median(lag_ic)), float(np.max(lag_ic)), float(np.max(lag_end))


def main(argv: list[str]) -> None:
    tmp = Path(tempfile.mkdtemp(prefix="streamed_ic_"))
    sessions = []
    if not argv or "sim" in argv:
        from pdrlearn.sim import simulate

        for sc in "ABCD":
            s = simulate(sc, user_seed=42)
            write_session(s, tmp / sc)
            sessions.append((f"sim {sc}", tmp / sc))
    if not argv or "real" in argv:
        for rel in REAL:
            p = ROOT / "datasets" / rel
            if p.exists():
                sessions.append((rel, p))
            else:
                print(f"{rel}: missing (link datasets/external)")
    for name, path in sessions:
        s = read_session(path)
        ic, ref_st = reference(s)
        tables = {"offline": get_pipeline("plasys")(s).steps,
                  "streaming": get_pipeline("plasys")(s, streaming=True, contacts=True).steps,
                  "run": run_steps(path, tmp / ("run_" + name.replace("/", "_").replace(" ", "_")))}
        print(f"{name}: {int(np.isfinite(ref_st).sum())} reference stride times")
        for k, t in tables.items():
            e_st, e_ic = errors(t, ic, ref_st)
            print(f"  {k:9s} stride time error {fmt(e_st)}; IC error {fmt(e_ic)}; "
                  f"strides with a stride time {int(np.isfinite(t['stride_time_s']).sum())}/{len(t)}")
        if "run" in tables and "streaming" in tables:
            a, b = tables["run"], tables["streaming"]
            if len(a) == len(b):
                d = np.abs(a["stride_time_s"].to_numpy(float) - b["stride_time_s"].to_numpy(float))
                print(f"  run vs streaming: max |stride time difference| {np.nanmax(d) * 1000:.3f} ms")
        med, mx, mx_end = latency(s)
        print(f"  E51 latency (newest sample - IC at the stride's return): median {med:.3f} s, max {mx:.3f} s; "
              f"newest sample - stride end max {mx_end:.3f} s")


if __name__ == "__main__":
    main(sys.argv[1:])
