"""A learned second stage for the offline waist IC detector, judged leave-one-subject-out (decision W33).

Issue 4's open target: lower-back step F1 >= 0.95 on the mobgap daily-activity recordings (Test11).
The rule route (W16-W32) stops at HA001 / HA002 / MS001 0.938 / 0.809 / 0.848. Here:

- **Stage 1 (candidates, high recall).** Every maximum of seed 003's 2.5 Hz zero-lag vertical
  acceleration (any height, at least ``CAND_MIN_S`` apart, plus the rule detector's own maxima), each with
  its IC by W3's rule (the last local AP maximum within 0.25 s before it). The rule outcomes of the
  default detector (W18/W20/W23/W28) become features, not decisions.
- **Stage 2 (classifier).** Per candidate, local features in seconds-based windows (below); a
  scikit-learn classifier scores it; candidates whose score passes a threshold are kept greedily by score
  with a non-maximum suppression at the shortest step (0.3 s, W16) between kept ICs.
- **Training sets.** (a) simulator only (no real labels): users 4-9 x scenarios A-D x 3 speeds, at
  ``irregular_rate`` 0 and 0.2 (100 Hz); (b) the same simulator runs + the Test11 and Test5 recordings of
  the other two real subjects (leave-one-subject-out: the held-out subject's Test11 and Test5 are never
  seen), with two sample weightings: every group (simulated user, real subject) weighs the same, or the
  simulator and the real recordings weigh half each (MLPClassifier takes no sample weights: its two (b) rows
  are one model); (c) the two other subjects only (no simulator). Real candidates are labelled only inside
  the INDIP bouts (+- 0.25 s) and outside untimed contacts (W9, X2), as they are scored. A candidate matched
  to a reference IC (one-to-one, 0.25 s, closest first) is a step; one within 0.25 s of a reference IC but
  not matched is left out of training (the NMS, not the classifier, decides between two candidates of one
  step); the rest are no step.
- **Threshold** on training data only: out-of-fold scores (groups: simulated users, real subjects), the
  threshold that maximises the pooled F1 after NMS on those folds.
- **Scored** as `experiments/waist_ic_errors.py` / `step_metrics` (real: inside the bouts, untimed
  contacts unscored, 0.25 s; simulator: every contact), on the held-out subject (Test11, Test5) and on
  simulated users 1-3 x A-D x 3 speeds (held out from every training set).

Features (``FEATURES``): rule outcomes (kept by the default detector, among its candidates, accepted by
height + motion gate), the motion-gate value (2 s std of the vertical acceleration / the 0.5 m/s^2
threshold, W4), the filtered vertical maximum (absolute, relative to the kept maxima within 3 s, to the
largest maximum within 0.3 s), the W20 lateral-velocity side strength and the side relation to the
previous / next kept contact, intervals to the neighbouring candidates and kept contacts (s and relative
to the local step period: median kept interval within 3 s), the AP acceleration at the IC (raw, above its
2 s mean W29, its rise over 0.15 s before, the drop to the FC after the vertical maximum), the IC-to-
vertical-maximum delay, the W29 IC's offset, |yaw rate| over +-0.3 s, and the vertical / ML / AP
acceleration std over +-0.5 s.

Models: logistic regression (standardised), HistGradientBoosting (depth 3, 150 trees, learning rate 0.05, no
early stopping: its random validation split made the results depend on the run), an MLP (16 hidden units).

``--export`` trains the shipped option (`InitialContactDetector(learned=True)`, `pdrlearn.waist.learned`):
HistGradientBoosting on the simulator + all three subjects (simulator = real weights), threshold from the
out-of-fold scores, written as JSON trees to pdrlearn/waist/ic_model.json and checked against scikit-learn.

Run: .venv/bin/python experiments/waist_ic_learned.py [--external datasets/external] [--quick] [--export]
Writes experiments/results/waist_ic_learned.md (not with --quick). ``--sim-pelvis realistic`` (decision W52):
the simulated training sessions with the realistic pelvis of decision S27 (the simulator test set keeps the
default), written to waist_ic_learned_realistic_pelvis.md; ``--rules-only`` prints the stage-1 table only.
"""

from __future__ import annotations

import argparse
import logging
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.signal import lowpass
from pdrlearn.sim import simulate
from pdrlearn.steps.evaluate import match_events, untimed_mask
from pdrlearn.waist import learned as L
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import _in_intervals, reference_bouts
from pdrlearn.waist.events import WALK_THRESHOLD_MPS2, InitialContactDetector

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = ("HA001", "HA002", "MS001")
TEST5 = {"HA001": ("HA001_Test5_Trial1", "HA001_Test5_Trial2"), "HA002": ("HA002_Test5_Trial2",),
         "MS001": ("MS001_Test5_Trial1", "MS001_Test5_Trial2")}
TOL = 0.25  # W9 matching tolerance
MIN_STEP_S = 0.3  # W16 shortest step: the NMS radius
SIM_TRAIN_USERS = (4, 5, 6, 7, 8, 9)
SIM_TEST_USERS = (1, 2, 3)
FEATURES = L.FEATURES


@dataclass
class Rec:
    """Candidates of one recording: IC / anchor sample indices, features, labels (1 step, 0 no step,
    -1 not used for training), scoring mask (candidates that are scored), reference and session."""
    name: str
    group: str
    t: np.ndarray
    ic: np.ndarray
    anchor: np.ndarray
    X: np.ndarray
    y: np.ndarray
    scored: np.ndarray
    ref: np.ndarray
    session: object
    real: bool
    rule_ic: np.ndarray
    session_fs: float


def candidates(imu) -> dict:
    """Stage 1: candidate ICs of ``imu`` with their features (``pdrlearn.waist.learned``)."""
    fs = imu.fs
    det = InitialContactDetector(learned=False).detect(imu)  # the W28 rule detector (explicit: W52)
    ap = lowpass(imu.acc_ap, min(20.0, 0.4 * fs), fs, causal=False)  # as InitialContactDetector
    ic, anchor, X = L.candidate_features(imu.acc_v, ap, imu.acc_ml, imu.w_z, fs, det.anchor_,
                                         walk_threshold=WALK_THRESHOLD_MPS2)
    return {"ic": ic, "anchor": anchor, "X": X, "rule_ic": det.ic_}


def _labels(ev_t: np.ndarray, ref: np.ndarray, usable: np.ndarray) -> np.ndarray:
    y = np.full(ev_t.size, -1, dtype=int)
    idx = np.flatnonzero(usable)
    order = idx[np.argsort(ev_t[idx], kind="stable")]
    i_d, _ = match_events(ev_t[order], ref, np.full(ref.size, TOL))
    y[idx] = 0
    if ref.size:
        d = np.min(np.abs(ev_t[idx][:, None] - ref[None, :]), axis=1)
        y[idx[d <= TOL]] = -1
    y[order[i_d]] = 1
    return y


def real_rec(ext: Path, name: str, group: str) -> Rec:
    s = read_session(ext / f"mobgap_{name}")
    imu = waist_imu(s)
    c = candidates(imu)
    t = imu.t[c["ic"]]
    ref = np.sort(s.extras["ics"]["ic_s"].dropna().to_numpy(float))
    b = reference_bouts(s)
    scored = _in_intervals(t, b.start_s.to_numpy(), b.end_s.to_numpy(), TOL) if b is not None else np.ones(t.size, bool)
    scored &= ~_untimed_any(t, s)
    return Rec(name, group, imu.t, c["ic"], c["anchor"], c["X"], _labels(t, ref, scored), scored, ref, s, True,
               c["rule_ic"], imu.fs)


def _untimed_any(t: np.ndarray, s) -> np.ndarray:
    """Candidates inside an untimed-contact interval, away from its timed ends (not labelled)."""
    out = np.zeros(t.size, dtype=bool)
    u = s.extras.get("ics_untimed")
    if u is None or len(u) == 0:
        return out
    for a, b in zip(u["after_s"], u["before_s"], strict=True):
        out |= (t > a + TOL) & (t < b - TOL)
    return out


def sim_rec(scenario: str, user: int, speed: str, irregular: float, pelvis: str = "model") -> Rec:
    s = simulate(scenario, user, speed=speed, rate_hz=100.0, irregular_rate=irregular, pelvis=pelvis)
    imu = waist_imu(s)
    c = candidates(imu)
    t = imu.t[c["ic"]]
    ref = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    scored = np.ones(t.size, dtype=bool)
    return Rec(f"sim u{user} {scenario} {speed} irr{irregular}", f"sim{user}", imu.t, c["ic"], c["anchor"], c["X"],
               _labels(t, ref, scored), scored, ref, s, False, c["rule_ic"], imu.fs)


def evaluate(rec: Rec, keep_t: np.ndarray) -> tuple[int, int, int, list[float]]:
    """TP, detections, references, timing errors (s) as step_metrics scores them."""
    ev = np.sort(keep_t)
    ref = rec.ref
    if rec.real:
        b = reference_bouts(rec.session)
        if b is not None:
            ev = ev[_in_intervals(ev, b.start_s.to_numpy(), b.end_s.to_numpy(), TOL)]
        ev = ev[~untimed_mask(ev, rec.session, TOL)]
    i_d, i_r = match_events(ev, ref, np.full(ref.size, TOL))
    return i_d.size, ev.size, ref.size, list(ev[i_d] - ref[i_r])


def detections(rec: Rec, score: np.ndarray, thr: float) -> np.ndarray:
    return rec.t[rec.ic[L.suppress(rec.ic, score, thr, round(MIN_STEP_S * rec.session_fs))]]


def make_model(kind: str):
    from sklearn.ensemble import HistGradientBoostingClassifier
    from sklearn.linear_model import LogisticRegression
    from sklearn.neural_network import MLPClassifier
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler
    if kind == "logreg":
        return make_pipeline(StandardScaler(), LogisticRegression(C=1.0, max_iter=2000))
    if kind == "hgb":
        return HistGradientBoostingClassifier(max_depth=3, max_iter=150, learning_rate=0.05, early_stopping=False,
                                              random_state=0)
    if kind == "mlp":
        return make_pipeline(StandardScaler(), MLPClassifier(hidden_layer_sizes=(16,), alpha=1e-2, max_iter=1000,
                                                             random_state=0))
    raise ValueError(kind)


WEIGHTS = {"w": "group"}  # "group": every group (simulated user, real subject) weighs the same;
# "domain": the simulator and the real recordings weigh half each (groups equal inside a domain)


def _fit(kind: str, recs: list[Rec]):
    X = np.vstack([r.X[r.y >= 0] for r in recs])
    y = np.concatenate([r.y[r.y >= 0] for r in recs])
    w = np.concatenate([np.full(int((r.y >= 0).sum()), 1.0 / max(1, _n_group(recs, r.group))) for r in recs])
    if WEIGHTS["w"] == "domain" and any(r.real for r in recs):
        dom = np.concatenate([np.full(int((r.y >= 0).sum()), r.real) for r in recs])
        n_groups = {d: len({r.group for r in recs if r.real == d}) for d in (True, False)}
        w = w / np.where(dom, n_groups[True], n_groups[False])
    m = make_model(kind)
    if kind == "hgb":
        m.fit(X, y, sample_weight=w * len(w) / w.sum())
    elif kind == "logreg":
        m.fit(X, y, logisticregression__sample_weight=w * len(w) / w.sum())
    else:
        m.fit(X, y)  # MLPClassifier takes no sample weights
    return m


def _n_group(recs: list[Rec], g: str) -> int:
    """Weight: each group (a simulated user, a real subject) contributes ~ equally per candidate set."""
    return sum(int((r.y >= 0).sum()) for r in recs if r.group == g)


def score_of(model, rec: Rec) -> np.ndarray:
    return model.predict_proba(rec.X)[:, 1] if rec.X.shape[0] else np.zeros(0)


def choose_threshold(kind: str, recs: list[Rec]) -> float:
    """Threshold maximising the pooled F1 of out-of-fold scores (one fold per group) on ``recs``."""
    groups = sorted({r.group for r in recs})
    oof: dict[int, np.ndarray] = {}
    folds = [groups[i::3] for i in range(3)] if len(groups) > 3 else [[g] for g in groups]
    for fold in folds:
        tr = [r for r in recs if r.group not in fold]
        m = _fit(kind, tr)
        for i, r in enumerate(recs):
            if r.group in fold:
                oof[i] = score_of(m, r)
    best, best_f1 = 0.5, -1.0
    real_w = [r for r in recs if r.real]
    for thr in np.round(np.arange(0.05, 0.96, 0.025), 3):
        f1s = []
        for part in ([r for r in recs if not r.real], real_w):
            if not part:
                continue
            tp = det = nref = 0
            for r in part:
                a, b, c, _ = evaluate(r, detections(r, oof[recs.index(r)], thr))
                tp, det, nref = tp + a, det + b, nref + c
            f1s.append(2 * tp / (det + nref) if det + nref else 0.0)
        f1 = float(np.mean(f1s))  # simulator and real count equally
        if f1 > best_f1:
            best, best_f1 = float(thr), f1
    return best


def fmt(tp: int, det: int, nref: int, dt: list[float], digits: int = 3) -> str:
    ms = 1e3 * np.asarray(dt) if dt else np.zeros(1)
    f1 = 2 * tp / (det + nref) if det + nref else float("nan")
    p = tp / det if det else float("nan")
    r = tp / nref if nref else float("nan")
    return f"{f1:.{digits}f} (P {p:.3f}, R {r:.3f}; TP {tp}, det {det}; IC {ms.mean():+.1f} ± {ms.std():.1f} ms)"


def pooled(parts: list[tuple[int, int, int, list[float]]]) -> tuple[int, int, int, list[float]]:
    tp = sum(p[0] for p in parts)
    det = sum(p[1] for p in parts)
    nref = sum(p[2] for p in parts)
    dt = [x for p in parts for x in p[3]]
    return tp, det, nref, dt


def export(sim_train: list[Rec], real: dict, t5: dict, sim_test: list[Rec], pelvis: str = "model") -> list[str]:
    """Train the shipped model on the simulator and all three subjects, convert it to JSON, check that the
    JSON evaluation equals scikit-learn's, and score `InitialContactDetector(learned=True)` (real data:
    in-sample, the leave-one-subject-out rows above are the honest numbers)."""
    train = list(sim_train) + [r for s in SUBJECTS for r in real[s] + t5[s]]
    thr = choose_threshold("hgb", train)
    model = _fit("hgb", train)
    info = {"trained_by": "experiments/waist_ic_learned.py --export", "decision": "W33",
            "estimator": "sklearn HistGradientBoostingClassifier(max_depth=3, max_iter=150, learning_rate=0.05, "
                         "early_stopping=False)",
            "weights": WEIGHTS["w"], "simulator": f"users {SIM_TRAIN_USERS}, A-D x 3 speeds x irregular_rate 0/0.2"
                                                  + ("" if pelvis == "model" else f", pelvis={pelvis} (S27, W52)"),
            "real": "mobgap HA001, HA002, MS001 Test11 + Test5 (inside the INDIP bouts)",
            "threshold": "out-of-fold pooled F1 (mean of simulator and real) on the training data",
            "n_candidates": int(sum((r.y >= 0).sum() for r in train))}
    tec = L.TreeEnsembleClassifier.from_sklearn(model, features=L.FEATURES, threshold=thr, info=info)
    X = np.vstack([r.X for r in train])
    diff = float(np.max(np.abs(tec.predict_proba(X)[:, 1] - model.predict_proba(X)[:, 1])))
    tec.save(L.MODEL_PATH)
    L._CACHE.clear()
    lines = [f"threshold {thr:.3f}, {len(tec.trees)} trees; max |P(JSON) - P(sklearn)| on the training "
             f"candidates {diff:.1e}", "",
             "| data | `InitialContactDetector(learned=True)` (real: in-sample) |", "|---|---|"]
    for s in SUBJECTS:
        for lab, recs in ((f"{s} Test11", real[s]), (f"{s} Test5", t5[s])):
            parts = []
            for r in recs:
                imu = waist_imu(r.session)
                parts.append(evaluate(r, imu.t[InitialContactDetector(learned=True).detect(imu).ic_]))
            lines.append(f"| {lab} | {fmt(*pooled(parts))} |")
    parts = []
    for r in sim_test:
        imu = waist_imu(r.session)
        parts.append(evaluate(r, imu.t[InitialContactDetector(learned=True).detect(imu).ic_]))
    lines.append(f"| simulator users 1-3 (held out) | {fmt(*pooled(parts), digits=4)} |")
    return lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--quick", action="store_true", help="fewer simulated runs (a smoke test)")
    ap.add_argument("--models", default="logreg,hgb,mlp")
    ap.add_argument("--weights", default="domain", choices=("group", "domain"),
                    help="sample weights of the exported model")
    ap.add_argument("--train", default="abc", help="training sets to run: any of a, b, c")
    ap.add_argument("--sim-pelvis", default="model", choices=("model", "realistic"),
                    help="pelvis of the simulated TRAINING sessions (decision W52; the simulator test set keeps "
                         "the default); 'realistic' also scores the rules on users 1-3 with that pelvis")
    ap.add_argument("--rules-only", action="store_true",
                    help="print the stage-1 / rules table only (no simulated training set, no models)")
    ap.add_argument("--export", action="store_true",
                    help="also train the shipped model (HGB, simulator + all three subjects) and write "
                         "pdrlearn/waist/ic_model.json")
    args = ap.parse_args()
    if args.export and args.rules_only:
        raise SystemExit("--export trains the shipped model (W33): run it without --rules-only")
    WEIGHTS["w"] = args.weights
    logging.basicConfig(level=logging.WARNING)
    t0 = time.time()
    ext = args.external
    if not (ext / "mobgap_HA002_Test11_Trial1").is_dir():
        raise SystemExit(f"{ext}: no mobgap sessions; run `pdrlearn fetch mobgap --out {ext}`")
    real = {s: [real_rec(ext, f"{s}_Test11_Trial1", s)] for s in SUBJECTS}
    t5 = {s: [real_rec(ext, n, s) for n in TEST5[s]] for s in SUBJECTS}
    scen = "AB" if args.quick else "ABCD"
    users = SIM_TRAIN_USERS[:2] if args.quick else SIM_TRAIN_USERS
    sim_train = [] if args.rules_only else [
        sim_rec(sc, u, sp, irr, args.sim_pelvis) for u in users for sc in scen for sp in ("slow", "normal", "fast")
        for irr in (0.0, 0.2)]
    sim_test = [sim_rec(sc, u, sp, 0.0) for u in SIM_TEST_USERS[:1 if args.quick else 3] for sc in scen
                for sp in ("slow", "normal", "fast")]
    log_lines = [f"candidates built in {time.time() - t0:.0f} s"]
    # stage 1 recall and the rule detector on the same scoring
    head = ["| data | stage 1 candidates (recall ceiling: every candidate kept) | W28 rule detector (default) |",
            "|---|---|---|"]
    for s in SUBJECTS:
        for lab, recs in ((f"{s} Test11", real[s]), (f"{s} Test5", t5[s])):
            allc = pooled([evaluate(r, r.t[r.ic]) for r in recs])
            rule = pooled([evaluate(r, r.t[r.rule_ic]) for r in recs])
            head.append(f"| {lab} | {fmt(*allc)} | {fmt(*rule)} |")
    rule_sim = pooled([evaluate(r, r.t[r.rule_ic]) for r in sim_test])
    allc_sim = pooled([evaluate(r, r.t[r.ic]) for r in sim_test])
    head.append(f"| simulator users 1-3 | {fmt(*allc_sim, digits=4)} | {fmt(*rule_sim, digits=4)} |")
    if args.sim_pelvis != "model":  # W52: the rules on the same walks with the training sessions' pelvis
        sim_test_p = [sim_rec(sc, u, sp, 0.0, args.sim_pelvis) for u in SIM_TEST_USERS[:1 if args.quick else 3]
                      for sc in scen for sp in ("slow", "normal", "fast")]
        head.append(f"| simulator users 1-3, pelvis={args.sim_pelvis} | "
                    f"{fmt(*pooled([evaluate(r, r.t[r.ic]) for r in sim_test_p]), digits=4)} | "
                    f"{fmt(*pooled([evaluate(r, r.t[r.rule_ic]) for r in sim_test_p]), digits=4)} |")
        for r0, r1 in zip(sim_test, sim_test_p, strict=True):  # the walks where the pelvis changes the rules
            e0, e1 = evaluate(r0, r0.t[r0.rule_ic]), evaluate(r1, r1.t[r1.rule_ic])
            if e0[:3] != e1[:3]:
                _, i_r = match_events(np.sort(r1.t[r1.rule_ic]), r1.ref, np.full(r1.ref.size, TOL))
                ics = r1.session.extras["ics"]
                lost = ics[~np.isin(ics["ic_s"].to_numpy(float), r1.ref[i_r])]
                log_lines.append(f"{r1.name}: rules TP/det/ref {e0[:3]} -> {e1[:3]} (pelvis={args.sim_pelvis}), "
                                 "unmatched contacts: " + ", ".join(f"{x.ic_s:.2f} s {x.foot} {x.kind}"
                                                                    for x in lost.itertuples()))
    rule_pool = pooled([evaluate(r, r.t[r.rule_ic]) for s in SUBJECTS for r in real[s]])
    head.append(f"| Test11 pooled | | {fmt(*rule_pool)} |")
    if args.rules_only:
        print("\n".join(head + [""] + log_lines), flush=True)
        return
    rows = ["| model | training | held out | Test11 | Test5 | threshold |", "|---|---|---|---|---|---|"]
    summary = []
    for kind in args.models.split(","):
        kinds = [k for k in ("a: simulator only", "b: simulator + two real subjects, groups equal",
                             "b: simulator + two real subjects, simulator = real",
                             "c: two real subjects only") if k[0] in args.train]
        for train_kind in kinds:
            WEIGHTS["w"] = "domain" if train_kind.endswith("= real") else "group"
            per_subj, t5_all, sim_parts = [], [], []
            fitted = None
            for s in SUBJECTS:
                train = [] if train_kind.startswith("c") else list(sim_train)
                if train_kind[0] in "bc":
                    train += [r for o in SUBJECTS if o != s for r in real[o] + t5[o]]
                if fitted is None or train_kind[0] in "bc":  # (a): one model for every subject
                    fitted = (_fit(kind, train), choose_threshold(kind, train))
                    model, thr = fitted
                    sim_parts.append(pooled([evaluate(r, detections(r, score_of(model, r), thr)) for r in sim_test]))
                model, thr = fitted
                r11 = pooled([evaluate(r, detections(r, score_of(model, r), thr)) for r in real[s]])
                r5 = pooled([evaluate(r, detections(r, score_of(model, r), thr)) for r in t5[s]])
                per_subj.append(r11)
                t5_all.append(r5)
                rows.append(f"| {kind} | {train_kind} | {s} | {fmt(*r11)} | {fmt(*r5)} | {thr:.3f} |")
            sim = pooled(sim_parts)
            pool = pooled(per_subj)
            p5 = pooled(t5_all)
            f = lambda x: 2 * x[0] / (x[1] + x[2])  # noqa: E731
            summary.append(f"| {kind} | {train_kind} | " + " / ".join(f"{f(x):.3f}" for x in per_subj)
                           + f" | {fmt(*pool)} | {fmt(*p5)} | {fmt(*sim, digits=4)} |")
            print(summary[-1], flush=True)
    rule_t5 = pooled([evaluate(r, r.t[r.rule_ic]) for s in SUBJECTS for r in t5[s]])
    f = lambda x: 2 * x[0] / (x[1] + x[2])  # noqa: E731
    summ_head = ["| model | training | Test11 F1 HA001 / HA002 / MS001 (held out) | Test11 pooled | Test5 (5 walks) "
                 "| simulator users 1-3 (held out; (b): the three LOSO models pooled) |", "|---|---|---|---|---|---|",
                 "| W28 rules (default) | - | "
                 + " / ".join(f"{f(pooled([evaluate(r, r.t[r.rule_ic]) for r in real[s]])):.3f}" for s in SUBJECTS)
                 + f" | {fmt(*rule_pool)} | {fmt(*rule_t5)} | {fmt(*rule_sim, digits=4)} |"]
    title = "# Learned second stage for the offline waist IC detector (W33)"
    if args.sim_pelvis != "model":
        title += f"; simulated training sessions with pelvis={args.sim_pelvis} (W52)"
    out = [title, "",
           "Scored as `step_metrics` (Test11/Test5: inside the INDIP bouts, untimed contacts unscored, 0.25 s); "
           "simulator: users 1-3 x A-D x 3 speeds, 100 Hz, every contact. Leave-one-subject-out: a held-out "
           "subject's Test11 and Test5 are in no training set; thresholds from out-of-fold scores of the "
           "training data.", "", "## Stage 1", ""] + head + ["", "## Summary", ""] + summ_head + summary + [
           "", "## Per held-out subject", ""] + rows + [
           "", f"Run time {time.time() - t0:.0f} s; " + "; ".join(log_lines)]
    WEIGHTS["w"] = args.weights
    if args.export:
        out += ["", "## Shipped model (`pdrlearn/waist/ic_model.json`)", ""] + export(sim_train, real, t5, sim_test,
                                                                                      args.sim_pelvis)
    text = "\n".join(out) + "\n"
    print(text)
    if not args.quick:
        suffix = "" if args.sim_pelvis == "model" else f"_{args.sim_pelvis}_pelvis"
        (ROOT / "experiments" / "results" / f"waist_ic_learned{suffix}.md").write_text(text)


if __name__ == "__main__":
    main()
