"""Where the daily-activity lower-back step F1 is lost: gate, contact picker or timing (decision 29 of
docs/decisions/steps.md; a diagnosis, no tuning, no detector change).

Every contact and every detection of `pdrlearn steps --detector waist-ic` (the default lower-back detector) on
the mobgap Test11 and Test5 recordings, scored as `score_steps` scores it (decision 25's `scored`: inside the
`wb` bouts, untimed and same-foot-gap detections unscored, one-to-one within 0.25 s), is given ONE cause and
put into context.

Cause of a missed contact (FN), first that applies:
- ``timing``: an unmatched detection 0.25-0.5 s away (the step was found, its contact time is out of tolerance);
- otherwise the step's own loading peak is looked at -- the highest positive maximum of the detector's filtered
  vertical acceleration 0-0.6 s after the contact (seed 003 sec. 3.1: one vertical maximum per step, after
  the IC) -- and the loss is ``gate`` when the motion gate (W4) is closed there (walking not detected),
  ``picker`` otherwise (a maximum under the 0.1 m/s^2 height, or accepted and dropped by the sequence rules
  W18-W28, or no maximum at all);
Cause of a false detection (FP): ``timing`` (an unmatched contact 0.25-0.5 s away, the same event as a timing
FN), else ``picker``, split into ``gap`` (inside a reference gap > 1.2 s of one bout: the subject paused,
shuffled or turned and INDIP has no contact) and ``step`` (between two contacts < 1.2 s apart, or at a bout
edge: a second maximum inside one step). Each FP also says whether its vertical maximum was accepted by the
gate and height (``acc``) or added by the sequence rules (W18 fills / ends, W28 end steps).

Context (from the reference, for this analysis only; no detector reads it): turning = |mean pelvis yaw rate|
over 1 s centred >= 0.45 rad/s (the turning component of W7's mixture, decision 28) -- the waist's own gyro,
not turns.csv; cadence from the contact's mean reference interval to its bout neighbours (slow < 80,
80-100, >= 100 steps/min); stairs from the reference strides' `terrain`; bout start / end = first / last two
contacts of a bout; short bout < 4 contacts. Detections outside the reference bouts are not scored (no
reference there) and are only counted.

Run: PYTHONPATH=$PWD python experiments/waist_ic_loss.py   (writes experiments/results/waist_ic_loss.md)
"""

from __future__ import annotations

import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import signal as sg

from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.steps.detectors import get_detector  # noqa: E402
from pdrlearn.steps.evaluate import in_intervals, match_events, reference_events  # noqa: E402
from pdrlearn.waist import _kernels as K  # noqa: E402
from pdrlearn.waist.ahrs import waist_imu  # noqa: E402
from pdrlearn.waist.events import InitialContactDetector, walking_gate  # noqa: E402
from waist_ic_context import scored  # noqa: E402  (decision 25's scorer, = score_steps)

ROOT = Path(__file__).resolve().parents[1]
EXT = ROOT / "datasets" / "external"
SUBJECTS = ("HA001", "HA002", "MS001")
TOL, NEAR_S, GAP_S = 0.25, 0.5, 1.2  # decision 7; W26's timing miss and reference gap
LOAD_S = 0.6  # the step's loading peak: 0-0.6 s after its contact
TURN_RPS = 0.45  # decision 28 / W7
CONTEXTS = ("all", "straight", "turning", "slow <80", "80-100", ">=100", "bout start", "bout end",
            "short bout <4", "stairs")


def recordings() -> list[str]:
    out = [f"mobgap_{s}_Test11_Trial1" for s in SUBJECTS]
    for s in SUBJECTS:
        out += [f"mobgap_{s}_Test5_Trial{k}" for k in (1, 2)]
    return [r for r in out if (EXT / r / "ics.csv").exists()]  # Test5 trials with a reference


def analyse(session, ev: np.ndarray, kw: dict | None = None) -> dict:
    """One cause and the contexts of every contact / detection of ``session`` (see module doc)."""
    sc, rt = scored(session, ev)
    i_d, i_r = match_events(sc, rt, TOL)
    ics = session.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    it, wb = ics["ic_s"].to_numpy(float), ics["wb_id"].to_numpy()
    foot = ics["foot"].astype(str).str[0].to_numpy()
    imu = waist_imu(session)
    fs, t = imu.fs, imu.t
    gate = walking_gate(imu, causal=False)
    taps = K.fir_taps(2.5, fs, int(round(0.3 * fs)))  # the detector's own filter (seed 003, W16)
    vf = K.fir_zero_lag(imu.acc_v - np.mean(imu.acc_v), taps)
    cand, _ = sg.find_peaks(vf, height=0.0, distance=max(1, int(round(0.3 * fs))))
    strong = (vf[cand] >= 0.1) & gate[cand]  # the detector's acceptance (W4 gate, 0.1 m/s^2 height)
    side = K.step_sides(K.lateral_velocity(imu.acc_ml, fs)[cand], strong)  # W20
    pruned = K.prune_same_side(cand, vf[cand], strong, side, fs)  # W20's same-side pruning alone
    rules = {"rhythm": True, "max_step_s": 1.5, "min_step_s": 0.3, "min_peak": 0.1, "side": side, "end_steps": True}
    no_w23 = K.rhythm_complete(cand, vf[cand], strong, fs, unshifted=False,
                               **{k: v for k, v in rules.items() if k != "rhythm"})
    det = InitialContactDetector(**(kw or {})).detect(imu)
    kept = np.isin(cand, det.anchor_)
    anchor_t = dict(zip(np.round(t[det.ic_], 6), det.anchor_, strict=True))
    yaw = K.rolling_mean(imu.w_z, fs, window_s=1.0, causal=False)
    terr = session.steps[["ic_s", "terrain"]].dropna() if session.steps is not None else pd.DataFrame()

    def idx(x):
        return int(np.clip(np.searchsorted(t, x), 0, t.size - 1))

    def turning(x):
        return bool(abs(yaw[idx(x)]) >= TURN_RPS)

    def stairs(x):
        if terr.empty:
            return False
        k = int(np.argmin(np.abs(terr["ic_s"].to_numpy(float) - x)))
        return str(terr["terrain"].iloc[k]) not in ("flat", "nan")

    def ctx_ref(x):
        k = int(np.argmin(np.abs(it - x)))
        same = np.flatnonzero(wb == wb[k])
        pos = int(np.searchsorted(it[same], x - 1e-9))
        nb = [abs(it[same][j] - x) for j in (pos - 1, pos + 1) if 0 <= j < same.size]
        spm = 60.0 / float(np.mean(nb)) if nb else np.nan
        return {"turning": turning(x), "cad": spm, "start": pos <= 1, "end": pos >= same.size - 2,
                "short": same.size < 4, "stairs": stairs(x),
                # a reference contact closer than W16's shortest step (0.3 s) to a neighbour of its bout
                "close": bool(nb) and min(nb) < 0.3}

    fn_idx = np.setdiff1d(np.arange(rt.size), i_r)
    fp_idx = np.setdiff1d(np.arange(sc.size), i_d)
    un_d, un_r = sc[fp_idx], rt[fn_idx]
    unscored = np.setdiff1d(ev[in_intervals(ev, reference_events(session, "waist", tolerance_s=TOL).intervals)], sc)
    rows = []
    for k, x in enumerate(rt):
        r = {"kind": "ref", "t": x, **ctx_ref(x), "cause": "tp" if k in set(i_r.tolist()) else ""}
        if not r["cause"]:
            d = np.abs(np.concatenate([un_d, unscored]) - x)
            if np.any((d > TOL) & (d <= NEAR_S)):
                r["cause"] = "timing"
            else:
                lo, hi = idx(x), idx(x + LOAD_S)
                w = np.flatnonzero((cand >= lo) & (cand <= hi))
                own = w[~kept[w]]  # maxima of this step the detector did not keep
                if not w.size or not own.size:  # no maximum, or all of them are other contacts' anchors
                    r["cause"] = "gate" if not gate[idx(x + 0.3)] else "picker"
                    r["why"] = ("gate closed" if r["cause"] == "gate" else "no vertical maximum" if not w.size
                                else "merged: its maximum is a neighbouring contact's")
                else:
                    i = int(own[np.argmax(vf[cand[own]])])
                    r["cause"] = "gate" if not gate[cand[i]] else "picker"
                    r["why"] = ("gate closed" if not gate[cand[i]] else "under 0.1 m/s^2" if vf[cand[i]] < 0.1
                                else "W20 same-side prune" if not pruned[i]
                                else "W23 no weight shift" if no_w23[i] else "other sequence rule")
                    r["why"] += f" (side {side[i]:+d}, yaw {yaw[cand[i]]:+.2f} rad/s)"
        rows.append(r)
    for x in un_d:
        j = int(np.searchsorted(it, x))
        a, b = (it[j - 1] if j > 0 else -np.inf), (it[j] if j < it.size else np.inf)
        same_bout = 0 < j < it.size and wb[j - 1] == wb[j]
        d = np.abs(un_r - x)
        an = anchor_t.get(round(float(x), 6))
        accepted = an is not None and bool(gate[an]) and vf[an] >= 0.1
        j_an = int(np.searchsorted(cand, an)) if an is not None else -1
        nearest = it[int(np.argmin(np.abs(it - x)))]
        c = ctx_ref(nearest)
        c["turning"] = turning(x)
        if np.any((d > TOL) & (d <= NEAR_S)):
            cause = "timing"
        else:
            cause = "gap" if same_bout and b - a > GAP_S else "step"
        rows.append({"kind": "fp", "t": x, **c, "cause": cause, "acc": accepted,
                     "why": f"ref {foot[j - 1] if j > 0 else '-'}->{foot[j] if j < it.size else '-'}, side "
                            f"{side[j_an] if j_an >= 0 else 0:+d}, h {vf[an] if an is not None else np.nan:.2f}"})
    ref_iv = reference_events(session, "waist", tolerance_s=TOL).intervals
    out_ev = ev[~in_intervals(ev, ref_iv)]
    return {"rows": pd.DataFrame(rows), "tp": int(i_d.size), "det": int(sc.size), "ref": int(rt.size),
            "outside": int(out_ev.size), "outside_turning": int(sum(turning(x) for x in out_ev))}


def context_mask(df: pd.DataFrame, c: str) -> pd.Series:
    return {"all": pd.Series(True, index=df.index), "straight": ~df["turning"], "turning": df["turning"],
            "slow <80": df["cad"] < 80, "80-100": (df["cad"] >= 80) & (df["cad"] < 100), ">=100": df["cad"] >= 100,
            "bout start": df["start"], "bout end": df["end"], "short bout <4": df["short"],
            "stairs": df["stairs"]}[c].fillna(False).astype(bool)


def f1(tp: int, det: int, ref: int) -> float:
    return 2 * tp / (det + ref) if det + ref else float("nan")


def table(res: dict, names: list[str]) -> None:
    print("| recording | context | contacts | TP | FN gate | FN picker | FN timing | FP picker gap | FP picker step "
          "| FP timing | recall |")
    print("|" + "---|" * 11)
    for name in names:
        df = res[name]["rows"]
        for c in CONTEXTS:
            m = context_mask(df, c)
            ref = df[m & (df["kind"] == "ref")]
            fp = df[m & (df["kind"] == "fp")]
            n = len(ref)
            if c != "all" and n == 0 and len(fp) == 0:
                continue
            cnt = ref["cause"].value_counts()
            fc = fp["cause"].value_counts()
            rec = cnt.get("tp", 0) / n if n else float("nan")
            print(f"| {name} | {c} | {n} | {cnt.get('tp', 0)} | {cnt.get('gate', 0)} | {cnt.get('picker', 0)} | "
                  f"{cnt.get('timing', 0)} | {fc.get('gap', 0)} | {fc.get('step', 0)} | {fc.get('timing', 0)} | "
                  f"{rec:.3f} |")


def main() -> None:
    warnings.filterwarnings("ignore")
    logging.basicConfig(level=logging.ERROR)
    det = get_detector("waist-ic")
    res = {}
    for rec in recordings():
        s = read_session(EXT / rec)
        ev = np.sort(det.detect(s)["event_s"].to_numpy(float))
        res[rec.replace("mobgap_", "").replace("_Trial1", "").replace("_Trial", "_T")] = analyse(s, ev)
    names = list(res)
    t11 = [n for n in names if "Test11" in n]
    t5 = [n for n in names if "Test5" in n]
    print("## waist-ic: F1 and loss by cause (each error one cause)\n")
    print("| recording | F1 (TP/det/ref) | FN gate | FN picker | FN timing | FP picker gap | FP picker step | "
          "FP timing | FP rule-added | detections outside the bouts (turning) |")
    print("|" + "---|" * 10)
    for group, label in ((t11, "Test11 pooled"), (t5, "Test5 pooled")):
        tot = {"tp": 0, "det": 0, "ref": 0}
        for n in group:
            r = res[n]
            df = r["rows"]
            for k in tot:
                tot[k] += r[k]
            cn = df[df["kind"] == "ref"]["cause"].value_counts()
            fp = df[df["kind"] == "fp"]
            fc = fp["cause"].value_counts()
            added = int((~fp["acc"].astype(bool)).sum()) if len(fp) else 0
            print(f"| {n} | {f1(r['tp'], r['det'], r['ref']):.3f} ({r['tp']}/{r['det']}/{r['ref']}) | "
                  f"{cn.get('gate', 0)} | {cn.get('picker', 0)} | {cn.get('timing', 0)} | {fc.get('gap', 0)} | "
                  f"{fc.get('step', 0)} | {fc.get('timing', 0)} | {added} | {r['outside']} ({r['outside_turning']}) |")
        print(f"| {label} | {f1(tot['tp'], tot['det'], tot['ref']):.3f} ({tot['tp']}/{tot['det']}/{tot['ref']}) "
              "| | | | | | | | |")
    for group, label in ((t11, "Test11"), (t5, "Test5")):
        print(f"\n## {label}: by context (a contact / detection counts in every context it has)\n")
        pooled = {"rows": pd.concat([res[n]["rows"] for n in group], ignore_index=True)}
        table({**res, "pooled": pooled}, [*group, "pooled"])
    print("\n## F1 lost per cause, Test11 pooled (F1 if that cause's errors were absent)\n")
    allr = pd.concat([res[n]["rows"] for n in t11], ignore_index=True)
    tp = int((allr["cause"] == "tp").sum())
    ref = int((allr["kind"] == "ref").sum())
    det = tp + int((allr["kind"] == "fp").sum())
    base = f1(tp, det, ref)
    for lab, fnc, fpc in (("gate (FN)", ["gate"], []), ("picker (FN)", ["picker"], []),
                          ("picker (FP gap)", [], ["gap"]), ("picker (FP step)", [], ["step"]),
                          ("timing (FN+FP pairs)", ["timing"], ["timing"])):
        nfn = int(((allr["kind"] == "ref") & allr["cause"].isin(fnc)).sum())
        nfp = int(((allr["kind"] == "fp") & allr["cause"].isin(fpc)).sum())
        if lab.startswith("timing"):  # a timing pair: the detection becomes the hit
            g = f1(tp + min(nfn, nfp), det, ref)
        else:
            g = f1(tp + nfn, det + nfn, ref) if nfn else f1(tp, det - nfp, ref)
        print(f"- {lab}: {nfn} FN, {nfp} FP -> F1 {base:.3f} -> {g:.3f} (+{g - base:.3f})")
    print("\n## Missed contacts by detail, Test11 pooled (turning = |1 s mean yaw rate| >= 0.45 rad/s)\n")
    fn = allr[(allr["kind"] == "ref") & (allr["cause"] != "tp")]
    reason = fn["why"].fillna("").str.replace(r" \(side.*", "", regex=True).replace("", "timing (found, > 0.25 s)")
    print("| detail | FN | of them turning | of them < 0.3 s from a reference neighbour |\n|---|---|---|---|")
    for k, g in fn.groupby(reason):
        print(f"| {k} | {len(g)} | {int(g['turning'].sum())} | {int(g['close'].sum())} |")
    print("\n## Every error (recording, kind, t s, cause, detail, context)\n")
    for n in names:
        df = res[n]["rows"]
        for r in df[(df["kind"] == "fp") | (df["cause"] != "tp")].itertuples():
            ctx = [k for k in ("turning", "start", "end", "short", "stairs", "close") if getattr(r, k)]
            detail = r.why if isinstance(r.why, str) else ""
            if r.kind == "fp":
                detail += " acc" if r.acc else " rule-added"
            print(f"{n} {'FN' if r.kind == 'ref' else 'FP'} {r.t:.2f} {r.cause} [{detail.strip()}] "
                  f"cad {r.cad:.0f} {' '.join(ctx)}")


if __name__ == "__main__":
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main()
    (ROOT / "experiments" / "results" / "waist_ic_loss.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
