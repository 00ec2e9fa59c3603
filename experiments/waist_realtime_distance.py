"""Why `waist-pendulum` offline and realtime (W31) track different Test11 distances (decision W35).

Per mobgap subject's Test11 (`pdrlearn fetch mobgap --out datasets/external`), meta.json defaults (K = 1;
a calibration multiplies both pipelines' lengths by the same K, W21, because both Test5 detections agree):
1. per reference bout: the steps each pipeline counts (midpoint inside the bout, W21) and their total
   length, against the INDIP `Length` and the bout's own strides (W25); the steps both have (the same two
   contacts) and whether they got the same length;
2. the contacts only one detector has (inside the bouts +- 0.25 s), each labelled `timed` (within 0.25 s of
   a timed INDIP contact), `untimed` (inside the interval of an INDIP contact without a time, X2: a step that
   happened) or `none`, and what they cost in distance: steps a missing contact removes (a contact gap over
   the longest step, 1.5 s, ends the walking sequence and its steps carry no length) or joins;
3. the window trace behind one of them (HA002 8.91 s): the W20 side cue at that maximum in the W31 windows
   ending 1.25-2.25 s after it;
4. (--side-cue) the W20 side cue in the windows that decide (maxima 1.75-2.0 s before the window end) against
   the same cue on the whole recording: agreement of the side, |difference| / the median |v|; for scipy's
   default padding of the zero-phase filters (the detector's) and 2 s of odd / even reflection (W31's
   variants), each against its own whole-recording cue;
5. (--variants) the realtime pipeline with other decision rules, calibrated on Test5 as
   `experiments/waist.py`: a contact kept when it is in at least `need` of the last `k` windows (the
   decision window and the k - 1 before it, same contact = ICs within 0.15 s), or the side cue padded as in 4.

Run: .venv/bin/python experiments/waist_realtime_distance.py [--external datasets/external] [--side-cue]
[--variants]
Writes experiments/results/waist_realtime_distance.md.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd
from scipy import signal as sg

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import bout_stride_length, reference_bouts, steps_in_interval
from pdrlearn.waist.events import _window, walking_gate

# W31's padded side-cue variant, one definition for both scripts
from waist_realtime_ic import _padded_lateral_velocity as _padded_lv  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = ("HA001", "HA002", "MS001")
TOL = 0.25  # s, the step-matching tolerance of step_metrics
SAME = 0.05  # s: two detectors' contacts closer than this are the same contact


def _walking(st: pd.DataFrame) -> pd.DataFrame:
    return st[st["has_next"].to_numpy(bool)]


def _status(t: float, ref: np.ndarray, untimed: pd.DataFrame) -> str:
    if ref.size and np.min(np.abs(ref - t)) <= TOL:
        return "timed"
    if any((u.after_s + TOL < t < u.before_s - TOL) for u in untimed.itertuples()):
        return "untimed"
    return "none"


def bouts_table(name: str, s, off: pd.DataFrame, rt: pd.DataFrame) -> list[dict]:
    rows = []
    wo, wr = _walking(off), _walking(rt)
    for b in reference_bouts(s).itertuples():
        so = wo[steps_in_interval(wo, b.start_s, b.end_s)]
        sr = wr[steps_in_interval(wr, b.start_s, b.end_s)]
        ko = {(round(x, 3), round(y, 3)): v for x, y, v in zip(so.start_s, so.end_s, so.length_m, strict=True)}
        kr = {(round(x, 3), round(y, 3)): v for x, y, v in zip(sr.start_s, sr.end_s, sr.length_m, strict=True)}
        common = sorted(set(ko) & set(kr))
        ls, _ = bout_stride_length(s, b.start_s, b.end_s)
        rows.append({"subject": name, "bout_s": round(b.start_s, 2), "L_m": b.length_m, "L_strides_m": ls,
                     "offline_m": so.length_m.sum(), "realtime_m": sr.length_m.sum(),
                     "offline_steps": len(so), "realtime_steps": len(sr), "common_steps": len(common),
                     "common_same_length": sum(abs(ko[k] - kr[k]) < 1e-9 for k in common),
                     "common_offline_m": sum(ko[k] for k in common), "common_realtime_m": sum(kr[k] for k in common)})
    return rows


def contacts_table(name: str, s, off: pd.DataFrame, rt: pd.DataFrame) -> list[dict]:
    b = reference_bouts(s)
    ref = np.sort(s.extras["ics"]["ic_s"].dropna().to_numpy(float))
    untimed = s.extras.get("ics_untimed", pd.DataFrame(columns=["after_s", "before_s"]))
    rows = []
    for label, a, other in (("offline only", off, rt), ("realtime only", rt, off)):
        ta, tb = a["start_s"].to_numpy(float), other["start_s"].to_numpy(float)
        for i, t in enumerate(ta):
            inside = ((t >= b.start_s - TOL) & (t <= b.end_s + TOL)).any()
            if not inside or (tb.size and np.min(np.abs(tb - t)) <= SAME):
                continue
            # what the other detector does without it: the step before it spans the gap or ends a sequence
            j = int(np.searchsorted(tb, t)) - 1
            gap = float(tb[j + 1] - tb[j]) if 0 <= j < tb.size - 1 else float("nan")
            rows.append({"subject": name, "contact": label.split()[0] + " only", "t_s": round(t, 2),
                         "reference": _status(t, ref, untimed),
                         "steps_at_it_m": round(float(a["length_m"].iloc[i]
                                                      + (a["length_m"].iloc[i - 1] if i else 0.0)), 3),
                         "other_gap_s": round(gap, 2),
                         "other": "sequence break" if gap > 1.5 else "one longer step"})
    return rows


def side_trace(s, t_max: float) -> list[dict]:
    """The W20 side cue and the detector's verdict at the vertical maximum nearest ``t_max`` in the W31
    windows (the offline detector on ``[T - 12 s, T)``, ``T`` on the 0.25 s decision grid) ending 1.25 to
    2.25 s after it (the one ending 1.75-2.0 s after its contact decides it), and on the whole recording."""
    from pdrlearn.waist.events import InitialContactDetector

    imu = waist_imu(s)
    fs = imu.fs
    det = InitialContactDetector()
    hop, span = int(round(K.DECISION_HOP_S * fs)), int(round((K.DECISION_HISTORY_S + K.DECISION_DELAY_S
                                                                + K.DECISION_HOP_S) * fs))
    i_max = int(round((t_max - imu.t[0]) * fs))
    ends = [tt for tt in range(hop, len(imu.t) + 1, hop) if 1.25 * fs <= tt - i_max <= 2.25 * fs]
    taps = K.fir_taps(2.5, fs, int(round(0.3 * fs)))
    rows = []
    for hi in [*ends, None]:
        lo = 0 if hi is None else max(0, hi - span)
        w = _window(imu, lo, len(imu.t) if hi is None else hi)
        vf = K.fir_zero_lag(w.acc_v - np.mean(w.acc_v), taps)
        cand, _ = sg.find_peaks(vf, height=0.0, distance=int(round(0.3 * fs)))
        strong = (vf[cand] >= 0.1) & walking_gate(w)[cand]
        v = K.lateral_velocity(w.acc_ml, fs)[cand]
        side = K.step_sides(v, strong)
        c = int(np.argmin(np.abs(w.t[cand] - t_max)))
        ic, _, an = det._offline(w)
        rows.append({"window_end_s": "whole recording" if hi is None else f"{imu.t[0] + hi / fs:.2f}",
                     "after_max_s": "-" if hi is None else f"{(hi - lo - cand[c]) / fs:.2f}",
                     "v_ml_mps": round(float(v[c]), 4),
                     "third_of_median_mps": round(float(np.median(np.abs(v[strong]))) / 3, 4),
                     "side": int(side[c]), "height_mps2": round(float(vf[cand[c]]), 3),
                     "kept": bool(np.any(np.abs(an - cand[c]) <= 1))})
    return rows


SIDE_VARIANTS = {"scipy default (detector)": None, "odd 2 s": ("odd", 2.0), "even 2 s": ("even", 2.0)}


def side_cue_at_decisions(s) -> list[dict]:
    imu = waist_imu(s)
    fs = imu.fs
    taps = K.fir_taps(2.5, fs, int(round(0.3 * fs)))
    dist = int(round(0.3 * fs))
    hop, span = int(round(K.DECISION_HOP_S * fs)), int(round((K.DECISION_HISTORY_S + K.DECISION_DELAY_S
                                                                + K.DECISION_HOP_S) * fs))
    d0, d1 = int(round(K.DECISION_DELAY_S * fs)), int(round((K.DECISION_DELAY_S + K.DECISION_HOP_S) * fs))

    def cues(w, lv):
        vf = K.fir_zero_lag(w.acc_v - np.mean(w.acc_v), taps)
        cand, _ = sg.find_peaks(vf, height=0.0, distance=dist)
        strong = (vf[cand] >= 0.1) & walking_gate(w)[cand]
        v = lv(w.acc_ml, fs)
        return cand, strong, v, K.step_sides(v[cand], strong)

    rows = []
    for name, pad in SIDE_VARIANTS.items():
        lv = K.lateral_velocity if pad is None else _padded_lv(*pad)
        cand, strong, v, side = cues(imu, lv)
        scale = float(np.median(np.abs(v[cand[strong]])))
        same = n = 0
        rel = []
        for hi in range(hop, len(imu.t) + 1, hop):
            m = strong & (cand > hi - d1) & (cand <= hi - d0)
            if not m.any():
                continue
            lo = max(0, hi - span)
            cw, _, vw, sw = cues(_window(imu, lo, hi), lv)
            for c in cand[m]:
                j = np.flatnonzero(cw + lo == c)
                if j.size:
                    n += 1
                    same += int(sw[j[0]] == side[cand == c][0])
                    rel.append(abs(vw[c - lo] - v[c]) / scale)
        rows.append({"side cue padding": name, "maxima decided": n, "same side as whole recording": same,
                     "agreement": same / n, "median |dv| / median |v|": float(np.median(rel)),
                     "p90 |dv| / median |v|": float(np.percentile(rel, 90))})
    return rows


def voting(k: int, need: int, tol_s: float = 0.15):
    """W31's ``delayed_decisions`` where a contact in the decision range is kept when it is in at least
    ``need`` of the last ``k`` windows (same contact: ICs within ``tol_s``; taken from the latest window)."""
    def dd(n, fs, detect, *, delay_s=K.DECISION_DELAY_S, hop_s=K.DECISION_HOP_S, history_s=K.DECISION_HISTORY_S,
           min_step_s=0.3, final=True):
        hop, dly = max(1, int(round(hop_s * fs))), int(round(delay_s * fs))
        hist, min_gap, tol = int(round(history_s * fs)), max(1, int(round(min_step_s * fs))), int(round(tol_s * fs))
        times = list(range(hop, n + 1, hop))
        if final and (not times or times[-1] != n):
            times.append(n)
        wins: list = []
        out: list = []
        done = -1
        for tt in times:
            last = final and tt == n
            upto = n - 1 if last else tt - dly
            if upto <= done:
                continue
            lo = max(0, tt - hist - dly - hop)
            ic, fc, an = detect(lo, tt)
            wins.append((np.asarray(ic) + lo, np.asarray(fc) + lo, np.asarray(an) + lo))
            group = wins[-k:]
            found = sorted((a, b, c, g) for g, w in enumerate(group) for a, b, c in zip(*w, strict=True)
                           if done < a <= upto)
            clusters: list = []
            for x in found:
                if clusters and x[0] - clusters[-1][-1][0] <= tol:
                    clusters[-1].append(x)
                else:
                    clusters.append([x])
            for cl in clusters:
                if last or len({x[3] for x in cl}) >= min(need, len(group)):
                    a, b, c, _ = max(cl, key=lambda x: x[3])
                    if not out or a - out[-1][0] >= min_gap:
                        out.append((a, b, c, tt))
            done = upto
        o = np.array(out, dtype=int).reshape(-1, 4)
        return o[:, 0], o[:, 1], o[:, 2], o[:, 3]
    return dd


DECISION_VARIANTS = {"W31 (default)": None, "any of 2 windows": ("vote", 2, 1), "2 of 3": ("vote", 3, 2),
                     "3 of 4": ("vote", 4, 3), "side cue odd-padded 2 s": ("pad", "odd"),
                     "side cue even-padded 2 s": ("pad", "even")}


def decision_variants(ext: Path) -> pd.DataFrame:
    """Realtime `waist-pendulum` per decision variant, calibrated on Test5 as `experiments/waist.py` does:
    Test11 step F1 and median |per-bout error| vs `Length` / vs strides per subject, pooled over the bouts."""
    from unittest import mock

    import waist as W

    runs = [r for r in W.external_runs(ext) if "Test11" in r[1]]
    cfg = [("realtime", "waist-pendulum", {"realtime": True})]
    rows = []
    for name, v in DECISION_VARIANTS.items():
        dd = voting(*v[1:]) if v and v[0] == "vote" else K.delayed_decisions
        lv = _padded_lv(v[1], 2.0) if v and v[0] == "pad" else K.lateral_velocity
        with mock.patch.object(K, "delayed_decisions", dd), mock.patch.object(K, "lateral_velocity", lv):
            bouts: list = []
            df = W.real(ext, runs, configs=cfg, bouts=bouts)
        b = pd.DataFrame(bouts)
        b = b[b.params == "calibrated"]
        row = {"decision": name}
        for subj, g in b.groupby("subject"):
            d = df[(df.subject == subj) & (df.params == "calibrated")].iloc[0]
            row[subj] = (f"F1 {d.step_f1:.3f}, {g.error_pct.abs().median():.1f} / "
                         f"{g.error_strides_pct.abs().median():.1f} %")
        row["pooled"] = f"{b.error_pct.abs().median():.2f} / {b.error_strides_pct.abs().median():.2f} %"
        rows.append(row)
        print(row, flush=True)
    return pd.DataFrame(rows)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--side-cue", action="store_true", help="the side cue at the deciding windows (section 4)")
    ap.add_argument("--variants", action="store_true", help="realtime decision variants, calibrated (section 5)")
    a = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    bouts, contacts = [], []
    for name in SUBJECTS:
        s = read_session(a.external / f"mobgap_{name}_Test11_Trial1")
        off = get_pipeline("waist-pendulum")(s).steps
        rt = get_pipeline("waist-pendulum")(s, realtime=True).steps
        bouts += bouts_table(name, s, off, rt)
        contacts += contacts_table(name, s, off, rt)
    bt, ct = pd.DataFrame(bouts), pd.DataFrame(contacts)
    tot = bt.groupby("subject")[["L_m", "L_strides_m", "offline_m", "realtime_m", "offline_steps", "realtime_steps",
                                 "common_steps", "common_same_length", "common_offline_m", "common_realtime_m"]].sum()
    for k in ("offline", "realtime"):
        tot[f"{k}_vs_L_pct"] = 100 * (tot[f"{k}_m"] / tot["L_m"] - 1)
        tot[f"{k}_vs_strides_pct"] = 100 * (tot[f"{k}_m"] / tot["L_strides_m"] - 1)
    summary = (ct.groupby(["contact", "reference"]).size().unstack(fill_value=0) if len(ct) else pd.DataFrame())
    trace = pd.DataFrame(side_trace(read_session(a.external / "mobgap_HA002_Test11_Trial1"), 8.91))
    pd.set_option("display.width", 250)
    parts = [("Per subject (Test11, meta.json defaults, steps inside the reference bouts)", tot.reset_index()),
             ("Per bout", bt), ("Contacts only one detector has (inside the bouts)", ct),
             ("Those contacts by reference label", summary.reset_index() if len(summary) else summary),
             ("W20 side cue at HA002's 8.91 s maximum, W31 windows ending after it", trace)]
    if a.side_cue:
        for name in SUBJECTS:
            sc = pd.DataFrame(side_cue_at_decisions(read_session(a.external / f"mobgap_{name}_Test11_Trial1")))
            parts.append((f"{name} Test11: W20 side cue of the maxima each W31 window decides vs the whole recording",
                          sc))
    if a.variants:
        parts.append(("Realtime decision variants, calibrated on Test5: Test11 F1, median |per-bout error| vs "
                      "Length / vs strides", decision_variants(a.external)))
    lines = ["# Offline vs realtime waist-pendulum distance on Test11 (decision W35)", "",
             "Generated by `experiments/waist_realtime_distance.py`.", ""]
    for title, df in parts:
        print(f"\n{title}:")
        print(df.round(3).to_string(index=False))
        lines += [f"## {title}", "", df.round(3).to_markdown(index=False), ""]
    out = ROOT / "experiments" / "results" / "waist_realtime_distance.md"
    out.write_text("\n".join(lines) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
