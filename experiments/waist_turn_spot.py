"""Where the daily-activity bout distance excess lies by the steps' turning (issue 8, decisions W150, W151).

Per detected ``waist-pendulum`` step of the mobgap Test11 recordings (calibrated on the subject's Test5 walks, as
experiments/waist.py; and HA001 calibrated on Test5 Trial1 only, the demo row) a reference length: the mean of both
feet's distance travelled over the step, each foot's cumulative INDIP stride length linear in time between its
contacts (:func:`reference_progression`; steps that touch a stride without a length, or lie outside a bout, have
none). Each step's turn cues:
- ``net``: the vertical-gyro rotation from its contact to the next (``dyaw_rad``, the one W19's ``cos`` reads);
- ``total``: the integrated |yaw rate| over the step (a wiggle in place turns the pelvis both ways, net ~0);
- ``rate``: ``total`` / step time (deg/s).
Printed: per bout, the excess (tracked - Length) and how much of the tracked - reference excess lies in steps
above each cue threshold (30 / 45 deg per step); per bin of ``net`` and of ``total``, the steps' tracked and
reference metres and the median ratio reference / tracked; and whether a pivot cue separates the steps whose
reference is short (under 0.2 m, a pivot / shuffle) from the rest (recall / precision of each cue).

Run: PYTHONPATH=. .venv/bin/python experiments/waist_turn_spot.py [--external datasets/external] [--options JSON]
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
import waist_bout_parts as BP  # noqa: E402
from pdrlearn.waist.ahrs import waist_imu  # noqa: E402
from pdrlearn.waist.evaluate import distance_metrics, reference_bouts, steps_in_interval  # noqa: E402

#: a reference step under this is a pivot / shuffle (a normal step of these subjects is 0.3-0.65 m, bouts.csv)
SHORT_REF_M = 0.2
CUE_DEG = (30.0, 45.0)
BINS_DEG = (0, 15, 30, 45, 60, 90, 360)


def reference_progression(session, t: np.ndarray) -> np.ndarray:
    """The walker's reference distance travelled (m) at the times ``t``: the mean over both feet of each foot's
    cumulative INDIP stride length, linear in time over each stride (start_s -> end_s of a ``steps.csv`` row); NaN
    at a time inside a stride without a length or outside either foot's strides."""
    st = session.steps
    out = []
    for foot in ("left", "right"):
        s = st[st["foot"] == foot].sort_values("start_s")
        a, b, length = (s[c].to_numpy(float) for c in ("start_s", "end_s", "length_m"))
        d = np.full(len(t), np.nan)
        cum = np.concatenate([[0.0], np.cumsum(np.nan_to_num(length))])
        for k in range(len(a)):
            inside = (t >= a[k]) & (t <= b[k])
            if np.isfinite(length[k]):
                d[inside] = cum[k] + length[k] * (t[inside] - a[k]) / (b[k] - a[k])
            else:
                d[inside] = np.nan
        out.append(d)
    return 0.5 * (out[0] + out[1])


def step_table(steps: pd.DataFrame, session, subject: str) -> pd.DataFrame:
    """One row per detected step with a length inside a reference bout: tracked and reference length, the turn
    cues (module docstring), the bout."""
    imu = waist_imu(session)
    has_next = steps["has_next"].to_numpy(bool)
    t0, t1 = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    a = np.clip(np.searchsorted(imu.t, t0), 0, len(imu.t) - 1)
    b = np.clip(np.searchsorted(imu.t, t1), 0, len(imu.t) - 1)
    absrate = np.concatenate([[0.0], np.cumsum(np.abs(imu.w_z[1:]) * np.diff(imu.t))])
    total = np.degrees(absrate[b] - absrate[a])
    ref = reference_progression(session, t1) - reference_progression(session, t0)
    rows = []
    for j, bt in enumerate(reference_bouts(session).itertuples()):
        m = steps_in_interval(steps, bt.start_s, bt.end_s) & has_next
        for i in np.flatnonzero(m):
            dur = t1[i] - t0[i]
            rows.append({"subject": subject, "bout": j, "start_s": t0[i], "dur_s": dur,
                         "tracked_m": float(abs(steps["length_m"].iloc[i])), "ref_m": ref[i],
                         "net_deg": float(np.degrees(abs(steps["dyaw_rad"].iloc[i]))), "total_deg": total[i],
                         "rate_dps": total[i] / dur if dur > 0 else np.nan})
    return pd.DataFrame(rows)


def bout_summary(steps: pd.DataFrame, session, tab: pd.DataFrame, subject: str) -> pd.DataFrame:
    """Per reference bout: excess vs Length (m, %), and the tracked - reference excess (m) of the steps with a
    reference, all of them and those whose net / total turn reaches each of :data:`CUE_DEG`."""
    d = distance_metrics(steps, session)
    rows = []
    for j, b in enumerate(d["bouts"]):
        t = tab[(tab.bout == j)]
        r = t[np.isfinite(t.ref_m)]
        row = {"subject": subject, "start_s": b["start_s"], "L_m": b["reference_m"], "tracked_m": b["tracked_m"],
               "err_L_pct": b["error_pct"], "excess_L_m": b["tracked_m"] - b["reference_m"],
               "steps": len(t), "with_ref": len(r), "excess_ref_m": float((r.tracked_m - r.ref_m).sum())}
        for c in CUE_DEG:
            for cue in ("net", "total"):
                s = r[r[f"{cue}_deg"] >= c]
                row[f"{cue}>={c:g}"] = f"{len(s)}:{float((s.tracked_m - s.ref_m).sum()):+.2f}"
        rows.append(row)
    return pd.DataFrame(rows)


def bins(tab: pd.DataFrame, cue: str) -> pd.DataFrame:
    """Per bin of ``cue`` (deg): steps, tracked and reference metres, excess, median reference / tracked."""
    r = tab[np.isfinite(tab.ref_m)]
    cut = pd.cut(r[f"{cue}_deg"], BINS_DEG, right=False)
    g = r.groupby(cut, observed=True)
    return pd.DataFrame({"n": g.size(), "tracked_m": g.tracked_m.sum(), "ref_m": g.ref_m.sum(),
                         "excess_m": g.apply(lambda x: (x.tracked_m - x.ref_m).sum(), include_groups=False),
                         "median_ref_over_tracked": g.apply(lambda x: np.median(x.ref_m / x.tracked_m.clip(1e-3)),
                                                            include_groups=False),
                         "median_ref_m": g.ref_m.median(), "median_tracked_m": g.tracked_m.median()})


def separation(tab: pd.DataFrame) -> pd.DataFrame:
    """How well each cue (net / total turn, at each threshold) picks the steps whose reference is short (under
    :data:`SHORT_REF_M`): recall, precision, and the excess (m) of the picked and of the short steps."""
    r = tab[np.isfinite(tab.ref_m)]
    short = r.ref_m < SHORT_REF_M
    rows = []
    for cue in ("net", "total"):
        for c in (*CUE_DEG, 60.0, 90.0):
            pick = r[f"{cue}_deg"] >= c
            rows.append({"cue": f"{cue} >= {c:g} deg", "picked": int(pick.sum()), "short": int(short.sum()),
                         "recall": (pick & short).sum() / max(short.sum(), 1),
                         "precision": (pick & short).sum() / max(pick.sum(), 1),
                         "picked_excess_m": float((r.tracked_m - r.ref_m)[pick].sum()),
                         "picked_ref_m": float(r.ref_m[pick].sum()),
                         "short_excess_m": float((r.tracked_m - r.ref_m)[short].sum())})
    return pd.DataFrame(rows)


def main() -> None:
    opt = None
    if "--options" in sys.argv:
        k = sys.argv.index("--options")
        opt = json.loads(sys.argv[k + 1])
        del sys.argv[k:k + 2]
    external, runs = W.test11_cli()
    tabs, bouts = [], []
    for cal, name in runs:
        steps, s = BP.track(external, cal, name, opt)
        subj = name.split("_")[1]
        t = step_table(steps, s, subj)
        tabs.append(t)
        bouts.append(bout_summary(steps, s, t, subj))
    tab = pd.concat(tabs, ignore_index=True)
    bt = pd.concat(bouts, ignore_index=True)
    print(f"options: {opt or 'defaults'}; calibrated on each subject's Test5 walks")
    print("per bout (excess in m; 'net>=30' = steps:excess(tracked - reference) of the steps turning >= 30 deg):")
    print(bt.round(2).to_string(index=False))
    print(f"\npooled median |bout error| vs Length: {bt.err_L_pct.abs().median():.2f} %")
    for cue in ("net", "total"):
        print(f"\nper bin of the {cue} turn per step (deg), steps with a reference:")
        print(bins(tab, cue).round(3).to_string())
    print(f"\ndoes a turn cue pick the steps whose reference is under {SHORT_REF_M} m?")
    print(separation(tab).round(3).to_string(index=False))
    ha = [r for r in runs if r[1].split("_")[1] == "HA001"][0][1]
    steps, s = BP.track(external, [ha.replace("Test11", "Test5")], ha, opt)
    t = step_table(steps, s, "HA001")
    b = bout_summary(steps, s, t, "HA001")
    d = distance_metrics(steps, s)
    print(f"\ndemo (HA001 Test11, calibrated on Test5 Trial1 only): total {d['distance_error_pct']:.2f} %, median per "
          f"bout {d['bout_distance_error_median_pct']:.2f} %, excess vs Length {b.excess_L_m.sum():.2f} m")
    print(b.round(2).to_string(index=False))
    print(t[t.bout.isin([3, 5])].round(3).to_string(index=False))


if __name__ == "__main__":
    main()
