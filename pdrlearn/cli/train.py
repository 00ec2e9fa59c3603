"""``pdrlearn train`` and ``pdrlearn evaluate``: per-user step classifiers (thesis ch. 6)."""
# ruff: noqa: B008  (typer options are declared as defaults)

from __future__ import annotations

import time
from pathlib import Path

import typer

from pdrlearn.classify.cv_report import cv_title, grouped
from pdrlearn.cli.common import (
    FORCE_HELP,
    LENGTH_UNITS_HELP,
    METHODS_HELP,
    PICKLE_HELP,
    check_train_options,
    console,
    cv_groups_option,
    existed,
    grouped_skips,
    json_safe,
    out_folder,
    param_option,
    print_json,
    print_table,
    progress,
    replaced,
    report_folder,
    resample_options,
    split_choices,
    split_length_units,
    train_resample_option,
)
from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError, shell_quote
from pdrlearn.session_dirs import find_session_dirs, read_session_dirs

EVAL_RESAMPLE_OPT, EVAL_NO_RESAMPLE_OPT = resample_options("scored")  # decision B113, track's text


def train(
    data_dirs: list[Path] = typer.Argument(..., help="Labelled session folders (or folders of sessions)."),
    out: Path = typer.Option(..., "--out", "-o", help="Model directory to write (an existing one only with --force)."),
    tasks: str = typer.Option(
        None, help="Comma list of terrain,direction,length (default: what is labelled)."
    ),
    methods: str = typer.Option(None, help=METHODS_HELP),  # decisions C14, C74
    units: str = typer.Option(None, help="Comma list of foot,waist,fused,combined (default: all the data allow; "
                              "fused = soft vote of the unit models, combined = one svm/nn model on both units' "
                              "features, decisions C7, C22)."),
    length_units: str = typer.Option(None, "--length-units", help=LENGTH_UNITS_HELP),
    cv: int = typer.Option(10, help="Folds of the stratified cross-validation (thesis: 10)."),
    cv_groups: str = cv_groups_option(),  # decisions C29, C59, C95 (C98: train-all's too)
    seed: int = typer.Option(0, help="Seed of folds, DTW references and network initialisation."),
    user: str = typer.Option(None, help="User name stored in the manifest, replacing the sessions' meta.json 'user' / "
                      "'subject' everywhere the model (and a bundle exported from it) names a user: a pseudonym such "
                      "as P001 (several users: P001-1, P001-2, ...; decision E174). Default: the sessions' own name, "
                      "else 'unnamed' (B88)."),
    boundaries: str = typer.Option(
        "given",
        help="Step-window boundaries: 'given' (the labelled start/end) or 'rest' (each boundary moved to the "
        "middle of the foot's rest nearby: rest-to-rest windows, decision C13). Stored in the model; "
        "evaluate, predict and the exported runtime cut windows the same way.",
    ),
    distance_calibration: bool = typer.Option(
        True, "--distance-calibration/--no-distance-calibration",
        help="Estimate the user's distance gain and stride spread from the straight level strides of the "
        "labelled sessions, once with the offline engine (decision L26; M3 applies it) and once with the "
        "streamed stride kernel (L41; track --streaming and the runtime apply it). Turn off for a model pooled over "
        "several users or devices: a pooled gain corrects no one's sensor.",
    ),
    resample: float = train_resample_option(),  # decisions C56, C62: train-all's too
    param: list[str] = param_option(),  # decision C96 (C98: train-all's too)
    report: Path = typer.Option(None, "--report", help="Folder for the CV tables (cv.csv; louo.csv with "
                                "--cv-groups user), one confusion PNG per task and report.md (decision C143)."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON summary object."),
) -> None:
    """Train a user's terrain / direction / length classifiers and save a model directory.

    Every task x method x unit is scored by cross-validation (stratified folds of the pooled steps; with
    --cv-groups user and sessions of several users, folds of whole users); the best two-unit model per task
    (fused or combined) is chosen.
    Tasks without labels (or with a missing class) are skipped and listed, unless asked for with --tasks.

    Examples:

        pdrlearn train out/sim/u1 --out models/u1

        pdrlearn train datasets/real/gaitmap_level_left datasets/real/gaitmap_stairs_up_left \\
            datasets/real/gaitmap_stairs_down_left --out models/gaitmap --tasks terrain --cv 5

        pdrlearn train datasets/real/gaitmap_* --out models/gaitmap --tasks terrain \\
            --boundaries rest --methods heuristic,dtw,svm,nn,ensemble

        pdrlearn train out/sim/u1 --out out/models/u1_c10 --cv-groups block --param svm.C=10 --param nn.hidden=32

        pdrlearn train out/sim/u1 --out out/models/u1_r --report out/train_u1
    """
    from pdrlearn.classify.spread import chance_line
    from pdrlearn.classify.training import check_settings, check_task_methods, check_user, train_user
    from pdrlearn.features.windows import BOUNDARIES

    if boundaries not in BOUNDARIES:
        raise DataError(f"train: --boundaries {boundaries!r}; choose one of {', '.join(BOUNDARIES)}")
    user = check_user(user)  # decision B339: before any data is read
    t_list, m_list, u_list, per_task = split_choices(tasks=tasks, methods=methods, units=units)
    t_all, m_all, u_all = check_settings(tasks=t_list, methods=m_list, units=u_list, cv=cv, seed=seed,
                                         resample_hz=resample)  # C62: before any data is read
    per_task = check_task_methods(per_task, t_all)  # decisions C74, C78: before any data is read
    hyper = check_train_options(cv_groups, param, m_all, per_task)  # decisions C95, C96: before any data is read
    l_list = split_length_units(length_units)  # decision C38: checked before any data is read
    out_folder(out, "model", force=force, inputs=tuple(data_dirs))
    if report is not None:  # decision C143: checked before the work, like --out
        report_folder(report, out, command="train", what="model directory", kind="train-report", force=force,
                      inputs=tuple(data_dirs))
    was = existed(out)
    sessions = read_session_dirs(data_dirs)
    total = sum(len(per_task.get(t, m_all)) for t in t_all) * len(u_all)
    t0 = time.perf_counter()
    with progress("training", total, enabled=not as_json) as advance:
        model = train_user(
            sessions, tasks=t_list, methods=m_list, units=u_list, cv=cv, seed=seed, user=user,
            boundaries=boundaries, advance=advance, distance_calibration=distance_calibration,
            cv_groups=cv_groups, length_units=l_list, resample_hz=resample, task_methods=per_task, params=hyper,
        )
    seconds = time.perf_counter() - t0
    model.save(out)
    replaced(out, was)
    if report is not None:  # decision C143
        from pdrlearn.atomic import atomic_directory
        from pdrlearn.classify.cv_report import write_model_report

        had_report = existed(report)
        with atomic_directory(report) as tmp:
            write_model_report(model, tmp)
        replaced(report, had_report)
    summary = {
        "out": str(out),
        "report": None if report is None else str(report),  # decision C143
        "user": model.user,
        "users": model.data_summary.get("users", []),  # decision C35
        "sessions": len(sessions),
        "boundaries": model.boundaries,
        "seconds": round(seconds, 2),
        "cv_groups": model.settings["cv_groups"],  # decision B210: what the folds used; what was asked, per task
        "cv_groups_asked": model.settings.get("cv_groups_asked", model.settings["cv_groups"]),
        "cv_groups_by_task": model.settings.get("cv_groups_by_task", {}),
        "cv_users": model.settings["cv_users"],
        "cv_sessions": model.settings.get("cv_sessions", 0),  # decision C59
        "cv_blocks": model.settings.get("cv_blocks", 0),  # decision C95: the folds used; C114: and asked
        **({"cv_blocks_asked": model.settings["cv_blocks_asked"]} if "cv_blocks_asked" in model.settings else {}),
        "params": model.settings.get("params", {}),  # decision C96
        "skipped": model.skipped,
        "distance_calibration": model.data_summary.get("distance_calibration"),
        "tasks": {
            t: {
                "chosen": {"method": tm.chosen[0], "unit": tm.chosen[1]},
                "n_steps": tm.n_steps,
                "n_skipped_labels": tm.n_skipped_labels,
                "cv": {m: {u: r["accuracy"] for u, r in per.items()} for m, per in tm.cv.items()},
                "cv_balanced": {m: {u: r["balanced_accuracy"] for u, r in per.items()} for m, per in tm.cv.items()},
                # decision C41: each fold's accuracy, mean, sd and the 95 % t-interval over the folds
                "cv_folds": {m: {u: r.get("folds") for u, r in per.items()} for m, per in tm.cv.items()},
                "chosen_reason": chosen_reason(tm),
                "skipped": tm.skipped,
            }
            for t, tm in model.tasks.items()
        },
    }
    if as_json:
        print_json(json_safe(summary))
        return
    from rich.table import Table

    from pdrlearn.classify.cv_report import cv_frame, display_table, text_rows

    c = console()
    cv_all = cv_frame(model)  # decision C150: the table of cv.csv, report.md and `pdrlearn report`
    for t, tm in model.tasks.items():
        # the title as its own line: as a table title rich wrapped it to the table's width
        r0 = tm.cv[tm.chosen[0]][tm.chosen[1]]
        c.print(f"{t}: {tm.n_steps} steps, {cv_title(r0)} (chosen: {tm.chosen[0]}/{tm.chosen[1]})", markup=False)
        # decision C36: the rows are ranked by balanced accuracy (mean of the class columns), so it is shown;
        # decision C41: the folds' spread of the accuracy beside the pooled one; C144: the thesis' figure
        shown = display_table(cv_all[cv_all["task"] == t], tm.classes, order=tm.ranking())
        tab = Table()
        for col in shown.columns:
            tab.add_column(col, no_wrap=col in ("method", "unit", "folds", "95 % CI"))
        for row in text_rows(shown):
            tab.add_row(*row)
        print_table(c, tab)  # decision C41: piped, the wider table is not cut to 80 columns
        c.print(f"  {SPREAD_NOTE}", markup=False)
        chance = chance_line((f"{m}/{u}", tm.cv[m][u]) for m, u in tm.ranking())  # decision C141
        if chance:
            c.print(f"  {chance}", markup=False)
        users_line = louo_line(r0)
        if users_line:
            c.print(f"  {users_line}", markup=False)
        weights = fused_weights_line(tm)
        if weights:
            c.print(f"  {weights}", markup=False)
        c.print(f"  {chosen_reason(tm)}", markup=False)
        for s in grouped_skips(tm.skipped):
            c.print(f"  skipped {s}", markup=False)
    # decision C53: the skipped tasks and "no classifier trained" (C17) are train_user's warnings, logged once
    cal = summary["distance_calibration"]
    if cal is None:
        c.print("distance calibration: off (--no-distance-calibration)")
    elif cal.get("reason"):
        c.print(f"distance calibration: gain 1 ({cal['reason']})")
    else:
        users = model.data_summary.get("users") or []
        pooled = f", pooled over {len(users)} users" if len(users) > 1 else ""  # decision C35
        c.print(f"distance calibration: gain {cal['gain']:.4f} from {cal['n_strides']} straight level strides"
                f"{pooled} ({decision_ref('L26')}; offline M3 applies it){_streamed_gain(cal)}")  # decision D49
    c.print(f"step windows: {model.boundaries} boundaries")
    if summary["params"]:  # decision C96
        c.print("hyperparameters: " + ", ".join(f"{m}.{n}={v}" for m, names in summary["params"].items()
                                                for n, v in names.items()) + " (--param; the rest thesis defaults)")
    c.print(f"model written to {out} ({seconds:.1f} s)")
    if report is not None:
        c.print(f"report written to {report} (cv.csv, confusion PNGs, report.md)")


#: how the train table's spread columns are computed (decision C41), printed under each table
SPREAD_NOTE = ("all, balanced: pooled over the steps; folds: mean±sd of the folds' accuracies; 95 % CI: exact "
               "binomial (Clopper-Pearson) interval of 'all' over the pooled steps (optimistic: steps of one walk "
               f"are not independent; {decision_ref('C41', 'C58', topic='classifiers')})")  # decision D49


def louo_line(r: dict) -> str | None:
    """The chosen model's accuracy on each held-out user (session) of a leave-one-user-out CV (decisions C43,
    C59), e.g. ``chosen model per held-out user: user:u1 93.0 %, user:u2 97.5 %``; None for folds of steps."""
    f = r.get("folds") or {}
    kind, groups = grouped(r)
    who_list = f.get(f"{kind}s")
    if not who_list:
        return None
    what = kind if r["n_folds"] == groups else f"fold of {kind}s"
    return f"chosen model per held-out {what}: " + ", ".join(
        f"{who} {100 * a:.1f} % ({n} steps)" for who, a, n in zip(who_list, f["accuracy"], f["n_steps"], strict=True))


def fused_weights_line(tm) -> str | None:
    """Decision C124: the unit weights of the task's fused soft votes (foot/waist), the zero-weight ones marked as
    reading one unit (their rows equal the unit model's); None without a soft vote."""
    from pdrlearn.classify.training import zero_weight_unit

    parts = []
    for m, per in tm.cv.items():
        w = (per.get("fused") or {}).get("weights")
        if w:
            zero = zero_weight_unit(per["fused"])
            other = "waist" if zero == "foot" else "foot"
            parts.append(f"{m} {w['foot']:.2f}/{w['waist']:.2f}"
                         + (f" (reads the {other} only: not a two-unit model for the choice)" if zero else ""))
    return (f"fused weights (foot/waist; {decision_ref('C124', topic='classifiers')}): "  # decision D49
            + ", ".join(parts)) if parts else None


def chosen_reason(tm) -> str:
    """Why ``tm.chosen`` was chosen (decision C36): the best balanced CV accuracy among the two-unit models
    (decision C8/C23), and the one-unit models that rank above it."""
    from pdrlearn.classify.training import TWO_UNIT

    m, u = tm.chosen
    bal = tm.cv[m][u]["balanced_accuracy"] or 0.0
    if u not in TWO_UNIT:
        return f"chosen: {m}/{u}, the best balanced CV accuracy ({100 * bal:.1f} %)"
    above = []
    one = tm.one_unit_votes()  # decision C124
    for mm, uu in tm.ranking():
        if (mm, uu) == (m, u):
            break
        above.append(f"{mm}/{uu} {100 * (tm.cv[mm][uu]['balanced_accuracy'] or 0.0):.1f} %"
                     + (" (a unit weight 0)" if (mm, uu) in one else ""))
    why = (f"chosen: {m}/{u}, the best balanced CV accuracy ({100 * bal:.1f} %) among the models reading both "
           f"units (fused, combined; {decision_ref('C8', topic='classifiers')})")  # decision D49
    if above:
        why += f"; ranked higher but reading one unit: {', '.join(above)}"
    return why


def _streamed_gain(cal: dict) -> str:
    """The streamed stride kernel's gain of a calibration record (decision L41), as the end of the line."""
    st = cal.get("streaming")
    if not isinstance(st, dict):
        return ""
    if st.get("reason"):
        return f"; streamed: gain 1 ({st['reason']})"
    return (f"; streamed: gain {st['gain']:.4f} from {st['n_strides']} strides ({decision_ref('L41')}; track "
            "--streaming and the runtime apply it)")  # decision D49


def evaluate(
    model_dir: Path = typer.Argument(..., help=f"Model directory written by 'pdrlearn train' ({PICKLE_HELP}), or a "
                                     "runtime bundle "
                                     "('pdrlearn export'; its chosen models scored on the strides the runtime "
                                     "detects, decision E193)."),
    data_dirs: list[Path] = typer.Argument(..., help="Labelled session folders (or folders of sessions)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object (tasks.<task>.accuracy on the "
                                 "labelled boundaries, tasks.<task>.detected.accuracy on the strides the runtime "
                                 "detects, decision C49 ...)."),
    report: Path = typer.Option(None, "--report", help="Folder for report.md/json and confusion PNGs."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    warn_out_of_domain: float = typer.Option(None, "--warn-out-of-domain", help="Warn (one line) when at least "
                                             "this fraction of the labelled steps (of a bundle: the detected "
                                             "strides) lie outside the model's training range, e.g. 0.25 (off by "
                                             "default; the fraction is always in the result as "
                                             "out_of_domain_fraction, decisions C16, E198)."),
    predictions_out: Path = typer.Option(
        None, "--predictions-out", metavar="FILE.csv",
        help="Write one row per scored step: session, step (its data row in the session's steps.csv, 0 = the "
        "first row under the header), start_s, end_s, task, true, predicted, correct, the method and unit that "
        "classified it and their probability of each class (p_<class>); written atomically (decision C42)."),
    all_methods: bool = typer.Option(False, "--all-methods", help="Score every method x unit on the strides the "
                                     "runtime detects too (JSON tasks.<t>.methods.<m>.units.<u>.detected, decision "
                                     "C97), and with --predictions-out write every method x unit's class of each "
                                     "labelled step matched to a detected stride and classified by "
                                     "every model (the same steps, for paired tests; p_<class> empty) instead of "
                                     "the chosen model's rows on the "
                                     "labelled boundaries (decision C125)."),
    resample: bool = EVAL_RESAMPLE_OPT,
    no_resample: bool = EVAL_NO_RESAMPLE_OPT,
    warn_gait_range: bool = typer.Option(False, "--warn-gait-range", help="Warn (one line) when sessions' labelled "
                                         "strides walk outside the validated walking range (decision L95); off by "
                                         "default, the sessions are always in the result as "
                                         "gait_out_of_range_sessions (decision L332)."),
) -> None:
    """Accuracy per class x method x unit (thesis Tables 27/28/33), confusion matrices, per-step latency.

    The model is scored as fitted, on the sessions given (no cross-validation): for leave-one-user-out scores
    train with `pdrlearn train ... --cv-groups user` (decisions C29, C43). Each task's first figure is the
    chosen model's accuracy on the strides the runtime and `track --model` detect (matched to the labelled
    steps); the table scores the labelled boundaries (decision C49). A runtime bundle (e.g. the shipped
    models/plasys-sim-default) is scored as `pdrlearn run` replays it: one row per task, its chosen model on the
    strides the runtime detects (decision E193); a bundle refuses --report, --predictions-out, --resample,
    --no-resample, --warn-gait-range and --all-methods, which need a model directory's per-method models
    (decision E198). --all-methods scores every method x unit on the detected strides, and with
    --predictions-out writes each model's class of the matched steps every model classified (decision C125).

    Examples:

        pdrlearn evaluate out/models/u1 out/sim/u1_test --report out/eval_u1

        pdrlearn evaluate out/models/u1 out/sim/u1_test --json

        pdrlearn evaluate out/models/u1 out/sim/u1_test --predictions-out out/eval_u1_steps.csv

        pdrlearn evaluate models/plasys-sim-default out/sim/u1_test
    """
    from pdrlearn.outfolder import manifest_kind

    if manifest_kind(Path(model_dir)) == "a runtime bundle":  # decision E193: score the shipped / exported bundle
        from pdrlearn.export.score import MODEL_DIR_ONLY

        given = [o for o, v in zip(MODEL_DIR_ONLY, (report, predictions_out, resample or None,
                                                    no_resample or None, warn_gait_range or None,
                                                    all_methods or None), strict=True)
                 if v is not None]
        return _evaluate_bundle(model_dir, data_dirs, as_json, given, warn_out_of_domain)
    from pdrlearn.classify import evaluate_model, load_model
    from pdrlearn.classify.detected import detected_lines
    from pdrlearn.classify.detected_rules import track_length_line
    from pdrlearn.classify.evaluation import (
        evaluation_stages,
        headline,
        write_predictions,
    )
    from pdrlearn.classify.uncovered import uncovered_line
    from pdrlearn.cli.common import out_file
    from pdrlearn.io.resample import at_model_rate, log_grouped, resample_mode

    rate_mode = resample_mode(resample, no_resample)  # decision B113
    swapped_order(model_dir, data_dirs)  # decision B392: `evaluate SESSIONS MODEL`

    if predictions_out is not None and report is not None and Path(predictions_out).resolve().is_relative_to(
            Path(report).resolve()):  # the next `--report --force` would delete it (decision C47)
        raise DataError(f"evaluate: --predictions-out {predictions_out} is inside the --report folder {report}, "
                        "which --report --force replaces; write it outside, e.g. "
                        f"{Path(report).parent / (Path(report).name + '_steps.csv')}")
    if predictions_out is not None:  # checked before the work (decision B26: --force replaces only its own kind)
        out_file(predictions_out, (".csv",), "predictions", force=force)
    had_predictions = predictions_out is not None and existed(predictions_out)

    if report is not None:
        # evaluation.json alone is the documented `--json > DIR/evaluation.json` redirect, made by the shell
        out_folder(report, "evaluation", force=force, inputs=(model_dir, *data_dirs),
                   allow=("evaluation.json",), option="--report")
    # not atomic: the folder may hold the file the shell is redirecting --json into (written in place)
    was = report is not None and (report / "report.md").is_file()
    # the same progress bar as train (stderr, a terminal only, not with --json): loading the model (~2 s),
    # reading each session, then evaluate_model's stages (its total is known once the model is loaded);
    # -v logs each scored model
    from pdrlearn.cohort import captured_warnings
    from pdrlearn.io import read_session
    from pdrlearn.warning_lines import warning_code

    # decision B95: the warnings printed (held-out, out-of-domain, rate ...) also go into the JSON, for `report`
    with captured_warnings(echo=True) as warned, progress("evaluating", None, enabled=not as_json) as advance:
        model = load_model(model_dir)  # checked before the sessions, as before the bar
        dirs = find_session_dirs(data_dirs)
        advance(1, total=1 + len(dirs) + evaluation_stages(model, report=report is not None))
        sessions, said = [], {}
        for d in dirs:
            sessions.append(at_model_rate(read_session(d), model, rate_mode, command="evaluate", said=said))  # B113
            advance(1)
        log_grouped(said)
        tables: list | None = [] if predictions_out is not None else None
        result = evaluate_model(model, sessions, report_dir=report, advance=advance,
                                warn_out_of_domain=warn_out_of_domain, step_predictions=tables,
                                warn_gait_range=warn_gait_range, all_methods=all_methods)  # decision C125
    result["warnings"] = list(dict.fromkeys(warned)) + _chance_notes(result)  # decision C149: the C141 note too
    result["warning_codes"] = [warning_code(w) for w in result["warnings"]]  # decision B350, as evaluate_model's
    if not model.tasks:  # decision C17: a model trained on level walks only holds a distance calibration
        raise DataError(f"evaluate: {model_dir} has no trained classifier to evaluate (training skipped every "
                        "task), only a distance calibration; evaluate its tracking with `pdrlearn track SESSION "
                        f"--model {shell_quote(model_dir)}`")
    if not result["tasks"]:
        raise DataError(
            f"evaluate: the sessions have no labels for the model's tasks ({', '.join(model.tasks)}); "
            + "; ".join(result["skipped"])
        )
    if was:
        replaced(report, was)
    if predictions_out is not None:
        result["predictions_out"] = str(predictions_out)
        result["n_predictions"] = write_predictions(tables, predictions_out)
        replaced(predictions_out, had_predictions)
    if as_json:
        print_json(json_safe(result))
        return

    c = console()
    for task, r in result["tasks"].items():
        _task_table(c, r, task, f"{task}: {r['n_steps']} steps - chosen {r['chosen']['method']}/{r['chosen']['unit']} "
                    f"{headline(r)}")
        for line in detected_lines(r.get("detected")):  # decision C76
            c.print(f"  {line}", markup=False)
        line = uncovered_line(task, r.get("uncovered"), r["classes"])  # decision C160
        if line:
            c.print(f"  {line}", markup=False)
        line = track_length_line(r.get("detected"), r.get("detected_track"))  # decision C226
        if line:
            c.print(f"  {line}", markup=False)
        for s in r["skipped"]:
            c.print(f"  skipped {s}")
    c.print(f"step windows: {result.get('boundaries', model.boundaries)} boundaries, "
            f"{result['windows_ms_per_step']:.3f} ms/step")
    if result.get("out_of_domain_fraction") is not None:  # decision C16
        c.print(f"{100 * result['out_of_domain_fraction']:.0f} % of the labelled steps lie outside the model's "
                "training range", markup=False)
    for s in result["skipped"]:
        c.print(f"skipped {s}")
    if report is not None:
        c.print(f"report written to {report}")
    if predictions_out is not None:
        c.print(f"{result['n_predictions']} step predictions written to {predictions_out}", markup=False)


def swapped_order(model_dir: Path, data_dirs: list[Path]) -> None:
    """Decision B392: ``evaluate SESSIONS MODEL_DIR`` (the arguments swapped) is one line giving the order, when the
    first argument holds no manifest.json and a later one does (a model directory)."""
    from pdrlearn.classify.model_dir import MANIFEST

    if (Path(model_dir) / MANIFEST).is_file():
        return
    models = [d for d in data_dirs if (Path(d) / MANIFEST).is_file()]
    if models:
        rest = [d for d in [model_dir, *data_dirs] if d != models[0]]
        raise DataError(f"evaluate: {model_dir} is not a model directory but {models[0]} is: the model comes first, "
                        f"then the sessions: `pdrlearn evaluate {shell_quote(models[0])} "
                        f"{' '.join(shell_quote(d) for d in rest)}` (decision B392)")


def _evaluate_bundle(bundle_dir: Path, data_dirs: list[Path], as_json: bool, given: list[str],
                     warn_out_of_domain: float | None) -> None:
    """Decision E193: a runtime bundle's chosen models scored on the strides the runtime detects in labelled
    sessions (pdrlearn.export.score), printed as the model directory's table (one row per task); the absent-class
    and out-of-domain lines as a model directory's (E198)."""
    if given:
        raise DataError(f"evaluate: {', '.join(given)} needs a model directory written by 'pdrlearn train'; "
                        f"{bundle_dir} is an exported runtime bundle (scored with its chosen models only): drop "
                        f"{', '.join(given)}, or evaluate the model directory the bundle was exported from")
    from pdrlearn.classify.evaluation import table_pairs
    from pdrlearn.classify.uncovered import uncovered_line, uncovered_note
    from pdrlearn.cohort import captured_warnings
    from pdrlearn.export.score import score_bundle
    from pdrlearn.runtime.bundle import WAIST_SCHEMA_NAME, bundle_kind
    from pdrlearn.warning_lines import warning_code

    if bundle_kind(bundle_dir) == WAIST_SCHEMA_NAME:
        raise DataError(f"evaluate: {bundle_dir} is a waist-only bundle, whose steps carry no classes to score; "
                        f"give a foot-unit bundle or a model directory (track the sessions with `pdrlearn run "
                        f"{shell_quote(bundle_dir)} SESSION --json` for their step F1 and distance)")
    dirs = find_session_dirs(data_dirs)
    with captured_warnings(echo=True) as warned, progress("evaluating", len(dirs), enabled=not as_json) as advance:
        result = score_bundle(bundle_dir, dirs, advance=advance, warn_out_of_domain=warn_out_of_domain)
    result["warnings"] = list(dict.fromkeys(warned))
    result["warning_codes"] = [warning_code(w) for w in result["warnings"]]
    if not result["tasks"]:
        raise DataError("evaluate: the sessions have no labels the bundle's tasks can be scored on; "
                        + "; ".join(result["skipped"]))
    if as_json:
        print_json(json_safe(result))
        return
    c = console()
    for task, r in result["tasks"].items():
        scored, chosen = r["scored_model"], r["chosen"]
        who = ("bundle's chosen" if scored == chosen else  # decision E196: the model that ran, one row each
               f"bundle's foot-only (the chosen {chosen['method']}/{chosen['unit']} ran on no session)")
        _task_table(c, r, task, f"{task}: {r['n_steps']} strides - {who} {scored['method']}/{scored['unit']} "
                    f"{100 * r['accuracy']:.1f} % on the strides the runtime detects (matched to the labelled steps)"
                    + ("; one row per model the runtime used" if len(table_pairs(r)) > 1 else "")
                    + uncovered_note(r))  # decision C179
        line = uncovered_line(task, r.get("uncovered"), r["classes"])  # decision C166: as a model directory's (C160)
        if line:
            c.print(f"  {line}", markup=False)
    if result.get("out_of_domain_fraction") is not None:  # decisions C16, E198: as a model directory's
        c.print(f"{100 * result['out_of_domain_fraction']:.0f} % of the detected strides lie outside the model's "
                "training range", markup=False)
    for s in result["skipped"]:
        c.print(f"skipped {s}", markup=False)


def _task_table(c, r: dict, task: str, title: str) -> None:
    """One task's evaluation: ``title``, the per-class table (decision C60: with balanced %) and the chosen model's
    precision / recall / F1 per class (decision C37); a model directory's and a bundle's (E193) alike."""
    from rich.table import Table

    from pdrlearn.classify.evaluation import results_head, results_table, table_pairs
    from pdrlearn.classify.spread import chance_line

    c.print(title, markup=False)
    tab = Table()
    for col in results_head(r, task):  # decision C144: with the thesis' figure
        tab.add_column(col)
    for row in results_table(r, task):
        tab.add_row(*row)
    print_table(c, tab)  # piped, at the width it needs: the thesis column made 80 columns wrap the headers
    c.print("  chosen model per class, precision / recall / F1 %: " + ", ".join(
        f"{k} {_pct(r['precision'][k])} / {_pct(r['per_class'][k])} / {_pct(r['f1'][k])}"
        for k in r["classes"]), markup=False)
    chance = chance_line((f"{m}/{u}", r["methods"][m]["units"][u]) for m, u in table_pairs(r))  # decision C141
    if chance:
        c.print(f"  {chance}", markup=False)


def _chance_notes(result: dict) -> list[str]:
    """Decision C149: each task's C141 chance note (:func:`~pdrlearn.classify.spread.chance_line`, the line printed
    under its table) as ``"TASK: note"``, for the JSON's warnings."""
    from pdrlearn.classify.evaluation import table_pairs
    from pdrlearn.classify.spread import chance_line

    out = []
    for task, r in (result.get("tasks") or {}).items():
        line = chance_line((f"{m}/{u}", r["methods"][m]["units"][u]) for m, u in table_pairs(r))
        if line:
            out.append(f"{task}: {line}")
    return out


def _pct(v) -> str:
    return "-" if v is None else f"{100 * v:.1f}"


def register(app: typer.Typer) -> None:
    app.command("train")(train)
    app.command("evaluate")(evaluate)
