"""Decisions L311, L313: per-foot step length of `pdrlearn gait` and the 10 m walk test's timing, on fresh simulated
users 6000-6029 against the simulator's truth (ics.csv step lengths; trajectory.csv's body position).

    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/step_length_l310.py [--part steps|tenmwt|both]

Part steps (users 6000-6019): two feet of one walk (`simulate --foot left` + right, S54), step-length asymmetry
a = 0.001 (~symmetric; ics.csv gives step lengths only with the knob) / 0.1 / 0.2 / 0.3 / 0.4 in turn,
paretic side left on even users and right on odd ones, users 6010-6019 with
half of a as step-time asymmetry too, users 6015-6019 on a route with a 180 deg turn. Each tracked step is matched
to the true step landing on the same foot within 0.15 s (kind 'walk'); printed: step length error (tracked - true),
with and without L310's closing-step scale, and the symmetry index / ratio against the true ones of the same steps.
Part tenmwt (users 6020-6029): straight walks of known speed (20 m, 14.5 m and 12 m); printed: the middle 10 m's
time and speed from the foot track (and, as L313 measured before refusing it, the lower back's) against the body's
true crossing of 2 m and 12 m.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.track.bilateral import common_frame, foot_events, merged_contacts, pair_sessions, step_table
from pdrlearn.track.clinical import symmetry_index_pct
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.waist import track_waist
from pdrlearn.track.walk_test import ten_metre_walk

STRAIGHT = "stand:3, straight:14, stand:3"
TURN = "stand:3, straight:8, turn:180, straight:8, stand:3"


def simulate(out: Path, *args: str) -> None:
    from typer.testing import CliRunner

    from pdrlearn.cli import app

    res = CliRunner().invoke(app, ["simulate", *args, "--out", str(out)])
    if res.exit_code != 0:
        raise SystemExit(f"simulate {args}: {res.output}")


def matched(steps: pd.DataFrame, ics: pd.DataFrame) -> pd.DataFrame:
    walk = ics[ics["kind"] == "walk"]
    rows = []
    for _, s in steps.iterrows():
        cand = walk[walk["foot"] == s["side"]]
        if not len(cand):
            continue
        j = (cand["ic_ms"] / 1000 - s["ic_s"]).abs().idxmin()
        if abs(cand.loc[j, "ic_ms"] / 1000 - s["ic_s"]) < 0.15:
            rows.append((s["side"], s["step_length_m"], s["raw"], cand.loc[j, "step_length_m"]))
    return pd.DataFrame(rows, columns=["side", "tracked", "raw", "true"])


def si_ratio(df: pd.DataFrame, col: str) -> tuple[float, float]:
    m = [df.loc[(df["side"] == s) & df[col].notna() & df["tracked"].notna(), col].mean() for s in ("left", "right")]
    return symmetry_index_pct(*m), m[0] / m[1]


def part_steps(tmp: Path) -> None:
    errs, raw_errs, si_err, ratio_err = [], [], [], []
    for u in range(6000, 6020):
        i = u - 6000
        a = (0.001, 0.1, 0.2, 0.3, 0.4)[i % 5]  # 0.001: ics.csv has step lengths only with the knob (S42)
        side = "left" if u % 2 == 0 else "right"
        route = TURN if u >= 6015 else STRAIGHT
        args = ["--route", route, "--user-seed", str(u), "--rate", "100",
                "--step-length", f"{0.3 + 0.05 * (i % 5):.2f}",
                "--step-time", f"{0.6 + 0.05 * (i % 4):.2f}", "--step-length-asymmetry", str(a),
                "--paretic-side", side]
        if u >= 6010:
            args += ["--step-time-asymmetry", str(a / 2)]
        for foot in ("left", "right"):
            simulate(tmp / f"u{u}_{foot}", *args, "--foot", foot)
        res = pair_sessions(tmp / f"u{u}_left", tmp / f"u{u}_right")
        st = res["steps"].copy()
        # the same steps without L310's closing-step scale (the "before")
        ev = [foot_events(track_plasys(read_session(tmp / f"u{u}_{f}"), toe_off=True).steps) for f in ("left", "right")]
        raw = step_table(merged_contacts(common_frame(ev[0], ev[1]), ev[1]))
        st["raw"] = raw["step_length_m"].to_numpy() if len(raw) == len(st) else np.nan
        m = matched(st, pd.read_csv(tmp / f"u{u}_right" / "ics.csv"))
        e, er = (m["tracked"] - m["true"]).dropna(), (m["raw"] - m["true"]).dropna()
        si_t, r_t = si_ratio(m, "tracked")
        si_true, r_true = si_ratio(m, "true")
        errs += list(e)
        raw_errs += list(er)
        si_err.append(si_t - si_true)
        ratio_err.append(r_t - r_true)
        w = res["walk"]
        print(f"u{u} a={a} paretic={side} {'turn' if route == TURN else 'straight'}: {len(e)} steps with a length "
              f"matched of {len(st)}, error median {e.median():+.3f} m SD {e.std():.3f} max|.| {e.abs().max():.3f} "
              f"(no closure: median {er.median():+.3f} SD {er.std():.3f} max|.| {er.abs().max():.3f}); "
              f"SI {si_t:.1f} % vs true {si_true:.1f} %, ratio {r_t:.3f} vs {r_true:.3f}; "
              f"scale {w['step_length_scale_pct']}", flush=True)
    e, er = np.array(errs), np.array(raw_errs)
    print(f"ALL steps n={len(e)}: error median {np.median(e):+.4f} m, SD {e.std(ddof=1):.4f}, max |.| "
          f"{np.abs(e).max():.4f}; without the closing-step scale n={len(er)}: median {np.median(er):+.4f}, SD "
          f"{er.std(ddof=1):.4f}, max |.| {np.abs(er).max():.4f}")
    si, ra = np.array(si_err), np.array(ratio_err)
    print(f"SI tracked - true over the {np.isfinite(si).sum()} walks with step lengths (L311: an unanchored walk has "
          f"none): median {np.nanmedian(si):+.2f}, max |.| {np.nanmax(np.abs(si)):.2f} points; ratio median "
          f"{np.nanmedian(ra):+.4f}, max |.| {np.nanmax(np.abs(ra)):.4f}")


def true_middle(traj: pd.DataFrame) -> float:
    t, x = traj["timestamp"].to_numpy(float) / 1000, traj["x"].to_numpy(float)
    d = x - x[0]
    t0, t1 = (t[np.argmax(d >= lim)] for lim in (2.0, 12.0))
    return float(t1 - t0)


def part_tenmwt(tmp: Path) -> None:
    ef, ew = [], []
    for u in range(6020, 6030):
        i = u - 6020
        length = 20 if i < 6 else (14.5 if i < 8 else 12)
        sl, stt = 0.25 + 0.05 * (i % 6), 0.5 + 0.06 * (i % 5)
        d = tmp / f"w{u}"
        simulate(d, "--route", f"stand:3, straight:{length}, stand:3", "--user-seed", str(u), "--rate", "100",
                 "--step-length", f"{sl:.2f}", "--step-time", f"{stt:.2f}")
        truth = true_middle(pd.read_csv(d / "trajectory.csv")) if length >= 14 else None
        s = read_session(d)
        foot = ten_metre_walk(track_plasys(s).steps)
        # the lower back as the kernel would read it without L313's refusal (its steps' unit relabelled)
        waist = ten_metre_walk(track_waist(s, pipeline="waist-pendulum").steps.assign(unit="waist-unrefused"))
        line = f"u{u} {length} m, {sl:.2f} m / {stt:.2f} s (~{sl / stt:.2f} m/s):"
        for name, r, acc in (("foot", foot, ef), ("waist", waist, ew)):
            if r["ten_m_walk_time_s"] is None:
                line += f" {name} not timed ({r['ten_m_walk_note'][:60]}...)"
                continue
            line += f" {name} {r['ten_m_walk_time_s']:.2f} s {r['ten_m_walk_speed_mps']:.3f} m/s"
            if truth is not None:
                err = 10 / r["ten_m_walk_time_s"] - 10 / truth
                acc.append(100 * err / (10 / truth))
                line += f" (true {truth:.2f} s {10 / truth:.3f} m/s, speed error {acc[-1]:+.2f} %)"
        print(line, flush=True)
    for name, acc in (("foot", ef), ("waist", ew)):
        a = np.array(acc)
        if len(a):
            print(f"{name}: speed error median {np.median(a):+.2f} %, max |.| {np.abs(a).max():.2f} % (n={len(a)})")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--part", default="both", choices=("steps", "tenmwt", "both"))
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    with tempfile.TemporaryDirectory() as t:
        if args.part in ("steps", "both"):
            part_steps(Path(t))
        if args.part in ("tenmwt", "both"):
            part_tenmwt(Path(t))


if __name__ == "__main__":
    main()
