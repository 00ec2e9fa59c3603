"""Step characterization: thesis Tables 27, 28, 33 on simulated users + the real-data terrain study.

Simulated part (thesis protocol, ch. 6): per user and task, calibration exercises of that task
(pdrlearn.sim "terrain" / "direction" / "length") are the training data (10-fold CV inside
:func:`pdrlearn.classify.train_user`, which also holds out validation data for the NN's early stopping and
learns the unit-fusion weights on out-of-fold predictions); other walks of the same exercise (other
seeds) are the test set. Test accuracy per class x method x unit is pooled over users and printed beside
the thesis' numbers.

Real part: the gaitmap foot recordings (terrain label per stride, 'unclear' skipped): 10-fold CV over all
four recordings, train on the left foot -> test on the right foot, and a continuous stride-length
regression on the level-walk strides with mocap reference lengths.

Usage::

    .venv/bin/python experiments/characterization.py            # 2 users, thesis-sized protocol
    .venv/bin/python experiments/characterization.py --quick    # 1 user, fewer walks (smoke run)
    .venv/bin/python experiments/characterization.py --boundaries rest   # rest-to-rest step windows
    .venv/bin/python experiments/characterization.py --boundaries rest --ensemble   # + the nn/svm/dtw vote

Writes experiments/results/characterization.md and .csv (``--boundaries rest``: characterization_rest.*).
A partial run (``--users``, ``--train-walks``, ``--test-walks``, ``--cv``, ``--seed``, ``--quick`` or ``--no-real``
not at the default) writes ``characterization*_partial.*`` instead (steps decision 67).
The real-data CV is printed for both step-window boundary modes (decision 13, docs/decisions/features.md).
"""

from __future__ import annotations

import argparse
import logging
import time
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]

from partial import partial_note, partial_options, result_name  # noqa: E402
from pdrlearn.classify import evaluate_model, train_user  # noqa: E402
from pdrlearn.classify.evaluation import ROW_ORDER  # noqa: E402
from pdrlearn.classify.thesis import THESIS_ACCURACY, THESIS_TABLE  # noqa: E402
from pdrlearn.classify.training import DEFAULT_METHODS  # noqa: E402

log = logging.getLogger("characterization")

#: Thesis results, accuracy % per class and unit: thesis Table 27 (terrain), Table 28 (direction),
#: Table 33 (length). Keys: (method, unit) -> {class: %}. "fusion" = Heuristic Fusion.
THESIS = THESIS_ACCURACY  # thesis Tables 27, 28, 33: the package's copy (decision C144)
# The thesis' "SVM/NN Fusion" rows are one model on both units' features (ch. 6.1.1.1, 6.1.1.2, 6.2.1, 6.3.1):
# our unit "combined" (decision C22), keyed so above; "fused" (soft vote, C7) has no thesis row (decision C90).
#: decision C90: the protocol difference every table beside the thesis states
PROTOCOL_NOTE = (
    "Protocol difference (decision C90): the thesis tested terrain on path D (stairs up, down, up; ch. 6.1.1) and "
    "direction and length on path B with two curves (ch. 6.2.1, 6.3.1); here the test walks are held-out repeats "
    "of the calibration exercises, straight walks whose only turns are short turnaround steps. On the thesis "
    "walks the length class is markedly worse (decision C88: the strides turning 15 deg or more), so these "
    "figures are an upper bound for walking with turns.")
TABLE_NO = THESIS_TABLE
ROWS = ROW_ORDER  # thesis Tables 27, 28, 33 row order
#: Training / test set sizes of the thesis (steps): terrain 970 + 170 validation / 540 test (ch. 6.1.1),
#: direction 450 + 100 / 100 (ch. 6.2.1), length 855 + 171 / 114 (ch. 6.3.1). The thesis adds that a
#: training set 5 (terrain) to 10 (length) times smaller gives similar results (ch. 6.1.3, 6.3.3); a
#: user's calibration is one exercise per task (~75 / 50 / 90 steps, the simulator's exercises), so we train on
#: ``--train-walks`` exercises and test on ``--test-walks`` other ones.
THESIS_SIZES = {"terrain": (970, 170, 540), "direction": (450, 100, 100), "length": (855, 171, 114)}


def pooled_confusions(results: list[dict], task: str) -> dict[tuple[str, str], np.ndarray]:
    """Sum the confusion matrices of every (method, unit) over users."""
    out: dict[tuple[str, str], np.ndarray] = {}
    for r in results:
        t = r["tasks"].get(task)
        if t is None:
            continue
        for m, d in t["methods"].items():
            for u, res in d["units"].items():
                cm = np.asarray(res["confusion"], dtype=float)
                out[(m, u)] = out.get((m, u), 0) + cm
    return out


def per_class(cm: np.ndarray, classes: list[str]) -> dict[str, float]:
    rows = cm.sum(axis=1)
    return {c: (100 * cm[i, i] / rows[i] if rows[i] else float("nan")) for i, c in enumerate(classes)}


def simulated_study(users: list[int], train_walks: int, test_walks: int, cv: int, seed: int,
                    boundaries: str = "given", methods: list[str] | None = None):
    from pdrlearn.features import TASK_CLASSES
    from pdrlearn.sim.simulate import simulate

    rows, md, timing = [], [], {}
    results: dict[str, list[dict]] = {t: [] for t in TASK_CLASSES}
    cv_results: dict[str, list] = {t: [] for t in TASK_CLASSES}
    chosen: dict[str, list] = {t: [] for t in TASK_CLASSES}
    latency: dict[str, dict] = {t: {} for t in TASK_CLASSES}
    for user in users:
        t_user = 0.0
        for task in TASK_CLASSES:
            train = [simulate(task, user_seed=user, seed=k) for k in range(train_walks)]
            test = [simulate(task, user_seed=user, seed=1000 + k) for k in range(test_walks)]
            t0 = time.perf_counter()
            # every unit named: the svm/nn soft votes are trained beside the combined models, which replace them
            # by default (decision C23), so that both are compared
            model = train_user(train, tasks=[task], cv=cv, seed=seed, user=f"u{user}", boundaries=boundaries,
                               methods=methods, units=["foot", "waist", "fused", "combined"])
            dt = time.perf_counter() - t0
            t_user += dt
            tm = model.tasks[task]
            log.info(
                "user %d %s: %d training steps, trained in %.1f s, chosen %s",
                user,
                task,
                tm.n_steps,
                dt,
                tm.chosen,
            )
            res = evaluate_model(model, test, latency_steps=20)
            results[task].append(res)
            cv_results[task].append(tm)
            det = res["tasks"][task].get("detected") or {}  # C49: what track --model and the runtime get (C54)
            chosen[task].append((tm.chosen, res["tasks"][task]["accuracy"], res["tasks"][task]["n_steps"], tm.n_steps,
                                 det.get("accuracy", float("nan")), det.get("n_steps", 0)))
            for m, d in res["tasks"][task]["methods"].items():
                for u, r in d["units"].items():
                    latency[task].setdefault((m, u), []).append(r["latency_ms"])
        timing[user] = t_user
    for task, classes in TASK_CLASSES.items():
        classes = list(classes)
        test_cm = pooled_confusions(results[task], task)
        cv_cm: dict = {}
        for tm in cv_results[task]:
            for m, per in tm.cv.items():
                for u, r in per.items():
                    cv_cm[(m, u)] = cv_cm.get((m, u), 0) + np.asarray(r["confusion"], dtype=float)
        head = ["method", "unit"] + [f"{c} ours (thesis)" for c in classes] + ["all % test", "all % CV", "ms/step"]
        n_test = sum(c[2] for c in chosen[task])
        n_train = sum(c[3] for c in chosen[task])
        lines = [
            f"### {task} (thesis Table {TABLE_NO[task]}): {len(users)} user(s), {n_train} training steps, "
            f"{n_test} test steps (thesis {THESIS_SIZES[task][0]} + {THESIS_SIZES[task][1]} / "
            f"{THESIS_SIZES[task][2]})",
            "",
            "Our heuristic / fusion rows use the thesis' rule tables and weights with cut points learned per user "
            "(the default `thresholds=\"joint\"`, features decision 8); the thesis rows use its printed cut points.",
            "",
            "| " + " | ".join(head) + " |",
            "|" + "---|" * len(head),
        ]
        for key in ROWS:
            if key not in test_cm:
                continue
            pc = per_class(test_cm[key], classes)
            cvc = cv_cm.get(key)
            all_test = 100 * np.trace(test_cm[key]) / test_cm[key].sum()
            all_cv = 100 * np.trace(cvc) / cvc.sum() if cvc is not None else float("nan")
            ref = THESIS[task].get(key, {})
            cells = [f"{pc[c]:.1f} ({ref[c]:g})" if c in ref else f"{pc[c]:.1f} (-)" for c in classes]
            lat = float(np.median(latency[task][key]))
            lines.append("| " + " | ".join([*key, *cells, f"{all_test:.1f}", f"{all_cv:.1f}", f"{lat:.3f}"]) + " |")
            for c in classes:
                rows.append(
                    {
                        "study": "simulated",
                        "table": TABLE_NO[task],
                        "task": task,
                        "method": key[0],
                        "unit": key[1],
                        "class": c,
                        "ours_test_pct": round(pc[c], 2),
                        "thesis_pct": ref.get(c),
                        "ours_all_test_pct": round(all_test, 2),
                        "ours_all_cv_pct": round(all_cv, 2),
                        "latency_ms": round(lat, 4),
                    }
                )
        ch = [f"u{u}: {c[0][0]}/{c[0][1]} {100 * c[1]:.1f} % (detected strides {100 * c[4]:.1f} %)"
              for u, c in zip(users, chosen[task], strict=True)]
        n_det = sum(c[5] for c in chosen[task])
        det_all = sum(c[4] * c[5] for c in chosen[task] if c[5]) / n_det if n_det else float("nan")
        lab_all = sum(c[1] * c[2] for c in chosen[task]) / n_test if n_test else float("nan")
        lines += ["", f"Chosen method per user (test accuracy on the labelled boundaries; in brackets on the strides "
                  f"track/run detect, decision C54): {'; '.join(ch)}",
                  "", f"Chosen models pooled: {100 * lab_all:.1f} % of {n_test} steps on the labelled boundaries, "
                  f"{100 * det_all:.1f} % of {n_det} on the strides track/run detect (what their users get)."]
        md.append("\n".join(lines))
    md.append(soft_vote_vs_combined(results, cv_results))
    return md, rows, timing


def soft_vote_vs_combined(results: dict, cv_results: dict) -> str:
    """Decision C23: pooled test accuracy of the soft vote (unit fused) and the combined feature vector
    (unit combined) for svm and nn per task, and of the model C8 chooses with and without the combined
    models among its candidates (without: the best fused model by the same CV key)."""
    from pdrlearn.classify.training import _score_key

    head = ["task", "svm fused", "svm combined", "nn fused", "nn combined", "chosen without combined",
            "chosen with combined", "chosen, default (svm/nn soft votes replaced)"]
    lines = ["### soft vote (fused) vs combined features (decision C23): pooled test accuracy %", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for task in results:
        cells, hits = [], {"without": [0, 0], "with": [0, 0]}
        for m in ("svm", "nn"):
            for u in ("fused", "combined"):
                ok = n = 0
                for res in results[task]:
                    r = res["tasks"][task]["methods"].get(m, {}).get("units", {}).get(u)
                    if r is not None:
                        ok += r["accuracy"] * r["n_steps"]
                        n += r["n_steps"]
                cells.append(f"{100 * ok / n:.1f}" if n else "-")
        picks = {"without": [], "with": [], "default": []}
        hits["default"] = [0, 0]
        for res, tm in zip(results[task], cv_results[task], strict=True):
            def best(keep, tm=tm):
                return min(((m, u) for m, per in tm.cv.items() for u in per if keep(m, u)),
                           key=lambda p: _score_key(tm.cv[p[0]][p[1]], p[0], p[1]))
            without = best(lambda m, u: u == "fused")
            default = best(lambda m, u: u == "combined" or (u == "fused" and m not in ("svm", "nn")))
            for key, pair in (("without", without), ("with", tm.chosen), ("default", default)):
                r = res["tasks"][task]["methods"][pair[0]]["units"][pair[1]]
                hits[key][0] += r["accuracy"] * r["n_steps"]
                hits[key][1] += r["n_steps"]
                picks[key].append("/".join(pair))
        for key in ("without", "with", "default"):
            cells.append(f"{100 * hits[key][0] / hits[key][1]:.1f} ({', '.join(picks[key])})")
        lines.append("| " + " | ".join([task, *cells]) + " |")
    return "\n".join(lines)


def _append_method_rows(res: dict, study: str, cols: list[str], row_class: str, lines: list, rows: list) -> None:
    """One table line per method x unit of an ``evaluate_model`` terrain result (per-class % of ``cols``,
    then the overall % when ``row_class == "all"``) and one CSV row with ``row_class``'s accuracy."""
    for m, d in res["methods"].items():
        for u, r in d["units"].items():
            vals = [100 * r["per_class"][c] for c in cols] + ([100 * r["accuracy"]] if row_class == "all" else [])
            lines.append(f"| {m} | {u} | " + " | ".join(f"{v:.1f}" for v in vals) + " |")
            pct = r["accuracy"] if row_class == "all" else r["per_class"][row_class]
            rows.append({"study": study, "task": "terrain", "method": m, "unit": u, "class": row_class,
                         "ours_test_pct": round(100 * pct, 2)})


def real_terrain_study(cv: int, seed: int, boundaries: str = "given", methods: list[str] | None = None):
    from sklearn.linear_model import RidgeCV
    from sklearn.model_selection import StratifiedKFold, cross_val_predict
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    from pdrlearn.classify.training import make_estimator, session_windows
    from pdrlearn.features import SegmentFeatures
    from pdrlearn.io import read_session

    real = ROOT / "datasets" / "real"
    names = [
        "gaitmap_level_left",
        "gaitmap_level_right",
        "gaitmap_stairs_up_left",
        "gaitmap_stairs_down_left",
    ]
    sessions = [read_session(real / n) for n in names]
    md, rows = [], []
    # 1) cross-validated, all recordings pooled; step windows cut at the labelled boundaries and rest to
    #    rest (decision 13 in docs/decisions/features.md), the study's own choice first
    for bnd in dict.fromkeys([boundaries, "given", "rest"]):
        t0 = time.perf_counter()
        model = train_user(sessions, tasks=["terrain"], cv=cv, seed=seed, user="gaitmap", boundaries=bnd,
                           methods=methods)
        dt = time.perf_counter() - t0
        tm = model.tasks["terrain"]
        classes = tm.classes
        lines = [
            f"### real foot terrain, {tm.cv[tm.chosen[0]][tm.chosen[1]]['n_folds']}-fold CV over 4 gaitmap "
            f"recordings, boundaries={bnd} ({tm.n_steps} strides, {tm.n_skipped_labels} 'unclear' skipped; "
            f"trained in {dt:.1f} s)",
            "",
            "| method | unit | " + " | ".join(f"{c} %" for c in classes) + " | all % |",
            "|---|---|" + "---|" * (len(classes) + 1),
        ]
        for m, u in tm.ranking():
            r = tm.cv[m][u]
            lines.append(
                f"| {m} | {u} | "
                + " | ".join(f"{100 * r['per_class'][c]:.1f}" for c in classes)
                + f" | {100 * r['accuracy']:.1f} |"
            )
            for c in classes:
                rows.append(
                    {
                        "study": f"real-cv-{bnd}",
                        "task": "terrain",
                        "method": m,
                        "unit": u,
                        "class": c,
                        "ours_test_pct": round(100 * r["per_class"][c], 2),
                        "ours_all_cv_pct": round(100 * r["accuracy"], 2),
                    }
                )
        best = tm.cv[tm.chosen[0]][tm.chosen[1]]["accuracy"]
        lines.append(f"\nChosen: {tm.chosen[0]}/{tm.chosen[1]} (CV {100 * best:.1f} %)")
        md.append("\n".join(lines))
    # 2) across feet: train on the left-foot recordings, test on the right foot (flat strides only)
    left = [s for s in sessions if s.name.endswith("_left")]
    right = [s for s in sessions if s.name.endswith("_right")]
    model_l = train_user(left, tasks=["terrain"], cv=cv, seed=seed, user="gaitmap-left", boundaries=boundaries,
                         methods=methods)
    res = evaluate_model(model_l, right, latency=False)["tasks"]["terrain"]
    lines = [
        "### real foot terrain across feet: train left foot (3 recordings), test right foot "
        f"(level walk, {res['n_steps']} flat strides; boundaries={boundaries})",
        "",
        "| method | unit | flat % (right foot) |",
        "|---|---|---|",
    ]
    _append_method_rows(res, "real-across-feet", ["flat"], "flat", lines, rows)
    md.append("\n".join(lines))
    # 3) sim-to-real: a model trained on simulated terrain exercises (foot unit only) classifies the real strides
    from pdrlearn.sim.simulate import simulate

    sim = [simulate("terrain", user_seed=u, seed=0) for u in (1, 2)]
    model_s = train_user(sim, tasks=["terrain"], units=["foot"], cv=cv, seed=seed, user="sim", methods=methods,
                         boundaries=boundaries)
    res = evaluate_model(model_s, sessions, latency=False)["tasks"]["terrain"]
    lines = [
        "### sim-to-real: trained on simulated terrain exercises (2 users, foot unit), tested on the "
        f"{res['n_steps']} real gaitmap strides (boundaries={boundaries})",
        "",
        "| method | unit | flat % | up % | down % | all % |",
        "|---|---|---|---|---|---|",
    ]
    _append_method_rows(res, "sim-to-real", list(classes), "all", lines, rows)
    md.append("\n".join(lines))
    # 4) per-class accuracy of the chosen pooled model, explicitly held out by recording is impossible for
    #    up/down (one recording each); 5) continuous stride length on the level walks (mocap reference)
    level = [s for s in sessions if "level" in s.name]
    wins = session_windows(level, n_samples=40)
    feats = SegmentFeatures(channels=("foot_acc_fwd", "foot_acc_v", "foot_pitch"))
    Xs, ys, gs = [], [], []
    for i, w in enumerate(wins):
        keep = w.steps["length_m"].notna().to_numpy()
        F = feats.fit_transform(w.X[keep])
        Xs.append(np.column_stack([F, w.durations_s[keep]]))
        ys.append(w.steps["length_m"].to_numpy()[keep])
        gs.append(np.full(keep.sum(), i))
    X, y, g = np.vstack(Xs), np.concatenate(ys), np.concatenate(gs)
    reg = make_pipeline(StandardScaler(), RidgeCV(alphas=np.logspace(-2, 3, 20)))
    lines = [
        "### real continuous stride length (gaitmap level walks, mocap reference; ridge regression on "
        "73 segment features + duration)",
        "",
        "| protocol | strides | RMSE m | MAE m | baseline RMSE m (mean length) |",
        "|---|---|---|---|---|",
    ]
    bins = np.digitize(y, np.quantile(y, [0.33, 0.66]))
    pred = cross_val_predict(reg, X, y, cv=StratifiedKFold(5, shuffle=True, random_state=seed).split(X, bins))
    base = np.sqrt(np.mean((y - y.mean()) ** 2))
    rmse, mae = np.sqrt(np.mean((pred - y) ** 2)), np.mean(np.abs(pred - y))
    lines.append(f"| 5-fold CV, both feet | {len(y)} | {rmse:.3f} | {mae:.3f} | {base:.3f} |")
    rows.append(
        {
            "study": "real-length",
            "task": "length_m",
            "method": "ridge",
            "unit": "foot",
            "class": "cv",
            "rmse_m": round(rmse, 4),
            "mae_m": round(mae, 4),
            "baseline_rmse_m": round(base, 4),
        }
    )
    for tr_i, te_i in ((0, 1), (1, 0)):
        tr, te = g == tr_i, g == te_i
        p = reg.fit(X[tr], y[tr]).predict(X[te])
        rmse = np.sqrt(np.mean((p - y[te]) ** 2))
        b = np.sqrt(np.mean((y[te] - y[tr].mean()) ** 2))
        lines.append(
            f"| train {names[tr_i][8:]}, test {names[te_i][8:]} | {te.sum()} | {rmse:.3f} | "
            f"{np.mean(np.abs(p - y[te])):.3f} | {b:.3f} |"
        )
        rows.append(
            {
                "study": "real-length",
                "task": "length_m",
                "method": "ridge",
                "unit": "foot",
                "class": f"{names[tr_i]}->{names[te_i]}",
                "rmse_m": round(rmse, 4),
                "baseline_rmse_m": round(b, 4),
            }
        )
    md.append("\n".join(lines))
    _ = make_estimator  # the same factory the CLI uses trains every model above
    return md, rows


#: the options that make a run partial (steps decision 67): a smaller protocol or the real part left out
PARTIAL_OPTIONS = ("users", "train_walks", "test_walks", "cv", "seed", "quick", "no_real")


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, nargs="+", default=[1, 2], help="simulated user seeds (thesis: 2)")
    ap.add_argument("--train-walks", type=int, default=2, help="calibration exercises per task for training")
    ap.add_argument("--test-walks", type=int, default=2, help="other exercises per task for testing")
    ap.add_argument("--cv", type=int, default=10, help="folds (thesis: 10)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--quick", action="store_true", help="1 user, 1 training and 1 test walk")
    ap.add_argument("--no-real", action="store_true", help="skip the real-data study")
    ap.add_argument("--boundaries", choices=("given", "rest"), default="given",
                    help="step-window boundaries (decision 13): 'rest' writes characterization_rest.md/.csv")
    ap.add_argument("--ensemble", action="store_true",
                    help="also train the opt-in 'ensemble' method (decision C14); adds '_ensemble' to the file names")
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results")
    return ap


def output_stem(argv: list[str] | None = None) -> tuple[argparse.Namespace, list[str], str]:
    """The parsed options, the options that make the run partial and the results' file stem (steps 67)."""
    ap = build_parser()
    args = ap.parse_args(argv)
    changed = partial_options(ap, args, PARTIAL_OPTIONS)
    stem = "characterization" + ("_rest" if args.boundaries == "rest" else "") + ("_ensemble" if args.ensemble else "")
    return args, changed, result_name(stem, bool(changed))


def main(argv: list[str] | None = None) -> int:
    args, changed, stem = output_stem(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    if args.quick:
        args.users, args.train_walks, args.test_walks = args.users[:1], 1, 1
    t0 = time.perf_counter()
    methods = [*DEFAULT_METHODS, "ensemble"] if args.ensemble else None
    md, rows, timing = simulated_study(args.users, args.train_walks, args.test_walks, args.cv, args.seed,
                                       args.boundaries, methods)
    parts = [
        "# Step characterization: ours beside thesis Tables 27, 28, 33",
        "",
        "Cells: test accuracy % per class, ours (thesis). Simulated users (pdrlearn.sim), training = "
        f"{args.train_walks} calibration exercise(s) per task, test = {args.test_walks} other exercise(s) of "
        "the same user; 'all % CV' = cross-validated accuracy on the training data; ms/step = median "
        "per-step latency of feature extraction + classification (this machine, one step at a time; "
        f"step windowing not included). Step windows: boundaries={args.boundaries}; methods: "
        f"{', '.join(methods or DEFAULT_METHODS)}. Generated by "
        "experiments/characterization.py.",
        "",
        PROTOCOL_NOTE,
        "",
        *md,
        "",
        f"### per-user training time (3 tasks x 5 methods x units, {args.cv}-fold CV)",
        "",
        "| user | seconds |",
        "|---|---|",
    ]
    parts += [f"| u{u} | {s:.1f} |" for u, s in timing.items()]
    if not args.no_real:
        md_r, rows_r = real_terrain_study(args.cv, args.seed, args.boundaries, methods)
        parts += ["", "## Real recordings (gaitmap foot IMU)", "", *md_r]
        rows += rows_r
    parts.append(f"\nTotal run time {time.perf_counter() - t0:.0f} s.")
    text = "\n".join(parts) + "\n"
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / f"{stem}.md").write_text(text)
    pd.DataFrame(rows).to_csv(args.out / f"{stem}.csv", index=False)
    print(text)
    if changed:
        print(partial_note(changed))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
