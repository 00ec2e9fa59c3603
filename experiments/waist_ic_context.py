"""Daily-activity IC errors by walking-bout context (decision 25 of docs/decisions/steps.md; no tuning).

For the Test11 recordings of the mobgap subjects, every error of `pdrlearn steps --detector waist-ic` (the
default lower-back detector), scored exactly as `score_steps` scores it (inside the `wb` bouts widened by the
tolerance, untimed INDIP contacts and one detection per same-foot reference gap unscored, one-to-one matching
within 0.25 s, decisions 7, 19, 20), is put into context from the reference's own labels (bouts.csv,
turns.csv, ics.csv feet; for this analysis only, no detector reads them):

- missed contacts (FN): bout start (first two contacts of a bout), bout end (last two), inside a reference
  turn, in a short bout (< 10 timed contacts), slow (the contact's mean reference interval to its
  neighbours > 0.75 s, i.e. cadence < 80 steps/min), motion gate closed (2 s std of the vertical
  acceleration <= 0.5 m/s^2, W4), "timing miss" (an unmatched scored detection 0.25-0.5 s away: the
  step was seen, too far from the INDIP time) and "IC late" (a kept vertical maximum 0.25-0.6 s after the
  contact whose IC lies more than 0.25 s after it, whether or not that detection is scored);
- false detections (FP): timing miss (an unmatched reference contact 0.25-0.5 s away), in a reference gap
  > 1.2 s, inside one step (between two contacts of opposite feet less than 1.2 s apart), bout start/end
  (before the second or after the second-last contact), inside a reference turn;
- whether the lab's second reference (Stereophoto, `ics_stereophoto.csv`, docs/external-data.md X4; only inside
  its capture volume) has a contact within 0.25 s of the error;
- the signed offsets of the matched contacts against the tolerance (histogram of |dt|);
- stairs: the reference's `terrain` column (steps.csv) -- every Test11 stride of these subjects is `flat`.
The categories overlap (a contact can be a bout start in a turn); each row counts it once per category.

mobgap's own IC detector on the same recordings: the F1 of the raw ICs of its pipelines' gait sequences
(`raw_step_f1` of experiments/results/peers.csv, written by experiments/peers.py in its own venv; read
here, not re-run).

Run: PYTHONPATH=$PWD python experiments/waist_ic_context.py [--external datasets/external]
Writes experiments/results/waist_ic_context.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.steps.detectors import get_detector
from pdrlearn.steps.evaluate import (
    in_intervals,
    match_events,
    reference_events,
    same_foot_gap_mask,
    untimed_mask,
)
from pdrlearn.waist import _kernels as K
from pdrlearn.waist import events as E
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import InitialContactDetector

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = ("HA001", "HA002", "MS001")
TOL = 0.25  # decision 7
NEAR_S = 0.5  # a timing miss: the other side 0.25-0.5 s away (W26)
SLOW_S = 0.75  # mean interval to the neighbouring contacts > 0.75 s = cadence < 80 steps/min
SHORT_BOUT = 10  # timed contacts
GAP_S = 1.2  # W26/W45's reference gap


def scored(session, ev: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The detections `score_steps` scores and the reference contacts (sorted)."""
    ref = reference_events(session, "waist", tolerance_s=TOL)
    sc = ev[in_intervals(ev, ref.intervals)]
    un = untimed_mask(sc, session, TOL)
    lost = same_foot_gap_mask(sc, session, TOL, taken=un)
    return sc[~(un | lost)], np.sort(ref.times)


def analyse(session, ev: np.ndarray) -> dict:
    sc, rt = scored(session, ev)
    i_d, i_r = match_events(sc, rt, TOL)
    ics = session.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    it = ics["ic_s"].to_numpy(float)
    foot = ics["foot"].astype(str).str[0].to_numpy()
    wb = ics["wb_id"].to_numpy()
    turns = session.extras.get("turns")
    tw = turns[["start_s", "end_s"]].to_numpy(float) if turns is not None and len(turns) else np.empty((0, 2))
    so = session.extras.get("ics_stereophoto")
    st = np.sort(so["ic_s"].dropna().to_numpy(float)) if so is not None and "ic_s" in so else np.empty(0)
    imu = waist_imu(session)
    sigma = K.rolling_std(imu.acc_v, imu.fs, causal=False)
    det = InitialContactDetector().detect(imu)  # the same contacts as `ev` (waist-ic = this detector)
    vmax_t, ic_t = imu.t[det.anchor_], imu.t[det.ic_]

    def gate_closed(t):
        return sigma[int(np.argmin(np.abs(imu.t - t)))] <= E.WALK_THRESHOLD_MPS2

    fn_idx = np.setdiff1d(np.arange(rt.size), i_r)
    fp_idx = np.setdiff1d(np.arange(sc.size), i_d)
    un_d, un_r = sc[fp_idx], rt[fn_idx]
    fn_rows, fp_rows = [], []
    for t in un_r:
        k = int(np.argmin(np.abs(it - t)))
        same = np.flatnonzero(wb == wb[k])
        pos = int(np.searchsorted(it[same], t - 1e-9))
        nb = [it[same][j] for j in (pos - 1, pos + 1) if 0 <= j < same.size]
        interval = float(np.mean([abs(t - x) for x in nb])) if nb else np.nan
        d = np.abs(un_d - t)
        fn_rows.append({"t": t, "start": pos <= 1, "end": pos >= same.size - 2,
                        "turn": bool(in_intervals(np.array([t]), tw)[0]), "short": same.size < SHORT_BOUT,
                        "slow": interval > SLOW_S, "gate": gate_closed(t),
                        "timing": bool(np.any((d > TOL) & (d <= NEAR_S))),
                        # the step was found, its IC too late: a kept vertical maximum 0.25-0.6 s after the
                        # contact whose IC (W3: last AP maximum <= 0.25 s before it) lies > 0.25 s after it
                        "late_ic": bool(np.any((vmax_t - t > TOL) & (vmax_t - t <= 0.6) & (ic_t - t > TOL))),
                        "stereo": bool(st.size and np.min(np.abs(st - t)) <= TOL)})
    for t in un_d:
        j = int(np.searchsorted(it, t))
        a, b = (it[j - 1] if j > 0 else -np.inf), (it[j] if j < it.size else np.inf)
        same_bout = 0 < j < it.size and wb[j - 1] == wb[j]
        if same_bout:  # position of the contact before it in its bout
            members = np.flatnonzero(wb == wb[j - 1])
            pos, n = int(np.searchsorted(members, j - 1)), members.size
            edge = pos == 0 or pos >= n - 2  # before the second or after the second-last contact
        else:
            edge = True  # before the first / after the last contact of a bout (inside its tolerance)
        d = np.abs(un_r - t)
        fp_rows.append({"t": t, "timing": bool(np.any((d > TOL) & (d <= NEAR_S))),
                        "gap": same_bout and b - a > GAP_S,
                        "in_step": same_bout and b - a <= GAP_S and foot[j - 1] != foot[j],
                        "edge": edge, "turn": bool(in_intervals(np.array([t]), tw)[0]), "gate": gate_closed(t),
                        "stereo": bool(st.size and np.min(np.abs(st - t)) <= TOL)})
    dt = sc[i_d] - rt[i_r]
    return {"tp": int(i_d.size), "det": int(sc.size), "ref": int(rt.size), "fn": fn_rows, "fp": fp_rows,
            "dt": dt, "n_stereo": int(st.size)}


def f1(tp: int, det: int, ref: int) -> float:
    return 2 * tp / (det + ref) if det + ref else float("nan")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--subjects", default=",".join(SUBJECTS))
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.basicConfig(level=logging.ERROR)
    det = get_detector("waist-ic")
    res = {}
    for sub in args.subjects.split(","):
        s = read_session(args.external / f"mobgap_{sub}_Test11_Trial1")
        ev = np.sort(det.detect(s)["event_s"].to_numpy(float))
        res[sub] = analyse(s, ev)
        terrain = s.steps["terrain"].astype(str).value_counts().to_dict() if s.steps is not None else {}
        res[sub]["terrain"] = terrain
    print("## waist-ic on Test11: F1 and errors by context (categories overlap)\n")
    cols = ["subject", "F1 (TP/det/ref)", "FN", "FN bout start", "FN bout end", "FN turn", "FN short bout",
            "FN slow (>0.75 s)", "FN gate closed", "FN timing miss", "FN step found, IC > 0.25 s late",
            "FN Stereophoto contact within 0.25 s", "FP", "FP timing miss", "FP ref gap >1.2 s",
            "FP inside a step", "FP bout edge", "FP turn", "FP gate closed", "FP Stereophoto contact within 0.25 s",
            "Stereophoto contacts", "stairs"]
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * 22)
    tot = {"tp": 0, "det": 0, "ref": 0}
    for sub, r in res.items():
        for k in tot:
            tot[k] += r[k]
        fn, fp = pd.DataFrame(r["fn"]), pd.DataFrame(r["fp"])
        c = [int(fn[k].sum()) if len(fn) else 0 for k in ("start", "end", "turn", "short", "slow", "gate", "timing",
                                                       "late_ic", "stereo")]
        p = [int(fp[k].sum()) if len(fp) else 0 for k in ("timing", "gap", "in_step", "edge", "turn", "gate", "stereo")]
        stairs = ", ".join(f"{k} {v}" for k, v in r["terrain"].items())
        print(f"| {sub} | {f1(r['tp'], r['det'], r['ref']):.3f} ({r['tp']}/{r['det']}/{r['ref']}) | {len(fn)} | "
              + " | ".join(map(str, c)) + f" | {len(fp)} | " + " | ".join(map(str, p))
              + f" | {r['n_stereo']} | {stairs} |")
    print(f"\npooled F1 {f1(tot['tp'], tot['det'], tot['ref']):.3f} ({tot['tp']}/{tot['det']}/{tot['ref']})")
    print("\n## Offsets of the matched contacts (detection - INDIP), against the 0.25 s tolerance\n")
    bins = [0, 0.05, 0.1, 0.15, 0.2, 0.25]
    print("| subject | n | mean (ms) | sd (ms) | " + " | ".join(f"|dt| {a:.2f}-{b:.2f}" for a, b in
                                                        zip(bins[:-1], bins[1:], strict=True)) + " |")
    print("|" + "---|" * (4 + len(bins) - 1))
    for sub, r in res.items():
        h = np.histogram(np.abs(r["dt"]), bins=bins)[0]
        print(f"| {sub} | {r['dt'].size} | {1000 * r['dt'].mean():+.1f} | {1000 * r['dt'].std():.1f} | "
              + " | ".join(map(str, h)) + " |")
    print("\n## Every error (t s; flags)\n")
    for sub, r in res.items():
        for kind in ("fn", "fp"):
            for row in r[kind]:
                flags = [k for k, v in row.items() if k != "t" and v]
                print(f"{sub} {kind.upper()} {row['t']:.2f} {' '.join(flags)}")
    peers = ROOT / "experiments" / "results" / "peers.csv"
    if peers.exists():
        p = pd.read_csv(peers)
        p = p[p["pipeline"].astype(str).str.startswith("mobgap") & (p["test"] == "Test11_Trial1")]
        p = p.drop_duplicates(["subject", "pipeline"])
        print("\n## mobgap 1.2.0 on the same recordings (experiments/results/peers.csv, experiments/peers.py)\n")
        print("| subject | pipeline | raw IC F1 (all its gait sequences) | final-stride IC F1 (P, R) |")
        print("|---|---|---|---|")
        for q in p.itertuples():
            print(f"| {q.subject} | {q.pipeline} ({q.params}) | {q.raw_step_f1:.3f} | {q.step_f1:.3f} "
                  f"({q.step_precision:.3f}, {q.step_recall:.3f}) |")


if __name__ == "__main__":
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main()
    (ROOT / "experiments" / "results" / "waist_ic_context.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
