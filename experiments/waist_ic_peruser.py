"""A per-user learned IC stage, trained with the user's own labelled contacts (decision W54).

W33's learned second stage (``experiments/waist_ic_learned.py``, imported, not copied) left one subject
out; here each subject's own labelled contacts join the training set, as a user who labels part of their
own recording would:

- **Split.** Each subject's Test11 recording is cut at the gap between two consecutive reference bouts
  (level ``wb``) whose cumulative timed-contact count is closest to half; the cut is the middle of that gap.
  Each half is a contiguous time range of whole bouts.
- **Per-user model** for subject s and half h: W33's HGB (depth 3, 150 trees, rate 0.05), "simulator =
  real" weights, trained on W33's simulator runs (users 4-9 x A-D x 3 speeds x irregular_rate 0 / 0.2), the
  other two subjects' Test11 + Test5, s's own Test5 trials and s's Test11 half h. Own Test5 + own half are
  one group "s" (weight x1: like one whole subject; ``--own-weight`` adds variants, e.g. x3). Threshold:
  W33's out-of-fold F1 on the training data (folds by group), never the test half.
- **Baselines on the same data:** the default rules detector and W33's leave-one-subject-out model (the
  same training set without any own data).
- **Scored** with ``score_steps`` (what ``step_metrics`` uses: inside the half's reference bouts, untimed
  contacts and one detection per same-foot gap unscored, decision 20, 0.25 s) on the held-out half only.
  Test5: each trial scored by the per-user model of half 1 retrained without that trial. Simulator: users
  1-3 x A-D x 3 speeds (held out), scored by every per-user model (W33's scorer, every contact), pooled.

Candidates are built once and cached in /tmp (keyed by the source of pdrlearn/waist and pdrlearn/sim).

Run: PYTHONPATH=$PWD .venv/bin/python experiments/waist_ic_peruser.py [--external datasets/external]
     [--own-weight 1,3] [--quick]
Writes experiments/results/waist_ic_peruser.md (not with --quick).
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import logging
import pickle
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.steps.evaluate import score_steps
from pdrlearn.waist.evaluate import reference_bouts

ROOT = Path(__file__).resolve().parents[1]
import waist_ic_learned as W  # noqa: E402

OUT = ROOT / "experiments" / "results" / "waist_ic_peruser.md"
CACHE = Path("/tmp/pdrlearn_waist_ic_peruser_cache")
OWN = {"group": None, "factor": 1.0}  # the own group's weight factor (see _n_group_own)
_ORIG_N_GROUP = W._n_group


def _n_group_own(recs, g):
    """W33's per-group normaliser, with the own group counted ``OWN["factor"]`` times (x3: three subjects)."""
    n = _ORIG_N_GROUP(recs, g)
    return n / OWN["factor"] if g == OWN["group"] else n


W._n_group = _n_group_own  # W33's _fit looks the name up at call time


def _source_key() -> str:
    h = hashlib.sha1()
    for sub in ("pdrlearn/waist", "pdrlearn/sim", "pdrlearn/signal"):
        for p in sorted((ROOT / sub).rglob("*.py")):
            h.update(p.read_bytes())
    h.update((ROOT / "experiments" / "waist_ic_learned.py").read_bytes())
    return h.hexdigest()[:12]


def build(ext: Path, quick: bool) -> dict:
    CACHE.mkdir(exist_ok=True)
    f = CACHE / f"recs_{_source_key()}_{'quick' if quick else 'full'}.pkl"
    if f.exists():
        return pickle.loads(f.read_bytes())
    real = {s: W.real_rec(ext, f"{s}_Test11_Trial1", s) for s in W.SUBJECTS}
    t5 = {s: [W.real_rec(ext, n, s) for n in W.TEST5[s]] for s in W.SUBJECTS}
    scen = "AB" if quick else "ABCD"
    users = W.SIM_TRAIN_USERS[:2] if quick else W.SIM_TRAIN_USERS
    sim_train = [W.sim_rec(sc, u, sp, irr) for u in users for sc in scen for sp in ("slow", "normal", "fast")
                 for irr in (0.0, 0.2)]
    sim_test = [W.sim_rec(sc, u, sp, 0.0) for u in W.SIM_TEST_USERS[:1 if quick else 3] for sc in scen
                for sp in ("slow", "normal", "fast")]
    d = {"real": real, "t5": t5, "sim_train": sim_train, "sim_test": sim_test}
    f.write_bytes(pickle.dumps(d))
    return d


def split_time(session) -> tuple[float, int, int]:
    """The cut between two consecutive reference bouts closest to half the timed contacts: (time, n1, n2)."""
    b = reference_bouts(session).sort_values("start_s").reset_index(drop=True)
    ref = np.sort(session.extras["ics"]["ic_s"].dropna().to_numpy(float))
    cnt = np.array([np.sum((ref >= a - W.TOL) & (ref <= e + W.TOL)) for a, e in zip(b.start_s, b.end_s, strict=True)])
    cum = np.cumsum(cnt)[:-1]
    k = int(np.argmin(np.abs(cum - ref.size / 2.0)))
    cut = 0.5 * (float(b.end_s[k]) + float(b.start_s[k + 1]))
    return cut, int(np.sum(ref < cut)), int(np.sum(ref >= cut))


def _restrict(df: pd.DataFrame | None, col: str, lo: float, hi: float):
    if df is None:
        return None
    v = df[col].to_numpy(float)
    return df[(v >= lo) & (v < hi)].reset_index(drop=True)


def half_rec(rec: W.Rec, lo: float, hi: float, tag: str) -> W.Rec:
    """``rec`` seen through the time range [lo, hi): labels, reference, bouts and untimed contacts outside
    it removed (its candidates' features are computed on the whole signal, which carries no labels)."""
    ex = dict(rec.session.extras)
    ex["bouts"] = _restrict(ex.get("bouts"), "start_s", lo, hi)
    ex["ics"] = _restrict(ex["ics"].dropna(subset=["ic_s"]), "ic_s", lo, hi)
    if ex.get("ics_untimed") is not None:
        ex["ics_untimed"] = _restrict(ex["ics_untimed"], "after_s", lo, hi)
    ses = dataclasses.replace(rec.session, extras=ex)
    t = rec.t[rec.ic]
    inside = (t >= lo) & (t < hi)
    return dataclasses.replace(rec, name=f"{rec.name} {tag}", session=ses, y=np.where(inside, rec.y, -1),
                               scored=rec.scored & inside, ref=rec.ref[(rec.ref >= lo) & (rec.ref < hi)])


def score_real(rec: W.Rec, keep_t: np.ndarray) -> tuple[int, int, int, list[float]]:
    """TP, scored detections, references, timing errors: ``score_steps`` (step_metrics' scorer) on the
    (half) session of ``rec``."""
    steps = pd.DataFrame({"event_s": np.sort(np.asarray(keep_t, float)), "unit": "waist"})
    sc = score_steps(steps, rec.session, unit="waist")
    return sc["true_positives"], sc["scored_count"], sc["reference_count"], []


def train(recs: list[W.Rec], own: str | None, factor: float):
    OWN["group"], OWN["factor"] = own, factor
    try:
        return W._fit("hgb", recs), W.choose_threshold("hgb", recs)
    finally:
        OWN["group"], OWN["factor"] = None, 1.0


def run(rec: W.Rec, model) -> np.ndarray:
    m, thr = model
    return W.detections(rec, W.score_of(m, rec), thr)


def f1(x) -> float:
    return 2 * x[0] / (x[1] + x[2]) if x[1] + x[2] else float("nan")


def cell(x) -> str:
    return f"{f1(x):.3f} ({x[0]}/{x[1]}/{x[2]})"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--own-weight", default="1,3", help="weights of the own group (1 = like one whole subject)")
    ap.add_argument("--quick", action="store_true", help="fewer simulated runs (a smoke test)")
    args = ap.parse_args()
    logging.basicConfig(level=logging.WARNING)
    W.WEIGHTS["w"] = "domain"  # W33's shipped weighting: simulator = real
    t0 = time.process_time()
    ext = args.external
    if not (ext / "mobgap_HA002_Test11_Trial1").is_dir():
        raise SystemExit(f"{ext}: no mobgap sessions; run `pdrlearn fetch mobgap --out {ext}`")
    d = build(ext, args.quick)
    real, t5, sim_train, sim_test = d["real"], d["t5"], d["sim_train"], d["sim_test"]
    weights = [float(w) for w in args.own_weight.split(",")]
    print(f"candidates ready ({time.process_time() - t0:.0f} s CPU)", flush=True)

    split_lines = ["| subject | cut (s) | timed contacts half 1 / half 2 | bouts half 1 / half 2 |",
                   "|---|---|---|---|"]
    halves = {}
    for s in W.SUBJECTS:
        cut, n1, n2 = split_time(real[s].session)
        r = real[s]
        halves[s] = (half_rec(r, -np.inf, cut, "H1"), half_rec(r, cut, np.inf, "H2"))
        nb = [len(reference_bouts(h.session)) for h in halves[s]]
        split_lines.append(f"| {s} | {cut:.2f} | {n1} / {n2} | {nb[0]} / {nb[1]} |")
    print("\n".join(split_lines), flush=True)

    others = {s: [r for o in W.SUBJECTS if o != s for r in [real[o]] + t5[o]] for s in W.SUBJECTS}
    loso = {}
    for s in W.SUBJECTS:
        loso[s] = train(list(sim_train) + others[s], None, 1.0)
        print(f"LOSO {s} thr {loso[s][1]:.3f} ({time.process_time() - t0:.0f} s CPU)", flush=True)
    res = {}  # (s, test half index) -> {"rules", "loso", "pu<w>"}: (tp, det, nref, [])
    sim_parts = {w: [] for w in weights}
    thr_lines = []
    for s in W.SUBJECTS:
        for h in (0, 1):
            tr_half, te_half = halves[s][h], halves[s][1 - h]
            row = {"rules": score_real(te_half, te_half.t[te_half.rule_ic]),
                   "loso": score_real(te_half, run(te_half, loso[s]))}
            for w in weights:
                model = train(list(sim_train) + others[s] + t5[s] + [tr_half], s, w)
                row[f"pu{w:g}"] = score_real(te_half, run(te_half, model))
                sim_parts[w].append(W.pooled([W.evaluate(r, run(r, model)) for r in sim_test]))
                thr_lines.append(f"{s} train H{h + 1} weight x{w:g}: threshold {model[1]:.3f}")
            res[(s, h)] = row
            print(f"{s} test H{2 - h}: " + " ".join(f"{k} {cell(v)}" for k, v in row.items())
                  + f" ({time.process_time() - t0:.0f} s CPU)", flush=True)

    # Test5: per-user model of half 1 (x1 and every weight) retrained without the scored trial
    t5_rows = []
    t5_pool = {k: [] for k in ["rules", "loso"] + [f"pu{w:g}" for w in weights]}
    for s in W.SUBJECTS:
        for i, trial in enumerate(t5[s]):
            rest = [r for j, r in enumerate(t5[s]) if j != i]
            row = {"rules": score_real(trial, trial.t[trial.rule_ic]), "loso": score_real(trial, run(trial, loso[s]))}
            for w in weights:
                model = train(list(sim_train) + others[s] + rest + [halves[s][0]], s, w)
                row[f"pu{w:g}"] = score_real(trial, run(trial, model))
            for k, v in row.items():
                t5_pool[k].append(v)
            t5_rows.append(f"| {trial.name} | " + " | ".join(cell(v) for v in row.values()) + " |")
            print(t5_rows[-1], f"({time.process_time() - t0:.0f} s CPU)", flush=True)

    keys = ["rules", "loso"] + [f"pu{w:g}" for w in weights]
    names = {"rules": "rules (default)", "loso": "W33 LOSO (no own data)"}
    names.update({f"pu{w:g}": f"per-user x{w:g}" for w in weights})
    head = "| subject, test half | " + " | ".join(names[k] for k in keys) + " |"
    sep = "|---|" + "---|" * len(keys)
    lines = [head, sep]
    for s in W.SUBJECTS:
        for h in (0, 1):
            lines.append(f"| {s} test H{2 - h} (trained on H{h + 1}) | "
                         + " | ".join(cell(res[(s, h)][k]) for k in keys) + " |")
        lines.append(f"| **{s} both halves** | "
                     + " | ".join(cell(W.pooled([res[(s, h)][k] for h in (0, 1)])) for k in keys) + " |")
    lines.append("| **pooled, six halves** | "
                 + " | ".join(cell(W.pooled([res[(s, h)][k] for s in W.SUBJECTS for h in (0, 1)])) for k in keys)
                 + " |")
    t5_head = ["| Test5 trial | " + " | ".join(names[k] for k in keys) + " |", sep]
    t5_rows.append("| **pooled** | " + " | ".join(cell(W.pooled(t5_pool[k])) for k in keys) + " |")
    rule_sim = W.pooled([W.evaluate(r, r.t[r.rule_ic]) for r in sim_test])
    sim_lines = ["| model | simulator users 1-3 (pooled over the models) |", "|---|---|",
                 f"| rules (default) | {W.fmt(*rule_sim, digits=4)} |"]
    sim_lines += [f"| per-user x{w:g} (six models) | {W.fmt(*W.pooled(sim_parts[w]), digits=4)} |" for w in weights]

    verdict = []
    for w in weights:
        k = f"pu{w:g}"
        pool = f1(W.pooled([res[(s, h)][k] for s in W.SUBJECTS for h in (0, 1)]))
        subj = all(f1(W.pooled([res[(s, h)][k] for h in (0, 1)]))
                   >= f1(W.pooled([res[(s, h)]["rules"] for h in (0, 1)])) for s in W.SUBJECTS)
        t5ok = all(abs(f1(v) - 1.0) < 1e-12 for v in t5_pool[k])
        simf = f1(W.pooled(sim_parts[w]))
        verdict.append(f"- x{w:g}: (1) pooled {pool:.3f} >= 0.95: {pool >= 0.95}; (2) every subject >= rules: "
                       f"{subj}; (3) every Test5 trial 1.000: {t5ok}; (4) simulator {simf:.4f} >= 0.999: "
                       f"{simf >= 0.999}; all: {pool >= 0.95 and subj and t5ok and simf >= 0.999}")
    out = ["# Per-user learned IC stage (W54)", "",
           "Cells: F1 (TP / scored detections / reference contacts), `score_steps` on the held-out half "
           "(inside its reference bouts, untimed contacts and one detection per same-foot gap unscored, "
           "0.25 s). Per-user models: W33's HGB (simulator = real weights) + the other two subjects' Test11 + "
           "Test5 + own Test5 + own Test11 half (own group weight x1 = like one whole subject). W33 LOSO: the "
           "same without own data.", "", "## Split", ""] + split_lines + [
           "", "## Test11, held-out halves", ""] + lines + [
           "", "## Test5 (per-user: model of half 1 retrained without the scored trial)", ""] + t5_head + t5_rows + [
           "", "## Simulator", ""] + sim_lines + ["", "## Adoption rule (W54; judged on x1)", ""] + verdict + [
           "", "Thresholds: " + "; ".join(thr_lines), "", f"CPU time {time.process_time() - t0:.0f} s"]
    text = "\n".join(out) + "\n"
    print(text)
    if not args.quick:
        OUT.write_text(text)


if __name__ == "__main__":
    main()
