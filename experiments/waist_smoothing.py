"""mobgap's per-second step-length smoothing on `waist-pendulum`, judged by decision W56's adoption rule.

Runs `experiments/waist.py`'s protocols for the calibrated offline `waist-pendulum` (W18/W19/W27 on) with each
``length_smoothing`` mode (``none`` = today's default, ``mobgap``, ``hampel``, ``seconds``; decision W56): the mobgap
subjects (`--external`, from `pdrlearn fetch mobgap`): each Test5 trial -> the other (HA001, MS001), the subject's
Test5 -> its Test11 (daily activities); pooled medians of |per-bout error| vs INDIP `Length` and vs the bouts' own
strides (W25) over the 4 Test5 and 15 Test11 bouts, per-subject Test11 medians, the uncalibrated rows beside; and
the simulator (users 1-3 calibrated on a measured "60 m" walk, scenarios A-D, median |distance error| vs the
strides). Then W56's rule, criterion by criterion, and the leave-one-subject-out pick as a check.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_smoothing.py [--external datasets/external] [--sim-users 3]
Writes experiments/results/waist_smoothing.md.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import pandas as pd

from waist import external_runs, pooled, real, simulated, summarize_sim  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
MODES = ("none", "mobgap", "hampel", "seconds")  # W56: the order that decides among passing modes (after none)
SUBJECTS = ("HA001", "HA002", "MS001")
# W56 adoption rule (written before the runs)
MAX_TEST5_RISE = 0.3  # points, pooled Test5 median (calibrated)
MAX_SUBJECT_RISE = 1.0  # points, each subject's Test11 median vs strides (calibrated)
MAX_SIM_RISE = 0.2  # points, simulator median |distance error|


def label(mode: str) -> str:
    return f"waist-pendulum smoothing={mode}"


def judge(pool: pd.DataFrame, ext: pd.DataFrame, sim: pd.DataFrame | None) -> tuple[list[str], str | None]:
    """W56's criteria (a)-(d) per mode against ``none``: lines to print and the mode adopted (or None)."""
    def cell(test, mode, col, params="calibrated"):
        r = pool[(pool.test == test) & (pool.pipeline == label(mode)) & (pool.params == params)]
        return float(r[col].iloc[0])

    def subj(s, mode):
        r = ext[(ext.subject == s) & ext.test.str.startswith("Test11") & (ext.pipeline == label(mode))
                & (ext.params == "calibrated")]
        return float(r["bout_err_strides_median_pct"].iloc[0])

    def simv(mode):
        if sim is None:
            return float("nan")
        return float(sim.loc[sim.pipeline == label(mode), "dist_err_abs_median_pct"].iloc[0])

    lines, adopted = [], None
    b = {"L": cell("Test11", "none", "bout_err_median_pct"), "S": cell("Test11", "none", "bout_err_strides_median_pct"),
         "T5": cell("Test5", "none", "bout_err_median_pct"), "sim": simv("none")}
    for mode in MODES[1:]:
        L, S = cell("Test11", mode, "bout_err_median_pct"), cell("Test11", mode, "bout_err_strides_median_pct")
        t5, sm = cell("Test5", mode, "bout_err_median_pct"), simv(mode)
        rises = {s: subj(s, mode) - subj(s, "none") for s in SUBJECTS}
        ok = {"a": L < b["L"] and S < b["S"], "b": t5 - b["T5"] <= MAX_TEST5_RISE,
              "c": all(r <= MAX_SUBJECT_RISE for r in rises.values()),
              "d": sim is not None and sm - b["sim"] <= MAX_SIM_RISE}
        lines.append(f"{mode}: (a) Test11 {b['L']:.3f} -> {L:.3f} % vs Length, {b['S']:.3f} -> {S:.3f} % vs strides "
                     f"{'PASS' if ok['a'] else 'FAIL'}; (b) Test5 {b['T5']:.3f} -> {t5:.3f} % "
                     f"{'PASS' if ok['b'] else 'FAIL'}; (c) per subject vs strides "
                     + ", ".join(f"{s} {subj(s, 'none'):.3f} -> {subj(s, mode):.3f}" for s in SUBJECTS)
                     + f" {'PASS' if ok['c'] else 'FAIL'}; (d) simulator {b['sim']:.3f} -> {sm:.3f} % "
                     f"{'PASS' if ok['d'] else 'FAIL'} => {'passes' if all(ok.values()) else 'fails'}")
        if adopted is None and all(ok.values()):
            adopted = mode
    return lines, adopted


def loso(bouts: pd.DataFrame) -> list[str]:
    """Per held-out subject: the mode with the lowest pooled Test11 median vs strides over the other two (check)."""
    b = bouts[(bouts.params == "calibrated") & bouts.test.str.startswith("Test11")]
    out = []
    for s in SUBJECTS:
        o = b[b.subject != s]
        med = {m: float(o.loc[o.pipeline == label(m), "error_strides_pct"].abs().median()) for m in MODES}
        best = min(med, key=med.get)
        out.append(f"held out {s}: the others pick {best} (" + ", ".join(f"{m} {v:.3f}" for m, v in med.items()) + ")")
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 250)
    configs = [(label(m), "waist-pendulum", {"length_smoothing": m}) for m in MODES]
    runs = external_runs(args.external)
    if not runs:
        raise SystemExit(f"{args.external}: no mobgap sessions with a reference; run "
                         f"`pdrlearn fetch mobgap --out {args.external}` first")
    bouts: list = []
    ext = real(args.external, runs, configs, bouts=bouts)
    bdf = pd.DataFrame(bouts)
    pool = pooled(ext, bdf)
    cols = ["test", "pipeline", "params", "bouts", "step_f1", "bout_err_median_pct", "bout_err_strides_median_pct",
            "stride_mae_m"]
    print("pooled over subjects:")
    print(pool[cols].round(3).to_string(index=False))
    per = ext[ext.test.str.startswith("Test11") | ext.test.str.startswith("Test5")][
        ["subject", "test", "pipeline", "params", "bout_err_median_pct", "bout_err_strides_median_pct"]]
    print("\nper subject and run:")
    print(per.round(3).to_string(index=False))
    sim_sum = None
    if args.sim_users > 0:
        sim = simulated(list(range(1, args.sim_users + 1)), configs)
        sim_sum = summarize_sim(sim)
        print(f"\nsimulated users 1..{args.sim_users}:")
        print(sim_sum.round(3).to_string(index=False))
    lines, adopted = judge(pool, ext, sim_sum)
    check = loso(bdf)
    print("\nW56 adoption rule (against none):")
    print("\n".join(lines))
    print("leave-one-subject-out check:")
    print("\n".join(check))
    verdict = f"adopted: {adopted}" if adopted else "no mode passes: length_smoothing stays 'none'"
    print(verdict)
    md = ["# mobgap's step-length smoothing on waist-pendulum (decision W56)", "",
          "Generated by `experiments/waist_smoothing.py`.", "", "## Pooled over subjects", "",
          pool[cols].round(3).to_markdown(index=False), "", "## Per subject and run", "",
          per.round(3).to_markdown(index=False), ""]
    if sim_sum is not None:
        md += [f"## Simulated users 1..{args.sim_users}", "", sim_sum.round(3).to_markdown(index=False), ""]
    md += ["## W56 adoption rule", ""] + [f"- {x}" for x in lines] + ["", "Leave-one-subject-out check:", ""]
    md += [f"- {x}" for x in check] + ["", f"**{verdict}**", ""]
    out = ROOT / "experiments" / "results" / "waist_smoothing.md"
    out.write_text("\n".join(md) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
