"""Decisions W494 / W495 (session 43, issue 8, trial T1 finding F2): the lower-back pipelines' walking bouts against
INDIP's WBs on the real mobgap recordings, mobgap's way (W493: ``pdrlearn.track.wb_scores``, the rows `track`
writes as wb_scores.csv), and the bout edges against INDIP's.

Per recording with INDIP WBs, ``--bout-rule mobgap``: waist-pendulum and waist-pll uncalibrated (meta.json defaults)
and waist-pendulum calibrated by experiments/waist.py's ``external_runs`` (a Test5 trial on the other, Test11 on both
Test5 trials; never on the recording tested). Pooled: WB precision / recall / F1 from the summed TP / FP / FN at
mobgap's 0.8, the median signed and |relative error| of cadence, stride length and speed over the TP WBs, and the
same medians over every WB paired with the bout overlapping it most (T1's wbcmp.py pairing). W495: the bouts' edge
differences (start_diff_s, end_diff_s; in s and in the bout's median step interval) and the WB scores of the
candidate that starts each detected bout at its second contact and ends it at its last-but-one (measured as a local
function first, then made `--bout-rule mobgap-indip`, whose rows these now are).

Run: PYTHONPATH=. .venv/bin/python experiments/wb_scores_w494.py [--external datasets/external]
(printed output: experiments/results/wb_scores_w494.txt)
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.track.bouts import bout_rule, detected_bouts, track_bouts  # noqa: E402
from pdrlearn.track.evaluate import track_summary  # noqa: E402
from pdrlearn.track.wb_scores import DMOS, wb_evaluation, wb_score_summary  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.evaluate import reference_wbs  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402
from waist import external_runs  # noqa: E402

RULE = bout_rule(preset="mobgap")
TRIMMED = bout_rule(preset="mobgap-indip")  # decision W495: each bout from its second contact to its last-but-one


def runs(ext: Path) -> list[tuple[str, str, list[str] | None, str]]:
    """(label, pipeline, calibration recordings or None, test recording) of every recording with INDIP WBs."""
    tests = [d.name for d in sorted(ext.glob("mobgap_*_Test*_Trial*"))
             if (d / "bouts.csv").is_file() and reference_wbs(read_session(d)) is not None]
    out = [(f"{p} uncalibrated", p, None, t) for p in ("waist-pendulum", "waist-pll") for t in tests]
    out += [("waist-pendulum calibrated", "waist-pendulum", cal, t) for cal, t in external_runs(ext) if t in tests]
    return out


def one(ext: Path, pipeline: str, cal: list[str] | None, test: str) -> tuple[pd.DataFrame, pd.DataFrame, dict]:
    """(wb_scores rows, the W495 candidate's rows, summary) of one tracked recording, as `track` computes them."""
    session = read_session(ext / test)
    params = None
    if cal:
        base, _ = resolve_params(read_session(ext / cal[0]), None)
        params = calibrate([read_session(ext / n) for n in cal], pipeline, params=base)
    res = get_pipeline(pipeline)(session, params=params)
    bouts = track_bouts(res, session, RULE)
    summary = track_summary(res, session, pipeline=pipeline, bouts=RULE, bout_table=bouts)
    table = pd.DataFrame(res.info["wb_scores"])
    trim, _ = wb_evaluation(detected_bouts(res.steps, TRIMMED), reference_wbs(session))  # W495's option
    step_s = float(np.median(np.diff(np.sort(res.steps["start_s"].to_numpy(float))))) if len(res.steps) > 1 else 1.0
    table["step_s"] = step_s
    return table, trim, summary


def pooled(table: pd.DataFrame) -> dict:
    """The pooled keys of :func:`wb_score_summary` over all recordings, and the T1-pairing medians."""
    keys = wb_score_summary(table)
    out = {"WB": keys["n_wb_reference"], "TP": keys["n_wb_tp"], "FP": keys["n_wb_fp"], "FN": keys["n_wb_fn"],
           "P": keys["wb_precision"], "R": keys["wb_recall"], "F1": keys["wb_f1"]}
    paired = table[table["match"].isin(["tp", "fn"]) & table["bout"].notna()]
    out["paired"] = len(paired)
    for name, _, _ in DMOS:
        out[f"{name} TP med/|med| %"] = (f"{keys[f'wb_{name}_error_median_signed_pct']:+.1f} / "
                                         f"{keys[f'wb_{name}_error_median_pct']:.1f}"
                                         if keys[f"wb_{name}_error_median_pct"] is not None else "-")
        e = paired[f"{name}_error_pct"].dropna()
        out[f"{name} paired med/|med| %"] = f"{e.median():+.1f} / {e.abs().median():.1f}"
    return out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ext = ap.parse_args(argv).external
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 250)
    pd.set_option("display.max_columns", 40)
    pd.set_option("display.max_rows", 200)
    tables, trims, per = [], [], []
    for label, pipeline, cal, test in runs(ext):
        t, trim, s = one(ext, pipeline, cal, test)
        name = test.removeprefix("mobgap_")
        tables.append(t.assign(config=label, recording=name))
        trims.append(trim.assign(config=label, recording=name))
        per.append({"config": label, "recording": name, "calibrated_on": "+".join(c.removeprefix("mobgap_")
                                                                                   for c in cal) if cal else "-",
                    **{k: s.get(k) for k in ("n_wb_reference", "n_wb_tp", "n_wb_fp", "n_wb_fn", "wb_f1",
                                             "wb_cadence_error_median_pct", "wb_stride_length_error_median_pct",
                                             "wb_speed_error_median_pct")}})
    all_rows, all_trim = pd.concat(tables, ignore_index=True), pd.concat(trims, ignore_index=True)
    print("Per recording (--bout-rule mobgap; W493's summary keys):")
    print(pd.DataFrame(per).round(3).to_string(index=False))
    print("\nEvery WB with the bout overlapping it most (wb_scores.csv rows, tp / fn):")
    cols = ["config", "recording", "match", "ref_wb", "ref_start_s", "ref_end_s", "bout_start_s", "bout_end_s",
            "overlap_ref_frac", "overlap_bout_frac", "start_diff_s", "end_diff_s", "cadence_error_pct",
            "stride_length_error_pct", "speed_error_pct"]
    print(all_rows[all_rows["match"] != "fp"][cols].round(3).to_string(index=False))
    print("\nPooled over the recordings (W494): WB detection at overlap 0.8 and per-WB DMO errors (detected - INDIP) / "
          "INDIP; TP: mobgap's matched WBs; paired: every WB with an overlapping bout (T1's pairing)")
    summary = [{"config": c, **pooled(g)} for c, g in all_rows.groupby("config", sort=False)]
    print(pd.DataFrame(summary).round(3).to_string(index=False))
    for thr in (0.51,):  # the same matching at mobgap's lowest admissible threshold, from the table's own bouts
        print(f"\nWB detection at overlap {thr} (mobgap's bound: above 0.5):")
        alt = []
        for c, g in all_rows.groupby("config", sort=False):
            tp = int(((g["match"] != "fp") & (g["overlap_ref_frac"] >= thr) & (g["overlap_bout_frac"] >= thr)).sum())
            n_ref = int((g["match"] != "fp").sum())
            n_det = int(g.loc[g["bout"].notna()].groupby("recording")["bout"].nunique().sum())
            p, r = tp / n_det, tp / n_ref
            alt.append({"config": c, "WB": n_ref, "bouts": n_det, "TP": tp, "P": p, "R": r, "F1": 2 * p * r / (p + r)})
        print(pd.DataFrame(alt).round(3).to_string(index=False))
    print("\nW495: bout edges vs INDIP's WB (rows with an overlapping bout): median start_diff_s / end_diff_s, "
          "in s and in step intervals (the recording's median contact interval)")
    edge = []
    for c, g in all_rows[all_rows["match"].isin(["tp", "fn"]) & all_rows["bout"].notna()].groupby("config",
                                                                                                  sort=False):
        edge.append({"config": c, "n": len(g), "start_diff_s": g["start_diff_s"].median(),
                     "end_diff_s": g["end_diff_s"].median(),
                     "start_diff_steps": (g["start_diff_s"] / g["step_s"]).median(),
                     "end_diff_steps": (g["end_diff_s"] / g["step_s"]).median(),
                     "start earlier (n)": int((g["start_diff_s"] < 0).sum()),
                     "end later (n)": int((g["end_diff_s"] > 0).sum())})
    print(pd.DataFrame(edge).round(3).to_string(index=False))
    print("\nW495 candidate (each bout from its second contact to its last-but-one), pooled as above:")
    print(pd.DataFrame([{"config": c, **pooled(g)} for c, g in all_trim.groupby("config", sort=False)])
          .round(3).to_string(index=False))


if __name__ == "__main__":
    main()
