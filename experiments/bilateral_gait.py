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

Part 3 (``--rate``, decision L285): the real level pair decimated to 102.4 Hz (every other sample) against the
204.8 Hz pair: walk double support and each foot's IC / toe-off error against the mocap events.

Part 4 (``--pairs``, decision L286): two simulated feet of one hemiparetic walk (S54 ``--foot left``, S55
``--paretic-side``), fresh users 5530-5549, against the same sessions' labelled contacts; and the L284 clock-offset
warning on each pair as simulated and with the left track's contacts moved by +-100 ms.
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


def _event_errors(d: Path) -> tuple[list[float], list[float]]:
    """Tracked IC and toe-off of one labelled foot session minus its labels (nearest, within 0.15 / 0.3 s)."""
    s = read_session(d)
    st = track_plasys(s, toe_off=True).steps
    ev, tc = st["event_s"].to_numpy(float), st["tc_s"].to_numpy(float)
    e_ic, e_tc = [], []
    for _, r in s.steps.iterrows():
        k = int(np.nanargmin(np.abs(ev - r["ic_s"])))
        if abs(ev[k] - r["ic_s"]) < 0.15:
            e_ic.append(ev[k] - r["ic_s"])
        if np.isfinite(r.get("tc_s", np.nan)):
            j = int(np.nanargmin(np.abs(tc - r["tc_s"])))
            if abs(tc[j] - r["tc_s"]) < 0.3:
                e_tc.append(tc[j] - r["tc_s"])
    return e_ic, e_tc


def rate() -> None:
    import shutil

    with tempfile.TemporaryDirectory() as tmp:
        pair = {}
        for side in ("left", "right"):
            src, dst = ROOT / f"real/gaitmap_level_{side}", Path(tmp) / f"level102_{side}"
            shutil.copytree(src, dst)
            for f in ("fAccelerometer.csv", "fGyroscope.csv"):
                pd.read_csv(src / f).iloc[::2].to_csv(dst / f, index=False)  # 204.8 -> 102.4 Hz
            pair[side] = (src, dst)
        for k, name in ((0, "204.8 Hz"), (1, "102.4 Hz (decimated)")):
            res = pair_sessions(pair["left"][k], pair["right"][k])
            w, ref = res["walk"], res["reference"]["walk"]
            print(f"level pair {name}: DS {w['double_support_pct']:.1f} % (mocap {ref['double_support_pct']:.1f} %), "
                  f"SS L/R {w['single_support_pct_left']:.1f}/{w['single_support_pct_right']:.1f} %, step SI "
                  f"{w['step_time_s_si_pct']:.2f} %")
            for side in ("left", "right"):
                e_ic, e_tc = _event_errors(pair[side][k])
                print(f"  {side}: IC - mocap {stat(e_ic, 1000, ' ms')}; toe-off - mocap {stat(e_tc, 1000, ' ms')}")
    for side in ("left", "right"):
        d = ROOT / f"external/gaitmap_walk4x10_{side}"
        if d.is_dir():
            e_ic, _ = _event_errors(d)
            st = track_plasys(read_session(d), toe_off=True).steps
            print(f"walk4x10 {side} (102.4 Hz): IC - mocap {stat(e_ic, 1000, ' ms')}; tracked swing median "
                  f"{np.nanmedian(st['event_s'] - st['tc_s']):.3f} s, stance_pct median "
                  f"{np.nanmedian(st['stance_pct']):.1f}")


PAIR_USERS = range(5530, 5550)
PAIR_ASYM = (0.0, 0.2, 0.39, 0.6)
PAIR_GAIT = ((0.3, 0.75), (0.4, 0.65), (0.5, 0.6))  # step length (m), step time (s)


def _shifted(steps: pd.DataFrame, dt: float) -> pd.DataFrame:
    return steps.assign(**{c: steps[c] + dt for c in ("start_s", "end_s", "event_s", "tc_s")})


def pairs() -> None:
    from pdrlearn.track.bilateral import label_steps

    py = sys.executable
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for u in PAIR_USERS:
            a, side = PAIR_ASYM[u % 4], ("left", "right")[(u // 4) % 2]
            length, step = PAIR_GAIT[u % 3]
            dirs = {}
            for foot in ("left", "right"):
                dirs[foot] = Path(tmp) / f"u{u}_{foot}"
                subprocess.run([py, "-m", "pdrlearn", "simulate", "--route", "stand:3, straight:14, stand:3",
                                "--step-length", str(length), "--step-time", str(step), "--step-time-asymmetry",
                                str(a), "--paretic-side", side, "--foot", foot, "--user-seed", str(u), "--rate",
                                "100", "--out", str(dirs[foot])], check=True, capture_output=True)
            ses = {f: read_session(d) for f, d in dirs.items()}
            tr = {f: track_plasys(s, toe_off=True).steps for f, s in ses.items()}
            res = bilateral_gait(tr["left"], tr["right"])
            ref = bilateral_gait(label_steps(ses["left"]), label_steps(ses["right"]))
            w, r = res["walk"], ref["walk"]
            warned = {0.0: any("L284" in x for x in res["warnings"])}
            offs = {}
            for dt in (0.1, -0.1):
                sh = bilateral_gait(_shifted(tr["left"], dt), tr["right"])
                warned[dt] = any("L284" in x for x in sh["warnings"])
                offs[dt] = sh["walk"]["clock_offset_s"]
            ss_si = w["single_support_pct_si_pct"]
            rows.append(dict(user=u, a=a, paretic=side, si=w["step_time_s_si_pct"], si_ref=r["step_time_s_si_pct"],
                             ratio=w["step_time_s_ratio"], ratio_ref=r["step_time_s_ratio"], ss_si=ss_si,
                             ss_si_ref=r["single_support_pct_si_pct"], swing_si=w["swing_time_s_si_pct"],
                             off=w["clock_offset_s"], off_p=offs[0.1], off_m=offs[-0.1], warn0=warned[0.0],
                             warn_p=warned[0.1], warn_m=warned[-0.1], ds=w["double_support_pct"],
                             ds_ref=r["double_support_pct"]))
            x = rows[-1]
            print(f"user {u} a={a} paretic {side}: step SI {x['si']:.2f} (labels {x['si_ref']:.2f}) ratio "
                  f"{x['ratio']:.3f} ({x['ratio_ref']:.3f}); SS SI {x['ss_si']:.2f} ({x['ss_si_ref']:.2f}); swing SI "
                  f"{x['swing_si']:.2f}; DS {x['ds']:.1f} ({x['ds_ref']:.1f}); clock_offset {1000 * x['off']:+.0f} ms, "
                  f"+100 ms -> {1000 * x['off_p']:+.0f}, -100 ms -> {1000 * x['off_m']:+.0f}; L284 warning as "
                  f"simulated {x['warn0']}, +100 {x['warn_p']}, -100 {x['warn_m']}", flush=True)
    df = pd.DataFrame(rows)
    e_si, e_ss = df["si"] - df["si_ref"], df["ss_si"] - df["ss_si_ref"]
    long_right = df["a"] >= 0.2
    side_ok = ((df["ratio"] > 1) == (df["paretic"] == "left"))[long_right]
    print(f"{len(df)} pairs: step SI tracked - labels median {e_si.median():+.2f}, max |.| {e_si.abs().max():.2f} pp; "
          f"SS SI tracked - labels median {e_ss.median():+.2f}, max |.| {e_ss.abs().max():.2f} pp; longer step on the "
          f"paretic side {int(side_ok.sum())} of {int(long_right.sum())}; DS tracked - labels median "
          f"{(df['ds'] - df['ds_ref']).median():+.1f} pp")
    print(f"L284 warning: as simulated {int(df['warn0'].sum())} of {len(df)}; +100 ms {int(df['warn_p'].sum())} of "
          f"{len(df)}; -100 ms {int(df['warn_m'].sum())} of {len(df)}; clock_offset_s as simulated median "
          f"{1000 * df['off'].median():+.0f} ms, max |.| {1000 * df['off'].abs().max():.0f} ms")
    ok = (e_si.abs().max() <= 6 and e_ss.abs().max() <= 6 and bool(side_ok.all()) and not df["warn0"].any()
          and df["warn_p"].all() and df["warn_m"].all())
    print(f"L286 rule met: {ok}")


if __name__ == "__main__":
    real()
    if "--sim" in sys.argv:
        sim()
    if "--rate" in sys.argv:
        rate()
    if "--pairs" in sys.argv:
        pairs()
