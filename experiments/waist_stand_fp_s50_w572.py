"""Decision W572 (docs/decisions/waist.md): what W518's 14 "stand" false positives of the default offline
`waist-pendulum` on the real Test11 recordings (HA001, HA002, MS001) look like in the lower back's own signals, beside
the track's true contacts (diagnosis, no behaviour change).

Per scored detection of the default track (``step_metrics``' scoring, INDIP the truth, W518's groups: ``TP``,
``FP stand`` - an FP inside an INDIP gap > 1.2 s within a bout - and ``FP other``), the walker's own cues (nothing
read from the reference but the group):

- ``v/med``: the detection's 2.5 Hz vertical maximum over the recording's median kept one (W518's);
- ``prev/loc``, ``next/loc``: the intervals to the track's previous / next contact over the walker's local step time
  (the median of the 6 nearest intervals of its walking sequence, W18's ``local_medians`` idea; contacts <= 1.5 s);
- ``still``: the share of standstill samples (W354's mask) within 0.5 s of the contact;
- ``|yaw|``: the mean |vertical rate| (deg/s) within 0.5 s;
- ``ap/v``, ``ml/v``: the RMS of the AP / ML horizontal acceleration over the RMS of the vertical one within 0.5 s;
- ``v rms/loc``: the vertical acceleration's RMS within 0.5 s over the median of the same at the sequence's other
  contacts (the walker's own steps in that sequence);
- ``seq``: the contact's place in its walking sequence (``i/n``).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_stand_fp_s50_w572.py [--external datasets/external]
Writes experiments/results/waist_stand_fp_s50_w572.md.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import waist_f1_s46_w518 as F  # noqa: E402  experiments/waist_f1_s46_w518.py: W518's groups
import waist_ic_classes as W  # noqa: E402
import waist_ic_misses_w235 as M  # noqa: E402
from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.ahrs import waist_imu

HALF_S = 0.5  # the window around a contact (s): about one step at a walking cadence


def sequences(e: np.ndarray, has_next: np.ndarray) -> np.ndarray:
    """The walking-sequence number of each contact (a ``has_next`` chain)."""
    out = np.zeros(e.size, int)
    for j in range(1, e.size):
        out[j] = out[j - 1] + (0 if has_next[j - 1] else 1)
    return out


def local_step(e: np.ndarray, seq: np.ndarray, j: int, k: int = 6) -> float:
    """The median of the (up to) ``k`` intervals of contact ``j``'s sequence nearest to it (s)."""
    idx = np.flatnonzero(seq == seq[j])
    if idx.size < 3:
        return np.nan
    d = np.diff(e[idx])
    mid = 0.5 * (e[idx][1:] + e[idx][:-1])
    near = np.argsort(np.abs(mid - e[j]))[:k]
    return float(np.median(d[near]))


def window_cues(imu, t: float) -> dict:
    sel = (imu.t >= t - HALF_S) & (imu.t <= t + HALF_S)
    v = np.sqrt(np.mean(imu.acc_v[sel] ** 2))
    return {"still": float(np.mean(imu.still()[sel])), "yaw": float(np.degrees(np.mean(np.abs(imu.w_z[sel])))),
            "ap": float(np.sqrt(np.mean(imu.acc_ap[sel] ** 2)) / v),
            "ml": float(np.sqrt(np.mean(imu.acc_ml[sel] ** 2)) / v),
            "vrms": float(v)}


def contact_cues(session, steps) -> dict:
    """Every contact of ``steps`` (sorted): its time ``e``, W573's four cues (``vloc``, ``still``, ``ml``, ``amp``)
    and ``inner`` (neither the first nor the last of its walking sequence)."""
    st = steps.sort_values("event_s", kind="stable")
    e, has_next = st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool)
    imu = waist_imu(session)
    seq = sequences(e, has_next)
    cues = [window_cues(imu, t) for t in e]
    vr = np.array([x["vrms"] for x in cues])
    c = M.stages(session)
    med_h = float(np.median(c["h"][np.flatnonzero(c["det"])]))
    out = {k: np.full(e.size, np.nan) for k in ("vloc", "still", "ml", "amp")}
    inner = np.zeros(e.size, bool)
    for j in range(e.size):
        same = np.flatnonzero(seq == seq[j])
        others = same[same != j]
        inner[j] = same[0] != j and same[-1] != j
        out["vloc"][j] = vr[j] / np.median(vr[others]) if others.size else np.nan
        out["still"][j], out["ml"][j] = cues[j]["still"], cues[j]["ml"]
        _, i = M.fp_stage(e[j], c)
        out["amp"][j] = np.nan if i is None else float(c["h"][i] / med_h)
    return {"e": e, "inner": inner, **out}


def rows_of(sub: str, session) -> list[dict]:
    res = track_waist(session, pipeline="waist-pendulum")
    st = res.steps.sort_values("event_s", kind="stable")
    e, has_next = st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool)
    r = W.classify(session, st)
    fps = {round(x["t"], 6): x for x in r["fp"]}
    c = M.stages(session)
    kept = np.flatnonzero(c["det"])
    med_h = float(np.median(c["h"][kept]))
    imu = waist_imu(session)
    seq = sequences(e, has_next)
    cues = [window_cues(imu, t) for t in e]
    vr = np.array([x["vrms"] for x in cues])
    out = []
    for t in F.scored_detections(session, e):
        j = int(np.argmin(np.abs(e - t)))
        x = fps.get(round(t, 6))
        grp = "TP" if x is None else "FP stand" if x["gap"] else "FP other"
        _, i = M.fp_stage(t, c)
        loc = local_step(e, seq, j)
        same = np.flatnonzero(seq == seq[j])
        others = same[same != j]
        prev = t - e[j - 1] if j > 0 and seq[j - 1] == seq[j] else np.nan
        nxt = e[j + 1] - t if j + 1 < e.size and seq[j + 1] == seq[j] else np.nan
        out.append({"sub": sub, "t": t, "grp": grp, "amp": np.nan if i is None else float(c["h"][i] / med_h),
                    "prev": prev / loc, "next": nxt / loc, "loc": loc,
                    "vloc": cues[j]["vrms"] / np.median(vr[others]) if others.size else np.nan,
                    "pos": f"{int(np.searchsorted(same, j)) + 1}/{same.size}", **cues[j]})
    return out


def gap_rows(sub: str, session) -> list[dict]:
    """Every INDIP gap > 1.2 s inside a bout (W518's stops): its span, the feet at its ends, the track's contacts in
    it, the pelvis' heading change over it and the vertical RMS over it against its bout's walking."""
    res = track_waist(session, pipeline="waist-pendulum")
    e = np.sort(res.steps["event_s"].to_numpy(float))
    fp = np.array([x["t"] for x in W.classify(session, res.steps)["fp"] if x["gap"]])
    ics = session.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    it, wb = ics["ic_s"].to_numpy(float), ics["wb_id"].to_numpy()
    foot = ics["foot"].astype(str).str[0].to_numpy()
    imu = waist_imu(session)
    out = []
    for j in range(1, it.size):
        a, b = it[j - 1], it[j]
        if wb[j] != wb[j - 1] or b - a <= W.C.GAP_S:
            continue
        inside = e[(e > a + W.C.TOL) & (e < b - W.C.TOL)]
        sel = (imu.t > a + 0.3) & (imu.t < b - 0.3)
        bout = (imu.t >= it[wb == wb[j]].min()) & (imu.t <= it[wb == wb[j]].max()) & ~sel
        ia, ib = (int(np.searchsorted(imu.t, x)) for x in (a, b))
        n_fp = int(np.sum(np.isin(np.round(inside, 6), np.round(fp, 6))))
        out.append({"sub": sub, "a": a, "b": b, "feet": foot[j - 1] + foot[j], "n": inside.size, "n_fp": n_fp,
                    "kind": "stand FP" if n_fp else "unscored only" if inside.size else "no contact",
                    "at": " ".join(f"{x:.2f}" for x in inside),
                    "dyaw": float(np.degrees(imu.yaw[min(ib, imu.t.size - 1)] - imu.yaw[ia])),
                    "vrel": float(np.std(imu.acc_v[sel]) / np.std(imu.acc_v[bout])) if sel.any() else np.nan,
                    "still": float(np.mean(imu.still()[sel])) if sel.any() else np.nan})
    return out


def main(external: Path) -> None:
    rows = [x for sub in F.SUBJECTS for x in rows_of(sub, read_session(external / f"mobgap_{sub}_Test11_Trial1"))]
    print("## W572: the lower back's cues at W518's stand FPs and at the true contacts (Test11, default track)\n")
    print("| rec | t s | group | seq | loc s | prev/loc | next/loc | v/med | v rms/loc | still | |yaw| deg/s | "
          "ap/v | ml/v |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for x in rows:
        if x["grp"] == "TP":
            continue
        print(f"| {x['sub']} | {x['t']:.2f} | {x['grp']} | {x['pos']} | {x['loc']:.2f} | {x['prev']:.2f} | "
              f"{x['next']:.2f} | {x['amp']:.2f} | {x['vloc']:.2f} | {x['still']:.2f} | {x['yaw']:.1f} | "
              f"{x['ap']:.2f} | {x['ml']:.2f} |")
    print("\n## Every INDIP gap > 1.2 s inside a bout (the stops): the track's contacts inside (0.25 s off its ends), "
          "the heading change over it, the vertical SD over its inner part (0.3 s off the ends) against the rest of "
          "its bout, its standstill share\n")
    print("| rec | gap s | length s | feet | track contacts inside | of them stand FPs | yaw change deg | "
          "v SD / bout | still |\n|---|---|---|---|---|---|---|---|---|")
    gl = [g for sub in F.SUBJECTS for g in gap_rows(sub, read_session(external / f"mobgap_{sub}_Test11_Trial1"))]
    for g in gl:
        print(f"| {g['sub']} | {g['a']:.2f}-{g['b']:.2f} | {g['b'] - g['a']:.2f} | {g['feet']} | {g['n']}"
              f"{': ' + g['at'] if g['n'] else ''} | {g['n_fp']} | {g['dyaw']:.0f} | {g['vrel']:.2f} | "
              f"{g['still']:.2f} |")
    print("\n| gaps | n | same foot at both ends | median length s | median abs yaw change deg | median v SD / bout "
          "| median still |\n|---|---|---|---|---|---|---|")
    for kind in ("stand FP", "unscored only", "no contact"):
        sel = [g for g in gl if g["kind"] == kind]
        print(f"| {kind} | {len(sel)} | {sum(g['feet'][0] == g['feet'][1] for g in sel)} | "
              f"{np.median([g['b'] - g['a'] for g in sel]):.2f} | {np.median([abs(g['dyaw']) for g in sel]):.0f} | "
              f"{np.median([g['vrel'] for g in sel]):.2f} | {np.median([g['still'] for g in sel]):.2f} |")
    print("\n## Distributions (10th / 50th / 90th percentile) by group\n")
    keys = (("prev/loc", "prev"), ("next/loc", "next"), ("v/med", "amp"), ("v rms/loc", "vloc"),
            ("still", "still"), ("|yaw|", "yaw"), ("ap/v", "ap"), ("ml/v", "ml"))
    print("| group | n | " + " | ".join(k for k, _ in keys) + " |\n|---|---|" + "---|" * len(keys))
    for g in ("TP", "FP stand", "FP other"):
        sel = [x for x in rows if x["grp"] == g]
        cells = []
        for _, k in keys:
            a = np.array([x[k] for x in sel], float)
            a = a[np.isfinite(a)]
            cells.append(" / ".join(f"{v:.2f}" for v in np.percentile(a, [10, 50, 90])) if a.size else "-")
        print(f"| {g} | {len(sel)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    M.cli_run(__doc__, main, "waist_stand_fp_s50_w572.md")
