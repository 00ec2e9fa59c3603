"""Issue 8, decision W317: where the tracker's own Test11 bout error (W273's "without both reference terms") lies per
step -- turning vs straight steps, slow vs normal ones. Diagnosis only: no behaviour change.

Protocol and segments: experiments/waist_bout_terms.py (W220: K from the subject's Test5 walks, tested on Test11,
`waist-pendulum` with today's defaults; anchors = detected contacts matched one-to-one to INDIP's timed contacts;
a segment = the tracked and reference steps between two anchors). The tracker's own error of a bout is
``tracked - sum s_j`` (s_j = INDIP's stride / 2 per reference step), i.e. W273's error with both reference terms
removed. Each segment is classed:
- turning = a reference step's midpoint inside an INDIP turn (turns.csv) OR a tracked step whose mean yaw rate
  (|dyaw_rad| / its IC-to-IC time) W82's prior turn classifier (`TurnClassifier()`, boundary 0.136 rad/s) calls
  turning; else straight;
- kind = count (n tracked != n reference steps: missed / extra contacts) or step (n = n: correctly delimited);
- pace (step segments): slow = the reference step's cadence below 0.9 x the calibration walks' median cadence
  (W211's lower bound), else normal;
- edge = W220's place "edge" (outside the first / last anchor or holding the bout's first / last step), printed.
Per correctly delimited single step it prints the tracked length, the pendulum before W19's ``cos(turn)``
(``length_m / cos(min(|dyaw|, 90 deg))``) and the reference, by class.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_bout_turn_w317.py [--external datasets/external]
"""

from __future__ import annotations

import os
import sys

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
import waist_bout_terms as T  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.waist.evaluate import reference_bouts  # noqa: E402
from pdrlearn.waist.heading import TurnClassifier  # noqa: E402

RESULT = W.ROOT / "experiments" / "results" / "waist_bout_turn_w317.txt"
SLOW = 0.9  # W211: the calibration's cadence range starts at x0.9
CLASSES = ("turn count", "turn step", "straight count", "straight step slow", "straight step normal")


def step_turning(sel: pd.DataFrame) -> np.ndarray:
    """Per tracked step: W82's prior turn classifier on its mean yaw rate |dyaw| / IC-to-IC time (rad/s)."""
    dt = np.maximum((sel["end_s"] - sel["start_s"]).to_numpy(float), 1e-3)
    rate = np.abs(np.nan_to_num(sel["dyaw_rad"].to_numpy(float))) / dt
    return TurnClassifier().predict(rate).astype(bool)


def classify(steps: pd.DataFrame, session, subject: str, params: str, cal_spm: float) -> tuple[list, list]:
    """Per bout the tracker's own error by class (metres) and one row per correctly delimited single step."""
    turns = T.session_turns(session)
    bouts, singles = [], []
    for b in reference_bouts(session).itertuples():
        g = T.bout_segments(steps, session, b.start_s, b.end_s, turns)
        sel, dl, s, r = g["sel"], g["dl"], g["s"], g["r"]
        yaw_turn = step_turning(sel)
        dyaw = np.abs(np.nan_to_num(sel["dyaw_rad"].to_numpy(float)))
        row = {"subject": subject, "params": params, "start_s": b.start_s, "L_m": b.length_m,
               "own_m": float(dl.sum() - s.sum()), "err_m": float(dl.sum()) - b.length_m,
               **dict.fromkeys(CLASSES, 0.0)}
        for seg in g["segments"]:
            dm, rm = seg["dm"], seg["rm"]
            t_indip, t_yaw = bool((g["in_turn"] & rm).any()), bool(yaw_turn[dm].any())
            turning = t_indip or t_yaw
            if seg["kind"] == "count":
                row["turn count" if turning else "straight count"] += seg["e"]
                continue
            dur = np.diff(r)[rm]
            slow = bool((60 / dur < SLOW * cal_spm).any())
            cls = "turn step" if turning else f"straight step {'slow' if slow else 'normal'}"
            row[cls] += seg["e"]
            if dm.sum() == 1:
                cos = np.cos(min(float(dyaw[dm][0]), np.pi / 2))  # W19's factor
                singles.append({"subject": subject, "params": params, "start_s": float(sel["start_s"][dm].iloc[0]),
                                "class": cls, "turns_csv": t_indip, "yaw_turn": t_yaw, "edge": seg["place"] == "edge",
                                "dyaw_deg": float(np.degrees(dyaw[dm][0])), "cadence_spm": float(60 / dur[0]),
                                "tracked_m": float(dl[dm][0]), "reference_m": float(s[rm][0]),
                                "pendulum_m": float(dl[dm][0] / cos) if cos > 1e-6 else np.nan})
        assert abs(sum(row[c] for c in CLASSES) - row["own_m"]) < 1e-9
        bouts.append(row)
    return bouts, singles


def main() -> None:
    ext, runs = W.test11_cli()
    bouts, singles = [], []
    for subject, test, params in T.calibrated_test11(ext, runs):
        cal_spm = float(params.gait["median_cadence_spm"])
        for name, p in (("calibrated", params), ("defaults", None)):
            b, s = classify(get_pipeline("waist-pendulum")(test, params=p).steps, test, subject, name, cal_spm)
            bouts += b
            singles += s
    t, m = pd.DataFrame(bouts), pd.DataFrame(singles)
    for c in (*CLASSES, "own_m", "err_m"):
        t[f"{c} %"] = 100 * t[c] / t.L_m
    out: list[str] = [f"Command: `PYTHONPATH=. .venv/bin/python experiments/waist_bout_turn_w317.py --external "
                      f"{os.path.relpath(ext.absolute(), W.ROOT)}`", ""]

    def say(*parts) -> None:  # every line is printed and saved
        out.append(" ".join(str(x) for x in parts))
    pct = [f"{c} %" for c in CLASSES]
    say("per bout, the tracker's own error (tracked - sum of INDIP stride/2 per step; W273 without both ref terms) and"
        " its classes, % of Length:")
    say(t[["subject", "params", "start_s", "L_m", "own_m %", *pct]].round(2).to_string(index=False))
    say("\nper subject: summed own error (m) by class; median |own %| over the bouts; median |error vs Length| (the"
        " issue's metric) as is and without the turn step class; median |class %|; median |own %| without the class:")
    rows = []
    for (params, subject), h in [*t.groupby(["params", "subject"], sort=False),
                                 *(((p, "pooled"), h) for p, h in t.groupby("params", sort=False))]:
        r = {"params": params, "subject": subject, "bouts": len(h), "own_m": h.own_m.sum(),
             "median |own %|": h["own_m %"].abs().median(), "median |err_L|": h["err_m %"].abs().median(),
             "err_L w/o turn step": (h["err_m %"] - h["turn step %"]).abs().median()}
        r.update({f"{c} m": h[c].sum() for c in CLASSES})
        r.update({f"|{c}|": h[f"{c} %"].abs().median() for c in CLASSES})
        r.update({f"w/o {c}": (h["own_m %"] - h[f"{c} %"]).abs().median() for c in CLASSES})
        rows.append(r)
    say(pd.DataFrame(rows).round(3).to_string(index=False))
    say("\ncorrectly delimited single steps by class: tracked, pendulum before W19's cos, INDIP stride/2 (medians, m);"
        " ratios tracked / reference and pendulum / reference (medians); summed tracked - reference (m):")

    def table(h: pd.DataFrame, keys: list[str], sort: bool = False) -> str:
        return h.groupby(keys, sort=sort, observed=True).agg(
            n=("tracked_m", "size"), ref_m=("reference_m", "median"), tracked_m=("tracked_m", "median"),
            pendulum_m=("pendulum_m", "median"),
            tracked_over_ref=("tracked_m", lambda x: float((x / h.loc[x.index, "reference_m"]).median())),
            pendulum_over_ref=("pendulum_m", lambda x: float((x / h.loc[x.index, "reference_m"]).median())),
            sum_err_m=("tracked_m", lambda x: float((x - h.loc[x.index, "reference_m"]).sum())),
            dyaw_deg=("dyaw_deg", "median"), cadence_spm=("cadence_spm", "median")).round(3).to_string()
    say(table(m, ["params", "subject", "class"]))
    say("\nturning single steps by how they are turning (turns_csv: midpoint in an INDIP turn; yaw_turn: W82's"
        " classifier on the step's yaw rate), calibrated:")
    c = m[(m.params == "calibrated") & (m["class"] == "turn step")]
    say(table(c, ["subject", "turns_csv", "yaw_turn"]))
    say("\nsingle steps by |dyaw| bin, calibrated, pooled over the subjects:")
    cc = m[m.params == "calibrated"].assign(dyaw_bin=pd.cut(m.dyaw_deg, [0, 10, 20, 35, 50, 90, 360], right=False))
    say(table(cc, ["dyaw_bin"], sort=True))
    say("\nsingle steps with a length by INDIP step length (m) bin, turning vs straight, calibrated, pooled: is the"
        " over-read the turn's or the short step's?")
    k = m[(m.params == "calibrated") & (m.tracked_m > 0)]
    k = k.assign(turning=k["class"] == "turn step", ref_bin=pd.cut(k.reference_m, [0, 0.2, 0.3, 0.4, 0.5, 0.6, 2]))
    say(table(k, ["turning", "ref_bin"], sort=True))
    for turning, h in k.groupby("turning"):
        slope = np.polyfit(np.log(h.reference_m), np.log(h.pendulum_m), 1)[0]
        say(f"  turning={turning}: {len(h)} steps, log-log slope of the pendulum length on INDIP's {slope:.3f}"
            " (1 = proportional)")
    say("\nsingle steps at the bouts' edges vs inside (calibrated):")
    say(table(m[m.params == "calibrated"], ["subject", "edge"]))
    text = "\n".join(out) + "\n"
    sys.stdout.write(text)
    RESULT.write_text(text)


if __name__ == "__main__":
    main()
