"""Decisions W501-W503 (session 44, issue 8): why a per-user calibration makes the real straight walks worse, and
other estimators of the pendulum gain K on the same calibration walks.

The calibration (``pdrlearn.waist.calibration.calibrate``, waist-pendulum) fits seed 003 eq. 1,
``d = K 2 sqrt(2 L h - h^2) + F``, on the detected steps of each reference walking bout of the calibration recordings
(``bouts.csv``, INDIP ``Length``). Walks of one speed give a K-only fit with F kept at 0 (decision W8), so
``K = sum D / sum c g`` (W21). This script prints, per calibration, the fit (K, F, how, steps, strides, the per-stride
gains of W48 and the gain of the bout's interior steps), and per reference bout the error of every arm.

Arms (all on the same calibration walks; ``experiments/waist.py``'s external protocol unchanged: per subject the
other Test5 trial for Test5, all its Test5 trials for Test11, never the tested recording):

- ``defaults``: no calibration (meta.json defaults, K0 = 4.587/4, W46; on the simulator K0 in place of the fit);
- ``calibrated``: the current fit;
- ``shrunk``: decision W48's precision-weighted mean of K_cal and K0 (its own per-stride se, tau from the other
  subjects' Test5 walks; ``calibrate --shrink``), i.e. shrunk toward the defaults by the number of calibration
  strides and their scatter;
- ``stride-median``: a robust fit, the median of the walks' per-stride gains (W48's ``stride_gains``) instead of
  their ratio of sums;
- ``pretest``: K0 unless the walk's K differs from it by more than 1.96 se (the calibration shows the user is not
  the population at the 5 % level), else K_cal.

The simulator (users with known step length, ``pdrlearn.sim``): ``experiments/waist.py``'s protocol (a "60 m" walk)
and the same with a Test5-like "5 m" calibration walk (seeds 1-5). The adoption rule is decision W502 (written
before measuring).

Run: .venv/bin/python experiments/waist_calibration_s44.py [--external datasets/external] [--sim-users 3]
Writes experiments/results/waist_calibration_s44.md.
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import waist as W  # noqa: E402  (experiments/waist.py: the same runs, metrics and simulator protocol)
import waist_k_shrinkage as S  # noqa: E402  (W48's evidence and leave-one-subject-out tau)
from pdrlearn.waist import _kernels as K  # noqa: E402
from pdrlearn.waist.calibration import calibration_walks  # noqa: E402
from pdrlearn.waist.params import DEFAULT_K, TAU_K  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PENDULUM = [W.CONFIGS[0]]  # waist-pendulum, default options
ARMS = ("calibrated", "shrunk", "stride-median", "pretest")
Z_PRETEST = 1.96  # two-sided 5 % normal quantile
SUBJECT_SLACK = 0.5  # W502 (3)
SHORT_SEEDS = (1, 2, 3, 4, 5)
SHORT_M = 5.0  # about a Test5 walk (4.1-5.0 m of INDIP Length)


def stride_gains(params, sessions, distances) -> np.ndarray:
    """W48's per-stride gains of every calibration walk, pooled (F as fitted)."""
    out = []
    for i, s in enumerate(sessions):
        d = None if distances is None else distances[i]
        for w in calibration_walks(s, "waist-pendulum", distance_m=d, params=params):
            out.append(K.stride_gains(w.distance_m, w.g, w.factors(), params.f_m))
    x = np.concatenate(out) if out else np.zeros(0)
    return x[np.isfinite(x)]


def arm_adjust(arm: str, tau_of=None):
    """``adjust`` for :func:`W.real` / :func:`W.simulated`: the gain of ``arm`` from the calibrated params."""
    def adjust(params, sessions, distances):
        rec = params.k_shrinkage or {}
        k_cal, se = rec.get("k_cal", params.k), rec.get("se")
        k_only = params.f_m == 0  # every fit here is K only (walks of one speed, W8)
        if arm == "calibrated" or not k_only:
            return params
        if arm == "defaults":  # the simulator's users: K0 in place of the fit (F = 0 both)
            k = DEFAULT_K
        elif arm == "shrunk":
            tau = tau_of(sessions) if tau_of is not None else TAU_K
            k = k_cal if se is None else K.shrink_gain(k_cal, se, DEFAULT_K, tau)
        elif arm == "stride-median":
            g = stride_gains(params, sessions, distances)
            k = float(np.median(g)) if g.size else k_cal
        elif arm == "pretest":
            k = k_cal if se is None or abs(k_cal - DEFAULT_K) > Z_PRETEST * se else DEFAULT_K
        else:
            raise ValueError(arm)
        return dataclasses.replace(params, k=float(k))
    return adjust


def fit_table(ext: Path, runs) -> pd.DataFrame:
    """Per calibration: K, F, the fit, steps, strides and gains (the finding, W501)."""
    rows = []
    fits: list = []
    W.real(ext, runs, PENDULUM, defaults=False, fits=fits)
    for (cal_names, test), p in zip(runs, fits, strict=True):
        from pdrlearn.io import read_session

        sess = [read_session(ext / n) for n in cal_names]
        walks = [w for s in sess for w in calibration_walks(s, "waist-pendulum", params=p)]
        g = np.concatenate([w.g for w in walks])
        c = np.concatenate([w.factors() for w in walks])
        inner = sum(w.distance_m * (len(w.g) - 2) / len(w.g) for w in walks) / sum(float(np.sum(w.g[1:-1]))
                                                                                   for w in walks)
        sg = stride_gains(p, sess, None)
        rec = p.k_shrinkage
        rows.append({"test": test.replace("mobgap_", ""), "calibrated_on": "+".join(n.split("_", 2)[2]
                                                                                    for n in cal_names),
                     "walks": len(walks), "steps": len(g), "turn_steps": int(np.sum(c < 0.95)),
                     "K": p.k, "F_m": p.f_m, "fit": "K only" if p.f_m == 0 else "K and F",
                     "se": rec["se"], "strides": rec["n_strides"], "stride_K_min": sg.min(), "stride_K_max": sg.max(),
                     "K_interior_steps": inner, "z_vs_K0": (p.k - DEFAULT_K) / rec["se"] if rec["se"] else np.nan})
    return pd.DataFrame(rows)


def run_real(ext: Path, runs, tau_loso: dict) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Per-bout errors of every arm (one column each) and the runs' K per arm."""
    subj_of = {}
    for cal_names, _t in runs:
        for n in cal_names:
            subj_of[n] = n.split("_")[1]

    def tau_of(sessions):
        return tau_loso[subj_of[sessions[0].name]][0]

    per_arm, ks = {}, {}
    for arm in ARMS:
        b: list = []
        fits: list = []
        W.real(ext, runs, PENDULUM, bouts=b, defaults=(arm == "calibrated"), fits=fits,
               adjust=arm_adjust(arm, tau_of))
        per_arm[arm] = pd.DataFrame(b)
        ks[arm] = [p.k for p in fits]
    key = ["subject", "test", "start_s"]
    base = per_arm["calibrated"]
    out = base[base.params == "defaults"][key + ["reference_m", "n_steps", "n_reference_steps", "error_pct"]]
    out = out.rename(columns={"error_pct": "defaults"})
    for arm in ARMS:
        a = per_arm[arm]
        out = out.merge(a[a.params == "calibrated"][key + ["error_pct"]].rename(columns={"error_pct": arm}), on=key)
    kdf = pd.DataFrame({"test": [t.replace("mobgap_", "") for _c, t in runs], **{a: ks[a] for a in ARMS}})
    return out, kdf


def medians(bouts: pd.DataFrame, arms) -> tuple[pd.DataFrame, pd.DataFrame]:
    b = bouts.assign(kind=bouts["test"].str.split("_").str[0])
    pooled = b.groupby("kind")[list(arms)].agg(lambda x: float(np.median(np.abs(x))))
    pooled.insert(0, "bouts", b.groupby("kind").size())
    subj = b.groupby(["kind", "subject"])[list(arms)].agg(lambda x: float(np.median(np.abs(x))))
    subj.insert(0, "bouts", b.groupby(["kind", "subject"]).size())
    return pooled.reset_index(), subj.reset_index()


def run_sim(users: list[int]) -> pd.DataFrame:
    """Median |distance error| (%) per arm: the standard protocol and the short calibration walks."""
    rows = []
    for arm in ("defaults",) + ARMS:
        sim = W.simulated(users, PENDULUM, adjust=arm_adjust(arm))
        std = float(W.summarize_sim(sim).dist_err_abs_median_pct.iloc[0])
        short = pd.concat([W.simulated(users, PENDULUM, adjust=arm_adjust(arm), cal_length_m=SHORT_M, cal_seed=sd)
                           for sd in SHORT_SEEDS])
        rows.append({"arm": arm, "sim_60m_median_abs_pct": std,
                     "sim_5m_median_abs_pct": float(np.median(np.abs(short.dist_err_pct))),
                     "sim_5m_p90_abs_pct": float(np.percentile(np.abs(short.dist_err_pct), 90)),
                     "sim_5m_tracks": len(short)})
    return pd.DataFrame(rows)


def verdict(pooled: pd.DataFrame, subj: pd.DataFrame, sim: pd.DataFrame, arm: str) -> dict[str, bool]:
    """W502's rule for ``arm`` against ``calibrated`` (values rounded to 3 decimals as printed)."""
    p = pooled.set_index("kind")
    r = {f"(1) Test5 pooled falls ({p.loc['Test5', arm]:.3f} vs {p.loc['Test5', 'calibrated']:.3f} %)":
         round(p.loc["Test5", arm], 3) < round(p.loc["Test5", "calibrated"], 3),
         f"(2) Test11 pooled falls ({p.loc['Test11', arm]:.3f} vs {p.loc['Test11', 'calibrated']:.3f} %)":
         round(p.loc["Test11", arm], 3) < round(p.loc["Test11", "calibrated"], 3)}
    worst = float((subj[arm] - subj["calibrated"]).max())
    r[f"(3) no subject worse by > {SUBJECT_SLACK} points (worst {worst:+.3f})"] = round(worst, 3) <= SUBJECT_SLACK
    s = sim.set_index("arm")
    r[f"(4) simulator not higher ({s.loc[arm, 'sim_60m_median_abs_pct']:.3f} vs "
      f"{s.loc['calibrated', 'sim_60m_median_abs_pct']:.3f} %)"] = (
        round(s.loc[arm, "sim_60m_median_abs_pct"], 3) <= round(s.loc["calibrated", "sim_60m_median_abs_pct"], 3))
    return r


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 220)
    runs = W.external_runs(args.external)
    if not runs:
        raise SystemExit(f"{args.external}: no mobgap sessions with a reference; run `make external` first")
    walks = {t.split("_")[1]: cal for cal, t in runs if "Test11" in t}
    ev = {s: S.evidence(args.external, names) for s, names in walks.items()}
    tau_loso = {s: S.taus(ev, s) for s in ev}
    fits = fit_table(args.external, runs)
    bouts, kdf = run_real(args.external, runs, tau_loso)
    arms = ("defaults",) + ARMS
    pooled, subj = medians(bouts, arms)
    sim = run_sim(list(range(1, args.sim_users + 1)))
    lines = ["# W501-W503: the per-user calibration of the pendulum gain on the real straight walks", "",
             "Generated by `experiments/waist_calibration_s44.py` (docstring: arms and protocol; rule: W502).", "",
             "## The calibrations (W501)", "", fits.round(4).to_markdown(index=False), "",
             "## K per run and arm", "", kdf.round(4).to_markdown(index=False), "",
             "## Per reference bout: signed error vs INDIP `Length` (%)", "", bouts.round(3).to_markdown(index=False),
             "", "## Median |bout error| (%), pooled", "", pooled.round(3).to_markdown(index=False), "",
             "## Median |bout error| (%) per subject", "", subj.round(3).to_markdown(index=False), "",
             f"## Simulator (users 1-{args.sim_users}): median |distance error| (%), the 60 m calibration of "
             f"`experiments/waist.py` and {SHORT_M:g} m calibration walks (seeds {SHORT_SEEDS[0]}-{SHORT_SEEDS[-1]})",
             "", sim.round(3).to_markdown(index=False), "", "## W502's rule", ""]
    for arm in ARMS[1:]:
        v = verdict(pooled, subj, sim, arm)
        lines += [f"- **{arm}**: {'adopt' if all(v.values()) else 'not adopted'}"]
        lines += [f"  - {k}: {'yes' if ok else 'NO'}" for k, ok in v.items()]
    text = "\n".join(lines) + "\n"
    print(text)
    out = ROOT / "experiments" / "results" / "waist_calibration_s44.md"
    out.write_text(text)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
